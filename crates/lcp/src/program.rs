//! Linear programs with complementarity constraints: the general form the
//! restricted-entry simplex solves, to which the mixed LCP and the design
//! problem (extra columns for profile parameters, an objective) reduce.
//!
//! ```text
//!     minimize   c^T x                      (optional: without c, any feasible point)
//!     subject to A x = b
//!                x_j >= 0  or  x_j free     (per unknown)
//!                x_i x_j = 0                 (per complementary pair)
//! ```
//!
//! Columns of `A` are added in named blocks, dense or unit (`coef * e_row`,
//! for slacks), so a problem reads like its equations; see
//! [`ProgramBuilder`].

use std::ops::Range;

use faer::{Col, ColRef, Mat, MatRef};

use crate::LcpError;
use crate::certificate::Certificate;
use crate::problem::{Bound, check_finite_col, check_finite_mat, check_size};

/// One column of a program's constraint matrix `A`.
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

/// A linear program with complementarity constraints (see the module documentation).
#[derive(Debug, Clone)]
pub struct ComplementaryProgram {
    pub(crate) rows: usize,
    pub(crate) dense: Mat<f64>,
    pub(crate) columns: Vec<Column>,
    pub(crate) bounds: Vec<Bound>,
    pub(crate) complement: Vec<Option<usize>>,
    pub(crate) b: Col<f64>,
    pub(crate) cost: Option<Vec<f64>>,
    /// Unknowns held non-basic at 0 through phase 1 (they may enter only in
    /// phase 2): design variables, in the paper's two-part design method.
    pub(crate) deferred: Vec<bool>,
    blocks: Vec<(usize, String)>,
}

/// Builds a [`ComplementaryProgram`] block by block.
///
/// ```
/// use elcon_lcp::{Bound, Options, ProgramBuilder};
/// use faer::{col, mat};
/// // minimize x0 + x1  s.t.  x0 - x1 + s = 1,  x0 + x1 - t = 1, all >= 0, x0 s = 0
/// let mut p = ProgramBuilder::new(2);
/// let x = p.dense_columns("x", mat![[1.0, -1.0], [1.0, 1.0]].as_ref(), Bound::NonNegative).unwrap();
/// let s = p.unit_columns("s", 0..1, 1.0, Bound::NonNegative).unwrap();
/// let t = p.unit_columns("t", 1..2, -1.0, Bound::NonNegative).unwrap();
/// p.complementary(x.start, s.start).unwrap();
/// p.cost(x.start, 1.0).unwrap();
/// p.cost(x.start + 1, 1.0).unwrap();
/// p.rhs(col![1.0, 1.0].as_ref()).unwrap();
/// let sol = p.build().unwrap().solve(&Options::default()).unwrap();
/// assert!(sol.certificate.holds());
/// assert!((sol.objective.unwrap() - 1.0).abs() < 1e-12);
/// # let _ = t;
/// ```
#[derive(Debug, Clone)]
pub struct ProgramBuilder {
    rows: usize,
    dense_data: Vec<f64>,
    dense_cols: usize,
    columns: Vec<Column>,
    bounds: Vec<Bound>,
    complement: Vec<Option<usize>>,
    b: Option<Col<f64>>,
    cost: Vec<f64>,
    has_cost: bool,
    deferred: Vec<bool>,
    blocks: Vec<(usize, String)>,
}

impl ProgramBuilder {
    /// A program with `rows` equality rows and no unknowns yet.
    pub fn new(rows: usize) -> Self {
        Self {
            rows,
            dense_data: Vec::new(),
            dense_cols: 0,
            columns: Vec::new(),
            bounds: Vec::new(),
            complement: Vec::new(),
            b: None,
            cost: Vec::new(),
            has_cost: false,
            deferred: Vec::new(),
            blocks: Vec::new(),
        }
    }

    /// Adds one unknown per column of `block` (`rows` x k); returns their indices.
    pub fn dense_columns(
        &mut self,
        name: &str,
        block: MatRef<'_, f64>,
        bound: Bound,
    ) -> Result<Range<usize>, LcpError> {
        check_size("dense_columns block", block.nrows(), self.rows, "rows")?;
        check_finite_mat("dense_columns block", block)?;
        let start = self.columns.len();
        self.blocks.push((start, name.to_string()));
        for j in 0..block.ncols() {
            self.dense_data
                .extend((0..self.rows).map(|i| block[(i, j)]));
            self.columns.push(Column::Dense(self.dense_cols));
            self.dense_cols += 1;
            self.push_meta(bound);
        }
        Ok(start..self.columns.len())
    }

