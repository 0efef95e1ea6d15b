//! An approximate inverse of the lattice operator, for a preconditioned
//! conjugate gradient (Vollebregt 2014, "A new solver for the elastic
//! normal contact problem using conjugate gradients, deflation, and an
//! FFT-based preconditioner", J. Comput. Phys. 257): the inverse of the
//! operator's symbol, applied by a periodic FFT on the half-size grid
//! `Q1 x Q2`, `Q_a = P_a / 2 >= n_a` (the padded grid's halves, 5-smooth,
//! holding the box without padding):
//!
//! ```text
//!     z = IDFT_Q( DFT_Q(r) / Ŝ_Q ) / (Q1 Q2),     Ŝ_Q[m1, m2] = P1 P2 ŝ[2 m1, 2 m2] + 1/(k_w A)
//! ```
//!
//! with `ŝ = DFT(Kc) / (P1 P2)` the convolution's stored spectrum and the
//! Winkler diagonal added. `Ŝ_Q` is exactly the spectrum of the kernel
//! folded onto the periodic Q grid, `Kf[a] = Kc[a] + Kc[a + Q]`
//! (`DFT_P(Kc)` at the even frequencies `2 m` is `DFT_Q(Kf)` at `m`), so
//! `z` solves `Kf ⊛ z = r` on the periodic box: near `S^{-1} r` away from
//! the box's edges, the `|k|`-weighting (`Ŝ ~ 2 / (E* |k| h^2)`) that
//! undoes the half-space operator's smoothing. A value of `Ŝ_Q` below
//! [`SYMBOL_FLOOR`] times the largest is raised to it: the map stays
//! symmetric positive definite.
//!
//! Cost: `n1` real row transforms of length `Q2` and `Q2/2 + 1` complex
//! column transforms of length `Q1`, each forward and back: a quarter of
//! the product's transforms on the `P1 x P2` grid (half the rows, half the
//! columns, no second band). Memory: the symbol, `8 (Q1/2 + 1)(Q2/2 + 1)`
//! bytes (about 2 bytes a cell of the box), and the plans; an application
//! borrows a product's buffers (a [`LatticeWorkspace`](super::LatticeWorkspace)
//! or a caller's scratch stack): the box's row spectra,
//! `n1 x (Q2/2 + 1)` complex values, are exactly a band of the product's,
//! and the column stage works in place on them a wave of columns at a time
//! (gathered into the workspace's wave, transformed, written back), as the
//! product's does. Each row's and column's transform is done by one
//! thread, nothing summed across threads: the values do not depend on
//! their number, nor on the wave's size.

use realfft::RealFftPlanner;

use super::convolution::{Buffers, Convolution, columns_back, share};
use super::grid::{C64, COLUMN_BATCH, Plans, RowBuffers};
use crate::error::{InfluenceError, try_vec};

/// The symbol's floor: a value of `Ŝ_Q` below `max Ŝ_Q / (SYMBOL_FLOOR
/// max(Q1, Q2))` is raised to it. A half-space symbol falls like `1/|k|`,
/// from the lowest frequency to the highest by about `max(Q1, Q2)`: the
/// floor leaves it whole and keeps the map positive definite where the
/// windowed, truncated kernel's spectrum comes near 0.
pub const SYMBOL_FLOOR: f64 = 8.0;

/// The padded spectrum `ŝ` at `(j1, j2)` smoothed by `[1/4, 1/2, 1/4]`
/// along both axes: the spectrum of the kernel times the Hann window
/// `(1 + cos(2π a1/P1))(1 + cos(2π a2/P2)) / 4`, which tapers the kernel
/// to 0 at the padded grid's half-length. The box-truncated kernel's own
/// spectrum rings (Gibbs) and dips below 0 where `P = 2 n` exactly; the
/// window, a positive definite function, takes most of that away.
fn windowed(convolution: &Convolution, j1: usize, j2: usize) -> f64 {
    let g = convolution.grid;
    let stored = g.half_rows();
    // The spectrum is even with period P: index j reflected into 0..=P/2.
    let reflect = |j: isize, p: usize| {
        let j = j.unsigned_abs();
        if j > p / 2 { p - j } else { j }
    };
    let weights = [(-1isize, 0.25), (0, 0.5), (1, 0.25)];
    let mut sum = 0.0;
    for (d2, w2) in weights {
        let i2 = reflect(j2 as isize + d2, g.padded_columns);
        for (d1, w1) in weights {
            let i1 = reflect(j1 as isize + d1, g.padded_rows);
            sum += w1 * w2 * convolution.spectrum[i2 * stored + i1];
        }
    }
    sum
}

