//! The compact (Tucker) tableau and its pivot, with delayed updates.
//!
//! For a basis `B` of `A x = b`, the basic variables are affine functions of
//! the non-basic ones:
//!
//! ```text
//!     x_B = b̄ + T x_N,     T = -B^{-1} A_N,   b̄ = B^{-1} b
//!     c^T x = c_B^T b̄ + (c_N + c_B^T T) x_N      (one extra row per objective)
//! ```
//!
//! Only the non-basic columns are stored (the basic ones are the identity).
//! A pivot exchanges basic `x_B[r]` with non-basic `x_N[s]` (`p = T[r, s]`,
//! `c = T[:, s]`, `ρ = T[r, :]`):
//!
//! ```text
//!     T'[i, j] = T[i, j] - c_i ρ_j / p    (i != r, j != s)   a rank-1 update
//!     T'[i, s] = c_i / p                   (i != r)
//!     T'[r, j] = -ρ_j / p                  (j != s),   T'[r, s] = 1 / p
//! ```
//!
//! The rank-1 updates are not applied to the whole matrix at each pivot (a
//! pass over all of `T` per pivot, bound by memory bandwidth): the tableau is
//! kept as `T = T0 - U V^T`, `U` and `V` holding the last k updates (k up to
//! [`UPDATE_BLOCK`], or [`lemke_update_block`]), and every k pivots
//! `T0 -= U V^T` is done
//! as one faer matrix product, at the speed of a matrix multiply. A pivot
//! reads only what it needs through the correction: the entering column, the
//! pivot row, entries of the lexicographic rule; the right-hand side and the
//! objective rows, read at every step, are kept current explicitly. Row r
//! and column s are written into `T0` exactly as above (their `U`, `V`
//! entries zeroed), so a pivot's arithmetic is that of the explicit tableau.
//!
//! The ratio test is lexicographic: ties in the step length (ratios within a
//! relative `tie` of the smallest, or rows the smallest step brings to the
//! zero level) are broken by the rows of `[b̄, B^{-1}]` divided by the pivot
//! column, where `B^{-1}` is taken relative to the initial basis (an identity
//! in the scaled system), which makes the sequence of bases non-repeating.

use faer::linalg::matmul::matmul;
use faer::prelude::*;
use faer::{Accum, Col, Mat, Par, Row};

use crate::LcpError;
use crate::linalg::try_mat;
use crate::tableau::system::{BasisFactor, Singular, System};
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
#[derive(Debug, Clone)]
pub(crate) struct Ratio {
    /// The leaving row.
    pub row: usize,
    /// The step length (entering variable's new magnitude), in scaled units.
    pub theta: f64,
    /// The entering column the test read (all rows), handed on to the pivot.
    pub column: Col<f64>,
}

/// A row that limits the entering variable in a ratio test.
struct Limit {
    row: usize,
    /// The step at which its basic value reaches its bound.
    theta: f64,
    /// The magnitude of its pivot entry.
    pivot: f64,
    /// Whether its basic value is held at exactly 0 (an artificial).
    fixed: bool,
    /// Its basic value (0 at or below the zero level).
    value: f64,
}

/// A row tied on the step length, for the lexicographic rule.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tied {
    /// The row.
    pub row: usize,
    /// The magnitude of its pivot entry (the rule's divisor).
    pub pivot: f64,
}

/// Pivots kept as a delayed rank-k correction before it is applied to the
/// whole tableau by one matrix product. The product costs `2 rows cols`
/// flops per pivot whatever the block, but reads and writes all of `T0`
/// once per block; a larger block costs more per read of a column or row
/// (`rows k`, `cols k`). The restricted-entry simplex reads several
/// candidate columns per pivot: 64 suits it (128 was slower on the
/// crowned roller's design program, 2203 rows).
pub(crate) const UPDATE_BLOCK: usize = 64;

