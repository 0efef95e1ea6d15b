//! The compact (Tucker) tableau and its pivot.
//!
//! For a basis `B` of `A x = b`, the basic variables are affine functions of
//! the non-basic ones:
//!
//! ```text
//!     x_B = b̄ + T x_N,     T = -B^{-1} A_N,   b̄ = B^{-1} b
//!     c^T x = c_B^T b̄ + (c_N + c_B^T T) x_N      (one extra row per objective)
//! ```
//!
//! Only the non-basic columns are stored (the basic ones are the identity), as
//! one column-major faer matrix `(m + objectives) x (n_N + 1)` whose last
//! column is `b̄`. A pivot exchanges basic `x_B[r]` with non-basic `x_N[s]`
//! (`p = T[r, s]`):
//!
//! ```text
//!     T'[i, j] = T[i, j] - T[i, s] T[r, j] / p    (i != r, j != s)   rank-1 update, by faer
//!     T'[i, s] = T[i, s] / p                       (i != r)
//!     T'[r, j] = -T[r, j] / p                      (j != s),   T'[r, s] = 1 / p
//! ```
//!
//! The ratio test is lexicographic: ties in the step length are broken by the
//! rows of `[b̄, B^{-1}]` divided by the pivot column, where `B^{-1}` is taken
//! relative to the initial basis (an identity in the scaled system), which
//! makes the sequence of bases non-repeating.

use faer::linalg::matmul::matmul;
use faer::prelude::*;
use faer::{Accum, Mat, Par};

use crate::dense::Lu;
use crate::system::System;
use crate::tolerance::Tolerances;

/// Where a variable stands in the tableau.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Position {
    /// Basic at this row.
    Basic(usize),
    /// Non-basic at this column.
    Nonbasic(usize),
}

/// How a row takes part in a ratio test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RowRule {
    /// Not at all (its basic variable is free).
    Skip,
    /// Its basic variable must stay >= 0.
    Bounded,
    /// Its basic variable must stay exactly 0 (an artificial left in the basis at level 0).
    Fixed,
}

/// Result of a ratio test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ratio {
    /// The leaving row.
    pub row: usize,
    /// The step length (entering variable's new magnitude), in scaled units.
    pub theta: f64,
}

/// The compact tableau.
pub(crate) struct Tableau {
    /// `(m + objectives) x (n_N + 1)`; the last column is `b̄`.
    pub t: Mat<f64>,
    /// Number of constraint rows `m`.
    pub m: usize,
    /// Basic variable of each row.
    pub basic: Vec<usize>,
    /// Non-basic variable of each column.
    pub nonbasic: Vec<usize>,
    /// Position of each variable.
    pub position: Vec<Position>,
    /// The initial basis (its `B^{-1}` columns drive the lexicographic rule).
    pub reference: Vec<usize>,
    /// Parallelism of the rank-1 update.
    pub par: Par,
    scratch_u: Mat<f64>,
    scratch_v: Mat<f64>,
}

impl Tableau {
    /// Builds the tableau of an initial basis whose columns in `system` are
    /// `+1` unit columns (an identity after ordering by row): `T = -A_N`,
    /// `b̄ = b`, and one objective row per cost vector of the system.
    pub fn from_identity(system: &System, basis: Vec<usize>, par: Par) -> Self {
        let m = system.rows;
        let nv = system.vars();
        let mut position = vec![Position::Nonbasic(usize::MAX); nv];
        for (i, &v) in basis.iter().enumerate() {
            position[v] = Position::Basic(i);
        }
        let nonbasic: Vec<usize> = (0..nv)
            .filter(|v| !matches!(position[*v], Position::Basic(_)))
            .collect();
        for (j, &v) in nonbasic.iter().enumerate() {
            position[v] = Position::Nonbasic(j);
        }
        let nobj = system.costs.len();
        let n = nonbasic.len();
        let mut t = Mat::<f64>::zeros(m + nobj, n + 1);
        for (j, &v) in nonbasic.iter().enumerate() {
            system.write_column(v, t.as_mut().col_mut(j).subrows_mut(0, m), -1.0);
        }
        for i in 0..m {
            t[(i, n)] = system.b[i];
        }
        let mut tab = Self {
            t,
            m,
            basic: basis.clone(),
            nonbasic,
            position,
            reference: basis,
            par,
            scratch_u: Mat::zeros(m + nobj, 1),
            scratch_v: Mat::zeros(1, n + 1),
        };
        tab.recompute_objectives(system);
        tab
    }

