//! Lemke's complementary pivoting method (Lemke 1965) with a covering vector
//! and a lexicographic minimum-ratio test.
//!
//! ```text
//!     w = M z + d z0 + q,   w, z, z0 >= 0,   z^T w = 0
//! ```
//!
//! Start with `w` basic; `z0` enters at the level that makes `w >= 0`
//! (`z0 = max_i -q_i / d_i`), the row attaining it leaving; then the
//! complement of the variable that just left enters, the lexicographic ratio
//! test picks the leaving one (preferring `z0` whenever it ties), until `z0`
//! leaves (a solution) or no row limits the entering variable (a secondary
//! ray: for copositive-plus `M`, e.g. positive semidefinite, this proves that
//! no solution exists).
//!
//! The mixed form (equality rows `0 = C z + D u + r`, free `u`, as many rows
//! as free unknowns) is solved as the standard LCP of size `n + 2k` obtained
//! by splitting `u = u+ - u-` and the equalities into two opposite
//! inequalities:
//!
//! ```text
//!     M' = [ M   B  -B ]     q' = [  q ]
//!          [ C   D  -D ]          [  r ]
//!          [-C  -D   D ]          [ -r ]
//! ```
//!
//! `M'` is positive semidefinite whenever `M` is and `[B; D]`, `[C D]` form a
//! skew pair (`C = -B^T`, `D = 0`, as in the contact problem with its sign
//! conventions up to a symmetric scaling), so the method's guarantee carries over.
//!
//! A symmetric `M` with a positive diagonal, in the standard form or the
//! contact form (one free unknown whose column `b <= 0` is proportional to
//! minus its equality row), is first solved on the symmetric tableau of
//! [`crate::sweep`]: Lemke's path in its parametric principal-pivoting form,
//! the covering vector being the approach's column, which halves the work
//! of the delayed updates and reads one column per pivot. What that form
//! cannot finish (a matrix that is not positive definite where the path
//! goes) continues here, its pivots counted; an explicit covering vector or
//! refactorization interval (the retry's options) comes here directly.

use faer::{Col, Mat};

use crate::dense::norm_inf;
use crate::problem::{Bound, MixedLcpRef, Options, RawSolution, Statistics};
use crate::system::{Column, System};
use crate::tableau::{Position, RowRule, Tableau, lemke_update_block};
use crate::{LcpError, Method, sweep};

/// Most Ruiz passes of the equilibration (it stops earlier once every row
/// and column maximum is within a factor 2 of 1).
pub(crate) const EQUILIBRATION_PASSES: usize = 40;

/// Size of the standard LCP Lemke's method pivots on for a mixed problem.
pub(crate) fn split_size(p: &MixedLcpRef<'_>) -> usize {
    p.size() + 2 * p.extras()
}

