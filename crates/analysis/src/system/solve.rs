//! The solve of a system: Newton's method on the border unknowns, every
//! zone's complementarity problem solved exactly at each step.
//!
//! The system's bordered problem is the optimality condition of a convex
//! program (the elastic energy with the separations as constraints), whose
//! dual in the bodies' free motions λ is concave and continuously
//! differentiable:
//!
//! ```text
//!     g(λ) = λ.b - 1/2 sum_z F_z^T S_z F_z,      grad g = b - sum_z T_z^T L_z^T F_z,
//! ```
//!
//! with `F_z(λ)` the zone's forces under the modes `m_z = T_z λ + t_z`
//! (each a complementarity problem under prescribed approach and tilts,
//! solved exactly by the engine, in parallel over the zones; and
//! `F^T S F = F^T (L m - eps)` by complementarity). Its Hessian is
//! `-sum_z T_z^T K_z T_z`, `K_z = L_J^T S_JJ^{-1} L_J` the zone's rigid
//! stiffness on its contact set J (one restricted solve per zone). The
//! iteration is Newton's with a Levenberg damping on motions that no
//! contact holds yet (an element out of contact, the first step of a
//! system with clearance) and a backtracking line search on g: it ascends
//! a concave function to its maximum, where the bodies are in equilibrium.
//! On a fixed contact set the forces are affine in λ, so once the sets
//! settle the step is exact and the residual falls to rounding.
//!
//! The certificate is computed from the original data: each zone's (from
//! its own S, eps and modes), and each free motion's equilibrium residual
//! `|sum_z (T_z^T R_z)_d - b_d|` over the scale of its terms.

use std::time::Instant;

use elcon_lcp::{Cancel, LcpError, Method, Options, Par};
use faer::{Mat, Side};
use rayon::prelude::*;

use super::System;
use crate::{AnalysisError, ContactProblem, ContactSolution, Loading};

/// How a system is solved.
#[derive(Debug, Clone)]
pub struct SystemSettings {
    /// The engine's method for every zone (`None`: each zone's default).
    pub method: Option<Method>,
    /// The engine's options for every zone.
    pub options: Options,
    /// The largest equilibrium residual accepted, relative to the scale of
    /// each free motion's terms.
    pub tolerance: f64,
    /// The most Newton steps.
    pub max_iterations: usize,
    /// A starting point for the free motions (in the order of
    /// [`System::free_motions`]; zeros when `None`): a neighbouring load's
    /// answer, or a simpler model's (a bearing's Hertz springs).
    pub initial: Option<Vec<f64>>,
}

impl Default for SystemSettings {
    fn default() -> Self {
        Self {
            method: None,
            options: Options::default(),
            tolerance: 1e-9,
            max_iterations: 100,
            initial: None,
        }
    }
}

/// The residuals of a system's solution, from the original data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SystemCertificate {
    /// The largest free motion's equilibrium residual over the scale of its
    /// terms (the applied load and every zone's share).
    pub equilibrium: f64,
    /// The worst zone's worst residual (its forces, gaps and
    /// complementarity; `crate::ContactCertificate::worst`).
    pub zones: f64,
    /// Which zone that is.
    pub worst_zone: usize,
    /// The tolerance the equilibrium is judged against (each zone is judged
    /// against its own).
    pub tolerance: f64,
    /// Whether every zone's certificate holds.
    pub zones_hold: bool,
}

impl SystemCertificate {
    /// Whether the equilibrium and every zone's certificate hold.
    pub fn holds(&self) -> bool {
        self.zones_hold && self.equilibrium <= self.tolerance
    }
}

/// A zone's answer in a system: its contact solution under the modes the
/// bodies gave it.
pub type ZoneSolution = ContactSolution;

