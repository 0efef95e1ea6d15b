//! The discrete frictionless contact problem of Conry & Seireg (1971), its
//! reduction to a (mixed) LCP, and its certified solution.
//!
//! N candidate points k with forces `F_k >= 0` (the paper's F), gaps after
//! deformation `Y_k >= 0` (Y), initial separations `eps_k` (ε) and the
//! rigid-body approach `alpha` (α); `S = A(1) + A(2)` the influence matrix:
//!
//! ```text
//!     Y = S F + eps - alpha e        compatibility          (paper eq. 3, 6)
//!     e^T F = P                      equilibrium            (eq. 2)
//!     F >= 0, Y >= 0, F_k Y_k = 0    contact criterion      (eq. 4)
//! ```
//!
//! Load control (P given) is the engine's bordered LCP `w = S z - B λ + q`,
//! `B^T z = b` with `z = F`, `w = Y`, `λ = alpha`, `B = e`, `q = eps`,
//! `b = P`. Displacement control (alpha given, P = e^T F follows) is the
//! plain LCP `Y = S F + (eps - alpha e)`.

use std::sync::Arc;
use std::time::Instant;

use elcon_influence::{
    Body, Dimension, Folding, LatticeKernel, Model, PointSet, assemble, assemble_folded,
};
use elcon_lcp::{BorderedLcpRef, Certificate, Method, Operator, OperatorLcp, Options, Statistics};
use faer::{Col, ColRef, Mat, MatRef};

use crate::AnalysisError;
use crate::edge::EdgeLaw;
use crate::influence::{Influence, Products};
use crate::loading::Loading;
use crate::rigid::{Rigid, RigidMode, point};

/// Separations equal to this fraction of their largest magnitude count as
/// symmetric (they come from the same formula at mirrored points, so they
/// are equal to rounding).
const SYMMETRY_TOLERANCE: f64 = 1e-14;

/// The shape of one surface near the initial point of contact, as its height
/// above the common tangent plane. Radii are positive for convex surfaces and
/// negative for concave ones (a ball in a groove).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Surface {
    /// A plane: height 0.
    Plane,
    /// A sphere of radius R: height `(x^2 + y^2) / (2R)` (Hertz's paraboloid).
    Sphere {
        /// Radius R (length; negative = concave).
        radius: f64,
    },
    /// A cylinder of radius R with its axis along y: height `x^2 / (2R)`.
    Cylinder {
        /// Radius R (length; negative = concave).
        radius: f64,
    },
}

impl Surface {
    fn height(&self, x: f64, y: f64) -> f64 {
        match *self {
            Surface::Plane => 0.0,
            Surface::Sphere { radius } => (x * x + y * y) / (2.0 * radius),
            Surface::Cylinder { radius } => x * x / (2.0 * radius),
        }
    }

    fn validate(&self, field: &'static str, dimension: Dimension) -> Result<(), AnalysisError> {
        let radius = match *self {
            Surface::Plane => return Ok(()),
            Surface::Sphere { radius } | Surface::Cylinder { radius } => radius,
        };
        if !(radius.is_finite() && radius != 0.0) {
            return Err(AnalysisError::InvalidInput {
                field,
                value: radius,
                reason: "a radius must be finite and non-zero (negative for a concave surface)",
            });
        }
        if matches!(self, Surface::Sphere { .. }) && dimension == Dimension::Line {
            return Err(AnalysisError::Incompatible {
                field,
                reason: "a sphere needs a surface point set; for a 2D line contact use a cylinder"
                    .into(),
            });
        }
        Ok(())
    }
}

/// Where the initial separations come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// Two surfaces: `eps_k = h1(x_k, y_k) + h2(x_k, y_k)`.
    Surfaces(Surface, Surface),
    /// Given separations, one per point (length).
    Separation(Vec<f64>),
}

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

/// `Serialize` (the `serde` feature), in the shape of result.json's
/// `certificate` (docs/results.md): the stored residuals with the worst of
/// them and whether it holds, which are computed, between them. Written by
/// hand for those two.
#[cfg(feature = "serde")]
mod serialize {
    use serde::ser::{Serialize, SerializeStruct, Serializer};

    use super::ContactCertificate;

