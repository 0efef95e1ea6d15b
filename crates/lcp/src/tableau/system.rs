//! The linear system `A x = b` every method pivots on, stored by columns, and
//! its equilibration.
//!
//! A column of `A` is either dense (a column of one dense `m x n_d` faer
//! matrix) or a unit column `coef * e_row` (slacks, artificials, the `w` of an
//! LCP). Equilibration (Ruiz 2001, on max-norms) scales `A' = R A C`,
//! `b' = R b`, `x = C x'` with `R`, `C` diagonal powers of two: power-of-two
//! scaling is exact in floating point, so the scaled data *is* the original
//! data in other units, and refactorizing from it is refactorizing from the
//! original.

use faer::prelude::*;
use faer::{Col, Mat, MatMut, Par};

use crate::linalg::Lu;
pub(crate) use crate::program::Column;
use crate::tolerance::ROUNDING_LEVEL;

/// Most geometric-mean passes of the equilibration (two bring a spread of
/// 1e11 between blocks down to the data's own; Ruiz passes finish).
const GEOMETRIC_PASSES: usize = 4;

/// Most Ruiz passes of the equilibration (it stops earlier once every row
/// and column maximum is within a factor 2 of 1).
pub(crate) const EQUILIBRATION_PASSES: usize = 40;

/// A basis, or a block, that is numerically singular: its LU's smallest
/// over largest pivot magnitude (0 when a row is covered twice).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Singular {
    /// Smallest over largest magnitude on U's diagonal.
    pub ratio: f64,
}

impl Singular {
    /// The engine's error for a singular basis met at `pivot` in a tableau
    /// of `size` rows.
    pub fn at(self, size: usize, pivot: usize) -> crate::LcpError {
        crate::LcpError::SingularBasis {
            size,
            pivot,
            ratio: self.ratio,
        }
    }
}

/// `A x = b` with optional cost vectors (one per objective row).
#[derive(Debug, Clone)]
pub(crate) struct System {
    /// Number of rows `m`.
    pub rows: usize,
    /// The dense columns.
    pub dense: Mat<f64>,
    /// Every column of `A`, in variable order.
    pub columns: Vec<Column>,
    /// Right-hand side `b`.
    pub b: Col<f64>,
    /// Cost vectors `c` (length = number of variables), one per objective row.
    pub costs: Vec<Vec<f64>>,
    /// Column scale of each variable: `x = col_scale * x'` (1 when unscaled).
    pub col_scale: Vec<f64>,
    /// Row scale: `b' = row_scale * b` (1 when unscaled).
    pub row_scale: Vec<f64>,
}

impl System {
    /// Number of variables.
    pub fn vars(&self) -> usize {
        self.columns.len()
    }

    /// Writes column `var` of `A` into `out` (length `rows`).
    pub fn write_column(&self, var: usize, mut out: faer::ColMut<'_, f64>, factor: f64) {
        match self.columns[var] {
            Column::Dense(j) => {
                let src = &self.dense.col_as_slice(j)[..self.rows];
                match out.rb_mut().try_as_col_major_mut() {
                    Some(out) => {
                        for (o, a) in out.as_slice_mut().iter_mut().zip(src) {
                            *o = factor * a;
                        }
                    }
                    None => {
                        for (i, a) in src.iter().enumerate() {
                            out[i] = factor * a;
                        }
                    }
                }
            }
            Column::Unit { row, coef } => {
                out.fill(0.0);
                out[row] = factor * coef;
            }
        }
    }

    /// Gathers the columns `vars` of `A` (times `factor`) into the columns of `out`.
    pub fn gather(&self, vars: &[usize], mut out: MatMut<'_, f64>, factor: f64) {
        for (k, &v) in vars.iter().enumerate() {
            self.write_column(v, out.rb_mut().col_mut(k), factor);
        }
    }

    /// `A x` for the full vector `x`, and the magnitude of its terms `|A| |x|`.
    pub fn apply_with_terms(&self, x: &[f64]) -> (Col<f64>, Col<f64>) {
        let mut y = Col::<f64>::zeros(self.rows);
        let mut terms = Col::<f64>::zeros(self.rows);
        for (var, col) in self.columns.iter().enumerate() {
            let xv = x[var];
            if xv == 0.0 {
                continue;
            }
            match *col {
                Column::Dense(j) => {
                    for i in 0..self.rows {
                        let a = self.dense[(i, j)] * xv;
                        y[i] += a;
                        terms[i] += a.abs();
                    }
                }
                Column::Unit { row, coef } => {
                    y[row] += coef * xv;
                    terms[row] += (coef * xv).abs();
                }
            }
        }
        (y, terms)
    }