/// A certified system solution.
#[derive(Debug, Clone)]
pub struct SystemSolution {
    /// Each zone's contact solution (its `approach`, `tilt_x`, `tilt_y` are
    /// the modes the bodies gave it; its `load`, `moment_x`, `moment_y`
    /// its resultant).
    pub zones: Vec<ZoneSolution>,
    /// The free motions at equilibrium (length or radians), in the order of
    /// [`System::free_motions`].
    pub motions: Vec<f64>,
    /// Every body's six motions (length or radians; fixed ones 0,
    /// prescribed ones as given), in the order of [`super::Motion::ALL`].
    pub displacements: Vec<[f64; 6]>,
    /// Residuals from the original data.
    pub certificate: SystemCertificate,
    /// Newton steps taken.
    pub iterations: usize,
    /// Zone solves made (every zone at every trial point).
    pub zone_solves: usize,
    /// Seconds spent solving.
    pub seconds: f64,
}

/// The system at one value of λ: every zone solved.
struct State {
    lambda: Vec<f64>,
    zones: Vec<ContactSolution>,
    /// `sum_z T_z^T R_z - b`.
    residual: Vec<f64>,
    /// The scale of each residual's terms, floored by the system's force
    /// (the largest load, applied or carried by a zone) times the motion's
    /// lever: a motion whose terms are all rounding (an unloaded roller's
    /// tilt) is measured on the system's scale, not its own.
    scale: Vec<f64>,
    /// `g(λ)`.
    value: f64,
}

impl State {
    /// The largest relative equilibrium residual.
    fn equilibrium(&self) -> f64 {
        self.residual
            .iter()
            .zip(&self.scale)
            .map(|(r, s)| if *s > 0.0 { r.abs() / s } else { r.abs() })
            .fold(0.0, f64::max)
    }
}

impl System {
    /// Solves the system: every body in equilibrium, every zone's contact
    /// conditions, certified.
    ///
    /// # Errors
    /// [`AnalysisError::SystemNotConverged`] when the Newton steps stop
    /// short of equilibrium (with the residual reached), and the zones'
    /// own errors ([`AnalysisError::Engine`]...), among them an interrupt:
    /// the calling thread's watched token (`elcon_lcp::Cancel::watch`) is
    /// polled between steps and by every zone's solve.
    pub fn solve(&self, settings: &SystemSettings) -> Result<SystemSolution, AnalysisError> {
        let start = Instant::now();
        let d = self.free.len();
        let lambda = match &settings.initial {
            Some(v) if v.len() != d => {
                return Err(AnalysisError::SizeMismatch {
                    field: "initial",
                    expected: d,
                    found: v.len(),
                });
            }
            Some(v) => v.clone(),
            None => vec![0.0; d],
        };
        let reference = &self.reference;
        let mut solves = 0;
        let mut state = self.evaluate(lambda, None, settings, &mut solves)?;
        let mut damping = 1e-4;
        let mut iterations = 0;
        while state.equilibrium() > settings.tolerance {
            if iterations == settings.max_iterations {
                return Err(AnalysisError::SystemNotConverged {
                    iterations,
                    residual: state.equilibrium(),
                });
            }
            if Cancel::requested() {
                return Err(AnalysisError::Engine(LcpError::Cancelled));
            }
            iterations += 1;
            let hessian = self.stiffness(&state, settings)?;
            let step = newton_step(&hessian, reference, &state.residual, damping)?;
            let (next, full) = self.line_search(&state, &step, settings, &mut solves)?;
            damping = if full {
                (damping * 0.1).max(1e-12)
            } else {
                (damping * 10.0).min(1e6)
            };
            state = next;
        }
        Ok(self.finish(state, settings, iterations, solves, start))
    }

