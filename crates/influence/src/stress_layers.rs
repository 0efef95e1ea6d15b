//! The stresses at one depth below every point of a lattice, by
//! zero-padded FFT convolution: on a lattice the stress influence
//! coefficient of a cell depends on the offset of the lattice indices
//! alone, so each component of a depth layer is a discrete convolution of
//! the pressures,
//!
//! ```text
//!     sigma_c(i, j; z) = sum_(i', j') p(i', j') T_c((i - i') dx, (j - j') dy, z)
//! ```
//!
//! computed as the pointwise product of the spectra on a box of at least
//! twice the lattice's extent less one (no wrap-around; the smallest even
//! 5-smooth length, fast for the FFT), `O(N log N)` a component, instead of
//! the direct sum's `O(N N_contact)`. T is Love's uniform pressure on the
//! cell ([`love_rectangle_stress`]) or a point force's
//! ([`point_force`], times the cell's area); on a line, the strip's
//! ([`strip_stress`]), a one-dimensional convolution. Memory: the pressure
//! spectrum and one product buffer (about 32 bytes a box cell each, half a
//! spectrum of reals), and the layer's six components at the points (48
//! bytes a point): about 112 bytes a point at each depth, nothing kept
//! between depths but what the caller keeps.

use realfft::RealFftPlanner;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

use crate::dimension::Dimension;
use crate::error::{InfluenceError, try_vec};
use crate::lattice_operator::padded_length;
use crate::models::{Body, Model};
use crate::points::PointSet;
use crate::stress::{
    Stress, love_rectangle_stress, love_rectangle_table, point_force, strip_stress,
};

/// Which stress influence coefficient a layer is computed with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum StressKernel {
    /// Love's uniform pressure on each cell (surface).
    Rectangle,
    /// A point force at each cell's centre (surface; valid a cell or more
    /// below it).
    PointForce,
    /// A uniform strip in plane strain (line).
    Strip,
}

impl StressKernel {
    /// The kernel of a body's model and its Poisson's ratio, or why the
    /// body has no field below its surface (a rigid body, a Winkler
    /// foundation, a beam).
    ///
    /// # Errors
    /// The reason, for a body that is not an elastic half-space.
    pub fn of(body: &Body) -> Result<(StressKernel, f64), &'static str> {
        match body.model() {
            Model::UniformPatch { material } => {
                Ok((StressKernel::Rectangle, material.poissons_ratio()))
            }
            Model::PointForce { material } => {
                Ok((StressKernel::PointForce, material.poissons_ratio()))
            }
            Model::PlaneStrainStrip { material, .. } => {
                Ok((StressKernel::Strip, material.poissons_ratio()))
            }
            Model::Rigid => Err("a rigid body has no stresses"),
            Model::Winkler { .. } => {
                Err("a Winkler foundation is not a half-space: no stresses below its surface")
            }
            _ => Err("a beam is not a half-space: its stresses are its bending's"),
        }
    }

    /// The stress at `(x, y)` from a cell's centre and depth `z` > 0 of a
    /// unit pressure on the cell of `dx` x `dy` (the point force of the
    /// cell's area for [`StressKernel::PointForce`]; `dy` unused on a
    /// line), Poisson's ratio `nu`.
    pub fn unit(self, (x, y, z): (f64, f64, f64), (dx, dy): (f64, f64), nu: f64) -> Stress {
        match self {
            StressKernel::Rectangle => love_rectangle_stress(x, y, z, dx, dy, nu),
            StressKernel::Strip => strip_stress(x, z, dx, nu),
            StressKernel::PointForce => {
                let mut s = Stress::default();
                s.add_scaled(dx * dy, &point_force(x, y, z, nu));
                s
            }
        }
    }
}

/// The stress layers of one pressure field on a lattice (see the module
/// documentation).
pub struct StressLayers {
    /// The points' offsets in the box, `(i - i0, j - j0)`.
    offsets: Vec<(usize, usize)>,
    /// Rows of the padded grid that hold points (the lattice's extent
    /// along i): the inverse transform writes only these.
    rows: usize,
    /// The box: padded sizes along i (x) and j (y).
    size: (usize, usize),
    cell: (f64, f64),
    nu: f64,
    kernel: StressKernel,
    /// The pressures' spectrum (real to complex along j, complex along i).
    spectrum: Vec<Complex<f64>>,
    forward_j: Arc<dyn realfft::RealToComplex<f64>>,
    inverse_j: Arc<dyn realfft::ComplexToReal<f64>>,
    forward_i: Arc<dyn Fft<f64>>,
    inverse_i: Arc<dyn Fft<f64>>,
}