/// The block for Lemke's method, which reads one column and one row per
/// pivot, by the tableau's row count: 64 while the tableau stays in cache,
/// 128 from 1500 rows up, where the product's pass over `T0` (31 MB at
/// N = 1961) is bound by memory and fewer passes pay (`scaling_probe
/// --method lemke`, Hertz on Love patches, 2-core Zen 4).
pub(crate) fn lemke_update_block(rows: usize) -> usize {
    if rows >= 1500 { 128 } else { UPDATE_BLOCK }
}

/// The compact tableau, as `T = T0 - U V^T` (see the module documentation).
pub(crate) struct GeneralTableau {
    /// `T0`: `(m + objectives) x (n_N + 1)`; the last column is `b̄`.
    t0: Mat<f64>,
    /// The delayed updates' left factors, `(m + objectives) x block`.
    u: Mat<f64>,
    /// The delayed updates' right factors, `(n_N + 1) x block` (a
    /// pivot writes one of its columns, contiguous).
    v: Mat<f64>,
    /// Number of delayed updates held.
    k: usize,
    /// The current right-hand side column (objective values included).
    rhs: Vec<f64>,
    /// The current objective rows, `objectives x (n_N + 1)`.
    objectives: Mat<f64>,
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
    /// Parallelism of the block updates.
    pub par: Par,
}

impl GeneralTableau {
    /// Builds the tableau of an initial basis whose columns in `system` are
    /// `+1` unit columns (an identity after ordering by row): `T = -A_N`,
    /// `b̄ = b`, and one objective row per cost vector of the system; `block`
    /// pending updates at most.
    ///
    /// # Errors
    /// [`LcpError::AllocationFailed`] when the tableau cannot be allocated.
    pub fn from_identity(
        system: &System,
        basis: Vec<usize>,
        par: Par,
        block: usize,
    ) -> Result<Self, LcpError> {
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
        let mut t0 = try_mat(m + nobj, n + 1, "the general tableau", |_, _| 0.0)?;
        for (j, &v) in nonbasic.iter().enumerate() {
            system.write_column(v, t0.as_mut().col_mut(j).subrows_mut(0, m), -1.0);
        }
        for i in 0..m {
            t0[(i, n)] = system.b[i];
        }
        let mut tab = Self {
            u: Mat::zeros(m + nobj, block),
            v: Mat::zeros(n + 1, block),
            k: 0,
            rhs: Vec::new(),
            objectives: Mat::zeros(nobj, n + 1),
            t0,
            m,
            basic: basis.clone(),
            nonbasic,
            position,
            reference: basis,
            par,
        };
        tab.recompute_objectives(system);
        Ok(tab)
    }

    /// Number of non-basic columns (without the right-hand side).
    pub fn n(&self) -> usize {
        self.nonbasic.len()
    }

    /// Current value `b̄_i` of the basic variable of row `i`.
    pub fn rhs(&self, i: usize) -> f64 {
        self.rhs[i]
    }

    /// Objective row `k`: its current value.
    pub fn objective_value(&self, k: usize) -> f64 {
        self.objectives[(k, self.nonbasic.len())]
    }

    /// Objective row `k`: reduced cost of non-basic column `j`.
    pub fn reduced_cost(&self, k: usize, j: usize) -> f64 {
        self.objectives[(k, j)]
    }

    /// Entry `(i, j)` of the current tableau (constraint rows).
    pub fn entry(&self, i: usize, j: usize) -> f64 {
        let mut v = self.t0[(i, j)];
        for l in 0..self.k {
            v -= self.u[(i, l)] * self.v[(j, l)];
        }
        v
    }

