//! Lemke's method for a symmetric `M`, in its parametric principal-pivoting
//! form on the symmetric tableau (`crate::tableau::swept`).
//!
//! In the mixed form's sign (`b = -B`, the border's columns; `C = B^T` its
//! rows; `λ` the free unknowns) the path is
//!
//! ```text
//!     w = M z + q + b λ,   z >= 0, w >= 0, z^T w = 0
//!     one row:       λ (the approach) rises from the first contact until C z = P
//!     k rows:        C z = t P, t from 0 to 1, from the first contact (an LP, k rows)
//!     standard LCP:  b = -1 (the covering vector), λ = -z0 rises to 0
//! ```
//!
//! and the values are `x_i = σ_i (q̄_i + b̄_i λ)` on the swept data. Each
//! step moves `λ` along a direction `δ`: for one row or the standard LCP,
//! `δ = 1` (the path is parametrized by `λ` itself, Lemke's covering
//! variable); for k rows, `δ = G^{-1} (P - C z)` with `G = d(C z)/dλ =
//! C_J M_JJ^{-1} B_J` on the active set (k x k, positive definite for a
//! positive definite `M` and a border of full rank on `J`): the Newton step
//! to the resultants on this active set, so a step of 1 ends the path.
//!
//! The pivot rule: step to the first value reaching zero (a step of length
//! 0 when one at zero is falling), or to the end, whichever is first; ties
//! go to the first under the perturbation `q + ε g` of the tableau
//! (`ε`'s coefficient over the value's fall; with k rows, `λ` moves with
//! `ε` too, by `-G^{-1} dC z/dε`). The pivot is then on that value's index
//! (in or out of `J`). A run of zero steps longer than `2 n + 10`, a step
//! that is not finite, a pivot that is not that of a positive definite
//! block, a load that stops rising, a singular `G` and the pivot limit are
//! breakdowns. The final basic solution is computed from the original data
//! on the found active set (a Cholesky of `M_JJ` and the border's Schur
//! complement, refined).

use faer::{Col, Mat};

use crate::LcpError;
use crate::methods::{
    Answer, Attempted, Failure, NotApplicable, PathStart, finish_on_active_set, path_start,
    symmetric_path,
};
use crate::options::Options;
use crate::problem::Problem;
use crate::statistics::{Breakdown, Work};
use crate::tableau::swept::{Start, Stop, ZeroRun, definite_pivot, start};
use crate::tolerance::Tolerances;

/// Where the path applies (see [`symmetric_path`]).
pub(crate) fn applies(problem: &Problem<'_>) -> Result<Stop, NotApplicable> {
    symmetric_path(problem)
}

/// Lemke's path on the symmetric tableau (see the module documentation).
pub(crate) fn attempt(problem: &Problem<'_>, opts: &Options) -> Attempted {
    let stop = match applies(problem) {
        Ok(stop) => stop,
        Err(_) => return Err(Failure::new(Breakdown::NoStart, Work::default())),
    };
    let p = &problem.mixed;
    // A border starts from the approach when its first column is one, else
    // (several rows) from their first contact, an LP, ordered from it.
    let begin = match stop {
        Stop::Border => match path_start(problem, opts) {
            Some(begin) => Some(begin),
            None => return Err(Failure::new(Breakdown::NoStart, Work::default())),
        },
        Stop::Parameter => None,
    };
    let keys = match &begin {
        Some(PathStart::FirstContact(_, keys)) => Some(keys.as_slice()),
        _ => None,
    };
    let start = match start(p, opts, &stop, keys) {
        Ok(start) => start,
        Err(failed) => {
            let (e, work) = *failed;
            return Err(Failure::error(e, work));
        }
    };
    let mut walk = Walk::new(start, stop, opts);
    match &begin {
        Some(PathStart::FirstContact(contact, _)) => {
            walk.phase = Phase::Resultants;
            walk.enter_first_contact(&contact.basis, &contact.lambda)?;
        }
        None if walk.trivial() => {
            // A standard LCP with q >= 0: z = 0 solves it.
            let n = p.size();
            return Ok(Answer {
                z: Col::zeros(n),
                u: Col::zeros(0),
                basic: vec![false; n],
                work: walk.state.work,
            });
        }
        _ => {}
    }
    walk.run()?;
    let Start {
        order, path, work, ..
    } = walk.state;
    finish_on_active_set(problem, opts, &order, &path.into, work)
}