    /// Equilibrates in place: geometric-mean scaling, then Ruiz on max-norms,
    /// rounded to powers of two.
    ///
    /// Only the dense columns take part: a unit column `coef * e_row` can be
    /// given any scale, so it is scaled afterwards to keep `|coef'| = 1`
    /// exactly (slack and artificial columns stay identity columns).
    ///
    /// Max-norm scaling alone is not enough: `[-S e; e^T 0]` with S in m/N
    /// (entries ~1e-11) already has every row and column maximum equal to 1
    /// (the ones), so Ruiz leaves S eleven orders of magnitude below the
    /// pivot tolerance. Geometric scaling (`r_i = 1 / sqrt(max_j |a_ij| min_j
    /// |a_ij|)` over the non-zeros, then the same for columns; Fulkerson &
    /// Wolfe 1962, as in LP codes) brings the spread of every row and column
    /// to its geometric middle; Ruiz passes then bring every maximum to
    /// within a factor 2 of 1. `iterations` bounds the passes of each; the
    /// sweeps over the dense block use up to `par`'s threads.
    pub fn equilibrate(&mut self, iterations: usize, par: Par) {
        let threads = self.sweep_threads(par);
        let m = self.rows;
        let nv = self.vars();
        let mut r = vec![1.0f64; m];
        let mut c = vec![1.0f64; nv];
        let dense: Vec<(usize, usize)> = self
            .columns
            .iter()
            .enumerate()
            .filter_map(|(var, col)| match *col {
                Column::Dense(j) => Some((var, j)),
                Column::Unit { .. } => None,
            })
            .collect();
        // A symmetric positive definite block (an influence matrix) is
        // balanced by its diagonal: with r_i = c_i = |a_ii|^(-1/2) every
        // entry is at most 1 in magnitude and the diagonal is 1. The rows and
        // columns without a diagonal (equality rows, the approach's column)
        // are then scaled by their own largest entry. When that guess holds,
        // one Ruiz sweep confirms it and the geometric stage is not needed.
        let guessed = self.diagonal_guess(&dense, &mut r, &mut c);
        // Both stages update rows and columns together from one sweep over
        // the block (as Ruiz's algorithm does), so a pass costs one read of
        // the matrix. Geometric passes (at most GEOMETRIC_PASSES) bring every
        // row's and column's largest and smallest entry to reciprocal values;
        // they stop early when the largest spread no longer halves.
        let mut last_spread = f64::INFINITY;
        let geometric = if guessed {
            0
        } else {
            iterations.min(GEOMETRIC_PASSES)
        };
        for _ in 0..geometric {
            let (rows, cols) = self.extremes(&dense, &r, &c, threads);
            let mut spread = 1.0f64;
            for (i, &(hi, lo)) in rows.iter().enumerate() {
                if hi > 0.0 {
                    r[i] /= (hi * lo).sqrt().sqrt();
                    spread = spread.max(hi / lo);
                }
            }
            for (&(var, _), &(hi, lo)) in dense.iter().zip(&cols) {
                if hi > 0.0 {
                    c[var] /= (hi * lo).sqrt().sqrt();
                    spread = spread.max(hi / lo);
                }
            }
            if spread > 0.5 * last_spread {
                break;
            }
            last_spread = spread;
        }
        // Ruiz passes on max-norms, until every row and column maximum is
        // within a factor 2 of 1.
        for _ in 0..iterations {
            let (rows, cols) = self.extremes(&dense, &r, &c, threads);
            let mut balanced = true;
            for (i, &(hi, _)) in rows.iter().enumerate() {
                if hi > 0.0 {
                    balanced &= (0.5..=2.0).contains(&hi);
                    r[i] /= hi.sqrt();
                }
            }
            for (&(var, _), &(hi, _)) in dense.iter().zip(&cols) {
                if hi > 0.0 {
                    balanced &= (0.5..=2.0).contains(&hi);
                    c[var] /= hi.sqrt();
                }
            }
            if balanced {
                break;
            }
        }
        // Round to powers of two. Unit columns get exactly 1 / (r |coef|), so a
        // unit column with |coef| = 1 stays an identity column.
        let pow2 = |v: f64| 2f64.powi(v.log2().round() as i32);
        for ri in r.iter_mut() {
            *ri = pow2(*ri);
        }
        for (var, col) in self.columns.iter().enumerate() {
            c[var] = match *col {
                Column::Unit { row, coef } if coef != 0.0 => pow2(1.0 / (r[row] * coef.abs())),
                Column::Unit { .. } => 1.0,
                Column::Dense(_) => pow2(c[var]),
            };
        }
        // Scales that would overflow the right-hand side or a scale itself
        // (data spanning more than double precision) are not applied.
        let finite = r.iter().chain(&c).all(|v| v.is_finite() && *v > 0.0)
            && (0..self.rows).all(|i| (self.b[i] * r[i]).is_finite());
        if !finite {
            return;
        }
        self.apply_scaling(&r, &c);
    }

