//! Designs judged below the surface: the objective of a design as the
//! largest subsurface stress of the bodies with a field (the von Mises
//! stress or the largest shear, Tresca), and the descent's linear model of
//! it.
//!
//! A body's stress at q is linear in the contact pressures, each point's
//! stress influence coefficient `T_qk` (Love's rectangle, the point force
//! or the strip, with that body's Poisson's ratio: `elcon_influence`'s
//! kernels),
//!
//! ```text
//!     sigma_q = sum_k T_qk F_k / A_k,          case l's merit  max_q s(sigma_q) / r_l
//! ```
//!
//! with s the von Mises stress (convex in the tensor) or Tresca's. The
//! maximum is taken over a fixed set of points per case: every point of the
//! grid at each of [`DEPTHS`] depths down to [`DEPTH_SPAN`] of the case's
//! contact half-width at the descent's start (the depth layers by FFT on a
//! lattice, direct sums elsewhere). The descent's model rows are the
//! linearizations at candidate points q (each axial station's largest,
//! and the points above and below it),
//!
//! ```text
//!     (s_q + g_q^T T_qJ diag(1/A_J) X d) / r_l <= t,      g_q = ds/dsigma at sigma_q,  X = dF_J/dtheta
//! ```
//!
//! `g_q` is `3 s'/(2 s)` (s' the deviator, shears counted twice) for von
//! Mises, `(n1 n1^T - n3 n3^T) / 2` for Tresca (n1, n3 the principal
//! directions of the largest and smallest principal stresses). A body's
//! singular edges kept clear ([`crate::DesignOptions::edge_clearance`])
//! keep their weighted pressure rows (`w_k F_k / (A_k r_l)`) beside the
//! stress rows, so the contact stays off them as in a pressure design.

use elcon_analysis::ContactSolution;
use elcon_analysis::subsurface::{StressField, contact_half_width, depth_grid};
use elcon_influence::{Body, Stress, StressKernel};
use faer::{Mat, MatRef};

use crate::DesignError;
use crate::constraint::Constraint;
use crate::objective::Objective;
use crate::prepared::Case;

/// Depths of each case's fixed grid of depths.
pub const DEPTHS: usize = 32;
/// How deep the depth grid reaches, in the start's contact half-widths
/// (elcon-analysis's, whose [`depth_grid`] the cases' depths are).
pub use elcon_analysis::subsurface::DEPTH_SPAN;
/// A candidate point becomes a model row when its stress is at least this
/// share of its case's largest: lower ones cannot bind within a trust
/// region the model is good in.
const CANDIDATE_SHARE: f64 = 0.5;

/// The components of a stress in [`Objective::gradient`]'s order.
fn components(s: &Stress) -> [f64; 6] {
    [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz]
}

/// A stress objective as a design's setup holds it: the measure and the
/// bodies with a field (distinct kernels and ratios: twin bodies count
/// once).
#[derive(Debug, Clone)]
pub(crate) struct StressObjective {
    objective: Objective,
    fields: Vec<(StressKernel, f64)>,
}

impl StressObjective {
    /// The stress objective over `bodies`, or `None` for the pressure
    /// objective.
    ///
    /// # Errors
    /// [`DesignError::Objective`] when no body has a field (rigid, beams,
    /// Winkler foundations) or none is given.
    pub(crate) fn new(objective: Objective, bodies: &[Body]) -> Result<Option<Self>, DesignError> {
        if !objective.is_stress() {
            return Ok(None);
        }
        let mut fields: Vec<(StressKernel, f64)> = Vec::new();
        let mut why = Vec::new();
        for body in bodies {
            match StressKernel::of(body) {
                Ok(f) if !fields.contains(&f) => fields.push(f),
                Ok(_) => {}
                Err(reason) => why.push(reason),
            }
        }
        if fields.is_empty() {
            let reason = if bodies.is_empty() {
                "no body given to measure the stresses of (DesignOptions::bodies)".to_string()
            } else {
                format!(
                    "no body has a stress field below its surface ({}); use objective = \"pressure\"",
                    why.join("; ")
                )
            };
            return Err(DesignError::Objective {
                objective: objective.name(),
                reason,
            });
        }
        Ok(Some(Self { objective, fields }))
    }