/// The two stretches of a bordered path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Along the approach (the first border column), the other free
    /// unknowns held, until the first resultant is met (the whole path of
    /// one row, and of a standard LCP).
    Approach,
    /// All free unknowns along the Newton direction to the resultants.
    Resultants,
}

/// The sums over the active set a step needs (k rows, k x k): the load
/// `L = C z`, the size of its terms, `G = dL/dλ` and `h = dL/dε`.
struct Sums {
    load: Vec<f64>,
    size: Vec<f64>,
    g: Mat<f64>,
    h: Vec<f64>,
}

impl Sums {
    fn new(k: usize) -> Self {
        Self {
            load: vec![0.0; k],
            size: vec![0.0; k],
            g: Mat::zeros(k, k),
            h: vec![0.0; k],
        }
    }

    fn clear(&mut self) {
        self.load.fill(0.0);
        self.size.fill(0.0);
        self.h.fill(0.0);
        self.g.fill(0.0);
    }
}

/// The walk along the path.
struct Walk {
    phase: Phase,
    /// The order, the tableau, the path's state, the border's weights,
    /// resultants and units, and the work: as [`start`] set them out, then
    /// as each pivot leaves them.
    state: Start,
    /// The free unknowns λ' (scaled: `λ_l = units_l λ'_l`).
    lambda: Vec<f64>,
    /// The direction of the step, `dλ / ds` (scaled), and `dλ / dε` at a
    /// fixed load (0 along the approach: `λ_1` is then the parameter).
    delta: Vec<f64>,
    gamma: Vec<f64>,
    sums: Sums,
    stop: Stop,
    tol: Tolerances,
    limit: usize,
    zero_run: ZeroRun,
    /// Per position: the values, their rates along the step, each falling
    /// value's step to zero.
    value: Vec<f64>,
    rate: Vec<f64>,
    reach: Vec<f64>,
    /// The zero tests' scales: the largest term `|q̄_i| + sum |λ_l b̄_il|`
    /// on and off the active set, and the largest rate on and off it
    /// (forces and gaps have their own units).
    scales: [f64; 4],
}

/// `a` or `v`, whichever is larger, by a plain comparison: it leaves a NaN
/// out as `f64::max` does, without its extra instructions on the critical
/// path of the pivot rule's passes.
#[inline(always)]
fn larger(a: f64, v: f64) -> f64 {
    if v > a { v } else { a }
}

/// The step at which a value `x` moving at rate `r` reaches zero: 0 at or
/// below its zero level, infinite when it does not fall (faster than the
/// rates' zero level). `zero` holds the zero tests' levels of values and of
/// rates, on and off the active set (`joined`): `[zscale, wscale, zrates,
/// wrates]` times the zero tolerance.
#[inline(always)]
fn reach(x: f64, r: f64, joined: bool, zero: &[f64; 4]) -> f64 {
    let (level, falls) = if joined {
        (zero[0], -zero[2])
    } else {
        (zero[1], -zero[3])
    };
    if r < falls {
        if x <= level { 0.0 } else { x / -r }
    } else {
        f64::INFINITY
    }
}

impl Walk {
    fn new(start: Start, stop: Stop, opts: &Options) -> Self {
        let n = start.order.len();
        let path = &start.path;
        // The approach's first contact, the least λ_1 at which some
        // w_i = q_i + b_i1 λ_1 is 0, the other free unknowns at 0 (a first
        // contact of k rows sets all of them from its LP instead).
        let alpha = (0..n)
            .filter(|&i| path.bbar[i] < 0.0)
            .map(|i| path.qbar[i] / -path.bbar[i])
            .fold(f64::INFINITY, f64::min);
        let k = path.columns();
        let mut delta = vec![0.0; k];
        delta[0] = 1.0;
        Self {
            phase: Phase::Approach,
            state: start,
            lambda: (0..k).map(|l| if l == 0 { alpha } else { 0.0 }).collect(),
            delta,
            gamma: vec![0.0; k],
            sums: Sums::new(k),
            stop,
            tol: opts.tolerances,
            limit: opts.pivot_limit(n, n),
            zero_run: ZeroRun::new(n),
            value: vec![0.0; n],
            rate: vec![0.0; n],
            reach: vec![0.0; n],
            scales: [0.0; 4],
        }
    }