    impl Serialize for ContactCertificate {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            let mut s = serializer.serialize_struct("ContactCertificate", 7)?;
            s.serialize_field("equilibrium", &self.equilibrium)?;
            s.serialize_field("min_force", &self.min_force)?;
            s.serialize_field("min_gap", &self.min_gap)?;
            s.serialize_field("complementarity", &self.complementarity)?;
            s.serialize_field("worst", &self.worst())?;
            s.serialize_field("tolerance", &self.tolerance)?;
            s.serialize_field("holds", &self.holds())?;
            s.end()
        }
    }
}

/// A discrete contact problem: points, influence matrix, separations, loading.
#[derive(Debug, Clone)]
pub struct ContactProblem {
    points: PointSet,
    /// Shared between problems that differ only in loading or separation.
    influence: Influence,
    separation: Vec<f64>,
    loading: Loading,
    /// The rigid-body unknowns of `loading` (folded with the problem).
    rigid: Rigid,
    assembly_seconds: f64,
    body_edges: (bool, bool),
    /// The orbits of a mirror-symmetric problem, when it was folded.
    folding: Option<Arc<Folding>>,
    /// The mirror groups the points and the models respect, largest first:
    /// a free rotation that is odd under one the separations respect too
    /// is zero at the solution and not an unknown, folded or not. `None`
    /// for a matrix-free problem: its orbits (8.5 bytes a point each) are
    /// found again when a new loading or separation asks.
    groups: Option<Arc<Vec<Folding>>>,
    /// How the pressure falls at the contact's edge (crate::edge).
    edge: EdgeLaw,
}

impl ContactProblem {
    /// Assembles `S = A(1) + A(2)` of the two bodies on `points` and the
    /// initial separations of `geometry`.
    pub fn new(
        points: PointSet,
        body1: &Body,
        body2: &Body,
        geometry: &Geometry,
        loading: Loading,
    ) -> Result<Self, AnalysisError> {
        Self::build(points, [body1, body2], geometry, loading, false)
    }

    /// As [`ContactProblem::new`], but when the points, both bodies' models
    /// and the separations are mirror symmetric (`elcon_influence::Folding`),
    /// the problem is folded: one unknown per orbit of points, the folded
    /// matrix assembled in place of S (never the full S), a quarter or an
    /// eighth of the size. The solution is the same (the contact solution is
    /// unique, hence symmetric) and is returned for every point; the
    /// engine's certificate is that of the folded system, an exact
    /// regrouping of the original sums. Without a symmetry it is
    /// [`ContactProblem::new`].
    pub fn symmetric(
        points: PointSet,
        body1: &Body,
        body2: &Body,
        geometry: &Geometry,
        loading: Loading,
    ) -> Result<Self, AnalysisError> {
        Self::build(points, [body1, body2], geometry, loading, true)
    }

    /// [`ContactProblem::new`] (`fold` false) and
    /// [`ContactProblem::symmetric`] (`fold` true): the separations and the
    /// loading are validated before the O(N^2) assembly, then, if asked, the
    /// largest symmetry group the separations (shifted by the prescribed
    /// motions) and the free rigid motions respect too is looked for
    /// (`crate::rigid`), and the folded or the full matrix is assembled.
    fn build(
        points: PointSet,
        bodies: [&Body; 2],
        geometry: &Geometry,
        loading: Loading,
        fold: bool,
    ) -> Result<Self, AnalysisError> {
        let start = Instant::now();
        let layout = Layout::of(&points, bodies, geometry, &loading, fold)?;
        let influence = match &layout.folding {
            Some(f) => assemble_folded(&points, &bodies, f)?,
            None => assemble(&points, &bodies)?,
        };
        Ok(Self {
            points,
            influence: Influence::Dense(Arc::new(influence)),
            separation: layout.separation,
            loading,
            rigid: layout.rigid,
            assembly_seconds: start.elapsed().as_secs_f64(),
            body_edges: (false, false),
            folding: layout.folding.map(Arc::new),
            groups: Some(Arc::new(layout.groups)),
            edge: EdgeLaw::of(bodies),
        })
    }