/// Rows or columns a thread takes up at least at once.
const LINES_PER_TASK: usize = 8;

/// The approximate inverse `r -> z` of a [`LatticeKernel`](super::LatticeKernel):
/// `z = IDFT_Q(DFT_Q(r) / Ŝ_Q) / (Q1 Q2)`, the inverse of the kernel's
/// symbol by a periodic FFT on the half-size grid `Q1 x Q2` (Vollebregt
/// 2014). It holds its symbol and plans, no buffer of the box's size (an
/// application borrows a product's workspace). Made by
/// [`LatticeKernel::preconditioner`](super::LatticeKernel::preconditioner),
/// applied by [`LatticeKernel::precondition_with`](super::LatticeKernel::precondition_with).
pub struct LatticePreconditioner {
    /// The box's rows and columns `n1 x n2`, the periodic grid `Q1 x Q2`.
    rows: usize,
    q1: usize,
    q2: usize,
    /// `1 / (Q1 Q2 Ŝ_Q[m1, m2])` at `m2 (Q1/2 + 1) + m1`, `m1 <= Q1/2`,
    /// `m2 <= Q2/2` (even in both).
    symbol: Vec<f64>,
    /// The FFT plans of its grid.
    plans: Plans,
}

impl std::fmt::Debug for LatticePreconditioner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LatticePreconditioner")
            .field("periodic_grid", &(self.q1, self.q2))
            .finish_non_exhaustive()
    }
}

impl LatticePreconditioner {
    /// The preconditioner of `convolution` with the Winkler diagonal
    /// `winkler` (see the module documentation).
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when its memory cannot be
    /// allocated.
    pub(super) fn new(convolution: &Convolution, winkler: f64) -> Result<Self, InfluenceError> {
        let g = convolution.grid;
        let (q1, q2) = (g.padded_rows / 2, g.padded_columns / 2);
        let (h1, h2) = (q1 / 2 + 1, q2 / 2 + 1);
        let scale = g.padded_rows as f64 * g.padded_columns as f64;
        let mut symbol = try_vec(h1 * h2, 0.0, "preconditioner symbol")?;
        for m2 in 0..h2 {
            for m1 in 0..h1 {
                symbol[m2 * h1 + m1] = scale * windowed(convolution, 2 * m1, 2 * m2) + winkler;
            }
        }
        let largest = symbol.iter().fold(0.0f64, |m, &v| m.max(v));
        let floor = largest / (SYMBOL_FLOOR * q1.max(q2) as f64);
        let periodic = q1 as f64 * q2 as f64;
        for v in &mut symbol {
            *v = 1.0 / (periodic * v.max(floor));
        }
        let plans = Plans::new(&mut RealFftPlanner::<f64>::new(), q1, q2);
        Ok(Self {
            rows: g.rows,
            q1,
            q2,
            symbol,
            plans,
        })
    }

    /// The periodic grid `(Q1, Q2)` it works on.
    pub fn periodic_grid(&self) -> (usize, usize) {
        (self.q1, self.q2)
    }

