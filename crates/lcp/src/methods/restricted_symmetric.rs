//! The restricted-entry simplex (Wolfe 1959; Conry & Seireg's Fig. 2, see
//! the general tableau's form in `restricted_general`) on the symmetric
//! tableau (`crate::tableau::swept`), for a border of one row (the contact
//! problem's approach and load) with a symmetric `M` and no initial
//! interference.
//!
//! The contact form is `w = M z + q + b α`, `c^T z = P`, `c = -κ b`,
//! `b <= 0`, `q >= 0`. The general simplex starts with every gap basic
//! and the load row's artificial `Z = P - c^T z`, enters the approach `α`
//! (to the first contact), then minimizes `Z`. Each of its bases in phase 1
//! is then of one family: an active set `J` (`z_J` basic) and one index
//! `s` outside it, the pin, whose zero gap fixes `α` (`w_s` non-basic, `α`
//! basic in its row); every other gap is basic. Its tableau is the swept
//! matrix `A` of `J` (see `crate::tableau::swept`) after one more pivot, of `α`
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
//!   first under the perturbation `q + ε g` of the symmetric tableau, in place of
//!   the general tableau's lexicographic rule on `B^{-1}`, which this form
//!   does not keep.
//!
//! The final basic solution on the active set is computed from the data. A
//! candidate list that runs out, a pivot that is not positive definite (`M`
//! not, where the path goes), a run of zero steps longer than `2 n + 10`, a
//! step that is not finite, or a final set that does not solve the problem
//! are breakdowns (the strategy then runs the general tableau, whose errors
//! say what is wrong).
//!
//! A border of several rows (tilts) has no such one-pin family of bases:
//! the restricted-entry simplex solves it on the general tableau.
//! Equilibration differs from the general tableau's (exact powers of two
//! here, Ruiz passes there), so Dantzig's choice, and the path, can differ
//! where two reduced costs are close; the answer does not, for a positive
//! definite `M`.

use faer::Col;

use crate::LcpError;
use crate::methods::{Attempted, Failure, NotApplicable, finish_on_active_set, symmetric_path};
use crate::options::Options;
use crate::problem::Problem;
use crate::statistics::{Breakdown, Work};
use crate::tableau::swept::{self, Path, Start, Stop, Swept, ZeroRun};
use crate::tolerance::Tolerances;

