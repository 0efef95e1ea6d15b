//! The load cases of a design, prepared once for either method: each case's
//! axial stations, measures `A_k`, load, free rigid motions (their levers
//! `m_k` and resultants `b`) and separations shifted by its prescribed
//! motions,
//!
//! ```text
//!     eps_k  ->  eps_k - sum_prescribed value m_k
//! ```
//!
//! and what a method's start returns: the parameters it found, the worst
//! intensity its own solutions reach, and how it got there.

use elcon_analysis::{ContactProblem, ContactSolution};
use elcon_influence::PointSet;
use elcon_lcp::{Certificate, Statistics};
use faer::Mat;

use crate::evaluate::load_of;
use crate::{Axis, DesignError};

/// One load case, prepared: its points' stations, measures and load, and
/// its free rigid motions (the approach first, then the free rotations,
/// including those its symmetry makes zero: a correction may break the
/// symmetry, and its re-analysis then frees them) with the separations
/// shifted by the prescribed ones.
pub(crate) struct Case<'a> {
    pub(crate) problem: &'a ContactProblem,
    pub(crate) station: Vec<usize>,
    pub(crate) measures: Vec<f64>,
    pub(crate) load: f64,
    /// The free motions' levers at every point (n x k) and resultants.
    pub(crate) levers: Mat<f64>,
    pub(crate) resultants: Vec<f64>,
    /// `eps` shifted by the prescribed motions.
    pub(crate) separation: Vec<f64>,
    /// Reference intensity r_l.
    pub(crate) reference: f64,
    /// Each point's weight w_k in the objective `max_k w_k F_k / (A_k r_l)`:
    /// [`EDGE_WEIGHT`] on the bodies' singular edges when the design keeps
    /// the contact off them ([`DesignOptions::edge_clearance`](crate::DesignOptions::edge_clearance)), else 1.
    pub(crate) weights: Vec<f64>,
}

/// The weight of a point on a body's singular edge (a roller's end) when
/// the design keeps the contact off it: an intensity there counts this
/// many times in the objective, so the design relieves the edge first and
/// leaves it at most a hundredth of the worst intensity elsewhere (a
/// larger weight stretches the step programs' rows beyond what their
/// pivots resolve).
pub const EDGE_WEIGHT: f64 = 100.0;

impl<'a> Case<'a> {
    /// The case with the rotations its symmetry makes zero held, as its
    /// own analysis holds them (`ContactProblem::rigid`; the same motions
    /// when its symmetry holds none, [`Case::holds_rotations`]). The design
    /// program falls back to it when it finds no complementary start with
    /// them free (the restricted-entry rule can stall on a symmetric
    /// case's free rotation: Example 2's centred beam).
    pub(crate) fn held(&self) -> Case<'a> {
        let rigid = self.problem.rigid();
        let points = self.problem.points();
        Case {
            problem: self.problem,
            station: self.station.clone(),
            measures: self.measures.clone(),
            load: self.load,
            levers: Mat::from_fn(points.len(), rigid.free.len(), |k, j| {
                rigid.free[j]
                    .0
                    .lever((points.x(k), points.y(k)), rigid.load_point)
            }),
            resultants: rigid.free.iter().map(|&(_, v)| v).collect(),
            separation: self.separation.clone(),
            reference: self.reference,
            weights: self.weights.clone(),
        }
    }

    /// Whether the case's analysis holds a rotation at zero by symmetry
    /// that the design leaves free.
    pub(crate) fn holds_rotations(&self) -> bool {
        self.problem.rigid().free.len() != self.resultants.len()
    }

    /// The design's measure of `solution`: `max_k w_k F_k / (A_k r_l)`.
    pub(crate) fn merit(&self, solution: &ContactSolution) -> f64 {
        solution
            .forces
            .iter()
            .zip(&self.measures)
            .zip(&self.weights)
            .map(|((f, a), w)| w * f / a)
            .fold(0.0f64, f64::max)
            / self.reference
    }
}

/// The axial stations of point sets (the load cases' points, say): the
/// distinct axial positions of all their points, increasing, positions
/// within 1e-9 of the whole range merged into the first of them; and, per
/// set, each point's station (an index into the stations). These are the
/// stations a design's free profile has one drop at (`Design::stations`)
/// and its table is written at.
pub fn axial_stations<'a>(
    sets: impl IntoIterator<Item = &'a PointSet>,
    axis: Axis,
) -> (Vec<f64>, Vec<Vec<usize>>) {
    let all: Vec<Vec<f64>> = sets.into_iter().map(|p| axis.positions(p)).collect();
    let mut sorted: Vec<f64> = all.iter().flatten().copied().collect();
    sorted.sort_by(f64::total_cmp);
    let range = sorted.last().copied().unwrap_or(0.0) - sorted.first().copied().unwrap_or(0.0);
    let merge = 1e-9 * range.max(f64::MIN_POSITIVE);
    let mut stations: Vec<f64> = Vec::new();
    for s in sorted {
        if stations.last().is_none_or(|&last| s - last > merge) {
            stations.push(s);
        }
    }
    let index = all
        .iter()
        .map(|positions| {
            positions
                .iter()
                .map(|&s| {
                    let i = stations.partition_point(|&st| st < s - merge);
                    i.min(stations.len() - 1)
                })
                .collect()
        })
        .collect();
    (stations, index)
}

