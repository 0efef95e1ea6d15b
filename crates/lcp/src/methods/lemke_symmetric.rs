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
use crate::tableau::swept::{Path, Start, Stop, Swept, ZeroRun, definite_pivot, start};
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
    let start = start(p, opts, &stop, keys);
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
                work: walk.work,
            });
        }
        _ => {}
    }
    walk.run()?;
    let Walk {
        order, path, work, ..
    } = walk;
    finish_on_active_set(problem, opts, &order, &path.into, work)
}

/// The direction of a step and where it ends.
struct Direction {
    /// `dλ / ds` (scaled units).
    delta: Vec<f64>,
    /// `dλ / dε` at fixed load (0 for one row: `λ` is the parameter).
    gamma: Vec<f64>,
    /// The step `s` at which the path ends along `delta`.
    to_stop: f64,
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

/// The walk along the path.
struct Walk {
    phase: Phase,
    order: Vec<usize>,
    tab: Swept,
    diagonal: Vec<f64>,
    path: Path,
    /// Border weights (row-major k x n) and resultants, scaled.
    weight: Vec<f64>,
    load: Vec<f64>,
    /// The free unknowns λ' (scaled: `λ_l = units_l λ'_l`).
    lambda: Vec<f64>,
    units: Vec<f64>,
    stop: Stop,
    work: Work,
    tol: Tolerances,
    limit: usize,
    zero_run: ZeroRun,
    /// Scratch per position: the border's part of each value, each rate,
    /// the values, each value's step to zero.
    part: Vec<f64>,
    rate: Vec<f64>,
    value: Vec<f64>,
    reach: Vec<f64>,
}

impl Walk {
    fn new(start: Start, stop: Stop, opts: &Options) -> Self {
        let Start {
            order,
            tab,
            diagonal,
            path,
            weight,
            load,
            units,
            work,
        } = start;
        let n = order.len();
        // The approach's first contact, the least λ_1 at which some
        // w_i = q_i + b_i1 λ_1 is 0, the other free unknowns at 0 (a first
        // contact of k rows sets all of them from its LP instead).
        let alpha = (0..n)
            .filter(|&i| path.bbar[i] < 0.0)
            .map(|i| path.qbar[i] / -path.bbar[i])
            .fold(f64::INFINITY, f64::min);
        let k = path.columns();
        Self {
            phase: Phase::Approach,
            order,
            tab,
            diagonal,
            path,
            weight,
            load,
            lambda: (0..k).map(|l| if l == 0 { alpha } else { 0.0 }).collect(),
            units,
            stop,
            work,
            tol: opts.tolerances,
            limit: opts.pivot_limit(n, n),
            zero_run: ZeroRun::new(n),
            part: vec![0.0; n],
            rate: vec![0.0; n],
            value: vec![0.0; n],
            reach: vec![0.0; n],
        }
    }

    /// A standard LCP whose first contact is at or past the end (`q >= 0`).
    fn trivial(&self) -> bool {
        self.stop == Stop::Parameter && self.lambda[0] >= 0.0
    }

    fn n(&self) -> usize {
        self.order.len()
    }

    /// The first contact of k rows: `λ` from the LP (in scaled units), and
    /// its basis joins the active set (steps of length 0; the first is
    /// Lemke's first pivot, the rest are degenerate).
    fn enter_first_contact(&mut self, basis: &[usize], lambda: &[f64]) -> Result<(), Failure> {
        for (l, &v) in lambda.iter().enumerate() {
            self.lambda[l] = v / self.units[l];
        }
        let mut position = vec![0; self.n()];
        for (t, &i) in self.order.iter().enumerate() {
            position[i] = t;
        }
        for &i in basis {
            let t = position[i];
            if self.work.pivots > 0 {
                self.work.degenerate_pivots += 1;
            }
            self.pivot(t)?;
        }
        Ok(())
    }