    /// Number of non-basic columns (without the right-hand side).
    pub fn n(&self) -> usize {
        self.nonbasic.len()
    }

    /// Current value `b̄_i` of the basic variable of row `i`.
    pub fn rhs(&self, i: usize) -> f64 {
        self.t[(i, self.nonbasic.len())]
    }

    /// Objective row `k`: its current value.
    pub fn objective_value(&self, k: usize) -> f64 {
        self.t[(self.m + k, self.nonbasic.len())]
    }

    /// Objective row `k`: reduced cost of non-basic column `j`.
    pub fn reduced_cost(&self, k: usize, j: usize) -> f64 {
        self.t[(self.m + k, j)]
    }

    /// Recomputes the objective rows from the cost vectors and the current
    /// constraint rows: `d = c_N + c_B^T T`, value `c_B^T b̄`.
    pub fn recompute_objectives(&mut self, system: &System) {
        let m = self.m;
        let ncol = self.nonbasic.len() + 1;
        for (k, cost) in system.costs.iter().enumerate() {
            let cb = Mat::<f64>::from_fn(1, m, |_, i| cost[self.basic[i]]);
            let mut row = Mat::<f64>::zeros(1, ncol);
            for (j, &v) in self.nonbasic.iter().enumerate() {
                row[(0, j)] = cost[v];
            }
            matmul(
                row.as_mut(),
                Accum::Add,
                cb.as_ref(),
                self.t.as_ref().subrows(0, m),
                1.0,
                Par::Seq,
            );
            for j in 0..ncol {
                self.t[(m + k, j)] = row[(0, j)];
            }
        }
    }

    /// Exchanges the basic variable of row `r` with the non-basic variable of
    /// column `s`. Returns the variable that left.
    pub fn pivot(&mut self, r: usize, s: usize) -> usize {
        let rows = self.t.nrows();
        let ncol = self.t.ncols();
        let p = self.t[(r, s)];
        let inv = 1.0 / p;
        for i in 0..rows {
            self.scratch_u[(i, 0)] = self.t[(i, s)];
        }
        for j in 0..ncol {
            self.scratch_v[(0, j)] = self.t[(r, j)] * inv;
        }
        matmul(
            self.t.as_mut(),
            Accum::Add,
            self.scratch_u.as_ref(),
            self.scratch_v.as_ref(),
            -1.0,
            self.par,
        );
        for j in 0..ncol {
            self.t[(r, j)] = -self.scratch_v[(0, j)];
        }
        for i in 0..rows {
            self.t[(i, s)] = self.scratch_u[(i, 0)] * inv;
        }
        self.t[(r, s)] = inv;
        let entering = self.nonbasic[s];
        let leaving = self.basic[r];
        self.basic[r] = entering;
        self.nonbasic[s] = leaving;
        self.position[entering] = Position::Basic(r);
        self.position[leaving] = Position::Nonbasic(s);
        leaving
    }

    /// Entry `(i, k)` of `B^{-1}` relative to the reference basis: column `k`
    /// belongs to reference variable `reference[k]`.
    fn basis_inverse(&self, i: usize, k: usize) -> f64 {
        match self.position[self.reference[k]] {
            Position::Basic(row) => {
                if row == i {
                    1.0
                } else {
                    0.0
                }
            }
            Position::Nonbasic(j) => -self.t[(i, j)],
        }
    }