    /// The criterion with each case's depths fixed from its solution at the
    /// start: [`DEPTHS`] depths down to [`DEPTH_SPAN`] of its contact
    /// half-width (a cell or more deep for the point-force kernel).
    pub(crate) fn at(&self, cases: &[Case<'_>], solutions: &[ContactSolution]) -> StressCriterion {
        let depths = cases
            .iter()
            .zip(solutions)
            .map(|(case, solution)| {
                let points = case.problem.points();
                // No point in contact: a grid a cell deep.
                let contact = solution.contact.iter().copied();
                let half = contact_half_width(points, contact).unwrap_or(0.0);
                let point = self.fields.iter().any(|f| f.0 == StressKernel::PointForce);
                depth_grid(points, half, point, DEPTHS)
            })
            .collect();
        StressCriterion {
            objective: self.objective,
            fields: self.fields.clone(),
            depths,
        }
    }
}

/// How the descent measures a case: its weighted intensity
/// ([`Case::merit`]) or a stress below the surface.
#[derive(Debug, Clone)]
pub(crate) enum Criterion {
    /// The worst weighted intensity.
    Pressure,
    /// The worst stress.
    Stress(StressCriterion),
}

impl Criterion {
    /// Case l's merit under the criterion, with its largest stress measure
    /// under a stress objective (over its grid of points and depths). A
    /// stress merit is that largest stress over r_l, or a kept-clear
    /// edge's weighted intensity over r_l if larger.
    pub(crate) fn merit(
        &self,
        l: usize,
        case: &Case<'_>,
        solution: &ContactSolution,
    ) -> Result<(f64, Option<f64>), DesignError> {
        match self {
            Criterion::Pressure => Ok((case.merit(solution), None)),
            Criterion::Stress(c) => {
                let largest = c.sweep(l, case, solution)?.largest;
                let merit = (largest / case.reference).max(edge_merit(case, solution));
                Ok((merit, Some(largest)))
            }
        }
    }
}

/// A stress objective with each case's depths fixed (see the module
/// documentation).
#[derive(Debug, Clone)]
pub(crate) struct StressCriterion {
    objective: Objective,
    fields: Vec<(StressKernel, f64)>,
    /// Each case's depths.
    depths: Vec<Vec<f64>>,
}

/// A point of a case's field: its field, column (a point of the grid) and
/// depth.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    field: usize,
    column: usize,
    z: f64,
}

/// A case's field swept: its largest stress measure and the candidate
/// points of its model rows.
struct Sweep {
    largest: f64,
    candidates: Vec<Node>,
}

impl StressCriterion {
    /// The objective it measures.
    pub(crate) fn objective(&self) -> Objective {
        self.objective
    }

    /// Every grid point at every depth of case l, each field: the largest
    /// measure, and per axial station its largest point with the points
    /// above and below it (those at least [`CANDIDATE_SHARE`] of the
    /// largest).
    fn sweep(
        &self,
        l: usize,
        case: &Case<'_>,
        solution: &ContactSolution,
    ) -> Result<Sweep, DesignError> {
        let points = case.problem.points();
        let depths = &self.depths[l];
        let stations = case.station.iter().max().map_or(0, |s| s + 1);
        let mut best: Vec<(f64, Node, usize)> = Vec::new();
        let mut largest = 0.0f64;
        for (f, &(kernel, nu)) in self.fields.iter().enumerate() {
            let mut station_best = vec![(f64::NEG_INFINITY, 0usize, 0usize); stations];
            let layers = StressField::of_kernel(points, solution, kernel, nu)
                .layers_at(depths)
                .map_err(|e| DesignError::Objective {
                    objective: self.objective.name(),
                    reason: format!("the stress layers failed: {e}"),
                })?;
            for (j, layer) in layers.into_iter().enumerate() {
                for (k, s) in layer.iter().enumerate() {
                    let v = self.objective.measure(s);
                    largest = largest.max(v);
                    let b = &mut station_best[case.station[k]];
                    if v > b.0 {
                        *b = (v, k, j);
                    }
                }
            }
            best.extend(station_best.into_iter().filter(|b| b.0.is_finite()).map(
                |(v, column, j)| {
                    (
                        v,
                        Node {
                            field: f,
                            column,
                            z: depths[j],
                        },
                        j,
                    )
                },
            ));
        }
        let mut candidates = Vec::new();
        for (v, node, j) in best {
            if v < CANDIDATE_SHARE * largest {
                continue;
            }
            for jj in j.saturating_sub(1)..(j + 2).min(depths.len()) {
                candidates.push(Node {
                    z: depths[jj],
                    ..node
                });
            }
        }
        Ok(Sweep {
            largest,
            candidates,
        })
    }

