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
//! skew pair (`C = -B^T`, `D = 0`, as in a bordered problem), so the
//! method's guarantee carries over.

use faer::{Col, Mat};

use crate::LcpError;
use crate::linalg::norm_inf;
use crate::methods::{Answer, Attempted, Failure, NotApplicable};
use crate::options::Options;
use crate::problem::{Bound, MixedRef, Problem};
use crate::statistics::Work;
use crate::tableau::basic::basic_solution;
use crate::tableau::general::{GeneralTableau, Position, RowRule, Tied, lemke_update_block};
use crate::tableau::system::{Column, EQUILIBRATION_PASSES, System};

/// Size of the standard LCP Lemke's method pivots on for a mixed problem.
pub(crate) fn split_size(p: &MixedRef<'_>) -> usize {
    p.size() + 2 * p.extras()
}

/// Whether Lemke's method applies: as many equality rows as extra
/// unknowns, every one free.
pub(crate) fn applies(problem: &Problem<'_>) -> Result<(), NotApplicable> {
    let p = &problem.mixed;
    let (k, me) = (p.extras(), p.equalities());
    if k != me {
        return Err(NotApplicable::new(format!(
            "it needs as many equality rows as extra unknowns (got {me} rows, {k} unknowns); use the restricted-entry simplex"
        )));
    }
    if p.bounds.iter().any(|b| *b != Bound::Free) {
        return Err(NotApplicable::new(
            "non-negative extra unknowns without complementary rows are not an LCP; use the restricted-entry simplex",
        ));
    }
    Ok(())
}

/// Lemke's method on the split standard form of `problem` (see the module
/// documentation).
pub(crate) fn attempt(problem: &Problem<'_>, opts: &Options) -> Attempted {
    let p = &problem.mixed;
    let (n, k, me) = (p.size(), p.extras(), p.equalities());
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
    let split = core(dense, q, opts)?;
    let z = Col::from_fn(n, |i| split.z[i]);
    let u = Col::from_fn(k, |j| split.z[n + j] - split.z[n + k + j]);
    Ok(Answer {
        z,
        u,
        basic: split.basic[..n].to_vec(),
        work: split.work,
    })
}

/// The answer of [`core()`] on the split standard form.
struct Split {
    z: Col<f64>,
    basic: Vec<bool>,
    work: Work,
}

/// Lemke on the standard LCP `w = M z + q` given as the tableau's dense
/// block `[-M | *]` (n x (n + 1), the last column overwritten with the
/// covering vector): returns `z`, which `z_i` are basic, and the work.
fn core(dense: Mat<f64>, q: Col<f64>, opts: &Options) -> Result<Split, Failure> {
    let n = q.nrows();
    let mut work = Work {
        tableau_rows: n,
        tableau_columns: n + 2,
        ..Work::default()
    };
    if q.iter().all(|&v| v >= 0.0) {
        return Ok(Split {
            z: Col::zeros(n),
            basic: vec![false; n],
            work,
        });
    }
    let sys = system(dense, q, opts);
    let par = opts.par(n, n + 2);
    let mut tab =
        match GeneralTableau::from_identity(&sys, (0..n).collect(), par, lemke_update_block(n)) {
            Ok(tab) => tab,
            Err(e) => return Err(Failure::error(e, work)),
        };
    let leaving = match enter_covering(&mut tab, opts) {
        Ok(leaving) => leaving,
        Err(e) => return Err(Failure::error(e, work)),
    };
    work.pivots = 1;
    if let Err(e) = walk(&mut tab, &sys, opts, &mut work, leaving) {
        return Err(Failure::error(e, work));
    }
    let basis = tab.basic.clone();
    let (xb, steps) = match basic_solution(&sys, &basis, Some(&mut tab), par, opts.refinement_steps)
    {
        Ok(v) => v,
        Err(singular) => return Err(Failure::error(singular.at(n, work.pivots), work)),
    };
    work.refinement_steps = steps;
    let mut z = Col::<f64>::zeros(n);
    let mut basic = vec![false; n];
    for (row, &var) in tab.basic.iter().enumerate() {
        if (n..2 * n).contains(&var) {
            z[var - n] = sys.col_scale[var] * xb[row];
            basic[var - n] = true;
        }
    }
    Ok(Split { z, basic, work })
}