    /// Bytes held: the symbol (the plans, O(Q1 + Q2), are left out; the
    /// buffers are the workspace's).
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>() + 8 * self.symbol.capacity()
    }

    /// `z = IDFT(DFT(r) / Ŝ_Q) / (Q1 Q2)` on the box, `r` spread on it and
    /// `z` gathered from it by `convolution`'s gather order, in the buffers
    /// of `ws` (a workspace of `convolution`'s grid: its row spectra hold
    /// `n1` rows of `Q2/2 + 1` values, its wave at least one column of Q1).
    pub(super) fn apply(
        &self,
        convolution: &Convolution,
        r: &[f64],
        z: &mut [f64],
        ws: Buffers<'_>,
    ) {
        let Buffers {
            spectra,
            columns: wave,
        } = ws;
        let spectra = &mut spectra[..self.rows * (self.q2 / 2 + 1)];
        self.rows_forward(convolution, r, spectra);
        self.columns_times_symbol(spectra, wave);
        self.rows_inverse(convolution, spectra, z);
    }

    /// Each lattice row of `r`, zero-padded to Q2, to its half spectrum in
    /// `spectra` (the rows shared among the threads).
    fn rows_forward(&self, convolution: &Convolution, r: &[f64], spectra: &mut [C64]) {
        let gather = &convolution.gather;
        share(
            spectra.chunks_mut(self.q2 / 2 + 1).collect(),
            LINES_PER_TASK,
            || self.plans.row_buffers(),
            |b, i, out| {
                b.row.fill(0.0);
                for s in gather.row(i) {
                    b.row[s.columns()].copy_from_slice(&r[s.points()]);
                }
                self.plans
                    .row_forward
                    .process_with_scratch(&mut b.row, out, &mut b.scratch)
                    .expect("buffer lengths follow the plan");
            },
        );
    }

    /// Each column of the row spectra, zero-padded from n1 to Q1,
    /// transformed, divided by the symbol and transformed back, in place: a
    /// wave of columns (as many Q1-long columns as `wave` holds) at a time,
    /// in batches of [`COLUMN_BATCH`] shared among the threads, then the
    /// first n1 values of each written back into its rows (the rows shared
    /// among the threads).
    fn columns_times_symbol(&self, spectra: &mut [C64], wave: &mut [C64]) {
        let (q1, h2) = (self.q1, self.q2 / 2 + 1);
        let per_wave = wave.len() / q1;
        assert!(per_wave > 0, "the workspace's wave holds a column of Q1");
        for first in (0..h2).step_by(per_wave) {
            let width = per_wave.min(h2 - first);
            let rows = &*spectra;
            share(
                wave[..width * q1].chunks_mut(COLUMN_BATCH * q1).collect(),
                1,
                || self.plans.scratch(),
                |scratch, b, batch| {
                    self.batch_times_symbol(rows, first + b * COLUMN_BATCH, batch, scratch);
                },
            );
            columns_back(
                spectra.chunks_mut(h2).collect(),
                LINES_PER_TASK,
                first,
                &wave[..width * q1],
                q1,
            );
        }
    }

    /// One batch of columns: the row spectra's columns `at..` read from
    /// `spectra`, zero-padded to Q1, each transformed, multiplied by the
    /// symbol (even in m1: frequency `Q1 - m` is `m`'s) and transformed
    /// back in `batch`.
    fn batch_times_symbol(
        &self,
        spectra: &[C64],
        at: usize,
        batch: &mut [C64],
        scratch: &mut [C64],
    ) {
        let (n1, q1, h1, h2) = (self.rows, self.q1, self.q1 / 2 + 1, self.q2 / 2 + 1);
        let width = batch.len() / q1;
        for (i, row) in spectra.chunks_exact(h2).enumerate() {
            for (t, &v) in row[at..at + width].iter().enumerate() {
                batch[t * q1 + i] = v;
            }
        }
        for (t, column) in batch.chunks_exact_mut(q1).enumerate() {
            let m2 = at + t;
            column[n1..].fill(C64::new(0.0, 0.0));
            self.plans
                .column_forward
                .process_with_scratch(column, scratch);
            let symbol = &self.symbol[m2 * h1..(m2 + 1) * h1];
            for (m1, c) in column.iter_mut().enumerate() {
                *c *= symbol[m1.min(q1 - m1)];
            }
            self.plans
                .column_inverse
                .process_with_scratch(column, scratch);
        }
    }

    /// Each lattice row back from its spectrum, gathered into `z` (the rows
    /// shared among the threads when the points are in lattice-row order,
    /// each writing its own slice of `z`).
    fn rows_inverse(&self, convolution: &Convolution, spectra: &[C64], z: &mut [f64]) {
        let gather = &convolution.gather;
        let h2 = self.q2 / 2 + 1;
        let one_row = |b: &mut RowBuffers, i: usize, out: &mut [f64], base: usize| {
            self.row_back(b, &spectra[i * h2..(i + 1) * h2]);
            for s in gather.row(i) {
                let points = s.points();
                out[points.start - base..points.end - base].copy_from_slice(&b.row[s.columns()]);
            }
        };
        match gather.row_slices(z) {
            Some(slices) => share(
                slices,
                LINES_PER_TASK,
                || self.plans.row_buffers(),
                |b, i, out| {
                    let base = gather.row(i).first().map_or(0, |s| s.points().start);
                    one_row(b, i, out, base);
                },
            ),
            None => {
                let mut b = self.plans.row_buffers();
                for i in 0..self.rows {
                    one_row(&mut b, i, z, 0);
                }
            }
        }
    }

    /// The inverse row transform of one row's half spectrum into `b.row`.
    fn row_back(&self, b: &mut RowBuffers, spectrum: &[C64]) {
        let last = b.spectrum.len() - 1;
        b.spectrum.copy_from_slice(spectrum);
        // DC and (Q2 even) Nyquist of a real row are real; drop the rounding.
        b.spectrum[0].im = 0.0;
        if self.q2.is_multiple_of(2) {
            b.spectrum[last].im = 0.0;
        }
        self.plans
            .row_inverse
            .process_with_scratch(&mut b.spectrum, &mut b.row, &mut b.scratch)
            .expect("buffer lengths follow the plan");
    }
}

