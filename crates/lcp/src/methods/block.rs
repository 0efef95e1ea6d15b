//! Block principal pivoting for LCPs with a symmetric positive definite `M`
//! (Júdice & Pires 1994; Kostreva 1978), extended to the mixed form with
//! free unknowns and as many equality rows (a border of k rows).
//!
//! Guess the set `J` of basic `z` (the contact set); solve the equilibrium on
//! it with a faer Cholesky of `M_JJ` and the border's Schur complement
//! (`crate::tableau::active_set`):
//!
//! ```text
//!     M_JJ z_J + B_J u = -q_J              (w_J = 0)
//!     C_J z_J + D u    = -r                (the equality rows)
//! ```
//!
//! then `w = M z + B u + q`. Every infeasible index (`z_i < 0` in `J`,
//! `w_i < 0` outside) moves to the other side at once. Safeguard (finite
//! termination): the number of infeasibilities must fall at least once every
//! `1 + BLOCK_RETRIES` iterations; otherwise single principal pivots on the
//! infeasible index of least number (Murty 1974), which terminate for a
//! P-matrix but may take very many steps, each a factorization: after
//! `MURTY_PIVOTS` of them the attempt gives up (a beam on a very stiff
//! foundation, 1500 unknowns, took 1931 iterations and 4 s where Lemke's
//! method takes 59 pivots and 0.07 s). A principal block that is not
//! positive definite, a singular border, that limit or the iteration cap is
//! a breakdown (the strategy then finishes by Lemke's method, which
//! terminates on every problem of this class).
//!
//! The first guess, without a warm start, comes from a prefix search: the
//! indices in the order in which they would activate, grown by a fixed
//! ratio until the block solution turns negative somewhere, so that the
//! factorization work is about that of the final contact set rather than of
//! the whole of `M` (see `prefix_search`).

use faer::Par;

use crate::LcpError;
use crate::linalg::norm_inf;
use crate::methods::{Answer, Attempted, Failure, NotApplicable, touch_order};
use crate::options::Options;
use crate::problem::{MixedRef, Problem};
use crate::statistics::{Breakdown, Work};
use crate::tableau::active_set::{BlockFailure, BlockSystem, Factor, violations};
use crate::tolerance::Tolerances;

/// Full block exchanges allowed without a fall in the infeasibility count.
const BLOCK_RETRIES: usize = 3;

/// Murty's single principal pivots allowed before the attempt gives up to
/// Lemke's method: the block exchange has stalled, and each single pivot
/// costs a factorization update where a Lemke pivot costs a rank-one
/// update of the tableau.
const MURTY_PIVOTS: usize = 16;

/// Whether block pivoting applies: free extra unknowns, as many equality
/// rows, and a symmetric `M`.
pub(crate) fn applies(problem: &Problem<'_>) -> Result<(), NotApplicable> {
    if !problem.free_square() {
        return Err(NotApplicable::new(
            "it needs free extra unknowns and as many equality rows; use the restricted-entry simplex",
        ));
    }
    if !problem.symmetric() {
        let (i, j) = crate::linalg::asymmetry(problem.mixed.m).unwrap_or((0, 0));
        return Err(NotApplicable::new(format!(
            "M is not symmetric (entry ({i}, {j})); use Lemke's method"
        )));
    }
    Ok(())
}