impl StressLayers {
    /// The layers of `pressures` (one per point, stress) on `points`, which
    /// must be a lattice.
    ///
    /// # Errors
    /// [`InfluenceError::LatticeRequired`] when the points are not a
    /// lattice; [`InfluenceError::AllocationFailed`] when the box's spectra
    /// cannot be allocated.
    pub fn new(
        points: &PointSet,
        pressures: &[f64],
        kernel: StressKernel,
        nu: f64,
    ) -> Result<Self, InfluenceError> {
        let lattice = points
            .lattice()
            .ok_or_else(|| InfluenceError::LatticeRequired {
                reason: "stress layers by FFT need the points on a lattice".into(),
            })?;
        let indices: Vec<(i64, i64)> = lattice.iter().collect();
        let (i0, j0) = indices
            .iter()
            .fold((i64::MAX, i64::MAX), |(a, b), &(i, j)| (a.min(i), b.min(j)));
        let (i1, j1) = indices
            .iter()
            .fold((i64::MIN, i64::MIN), |(a, b), &(i, j)| (a.max(i), b.max(j)));
        let extent = ((i1 - i0 + 1) as usize, (j1 - j0 + 1) as usize);
        let line = points.dimension() == Dimension::Line;
        let size = (
            padded_length(extent.0),
            if line { 1 } else { padded_length(extent.1) },
        );
        let offsets: Vec<(usize, usize)> = indices
            .iter()
            .map(|&(i, j)| ((i - i0) as usize, (j - j0) as usize))
            .collect();
        let cell = points.cell();
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        let mut layers = Self {
            offsets,
            rows: extent.0,
            size,
            cell: (cell.dx, cell.dy),
            nu,
            kernel,
            spectrum: Vec::new(),
            forward_j: real.plan_fft_forward(size.1.max(2)),
            inverse_j: real.plan_fft_inverse(size.1.max(2)),
            forward_i: complex.plan_fft_forward(size.0),
            inverse_i: complex.plan_fft_inverse(size.0),
        };
        let mut grid = try_vec(size.0 * layers.padded_j(), 0.0, "a stress layer")?;
        for (&(i, j), &p) in layers.offsets.iter().zip(pressures) {
            grid[i * layers.padded_j() + j] = p;
        }
        let mut spectrum = try_vec(
            layers.spectrum_len(),
            Complex::default(),
            "a stress layer's spectrum",
        )?;
        layers.forward(&mut grid, &mut spectrum);
        layers.spectrum = spectrum;
        Ok(layers)
    }

    /// The values of a spectrum: `P_i (P_j / 2 + 1)`.
    fn spectrum_len(&self) -> usize {
        self.size.0 * (self.padded_j() / 2 + 1)
    }

    /// The real length along j (at least 2, as realfft needs).
    fn padded_j(&self) -> usize {
        self.size.1.max(2)
    }

    /// The spectrum of the real `grid` (rows of `padded_j` along j; used
    /// as scratch) into `spectrum`.
    fn forward(&self, grid: &mut [f64], spectrum: &mut [Complex<f64>]) {
        let nj = self.padded_j();
        let half = nj / 2 + 1;
        for (row, out) in grid.chunks_mut(nj).zip(spectrum.chunks_mut(half)) {
            self.forward_j
                .process(row, out)
                .expect("the plan's own lengths");
        }
        along_i(&*self.forward_i, spectrum, half);
    }