#[cfg(test)]
mod tests {
    use super::super::LatticeKernel;
    use crate::assembly::assemble;
    use crate::fixtures::{disk_and_reversed, pool};
    use crate::material::Material;
    use crate::models::Body;
    use crate::points::PointSet;

    fn steel() -> Material {
        Material::new(30e6, 0.3).unwrap()
    }

    /// On a box whose padded lengths are exactly `2 n` the periodic grid
    /// is the box (`Q = n`), and a Fourier mode `cos(2π (m1 i / Q1 + m2 j /
    /// Q2))` on it is an eigenvector of the periodic convolution by the
    /// folded, windowed kernel: the preconditioner returns it divided by
    /// the eigenvalue, computed here in closed form from the dense S's
    /// entries, `Σ_{a, b} Kf(a, b) cos(2π (m1 a / Q1 + m2 b / Q2))` with
    /// `Kf(a, b) = Σ w(a*) w(b*) K(a*, b*)` over the images `a* ∈ {a, a -
    /// Q}` of the table (`|a*| < n`) and the Hann window `w(a) = (1 +
    /// cos(2π a / P)) / 2`.
    #[test]
    fn divides_a_fourier_mode_by_the_folded_kernels_eigenvalue() {
        let cases = [
            (
                16,
                16,
                vec![Body::uniform_patch(steel()), Body::point_force(steel())],
            ),
            (
                10,
                8,
                vec![Body::uniform_patch(steel()), Body::winkler(3e8)],
            ),
        ];
        for (n1, n2, bodies) in cases {
            let points = PointSet::grid_rectangle(1.0, 0.7, n1, n2).unwrap();
            let refs: Vec<&Body> = bodies.iter().collect();
            let s = assemble(&points, &refs).unwrap();
            let kernel = LatticeKernel::new(&points, &refs).unwrap();
            let pc = kernel.preconditioner().unwrap().unwrap();
            let mut ws = kernel.workspace().unwrap();
            assert_eq!(pc.periodic_grid(), (n1, n2));
            let lattice = points.lattice().unwrap();
            let (i0, j0) = lattice
                .iter()
                .fold((i64::MAX, i64::MAX), |m, (i, j)| (m.0.min(i), m.1.min(j)));
            let at: Vec<(usize, usize)> = lattice
                .iter()
                .map(|(i, j)| ((i - i0) as usize, (j - j0) as usize))
                .collect();
            let origin = at.iter().position(|&c| c == (0, 0)).unwrap();
            let k_of = |a: i64, b: i64| {
                let c = (a.unsigned_abs() as usize, b.unsigned_abs() as usize);
                s[(origin, at.iter().position(|&p| p == c).unwrap())]
            };
            let (p1, p2) = (2.0 * n1 as f64, 2.0 * n2 as f64);
            let hann = |a: i64, p: f64| (1.0 + (std::f64::consts::TAU * a as f64 / p).cos()) / 2.0;
            let images = |a: usize, n: usize| {
                let mut v = vec![a as i64];
                if a > 0 {
                    v.push(a as i64 - n as i64);
                }
                v
            };
            for (m1, m2) in [
                (0, 0),
                (1, 0),
                (0, 3),
                (2, 5),
                (n1 / 2, n2 / 2),
                (n1 - 3, 1),
            ] {
                let phase = |i: usize, j: usize| {
                    std::f64::consts::TAU
                        * (m1 as f64 * i as f64 / n1 as f64 + m2 as f64 * j as f64 / n2 as f64)
                };
                let mut eigenvalue = 0.0;
                for a in 0..n1 {
                    for b in 0..n2 {
                        let mut folded = 0.0;
                        for &a_star in &images(a, n1) {
                            for &b_star in &images(b, n2) {
                                folded +=
                                    hann(a_star, p1) * hann(b_star, p2) * k_of(a_star, b_star);
                            }
                        }
                        eigenvalue += folded * phase(a, b).cos();
                    }
                }
                let x: Vec<f64> = at.iter().map(|&(i, j)| phase(i, j).cos()).collect();
                let mut z = vec![0.0; x.len()];
                kernel.precondition_with(&x, &mut z, &pc, &mut ws);
                let scale = 1.0 / eigenvalue.abs();
                for (k, (&xk, &zk)) in x.iter().zip(&z).enumerate() {
                    assert!(
                        (zk - xk / eigenvalue).abs() <= 1e-10 * scale,
                        "{n1} x {n2}, mode ({m1}, {m2}), point {k}: {zk:e} against {:e}",
                        xk / eigenvalue
                    );
                }
            }
        }
    }