    /// Walks until the end (see the module documentation).
    fn run(&mut self) -> Result<(), Failure> {
        loop {
            let direction = self.direction()?;
            let step = self.steps(&direction);
            if direction.to_stop.is_nan()
                || (!step.is_finite() && !(direction.to_stop < f64::INFINITY))
            {
                // Nothing limits the path and it never reaches the end (a
                // ray), or the data's scale overflowed (a NaN load).
                let breakdown = if direction.to_stop.is_nan() {
                    Breakdown::NonFinite
                } else {
                    Breakdown::Ray
                };
                return Err(Failure::new(breakdown, self.work));
            }
            if direction.to_stop <= step {
                // The approach met the first resultant: with more rows, on
                // to the others (nothing to do when they are met too).
                if self.phase == Phase::Approach
                    && self.path.columns() > 1
                    && self.stop == Stop::Border
                {
                    self.lambda[0] += direction.to_stop;
                    self.phase = Phase::Resultants;
                    continue;
                }
                return Ok(());
            }
            let pivot_on = self.first_tied(step, &direction)?;
            if step == 0.0 {
                // (The path starts at the first contact: its first pivot is
                // Lemke's first, not a step of length 0.)
                if self.work.pivots > 0 {
                    self.work.degenerate_pivots += 1;
                }
            } else {
                for (l, d) in self.lambda.iter_mut().zip(&direction.delta) {
                    *l += step * d;
                }
            }
            if !self.zero_run.record(step == 0.0) {
                return Err(Failure::new(Breakdown::DegenerateRun, self.work));
            }
            if self.work.pivots >= self.limit {
                let error = LcpError::PivotLimit {
                    size: self.n(),
                    limit: self.limit,
                };
                return Err(Failure::error(error, self.work));
            }
            self.pivot(pivot_on)?;
        }
    }

    /// The principal pivot on position `t` (into `J` or out of it).
    fn pivot(&mut self, t: usize) -> Result<(), Failure> {
        let joins = !self.path.into[t];
        let c = self.tab.column(t);
        // (Scaled M: its diagonal, kept from the start.)
        if !definite_pivot(c[t], self.diagonal[t], joins, &self.tol) {
            return Err(Failure::new(Breakdown::NotPositiveDefinite, self.work));
        }
        self.tab.pivot(t, &c, joins);
        self.path.sweep(t, &c, joins);
        self.work.pivots += 1;
        Ok(())
    }

    /// The values at the current `λ` (into `value`, the border's part into
    /// `part`), the load on the active set and its derivatives, and the
    /// direction of the next step.
    fn direction(&mut self) -> Result<Direction, Failure> {
        let n = self.n();
        let k = self.path.columns();
        self.path.combine(&self.lambda, &mut self.part);
        for i in 0..n {
            let sigma = if self.path.into[i] { -1.0 } else { 1.0 };
            self.value[i] = sigma * (self.path.qbar[i] + self.part[i]);
        }
        if self.stop == Stop::Parameter {
            return Ok(Direction {
                delta: vec![1.0],
                gamma: vec![0.0],
                to_stop: -self.lambda[0],
            });
        }
        // L = C z on J, G = dL/dλ, h = dL/dε, and the size of L's terms.
        let (mut load, mut g, mut h) = (vec![0.0; k], Mat::<f64>::zeros(k, k), vec![0.0; k]);
        let mut scale: Vec<f64> = self.load.iter().map(|v| v.abs()).collect();
        for i in (0..n).filter(|&i| self.path.into[i]) {
            for l in 0..k {
                let w = self.weight[l * n + i];
                load[l] += w * self.value[i];
                scale[l] += (w * self.value[i]).abs();
                h[l] -= w * self.path.gbar[i];
                for m in 0..k {
                    g[(l, m)] -= w * self.path.bbar_column(m)[i];
                }
            }
        }
        if self.phase == Phase::Approach {
            let slope = g[(0, 0)];
            let to_stop = if slope > 0.0 {
                (self.load[0] - load[0]) / slope
            } else if self.path.into.iter().any(|&j| j) {
                // The load does not rise with the approach: M is not
                // positive definite on the contact set.
                return Err(Failure::new(Breakdown::NotPositiveDefinite, self.work));
            } else {
                f64::INFINITY
            };
            let mut delta = vec![0.0; k];
            delta[0] = 1.0;
            return Ok(Direction {
                delta,
                gamma: vec![0.0; k],
                to_stop,
            });
        }
        let rest: Vec<f64> = (0..k).map(|l| self.load[l] - load[l]).collect();
        if (0..k).all(|l| rest[l].abs() <= self.tol.zero * scale[l]) {
            // The resultants are met (to the zero tolerance of their terms).
            return Ok(Direction {
                delta: vec![0.0; k],
                gamma: vec![0.0; k],
                to_stop: 0.0,
            });
        }
        let Some(solve) = symmetric_solver(&g) else {
            return Err(Failure::new(Breakdown::SingularBorder, self.work));
        };
        let delta = solve(&rest);
        let gamma = solve(&h).into_iter().map(|v| -v).collect();
        Ok(Direction {
            delta,
            gamma,
            to_stop: 1.0,
        })
    }

