//! A certified contact solution read from the engine's answer: forces F,
//! pressures `p_k = F_k / A_k`, gaps Y, the rigid motions, the moments and
//! the load centre, the contact set and its extent (its edge resolved
//! within the outermost cells, `crate::edge`), the certificate (residuals
//! of `Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`, `F_k Y_k = 0`
//! from the original data, relative to their terms) and warnings.

use elcon_influence::Dimension;
use elcon_lcp::{Certificate, Statistics};

use super::problem::ContactProblem;
use crate::rigid::RigidMode;

/// A warning about a solution that is certified but may not mean what it seems.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Warning {
    /// The contact reaches an open edge of the candidate zone (not one
    /// declared a body's own by [`ContactProblem::with_body_edges`]): the
    /// true contact may be larger, and the answer truncated. Raised where the
    /// contact's edge, extrapolated from the outermost points
    /// (`crate::edge`), does not end inside their cells, or where that
    /// cannot be told. Enlarge the zone.
    ContactAtEdge {
        /// Points in contact on the zone's boundary.
        points: Vec<usize>,
    },
    /// Points where both the force and the gap are near zero (relative
    /// `sqrt(eps) ≈ 1.5e-8`, eps = `f64::EPSILON`, of their scales): whether
    /// they touch is uncertain.
    UncertainContact {
        /// The points concerned.
        points: Vec<usize>,
    },
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::ContactAtEdge { points } => write!(
                f,
                "contact reaches the edge of the candidate zone at {} point(s) and may go on beyond it: the answer may be truncated; enlarge the zone",
                points.len()
            ),
            Warning::UncertainContact { points } => write!(
                f,
                "{} point(s) have both force and gap near zero: the contact set is uncertain there",
                points.len()
            ),
        }
    }
}

/// The residuals of a contact solution, computed from the original S, eps
/// and P, each relative to the scale of the terms it is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactCertificate {
    /// `|e^T F - P|` over the scale of its terms, `sum |F_k| + P` (about
    /// `2 P`; 0 under displacement control).
    pub equilibrium: f64,
    /// Smallest force over the largest (negative = a tensile force).
    pub min_force: f64,
    /// Smallest gap over the scale of the gap's terms `max(|S| F + |eps| + |alpha|)` (negative = interpenetration).
    pub min_gap: f64,
    /// Largest `|F_k Y_k|` over (largest force x gap scale).
    pub complementarity: f64,
    /// The tolerance it is judged against.
    pub tolerance: f64,
}

impl ContactCertificate {
    fn from_engine(c: &Certificate) -> Self {
        Self {
            // A non-finite solution reads as an infinite equilibrium residual.
            equilibrium: if c.finite { c.equality } else { f64::INFINITY },
            min_force: c.min_z,
            min_gap: c.min_w,
            complementarity: c.complementarity,
            tolerance: c.tolerance,
        }
    }

    /// The worst relative residual (infinite if any residual is not finite).
    pub fn worst(&self) -> f64 {
        let parts = [
            self.equilibrium,
            -self.min_force,
            -self.min_gap,
            self.complementarity,
        ];
        if parts.iter().any(|v| !v.is_finite()) {
            return f64::INFINITY;
        }
        parts.into_iter().fold(0.0, f64::max)
    }

    /// Whether every residual is within the tolerance.
    pub fn holds(&self) -> bool {
        self.worst() <= self.tolerance
    }
}

impl std::fmt::Display for ContactCertificate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "equilibrium {:.1e}, min force {:.1e}, min gap {:.1e}, complementarity {:.1e}",
            self.equilibrium, self.min_force, self.min_gap, self.complementarity
        )
    }
}

/// A certified contact solution.
#[derive(Debug, Clone)]
pub struct ContactSolution {
    /// Contact force at each point, F_k (force; force per length in 2D).
    pub forces: Vec<f64>,
    /// Mean pressure over each point's cell, p_k = F_k / A_k (force per area; per length in 2D).
    pub pressures: Vec<f64>,
    /// Gap after deformation, Y_k (length).
    pub gaps: Vec<f64>,
    /// Rigid-body approach, alpha (length).
    pub approach: f64,
    /// Rotation of body 1 about the x axis through the load point, `θ_x`
    /// (radians; `crate::loading`).
    pub tilt_x: f64,
    /// Rotation of body 1 about the y axis through the load point, `θ_y` (radians).
    pub tilt_y: f64,
    /// Moment of the contact forces about the x axis through the load
    /// point, `sum F (y - y0)` (force length; it balances `M_x`).
    pub moment_x: f64,
    /// Moment of the contact forces about the y axis through the load
    /// point, `-sum F (x - x0)` (it balances `M_y`).
    pub moment_y: f64,
    /// The centre of the contact forces (where their resultant acts),
    /// `(sum F x, sum F y) / sum F`.
    pub load_centre: (f64, f64),
    /// Total load, e^T F (force; per length in 2D).
    pub load: f64,
    /// Largest p_k.
    pub max_pressure: f64,
    /// Indices of the points with F_k > 0.
    pub contact: Vec<usize>,
    /// Area (3D) or length (2D) of the contact: its cells', the edge
    /// resolved within the outermost cells where the pressure falls to it
    /// (`p^2` extrapolated to zero along the grid on a half-space, `p` on a
    /// foundation; whole cells on points that are not a lattice or an S
    /// given by [`ContactProblem::from_parts`]).
    pub contact_measure: f64,
    /// Contact radius `sqrt(area / pi)` (3D) or half-width `length / 2` (2D)
    /// from [`ContactSolution::contact_measure`].
    pub contact_extent: f64,
    /// The contact ellipse on a surface, from the pressure field's second
    /// moments (the ellipse of Hertz's pressure with the same moments,
    /// `crate::ContactEllipse`): its semi-axes and their direction, as an
    /// elliptical Hertz contact's are compared; `None` on a line, with
    /// fewer than 3 points in contact, or where the edge law is not known.
    pub contact_ellipse: Option<crate::ContactEllipse>,
    /// Residuals from the original data.
    pub certificate: ContactCertificate,
    /// The engine's statistics.
    pub statistics: Statistics,
    /// Seconds spent assembling S and eps.
    pub assembly_seconds: f64,
    /// Seconds spent solving (engine, certificate, post-processing).
    pub solve_seconds: f64,
    /// Warnings: truncated zone, uncertain contact.
    pub warnings: Vec<Warning>,
}