    /// A standard LCP whose first contact is at or past the end (`q >= 0`).
    fn trivial(&self) -> bool {
        self.stop == Stop::Parameter && self.lambda[0] >= 0.0
    }

    fn n(&self) -> usize {
        self.state.order.len()
    }

    /// The first contact of k rows: `λ` from the LP (in scaled units), and
    /// its basis joins the active set (steps of length 0; the first is
    /// Lemke's first pivot, the rest are degenerate).
    fn enter_first_contact(&mut self, basis: &[usize], lambda: &[f64]) -> Result<(), Failure> {
        for (l, &v) in lambda.iter().enumerate() {
            self.lambda[l] = v / self.state.units[l];
        }
        let mut position = vec![0; self.n()];
        for (t, &i) in self.state.order.iter().enumerate() {
            position[i] = t;
        }
        for &i in basis {
            let t = position[i];
            if self.state.work.pivots > 0 {
                self.state.work.degenerate_pivots += 1;
            }
            self.pivot(t)?;
        }
        Ok(())
    }

    /// Walks until the end (see the module documentation).
    fn run(&mut self) -> Result<(), Failure> {
        loop {
            crate::cancel::check().map_err(|c| Failure::new(c.into(), self.state.work))?;
            let (to_stop, step) = if self.along_approach() {
                self.approach_pass()?
            } else {
                let to_stop = self.survey()?;
                (to_stop, self.steps())
            };
            if to_stop.is_nan() || (!step.is_finite() && !(to_stop < f64::INFINITY)) {
                // Nothing limits the path and it never reaches the end (a
                // ray), or the data's scale overflowed (a NaN load).
                let breakdown = if to_stop.is_nan() {
                    Breakdown::NonFinite
                } else {
                    Breakdown::Ray
                };
                return Err(Failure::new(breakdown, self.state.work));
            }
            if to_stop <= step {
                // The approach met the first resultant: with more rows, on
                // to the others (nothing to do when they are met too).
                if self.phase == Phase::Approach
                    && self.state.path.columns() > 1
                    && self.stop == Stop::Border
                {
                    self.lambda[0] += to_stop;
                    self.phase = Phase::Resultants;
                    continue;
                }
                return Ok(());
            }
            let pivot_on = self.first_tied(step)?;
            if step == 0.0 {
                // (The path starts at the first contact: its first pivot is
                // Lemke's first, not a step of length 0.)
                if self.state.work.pivots > 0 {
                    self.state.work.degenerate_pivots += 1;
                }
            } else {
                for (l, d) in self.lambda.iter_mut().zip(&self.delta) {
                    *l += step * d;
                }
            }
            if !self.zero_run.record(step == 0.0) {
                return Err(Failure::new(Breakdown::DegenerateRun, self.state.work));
            }
            if self.state.work.pivots >= self.limit {
                let error = LcpError::PivotLimit {
                    size: self.n(),
                    limit: self.limit,
                };
                return Err(Failure::error(error, self.state.work));
            }
            self.pivot(pivot_on)?;
        }
    }

    /// The principal pivot on position `t` (into `J` or out of it).
    fn pivot(&mut self, t: usize) -> Result<(), Failure> {
        let joins = !self.state.path.into[t];
        let c = self.state.tab.column(t);
        // (Scaled M: its diagonal, kept from the start.)
        if !definite_pivot(c[t], self.state.diagonal[t], joins, &self.tol) {
            return Err(Failure::new(
                Breakdown::NotPositiveDefinite,
                self.state.work,
            ));
        }
        self.state.tab.pivot(t, &c, joins);
        self.state.path.sweep(t, &c, joins);
        self.state.work.pivots += 1;
        Ok(())
    }

    /// Whether the step is along the approach (or a standard LCP's
    /// parameter): `λ_1` is then the path's parameter.
    fn along_approach(&self) -> bool {
        self.phase == Phase::Approach || self.stop == Stop::Parameter
    }