/// Block principal pivoting on `problem` (see the module documentation).
pub(crate) fn attempt(problem: &Problem<'_>, opts: &Options) -> Attempted {
    let p = &problem.mixed;
    let n = p.size();
    let mut work = Work::default();
    let par = opts.par(n, n);
    let tol = opts.tolerances;
    let cap = opts.max_pivots.unwrap_or(3 * n + 50);
    let mut best = usize::MAX;
    let mut retries = BLOCK_RETRIES;
    let mut singles = 0usize;
    let key = touch_order(problem, opts).unwrap_or_else(|| keys(p));
    let mut factor = Factor::new(n);
    let mut active = match warm_start(p, opts) {
        Some(a) => a,
        None => prefix_search(p, &key, &mut factor, &tol, par, &mut work),
    };
    loop {
        work.iterations += 1;
        crate::cancel::check().map_err(|c| Failure::new(c.into(), work))?;
        // Iterations only need the signs of z and w; the solution is refined
        // once the active set is found (below).
        let solved = factor
            .update(p, &active, &key, par, &mut work)
            .and_then(|()| BlockSystem::new(p, &factor, par));
        let system = match solved {
            Ok(v) => v,
            // A principal block that is not positive definite (a beam's
            // clamped point has a zero row) or a singular Schur complement.
            Err(BlockFailure::NotPositiveDefinite) => {
                return Err(Failure::new(Breakdown::NotPositiveDefinite, work));
            }
            Err(BlockFailure::Singular) => {
                return Err(Failure::new(Breakdown::SingularBorder, work));
            }
            Err(BlockFailure::Allocation(e)) => {
                return Err(Failure::error(LcpError::from(e), work));
            }
        };
        let (mut z, mut u) = system.solution(p);
        let mut infeasible = violations(p, &active, &z, &u, &tol, par);
        if infeasible.is_empty() {
            // The active set is found: refine its solution from the original
            // data; if that moves a sign, the safeguarded exchange goes on.
            system.refine(p, &mut z, &mut u, opts.refinement_steps, &mut work);
            infeasible = violations(p, &active, &z, &u, &tol, par);
            if infeasible.is_empty() {
                return Ok(Answer {
                    z,
                    u,
                    basic: active,
                    work,
                });
            }
        }
        if work.iterations >= cap {
            return Err(Failure::new(Breakdown::IterationCap, work));
        }
        if infeasible.len() < best {
            best = infeasible.len();
            retries = BLOCK_RETRIES;
        } else if retries > 0 {
            retries -= 1;
        } else {
            // Murty's least-index single principal pivot.
            singles += 1;
            if singles > MURTY_PIVOTS {
                return Err(Failure::new(Breakdown::IterationCap, work));
            }
            let i = infeasible[0];
            active[i] = !active[i];
            work.pivots += 1;
            continue;
        }
        for &i in &infeasible {
            active[i] = !active[i];
        }
        work.pivots += infeasible.len();
    }
}
/// The order in which indices join the factor: by the threshold `q_i /
/// |B_i|` (for one extra unknown: the approach at which point i touches),
/// else by `q_i`. (A bordered problem is ordered by the approach at which
/// each index touches, or the gap at its first contact:
/// `crate::methods::touch_order`.)
fn keys(p: &MixedRef<'_>) -> Vec<f64> {
    (0..p.size())
        .map(|i| {
            let b = (0..p.extras()).fold(0.0f64, |a, j| a.max(p.b[(i, j)].abs()));
            if b > 0.0 { p.q[i] / b } else { p.q[i] }
        })
        .collect()
}

/// The warm start, if one was given and fits (with equality rows it must
/// activate at least one index, or the block system is singular).
fn warm_start(p: &MixedRef<'_>, opts: &Options) -> Option<Vec<bool>> {
    let a = opts.warm_start.as_ref()?;
    (a.len() == p.size() && (p.extras() == 0 || a.iter().any(|&x| x))).then(|| a.clone())
}

/// Growth of the prefix per step of [`prefix_search`] (its size times this,
/// plus [`PREFIX_STEP`]).
const PREFIX_GROWTH: f64 = 1.15;
/// The first prefix's size, and the fixed part of each step.
const PREFIX_STEP: usize = 32;
/// Steps in a row a prefix search grows past a singular Schur complement.
const SINGULAR_STEPS: usize = 3;

