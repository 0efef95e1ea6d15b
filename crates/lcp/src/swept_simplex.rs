//! The restricted-entry simplex (Wolfe 1959; Conry & Seireg's Fig. 2, see
//! [`crate::restricted`]) on the symmetric tableau of [`crate::sweep`], for
//! the contact form with a symmetric `M` and no initial interference.
//!
//! The contact form is `w = M z + q + b α`, `c^T z = P`, `c = -κ b`,
//! `b <= 0`, `q >= 0`. The general simplex starts with every gap basic
//! and the load row's artificial `Z = P - c^T z`, enters the approach `α`
//! (to the first contact), then minimizes `Z`. Each of its bases in phase 1
//! is then of one family: an active set `J` (`z_J` basic) and one index
//! `s` outside it, the pin, whose zero gap fixes `α` (`w_s` non-basic, `α`
//! basic in its row); every other gap is basic. Its tableau is the swept
//! matrix `A` of `J` (see [`crate::sweep`]) after one more pivot, of `α`
//! into row `s`, which is never made: with `y_j` the non-basic `w_J` and
//! `z_K`, and `σ_i = -1` on `J`, `+1` off it,
//!
//! ```text
//!     x_i = σ_i (q̄_i + α b̄_i + Σ_j A_ij y_j),   α = (w_s - q̄_s - Σ_j A_sj y_j) / b̄_s
//!     d x_i / d y_j = σ_i (A_ij - b̄_i A_sj / b̄_s),   d x_i / d w_s = σ_i b̄_i / b̄_s
//! ```
//!
//! A column of the simplex's tableau is a column of `A` less `b̄` times an
//! entry of column `s`. As `c = -κ b` and `M` is symmetric, the swept load
//! row is `-κ b̄`, so the phase-1 reduced costs are, with
//! `λ = dL/dα = -Σ_J c_i b̄_i` the load's slope on `J`,
//!
//! ```text
//!     d_j = κ b̄_j + λ A_sj / b̄_s,     d_{w_s} = -λ / b̄_s
//! ```
//!
//! (`O(n)` a pivot from column `s`). The rule is the general one:
//! - the entering unknown is the admissible one of most negative reduced
//!   cost (below `-cost` times the largest at the start of phase 1);
//! - restricted entry: `z_k` (`k` off `J`, not the pin) may enter only if
//!   `w_k` leaves at that pivot, `w_j` (`j` on `J`) only if `z_j` does (it
//!   is then preferred in a tie). That complement must fall, which its
//!   pinned rate `±(A_kk - b̄_k A_sk / b̄_s)` says from the swept diagonal
//!   (kept) and column `s`: a candidate whose complement does not fall is
//!   rejected without reading its column;
//! - the pivots: `z_s` entering is a sweep of `s` into `J`; the leaving
//!   `z_i` sweeps `i` out and pins it, a leaving `w_k` pins `k`, and a
//!   leaving `Z` ends phase 1. `w_s` entering (a release of the pin) leaves
//!   the same ways without the first sweep. `z_k` entering is a sweep of
//!   `k` in, `w_j` entering a sweep of `j` out. Phase 1 also ends when `Z`
//!   reaches zero while basic (a tie it lost), as the general simplex's
//!   does, before any further pivot;
//! - ties in the ratio test (other than a restricted entry's) go to the
//!   first under the perturbation `q + ε g` of [`crate::sweep`], in place of
//!   the general tableau's lexicographic rule on `B^{-1}`, which this form
//!   does not keep.
//!
//! The final basic solution on the active set is computed from the data
//! ([`crate::sweep::finish`]). A candidate list that runs out, a pivot that
//! is not positive definite (`M` not, where the path goes), a run of zero
//! steps longer than `2 n + 10`, a step that is not finite, or a final set
//! that does not solve the problem are breakdowns: the general tableau then
//! solves it (`restricted::solve_mixed`), whose errors say what is wrong.
//! Equilibration differs from the general tableau's (exact powers of two
//! here, Ruiz passes there), so Dantzig's choice, and the path, can differ
//! where two reduced costs are close; the answer does not, for a positive
//! definite `M`.

use faer::Col;

use crate::Method;
use crate::problem::{MixedLcpRef, Options, RawSolution, Statistics};
use crate::sweep::{self, Path, Start, Stop, Swept};
use crate::tolerance::Tolerances;