    /// Each falling value's step to zero along `direction` (0 at the zero
    /// level) into `reach`; returns the least.
    fn steps(&mut self, direction: &Direction) -> f64 {
        let n = self.n();
        let k = self.path.columns();
        self.path.combine(&direction.delta, &mut self.rate);
        // The zero tests' scales: the largest term |q̄_i| + Σ |λ_l b̄_il| on
        // and off the active set, and the largest rate on and off it
        // (forces and gaps have their own units). (Plain comparisons, as
        // throughout the pivot rules' passes: they leave a NaN out as
        // `f64::max` does, without its extra instructions on the loop's
        // critical path.)
        let larger = |a: f64, v: f64| if v > a { v } else { a };
        let (mut zscale, mut wscale, mut zrates, mut wrates) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            let sigma = if self.path.into[i] { -1.0 } else { 1.0 };
            self.rate[i] *= sigma;
            let terms = if k == 1 {
                self.part[i].abs()
            } else {
                (0..k).fold(0.0, |a, l| {
                    a + (self.lambda[l] * self.path.bbar_column(l)[i]).abs()
                })
            };
            let size = self.path.qbar[i].abs() + terms;
            if self.path.into[i] {
                zscale = larger(zscale, size);
                zrates = larger(zrates, self.rate[i].abs());
            } else {
                wscale = larger(wscale, size);
                wrates = larger(wrates, self.rate[i].abs());
            }
        }
        let [zscale, wscale, zrates, wrates] =
            [zscale, wscale, zrates, wrates].map(|v| self.tol.zero * v);
        let mut least = f64::INFINITY;
        for i in 0..n {
            let (xi, ri) = (self.value[i], self.rate[i]);
            let (zero, falls) = if self.path.into[i] {
                (zscale, -zrates)
            } else {
                (wscale, -wrates)
            };
            self.reach[i] = if ri < falls {
                let s = if xi <= zero { 0.0 } else { xi / -ri };
                least = if s < least { s } else { least };
                s
            } else {
                f64::INFINITY
            };
        }
        least
    }

    /// Among the values whose steps tie the least `step` (those at zero,
    /// when it is 0), the first to reach zero under the perturbation
    /// `q + ε g`: the least `ε`-coefficient over the value's fall.
    fn first_tied(&self, step: f64, direction: &Direction) -> Result<usize, Failure> {
        let n = self.n();
        let k = self.path.columns();
        let tied = step + self.tol.tie * step;
        let key = |i: usize| {
            let sigma = if self.path.into[i] { -1.0 } else { 1.0 };
            let moved = (0..k).fold(0.0, |a, l| {
                a + self.path.bbar_column(l)[i] * direction.gamma[l]
            });
            let e = if k == 1 {
                self.path.gbar[i]
            } else {
                self.path.gbar[i] + moved
            };
            (sigma * e).max(0.0) / -self.rate[i]
        };
        let first = (0..n)
            .filter(|&i| self.reach[i] <= tied)
            .map(|i| (i, key(i)))
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        // A step that is not finite (overflow, a NaN bound) is a breakdown.
        match (first, step.is_finite()) {
            (Some((i, _)), true) => Ok(i),
            _ => Err(Failure::new(Breakdown::NonFinite, self.work)),
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