    /// As [`ContactProblem::new`], with S held matrix-free: the product
    /// `S F` by a zero-padded FFT convolution of the lattice kernel
    /// (`elcon_influence::LatticeKernel`), O(N) memory instead of
    /// 8 N^2 bytes, for grids too large to store S (10^4 to 10^6 points).
    /// Solve it with [`Method::ConjugateGradient`]; the pivoting methods
    /// need S's entries and are refused. Not folded (a tilt that symmetry
    /// makes zero is still dropped from the unknowns).
    ///
    /// # Errors
    /// As [`ContactProblem::new`]; and as `LatticeOperator::new`: the
    /// points must be a lattice (`PointSet::grid_disk`, `grid_rectangle`,
    /// `line`), no body a beam.
    pub fn lattice(
        points: PointSet,
        body1: &Body,
        body2: &Body,
        geometry: &Geometry,
        loading: Loading,
    ) -> Result<Self, AnalysisError> {
        let start = Instant::now();
        let bodies = [body1, body2];
        // As Layout::of unfolded, the mirror groups tried one at a time
        // and none kept: at 10^5 points and more their orbits would
        // outweigh the operator.
        let separation = separations(&points, geometry)?;
        let rigid = check(&points, &separation, &loading, load_point(&bodies))?;
        let rigid = unfolded_rigid(&points, &bodies, &separation, rigid);
        let operator = LatticeKernel::new(&points, &bodies)?;
        Ok(Self {
            points,
            influence: Influence::Lattice(Arc::new(operator)),
            separation,
            loading,
            rigid,
            assembly_seconds: start.elapsed().as_secs_f64(),
            body_edges: (false, false),
            folding: None,
            groups: None,
            edge: EdgeLaw::of(bodies),
        })
    }

    /// Whether S is held matrix-free ([`ContactProblem::lattice`]).
    pub fn matrix_free(&self) -> bool {
        matches!(self.influence, Influence::Lattice(_))
    }

    /// The orbits the problem was folded with ([`ContactProblem::symmetric`]),
    /// or `None` for a problem solved in full.
    pub fn folding(&self) -> Option<&Folding> {
        self.folding.as_deref()
    }

    /// A problem from an influence matrix (N x N, length per force) and
    /// separations (N, length) built elsewhere; moments and rotations are
    /// about the origin.
    pub fn from_parts(
        points: PointSet,
        influence: Mat<f64>,
        separation: Vec<f64>,
        loading: Loading,
    ) -> Result<Self, AnalysisError> {
        let n = points.len();
        if influence.nrows() != n || influence.ncols() != n {
            return Err(AnalysisError::SizeMismatch {
                field: "influence",
                expected: n,
                found: if influence.nrows() != n {
                    influence.nrows()
                } else {
                    influence.ncols()
                },
            });
        }
        let rigid = check(&points, &separation, &loading, (0.0, 0.0))?;
        Ok(Self {
            points,
            influence: Influence::Dense(Arc::new(influence)),
            separation,
            loading,
            rigid,
            assembly_seconds: 0.0,
            body_edges: (false, false),
            folding: None,
            groups: Some(Arc::new(Vec::new())),
            edge: EdgeLaw::Cells,
        })
    }

    /// The candidate points.
    pub fn points(&self) -> &PointSet {
        &self.points
    }