    /// Adds one unknown with the dense column `column` (length `rows`).
    pub fn dense_column(
        &mut self,
        name: &str,
        column: ColRef<'_, f64>,
        bound: Bound,
    ) -> Result<usize, LcpError> {
        let r = self.dense_columns(name, column.as_mat(), bound)?;
        Ok(r.start)
    }

    /// Adds one unknown per row in `rows`, with column `coef * e_row` (slacks).
    pub fn unit_columns(
        &mut self,
        name: &str,
        rows: Range<usize>,
        coef: f64,
        bound: Bound,
    ) -> Result<Range<usize>, LcpError> {
        if rows.end > self.rows || rows.start > rows.end {
            return Err(LcpError::DimensionMismatch {
                field: "unit_columns rows",
                expected: self.rows,
                found: rows.end,
                unit: "rows",
            });
        }
        if !coef.is_finite() {
            return Err(LcpError::NonFinite {
                field: "unit_columns coef",
                index: 0,
                value: coef,
            });
        }
        let start = self.columns.len();
        self.blocks.push((start, name.to_string()));
        for row in rows {
            self.columns.push(Column::Unit { row, coef });
            self.push_meta(bound);
        }
        Ok(start..self.columns.len())
    }

    fn push_meta(&mut self, bound: Bound) {
        self.deferred.push(false);
        self.bounds.push(bound);
        self.complement.push(None);
        self.cost.push(0.0);
    }

    fn check_var(&self, field: &'static str, var: usize) -> Result<(), LcpError> {
        if var >= self.columns.len() {
            return Err(LcpError::DimensionMismatch {
                field,
                expected: self.columns.len(),
                found: var,
                unit: "as an unknown's index (out of range)",
            });
        }
        Ok(())
    }

    /// Declares `x_i x_j = 0`; both must be non-negative and not yet paired.
    pub fn complementary(&mut self, i: usize, j: usize) -> Result<(), LcpError> {
        self.check_var("complementary", i)?;
        self.check_var("complementary", j)?;
        let refused = [
            (
                self.deferred[i] || self.deferred[j],
                "a deferred unknown cannot be complementary",
            ),
            (
                i == j || self.complement[i].is_some() || self.complement[j].is_some(),
                "an unknown has at most one complement, and not itself",
            ),
            (
                self.bounds[i] != Bound::NonNegative || self.bounds[j] != Bound::NonNegative,
                "complementary unknowns must be non-negative",
            ),
        ];
        if let Some((_, reason)) = refused.into_iter().find(|(refuses, _)| *refuses) {
            return Err(LcpError::InvalidOption {
                field: "complementary",
                value: format!("({i}, {j})"),
                reason,
            });
        }
        self.complement[i] = Some(j);
        self.complement[j] = Some(i);
        Ok(())
    }

    /// Holds the unknowns `vars` non-basic at 0 through phase 1: they may
    /// enter only in phase 2, once a feasible complementary solution without
    /// them has been found. This is the paper's two-part design method: first
    /// a contact solution with no design separation, then the objective
    /// lowered with the design parameters as extra columns. Deferred unknowns
    /// cannot be complementary (their partner could not enter either).
    pub fn defer(&mut self, vars: Range<usize>) -> Result<(), LcpError> {
        if vars.start > vars.end {
            return Err(LcpError::InvalidOption {
                field: "defer",
                value: format!("{vars:?}"),
                reason: "an empty or reversed range",
            });
        }
        for var in vars {
            self.check_var("defer", var)?;
            if self.complement[var].is_some() {
                return Err(LcpError::InvalidOption {
                    field: "defer",
                    value: format!("{var}"),
                    reason: "a complementary unknown cannot be deferred",
                });
            }
            self.deferred[var] = true;
        }
        Ok(())
    }

    /// Sets the cost of unknown `var` in the objective `c^T x` (to be minimized).
    pub fn cost(&mut self, var: usize, value: f64) -> Result<(), LcpError> {
        self.check_var("cost", var)?;
        if !value.is_finite() {
            return Err(LcpError::NonFinite {
                field: "cost",
                index: var,
                value,
            });
        }
        self.cost[var] = value;
        self.has_cost = true;
        Ok(())
    }

    /// Sets the right-hand side `b` (length `rows`).
    pub fn rhs(&mut self, b: ColRef<'_, f64>) -> Result<(), LcpError> {
        check_size("rhs", b.nrows(), self.rows, "entries")?;
        check_finite_col("rhs", b)?;
        self.b = Some(b.to_owned());
        Ok(())
    }