    /// The diagonal scaling guess (see `equilibrate`); false, leaving `r`
    /// and `c` at 1, when fewer than 9 in 10 rows have a non-zero diagonal
    /// entry in the dense block (then the block has no such structure).
    fn diagonal_guess(&self, dense: &[(usize, usize)], r: &mut [f64], c: &mut [f64]) -> bool {
        let m = self.rows;
        let diag = m.min(dense.len());
        let mut has = vec![false; m];
        let mut col_has = vec![false; dense.len()];
        for i in 0..diag {
            let (var, j) = dense[i];
            let a = self.dense[(i, j)].abs();
            if a > 0.0 && a.is_finite() {
                r[i] = 1.0 / a.sqrt();
                c[var] = 1.0 / a.sqrt();
                has[i] = true;
                col_has[i] = true;
            }
        }
        if has.iter().filter(|&&h| h).count() * 10 < 9 * m {
            r.fill(1.0);
            c.fill(1.0);
            return false;
        }
        // Columns without a diagonal: their largest entry over the scaled rows.
        for (slot, &(var, j)) in dense.iter().enumerate() {
            if !col_has[slot] {
                let hi = self
                    .dense
                    .col_as_slice(j)
                    .iter()
                    .zip(r.iter())
                    .fold(0.0f64, |acc, (&a, &ri)| acc.max((a * ri).abs()));
                if hi > 0.0 {
                    c[var] = 1.0 / hi;
                }
            }
        }
        // Rows without a diagonal: their largest entry over the scaled columns.
        for i in (0..m).filter(|&i| !has[i]) {
            let hi = dense.iter().fold(0.0f64, |acc, &(var, j)| {
                acc.max((self.dense[(i, j)] * c[var]).abs())
            });
            if hi > 0.0 {
                r[i] = 1.0 / hi;
            }
        }
        true
    }

    /// Threads for a sweep over the dense block: one below 2^18 entries (a
    /// sweep is then faster than starting a thread), else `par`'s degree.
    fn sweep_threads(&self, par: Par) -> usize {
        if self.rows * self.dense.ncols() < 1 << 18 {
            1
        } else {
            par.degree()
        }
    }

    /// Largest and smallest non-zero `|a_ij r_i c_j|` of every row and of
    /// every dense column (in the order of `dense`), in one sweep; zeros
    /// count for neither (a row or column without a non-zero gets (0, inf)).
    /// Columns are split over threads, the rows' results merged.
    #[allow(clippy::type_complexity)]
    fn extremes(
        &self,
        dense: &[(usize, usize)],
        r: &[f64],
        c: &[f64],
        threads: usize,
    ) -> (Vec<(f64, f64)>, Vec<(f64, f64)>) {
        let m = self.rows;
        let sweep = |part: &[(usize, usize)]| {
            let (mut hi, mut lo) = (vec![0.0f64; m], vec![f64::INFINITY; m]);
            let mut cols = Vec::with_capacity(part.len());
            for &(var, j) in part {
                let cj = c[var];
                let (mut chi, mut clo) = (0.0f64, f64::INFINITY);
                for (((&a, &ri), h), l) in self
                    .dense
                    .col_as_slice(j)
                    .iter()
                    .zip(r)
                    .zip(&mut hi)
                    .zip(&mut lo)
                {
                    // Branch-free, so the loop vectorizes.
                    let v = (a * ri * cj).abs();
                    let nz = if v > 0.0 { v } else { f64::INFINITY };
                    *h = h.max(v);
                    *l = l.min(nz);
                    chi = chi.max(v);
                    clo = clo.min(nz);
                }
                cols.push((chi, clo));
            }
            (hi, lo, cols)
        };
        let (hi, lo, cols) = if threads <= 1 || dense.len() < 2 * threads {
            sweep(dense)
        } else {
            let chunk = dense.len().div_ceil(threads);
            let parts: Vec<_> = std::thread::scope(|scope| {
                let handles: Vec<_> = dense
                    .chunks(chunk)
                    .map(|part| scope.spawn(move || sweep(part)))
                    .collect();
                handles
                    .into_iter()
                    .map(|h| h.join().expect("a sweep thread does not panic"))
                    .collect()
            });
            let mut parts = parts.into_iter();
            let (mut hi, mut lo, mut cols) = parts.next().expect("at least one part");
            for (h2, l2, c2) in parts {
                for i in 0..m {
                    hi[i] = hi[i].max(h2[i]);
                    lo[i] = lo[i].min(l2[i]);
                }
                cols.extend(c2);
            }
            (hi, lo, cols)
        };
        (hi.into_iter().zip(lo).collect(), cols)
    }