/// Solves a mixed LCP by Lemke's method on its split standard form.
pub(crate) fn solve_mixed(p: &MixedLcpRef<'_>, opts: &Options) -> Result<RawSolution, LcpError> {
    let n = p.size();
    let k = p.extras();
    let me = p.equalities();
    if k != me {
        return Err(LcpError::Unsupported {
            method: "Lemke's method",
            reason: format!(
                "it needs as many equality rows as extra unknowns (got {me} rows, {k} unknowns); use the restricted-entry simplex"
            ),
        });
    }
    if p.bounds.iter().any(|b| *b != Bound::Free) {
        return Err(LcpError::Unsupported {
            method: "Lemke's method",
            reason: "non-negative extra unknowns without complementary rows are not an LCP; use the restricted-entry simplex"
                .into(),
        });
    }
    // A symmetric M: the parametric form on the symmetric tableau; anything
    // it cannot finish goes on below, its pivots counted.
    let mut before = None;
    if let Some(stop) = sweep::applies(p, opts) {
        match sweep::solve(p, opts, stop) {
            Ok(raw) => return Ok(raw),
            Err(stats) => before = Some(stats),
        }
    }
    // The tableau's dense block [-M' | -d] is written directly (no copy of M'
    // is kept): column j of -M' for j < ns, the covering vector after.
    let ns = n + 2 * k;
    let mut dense = Mat::<f64>::zeros(ns, ns + 1);
    let mut q = Col::<f64>::zeros(ns);
    for j in 0..n {
        let col = dense.col_as_slice_mut(j);
        for i in 0..n {
            col[i] = -p.m[(i, j)];
        }
        for e in 0..me {
            col[n + e] = -p.c[(e, j)];
            col[n + k + e] = p.c[(e, j)];
        }
    }
    for j in 0..k {
        for i in 0..n {
            dense[(i, n + j)] = -p.b[(i, j)];
            dense[(i, n + k + j)] = p.b[(i, j)];
        }
        for e in 0..me {
            dense[(n + e, n + j)] = -p.d[(e, j)];
            dense[(n + e, n + k + j)] = p.d[(e, j)];
            dense[(n + k + e, n + j)] = p.d[(e, j)];
            dense[(n + k + e, n + k + j)] = -p.d[(e, j)];
        }
    }
    for i in 0..n {
        q[i] = p.q[i];
    }
    for e in 0..me {
        q[n + e] = p.r[e];
        q[n + k + e] = -p.r[e];
    }
    let (z_full, basic_full, mut statistics) = core(dense, q, opts)?;
    if let Some(before) = before {
        statistics.absorb(&before);
    }
    let z = Col::from_fn(n, |i| z_full[i]);
    let u = Col::from_fn(k, |j| z_full[n + j] - z_full[n + k + j]);
    Ok(RawSolution {
        z,
        u,
        basic: basic_full[..n].to_vec(),
        statistics,
    })
}