/// Whether the restricted-entry simplex runs on the symmetric tableau: a
/// border of one row where Lemke's symmetric path applies, and `q >= 0`
/// (no row of the general simplex is negated, the load row's is its only
/// artificial).
pub(crate) fn applies(problem: &Problem<'_>) -> Result<(), NotApplicable> {
    let one_row = problem.border.is_some_and(|b| b.columns.ncols() == 1);
    if !one_row {
        return Err(NotApplicable::new(
            "the restricted-entry simplex runs on the symmetric tableau with a border of one row only; use the general tableau",
        ));
    }
    symmetric_path(problem)?;
    if problem.mixed.q.iter().any(|&q| q < 0.0) {
        return Err(NotApplicable::new(
            "the restricted-entry simplex on the symmetric tableau needs q >= 0 (no initial interference)",
        ));
    }
    Ok(())
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

/// The restricted-entry simplex on the symmetric tableau (see the module
/// documentation); on success, the final basic solution from the data.
pub(crate) fn attempt(problem: &Problem<'_>, opts: &Options) -> Attempted {
    if applies(problem).is_err() {
        return Err(Failure::new(Breakdown::NoStart, Work::default()));
    }
    let p = &problem.mixed;
    let start = match swept::start(p, opts, &Stop::Border, None) {
        Ok(start) => start,
        Err(failed) => {
            let (e, work) = *failed;
            return Err(Failure::error(e, work));
        }
    };
    let order = start.order.clone();
    let mut simplex = match Pinned::new(start, opts) {
        Ok(simplex) => simplex,
        Err(work) => return Err(Failure::new(Breakdown::NoStart, work)),
    };
    if let Err(breakdown) = simplex.run() {
        return Err(Failure::new(breakdown, simplex.work));
    }
    finish_on_active_set(problem, opts, &order, &simplex.path.into, simplex.work)
}

/// The simplex's state on the pinned tableau.
struct Pinned {
    tab: Swept,
    path: Path,
    /// The scaled `M`'s diagonal (the scale of a pivot's test), and the
    /// swept diagonal, kept through the pivots.
    diagonal: Vec<f64>,
    diag: Vec<f64>,
    /// The load row's weights on the scaled `z` and the load, scaled.
    weight: Vec<f64>,
    load: f64,
    /// `c = -κ b` (scaled alike, so also `D c = -κ D b`).
    kappa: f64,
    /// The position whose zero gap fixes the approach.
    pin: usize,
    work: Work,
    tol: Tolerances,
    limit: usize,
    zero_run: ZeroRun,
    /// The reduced costs' tolerance, from their scale at the start of phase 1.
    cost_tol: Option<f64>,
    /// Per iteration: the entering column's rates, and each falling
    /// value's step to zero (the values themselves are read from the
    /// path's state where a step needs them).
    rates: Vec<f64>,
    reach: Vec<f64>,
    /// The positions whose steps were within the tie bound of the least so
    /// far when the ratio test reached them (a superset of the final ties,
    /// in increasing position).
    near: Vec<usize>,
    /// Candidates found inadmissible at this pivot.
    rejected: Vec<Entering>,
}

/// The pin's column and what one pass over the values gives, per iteration.
struct PinState {
    /// The pin and its column of `A`.
    s: usize,
    cs: Col<f64>,
    /// `1 / b̄_s`.
    inv_bs: f64,
    /// The approach `α` and its ε coefficient under the perturbation.
    alpha: f64,
    alpha_g: f64,
    /// Zero levels of the forces (on `J`) and the gaps (off it).
    zzero: f64,
    wzero: f64,
    /// The load still to carry (the artificial `Z = P - L`) and its ε coefficient.
    excess: f64,
    excess_g: f64,
    /// The load's slope over `b̄_s`, and the release's reduced cost.
    lift: f64,
    release: f64,
    /// The reduced costs' tolerance.
    ctol: f64,
}

/// A pivot chosen by the rule.
struct Chosen {
    entering: Entering,
    leaving: Leaving,
    theta: f64,
    /// The entering column of `A`, when it was read (not the pin's).
    read: Option<Col<f64>>,
}

impl Pinned {
    /// The state after the approach entered (the first contact, ties to the
    /// first under the perturbation); `Err` (the work) when nothing ever
    /// touches, for the general tableau to report.
    fn new(start: Start, opts: &Options) -> Result<Self, Work> {
        let Start {
            tab,
            diagonal,
            path,
            weight,
            load,
            mut work,
            ..
        } = start;
        let n = path.qbar.len();
        let tol = opts.tolerances;
        // κ read where b is largest (no squares: b may be near the overflow
        // threshold).
        let largest = (0..n).max_by(|&i, &j| path.bbar[i].abs().total_cmp(&path.bbar[j].abs()));
        let Some(kappa) = largest.map(|t| weight[t] / -path.bbar[t]) else {
            return Err(work);
        };
        let touch = |t: usize| path.qbar[t].max(0.0) / -path.bbar[t];
        let falling = || (0..n).filter(|&t| path.bbar[t] < 0.0);
        let first = falling().map(touch).fold(f64::INFINITY, f64::min);
        let tied = first + tol.tie * first;
        let Some(pin) = first_under_perturbation(falling().filter(|&t| touch(t) <= tied), |t| {
            path.gbar[t] / -path.bbar[t]
        }) else {
            return Err(work);
        };
        work.pivots = 1;
        if first == 0.0 {
            work.degenerate_pivots += 1;
        }
        Ok(Self {
            tab,
            diag: diagonal.clone(),
            diagonal,
            path,
            weight,
            load: load[0],
            kappa,
            pin,
            work,
            tol,
            limit: opts.pivot_limit(n + 1, 2 * n + 1),
            zero_run: ZeroRun::new(n),
            cost_tol: None,
            rates: vec![0.0; n],
            reach: vec![0.0; n],
            near: Vec::new(),
            rejected: Vec::new(),
        })
    }

    /// Phase 1, to its end.
    fn run(&mut self) -> Result<(), Breakdown> {
        loop {
            crate::cancel::check()?;
            let Some(state) = self.state()? else {
                return Ok(());
            };
            let chosen = self.choose(&state)?;
            if self.apply(&state, chosen)? {
                return Ok(());
            }
        }
    }

    /// The pin's column and one pass over the values: the values and their
    /// ε coefficients, the load on `J` and its slope with α (the artificial
    /// is `Z = P - L`), and the zero tests' scales (the largest term on `J`
    /// and off it). `None` when the artificial is at zero: phase 1 ends.
    fn state(&mut self) -> Result<Option<PinState>, Breakdown> {
        let n = self.rates.len();
        let tol = self.tol;
        let s = self.pin;
        let cs = self.tab.column(s);
        let inv_bs = 1.0 / self.path.bbar[s];
        let alpha = -self.path.qbar[s] * inv_bs;
        // α's coefficient of ε under the perturbation.
        let alpha_g = -self.path.gbar[s] * inv_bs;
        if !(alpha.is_finite() && alpha_g.is_finite()) {
            return Err(Breakdown::NonFinite);
        }
        let (path, weight) = (&self.path, &self.weight);
        // (The values themselves are not kept: the ratio test recomputes
        // the falling ones, by the same expression.)
        let [carried, carried_g, slope, zscale, wscale] = in_lanes(
            n,
            #[inline(always)]
            |i, lane| {
                let (q, b) = (path.qbar[i], path.bbar[i]);
                let size = q.abs() + (alpha * b).abs();
                if path.into[i] {
                    let (x, e) = (q + alpha * b, path.gbar[i] + alpha_g * b);
                    let w = weight[i];
                    lane[0] -= w * x;
                    lane[1] -= w * e;
                    lane[2] -= w * b;
                    lane[3] = if size > lane[3] { size } else { lane[3] };
                } else {
                    lane[4] = if size > lane[4] { size } else { lane[4] };
                }
            },
        );
        let excess = self.load - carried;
        if excess <= tol.zero * self.load {
            // The artificial is at zero, basic or not: phase 1 ends (as the
            // general simplex's does), the pin's force and gap both zero.
            return Ok(None);
        }
        let lift = slope * inv_bs;
        let release = -lift;
        let kappa = self.kappa;
        let ctol = *self.cost_tol.get_or_insert_with(|| {
            let scale = (0..n).fold(release.abs(), |a, j| {
                a.max((kappa * path.bbar[j] + lift * cs[j]).abs())
            });
            tol.cost * scale.max(f64::MIN_POSITIVE)
        });
        Ok(Some(PinState {
            s,
            cs,
            inv_bs,
            alpha,
            alpha_g,
            zzero: tol.zero * zscale,
            wzero: tol.zero * wscale,
            excess,
            excess_g: -carried_g,
            lift,
            release,
            ctol,
        }))
    }

    /// The admissible candidate of most negative reduced cost (ties to the
    /// lowest position, the release last) not yet rejected at this pivot; a
    /// restricted entry's complement must fall, tested only for a candidate
    /// that would be the best so far.
    fn best_candidate(&self, st: &PinState) -> Option<(Entering, f64)> {
        let n = self.rates.len();
        let (mut best_d, mut best_j) = (-st.ctol, usize::MAX);
        for j in 0..n {
            let d = self.kappa * self.path.bbar[j] + st.lift * st.cs[j];
            if !(d < best_d) {
                continue;
            }
            if j != st.s {
                let rho = self.diag[j] - self.path.bbar[j] * st.cs[j] * st.inv_bs;
                let falls = if self.path.into[j] {
                    rho * self.diagonal[j] > self.tol.pivot
                } else {
                    rho < -self.tol.pivot * self.diagonal[j]
                };
                if !falls {
                    continue;
                }
            }
            if self.rejected.is_empty() || !self.rejected.contains(&Entering::Index(j)) {
                (best_d, best_j) = (d, j);
            }
        }
        let mut best = (best_j != usize::MAX).then_some((Entering::Index(best_j), best_d));
        if st.release < -st.ctol
            && best.is_none_or(|(_, e)| st.release < e)
            && !self.rejected.contains(&Entering::Release)
        {
            best = Some((Entering::Release, st.release));
        }
        best
    }

    /// The pivot of the rule: candidates in order of reduced cost until one
    /// is admissible. No admissible candidate left is a breakdown (the
    /// general tableau's zero-cost moves, or its report of an infeasible
    /// problem, take over).
    fn choose(&mut self, st: &PinState) -> Result<Chosen, Breakdown> {
        self.rejected.clear();
        loop {
            let Some((entering, d)) = self.best_candidate(st) else {
                return Err(Breakdown::NoCandidate);
            };
            self.rejected.push(entering);
            if let Some(chosen) = self.ratio_test(st, entering, d) {
                return Ok(chosen);
            }
        }
    }

    /// The ratio test of `entering` (reduced cost `d`): its column's rates
    /// (column j of `A`, read unless it is the pin's), each falling value's
    /// step to zero, the load row's last. `None` when the entry is not
    /// admissible (its complement does not leave) or nothing limits it.
    fn ratio_test(&mut self, st: &PinState, entering: Entering, d: f64) -> Option<Chosen> {
        let s = st.s;
        let (read, f) = match entering {
            Entering::Index(j) => ((j != s).then(|| self.tab.column(j)), st.cs[j] * st.inv_bs),
            Entering::Release => (None, -st.inv_bs),
        };
        let column = match entering {
            Entering::Index(j) if j == s => Some(&st.cs),
            _ => read.as_ref(),
        };
        let values = Values {
            qbar: &self.path.qbar,
            bbar: &self.path.bbar,
            into: &self.path.into,
            alpha: st.alpha,
            zero: [st.zzero, st.wzero],
        };
        let rule = Rates {
            column: column.map(|c| c.try_as_col_major().expect("contiguous").as_slice()),
            f,
            s,
            tol: self.tol,
        };
        let mut least = rule.steps(&values, &mut self.rates, &mut self.reach, &mut self.near);
        let to_load = st.excess / -d;
        least = least.min(to_load);
        if !least.is_finite() {
            return None;
        }
        let leaving = self.leaving(st, entering, d, least, to_load)?;
        Some(Chosen {
            entering,
            leaving,
            theta: least,
            read,
        })
    }

    /// Among the values whose steps tie the least: a restricted entry's
    /// complement when among them (else that entry is not admissible),
    /// otherwise the first under the perturbation, then the lowest position
    /// (the load row at position n).
    fn leaving(
        &self,
        st: &PinState,
        entering: Entering,
        d: f64,
        least: f64,
        to_load: f64,
    ) -> Option<Leaving> {
        let n = self.rates.len();
        let tied = least + self.tol.tie * least.abs();
        match entering {
            Entering::Index(j) if j != st.s => (self.reach[j] <= tied).then_some(Leaving::Value(j)),
            _ => {
                let tied = self
                    .near
                    .iter()
                    .copied()
                    .chain(std::iter::once(n))
                    .filter(|&i| if i == n { to_load } else { self.reach[i] } <= tied);
                let key = |i: usize| {
                    if i == n {
                        st.excess_g / -d
                    } else {
                        // The value's ε coefficient, as the state's pass
                        // forms it.
                        let e = self.path.gbar[i] + st.alpha_g * self.path.bbar[i];
                        let e = if self.path.into[i] { -e } else { e };
                        e / -self.rates[i]
                    }
                };
                match first_under_perturbation(tied, key)? {
                    i if i == n => Some(Leaving::Load),
                    i => Some(Leaving::Value(i)),
                }
            }
        }
    }

    /// The principal pivot on `p` (column `c` of `A`), tested against the
    /// scaled diagonal, with the swept diagonal kept. `false` (nothing
    /// changed) when the pivot is not that of a positive definite block.
    fn sweep(&mut self, p: usize, c: &Col<f64>, joins: bool) -> bool {
        if !swept::definite_pivot(c[p], self.diagonal[p], joins, &self.tol) {
            return false;
        }
        let a = c[p];
        self.tab.pivot(p, c, joins);
        self.path.sweep(p, c, joins);
        let inv = 1.0 / a;
        for (v, &ci) in self.diag.iter_mut().zip(c.iter()) {
            *v -= ci * ci * inv;
        }
        self.diag[p] = -inv;
        true
    }

    /// Makes the chosen pivot: one or two sweeps, and the new pin. `true`
    /// when the load row's artificial left (phase 1 ends).
    fn apply(&mut self, st: &PinState, chosen: Chosen) -> Result<bool, Breakdown> {
        let Chosen {
            entering,
            leaving,
            theta,
            read,
        } = chosen;
        let s = st.s;
        if self.work.pivots >= self.limit {
            return Err(Breakdown::Error(Box::new(LcpError::PivotLimit {
                size: self.rates.len() + 1,
                limit: self.limit,
            })));
        }
        if !theta.is_finite() {
            return Err(Breakdown::NonFinite);
        }
        let after = match (entering, read) {
            (Entering::Index(j), Some(c)) if j != s => {
                // A restricted entry: its complement leaves, j joins or leaves J.
                let joins = !self.path.into[j];
                self.sweep(j, &c, joins).then_some(None)
            }
            // z_s enters: s joins J, then as a release.
            (Entering::Index(_), _) => self.sweep(s, &st.cs, true).then_some(Some(leaving)),
            (Entering::Release, _) => Some(Some(leaving)),
        };
        let Some(after) = after else {
            return Err(Breakdown::NotPositiveDefinite);
        };
        // (A pivot that breaks down is not counted; the sweep out below is
        // the second half of one that was.)
        if theta == 0.0 {
            self.work.degenerate_pivots += 1;
        }
        if !self.zero_run.record(theta == 0.0) {
            return Err(Breakdown::DegenerateRun);
        }
        self.work.pivots += 1;
        match after {
            None => Ok(false),
            Some(Leaving::Load) => Ok(true),
            Some(Leaving::Value(i)) => {
                if self.path.into[i] {
                    // z_i leaves: i leaves J, and pins α.
                    let c = self.tab.column(i);
                    if !self.sweep(i, &c, false) {
                        return Err(Breakdown::NotPositiveDefinite);
                    }
                }
                self.pin = i;
                Ok(false)
            }
        }
    }
}

/// The basic values at the pin's approach: `x_i = σ_i (q̄_i + α b̄_i)`,
/// and their zero levels on `J` and off it.
struct Values<'a> {
    /// The path's `q̄`, `b̄` (its one column) and active set.
    qbar: &'a [f64],
    bbar: &'a [f64],
    into: &'a [bool],
    alpha: f64,
    zero: [f64; 2],
}