    /// Case l's model rows: each candidate's linearized measure over r_l
    /// (`x` the derivative of the forces of its contact set,
    /// `solution.contact`, with respect to the parameters), and the
    /// kept-clear edges' pressure rows.
    pub(crate) fn rows(
        &self,
        l: usize,
        case: &Case<'_>,
        solution: &ContactSolution,
        x: MatRef<'_, f64>,
    ) -> Result<Vec<Constraint>, DesignError> {
        let contact = &solution.contact;
        let m = x.ncols();
        let sweep = self.sweep(l, case, solution)?;
        let (values, gradients) = self.linearized(case, solution, &sweep.candidates);
        let rows = &gradients * x;
        let r = case.reference;
        let mut out: Vec<Constraint> = (0..sweep.candidates.len())
            .map(|q| Constraint {
                a: (0..m).map(|i| rows[(q, i)] / r).collect(),
                t_coefficient: -1.0,
                b: -values[q] / r,
            })
            .collect();
        for (a, &k) in contact.iter().enumerate() {
            if case.weights[k] == 1.0 {
                continue;
            }
            let scale = r * case.measures[k] / case.weights[k];
            out.push(Constraint {
                a: (0..m).map(|i| x[(a, i)] / scale).collect(),
                t_coefficient: -1.0,
                b: -solution.forces[k] / scale,
            });
        }
        Ok(out)
    }

    /// Each candidate's measure and its gradient with respect to the
    /// forces of the contact set: `g_q^T T_qk / A_k` (|candidates| x |J|).
    fn linearized(
        &self,
        case: &Case<'_>,
        solution: &ContactSolution,
        candidates: &[Node],
    ) -> (Vec<f64>, Mat<f64>) {
        let points = case.problem.points();
        let contact = &solution.contact;
        let mut values = Vec::with_capacity(candidates.len());
        let mut gradients = Mat::zeros(candidates.len(), contact.len());
        for (q, node) in candidates.iter().enumerate() {
            let (kernel, nu) = self.fields[node.field];
            let (xq, yq) = (points.x(node.column), points.y(node.column));
            let units: Vec<Stress> = contact
                .iter()
                .map(|&k| {
                    let cell = points.cell();
                    kernel.unit(
                        (xq - points.x(k), yq - points.y(k), node.z),
                        (cell.dx, cell.dy),
                        nu,
                    )
                })
                .collect();
            let mut sigma = Stress::default();
            for (u, &k) in units.iter().zip(contact) {
                sigma.add_scaled(solution.forces[k] / case.measures[k], u);
            }
            let g = self.objective.gradient(&sigma);
            values.push(self.objective.measure(&sigma));
            for (a, (u, &k)) in units.iter().zip(contact).enumerate() {
                let c = components(u);
                let dot: f64 = g.iter().zip(&c).map(|(g, c)| g * c).sum();
                gradients[(q, a)] = dot / case.measures[k];
            }
        }
        (values, gradients)
    }
}