    /// The influence matrix S (length per force), N x N, or `None` for a
    /// matrix-free problem ([`ContactProblem::lattice`]); for a folded
    /// problem ([`ContactProblem::symmetric`]) the folded matrix M of the
    /// representatives instead (see [`ContactProblem::folding`]).
    pub fn influence(&self) -> Option<MatRef<'_, f64>> {
        match &self.influence {
            Influence::Dense(s) => Some(Mat::as_ref(s)),
            Influence::Lattice(_) => None,
        }
    }

    /// The elastic deflections `S F` (length) under the forces `forces`
    /// (one per unknown: per point, or per orbit of a folded problem), from
    /// the dense S or the matrix-free operator alike.
    ///
    /// # Errors
    /// [`AnalysisError::SizeMismatch`] when `forces` has another length;
    /// [`AnalysisError::Influence`] when a matrix-free problem's workspace
    /// cannot be allocated.
    pub fn deflection(&self, forces: &[f64]) -> Result<Vec<f64>, AnalysisError> {
        let n = self.influence.len();
        if forces.len() != n {
            return Err(AnalysisError::SizeMismatch {
                field: "forces",
                expected: n,
                found: forces.len(),
            });
        }
        let mut y = vec![0.0; n];
        self.products()?.apply(forces, &mut y);
        Ok(y)
    }

    /// The products `S F` as an [`elcon_lcp::Operator`] (length per force;
    /// one entry per unknown), made once for many applications: a
    /// matrix-free problem's FFT workspace is allocated here, not per
    /// product as [`ContactProblem::deflection`] does.
    ///
    /// # Errors
    /// [`AnalysisError::Influence`] when a matrix-free problem's workspace
    /// cannot be allocated.
    pub fn products(&self) -> Result<Products<'_>, AnalysisError> {
        Ok(Products::of(&self.influence)?)
    }

    /// The initial separations eps (length).
    pub fn separation(&self) -> &[f64] {
        &self.separation
    }

    /// The loading.
    pub fn loading(&self) -> Loading {
        self.loading
    }

    /// The same problem under another loading (S is shared, not copied).
    pub fn with_loading(&self, loading: Loading) -> Result<Self, AnalysisError> {
        self.with(self.separation.clone(), loading)
    }

    /// The same problem with other initial separations (length, one per
    /// point; S is shared, not copied): a profile correction added to the
    /// geometry, a design's re-analysis.
    pub fn with_separation(&self, separation: Vec<f64>) -> Result<Self, AnalysisError> {
        self.with(separation, self.loading)
    }

    fn with(&self, separation: Vec<f64>, loading: Loading) -> Result<Self, AnalysisError> {
        // Validate through from_parts' checks without copying S.
        let rigid = check(&self.points, &separation, &loading, self.rigid.load_point)?;
        let rigid = match &self.folding {
            Some(f) => {
                let groups = std::slice::from_ref(f.as_ref());
                match symmetric_rigid(groups, &self.points, &separation, &rigid) {
                    Some((_, rigid)) => rigid,
                    None => {
                        return Err(AnalysisError::Incompatible {
                            field: "separation",
                            reason: format!(
                                "the separations or the loading break the symmetry ({}) the problem \
                                 was folded with; build it with ContactProblem::new to solve it in full",
                                f.group()
                            ),
                        });
                    }
                }
            }
            None => {
                // A matrix-free problem holds no orbits; its bodies are
                // half-spaces and foundations, invariant under every mirror.
                match &self.groups {
                    Some(groups) => symmetric_rigid(groups, &self.points, &separation, &rigid)
                        .map_or(rigid, |(_, r)| r),
                    None => unfolded_rigid(&self.points, &[], &separation, rigid),
                }
            }
        };
        Ok(Self {
            points: self.points.clone(),
            influence: self.influence.clone(),
            separation,
            loading,
            rigid,
            assembly_seconds: self.assembly_seconds,
            body_edges: self.body_edges,
            folding: self.folding.clone(),
            groups: self.groups.clone(),
            edge: self.edge,
        })
    }

    /// The rigid-body unknowns of the loading: which motions are free (the
    /// border of the engine's problem), prescribed, or zero by symmetry.
    pub fn rigid(&self) -> &Rigid {
        &self.rigid
    }

    /// The rigid-body unknowns of the loading before symmetry drops any:
    /// what a change of the separations (a design's correction, which may
    /// break the symmetry) has to keep free.
    pub fn rigid_without_symmetry(&self) -> Result<Rigid, AnalysisError> {
        Rigid::of(&self.loading, &self.points, self.rigid.load_point)
    }

    /// Declares that the candidate zone's extent along x (`along_x`), resp.
    /// y (`along_y`), is the bodies' own: contact that reaches those edges
    /// (a beam's ends, a roller's ends, a punch's rim) is real, not cut off
    /// by the zone, and raises no [`Warning::ContactAtEdge`]. By default
    /// every edge of the zone is an open one.
    pub fn with_body_edges(mut self, along_x: bool, along_y: bool) -> Self {
        self.body_edges = (along_x, along_y);
        self
    }

    /// The edges declared by [`ContactProblem::with_body_edges`].
    pub fn body_edges(&self) -> (bool, bool) {
        self.body_edges
    }

    /// Seconds spent assembling S and eps.
    pub fn assembly_seconds(&self) -> f64 {
        self.assembly_seconds
    }

    /// Solves starting from the contact set of `previous` (a solution of a
    /// similar problem: the previous load step, a neighbouring design), as
    /// `options.warm_start`. Block principal pivoting then starts from that
    /// set (on Hertz spheres, a load step from 90 to 100 lb is tested to take
    /// at most three iterations and fewer than a cold start); the tableau
    /// methods start from their usual basis (the option does not apply to
    /// them).
    /// The answer does not depend on the start.
    ///
    /// # Errors
    /// As [`ContactProblem::solve`]; a `previous` with another number of
    /// points is [`AnalysisError::SizeMismatch`].
    pub fn solve_from(
        &self,
        previous: &ContactSolution,
        method: Method,
        options: &Options,
    ) -> Result<ContactSolution, AnalysisError> {
        let n = self.points.len();
        if previous.forces.len() != n {
            return Err(AnalysisError::SizeMismatch {
                field: "previous.forces",
                expected: n,
                found: previous.forces.len(),
            });
        }
        let start: Vec<bool> = match &self.folding {
            Some(f) => (0..f.len())
                .map(|a| previous.forces[f.rep(a)] > 0.0)
                .collect(),
            None => previous.forces.iter().map(|&f| f > 0.0).collect(),
        };
        let mut options = options.clone();
        options.warm_start = Some(start);
        self.solve(method, &options)
    }

    /// Solves with the engine's `method`; the solution carries the
    /// certificate computed from the original S, eps and P.
    pub fn solve(
        &self,
        method: Method,
        options: &Options,
    ) -> Result<ContactSolution, AnalysisError> {
        let start = Instant::now();
        // The unknowns: every point, or one representative per orbit of a
        // folded problem, whose rows are scaled by 1 / s_a (docs of
        // `elcon_influence::Folding`): w_a = Y_a / s_a, and the equilibrium
        // row by 1 / |G|, which keeps [B; D] and [C D] a skew pair.
        let n = self.influence.len();
        let scale = |a: usize| self.folding.as_ref().map_or(1.0, |f| f.stabilizer(a));
        let order = self.folding.as_ref().map_or(1.0, |f| f.order() as f64);
        let rep = |a: usize| self.folding.as_ref().map_or(a, |f| f.rep(a));
        // The bordered form: q the separations shifted by the prescribed
        // rigid motions, a column per free motion (its lever; 1 for the
        // approach), each scaled by 1 / s_a when folded, and the resultants
        // (load, moments) over |G|.
        let rigid = &self.rigid;
        // Unfolded with no prescribed motion, q is eps itself: borrowed.
        let q = if self.folding.is_none() && rigid.prescribed.is_empty() {
            None
        } else {
            Some(Col::from_fn(n, |a| {
                let k = rep(a);
                (self.separation[k] + rigid.shift(point(&self.points, k))) / scale(a)
            }))
        };
        let q = q
            .as_ref()
            .map_or(ColRef::from_slice(&self.separation), Col::as_ref);
        let border = Mat::<f64>::from_fn(n, rigid.free.len(), |a, j| {
            rigid.free[j]
                .0
                .lever(point(&self.points, rep(a)), rigid.load_point)
                / scale(a)
        });
        let resultant = Col::from_fn(rigid.free.len(), |j| rigid.free[j].1 / order);
        let sol = match &self.influence {
            Influence::Dense(s) => BorderedLcpRef::new(Mat::as_ref(s), q)?
                .with_border(border.as_ref(), resultant.as_ref())?
                .solve(method, options)?,
            Influence::Lattice(_) => {
                let products = self.products()?;
                OperatorLcp::new(&products, q)?
                    .with_border(border.as_ref(), resultant.as_ref())?
                    .solve(method, options)?
            }
        };
        // The engine's border is not needed any more: at a million points
        // every column is 8 MB.
        drop(border);
        let elcon_lcp::LcpSolution {
            z,
            w,
            u,
            certificate,
            statistics,
            ..
        } = sol;
        let lambda: Vec<f64> = u.iter().copied().collect();
        // The gaps are the engine's w = M z - B λ + q, computed from the data
        // above: Y = S F + eps - (rigid motion); folded, row a is scaled by
        // 1 / s_a, so w_a = Y_a / s_a (the same sums regrouped) and
        // Y_a = s_a w_a, exactly (s_a is a power of two).
        let z = into_vec(z);
        let w = into_vec(w);
        let (forces, gaps, slack) = match &self.folding {
            Some(f) => {
                let folded_gaps: Vec<f64> = (0..n).map(|a| scale(a) * w[a]).collect();
                (f.unfold(&z), f.unfold(&folded_gaps), Some(f.unfold(&w)))
            }
            None => (z, w, None),
        };
        let engine = Engine {
            forces,
            gaps,
            slack,
            lambda,
            certificate,
            statistics,
            solve_seconds: start.elapsed().as_secs_f64(),
        };
        Ok(self.finish(engine))
    }

    /// The solution from the engine's answer at every point.
    fn finish(&self, engine: Engine) -> ContactSolution {
        let Engine {
            forces,
            gaps,
            slack,
            lambda,
            certificate,
            statistics,
            solve_seconds,
        } = engine;
        let certificate = &certificate;
        let slack = slack.as_deref().unwrap_or(&gaps);
        let n = self.points.len();
        let pressures: Vec<f64> = (0..n).map(|k| forces[k] / self.points.measure(k)).collect();
        let load: f64 = forces.iter().sum();
        let fmax = forces.iter().fold(0.0f64, |a, f| a.max(*f));
        let contact: Vec<usize> = (0..n).filter(|&k| forces[k] > 0.0).collect();
        let edge_of_contact = crate::edge::Edge::new(&self.points, &pressures, self.edge);
        let contact_measure = edge_of_contact.measure();
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
        let value = |mode| self.rigid.value(mode, &lambda);
        let (x0, y0) = self.rigid.load_point;
        let first_moment =
            |lever: &dyn Fn(usize) -> f64| -> f64 { (0..n).map(|k| forces[k] * lever(k)).sum() };
        let moment_x = first_moment(&|k| self.points.y(k) - y0);
        let moment_y = -first_moment(&|k| self.points.x(k) - x0);
        let centre = |moment: f64| if load > 0.0 { moment / load } else { 0.0 };
        ContactSolution {
            forces,
            pressures,
            gaps,
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
            certificate: ContactCertificate::from_engine(certificate),
            statistics,
            assembly_seconds: self.assembly_seconds,
            solve_seconds,
            warnings,
        }
    }
}