/// The points a design that must hold on any grid keeps out of contact:
/// those on the bodies' singular edges (a roller's ends), and those on
/// the candidate zone's open edges along the profile's `axis` (a side
/// that is not a body's own) of elastic half-spaces. A contact there is
/// cut off by the zone: the
/// bodies would go on touching beyond it, and a family free to spread the
/// load along its axis (a polynomial across a disk) would otherwise press
/// it against the zone's edge, whose cut peak grows as the grid refines.
/// Kept clear, the design stays inside the zone: the zone bounds how far
/// it may spread the contact.
pub(crate) fn cleared_points(problem: &ContactProblem, axis: Axis) -> Vec<usize> {
    let mut cleared = problem.singular_edge_points();
    // Only where the pressure at a cut edge is singular (elastic
    // half-spaces: every zone edge would be singular if it were the
    // bodies'); a beam's or a foundation's stays bounded and converges.
    let every_edge = problem.clone().with_body_edges(true, true);
    if every_edge.singular_edge_points().is_empty() {
        return cleared;
    }
    let (body_x, body_y) = problem.body_edges();
    let points = problem.points();
    cleared.extend((0..points.len()).filter(|&k| {
        let (x, y) = points.open_sides(k);
        match axis {
            Axis::X => x && !body_x,
            Axis::Y => y && !body_y,
        }
    }));
    cleared.sort_unstable();
    cleared.dedup();
    cleared
}

/// Every case prepared (each under load control and unfolded, checked by
/// `load_of`), with each point's station among `index`, its singular edges
/// and the zone's open edges along `axis` weighted by [`EDGE_WEIGHT`] when
/// `edge_clearance`.
pub(crate) fn prepare<'a>(
    cases: &'a [ContactProblem],
    index: Vec<Vec<usize>>,
    references: &[f64],
    (edge_clearance, axis): (bool, Axis),
) -> Result<Vec<Case<'a>>, DesignError> {
    cases
        .iter()
        .zip(index)
        .enumerate()
        .map(|(l, (problem, station))| {
            let load = load_of(problem, l)?;
            // The motions free before symmetry drops any: a correction may
            // break the case's symmetry (an odd term of a polynomial), and
            // the re-analysis then frees the rotation that symmetry held at
            // zero, so the program must leave it free too.
            let rigid = &problem
                .rigid_without_symmetry()
                .map_err(DesignError::analysis(format!("load case {l}")))?;
            let points = problem.points();
            let at = |k: usize| (points.x(k), points.y(k));
            let levers = Mat::from_fn(points.len(), rigid.free.len(), |k, j| {
                rigid.free[j].0.lever(at(k), rigid.load_point)
            });
            let shift = |k: usize| -> f64 {
                -rigid
                    .prescribed
                    .iter()
                    .map(|&(mode, value)| value * mode.lever(at(k), rigid.load_point))
                    .sum::<f64>()
            };
            let eps = problem.separation();
            let mut weights = vec![1.0; points.len()];
            if edge_clearance {
                for k in cleared_points(problem, axis) {
                    weights[k] = EDGE_WEIGHT;
                }
            }
            Ok(Case {
                problem,
                measures: points.measures(),
                station,
                load,
                levers,
                resultants: rigid.free.iter().map(|&(_, v)| v).collect(),
                separation: (0..points.len()).map(|k| eps[k] + shift(k)).collect(),
                reference: references[l],
                weights,
            })
        })
        .collect()
}

/// The reference intensities r_l: given (one per case, finite, > 0) or all
/// 1 (the design program's and the crown search's).
pub(crate) fn reference_intensities(
    given: Option<&[f64]>,
    cases: usize,
) -> Result<Vec<f64>, DesignError> {
    match given {
        None => Ok(vec![1.0; cases]),
        Some(r) if r.len() != cases => Err(DesignError::Incompatible {
            field: "reference_intensities",
            reason: format!(
                "has {} entries, expected {cases} (one per load case)",
                r.len()
            ),
        }),
        Some(r) => match r.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            Some(&v) => Err(DesignError::InvalidInput {
                field: "reference_intensities",
                value: v,
                reason: "every reference intensity must be finite and > 0",
            }),
            None => Ok(r.to_vec()),
        },
    }
}

/// Largest elastic deflection under a uniform pressure plus the largest
/// initial separation: the scale of the default c_max.
pub(crate) fn deflection_scale(c: &Case<'_>) -> Result<f64, DesignError> {
    let n = c.station.len();
    let total: f64 = c.measures.iter().sum();
    let uniform: Vec<f64> = (0..n).map(|j| c.load * c.measures[j] / total).collect();
    let deflected = c
        .problem
        .deflection(&uniform)
        .map_err(DesignError::analysis("the deflection scale"))?;
    let deflection = deflected.iter().fold(0.0f64, |a, v| a.max(*v));
    let eps = c
        .problem
        .separation()
        .iter()
        .fold(0.0f64, |a, e| a.max(e.abs()));
    Ok(deflection + eps)
}