    /// The zones solved at `lambda` (warm-started from `previous`), the
    /// equilibrium residual and the dual's value.
    fn evaluate(
        &self,
        lambda: Vec<f64>,
        previous: Option<&[ContactSolution]>,
        settings: &SystemSettings,
        solves: &mut usize,
    ) -> Result<State, AnalysisError> {
        let mut options = settings.options.clone();
        if self.zones.len() > 1 {
            // The zones run on the pool's threads; each alone.
            options.parallelism = Some(Par::Seq);
        }
        let modes: Vec<[f64; 3]> = self.maps.iter().map(|m| m.modes(&lambda)).collect();
        // The pool's threads watch the caller's token (an interrupt stops
        // every zone's solve).
        let token = Cancel::watched();
        let zones = (0..self.zones.len())
            .into_par_iter()
            .map(|z| {
                let solve = || {
                    let problem = &self.zones[z].problem;
                    let [alpha, tx, ty] = modes[z];
                    let loaded = problem
                        .with_loading(Loading::approach(alpha).with_tilt_x(tx).with_tilt_y(ty))?;
                    let method = settings.method.unwrap_or_else(|| problem.default_method());
                    match previous {
                        Some(p) => loaded.solve_from(&p[z], method, &options),
                        None => loaded.solve(method, &options),
                    }
                };
                match &token {
                    Some(t) => t.watch(solve),
                    None => solve(),
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        *solves += zones.len();
        let d = self.free.len();
        let mut residual: Vec<f64> = self.free.iter().map(|f| -f.load).collect();
        let mut scale: Vec<f64> = self.free.iter().map(|f| f.load.abs()).collect();
        let mut energy = 0.0;
        for ((sol, map), (m, zone)) in zones
            .iter()
            .zip(&self.maps)
            .zip(modes.iter().zip(&self.zones))
        {
            let resultant = [sol.load, sol.moment_x, sol.moment_y];
            for j in 0..d {
                for r in 0..3 {
                    residual[j] += map.t[(r, j)] * resultant[r];
                    scale[j] += (map.t[(r, j)] * resultant[r]).abs();
                }
            }
            let work: f64 = (0..3).map(|r| m[r] * resultant[r]).sum();
            let initial: f64 = sol
                .forces
                .iter()
                .zip(zone.problem.separation())
                .map(|(f, e)| f * e)
                .sum();
            energy += work - initial;
        }
        let force = zones
            .iter()
            .map(|z| z.load)
            .chain(self.free.iter().map(|f| f.load.abs()))
            .fold(0.0f64, f64::max);
        for (s, lever) in scale.iter_mut().zip(&self.levers) {
            *s = s.max(force * lever);
        }
        let value = lambda
            .iter()
            .zip(&self.free)
            .map(|(l, f)| l * f.load)
            .sum::<f64>()
            - 0.5 * energy;
        Ok(State {
            lambda,
            zones,
            residual,
            scale,
            value,
        })
    }

    /// `sum_z T_z^T K_z T_z`, `K_z = L_J^T S_JJ^{-1} L_J` on each zone's
    /// contact set J (zones out of contact add nothing).
    fn stiffness(
        &self,
        state: &State,
        settings: &SystemSettings,
    ) -> Result<Mat<f64>, AnalysisError> {
        let mut options = settings.options.clone();
        if self.zones.len() > 1 {
            options.parallelism = Some(Par::Seq);
        }
        let blocks = (0..self.zones.len())
            .into_par_iter()
            .map(|z| zone_stiffness(&self.zones[z].problem, &state.zones[z].contact, &options))
            .collect::<Result<Vec<_>, _>>()?;
        let d = self.free.len();
        let mut h = Mat::<f64>::zeros(d, d);
        for (k, map) in blocks.iter().zip(&self.maps) {
            if let Some(k) = k {
                h += map.t.transpose() * k * &map.t;
            }
        }
        Ok(h)
    }

    /// Backtracks along `step` until the dual rises enough (Armijo); the
    /// new state, and whether the whole step was taken.
    fn line_search(
        &self,
        state: &State,
        step: &[f64],
        settings: &SystemSettings,
        solves: &mut usize,
    ) -> Result<(State, bool), AnalysisError> {
        // The dual's slope along the step: grad g . step = -r . step.
        let slope: f64 = -state
            .residual
            .iter()
            .zip(step)
            .map(|(r, s)| r * s)
            .sum::<f64>();
        let mut s = 1.0;
        for _ in 0..40 {
            let lambda: Vec<f64> = state
                .lambda
                .iter()
                .zip(step)
                .map(|(l, d)| l + s * d)
                .collect();
            let next = self.evaluate(lambda, Some(&state.zones), settings, solves)?;
            let rise = next.value - state.value;
            // Rounding of g's terms: a step that changes nothing measurable
            // is taken when it lowers the residual.
            let noise = 1e-12 * (state.value.abs() + next.value.abs());
            if rise >= 1e-4 * s * slope - noise
                || next.equilibrium() < state.equilibrium() && rise >= -noise
            {
                return Ok((next, s == 1.0));
            }
            s *= 0.25;
        }
        Err(AnalysisError::SystemNotConverged {
            iterations: 0,
            residual: state.equilibrium(),
        })
    }

    /// The solution from the converged state.
    fn finish(
        &self,
        state: State,
        settings: &SystemSettings,
        iterations: usize,
        zone_solves: usize,
        start: Instant,
    ) -> SystemSolution {
        let (worst_zone, zones) = state
            .zones
            .iter()
            .map(|z| z.certificate.worst())
            .enumerate()
            .fold((0, 0.0f64), |a, (i, w)| if w > a.1 { (i, w) } else { a });
        let certificate = SystemCertificate {
            equilibrium: state.equilibrium(),
            zones,
            worst_zone,
            tolerance: settings.tolerance,
            zones_hold: state.zones.iter().all(|z| z.certificate.holds()),
        };
        let mut displacements: Vec<[f64; 6]> = self
            .bodies
            .iter()
            .map(|b| {
                b.dofs.map(|d| match d {
                    super::Dof::Prescribed { value } => value,
                    _ => 0.0,
                })
            })
            .collect();
        for (f, v) in self.free.iter().zip(&state.lambda) {
            displacements[f.body][f.motion.index()] = *v;
        }
        SystemSolution {
            zones: state.zones,
            motions: state.lambda,
            displacements,
            certificate,
            iterations,
            zone_solves,
            seconds: start.elapsed().as_secs_f64(),
        }
    }
}

/// A zone's 3 x 3 rigid stiffness `L_J^T S_JJ^{-1} L_J` on its contact set
/// `contact`, or `None` out of contact.
fn zone_stiffness(
    problem: &ContactProblem,
    contact: &[usize],
    options: &Options,
) -> Result<Option<Mat<f64>>, AnalysisError> {
    if contact.is_empty() {
        return Ok(None);
    }
    let points = problem.points();
    let levers = Mat::from_fn(contact.len(), 3, |i, r| {
        let k = contact[i];
        match r {
            0 => 1.0,
            1 => points.y(k),
            _ => -points.x(k),
        }
    });
    let x = problem
        .restricted_solve(contact, levers.as_ref(), options)?
        .x;
    Ok(Some(levers.transpose() * x))
}

/// The Newton step `(H + mu D) step = -r` in the motions scaled to a unit
/// reference stiffness (`D` the reference's diagonal), damped only where
/// H has no stiffness of its own: `step = -sum_i (q_i.r) q_i / (s_i + mu)`
/// over H's eigenpairs `(s_i, q_i)`, with `mu` zero on the well-held ones.
fn newton_step(
    hessian: &Mat<f64>,
    reference: &[f64],
    residual: &[f64],
    damping: f64,
) -> Result<Vec<f64>, AnalysisError> {
    let d = residual.len();
    let root: Vec<f64> = reference.iter().map(|v| v.sqrt()).collect();
    let scaled = Mat::from_fn(d, d, |i, j| hessian[(i, j)] / (root[i] * root[j]));
    let eigen =
        scaled
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| AnalysisError::SystemNotConverged {
                iterations: 0,
                residual: f64::NAN,
            })?;
    let (values, vectors) = (eigen.S(), eigen.U());
    let largest = (0..d).map(|i| values[i]).fold(0.0f64, f64::max);
    let mut step = vec![0.0; d];
    for i in 0..d {
        let q = vectors.col(i);
        let along: f64 = (0..d).map(|j| q[j] * residual[j] / root[j]).sum();
        let s = values[i].max(0.0);
        // Well held: Newton's step; held weakly or not at all: damped.
        let mu = if s > 1e-6 * largest { 0.0 } else { damping };
        let denominator = s + mu;
        if denominator > 0.0 {
            for j in 0..d {
                step[j] -= q[j] * along / denominator;
            }
        }
    }
    Ok(step.iter().zip(&root).map(|(s, r)| s / r).collect())
}