    /// Finishes the program.
    pub fn build(self) -> Result<ComplementaryProgram, LcpError> {
        if self.rows == 0 {
            return Err(LcpError::Empty { field: "rows" });
        }
        if self.columns.is_empty() {
            return Err(LcpError::Empty { field: "columns" });
        }
        let b = self.b.ok_or(LcpError::Empty { field: "rhs" })?;
        let dense = MatRef::from_column_major_slice(&self.dense_data, self.rows, self.dense_cols)
            .to_owned();
        Ok(ComplementaryProgram {
            rows: self.rows,
            dense,
            columns: self.columns,
            bounds: self.bounds,
            complement: self.complement,
            b,
            cost: self.has_cost.then_some(self.cost),
            deferred: self.deferred,
            blocks: self.blocks,
        })
    }
}

impl ComplementaryProgram {
    /// A program from already-validated parts (used by the mixed-LCP reduction).
    pub(crate) fn from_parts(
        rows: usize,
        dense: Mat<f64>,
        columns: Vec<Column>,
        bounds: Vec<Bound>,
        complement: Vec<Option<usize>>,
        b: Col<f64>,
    ) -> Self {
        let n = columns.len();
        Self {
            rows,
            dense,
            columns,
            bounds,
            complement,
            b,
            cost: None,
            deferred: vec![false; n],
            blocks: vec![(0, "x".to_string())],
        }
        .with_len_check(n)
    }

    fn with_len_check(self, n: usize) -> Self {
        debug_assert_eq!(self.bounds.len(), n);
        debug_assert_eq!(self.complement.len(), n);
        self
    }

    /// Number of equality rows.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of unknowns.
    pub fn unknowns(&self) -> usize {
        self.columns.len()
    }

    /// A readable name for unknown `var`: its block's name and its index in the block.
    pub fn name(&self, var: usize) -> String {
        match self.blocks.iter().rev().find(|(start, _)| *start <= var) {
            Some((start, name)) => format!("{name}[{}]", var - start),
            None => format!("x[{var}]"),
        }
    }

    /// `c^T x`, when the program has an objective.
    pub fn objective(&self, x: ColRef<'_, f64>) -> Option<f64> {
        self.cost
            .as_ref()
            .map(|c| c.iter().zip(x.iter()).map(|(c, x)| c * x).sum())
    }

    /// The certificate of a candidate `x` (see
    /// [`ProgramSolution::certificate`](crate::ProgramSolution::certificate)).
    pub fn certify(&self, x: ColRef<'_, f64>, tolerance: f64) -> Certificate {
        let m = self.rows;
        let mut ax = Col::<f64>::zeros(m);
        let mut terms = Col::<f64>::zeros(m);
        let mut activity = vec![0.0f64; self.columns.len()];
        for (var, col) in self.columns.iter().enumerate() {
            let xv = x[var];
            match *col {
                Column::Dense(j) => {
                    let mut cmax = 0.0f64;
                    for i in 0..m {
                        let a = self.dense[(i, j)];
                        ax[i] += a * xv;
                        terms[i] += (a * xv).abs();
                        cmax = cmax.max(a.abs());
                    }
                    activity[var] = cmax * xv;
                }
                Column::Unit { row, coef } => {
                    ax[row] += coef * xv;
                    terms[row] += (coef * xv).abs();
                    activity[var] = coef.abs() * xv;
                }
            }
        }
        for i in 0..m {
            terms[i] += self.b[i].abs();
        }
        let scale = crate::linalg::norm_inf(terms.as_ref());
        let rel = |v: f64| if scale > 0.0 { v / scale } else { 0.0 };
        let equality = rel((0..m).fold(0.0f64, |a, i| a.max((ax[i] - self.b[i]).abs())));
        let (mut min_z, mut min_w, mut min_u, mut comp) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for var in 0..self.columns.len() {
            if self.bounds[var] != Bound::NonNegative {
                continue;
            }
            let a = rel(activity[var]);
            match self.complement[var] {
                Some(other) if var < other => {
                    min_z = min_z.min(a);
                    comp = comp.max((a * rel(activity[other])).abs());
                }
                Some(_) => min_w = min_w.min(a),
                None => min_u = min_u.min(a),
            }
        }
        Certificate {
            min_z,
            min_w,
            min_u,
            complementarity: comp,
            equality,
            z_scale: scale,
            w_scale: scale,
            tolerance,
            finite: x.iter().all(|v| v.is_finite()),
        }
    }
}
