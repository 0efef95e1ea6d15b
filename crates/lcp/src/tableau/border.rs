//! The first contact of a bordered problem: where the rigid bodies touch
//! before anything deforms, under the given resultants.
//!
//! For `w = M z - B λ + q`, `B^T z = b`, follow the resultants from zero:
//! `B^T z = t b`, `t` from 0 to 1. As `t -> 0+` the forces are `z = t z1 +
//! O(t^2)`, and to first order `z1` solves the linear program
//!
//! ```text
//!     minimize q^T z1   subject to  B^T z1 = b,  z1 >= 0          (k rows)
//!     dual:    maximize b^T λ  subject to  q - B λ >= 0            (no interference)
//! ```
//!
//! whose optimal basis `J0` (k indices) is the set of first contacts and
//! whose dual `λ0` the rigid-body position there: for the contact problem
//! with one row, the least separation (the approach at first contact); with
//! tilts, the rigid position in which the points touching can carry the
//! load and its moments. The symmetric tableau's path starts there.
//!
//! The program is small (k rows, n columns): a revised simplex with a dense
//! k x k basis, two phases, Dantzig's choice and Bland's rule after a
//! degenerate pivot.

use faer::linalg::solvers::{PartialPivLu, Solve, SolveCore};
use faer::{Col, ColRef, Mat, MatRef};

use crate::linalg::norm_inf;
use crate::tolerance::Tolerances;

/// The first contact (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FirstContact {
    /// The k indices of the optimal basis, in row order.
    pub basis: Vec<usize>,
    /// The rigid-body unknowns there, `λ0` (k).
    pub lambda: Vec<f64>,
}

/// Why there is no first contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NoContact {
    /// No `z >= 0` has `B^T z = b`: the points cannot carry the resultants
    /// (the load's line of action misses their convex hull).
    Unreachable,
    /// Every rigid position interferes somewhere (`q - B λ >= 0` has no
    /// solution), or the program stalled.
    Interference,
}

/// Most simplex iterations per phase, per unknown.
const ITERATIONS_PER_UNKNOWN: usize = 20;

/// The revised simplex's state: unknowns `0..n` are the points (column
/// `B_j^T`), `n..n+k` the artificials (`±e_r`, the sign of `b_r`).
struct Lp<'a> {
    border: MatRef<'a, f64>,
    rhs: ColRef<'a, f64>,
    sign: Vec<f64>,
    basis: Vec<usize>,
    tol: Tolerances,
}

impl Lp<'_> {
    fn n(&self) -> usize {
        self.border.nrows()
    }

    fn column(&self, v: usize) -> Col<f64> {
        let (n, k) = (self.n(), self.border.ncols());
        if v < n {
            self.border.row(v).transpose().to_owned()
        } else {
            Col::from_fn(k, |r| if r == v - n { self.sign[r] } else { 0.0 })
        }
    }

    fn factor(&self) -> PartialPivLu<f64> {
        let k = self.basis.len();
        let mut b = Mat::<f64>::zeros(k, k);
        for (j, &v) in self.basis.iter().enumerate() {
            b.col_mut(j).copy_from(self.column(v));
        }
        b.partial_piv_lu()
    }

    /// Runs one phase with the costs `cost` (of every unknown, points and
    /// artificials); artificials never enter. `Err(Interference)` when the
    /// objective is unbounded below or the phase stalls.
    fn phase(&mut self, cost: &dyn Fn(usize) -> f64) -> Result<(), NoContact> {
        let (n, k) = (self.n(), self.border.ncols());
        let scale = (0..n + k).fold(0.0f64, |a, v| a.max(cost(v).abs()));
        let mut bland = false;
        for _ in 0..ITERATIONS_PER_UNKNOWN * (n + k) {
            let lu = self.factor();
            let mut x = self.rhs.to_owned();
            lu.solve_in_place_with_conj(faer::Conj::No, x.as_mat_mut());
            let cb = Col::from_fn(k, |r| cost(self.basis[r]));
            let y = lu.solve_transpose(&cb);
            // The entering point: most negative reduced cost (Dantzig), or
            // the first negative one (Bland) after a degenerate pivot.
            let mut entering: Option<(usize, f64)> = None;
            for v in (0..n).filter(|v| !self.basis.contains(v)) {
                let a = self.column(v);
                let reduced = cost(v) - (0..k).map(|r| y[r] * a[r]).sum::<f64>();
                let terms = cost(v).abs() + (0..k).map(|r| (y[r] * a[r]).abs()).sum::<f64>();
                if reduced < -self.tol.cost * terms.max(scale)
                    && entering.is_none_or(|e| reduced < e.1)
                {
                    entering = Some((v, reduced));
                    if bland {
                        break;
                    }
                }
            }
            let Some((v, _)) = entering else {
                return Ok(());
            };
            let mut dir = self.column(v);
            lu.solve_in_place_with_conj(faer::Conj::No, dir.as_mat_mut());
            let small = self.tol.pivot * norm_inf(dir.as_ref());
            let zero = self.tol.zero * norm_inf(x.as_ref());
            // The leaving row: least ratio, ties to the least basic unknown (Bland).
            let mut leaving: Option<(usize, f64)> = None;
            for r in 0..k {
                if dir[r] > small {
                    let ratio = x[r].max(0.0) / dir[r];
                    let better = leaving.is_none_or(|(l, t)| {
                        ratio < t || (ratio == t && self.basis[r] < self.basis[l])
                    });
                    if better {
                        leaving = Some((r, ratio));
                    }
                }
            }
            let Some((r, theta)) = leaving else {
                return Err(NoContact::Interference);
            };
            bland |= theta * dir[r] <= zero;
            self.basis[r] = v;
        }
        Err(NoContact::Interference)
    }
}