/// How a design's parameters were found.
#[derive(Debug, Clone)]
pub enum Solver {
    /// By the paper's program: its certificate (the residuals of its final
    /// basis from the program's data) and the engine's statistics.
    Program {
        /// The certificate of the program's solution.
        certificate: Certificate,
        /// The engine's statistics.
        statistics: Statistics,
    },
    /// By the case-decomposed descent (`DesignMethod::Descent`).
    Descent {
        /// Trust-region iterations (each a linear program over the
        /// parameters and one analysis of every case).
        iterations: usize,
        /// Steps accepted (the objective fell by a fraction of the model's
        /// prediction).
        accepted: usize,
        /// Contact analyses solved.
        analyses: usize,
        /// Engine pivots of every analysis and linear program together.
        pivots: usize,
        /// Why it stopped.
        stop: Stop,
    },
}

impl Solver {
    /// The method that ran: the program or the descent.
    pub fn method(&self) -> crate::DesignMethod {
        match self {
            Solver::Program { .. } => crate::DesignMethod::Program,
            Solver::Descent { .. } => crate::DesignMethod::Descent,
        }
    }
}

/// Why the descent stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The linear model predicts no decrease within the trust region (a
    /// stationary point of the min-max problem).
    Stationary,
    /// The trust region shrank below the parameters' resolution.
    TrustRegion,
    /// `DesignOptions::max_iterations` reached.
    IterationLimit,
}

#[cfg(test)]
mod tests {
    use super::*;
    use elcon_analysis::{Geometry, Loading, Storage, Surface};
    use elcon_influence::{Body, Material};

    /// Two spheres on a disk: symmetric, so the analysis drops both
    /// rotations (zero at the solution); the design keeps them free, since
    /// an odd correction breaks the symmetry and its re-analysis frees them.
    #[test]
    fn a_symmetric_case_keeps_the_rotations_its_symmetry_drops() {
        let steel = Material::new(30e6, 0.3).unwrap();
        let points = PointSet::grid_disk(0.002, 0.02).unwrap();
        let body = Body::uniform_patch(steel);
        let geometry = Geometry::Surfaces(
            Surface::Sphere { radius: 1.0 },
            Surface::Sphere { radius: 10.0 },
        );
        let case =
            ContactProblem::new(points, &body, &body, &geometry, Loading::load(100.0)).unwrap();
        assert_eq!(
            case.rigid().free.len(),
            1,
            "the analysis holds the rotations by symmetry"
        );
        let (_, index) = axial_stations([case.points()], Axis::Y);
        let prepared =
            prepare(std::slice::from_ref(&case), index, &[1.0], (false, Axis::Y)).unwrap();
        assert_eq!(prepared[0].levers.ncols(), 3);
        assert_eq!(prepared[0].resultants, vec![100.0, 0.0, 0.0]);
    }

    /// The points kept clear along y: on a roller's ends (its body edges
    /// along y); on a zone open along y, its ends too; never the sides
    /// across the axis or an interior point.
    #[test]
    fn the_cleared_points_are_the_body_edges_and_the_zones_open_sides() {
        // The roller's ends are the body's own edges.
        let (case, _) =
            elcon_fixtures::design_cases::aligned_roller(5e3, (5, 12), Storage::Dense).unwrap();
        let cleared = cleared_points(&case, Axis::Y);
        // The two rows of 5 points at the roller's ends.
        assert_eq!(cleared.len(), 10);
        assert!(cleared.iter().all(|&k| case.points().open_sides(k).1));
        // The same rows when the zone's ends along y are open, none along x.
        // (A beam or a foundation clears none: its pressure at a cut edge
        // is bounded.)
        let open = case.clone().with_body_edges(false, false);
        assert_eq!(cleared_points(&open, Axis::Y), cleared);
        assert!(cleared_points(&open, Axis::X).len() == 24);
        // Without edge clearance every weight is 1; with it the border's is EDGE_WEIGHT.
        let (_, index) = axial_stations([case.points()], Axis::Y);
        let kept = prepare(std::slice::from_ref(&case), index, &[1.0], (true, Axis::Y)).unwrap();
        let weighted = kept[0]
            .weights
            .iter()
            .filter(|&&w| w == EDGE_WEIGHT)
            .count();
        assert_eq!(weighted, 10);
        // A beam on a foundation: its pressure at a cut edge is bounded,
        // and no point is cleared, its ends open or not.
        let beam = elcon_influence::Beam {
            youngs_modulus: 30e6,
            second_moment: 16.0 / 3.0,
            loaded_point: 0.0,
        };
        let line = ContactProblem::new(
            PointSet::line(-4.45, 4.45, 20).unwrap(),
            &Body::beam(beam).unwrap(),
            &Body::winkler(1e7),
            &Geometry::Separation(vec![0.0; 20]),
            Loading::load(5e4),
        )
        .unwrap();
        assert!(cleared_points(&line, Axis::X).is_empty());
    }
}