/// Whether the restricted-entry simplex of `p` runs on the symmetric tableau:
/// the contact form of [`sweep::applies`] with `q >= 0` (no row of the
/// general simplex is negated, the load row's is its only artificial).
pub(crate) fn applies(p: &MixedLcpRef<'_>, opts: &Options) -> Option<f64> {
    match sweep::applies(p, opts) {
        Some(Stop::Load { load }) if p.q.iter().all(|&q| q >= 0.0) => Some(load),
        _ => None,
    }
}

/// An entering unknown of the pinned tableau.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Entering {
    /// The non-basic `y_j` at position `j`: `w_j` on the active set, `z_j`
    /// off it (`z_s` for the pin).
    Index(usize),
    /// `w_s`, the pin's gap.
    Release,
}

/// What leaves at a pivot.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Leaving {
    /// The basic value at position `i` (`z_i` on the active set, `w_i` off it).
    Value(usize),
    /// The load row's artificial `Z`: phase 1 ends.
    Load,
}

/// The principal pivot on `p` (column `c` of `A`), tested against the scaled
/// diagonal as in [`crate::sweep`], with the swept diagonal `diag` kept.
/// `false` (nothing changed) when the pivot is not that of a positive
/// definite block.
#[allow(clippy::too_many_arguments)]
fn sweep_on(
    tab: &mut Swept,
    path: &mut Path,
    diag: &mut [f64],
    diagonal: &[f64],
    p: usize,
    c: &Col<f64>,
    joins: bool,
    tol: &Tolerances,
) -> bool {
    if !sweep::definite_pivot(c[p], diagonal[p], joins, tol) {
        return false;
    }
    let a = c[p];
    tab.pivot(p, c, joins);
    path.sweep(p, c, joins);
    let inv = 1.0 / a;
    for (v, &ci) in diag.iter_mut().zip(c.iter()) {
        *v -= ci * ci * inv;
    }
    diag[p] = -inv;
    true
}