    /// Whether row `r` can be the leaving row of a ratio test of column `s`
    /// in direction `sigma` under rule `rule`, judged from the one entry
    /// `T[r, s]` (`O(k)`, no column read): a free row never leaves, and a
    /// bounded one only when its value falls, `-sigma T[r, s] > 0`.
    ///
    /// `false` only when [`ratio_test`](Self::ratio_test) certainly leaves
    /// `r` out: the entry is summed here in another order than the column
    /// the ratio test reads, so the sign test allows for that rounding
    /// (`2 (k + 2) ε` times the sum of the magnitudes of its terms, twice
    /// the bound of a sum of `k + 1` products, either way).
    pub fn may_leave(&self, r: usize, s: usize, sigma: f64, rule: RowRule) -> bool {
        match rule {
            RowRule::Skip => false,
            RowRule::Fixed => true,
            RowRule::Bounded => {
                let mut value = self.t0[(r, s)];
                let mut size = value.abs();
                for l in 0..self.k {
                    let term = self.u[(r, l)] * self.v[(s, l)];
                    value -= term;
                    size += term.abs();
                }
                let rounding = 4.0 * (self.k as f64 + 2.0) * f64::EPSILON * size;
                -sigma * value + rounding > 0.0
            }
        }
    }

    /// Column `j` of the current tableau, all rows (objective rows included).
    pub fn column(&self, j: usize) -> Col<f64> {
        let mut c = self.t0.col(j).to_owned();
        if self.k > 0 {
            matmul(
                c.as_mat_mut(),
                Accum::Add,
                self.u.as_ref().subcols(0, self.k),
                self.v
                    .as_ref()
                    .subcols(0, self.k)
                    .row(j)
                    .transpose()
                    .as_mat(),
                -1.0,
                Par::Seq,
            );
        }
        c
    }

    /// Constraint row `i` of the current tableau, all columns.
    fn row(&self, i: usize) -> Row<f64> {
        let mut r = self.t0.row(i).to_owned();
        if self.k > 0 {
            matmul(
                r.as_mat_mut(),
                Accum::Add,
                self.u.as_ref().subcols(0, self.k).row(i).as_mat(),
                self.v.as_ref().subcols(0, self.k).transpose(),
                -1.0,
                Par::Seq,
            );
        }
        r
    }

    /// Applies the delayed updates to `T0` (one matrix product).
    fn flush(&mut self) {
        if self.k == 0 {
            return;
        }
        matmul(
            self.t0.as_mut(),
            Accum::Add,
            self.u.as_ref().subcols(0, self.k),
            self.v.as_ref().subcols(0, self.k).transpose(),
            -1.0,
            self.par,
        );
        self.k = 0;
    }