/// A column's values as a vector (the column is freed).
fn into_vec(col: Col<f64>) -> Vec<f64> {
    col.iter().copied().collect()
}

/// The engine's answer at every point, before the solution's reading.
struct Engine {
    forces: Vec<f64>,
    gaps: Vec<f64>,
    /// The engine's w at every point (the gap, or for a folded problem the
    /// gap over its orbit's s_a): the scaling the certificate's `w_scale`
    /// measures. `None` when unfolded: then it is `gaps`.
    slack: Option<Vec<f64>>,
    /// The free rigid motions, in the order of `Rigid::free`.
    lambda: Vec<f64>,
    certificate: Certificate,
    statistics: Statistics,
    solve_seconds: f64,
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

/// What a problem will be, decided before its O(N^2) assembly: the
/// initial separations, the rigid unknowns and, when folded, the orbits.
/// [`ContactProblem::new`] and [`ContactProblem::symmetric`] build on it;
/// a caller estimating a problem's memory and time reads it without
/// assembling anything.
#[derive(Debug, Clone)]
pub struct Layout {
    /// The initial separations eps (length), one per point.
    pub separation: Vec<f64>,
    /// The rigid unknowns: free (the border's columns), prescribed, and
    /// dropped by symmetry.
    pub rigid: Rigid,
    /// The orbits the problem is folded with, if asked and symmetric.
    pub folding: Option<Folding>,
    /// The mirror groups the points and the models respect, largest first.
    pub groups: Vec<Folding>,
}

impl Layout {
    /// The layout of the problem `ContactProblem::new` (`fold` false) or
    /// `ContactProblem::symmetric` (`fold` true) would build from these
    /// arguments, with the same errors.
    pub fn of(
        points: &PointSet,
        bodies: [&Body; 2],
        geometry: &Geometry,
        loading: &Loading,
        fold: bool,
    ) -> Result<Self, AnalysisError> {
        let separation = separations(points, geometry)?;
        let rigid = check(points, &separation, loading, load_point(&bodies))?;
        let groups = Folding::detect_all(points, &bodies);
        let symmetric = symmetric_rigid(&groups, points, &separation, &rigid);
        let (folding, rigid) = match symmetric {
            Some((f, r)) if fold => (Some(f.clone()), r),
            Some((_, r)) => (None, r),
            None => (None, rigid),
        };
        Ok(Self {
            separation,
            rigid,
            folding,
            groups,
        })
    }