    /// Lexicographic minimum-ratio test for non-basic column `s` moving in
    /// direction `sigma` (+1 increases it, -1 decreases it).
    ///
    /// `rule(i)` says how row `i` takes part; `prefer` is a row chosen
    /// whenever it is among the ties (Lemke's `z0`, the complement in the
    /// restricted-entry rule). `zero_level` is the absolute level (scaled
    /// units) at or below which a basic value counts as zero. Returns `None`
    /// when no row limits the step (a ray).
    pub fn ratio_test(
        &self,
        s: usize,
        sigma: f64,
        rule: impl Fn(usize) -> RowRule,
        prefer: Option<usize>,
        tol: &Tolerances,
        zero_level: f64,
    ) -> Option<Ratio> {
        let m = self.m;
        let col = self.t.col(s);
        let colmax = (0..m).fold(0.0f64, |a, i| a.max(col[i].abs()));
        if colmax == 0.0 {
            return None;
        }
        let piv = tol.pivot * colmax;
        // (row, theta, pivot magnitude, fixed)
        let mut cand: Vec<(usize, f64, f64, bool)> = Vec::new();
        let mut theta_min = f64::INFINITY;
        for i in 0..m {
            let (theta, a, fixed) = match rule(i) {
                RowRule::Skip => continue,
                RowRule::Bounded => {
                    let a = -sigma * col[i];
                    if a <= piv {
                        continue;
                    }
                    let b = self.rhs(i);
                    let b = if b <= zero_level { 0.0 } else { b };
                    (b / a, a, false)
                }
                RowRule::Fixed => {
                    let a = col[i].abs();
                    if a <= piv {
                        continue;
                    }
                    (0.0, a, true)
                }
            };
            theta_min = theta_min.min(theta);
            cand.push((i, theta, a, fixed));
        }
        if cand.is_empty() {
            return None;
        }
        let limit = theta_min + tol.tie * theta_min;
        let ties: Vec<(usize, f64, bool)> = cand
            .into_iter()
            .filter(|c| c.1 <= limit)
            .map(|c| (c.0, c.2, c.3))
            .collect();
        let pick = |row: usize| Ratio {
            row,
            theta: theta_min,
        };
        if ties.len() == 1 {
            return Some(pick(ties[0].0));
        }
        if let Some(p) = prefer
            && ties.iter().any(|t| t.0 == p)
        {
            return Some(pick(p));
        }
        // An artificial held at zero leaves first: it must not become positive.
        if let Some(best) = ties
            .iter()
            .filter(|t| t.2)
            .max_by(|a, b| a.1.total_cmp(&b.1))
        {
            return Some(pick(best.0));
        }
        Some(pick(self.lex_select(
            ties.into_iter().map(|t| (t.0, t.1)).collect(),
            tol,
        )))
    }

    /// Among rows tied on the step length, the one whose row of `B^{-1}`
    /// divided by its pivot magnitude (`rows` = (row, divisor)) is
    /// lexicographically smallest; numerically indistinguishable rows go to
    /// the largest divisor (the stablest pivot).
    pub fn lex_select(&self, mut rows: Vec<(usize, f64)>, tol: &Tolerances) -> usize {
        for k in 0..self.reference.len() {
            if rows.len() <= 1 {
                break;
            }
            let vals: Vec<f64> = rows
                .iter()
                .map(|&(i, a)| self.basis_inverse(i, k) / a)
                .collect();
            let vmin = vals.iter().cloned().fold(f64::INFINITY, f64::min);
            let vscale = vals.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let keep = vmin + tol.tie * vscale;
            let mut idx = 0;
            rows.retain(|_| {
                let ok = vals[idx] <= keep;
                idx += 1;
                ok
            });
        }
        rows.iter()
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
            .map(|r| r.0)
            .unwrap_or(usize::MAX)
    }

    /// Recomputes the whole tableau from the system's data for the current
    /// basis: `T = -B^{-1} A_N`, `b̄ = B^{-1} b`, objective rows from the costs.
    /// Returns the LU pivot ratio of `B` (small = ill-conditioned) or an error
    /// ratio when `B` is singular.
    pub fn refactor(&mut self, system: &System) -> Result<f64, f64> {
        let m = self.m;
        let n = self.nonbasic.len();
        let mut bmat = Mat::<f64>::zeros(m, m);
        system.gather(&self.basic, bmat.as_mut(), 1.0);
        let lu = Lu::new(bmat, self.par);
        if lu.pivot_ratio <= f64::EPSILON * m as f64 {
            return Err(lu.pivot_ratio);
        }
        {
            let mut body = self.t.as_mut().subrows_mut(0, m);
            system.gather(&self.nonbasic, body.rb_mut().subcols_mut(0, n), -1.0);
            for i in 0..m {
                body[(i, n)] = system.b[i];
            }
            lu.solve_in_place(body);
        }
        self.recompute_objectives(system);
        Ok(lu.pivot_ratio)
    }
}