    /// The preconditioner holds its symbol and no buffer of the box's
    /// size: `8 (Q1/2 + 1)(Q2/2 + 1)` bytes (about 2 a cell of the box) and
    /// its struct, and an application needs no workspace but a product's.
    #[test]
    fn holds_only_its_symbol() {
        let points = PointSet::grid_disk(1.0, 60.0).unwrap();
        let kernel = LatticeKernel::new(&points, &[&Body::uniform_patch(steel())]).unwrap();
        let pc = kernel.preconditioner().unwrap().unwrap();
        let (q1, q2) = pc.periodic_grid();
        let symbol = 8 * (q1 / 2 + 1) * (q2 / 2 + 1);
        assert_eq!(
            pc.memory_bytes(),
            symbol + std::mem::size_of_val(&pc),
            "{q1} x {q2}"
        );
        assert!(pc.memory_bytes() < 3 * q1 * q2, "{q1} x {q2}");
    }

    #[test]
    fn a_foundation_alone_has_none() {
        let points = PointSet::grid_rectangle(1.0, 1.0, 6, 6).unwrap();
        let kernel = LatticeKernel::new(&points, &[&Body::winkler(3e8), &Body::rigid()]).unwrap();
        assert!(kernel.preconditioner().unwrap().is_none());
    }

    #[test]
    fn the_same_to_the_bit_on_any_number_of_threads() {
        // A disk in lattice-row order (rows written in parallel) and the
        // same points reversed (gathered on the caller's thread).
        let bodies = [&Body::uniform_patch(steel()), &Body::point_force(steel())];
        for (name, points) in disk_and_reversed() {
            let kernel = LatticeKernel::new(&points, &bodies).unwrap();
            let r: Vec<f64> = (0..points.len())
                .map(|k| ((k * 7919) % 1000) as f64 - 500.0)
                .collect();
            // On `threads`, with a workspace made on `made_on` threads (its
            // wave of columns sized for them), `dirty` after a product.
            let on = |threads: usize, made_on: usize, dirty: bool| {
                let mut ws = pool(made_on).install(|| kernel.workspace().unwrap());
                pool(threads).install(|| {
                    let pc = kernel.preconditioner().unwrap().unwrap();
                    let mut z = vec![0.0; r.len()];
                    if dirty {
                        kernel.apply_with(&r, &mut z, &mut ws);
                    }
                    kernel.precondition_with(&r, &mut z, &pc, &mut ws);
                    z.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
                })
            };
            let one = on(1, 1, false);
            assert!(one.iter().any(|&b| f64::from_bits(b) != 0.0), "{name}");
            for (threads, made_on, dirty) in
                [(2, 2, false), (3, 3, true), (1, 3, true), (3, 1, false)]
            {
                assert!(
                    one == on(threads, made_on, dirty),
                    "{name}: {threads} threads, a workspace of {made_on}, dirty: {dirty}"
                );
            }
        }
    }

    #[test]
    #[should_panic(expected = "the workspace was made for an operator of another grid")]
    fn a_workspace_of_another_grid_panics() {
        let bodies = [&Body::uniform_patch(steel())];
        let small = PointSet::grid_rectangle(1.0, 1.0, 6, 6).unwrap();
        let large = PointSet::grid_rectangle(1.0, 1.0, 12, 12).unwrap();
        let kernel = LatticeKernel::new(&small, &bodies).unwrap();
        let other = LatticeKernel::new(&large, &bodies).unwrap();
        let pc = kernel.preconditioner().unwrap().unwrap();
        let mut ws = other.workspace().unwrap();
        let (r, mut z) = (vec![1.0; small.len()], vec![0.0; small.len()]);
        kernel.precondition_with(&r, &mut z, &pc, &mut ws);
    }
}