/// The first contact of the border `B` (n x k) under the resultants `b`
/// with separations `q` (see the module documentation).
pub(crate) fn first_contact(
    border: MatRef<'_, f64>,
    resultant: ColRef<'_, f64>,
    q: ColRef<'_, f64>,
    tol: &Tolerances,
) -> Result<FirstContact, NoContact> {
    let (n, k) = (border.nrows(), border.ncols());
    let mut lp = Lp {
        border,
        rhs: resultant,
        sign: resultant
            .iter()
            .map(|&v| if v < 0.0 { -1.0 } else { 1.0 })
            .collect(),
        basis: (n..n + k).collect(),
        tol: *tol,
    };
    // Phase 1: the artificials' sum, to zero.
    lp.phase(&|v| if v < n { 0.0 } else { 1.0 })?;
    let lu = lp.factor();
    let mut x = resultant.to_owned();
    lu.solve_in_place_with_conj(faer::Conj::No, x.as_mat_mut());
    let level = tol.zero * norm_inf(resultant).max(f64::MIN_POSITIVE);
    let residual: f64 = (0..k)
        .filter(|&r| lp.basis[r] >= n)
        .map(|r| x[r].abs())
        .sum();
    if residual > level {
        return Err(NoContact::Unreachable);
    }
    // Artificials left basic at zero: exchange each for a point (B has full
    // column rank, so some point's entry in its row is non-zero).
    for r in 0..k {
        if lp.basis[r] < n {
            continue;
        }
        let lu = lp.factor();
        let row_of = |v: usize| {
            let mut d = lp.column(v);
            lu.solve_in_place_with_conj(faer::Conj::No, d.as_mat_mut());
            d[r].abs() / norm_inf(d.as_ref()).max(f64::MIN_POSITIVE)
        };
        let best = (0..n)
            .filter(|v| !lp.basis.contains(v))
            .map(|v| (v, row_of(v)))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match best {
            Some((v, a)) if a > tol.pivot => lp.basis[r] = v,
            _ => return Err(NoContact::Unreachable),
        }
    }
    // Phase 2: the separations.
    lp.phase(&|v| if v < n { q[v] } else { 0.0 })?;
    let lu = lp.factor();
    let cb = Col::from_fn(k, |r| q[lp.basis[r]]);
    let lambda = lu.solve_transpose(&cb);
    Ok(FirstContact {
        basis: lp.basis,
        lambda: lambda.iter().copied().collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::{col, mat};

    /// The first contact of `border` and `resultant` over `q`, at the
    /// default tolerances.
    fn start(
        border: &Mat<f64>,
        resultant: Col<f64>,
        q: &Col<f64>,
    ) -> Result<FirstContact, NoContact> {
        first_contact(
            border.as_ref(),
            resultant.as_ref(),
            q.as_ref(),
            &Tolerances::default(),
        )
    }

    #[test]
    fn one_row_is_the_least_separation() {
        let border = mat![[1.0], [1.0], [1.0], [1.0]];
        let q = col![0.3, 0.1, 0.2, 0.5];
        let first = start(&border, col![2.0], &q).unwrap();
        assert_eq!(first.basis, vec![1]);
        assert_eq!(first.lambda, vec![0.1]);
    }

    #[test]
    fn a_tilted_rigid_body_rests_on_the_points_around_the_load() {
        // Points at x = -2..2 with separations x^2 / 10 (a cylinder's
        // profile), columns (1, x), the load 1 at x = 0.5: resultants
        // (P, P e) = (1, 0.5). The rigid body rests on the two points either
        // side of the load, x = 0 and x = 1, each carrying half; the rigid
        // position is the line through their separations, λ = (0, 0.1).
        let xs = [-2.0, -1.0, 0.0, 1.0, 2.0];
        let border = Mat::from_fn(5, 2, |i, j| if j == 0 { 1.0 } else { xs[i] });
        let q = Col::from_fn(5, |i| xs[i] * xs[i] / 10.0);
        let first = start(&border, col![1.0, 0.5], &q).unwrap();
        let mut basis = first.basis.clone();
        basis.sort_unstable();
        assert_eq!(basis, vec![2, 3]);
        assert!(first.lambda[0].abs() <= 1e-16, "{first:?}");
        assert!((first.lambda[1] - 0.1).abs() <= 1e-16, "{first:?}");
        // The load outside the points' span [-2, 2] cannot be carried.
        let e = start(&border, col![1.0, 3.0], &q).unwrap_err();
        assert_eq!(e, NoContact::Unreachable);
    }

    #[test]
    fn interference_everywhere_has_no_start() {
        // A tilt alone (column x) with zero moment and two points already
        // interfering (q < 0) symmetrically: no rotation clears both, and
        // forces on both carry no moment, so the program is unbounded.
        let border = mat![[-1.0], [0.0], [1.0]];
        let q = col![-1.0, 0.5, -1.0];
        let e = start(&border, col![0.0], &q).unwrap_err();
        assert_eq!(e, NoContact::Interference);
    }
}