    /// Recomputes the right-hand side and the objective rows from `T0` (with
    /// no delayed update held) and the cost vectors: `d = c_N + c_B^T T`,
    /// value `c_B^T b̄`.
    pub fn recompute_objectives(&mut self, system: &System) {
        self.flush();
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
                self.t0.as_ref().subrows(0, m),
                1.0,
                Par::Seq,
            );
            for j in 0..ncol {
                self.t0[(m + k, j)] = row[(0, j)];
                self.objectives[(k, j)] = row[(0, j)];
            }
        }
        let n = self.nonbasic.len();
        self.rhs = (0..self.t0.nrows()).map(|i| self.t0[(i, n)]).collect();
    }

    /// Exchanges the basic variable of row `r` with the non-basic variable of
    /// column `s`, given that column as the current tableau has it (all rows,
    /// from [`column`](Self::column) or a [`Ratio`]). Returns the variable
    /// that left.
    pub fn pivot(&mut self, r: usize, s: usize, c: Col<f64>) -> usize {
        let rows = self.t0.nrows();
        let n = self.nonbasic.len();
        let rho = self.row(r);
        let p = c[r];
        let inv = 1.0 / p;
        if self.k == self.u.ncols() {
            self.flush();
        }
        // Row r and column s are written exactly; their delayed entries are
        // cleared so the correction leaves them alone.
        let k = self.k;
        for l in 0..k {
            self.u[(r, l)] = 0.0;
            self.v[(s, l)] = 0.0;
        }
        for i in 0..rows {
            self.u[(i, k)] = if i == r { 0.0 } else { c[i] };
        }
        for (j, v) in self.v.col_as_slice_mut(k).iter_mut().enumerate() {
            *v = if j == s { 0.0 } else { rho[j] * inv };
        }
        self.k += 1;
        for j in 0..=n {
            self.t0[(r, j)] = -rho[j] * inv;
        }
        for i in 0..rows {
            self.t0[(i, s)] = c[i] * inv;
        }
        self.t0[(r, s)] = inv;
        // The explicit copies: right-hand side and objective rows.
        let rho_n = rho[n] * inv;
        for i in 0..rows {
            self.rhs[i] = if i == r {
                -rho_n
            } else {
                self.rhs[i] - c[i] * rho_n
            };
        }
        for o in 0..self.objectives.nrows() {
            let ci = c[self.m + o];
            for j in 0..=n {
                self.objectives[(o, j)] = if j == s {
                    ci * inv
                } else {
                    self.objectives[(o, j)] - ci * rho[j] * inv
                };
            }
        }
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
            Position::Nonbasic(j) => -self.entry(i, j),
        }
    }

    /// Overwrites `r` with `B^{-1} r`, read from the tableau: the reference
    /// basis is the identity (its variable `k` has the unit column `e_k`), so
    /// `B^{-1} e_k` is `e_row` while that variable is basic at `row`, and
    /// `-T[:, j]` while it is non-basic at column `j`. Applies the delayed
    /// updates first.
    pub fn solve_basis(&mut self, r: &mut Col<f64>) {
        self.flush();
        let m = self.m;
        let mut y = Col::<f64>::zeros(m);
        for (k, &v) in self.reference.iter().enumerate() {
            let rk = r[k];
            if rk == 0.0 {
                continue;
            }
            match self.position[v] {
                Position::Basic(row) => y[row] += rk,
                Position::Nonbasic(j) => {
                    let col = &self.t0.col_as_slice(j)[..m];
                    for (yi, ti) in y.as_mut().iter_mut().zip(col) {
                        *yi -= rk * ti;
                    }
                }
            }
        }
        r.copy_from(&y);
    }

    /// `|B^{-1}|_1`, the largest column sum of magnitudes of `B^{-1}` (its
    /// columns as in [`solve_basis`](Self::solve_basis)). Applies the delayed
    /// updates first.
    pub fn basis_inverse_norm_1(&mut self) -> f64 {
        self.flush();
        let m = self.m;
        self.reference
            .iter()
            .map(|&v| match self.position[v] {
                Position::Basic(_) => 1.0,
                Position::Nonbasic(j) => self.t0.col_as_slice(j)[..m].iter().map(|x| x.abs()).sum(),
            })
            .fold(0.0f64, f64::max)
    }

    /// Multiplies every non-basic column by `columns` and the right-hand side
    /// by `rhs` (a drifted tableau, for tests of what notices one).
    #[cfg(test)]
    pub(crate) fn drift(&mut self, columns: f64, rhs: f64) {
        self.flush();
        let (m, n) = (self.m, self.n());
        for j in 0..n {
            for v in &mut self.t0.col_as_slice_mut(j)[..m] {
                *v *= columns;
            }
        }
        for v in &mut self.rhs {
            *v *= rhs;
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
        let col = self.column(s);
        let colmax = (0..m).fold(0.0f64, |a, i| a.max(col[i].abs()));
        if colmax == 0.0 {
            return None;
        }
        let piv = tol.pivot * colmax;
        let mut cand: Vec<Limit> = Vec::new();
        let mut theta_min = f64::INFINITY;
        for row in 0..m {
            let limit = match rule(row) {
                RowRule::Skip => continue,
                RowRule::Bounded => {
                    let pivot = -sigma * col[row];
                    if pivot <= piv {
                        continue;
                    }
                    let value = self.rhs(row);
                    let value = if value <= zero_level { 0.0 } else { value };
                    Limit {
                        row,
                        theta: value / pivot,
                        pivot,
                        fixed: false,
                        value,
                    }
                }
                RowRule::Fixed => {
                    let pivot = col[row].abs();
                    if pivot <= piv {
                        continue;
                    }
                    Limit {
                        row,
                        theta: 0.0,
                        pivot,
                        fixed: true,
                        value: 0.0,
                    }
                }
            };
            theta_min = theta_min.min(limit.theta);
            cand.push(limit);
        }
        if cand.is_empty() {
            return None;
        }
        // A row ties when its ratio is within `tie` of the smallest, or when
        // the step of the smallest brings its basic value to the zero level:
        // a ratio is a quotient of rounded values, and a row that reaches
        // zero with the step is a leaving candidate whatever its rounding.
        // (|theta_min|: a basic value that drifted below the zero level
        // gives a negative least step, which must tie with itself.)
        let bound = theta_min + tol.tie * theta_min.abs();
        let ties: Vec<Limit> = cand
            .into_iter()
            .filter(|c| c.theta <= bound || c.value - theta_min * c.pivot <= zero_level)
            .collect();
        if ties.is_empty() {
            // Every ratio is NaN (an overflow: the data's scale exceeds
            // double precision): no row can be trusted to limit the step.
            return None;
        }
        Some(Ratio {
            row: self.leaving(ties, prefer, tol),
            theta: theta_min,
            column: col,
        })
    }

    /// The row that leaves among `ties` (at least one): the only one;
    /// `prefer` when it is among them; else an artificial held at zero
    /// (the largest pivot of them); else the lexicographic choice.
    fn leaving(&self, ties: Vec<Limit>, prefer: Option<usize>, tol: &Tolerances) -> usize {
        if ties.len() == 1 {
            return ties[0].row;
        }
        if let Some(p) = prefer
            && ties.iter().any(|t| t.row == p)
        {
            return p;
        }
        // An artificial held at zero leaves first: it must not become positive.
        if let Some(best) = ties
            .iter()
            .filter(|t| t.fixed)
            .max_by(|a, b| a.pivot.total_cmp(&b.pivot))
        {
            return best.row;
        }
        let first = ties[0].row;
        let rows = ties
            .into_iter()
            .map(|t| Tied {
                row: t.row,
                pivot: t.pivot,
            })
            .collect();
        self.lex_select(rows, tol).unwrap_or(first)
    }

    /// Among rows tied on the step length, the one whose row of `B^{-1}`
    /// divided by its pivot magnitude is lexicographically smallest;
    /// numerically indistinguishable rows go to the largest pivot (the
    /// stablest). `None` only for no row.
    pub fn lex_select(&self, mut rows: Vec<Tied>, tol: &Tolerances) -> Option<usize> {
        for k in 0..self.reference.len() {
            if rows.len() <= 1 {
                break;
            }
            // A reference variable basic outside the tied rows has a zero in
            // each of them: no decision, and no need to read the tableau.
            if let Position::Basic(row) = self.position[self.reference[k]]
                && rows.iter().all(|t| t.row != row)
            {
                continue;
            }
            let vals: Vec<f64> = rows
                .iter()
                .map(|t| self.basis_inverse(t.row, k) / t.pivot)
                .collect();
            let vmin = vals.iter().cloned().fold(f64::INFINITY, f64::min);
            let vscale = vals.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let keep = vmin + tol.tie * vscale;
            let kept: Vec<Tied> = rows
                .iter()
                .zip(&vals)
                .filter(|(_, v)| **v <= keep)
                .map(|(t, _)| *t)
                .collect();
            // A level that keeps no row (non-finite entries) decides nothing.
            if !kept.is_empty() {
                rows = kept;
            }
        }
        rows.iter()
            .max_by(|a, b| a.pivot.total_cmp(&b.pivot).then(b.row.cmp(&a.row)))
            .map(|t| t.row)
    }

    /// Recomputes the whole tableau from the system's data for the current
    /// basis: `T = -B^{-1} A_N`, `b̄ = B^{-1} b`, objective rows from the costs.
    /// `B` is factored through its unit columns ([`BasisFactor`]). Returns the
    /// LU pivot ratio (small = ill-conditioned), or `Err` when `B` is
    /// numerically singular.
    pub fn refactor(&mut self, system: &System) -> Result<f64, Singular> {
        let m = self.m;
        let n = self.nonbasic.len();
        let factor = BasisFactor::new(system, &self.basic, self.par)?;
        self.k = 0;
        {
            let mut body = self.t0.as_mut().subrows_mut(0, m);
            system.gather(&self.nonbasic, body.rb_mut().subcols_mut(0, n), -1.0);
            for i in 0..m {
                body[(i, n)] = system.b[i];
            }
            factor.solve_in_place(body, self.par);
        }
        self.recompute_objectives(system);
        Ok(factor.pivot_ratio)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tableau::system::Column;

    /// The tableau of `-M z + w = q` (`w` basic) for a 6 x 6 symmetric
    /// positive definite `M` with entries of both signs off the diagonal,
    /// after three pivots held as delayed updates.
    fn pivoted() -> (GeneralTableau, Tolerances) {
        let m = 6;
        let entry = |i: usize, j: usize| {
            if i == j {
                4.0 + i as f64
            } else {
                ((i * 7 + j * 7 + i * j) % 5) as f64 * 0.3 - 0.6
            }
        };
        let mut columns: Vec<Column> = (0..m).map(Column::Dense).collect();
        columns.extend((0..m).map(|row| Column::Unit { row, coef: 1.0 }));
        let system = System {
            rows: m,
            dense: Mat::from_fn(m, m, |i, j| -entry(i, j)),
            columns,
            b: Col::from_fn(m, |i| 1.0 + 0.25 * i as f64),
            costs: vec![vec![0.0; 2 * m]],
            col_scale: vec![1.0; 2 * m],
            row_scale: vec![1.0; m],
        };
        let basis = (m..2 * m).collect();
        let mut tab = GeneralTableau::from_identity(&system, basis, Par::Seq, UPDATE_BLOCK)
            .expect("a small tableau");
        let tol = Tolerances::default();
        for var in [0, 2, 4] {
            let Position::Nonbasic(s) = tab.position[var] else {
                panic!("z_{var} starts non-basic");
            };
            let ratio = tab
                .ratio_test(s, 1.0, |_| RowRule::Bounded, None, &tol, 0.0)
                .expect("a positive definite M limits every z");
            tab.pivot(ratio.row, s, ratio.column);
        }
        assert_eq!(tab.k, 3, "the pivots are held as delayed updates");
        (tab, tol)
    }

    #[test]
    fn may_leave_follows_the_sign_of_the_entry_and_never_drops_the_leaving_row() {
        let (tab, tol) = pivoted();
        let (mut kept, mut dropped) = (0, 0);
        for s in 0..tab.n() {
            let column = tab.column(s);
            for r in 0..tab.m {
                for sigma in [1.0, -1.0] {
                    let may = tab.may_leave(r, s, sigma, RowRule::Bounded);
                    // Away from zero the answer is the sign of the entry.
                    if column[r].abs() > 1e-12 * norm(&column) {
                        assert_eq!(may, -sigma * column[r] > 0.0, "row {r}, column {s}");
                    }
                    let picked = tab
                        .ratio_test(s, sigma, |_| RowRule::Bounded, Some(r), &tol, 0.0)
                        .map(|ratio| ratio.row);
                    if may {
                        kept += 1;
                    } else {
                        dropped += 1;
                        assert_ne!(picked, Some(r), "row {r}, column {s}: dropped but leaves");
                    }
                }
            }
        }
        assert!(kept > 0 && dropped > 0, "both answers are exercised");
    }

    #[test]
    fn a_free_row_never_leaves_and_a_fixed_one_always_may() {
        let (tab, _) = pivoted();
        for s in 0..tab.n() {
            for r in 0..tab.m {
                assert!(!tab.may_leave(r, s, 1.0, RowRule::Skip));
                assert!(tab.may_leave(r, s, -1.0, RowRule::Fixed));
            }
        }
    }

    fn norm(c: &Col<f64>) -> f64 {
        c.iter().fold(0.0f64, |a, v| a.max(v.abs()))
    }
}