/// Lemke on the standard LCP `w = M z + q` given as the tableau's dense
/// block `[-M | *]` (n x (n + 1), the last column overwritten with the
/// covering vector): returns `z`, which `z_i` are basic, and statistics.
fn core(
    dense: Mat<f64>,
    q: Col<f64>,
    opts: &Options,
) -> Result<(Col<f64>, Vec<bool>, Statistics), LcpError> {
    let n = q.nrows();
    let mut stats = Statistics::new(Method::Lemke);
    stats.tableau_rows = n;
    stats.tableau_columns = n + 2;
    if q.iter().all(|&v| v >= 0.0) {
        return Ok((Col::zeros(n), vec![false; n], stats));
    }
    // Variables: w_i = i, z_j = n + j, z0 = 2n. A = [I, -M, -d], b = q.
    let z0 = 2 * n;
    debug_assert_eq!((dense.nrows(), dense.ncols()), (n, n + 1));
    let columns: Vec<Column> = (0..n)
        .map(|i| Column::Unit { row: i, coef: 1.0 })
        .chain((0..=n).map(Column::Dense))
        .collect();
    let mut sys = System {
        rows: n,
        dense,
        columns,
        b: q,
        costs: Vec::new(),
        col_scale: vec![1.0; 2 * n + 1],
        row_scale: vec![1.0; n],
    };
    if opts.equilibrate {
        sys.equilibrate(EQUILIBRATION_PASSES, opts.par(sys.rows, sys.dense.ncols()));
    }
    // Covering vector, in the scaled problem: d' = R d (ones by default).
    for i in 0..n {
        let d = opts
            .covering_vector
            .as_ref()
            .map_or(1.0, |d| d[i] * sys.row_scale[i]);
        sys.dense[(i, n)] = -d;
    }
    let par = opts.par(n, n + 2);
    let tol = opts.tolerances;
    let zero_level = tol.zero * norm_inf(sys.b.as_ref()).max(f64::MIN_POSITIVE);
    let limit = opts.pivot_limit(n, n);
    let refactor_every = opts.refactor_every(n);
    let mut tab = Tableau::from_identity(&sys, (0..n).collect(), par, lemke_update_block(n));

    // First pivot: z0 enters, the row of lexicographically smallest [b̄_i, β_i] / d_i leaves.
    let s0 = match tab.position[z0] {
        Position::Nonbasic(j) => j,
        Position::Basic(_) => unreachable!("z0 starts non-basic"),
    };
    let column0 = tab.column(s0);
    let rows: Vec<(usize, f64)> = (0..n).map(|i| (i, column0[i])).collect();
    let theta_min = rows
        .iter()
        .map(|&(i, d)| tab.rhs(i) / d)
        .fold(f64::INFINITY, f64::min);
    let limit_theta = theta_min + tol.tie * theta_min.abs();
    let ties: Vec<(usize, f64)> = rows
        .into_iter()
        .filter(|&(i, d)| tab.rhs(i) / d <= limit_theta)
        .collect();
    let r0 = tab
        .lex_select(ties, &tol)
        .ok_or(LcpError::NumericalBreakdown {
            size: n,
            pivot: 0,
            reason: "no row limits the covering variable: the data's scale exceeds double precision; rescale q and M",
        })?;
    let mut leaving = tab.pivot(r0, s0, column0);
    stats.pivots = 1;

    while leaving != z0 {
        let entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        let s = match tab.position[entering] {
            Position::Nonbasic(j) => j,
            Position::Basic(_) => unreachable!("the complement of a leaving variable is non-basic"),
        };
        let prefer = match tab.position[z0] {
            Position::Basic(r) => Some(r),
            Position::Nonbasic(_) => None,
        };
        let ratio = tab
            .ratio_test(s, 1.0, |_| RowRule::Bounded, prefer, &tol, zero_level)
            .ok_or_else(|| LcpError::RayTermination {
                size: n,
                pivot: stats.pivots,
                entering: if entering < n {
                    format!("w[{entering}]")
                } else {
                    format!("z[{}]", entering - n)
                },
            })?;
        if ratio.theta == 0.0 {
            stats.degenerate_pivots += 1;
        }
        leaving = tab.pivot(ratio.row, s, ratio.column);
        stats.pivots += 1;
        if leaving != z0 && stats.pivots >= limit {
            return Err(LcpError::PivotLimit { size: n, limit });
        }
        if refactor_every > 0 && stats.pivots.is_multiple_of(refactor_every) && leaving != z0 {
            tab.refactor(&sys)
                .map_err(|ratio| LcpError::SingularBasis {
                    size: n,
                    pivot: stats.pivots,
                    ratio,
                })?;
            stats.refactorizations += 1;
        }
    }

    let (xb, steps) = sys
        .basic_solution(
            &tab.basic.clone(),
            Some(&mut tab),
            par,
            opts.refinement_steps,
        )
        .map_err(|ratio| LcpError::SingularBasis {
            size: n,
            pivot: stats.pivots,
            ratio,
        })?;
    stats.refinement_steps = steps;
    let mut z = Col::<f64>::zeros(n);
    let mut basic = vec![false; n];
    for (row, &var) in tab.basic.iter().enumerate() {
        if (n..2 * n).contains(&var) {
            z[var - n] = sys.col_scale[var] * xb[row];
            basic[var - n] = true;
        }
    }
    Ok((z, basic, stats))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_non_finite_right_hand_side_is_a_breakdown_not_a_panic() {
        // Validated inputs are finite; this reaches the guard directly.
        let dense = Mat::from_fn(2, 3, |i, j| if i == j { -1.0 } else { 0.0 });
        let q = Col::from_fn(2, |_| f64::NAN);
        let options = Options {
            equilibrate: false,
            ..Options::default()
        };
        // q >= 0 fails for NaN, so the pivoting starts.
        let e = core(dense, q, &options).unwrap_err();
        assert!(matches!(
            e,
            LcpError::NumericalBreakdown {
                size: 2,
                pivot: 0,
                ..
            }
        ));
        assert!(
            e.to_string()
                .starts_with("numerical breakdown at pivot 0 (size 2): no row limits"),
            "{e}"
        );
    }
}