    /// A step along the approach (the one-row path's): one pass for the
    /// zero tests' scales, one for each falling value's step to zero and the
    /// first row's load on the active set and its slope; returns where the
    /// path ends along the approach and the least step. (Plain comparisons,
    /// as throughout the pivot rules' passes: they leave a NaN out as
    /// `f64::max` does, without its extra instructions on the loops'
    /// critical paths.)
    fn approach_pass(&mut self) -> Result<(f64, f64), Failure> {
        let n = self.n();
        let alpha = self.lambda[0];
        let path = &self.state.path;
        let (mut zscale, mut wscale, mut zrates, mut wrates) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for ((&q, &b), &joined) in path.qbar.iter().zip(&path.bbar[..n]).zip(&path.into) {
            let size = q.abs() + (alpha * b).abs();
            let (on, off) = if joined { (size, 0.0) } else { (0.0, size) };
            zscale = larger(zscale, on);
            wscale = larger(wscale, off);
            let (on, off) = if joined {
                (b.abs(), 0.0)
            } else {
                (0.0, b.abs())
            };
            zrates = larger(zrates, on);
            wrates = larger(wrates, off);
        }
        let zero = [zscale, wscale, zrates, wrates].map(|v| self.tol.zero * v);
        let (mut step, mut value, mut slope) = (f64::INFINITY, 0.0, 0.0);
        for i in 0..n {
            let joined = path.into[i];
            let sigma = if joined { -1.0 } else { 1.0 };
            let b = path.bbar[i];
            let (xi, ri) = (sigma * (path.qbar[i] + alpha * b), sigma * b);
            if joined && !self.state.weight.is_empty() {
                value += self.state.weight[i] * xi;
                slope += self.state.weight[i] * ri;
            }
            let s = reach(xi, ri, joined, &zero);
            self.reach[i] = s;
            step = if s < step { s } else { step };
        }
        let to_stop = match self.stop {
            Stop::Parameter => -alpha,
            Stop::Border if slope > 0.0 => (self.state.load[0] - value) / slope,
            // The load does not rise with the approach: M is not positive
            // definite on the contact set.
            Stop::Border if path.into.iter().any(|&j| j) => {
                return Err(Failure::new(
                    Breakdown::NotPositiveDefinite,
                    self.state.work,
                ));
            }
            Stop::Border => f64::INFINITY,
        };
        Ok((to_stop, step))
    }

    /// One pass over the values at the current `λ` for a Newton step: the
    /// values, the sums over the active set and the zero tests' scales;
    /// then the direction of the step, a second pass for its rates, and
    /// the step `s` at which the path ends along it.
    fn survey(&mut self) -> Result<f64, Failure> {
        let n = self.n();
        let k = self.state.path.columns();
        self.sums.clear();
        let (mut zscale, mut wscale) = (0.0f64, 0.0f64);
        let (path, sums, weight) = (&self.state.path, &mut self.sums, &self.state.weight);
        let (bbar, lambda) = (&path.bbar, &self.lambda);
        for i in 0..n {
            let joined = path.into[i];
            let sigma = if joined { -1.0 } else { 1.0 };
            let (part, terms) = (0..k).fold((0.0, 0.0), |(p, t), l| {
                let term = lambda[l] * bbar[l * n + i];
                (p + term, t + term.abs())
            });
            let x = sigma * (path.qbar[i] + part);
            self.value[i] = x;
            let size = path.qbar[i].abs() + terms;
            if !joined {
                wscale = larger(wscale, size);
                continue;
            }
            zscale = larger(zscale, size);
            for l in 0..k {
                let w = weight[l * n + i];
                sums.load[l] += w * x;
                sums.size[l] += (w * x).abs();
                sums.h[l] -= w * path.gbar[i];
                for m in 0..k {
                    sums.g[(l, m)] -= w * bbar[m * n + i];
                }
            }
        }
        (self.scales[0], self.scales[1]) = (zscale, wscale);
        let to_stop = self.direction()?;
        self.newton_rates();
        Ok(to_stop)
    }

