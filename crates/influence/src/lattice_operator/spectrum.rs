//! The kernel's spectrum: the kernel table K on the lattice's offsets,
//! embedded in the even `P1 x P2` circulant Kc, and its transform
//!
//! ```text
//!     DFT(Kc)[m1, m2] / (P1 P2),     m1 <= P1/2, m2 <= P2/2   (real: Kc is even)
//! ```
//!
//! by real transforms of the even extensions, rows then columns.

use realfft::RealFftPlanner;

use super::grid::{C64, Grid};
use crate::error::InfluenceError;
use crate::error::try_vec;
use crate::terms::Terms;

/// The kernel table of the bodies on the lattice's offsets (the one
/// [`assemble`](crate::assemble) gathers from, computed into the result)
/// and its spectrum `DFT(Kc) / (P1 P2)` on `(P1/2 + 1) x (P2/2 + 1)`
/// frequencies (see [`Convolution::spectrum`](super::convolution::Convolution::spectrum)); also the table's self-term.
/// Kc is even along both axes, so both stages are real transforms of even
/// sequences whose real parts are kept (the imaginary parts are rounding).
/// The row stage writes its spectra into the result, transposed (frequency
/// m2's values over i where the column stage reads them, `n1 <= P1/2 + 1`),
/// and the column stage transforms them in place: nothing of the box's
/// size is allocated but the result, which first holds the table, and the
/// table's copy kept for the operator's columns
/// ([`Convolution::add_columns`](super::convolution::Convolution::add_columns):
/// `n1 x n2` values, offset `(di, dj)` at `di n2 + dj`).
pub(super) fn kernel_spectrum(
    terms: &Terms,
    grid: &Grid,
    planner: &mut RealFftPlanner<f64>,
) -> Result<(Vec<f64>, Vec<f64>, f64), InfluenceError> {
    let (n1, n2) = (grid.rows, grid.columns);
    let half_rows = grid.half_rows();
    let row_fft = planner.plan_fft_forward(grid.padded_columns);
    let column_fft = planner.plan_fft_forward(grid.padded_rows);
    let zero = C64::new(0.0, 0.0);
    let mut scratch = vec![zero; row_fft.get_scratch_len().max(column_fft.get_scratch_len())];
    let mut spectrum = try_vec(grid.spectrum_len(), 0.0, "kernel spectrum")?;
    // The kernel table, transposed into the result (offset (di, dj) at
    // dj * half_rows + di: n2 <= P2/2 + 1 columns of n1 <= P1/2 + 1), so
    // that the row stage reads row di before it writes frequency m2's
    // values over the same di.
    terms.fill_table(n1, n2, &mut spectrum, (1, half_rows));
    let self_term = spectrum[0];
    let mut table = try_vec(n1 * n2, 0.0, "kernel table")?;
    for (di, row) in table.chunks_exact_mut(n2).enumerate() {
        for (dj, v) in row.iter_mut().enumerate() {
            *v = spectrum[dj * half_rows + di];
        }
    }
    // Rows: the even extension of each offset row di, transformed along j.
    let mut values = vec![0.0; n2];
    let mut row = vec![0.0; grid.padded_columns];
    let mut row_spectrum = vec![zero; grid.half_columns()];
    for di in 0..n1 {
        for (dj, v) in values.iter_mut().enumerate() {
            *v = spectrum[dj * half_rows + di];
        }
        even_extension(&values, &mut row);
        row_fft
            .process_with_scratch(&mut row, &mut row_spectrum, &mut scratch)
            .expect("buffer lengths follow the plan");
        for (m2, z) in row_spectrum.iter().enumerate() {
            spectrum[m2 * half_rows + di] = z.re;
        }
    }
    // Columns: the even extension along i of each frequency m2.
    let scale = 1.0 / (grid.padded_rows as f64 * grid.padded_columns as f64);
    let mut values = vec![0.0; n1];
    let mut column = vec![0.0; grid.padded_rows];
    let mut column_spectrum = vec![zero; half_rows];
    for out in spectrum.chunks_exact_mut(half_rows) {
        values.copy_from_slice(&out[..n1]);
        even_extension(&values, &mut column);
        column_fft
            .process_with_scratch(&mut column, &mut column_spectrum, &mut scratch)
            .expect("buffer lengths follow the plan");
        for (o, z) in out.iter_mut().zip(&column_spectrum) {
            *o = z.re * scale;
        }
    }
    Ok((spectrum, table, self_term))
}

/// `out` (length `P >= 2 n - 1`) = the even periodic extension of the
/// offsets `values[0..n]`: `out[b] = out[P - b] = values[b]`, 0 between.
fn even_extension(values: &[f64], out: &mut [f64]) {
    let (n, p) = (values.len(), out.len());
    debug_assert!(p + 1 >= 2 * n);
    out.fill(0.0);
    out[..n].copy_from_slice(values);
    for b in 1..n {
        out[p - b] = values[b];
    }
}