    fn apply_scaling(&mut self, r: &[f64], c: &[f64]) {
        let m = self.rows;
        for (var, col) in self.columns.iter_mut().enumerate() {
            match col {
                Column::Dense(j) => {
                    let cj = c[var];
                    for (a, &ri) in self.dense.col_as_slice_mut(*j).iter_mut().zip(r) {
                        *a *= ri * cj;
                    }
                }
                Column::Unit { row, coef } => *coef *= r[*row] * c[var],
            }
        }
        for i in 0..m {
            self.b[i] *= r[i];
            self.row_scale[i] *= r[i];
        }
        for cost in self.costs.iter_mut() {
            for (var, cv) in cost.iter_mut().enumerate() {
                *cv *= c[var];
            }
        }
        for var in 0..self.vars() {
            self.col_scale[var] *= c[var];
        }
    }

    /// `|B|_1`, the largest column sum of the basis's magnitudes.
    pub(crate) fn basis_norm_1(&self, basis: &[usize]) -> f64 {
        basis
            .iter()
            .map(|&v| match self.columns[v] {
                Column::Unit { coef, .. } => coef.abs(),
                Column::Dense(j) => self.dense.col(j).iter().map(|x| x.abs()).sum(),
            })
            .fold(0.0f64, f64::max)
    }

    /// Refines `x` (the basic variables of `basis`) with corrections from
    /// `solve` (an approximate `B^{-1}` applied in place) until the
    /// componentwise backward error max_i |b - B x|_i / (|B| |x| + |b|)_i is
    /// at rounding level (each row judged against its own terms: rows of very
    /// different scales, a force balance beside a compatibility row in
    /// length, must all be accurate), or stops improving, or after
    /// `max_steps`. Returns the best iterate, its error and the steps taken.
    pub(crate) fn refine_basic(
        &self,
        basis: &[usize],
        mut x: Col<f64>,
        max_steps: usize,
        mut solve: impl FnMut(&mut Col<f64>),
    ) -> Refined {
        let m = self.rows;
        let (mut best, mut best_error) = (x.clone(), f64::INFINITY);
        let mut steps = 0;
        for step in 0..=max_steps {
            let mut full = vec![0.0; self.vars()];
            for (k, &v) in basis.iter().enumerate() {
                full[v] = x[k];
            }
            let (bx, terms) = self.apply_with_terms(&full);
            let mut res = Col::<f64>::from_fn(m, |i| self.b[i] - bx[i]);
            let error = (0..m)
                .map(|i| {
                    let t = terms[i] + self.b[i].abs();
                    if t > 0.0 { res[i].abs() / t } else { 0.0 }
                })
                .fold(0.0f64, f64::max);
            if error < best_error {
                best.copy_from(&x);
                best_error = error;
            } else {
                break; // no longer improving
            }
            if error <= ROUNDING_LEVEL || step == max_steps {
                break;
            }
            solve(&mut res);
            x += &res;
            steps += 1;
        }
        Refined {
            x: best,
            error: best_error,
            steps,
        }
    }
}

/// A refined basic solution.
pub(crate) struct Refined {
    /// The best iterate.
    pub x: Col<f64>,
    /// Its componentwise backward error.
    pub error: f64,
    /// The refinement steps taken.
    pub steps: usize,
}