    /// The Newton direction to the resultants from the sums (see the
    /// module documentation); the path ends at a step of 1 along it.
    fn direction(&mut self) -> Result<f64, Failure> {
        let k = self.state.path.columns();
        let rest: Vec<f64> = (0..k)
            .map(|l| self.state.load[l] - self.sums.load[l])
            .collect();
        let scale: Vec<f64> = (0..k)
            .map(|l| self.sums.size[l] + self.state.load[l].abs())
            .collect();
        if (0..k).all(|l| rest[l].abs() <= self.tol.zero * scale[l]) {
            // The resultants are met (to the zero tolerance of their terms).
            self.delta.fill(0.0);
            self.gamma.fill(0.0);
            return Ok(0.0);
        }
        let Some(solve) = symmetric_solver(&self.sums.g) else {
            return Err(Failure::new(Breakdown::SingularBorder, self.state.work));
        };
        self.delta = solve(&rest);
        self.gamma = solve(&self.sums.h).into_iter().map(|v| -v).collect();
        Ok(1.0)
    }

    /// The rates of a Newton step, `σ_i sum_l δ_l b̄_il`, and their scales.
    fn newton_rates(&mut self) {
        let n = self.n();
        let k = self.state.path.columns();
        let (mut zrates, mut wrates) = (0.0f64, 0.0f64);
        for i in 0..n {
            let sigma = if self.state.path.into[i] { -1.0 } else { 1.0 };
            let r = sigma
                * (0..k).fold(0.0, |a, l| {
                    a + self.delta[l] * self.state.path.bbar[l * n + i]
                });
            self.rate[i] = r;
            if self.state.path.into[i] {
                zrates = larger(zrates, r.abs());
            } else {
                wrates = larger(wrates, r.abs());
            }
        }
        (self.scales[2], self.scales[3]) = (zrates, wrates);
    }

    /// Each falling value's step to zero along the step's direction (0 at
    /// the zero level) into `reach`; returns the least.
    fn steps(&mut self) -> f64 {
        let zero = self.scales.map(|v| self.tol.zero * v);
        let mut least = f64::INFINITY;
        for i in 0..self.n() {
            let s = reach(self.value[i], self.rate[i], self.state.path.into[i], &zero);
            self.reach[i] = s;
            least = if s < least { s } else { least };
        }
        least
    }

    /// Among the values whose steps tie the least `step` (those at zero,
    /// when it is 0), the first to reach zero under the perturbation
    /// `q + ε g`: the least `ε`-coefficient over the value's fall.
    fn first_tied(&self, step: f64) -> Result<usize, Failure> {
        let n = self.n();
        let k = self.state.path.columns();
        let tied = step + self.tol.tie * step;
        let along_approach = self.along_approach();
        let key = |i: usize| {
            let sigma = if self.state.path.into[i] { -1.0 } else { 1.0 };
            if along_approach {
                return (sigma * self.state.path.gbar[i]).max(0.0)
                    / (-sigma * self.state.path.bbar[i]);
            }
            let e = (0..k).fold(self.state.path.gbar[i], |a, l| {
                a + self.state.path.bbar[l * n + i] * self.gamma[l]
            });
            (sigma * e).max(0.0) / -self.rate[i]
        };
        let first = (0..n)
            .filter(|&i| self.reach[i] <= tied)
            .map(|i| (i, key(i)))
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        // A step that is not finite (overflow, a NaN bound) is a breakdown.
        match (first, step.is_finite()) {
            (Some((i, _)), true) => Ok(i),
            _ => Err(Failure::new(Breakdown::NonFinite, self.state.work)),
        }
    }
}

/// A solver for the k x k system `G x = y`, `G` symmetrized (it is
/// symmetric up to rounding for a symmetric border), by a Cholesky factor;
/// `None` when `G` is not positive definite (the border is singular on the
/// active set).
fn symmetric_solver(g: &Mat<f64>) -> Option<impl Fn(&[f64]) -> Vec<f64>> {
    use faer::linalg::solvers::Solve;
    let k = g.nrows();
    let sym = Mat::from_fn(k, k, |i, j| 0.5 * (g[(i, j)] + g[(j, i)]));
    let llt = sym.llt(faer::Side::Lower).ok()?;
    let l = llt.L();
    let scale = (0..k).fold(0.0f64, |a, i| a.max(sym[(i, i)]));
    if (0..k)
        .any(|i| !(l[(i, i)] * l[(i, i)] > crate::tolerance::SINGULAR_PER_ROW * k as f64 * scale))
    {
        return None;
    }
    Some(move |y: &[f64]| {
        let x = llt.solve(Col::from_fn(k, |i| y[i]));
        x.iter().copied().collect()
    })
}