    /// The unknowns of the contact solve: one per orbit when folded, else
    /// one per point.
    pub fn unknowns(&self) -> usize {
        self.folding
            .as_ref()
            .map_or(self.separation.len(), |f| f.len())
    }

    /// Whether some point starts in interference: a separation, shifted by
    /// the prescribed motions, below zero (the engine's `q` has a negative
    /// entry).
    pub fn interference(&self, points: &PointSet) -> bool {
        shifted(points, &self.separation, &self.rigid)
            .iter()
            .any(|&q| q < 0.0)
    }
}

/// Checks separations (size, finite) and loading (finite, P > 0) and
/// returns the rigid unknowns of the loading about `load_point`.
fn check(
    points: &PointSet,
    separation: &[f64],
    loading: &Loading,
    load_point: (f64, f64),
) -> Result<Rigid, AnalysisError> {
    let n = points.len();
    if separation.len() != n {
        return Err(AnalysisError::SizeMismatch {
            field: "separation",
            expected: n,
            found: separation.len(),
        });
    }
    if let Some((k, &v)) = separation.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(AnalysisError::NonFinite {
            field: "separation",
            index: k,
            value: v,
        });
    }
    loading.validate()?;
    Rigid::of(loading, points, load_point)
}

/// The point the load acts at: a beam's loaded point, else the origin.
fn load_point(bodies: &[&Body]) -> (f64, f64) {
    bodies
        .iter()
        .find_map(|b| match b.model() {
            Model::Beam { loaded_point, .. } => Some((*loaded_point, 0.0)),
            _ => None,
        })
        .unwrap_or((0.0, 0.0))
}