    /// The real grid of a spectrum (scaled by the FFT lengths) into `grid`,
    /// on the rows that hold points (the others are left as they are);
    /// the spectrum is scratch.
    fn inverse(&self, spectrum: &mut [Complex<f64>], grid: &mut [f64]) {
        let (ni, nj) = (self.size.0, self.padded_j());
        let half = nj / 2 + 1;
        along_i(&*self.inverse_i, spectrum, half);
        let rows = grid.chunks_mut(nj).zip(spectrum.chunks_mut(half));
        for (row, input) in rows.take(self.rows) {
            // The imaginary parts of the first and last bins are rounding.
            input[0].im = 0.0;
            if nj % 2 == 0 {
                input[half - 1].im = 0.0;
            }
            self.inverse_j
                .process(input, row)
                .expect("the plan's own lengths");
        }
        let scale = 1.0 / (ni * nj) as f64;
        grid[..self.rows * nj].iter_mut().for_each(|v| *v *= scale);
    }

    /// The kernel's stress at the lattice offset `(di, dj)` and depth `z`.
    fn coefficient(&self, di: i64, dj: i64, z: f64) -> Stress {
        let (dx, dy) = self.cell;
        self.kernel
            .unit((di as f64 * dx, dj as f64 * dy, z), self.cell, self.nu)
    }

    /// The stresses at depth `z` > 0 below every point, in the points'
    /// order.
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when a layer's buffers cannot be
    /// allocated.
    pub fn layer(&self, z: f64) -> Result<Vec<Stress>, InfluenceError> {
        let (ni, nj) = (self.size.0, self.padded_j());
        let line = self.size.1 == 1;
        // The coefficients at offsets of one sign, each computed once with
        // its six components: the other signs follow by parity (xx, yy, zz
        // even in both offsets, xy odd in both, xz odd in i, yz odd in j;
        // the cell is symmetric). The box holds offsets -n/2 .. n/2 - 1.
        let (qi, qj) = (ni / 2, if line { 1 } else { nj / 2 });
        let mut quarter: Vec<Stress> = Vec::new();
        quarter
            .try_reserve_exact(qi * qj)
            .map_err(|_| InfluenceError::AllocationFailed {
                what: "a stress layer's coefficients",
                bytes: qi * qj * std::mem::size_of::<Stress>(),
            })?;
        match self.kernel {
            StressKernel::Rectangle => {
                love_rectangle_table((qi, qj), z, self.cell, self.nu, &mut quarter);
            }
            _ => {
                for di in 0..qi {
                    for dj in 0..qj {
                        quarter.push(self.coefficient(di as i64, dj as i64, z));
                    }
                }
            }
        }
        let components: [fn(&Stress) -> f64; 6] =
            [|s| s.xx, |s| s.yy, |s| s.zz, |s| s.xy, |s| s.xz, |s| s.yz];
        // The signs of a component at negative offsets along i and j.
        let parity: [(f64, f64); 6] = [
            (1.0, 1.0),
            (1.0, 1.0),
            (1.0, 1.0),
            (-1.0, -1.0),
            (-1.0, 1.0),
            (1.0, -1.0),
        ];
        let mut out = vec![Stress::default(); self.offsets.len()];
        let mut grid = try_vec(ni * nj, 0.0, "a stress layer")?;
        let mut values = try_vec(ni * nj, 0.0, "a stress layer")?;
        let mut product = try_vec(
            self.spectrum_len(),
            Complex::default(),
            "a stress layer's spectrum",
        )?;
        let mut row = vec![0.0; qj];
        for (c, (component, (si, sj))) in components.iter().zip(parity).enumerate() {
            for (i, cells) in grid.chunks_exact_mut(nj).enumerate() {
                // The offsets of box row i, wrapped: row di of the quarter
                // with the sign of negative offsets along i.
                let (di, fi) = if i < qi { (i, 1.0) } else { (ni - i, si) };
                cells.fill(0.0);
                if di >= qi {
                    continue;
                }
                for (v, s) in row.iter_mut().zip(&quarter[di * qj..(di + 1) * qj]) {
                    *v = fi * component(s);
                }
                if line {
                    cells[0] = row[0];
                    continue;
                }
                cells[..qj].copy_from_slice(&row);
                // Negative offsets along j: cell nj - dj holds offset -dj.
                for dj in 1..qj.min(nj - qj + 1) {
                    cells[nj - dj] = sj * row[dj];
                }
            }
            self.forward(&mut grid, &mut product);
            product
                .iter_mut()
                .zip(&self.spectrum)
                .for_each(|(a, b)| *a *= b);
            self.inverse(&mut product, &mut values);
            let set: fn(&mut Stress, f64) = match c {
                0 => |s, v| s.xx = v,
                1 => |s, v| s.yy = v,
                2 => |s, v| s.zz = v,
                3 => |s, v| s.xy = v,
                4 => |s, v| s.xz = v,
                _ => |s, v| s.yz = v,
            };
            for (s, &(i, j)) in out.iter_mut().zip(&self.offsets) {
                set(s, values[i * nj + j]);
            }
        }
        Ok(out)
    }
}