impl ContactProblem {
    /// The solution from the engine's answer at every point.
    pub(super) fn finish(&self, engine: Engine) -> ContactSolution {
        let (forces, certificate) = (&engine.forces, &engine.certificate);
        let slack = engine.slack.as_deref().unwrap_or(&engine.gaps);
        let n = self.points.len();
        let pressures: Vec<f64> = (0..n).map(|k| forces[k] / self.points.measure(k)).collect();
        let load: f64 = forces.iter().sum();
        let fmax = forces.iter().fold(0.0f64, |a, f| a.max(*f));
        let contact: Vec<usize> = (0..n).filter(|&k| forces[k] > 0.0).collect();
        let edge_of_contact = crate::edge::Edge::new(&self.points, &pressures, self.edge);
        let contact_measure = edge_of_contact.measure();
        let contact_ellipse = crate::ellipse::pressure_ellipse(&self.points, &pressures, self.edge);
        let contact_extent = match self.points.dimension() {
            Dimension::Surface => (contact_measure / std::f64::consts::PI).sqrt(),
            Dimension::Line => contact_measure / 2.0,
        };
        // A gap is near zero relative to the scale of the gaps' terms (the
        // largest |S| F plus the sizes of eps and alpha), the certificate's
        // w_scale. Both are in the engine's scaling: a folded row is divided
        // by its s_a, and so is the precision of its w (its terms over s_a).
        let gap_scale = certificate.w_scale;
        let near = f64::EPSILON.sqrt();
        let uncertain: Vec<usize> = (0..n)
            .filter(|&k| fmax > 0.0 && forces[k] <= near * fmax && slack[k] <= near * gap_scale)
            .collect();
        let (body_x, body_y) = self.body_edges;
        let edge: Vec<usize> = contact
            .iter()
            .copied()
            .filter(|&k| {
                let (x, y) = self.points.open_sides(k);
                let open = (x && !body_x, y && !body_y);
                (open.0 || open.1) && edge_of_contact.may_be_truncated(k, open)
            })
            .collect();
        let mut warnings = Vec::new();
        if !edge.is_empty() {
            warnings.push(Warning::ContactAtEdge { points: edge });
        }
        if !uncertain.is_empty() {
            warnings.push(Warning::UncertainContact { points: uncertain });
        }
        let max_pressure = pressures.iter().fold(0.0f64, |a, p| a.max(*p));
        let value = |mode| self.rigid.value(mode, &engine.lambda);
        let (x0, y0) = self.rigid.load_point;
        // The points' coordinates walked once (a grid's by its runs), not
        // looked up point by point.
        let first_moment = |lever: &dyn Fn((f64, f64)) -> f64| -> f64 {
            self.points
                .positions()
                .enumerate()
                .map(|(k, at)| forces[k] * lever(at))
                .sum()
        };
        let moment_x = first_moment(&|(_, y)| y - y0);
        let moment_y = -first_moment(&|(x, _)| x - x0);
        let centre = |moment: f64| if load > 0.0 { moment / load } else { 0.0 };
        ContactSolution {
            forces: engine.forces,
            pressures,
            gaps: engine.gaps,
            approach: value(RigidMode::Approach),
            tilt_x: value(RigidMode::TiltX),
            tilt_y: value(RigidMode::TiltY),
            moment_x,
            moment_y,
            load_centre: (x0 - centre(moment_y), y0 + centre(moment_x)),
            load,
            max_pressure,
            contact,
            contact_measure,
            contact_extent,
            contact_ellipse,
            certificate: ContactCertificate::from_engine(certificate),
            statistics: engine.statistics,
            assembly_seconds: self.assembly_seconds,
            solve_seconds: engine.solve_seconds,
            warnings,
        }
    }
}

/// The engine's answer at every point, before the solution's reading.
pub(super) struct Engine {
    pub(super) forces: Vec<f64>,
    pub(super) gaps: Vec<f64>,
    /// The engine's w at every point (the gap, or for a folded problem the
    /// gap over its orbit's s_a): the scaling the certificate's `w_scale`
    /// measures. `None` when unfolded: then it is `gaps`.
    pub(super) slack: Option<Vec<f64>>,
    /// The free rigid motions, in the order of `Rigid::free`.
    pub(super) lambda: Vec<f64>,
    pub(super) certificate: Certificate,
    pub(super) statistics: Statistics,
    pub(super) solve_seconds: f64,
}