/// The system `[I, -M, -d] x = q` (variables `w_i = i`, `z_j = n + j`,
/// `z0 = 2n`), equilibrated, with the covering vector in the scaled
/// problem `d' = R d` (ones by default).
fn system(dense: Mat<f64>, q: Col<f64>, opts: &Options) -> System {
    let n = q.nrows();
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
    for i in 0..n {
        let d = opts
            .covering_vector
            .as_ref()
            .map_or(1.0, |d| d[i] * sys.row_scale[i]);
        sys.dense[(i, n)] = -d;
    }
    sys
}

/// The first pivot: `z0` enters, the row of lexicographically smallest
/// `[b̄_i, β_i] / d_i` leaves; returns the variable that left.
fn enter_covering(tab: &mut GeneralTableau, opts: &Options) -> Result<usize, LcpError> {
    let n = tab.m;
    let tol = opts.tolerances;
    let Position::Nonbasic(s0) = tab.position[2 * n] else {
        unreachable!("z0 starts non-basic")
    };
    let column0 = tab.column(s0);
    let rows: Vec<Tied> = (0..n)
        .map(|row| Tied {
            row,
            pivot: column0[row],
        })
        .collect();
    let theta_min = rows
        .iter()
        .map(|t| tab.rhs(t.row) / t.pivot)
        .fold(f64::INFINITY, f64::min);
    let limit_theta = theta_min + tol.tie * theta_min.abs();
    let ties: Vec<Tied> = rows
        .into_iter()
        .filter(|t| tab.rhs(t.row) / t.pivot <= limit_theta)
        .collect();
    let Some(r0) = tab.lex_select(ties, &tol) else {
        return Err(LcpError::NumericalBreakdown {
            size: n,
            pivot: 0,
            reason: "no row limits the covering variable: the data's scale exceeds double precision; rescale q and M",
        });
    };
    Ok(tab.pivot(r0, s0, column0))
}

/// The complementary pivots after the first, until `z0` leaves: the
/// complement of the variable that just left (`leaving`) enters, the
/// lexicographic ratio test (preferring `z0`) picks the leaving one; the
/// tableau is refactored from the data every `refactor_interval` pivots.
fn walk(
    tab: &mut GeneralTableau,
    sys: &System,
    opts: &Options,
    work: &mut Work,
    mut leaving: usize,
) -> Result<(), LcpError> {
    let n = tab.m;
    let z0 = 2 * n;
    let tol = opts.tolerances;
    let zero_level = tol.zero * norm_inf(sys.b.as_ref()).max(f64::MIN_POSITIVE);
    let limit = opts.pivot_limit(n, n);
    let refactor_every = opts.refactor_every(n);
    while leaving != z0 {
        crate::cancel::check()?;
        let entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        let Position::Nonbasic(s) = tab.position[entering] else {
            unreachable!("the complement of a leaving variable is non-basic")
        };
        let prefer = match tab.position[z0] {
            Position::Basic(r) => Some(r),
            Position::Nonbasic(_) => None,
        };
        let Some(ratio) = tab.ratio_test(s, 1.0, |_| RowRule::Bounded, prefer, &tol, zero_level)
        else {
            return Err(LcpError::RayTermination {
                size: n,
                pivot: work.pivots,
                entering: if entering < n {
                    format!("w[{entering}]")
                } else {
                    format!("z[{}]", entering - n)
                },
            });
        };
        if ratio.theta == 0.0 {
            work.degenerate_pivots += 1;
        }
        leaving = tab.pivot(ratio.row, s, ratio.column);
        work.pivots += 1;
        if leaving != z0 && work.pivots >= limit {
            return Err(LcpError::PivotLimit { size: n, limit });
        }
        if refactor_every > 0 && work.pivots.is_multiple_of(refactor_every) && leaving != z0 {
            tab.refactor(sys)
                .map_err(|singular| singular.at(n, work.pivots))?;
            work.refactorizations += 1;
        }
    }
    Ok(())
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
        let Err(failure) = core(dense, q, &options) else {
            panic!("a NaN right-hand side was solved");
        };
        let crate::statistics::Breakdown::Error(e) = failure.breakdown else {
            panic!("{:?}", failure.breakdown);
        };
        assert!(matches!(
            *e,
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