/// The restricted-entry simplex on the symmetric tableau, the load `load`;
/// on success, the final basic solution from the data. `Err` is the
/// attempt's statistics on a breakdown (see the module documentation).
pub(crate) fn solve(
    p: &MixedLcpRef<'_>,
    opts: &Options,
    load: f64,
) -> Result<RawSolution, Statistics> {
    let n = p.size();
    let tol = opts.tolerances;
    let Start {
        order,
        mut tab,
        diagonal,
        mut path,
        weight,
        load,
        mut stats,
    } = sweep::start(p, opts, Stop::Load { load }, Method::RestrictedSimplex);
    // c = -κ b (scaled alike, so also D c = -κ D b), read where b is
    // largest as `sweep::applies` does (no squares: b may be near the
    // overflow threshold).
    let largest = (0..n).max_by(|&i, &j| path.bbar[i].abs().total_cmp(&path.bbar[j].abs()));
    let Some(kappa) = largest.map(|t| weight[t] / -path.bbar[t]) else {
        return Err(stats);
    };
    // The approach enters: the first contact, ties to the first under the
    // perturbation. Nothing ever touching is for the general tableau to report.
    let touch = |t: usize| path.qbar[t].max(0.0) / -path.bbar[t];
    let falling = || (0..n).filter(|&t| path.bbar[t] < 0.0);
    let first = falling().map(touch).fold(f64::INFINITY, f64::min);
    let tied = first + tol.tie * first;
    let Some(mut pin) = first_under_perturbation(falling().filter(|&t| touch(t) <= tied), |t| {
        path.gbar[t] / -path.bbar[t]
    }) else {
        return Err(stats);
    };
    stats.pivots = 1;
    if first == 0.0 {
        stats.degenerate_pivots += 1;
    }
    let limit = opts.pivot_limit(n + 1, 2 * n + 1);
    let mut diag = diagonal.clone();
    let mut cost_tol = None;
    let mut zero_run = sweep::ZeroRun::new(n);
    // Per iteration: the basic values and their ε coefficients, the
    // entering column's rates, and each falling value's step to zero.
    let (mut xs, mut es) = (vec![0.0; n], vec![0.0; n]);
    let (mut rates, mut reach) = (vec![0.0; n], vec![0.0; n]);
    let mut rejected: Vec<Entering> = Vec::new();
    loop {
        let s = pin;
        let cs = tab.column(s);
        let bs = path.bbar[s];
        let inv_bs = 1.0 / bs;
        let alpha = -path.qbar[s] * inv_bs;
        // α's coefficient of ε under the perturbation.
        let alpha_g = -path.gbar[s] * inv_bs;
        if !(alpha.is_finite() && alpha_g.is_finite()) {
            return Err(stats);
        }
        // One pass: the values and their ε coefficients, the load on J and
        // its slope with α (the artificial is Z = P - L), and the zero
        // tests' scales (the largest term on J and off it).
        let [carried, carried_g, slope, zscale, wscale] = in_lanes(
            n,
            #[inline(always)]
            |i, lane| {
                let (q, b) = (path.qbar[i], path.bbar[i]);
                let (x, e) = (q + alpha * b, path.gbar[i] + alpha_g * b);
                let size = q.abs() + (alpha * b).abs();
                if path.into[i] {
                    (xs[i], es[i]) = (-x, -e);
                    let w = weight[i];
                    lane[0] -= w * x;
                    lane[1] -= w * e;
                    lane[2] -= w * b;
                    lane[3] = if size > lane[3] { size } else { lane[3] };
                } else {
                    (xs[i], es[i]) = (x, e);
                    lane[4] = if size > lane[4] { size } else { lane[4] };
                }
            },
        );
        let (zzero, wzero) = (tol.zero * zscale, tol.zero * wscale);
        let (excess, excess_g) = (load - carried, -carried_g);
        if excess <= tol.zero * load {
            // The artificial is at zero, basic or not: phase 1 ends (as the
            // general simplex's does), the pin's force and gap both zero.
            break;
        }
        let lift = slope * inv_bs;
        let release = -lift;
        let ctol = *cost_tol.get_or_insert_with(|| {
            let scale = (0..n).fold(release.abs(), |a, j| {
                a.max((kappa * path.bbar[j] + lift * cs[j]).abs())
            });
            tol.cost * scale.max(f64::MIN_POSITIVE)
        });
        rejected.clear();
        let chosen = loop {
            // The admissible candidate of most negative reduced cost (ties to
            // the lowest position, the release last); a restricted entry's
            // complement must fall, tested only for a candidate that would
            // be the best so far.
            let (mut best_d, mut best_j) = (-ctol, usize::MAX);
            for j in 0..n {
                let d = kappa * path.bbar[j] + lift * cs[j];
                if !(d < best_d) {
                    continue;
                }
                if j != s {
                    let rho = diag[j] - path.bbar[j] * cs[j] * inv_bs;
                    let falls = if path.into[j] {
                        rho * diagonal[j] > tol.pivot
                    } else {
                        rho < -tol.pivot * diagonal[j]
                    };
                    if !falls {
                        continue;
                    }
                }
                if rejected.is_empty() || !rejected.contains(&Entering::Index(j)) {
                    (best_d, best_j) = (d, j);
                }
            }
            let mut best = (best_j != usize::MAX).then_some((Entering::Index(best_j), best_d));
            if release < -ctol
                && best.is_none_or(|(_, e)| release < e)
                && !rejected.contains(&Entering::Release)
            {
                best = Some((Entering::Release, release));
            }
            // No admissible candidate left: the general tableau (its
            // zero-cost moves, or its report of an infeasible problem).
            let Some((entering, d)) = best else {
                return Err(stats);
            };
            rejected.push(entering);
            // The entering column's rates (column j of A, read unless it is
            // the pin's), and the largest of each kind (forces and gaps have
            // their own units), in one pass.
            let (read, f) = match entering {
                Entering::Index(j) => ((j != s).then(|| tab.column(j)), cs[j] * inv_bs),
                Entering::Release => (None, -inv_bs),
            };
            let column = match entering {
                Entering::Index(j) if j == s => Some(&cs),
                _ => read.as_ref(),
            };
            let [.., zmax, wmax] = in_lanes(
                n,
                #[inline(always)]
                |i, lane| {
                    // The release's column is b̄ / b̄_s: as a swept column of 0.
                    let a = column.map_or(0.0, |c| c[i]);
                    let r = a - path.bbar[i] * f;
                    let r = if i == s { 0.0 } else { r };
                    if path.into[i] {
                        rates[i] = -r;
                        lane[3] = if r.abs() > lane[3] { r.abs() } else { lane[3] };
                    } else {
                        rates[i] = r;
                        lane[4] = if r.abs() > lane[4] { r.abs() } else { lane[4] };
                    }
                },
            );
            let (zsmall, wsmall) = (tol.pivot * zmax, tol.pivot * wmax);
            // The ratio test: each falling value's step to zero, the load
            // row's (position n) last.
            let mut least = f64::INFINITY;
            for i in 0..n {
                let (zero, small) = if path.into[i] {
                    (zzero, zsmall)
                } else {
                    (wzero, wsmall)
                };
                let r = rates[i];
                reach[i] = if r < -small {
                    let theta = if xs[i] <= zero { 0.0 } else { xs[i] / -r };
                    // (A plain comparison: a NaN step is left out here and
                    // caught below, where no least step is finite.)
                    least = if theta < least { theta } else { least };
                    theta
                } else {
                    f64::INFINITY
                };
            }
            let to_load = excess / -d;
            least = least.min(to_load);
            if !least.is_finite() {
                continue;
            }
            // Ties: a restricted entry's complement when among them (else
            // that entry is not admissible), otherwise the first under the
            // perturbation, then the lowest position.
            let tied = least + tol.tie * least.abs();
            let leaving = match entering {
                Entering::Index(j) if j != s => {
                    if reach[j] <= tied {
                        Leaving::Value(j)
                    } else {
                        continue;
                    }
                }
                _ => {
                    // The load row at position n.
                    let tied = (0..=n).filter(|&i| if i == n { to_load } else { reach[i] } <= tied);
                    let key = |i: usize| {
                        if i == n {
                            excess_g / -d
                        } else {
                            es[i] / -rates[i]
                        }
                    };
                    match first_under_perturbation(tied, key) {
                        Some(i) if i == n => Leaving::Load,
                        Some(i) => Leaving::Value(i),
                        None => continue,
                    }
                }
            };
            break (entering, leaving, least, read);
        };
        let (entering, leaving, theta, read) = chosen;
        if stats.pivots >= limit || !theta.is_finite() {
            return Err(stats);
        }
        // The pivot: one or two sweeps, and the new pin.
        let mut sweep = |q: usize, c: &Col<f64>, joins: bool, path: &mut Path| {
            sweep_on(&mut tab, path, &mut diag, &diagonal, q, c, joins, &tol)
        };
        let after = match (entering, read) {
            (Entering::Index(j), Some(c)) if j != s => {
                // A restricted entry: its complement leaves, j joins or leaves J.
                let joins = !path.into[j];
                sweep(j, &c, joins, &mut path).then_some(None)
            }
            // z_s enters: s joins J, then as a release.
            (Entering::Index(_), _) => sweep(s, &cs, true, &mut path).then_some(Some(leaving)),
            (Entering::Release, _) => Some(Some(leaving)),
        };
        let Some(after) = after else {
            return Err(stats);
        };
        // (A pivot that breaks down is not counted; the sweep out below is
        // the second half of one that was.)
        if theta == 0.0 {
            stats.degenerate_pivots += 1;
        }
        if !zero_run.record(theta == 0.0) {
            return Err(stats);
        }
        stats.pivots += 1;
        match after {
            None => {}
            Some(Leaving::Load) => break,
            Some(Leaving::Value(i)) => {
                if path.into[i] {
                    // z_i leaves: i leaves J, and pins α.
                    let c = tab.column(i);
                    if !sweep_on(
                        &mut tab, &mut path, &mut diag, &diagonal, i, &c, false, &tol,
                    ) {
                        return Err(stats);
                    }
                }
                pin = i;
            }
        }
    }
    sweep::finish(p, opts, &order, &path.into, stats)
}