/// The initial active set without a warm start: the shortest prefix of the
/// indices in `key` order whose block solution has a negative `z`.
///
/// In a contact problem `key` is the approach at which each point touches,
/// and a prefix is the set of points of least separation. A prefix smaller
/// than the contact set pushes everywhere (`z > 0`) but leaves points outside
/// it interpenetrating, and the whole-set exchange of the first iterations
/// would jump from it to nearly every index: one factorization of the
/// whole of `M`. Growing the prefix by a fixed ratio instead, each step
/// factoring only the indices that join (the factor keeps the prefix), stops
/// at the first prefix whose solution turns negative: on a contact problem
/// at most about [`PREFIX_GROWTH`] times the contact set plus
/// [`PREFIX_STEP`], which the block iterations then shrink (a shrinking
/// prefix keeps its factor), so the factorization work is about that of the
/// contact set, not of `M`. It is a heuristic first guess: the iterations
/// correct any guess.
///
/// Without equality rows the prefix is capped at the indices with `q_i < 0`
/// (where `w` is negative at `z = 0`: the old initial guess); with them, the
/// first prefix holds at least the indices whose key ties the smallest (a
/// flat contact touches everywhere at once) to the zero tolerance of the
/// keys' scale, since equal separations computed from a geometry differ in
/// their last bits.
fn prefix_search(
    p: &MixedRef<'_>,
    key: &[f64],
    factor: &mut Factor,
    tol: &Tolerances,
    par: Par,
    work: &mut Work,
) -> Vec<bool> {
    let n = p.size();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| key[a].total_cmp(&key[b]).then(a.cmp(&b)));
    let (first, cap) = if p.extras() == 0 {
        let negative = (0..n).filter(|&i| p.q[i] < 0.0).count();
        (negative.min(PREFIX_STEP), negative)
    } else {
        let kmin = key.iter().copied().fold(f64::INFINITY, f64::min);
        let kscale = key.iter().fold(0.0f64, |a, k| a.max(k.abs()));
        let ties = key
            .iter()
            .filter(|&&k| k <= kmin + tol.zero * kscale)
            .count();
        (ties.max(PREFIX_STEP.min(n)), n)
    };
    let mut active = vec![false; n];
    let mut size = 0;
    let mut next = first;
    let mut singular = 0;
    while next > size {
        for &i in &order[size..next] {
            active[i] = true;
        }
        size = next;
        if size == cap {
            break;
        }
        let grown = cap.min((size as f64 * PREFIX_GROWTH) as usize + PREFIX_STEP);
        let solved = factor
            .update(p, &active, key, par, work)
            .and_then(|()| BlockSystem::new(p, factor, par));
        match solved {
            Ok(system) => {
                singular = 0;
                let (z, _) = system.solution(p);
                let zscale = norm_inf(z.as_ref());
                if z.iter().any(|&v| v < -tol.zero * zscale) {
                    break;
                }
            }
            // A singular Schur complement of the equality rows (a prefix
            // that does not yet reach every extra unknown): a larger prefix
            // may cure it, a few steps in a row at most (badly posed extra
            // unknowns would otherwise grow it to all of M for nothing).
            Err(BlockFailure::Singular) => {
                singular += 1;
                if singular > SINGULAR_STEPS {
                    break;
                }
            }
            // Not positive definite: the block iterations fall back; a
            // factor that cannot be allocated is reported by them.
            Err(BlockFailure::NotPositiveDefinite | BlockFailure::Allocation(_)) => break,
        }
        next = grown;
    }
    active
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::{BorderedLcpRef, MixedBorder};
    use faer::{Col, Mat};

    /// A contact-shaped problem on a 2-D grid of `side^2` points, spacing h:
    /// M the Boussinesq kernel h / (pi r) off the diagonal and a uniformly
    /// loaded square's 4 ln(1 + sqrt 2) / pi at its centre on it (the
    /// paper's own discretization, in units of the compliance), q the parabolic
    /// separation |x|^2 / 2, one free approach and the load row sum z = P:
    /// `M`, the border (ones) and `q`.
    fn contact(side: usize) -> (Mat<f64>, Mat<f64>, Col<f64>) {
        let n = side * side;
        let x = |i: usize| {
            let h = 2.0 / (side - 1) as f64;
            (-1.0 + h * (i % side) as f64, -1.0 + h * (i / side) as f64)
        };
        let m = Mat::from_fn(n, n, |i, j| {
            let ((a, b), (c, d)) = (x(i), x(j));
            let h = 2.0 / (side - 1) as f64;
            if i == j {
                4.0 * (1.0 + 2f64.sqrt()).ln() / std::f64::consts::PI
            } else {
                h / (std::f64::consts::PI * (a - c).hypot(b - d))
            }
        });
        let q = Col::from_fn(n, |i| {
            let (a, b) = x(i);
            (a * a + b * b) / 2.0
        });
        (m, Mat::from_fn(n, 1, |_, _| 1.0), q)
    }

    #[test]
    fn prefix_search_stops_just_past_the_contact_set() {
        let side = 31;
        let load = 4.0;
        let (m, border, q) = contact(side);
        let resultant = Col::from_fn(1, |_| load);
        let bordered = BorderedLcpRef::new(m.as_ref(), q.as_ref())
            .unwrap()
            .with_border(border.as_ref(), resultant.as_ref())
            .unwrap();
        let parts = MixedBorder::of(&bordered);
        let problem = Problem::bordered(&bordered, &parts);
        let p = problem.mixed;
        let opts = Options::default();
        let n = p.size();
        let key: Vec<f64> = (0..n).map(|i| p.q[i]).collect();
        let mut factor = Factor::new(n);
        let mut work = Work::default();
        let prefix = prefix_search(&p, &key, &mut factor, &opts.tolerances, Par::Seq, &mut work);
        let solution = attempt(&problem, &opts).unwrap();
        let contact: Vec<usize> = (0..n).filter(|&i| solution.basic[i]).collect();
        let size = prefix.iter().filter(|&&a| a).count();
        // Several growth steps were taken, and the prefix holds the
        // contact set and ends within one growth step past it.
        assert!(work.factorizations > 3, "{} steps", work.factorizations);
        assert!(contact.len() > 2 * PREFIX_STEP && contact.len() < n / 2);
        assert!(contact.iter().all(|&i| prefix[i]));
        let bound = (contact.len() as f64 * PREFIX_GROWTH) as usize + PREFIX_STEP;
        assert!(size <= bound, "prefix {size}, contact {}", contact.len());
        // The prefix is one: every index in it has a key no larger than
        // every index outside.
        let inside = (0..n).filter(|&i| prefix[i]).map(|i| key[i]);
        let outside = (0..n).filter(|&i| !prefix[i]).map(|i| key[i]);
        assert!(inside.fold(f64::MIN, f64::max) <= outside.fold(f64::MAX, f64::min));
    }
}