impl Values<'_> {
    /// The value at position `i` and its zero level.
    #[inline(always)]
    fn at(&self, i: usize) -> (f64, f64) {
        let x = self.qbar[i] + self.alpha * self.bbar[i];
        if self.into[i] {
            (-x, self.zero[0])
        } else {
            (x, self.zero[1])
        }
    }
}

/// The entering column's rates: `σ_i (a_i - b̄_i f)` with `a` the column
/// of `A` (none for the release, whose column is `b̄ / b̄_s`), `f` its
/// entry in the pin's row over `b̄_s`, and 0 at the pin `s`.
struct Rates<'a> {
    column: Option<&'a [f64]>,
    f: f64,
    s: usize,
    tol: Tolerances,
}

impl Rates<'_> {
    /// The rate at position `i`, before its sign `σ_i`.
    #[inline(always)]
    fn unsigned(&self, values: &Values<'_>, i: usize) -> f64 {
        let a = self.column.map_or(0.0, |c| c[i]);
        let r = a - values.bbar[i] * self.f;
        if i == self.s { 0.0 } else { r }
    }

    /// The rates into `rates`, each falling value's step to zero into
    /// `reach` (infinite when it does not fall), the positions within the
    /// tie bound of the least so far into `near`; returns the least step.
    /// A value falls when its rate is below `-pivot` times the largest
    /// rate of its kind (forces and gaps have their own units), which one
    /// pass cannot know: it takes every negative rate, and a second pass
    /// redoes the steps when one of them is not below that bound.
    fn steps(
        &self,
        values: &Values<'_>,
        rates: &mut [f64],
        reach: &mut [f64],
        near: &mut Vec<usize>,
    ) -> f64 {
        let tie = self.tol.tie;
        // The largest rate and the slowest fall of each kind, in registers
        // (an array indexed by the kind would carry each position's
        // update to the next through memory).
        let (mut zlargest, mut wlargest) = (0.0f64, 0.0f64);
        let (mut zslowest, mut wslowest) = (f64::INFINITY, f64::INFINITY);
        let mut least = f64::INFINITY;
        near.clear();
        for i in 0..rates.len() {
            let on = values.into[i];
            let r = self.unsigned(values, i);
            let r = if on { -r } else { r };
            rates[i] = r;
            let a = r.abs();
            if on {
                zlargest = if a > zlargest { a } else { zlargest };
            } else {
                wlargest = if a > wlargest { a } else { wlargest };
            }
            reach[i] = if r < 0.0 {
                let fall = -r;
                if on {
                    zslowest = if fall < zslowest { fall } else { zslowest };
                } else {
                    wslowest = if fall < wslowest { fall } else { wslowest };
                }
                falling_step(values, i, r, tie, &mut least, near)
            } else {
                f64::INFINITY
            };
        }
        let small = [zlargest, wlargest].map(|v| self.tol.pivot * v);
        if zslowest > small[0] && wslowest > small[1] {
            least
        } else {
            falling_steps(values, small, tie, rates, reach, near)
        }
    }
}