/// The first of `groups` (largest first) that the separations, shifted by
/// the prescribed motions, and the free rotations respect, with the
/// rotations odd under it dropped (`Rigid::folded`); `None` if none does.
fn symmetric_rigid<'g>(
    groups: &'g [Folding],
    points: &PointSet,
    separation: &[f64],
    rigid: &Rigid,
) -> Option<(&'g Folding, Rigid)> {
    let shifted = shifted(points, separation, rigid);
    groups
        .iter()
        .find_map(|f| respected(f, points, &shifted, rigid).map(|r| (f, r)))
}

/// [`symmetric_rigid`]'s rigid unknowns for a problem solved in full, the
/// groups detected one at a time ([`Folding::detect_each`]) and none kept.
/// The groups are not looked for when none could drop a free motion
/// ([`Rigid::may_drop`]; a group's orbits take about 8.5 bytes a point).
fn unfolded_rigid(points: &PointSet, bodies: &[&Body], separation: &[f64], rigid: Rigid) -> Rigid {
    if !rigid.may_drop() {
        return rigid;
    }
    let shifted = shifted(points, separation, &rigid);
    Folding::detect_each(points, bodies)
        .find_map(|f| respected(&f, points, &shifted, &rigid))
        .unwrap_or(rigid)
}

/// The rigid unknowns with the rotations odd under `group` dropped, when
/// the shifted separations and the free rotations respect it.
fn respected(group: &Folding, points: &PointSet, shifted: &[f64], rigid: &Rigid) -> Option<Rigid> {
    let folded = rigid.folded(group, points)?;
    group
        .is_invariant(shifted, SYMMETRY_TOLERANCE)
        .then_some(folded)
}

/// The separations shifted by the prescribed rigid motions (what the
/// engine's `q` holds at every point).
fn shifted(points: &PointSet, separation: &[f64], rigid: &Rigid) -> Vec<f64> {
    (0..points.len())
        .map(|k| separation[k] + rigid.shift(point(points, k)))
        .collect()
}

/// Initial separations of a geometry on a point set.
pub fn separations(points: &PointSet, geometry: &Geometry) -> Result<Vec<f64>, AnalysisError> {
    let n = points.len();
    match geometry {
        Geometry::Surfaces(s1, s2) => {
            s1.validate("surface1.radius", points.dimension())?;
            s2.validate("surface2.radius", points.dimension())?;
            Ok((0..n)
                .map(|k| {
                    let (x, y) = (points.x(k), points.y(k));
                    s1.height(x, y) + s2.height(x, y)
                })
                .collect())
        }
        Geometry::Separation(eps) => {
            if eps.len() != n {
                return Err(AnalysisError::SizeMismatch {
                    field: "separation",
                    expected: n,
                    found: eps.len(),
                });
            }
            Ok(eps.clone())
        }
    }
}
