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

use crate::LcpError;
use crate::dense::Lu;

/// One column of `A`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Column {
    /// Column `j` of the dense block.
    Dense(usize),
    /// `coef * e_row`.
    Unit {
        /// The row of the single non-zero.
        row: usize,
        /// Its value.
        coef: f64,
    },
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
                for i in 0..self.rows {
                    out[i] = factor * self.dense[(i, j)];
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
    /// within a factor 2 of 1. `iterations` bounds the passes of each.
    pub fn equilibrate(&mut self, iterations: usize) {
        let m = self.rows;
        let nv = self.vars();
        let mut r = vec![1.0f64; m];
        let mut c = vec![1.0f64; nv];
        // Geometric passes: stop when no row or column spread (max/min) shrinks by 10%.
        let mut last_spread = f64::INFINITY;
        for _ in 0..iterations {
            let mut rmax = vec![0.0f64; m];
            let mut rmin = vec![f64::INFINITY; m];
            for (var, col) in self.columns.iter().enumerate() {
                if let Column::Dense(j) = *col {
                    for i in 0..m {
                        let a = (self.dense[(i, j)] * r[i] * c[var]).abs();
                        if a > 0.0 {
                            rmax[i] = rmax[i].max(a);
                            rmin[i] = rmin[i].min(a);
                        }
                    }
                }
            }
            for i in 0..m {
                if rmax[i] > 0.0 {
                    r[i] /= (rmax[i] * rmin[i]).sqrt();
                }
            }
            let mut spread = 1.0f64;
            for (var, col) in self.columns.iter().enumerate() {
                if let Column::Dense(j) = *col {
                    let (mut hi, mut lo) = (0.0f64, f64::INFINITY);
                    for i in 0..m {
                        let a = (self.dense[(i, j)] * r[i] * c[var]).abs();
                        if a > 0.0 {
                            hi = hi.max(a);
                            lo = lo.min(a);
                        }
                    }
                    if hi > 0.0 {
                        c[var] /= (hi * lo).sqrt();
                        spread = spread.max(hi / lo);
                    }
                }
            }
            if spread > 0.9 * last_spread {
                break;
            }
            last_spread = spread;
        }
        // Ruiz passes on max-norms.
        for _ in 0..iterations {
            // r_i <- r_i / sqrt(max_j |a_ij r_i c_j|) over the dense columns
            let mut rmax = vec![0.0f64; m];
            for (var, col) in self.columns.iter().enumerate() {
                if let Column::Dense(j) = *col {
                    for i in 0..m {
                        rmax[i] = rmax[i].max((self.dense[(i, j)] * r[i] * c[var]).abs());
                    }
                }
            }
            let mut balanced = true;
            for i in 0..m {
                if rmax[i] > 0.0 {
                    balanced &= (0.5..=2.0).contains(&rmax[i]);
                    r[i] /= rmax[i].sqrt();
                }
            }
            // c_j <- c_j / sqrt(max_i |a_ij r_i c_j|)
            for (var, col) in self.columns.iter().enumerate() {
                if let Column::Dense(_) = col {
                    let cmax = self.column_max(*col, &r) * c[var];
                    if cmax > 0.0 {
                        balanced &= (0.5..=2.0).contains(&cmax);
                        c[var] /= cmax.sqrt();
                    }
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
        self.apply_scaling(&r, &c);
    }

    /// Largest `|a_ij r_i|` of a column.
    fn column_max(&self, col: Column, r: &[f64]) -> f64 {
        match col {
            Column::Dense(j) => {
                (0..self.rows).fold(0.0f64, |a, i| a.max((self.dense[(i, j)] * r[i]).abs()))
            }
            Column::Unit { row, coef } => (coef * r[row]).abs(),
        }
    }

    fn apply_scaling(&mut self, r: &[f64], c: &[f64]) {
        let m = self.rows;
        for (var, col) in self.columns.iter_mut().enumerate() {
            match col {
                Column::Dense(j) => {
                    let j = *j;
                    for i in 0..m {
                        self.dense[(i, j)] *= r[i] * c[var];
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

    /// Solves `B x_B = b` for the basis `basis` (variables, in row order) from
    /// this system's data, with iterative refinement. Returns `x_B`, the
    /// number of refinement steps taken, and the LU pivot ratio.
    pub fn basic_solution(
        &self,
        basis: &[usize],
        par: Par,
        max_steps: usize,
    ) -> Result<(Col<f64>, usize), f64> {
        let m = self.rows;
        let mut bmat = Mat::<f64>::zeros(m, m);
        self.gather(basis, bmat.as_mut(), 1.0);
        let lu = Lu::new(bmat, par);
        if lu.pivot_ratio <= f64::EPSILON * m as f64 {
            return Err(lu.pivot_ratio);
        }
        let mut x = self.b.clone();
        lu.solve_in_place(x.as_mat_mut());
        // Refine until the componentwise backward error
        // max_i |b - B x|_i / (|B| |x| + |b|)_i is at rounding level (each row
        // judged against its own terms: rows of very different scales, a
        // force balance beside a compatibility row in length, must all be
        // accurate), or stops improving; keep the best iterate.
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
            if error <= 2.0 * f64::EPSILON || step == max_steps {
                break;
            }
            lu.solve_in_place(res.as_mat_mut());
            x += &res;
            steps += 1;
        }
        let x = best;
        Ok((x, steps))
    }
}

/// Checks a matrix for NaN/inf, naming the field.
pub(crate) fn check_finite_mat(
    field: &'static str,
    a: faer::MatRef<'_, f64>,
) -> Result<(), LcpError> {
    match crate::dense::first_non_finite(a) {
        Some((index, value)) => Err(LcpError::NonFinite {
            field,
            index,
            value,
        }),
        None => Ok(()),
    }
}

/// Checks a vector for NaN/inf, naming the field.
pub(crate) fn check_finite_col(
    field: &'static str,
    a: faer::ColRef<'_, f64>,
) -> Result<(), LcpError> {
    for (index, &value) in a.iter().enumerate() {
        if !value.is_finite() {
            return Err(LcpError::NonFinite {
                field,
                index,
                value,
            });
        }
    }
    Ok(())
}