/// Each value's step to zero at `rates` (infinite unless its rate is below
/// `-small` of its kind), the positions within the tie bound of the least
/// so far into `near` (steps are >= 0, so that bound only falls as the
/// least does, and holds every step that ties the final least); returns
/// the least step.
fn falling_steps(
    values: &Values<'_>,
    small: [f64; 2],
    tie: f64,
    rates: &[f64],
    reach: &mut [f64],
    near: &mut Vec<usize>,
) -> f64 {
    let mut least = f64::INFINITY;
    near.clear();
    for (i, (&r, step)) in rates.iter().zip(reach.iter_mut()).enumerate() {
        let small = small[usize::from(!values.into[i])];
        *step = if r < -small {
            falling_step(values, i, r, tie, &mut least, near)
        } else {
            f64::INFINITY
        };
    }
    least
}

/// Value `i`'s step to zero at its falling rate `r < 0` (0 when it is
/// already at zero), folded into the least step so far, `least`, and into
/// `near` when within the tie bound of it. (A plain comparison: a NaN step
/// is left out of `least` and caught by the caller, where no least step is
/// finite.)
#[inline(always)]
fn falling_step(
    values: &Values<'_>,
    i: usize,
    r: f64,
    tie: f64,
    least: &mut f64,
    near: &mut Vec<usize>,
) -> f64 {
    let (x, zero) = values.at(i);
    let theta = if x <= zero { 0.0 } else { x / -r };
    *least = if theta < *least { theta } else { *least };
    if theta <= *least + tie * least.abs() {
        near.push(i);
    }
    theta
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

#[cfg(test)]
mod tests;