/// Five sums or maxima over `0..n`, each lane of four accumulating its own
/// (`body(i, lane)`; lanes start at 0): the additions and comparisons of
/// one index then do not wait on the previous one's. Returns the lanes'
/// sums for the first three and their maxima for the last two.
#[inline(always)]
fn in_lanes(n: usize, mut body: impl FnMut(usize, &mut [f64; 5])) -> [f64; 5] {
    let mut lanes = [[0.0f64; 5]; 4];
    let whole = n / 4 * 4;
    for base in (0..whole).step_by(4) {
        for (l, lane) in lanes.iter_mut().enumerate() {
            body(base + l, lane);
        }
    }
    for i in whole..n {
        body(i, &mut lanes[0]);
    }
    let sum = |k: usize| lanes.iter().map(|l| l[k]).sum::<f64>();
    let top = |k: usize| lanes.iter().map(|l| l[k]).fold(0.0, f64::max);
    [sum(0), sum(1), sum(2), top(3), top(4)]
}

/// Among the positions `tied` (those whose steps tie the least), the first
/// to reach zero under the perturbation: the least `key` (the ε coefficient
/// of the value over its fall), then the lowest position.
fn first_under_perturbation(
    tied: impl Iterator<Item = usize>,
    key: impl Fn(usize) -> f64,
) -> Option<usize> {
    tied.map(|i| (i, key(i)))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map(|(i, _)| i)
}