/// `fft` of every column of `spectrum` (rows of `half` values), in place:
/// the transform along i of the row spectra, [`COLUMN_BATCH`] columns at
/// a time (each row's values of a batch read at once, the batch's columns
/// transformed by one call).
fn along_i(fft: &dyn Fft<f64>, spectrum: &mut [Complex<f64>], half: usize) {
    let ni = spectrum.len() / half;
    let mut batch = vec![Complex::default(); ni * COLUMN_BATCH];
    let mut scratch = vec![Complex::default(); fft.get_inplace_scratch_len()];
    for first in (0..half).step_by(COLUMN_BATCH) {
        let width = COLUMN_BATCH.min(half - first);
        let batch = &mut batch[..ni * width];
        for i in 0..ni {
            let row = &spectrum[i * half + first..i * half + first + width];
            for (t, &v) in row.iter().enumerate() {
                batch[t * ni + i] = v;
            }
        }
        fft.process_with_scratch(batch, &mut scratch);
        for i in 0..ni {
            let row = &mut spectrum[i * half + first..i * half + first + width];
            for (t, v) in row.iter_mut().enumerate() {
                *v = batch[t * ni + i];
            }
        }
    }
}

/// Columns of the spectra transformed together along i.
const COLUMN_BATCH: usize = 16;

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct sum at point `k`.
    fn direct(points: &PointSet, pressures: &[f64], k: usize, z: f64, nu: f64) -> Stress {
        let cell = points.cell();
        let mut total = Stress::default();
        for (l, &p) in pressures.iter().enumerate() {
            let s = if points.dimension() == Dimension::Line {
                strip_stress(points.x(k) - points.x(l), z, cell.dx, nu)
            } else {
                love_rectangle_stress(
                    points.x(k) - points.x(l),
                    points.y(k) - points.y(l),
                    z,
                    cell.dx,
                    cell.dy,
                    nu,
                )
            };
            total.add_scaled(p, &s);
        }
        total
    }

    #[test]
    fn a_layer_by_fft_is_the_direct_sum() {
        let points = PointSet::grid_disk(0.1, 0.75).unwrap();
        let pressures: Vec<f64> = (0..points.len())
            .map(|k| {
                (1.0 - points.radius(k).powi(2) / 0.6f64.powi(2))
                    .max(0.0)
                    .sqrt()
                    + 0.01 * points.x(k)
            })
            .collect();
        let layers = StressLayers::new(&points, &pressures, StressKernel::Rectangle, 0.3).unwrap();
        for z in [0.05, 0.3, 0.9] {
            let layer = layers.layer(z).unwrap();
            for k in [0, points.len() / 3, points.len() / 2, points.len() - 1] {
                let d = direct(&points, &pressures, k, z, 0.3);
                for (a, b) in [
                    (layer[k].xx, d.xx),
                    (layer[k].yy, d.yy),
                    (layer[k].zz, d.zz),
                    (layer[k].xy, d.xy),
                    (layer[k].xz, d.xz),
                    (layer[k].yz, d.yz),
                ] {
                    assert!((a - b).abs() < 1e-12, "z = {z}, point {k}: {a} {b}");
                }
            }
        }
        let line = PointSet::line(-1.0, 1.0, 21).unwrap();
        let p: Vec<f64> = (0..21).map(|k| 1.0 - line.x(k).powi(2)).collect();
        let layers = StressLayers::new(&line, &p, StressKernel::Strip, 0.3).unwrap();
        let layer = layers.layer(0.4).unwrap();
        for k in [0, 10, 20] {
            let d = direct(&line, &p, k, 0.4, 0.3);
            assert!((layer[k].xx - d.xx).abs() < 1e-12 && (layer[k].xz - d.xz).abs() < 1e-12);
        }
    }
}
