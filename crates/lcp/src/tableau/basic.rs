//! The final basic solution of a general-tableau method, recomputed from the
//! original data: `B x_B = b` for the final basis `B`, iteratively refined
//! until the componentwise backward error
//! `max_i |b - B x|_i / (|B| |x| + |b|)_i` is at rounding level.
//!
//! The tableau already holds `B^{-1}` (relative to its initial identity
//! basis), so refinement first runs with it: a matrix-vector product per
//! step instead of an LU of the basis. A fresh LU of the basis
//! ([`BasisFactor`]) decides when that declines (a basis near singularity)
//! or stalls above [`TABLEAU_ACCEPT`] (a tableau that drifted).

use faer::{Col, Par};

use crate::tableau::general::GeneralTableau;
use crate::tableau::system::{BasisFactor, Refined, Singular, System};
use crate::tolerance::{NEAR_SINGULAR_PER_ROW, TABLEAU_ACCEPT};

/// The basic solution `x_B` for the basis `basis` (variables, in row order)
/// of `system`, and the refinement steps taken; `Err` for a numerically
/// singular basis. `tableau`, when given, is the general tableau of this
/// basis (see the module documentation); the better of its iterate and the
/// LU path's is kept.
pub(crate) fn basic_solution(
    system: &System,
    basis: &[usize],
    tableau: Option<&mut GeneralTableau>,
    par: Par,
    max_steps: usize,
) -> Result<(Col<f64>, usize), Singular> {
    let from_tableau =
        match tableau.and_then(|tab| refine_from_tableau(system, basis, tab, max_steps)) {
            Some(r) if r.error <= TABLEAU_ACCEPT => return Ok((r.x, r.steps)),
            other => other,
        };
    let factor = BasisFactor::new(system, basis, par)?;
    let mut x = system.b.clone();
    factor.solve_in_place(x.as_mat_mut(), par);
    let lu = system.refine_basic(basis, x, max_steps, |r| {
        factor.solve_in_place(r.as_mat_mut(), par);
    });
    Ok(match from_tableau {
        Some(t) if t.error < lu.error => (t.x, t.steps),
        _ => (lu.x, lu.steps),
    })
}

/// The basic solution refined from the tableau's right-hand side with the
/// `B^{-1}` the tableau holds ([`GeneralTableau::solve_basis`]). `None` for a
/// basis near singularity (a reciprocal condition estimate
/// `1 / (|B|_1 |B^{-1}|_1)` at or below [`NEAR_SINGULAR_PER_ROW`] times its
/// rows), on which refinement can reach a small backward error and a
/// meaningless answer: the LU path then decides.
pub(crate) fn refine_from_tableau(
    system: &System,
    basis: &[usize],
    tab: &mut GeneralTableau,
    max_steps: usize,
) -> Option<Refined> {
    let rcond = 1.0 / (system.basis_norm_1(basis) * tab.basis_inverse_norm_1());
    if rcond <= NEAR_SINGULAR_PER_ROW * system.rows as f64 {
        return None;
    }
    let x = Col::from_fn(system.rows, |i| tab.rhs(i));
    Some(system.refine_basic(basis, x, max_steps, |r| tab.solve_basis(r)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tableau::general::Position;
    use crate::tableau::system::Column;
    use faer::Mat;

    /// `[I, -M] x = q` with M = tridiag(-1, 4, -1) + a rank-one coupling
    /// (non-symmetric), its identity basis pivoted to the dense columns of
    /// the first `pivots` rows.
    fn pivoted(n: usize, pivots: usize) -> (System, GeneralTableau) {
        let dense = Mat::from_fn(n, n, |i, j| {
            let band = match i.abs_diff(j) {
                0 => 4.0,
                1 => -1.0,
                _ => 0.0,
            };
            -(band + 0.1 * (i as f64 + 1.0) / (j as f64 + 2.0))
        });
        let columns = (0..n)
            .map(|i| Column::Unit { row: i, coef: 1.0 })
            .chain((0..n).map(Column::Dense))
            .collect();
        let system = System {
            rows: n,
            dense,
            columns,
            b: Col::from_fn(n, |i| 1.0 + (i as f64).sin()),
            costs: Vec::new(),
            col_scale: vec![1.0; 2 * n],
            row_scale: vec![1.0; n],
        };
        let mut tab =
            GeneralTableau::from_identity(&system, (0..n).collect(), Par::Seq, 64).unwrap();
        for r in 0..pivots {
            let Position::Nonbasic(s) = tab.position[n + r] else {
                unreachable!()
            };
            let column = tab.column(s);
            tab.pivot(r, s, column);
        }
        (system, tab)
    }

    fn max_abs(v: &Col<f64>) -> f64 {
        v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
    }

    #[test]
    fn the_tableau_inverse_equals_an_lu_solve() {
        let (system, mut tab) = pivoted(150, 100);
        let basis = tab.basic.clone();
        let factor = BasisFactor::new(&system, &basis, Par::Seq).unwrap();
        let r = Col::from_fn(150, |i| (1.0 + i as f64).sqrt().sin());
        let mut from_lu = r.clone();
        factor.solve_in_place(from_lu.as_mat_mut(), Par::Seq);
        let mut from_tableau = r.clone();
        tab.solve_basis(&mut from_tableau);
        let diff = max_abs(&(&from_lu - &from_tableau));
        assert!(diff <= 1e-12 * max_abs(&from_lu), "{diff:e}");
    }

    #[test]
    fn the_tableau_path_refines_a_perturbed_solution_to_the_lu_one() {
        let (system, mut tab) = pivoted(150, 100);
        let basis = tab.basic.clone();
        let (lu, _) = basic_solution(&system, &basis, None, Par::Seq, 3).unwrap();
        // A right-hand side off by 1e-9 (relative): refinement must repair it.
        tab.drift(1.0, 1.0 + 1e-9);
        let r = refine_from_tableau(&system, &basis, &mut tab, 3).unwrap();
        assert!(
            r.steps >= 1 && r.error <= TABLEAU_ACCEPT,
            "{} steps, error {:e}",
            r.steps,
            r.error
        );
        let diff = max_abs(&(&lu - &r.x));
        assert!(diff <= 64.0 * f64::EPSILON * max_abs(&lu), "{diff:e}");
        let (y, _) = basic_solution(&system, &basis, Some(&mut tab), Par::Seq, 3).unwrap();
        assert_eq!(r.x, y);
    }

    #[test]
    fn a_drifted_tableau_falls_back_to_the_lu_solution() {
        let (system, mut tab) = pivoted(150, 100);
        let basis = tab.basic.clone();
        let (lu, _) = basic_solution(&system, &basis, None, Par::Seq, 3).unwrap();
        // Corrupt the tableau's B^{-1} and right-hand side far past what
        // refinement can repair: its own answer is rejected.
        tab.drift(3.0, 3.0);
        let r = refine_from_tableau(&system, &basis, &mut tab, 3).unwrap();
        assert!(r.error > TABLEAU_ACCEPT, "{:e}", r.error);
        let (x, _) = basic_solution(&system, &basis, Some(&mut tab), Par::Seq, 3).unwrap();
        let diff = max_abs(&(&lu - &x));
        assert!(diff <= 64.0 * f64::EPSILON * max_abs(&lu), "{diff:e}");
    }
}