/// The worst weighted intensity over r_l of a case's kept-clear edge
/// points (0 when none is kept clear).
fn edge_merit(case: &Case<'_>, solution: &ContactSolution) -> f64 {
    solution
        .forces
        .iter()
        .zip(&case.measures)
        .zip(&case.weights)
        .filter(|(_, w)| **w != 1.0)
        .map(|((f, a), w)| w * f / a)
        .fold(0.0f64, f64::max)
        / case.reference
}

#[cfg(test)]
mod tests {
    use elcon_analysis::{ContactProblem, Geometry, Loading, Method, Options, Surface};
    use elcon_influence::{Material, PointSet};

    use super::*;
    use crate::basis::Basis;
    use crate::descent::sensitivities;
    use crate::evaluate::solve_corrected;
    use crate::prepared::{axial_stations, prepare};
    use crate::{Axis, Family};

    /// The model rows of both stress measures against central differences
    /// of the measures at the same points, the parameters of a quadratic
    /// crown on a misaligned roller moved by a step too small to change its
    /// contact set.
    #[test]
    fn the_gradient_rows_match_finite_differences() {
        let steel = Body::uniform_patch(Material::new(210e3, 0.3).unwrap());
        let points = PointSet::grid_rectangle(0.3, 5.0, 7, 16).unwrap();
        let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
        let loading = Loading::load(5e3).with_tilt_x(2e-4);
        let problem = ContactProblem::builder(points, &steel, &steel, &geometry, loading)
            .fold(false)
            .build()
            .unwrap();
        let cases = std::slice::from_ref(&problem);
        let (stations, index) = axial_stations(cases.iter().map(ContactProblem::points), Axis::Y);
        let prepared = prepare(cases, index, &[2000.0], (false, crate::Axis::Y)).unwrap();
        let case = &prepared[0];
        let basis = Basis::new(Family::Quadratic, &stations, None).unwrap();
        let crown: Vec<f64> = stations.iter().map(|s| 4e-3 * (s / 5.0).powi(2)).collect();
        let theta = basis.fit(&crown);
        let options = Options::default();
        let solve = |theta: &[f64]| {
            let drops = basis.drops(theta);
            let drops = case.station.iter().map(|&st| drops[st]);
            solve_corrected(
                case.problem,
                drops,
                None,
                Method::BlockPivoting,
                &options,
                "t",
            )
            .unwrap()
        };
        let (corrected, solution) = solve(&theta);
        let x = sensitivities(case, &corrected, &solution, &basis, &options).unwrap();
        for objective in [Objective::VonMises, Objective::MaxShear] {
            let stress = StressObjective::new(objective, &[steel]).unwrap().unwrap();
            let criterion = stress.at(&prepared, std::slice::from_ref(&solution));
            let rows = criterion.rows(0, case, &solution, x.as_ref()).unwrap();
            let sweep = criterion.sweep(0, case, &solution).unwrap();
            assert!(!sweep.candidates.is_empty());
            let largest = rows
                .iter()
                .map(|r| r.a.iter().fold(0.0f64, |a, v| a.max(v.abs())));
            let largest = largest.fold(0.0f64, f64::max);
            for i in 0..basis.params() {
                let column = (0..basis.phi.nrows()).map(|st| basis.phi[(st, i)].abs());
                let h = 1e-8 / column.fold(0.0f64, f64::max);
                let at = |sign: f64| {
                    let mut moved = theta.clone();
                    moved[i] += sign * h;
                    let (_, s) = solve(&moved);
                    assert_eq!(
                        s.contact, solution.contact,
                        "the step changed the contact set"
                    );
                    criterion.linearized(case, &s, &sweep.candidates).0
                };
                let (up, down) = (at(1.0), at(-1.0));
                for (q, row) in rows.iter().take(sweep.candidates.len()).enumerate() {
                    let fd = (up[q] - down[q]) / (2.0 * h) / case.reference;
                    let error = (fd - row.a[i]).abs();
                    assert!(
                        error <= 1e-5 * largest,
                        "{objective:?} q {q} i {i}: {fd} {}",
                        row.a[i]
                    );
                }
            }
        }
    }
}