/// A factorization of a basis `B` (columns of `A` for the basic variables,
/// in row order) that exploits its unit columns: a unit column `coef e_i`
/// covers row i, and with the rows `R_u` they cover and the rest `R_d`,
///
/// ```text
///     B_dd x_D = y_{R_d}                                (an LU of order d = dense basic columns)
///     x_u = (y_i - B_{i,D} x_D) / coef_u,   i = row(u) in R_u
/// ```
///
/// For a contact basis (the forces of the contact set, the approach, the
/// gaps of the other points) d is the contact set's size plus one, not N:
/// the factorization costs (d / N)^3 of a full LU.
pub(crate) struct BasisFactor {
    /// The dense basic columns' positions in the basis, and their rows R_d.
    dense_slots: Vec<usize>,
    dense_rows: Vec<usize>,
    /// (slot, row, coef) of the unit basic columns.
    units: Vec<(usize, usize, f64)>,
    /// LU of B_dd.
    lu: Option<Lu>,
    /// B_{R_u, D}: the dense columns restricted to the rows the unit columns cover.
    coupling: Mat<f64>,
    /// Smallest over largest |U_ii| of B_dd's LU (1 if there is no dense column).
    pub pivot_ratio: f64,
}

impl BasisFactor {
    /// Factors the basis `basis` of `system`; `Err` when it is numerically
    /// singular (a row covered twice, or a singular B_dd).
    pub(crate) fn new(system: &System, basis: &[usize], par: Par) -> Result<Self, Singular> {
        let m = system.rows;
        let mut covered = vec![false; m];
        let (mut dense_slots, mut units) = (Vec::new(), Vec::new());
        for (slot, &v) in basis.iter().enumerate() {
            match system.columns[v] {
                Column::Unit { row, coef } if coef != 0.0 && !covered[row] => {
                    covered[row] = true;
                    units.push((slot, row, coef));
                }
                _ => dense_slots.push(slot),
            }
        }
        let dense_rows: Vec<usize> = (0..m).filter(|&i| !covered[i]).collect();
        if dense_rows.len() != dense_slots.len() {
            return Err(Singular { ratio: 0.0 });
        }
        let d = dense_slots.len();
        // Each dense column is written once into a scratch column and split
        // into B_dd and the coupling rows (no m x d copy).
        let mut bdd = Mat::<f64>::zeros(d, d);
        let mut coupling = Mat::<f64>::zeros(units.len(), d);
        let mut column = Col::<f64>::zeros(m);
        for (c, &slot) in dense_slots.iter().enumerate() {
            system.write_column(basis[slot], column.as_mut(), 1.0);
            for (i, &row) in dense_rows.iter().enumerate() {
                bdd[(i, c)] = column[row];
            }
            for (u, &(_, row, _)) in units.iter().enumerate() {
                coupling[(u, c)] = column[row];
            }
        }
        let (lu, pivot_ratio) = if d > 0 {
            let lu = Lu::new(bdd, par);
            let ratio = lu.pivot_ratio;
            if lu.is_singular() {
                return Err(Singular { ratio });
            }
            (Some(lu), ratio)
        } else {
            (None, 1.0)
        };
        Ok(Self {
            dense_slots,
            dense_rows,
            units,
            lu,
            coupling,
            pivot_ratio,
        })
    }

    /// Overwrites each column of `y` (m rows) with `B^{-1}` times it
    /// (entries in basis-slot order).
    pub(crate) fn solve_in_place(&self, mut y: MatMut<'_, f64>, par: Par) {
        let k = y.ncols();
        let d = self.dense_slots.len();
        let mut xd = Mat::from_fn(d, k, |i, j| y[(self.dense_rows[i], j)]);
        if let Some(lu) = &self.lu {
            lu.solve_in_place(xd.as_mut());
        }
        let mut yu = Mat::from_fn(self.units.len(), k, |u, j| y[(self.units[u].1, j)]);
        if d > 0 && !self.units.is_empty() {
            faer::linalg::matmul::matmul(
                yu.as_mut(),
                faer::Accum::Add,
                self.coupling.as_ref(),
                xd.as_ref(),
                -1.0,
                par,
            );
        }
        for j in 0..k {
            for (c, &slot) in self.dense_slots.iter().enumerate() {
                y[(slot, j)] = xd[(c, j)];
            }
            for (u, &(slot, _, coef)) in self.units.iter().enumerate() {
                y[(slot, j)] = yu[(u, j)] / coef;
            }
        }
    }
}
