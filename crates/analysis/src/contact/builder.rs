//! How a contact problem holds its influence matrix `S = A(1) + A(2)`
//! ([`Storage`]), decided in one place: [`ProblemBuilder`] (from
//! [`ContactProblem::builder`]) resolves [`Storage::Auto`], plans the
//! problem before its O(N^2) assembly (the storage, the method, the
//! unknowns and what the solve will cost: [`Plan`]) and builds it.
//!
//! A dense S costs `8 N^2` bytes and an exact method about `N^3` flops; a
//! folded S (a mirror-symmetric problem, one unknown per orbit) a quarter
//! or an eighth of that; the matrix-free lattice operator O(N) memory and
//! the conjugate gradient O(N log N) a product. [`Storage::Auto`] (the
//! default) folds a symmetric problem; above [`AUTO_DENSE_LIMIT`] unknowns
//! (after folding) it holds S matrix-free when the points are a lattice and
//! no body is a beam, unless the method asked for reads S's entries; else
//! it holds S dense. Asked for the conjugate gradient, it holds S
//! matrix-free whenever the lattice operator applies, unless the problem
//! folds to at most [`AUTO_DENSE_LIMIT`] unknowns (a small folded S is
//! cheaper dense; a large one's N^2 products cost more than the lattice's).

use std::sync::Arc;
use std::time::Instant;

use elcon_influence::{Body, LatticeKernel, LatticeOperator, PointSet, assemble, assemble_folded};
use elcon_lcp::Method;
use faer::Mat;

use super::geometry::{Geometry, separations};
use super::layout::{Layout, check, load_point, unfolded_rigid};
use super::problem::ContactProblem;
use crate::AnalysisError;
use crate::edge::EdgeLaw;
use crate::estimate::{Estimate, Tableau};
use crate::influence::Influence;
use crate::loading::{Loading, Normal};
use crate::storage::{AUTO_DENSE_LIMIT, Storage};

/// A contact problem, decided before it is built: the storage (resolved),
/// the method it will be solved by, and what the solve will cost.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// How S will be held: never [`Storage::Auto`]; [`Storage::Folded`]
    /// only when the problem does fold.
    pub storage: Storage,
    /// The method: the one asked for ([`ProblemBuilder::method`]), or the
    /// storage's default ([`Storage::default_method`]).
    pub method: Method,
    /// What the solve will cost.
    pub estimate: Estimate,
}

/// Builds a [`ContactProblem`]: the points, the two bodies, the geometry
/// and the loading, with how S is held ([`Storage`], default
/// [`Storage::Auto`]), the method it will be solved by (if the caller
/// knows), and the zone's edges that are the bodies' own.
///
/// ```
/// use elcon_analysis::{Body, ContactProblem, Geometry, Loading, Material, PointSet, Storage, Surface};
///
/// let steel = Material::new(210e3, 0.3).unwrap();
/// let body = Body::uniform_patch(steel);
/// let geometry = Geometry::Surfaces(Surface::Sphere { radius: 10.0 }, Surface::Plane);
/// let points = PointSet::grid_disk(0.05, 0.4).unwrap();
/// let builder = ContactProblem::builder(points, &body, &body, &geometry, Loading::load(100.0));
/// // Symmetric about both axes: Auto folds it, an eighth of the unknowns.
/// let plan = builder.plan().unwrap();
/// assert_eq!(plan.storage, Storage::Folded);
/// let problem = builder.build().unwrap();
/// let solution = problem.solve(plan.method, &Default::default()).unwrap();
/// assert!(solution.certificate.holds());
/// ```
#[derive(Debug, Clone)]
pub struct ProblemBuilder<'a> {
    points: PointSet,
    bodies: [&'a Body; 2],
    geometry: &'a Geometry,
    loading: Loading,
    storage: Storage,
    method: Option<Method>,
    fold: bool,
    body_edges: (bool, bool),
}

/// The storage's shorthands, each
/// `ContactProblem::builder(..).storage(storage).build()`.
macro_rules! stored {
    ($($(#[doc = $doc:literal])+ $name:ident => $storage:ident;)+) => {
        impl ContactProblem {
            $(
                $(#[doc = $doc])+
                pub fn $name(
                    points: PointSet,
                    body1: &Body,
                    body2: &Body,
                    geometry: &Geometry,
                    loading: Loading,
                ) -> Result<Self, AnalysisError> {
                    Self::builder(points, body1, body2, geometry, loading)
                        .storage(Storage::$storage)
                        .build()
                }
            )+
        }
    };
}

stored! {
    /// The problem with S dense and unfolded:
    /// `ContactProblem::builder(..).storage(Storage::Dense).build()`.
    new => Dense;
    /// The problem folded when it is mirror symmetric, dense otherwise:
    /// `ContactProblem::builder(..).storage(Storage::Folded).build()`.
    symmetric => Folded;
    /// The problem with S matrix-free:
    /// `ContactProblem::builder(..).storage(Storage::Lattice).build()`.
    lattice => Lattice;
}

impl ContactProblem {
    /// A [`ProblemBuilder`] for the problem of `body1` and `body2` on
    /// `points`, with the initial separations of `geometry`, under
    /// `loading`.
    pub fn builder<'a>(
        points: PointSet,
        body1: &'a Body,
        body2: &'a Body,
        geometry: &'a Geometry,
        loading: Loading,
    ) -> ProblemBuilder<'a> {
        ProblemBuilder {
            points,
            bodies: [body1, body2],
            geometry,
            loading,
            storage: Storage::Auto,
            method: None,
            fold: true,
            body_edges: (false, false),
        }
    }

    /// A problem from an influence matrix (N x N, length per force) and
    /// separations (N, length) built elsewhere, held dense; moments and
    /// rotations are about the origin.
    ///
    /// # Errors
    /// [`AnalysisError::SizeMismatch`] when S is not N x N,
    /// [`AnalysisError::NonFiniteEntry`] at S's first entry (by rows) that
    /// is NaN or infinite, and the checks of the separations and the
    /// loading every problem has.
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
        if let Some((row, column, value)) = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| (i, j, influence[(i, j)]))
            .find(|(_, _, v)| !v.is_finite())
        {
            return Err(AnalysisError::NonFiniteEntry {
                field: "influence",
                row,
                column,
                value,
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
}

impl<'a> ProblemBuilder<'a> {
    /// How S is to be held (default [`Storage::Auto`]).
    pub fn storage(mut self, storage: Storage) -> Self {
        self.storage = storage;
        self
    }

    /// The method the problem will be solved by: [`Storage::Auto`] then
    /// holds S's entries for a pivoting method and goes matrix-free for the
    /// conjugate gradient where it can. Default: none given, the storage's
    /// own ([`Storage::default_method`]).
    pub fn method(mut self, method: Method) -> Self {
        self.method = Some(method);
        self
    }

    /// Whether a mirror-symmetric problem may be folded (default true).
    /// With false, [`Storage::Auto`] never folds and [`Storage::Folded`] is
    /// [`Storage::Dense`].
    pub fn fold(mut self, fold: bool) -> Self {
        self.fold = fold;
        self
    }

    /// The candidate zone's extents that are the bodies' own (see
    /// [`ContactProblem::with_body_edges`]).
    pub fn body_edges(mut self, along_x: bool, along_y: bool) -> Self {
        self.body_edges = (along_x, along_y);
        self
    }

    /// The candidate points.
    pub fn points(&self) -> &PointSet {
        &self.points
    }

    /// The same problem on other points: the bodies, the geometry, the
    /// loading, the storage rule, the method, the folding and the body
    /// edges kept.
    pub(super) fn on(&self, points: PointSet) -> Self {
        Self {
            points,
            bodies: self.bodies,
            geometry: self.geometry,
            loading: self.loading,
            storage: self.storage,
            method: self.method,
            fold: self.fold,
            body_edges: self.body_edges,
        }
    }

    /// The points on the bodies' own edges where the pressure is singular
    /// if the contact reaches them, as the built problem's
    /// [`ContactProblem::singular_edge_points`].
    pub(super) fn singular_edge_points(&self) -> Vec<usize> {
        crate::edge::singular_edge_points(&self.points, self.body_edges, EdgeLaw::of(self.bodies))
    }

    /// The geometry the separations come from.
    pub(super) fn geometry(&self) -> &Geometry {
        self.geometry
    }

    /// The problem's [`Layout`] (its separations, rigid unknowns and
    /// symmetry) as the storage asked for would fold it, or the build's
    /// error.
    pub fn layout(&self) -> Result<Layout, AnalysisError> {
        Layout::of(
            &self.points,
            self.bodies,
            self.geometry,
            &self.loading,
            self.folds_if_symmetric(),
        )
    }

    /// Whether the storage asked for folds a symmetric problem.
    fn folds_if_symmetric(&self) -> bool {
        self.fold && matches!(self.storage, Storage::Auto | Storage::Folded)
    }

    /// The storage, the method and the cost of the problem, decided without
    /// assembling anything. A problem that cannot be laid out (the build
    /// will say why) is planned at its worst: every point an unknown, the
    /// general tableau.
    ///
    /// # Errors
    /// [`AnalysisError::Influence`] when [`Storage::Lattice`] is asked for
    /// points or bodies the lattice operator does not take (as the build
    /// would fail).
    pub fn plan(&self) -> Result<Plan, AnalysisError> {
        let layout = self.layout().ok();
        let operator = || LatticeOperator::estimate_bytes(&self.points, &self.bodies);
        let folds = layout.as_ref().is_some_and(|l| l.folding.is_some());
        let unknowns = layout.as_ref().map_or(self.points.len(), Layout::unknowns);
        let lattice_applies = || operator().is_ok();
        let storage = match self.storage {
            // A pivoting method reads S's entries, and a folded problem is
            // smaller dense.
            Storage::Auto => match self.method {
                // The conjugate gradient on a folded S only while that S is
                // small: above the limit its N^2 products cost more than
                // the lattice's FFT products over every point.
                Some(Method::ConjugateGradient)
                    if (!folds || unknowns > AUTO_DENSE_LIMIT) && lattice_applies() =>
                {
                    Storage::Lattice
                }
                None if unknowns > AUTO_DENSE_LIMIT && lattice_applies() => Storage::Lattice,
                _ if folds => Storage::Folded,
                _ => Storage::Dense,
            },
            Storage::Folded if folds => Storage::Folded,
            Storage::Folded | Storage::Dense => Storage::Dense,
            Storage::Lattice => Storage::Lattice,
        };
        let method = self.method.unwrap_or(storage.default_method());
        let estimate = match storage {
            Storage::Lattice => Estimate::matrix_free(storage, method, operator()?, &self.points),
            _ => {
                let symmetric = layout.as_ref().is_some_and(|l| {
                    matches!(self.loading.normal, Normal::Load(_))
                        && l.rigid.free.len() == 1
                        && !l.interference(&self.points)
                });
                let tableau = if symmetric {
                    Tableau::Symmetric
                } else {
                    Tableau::General
                };
                let unknowns = if storage == Storage::Folded {
                    unknowns
                } else {
                    self.points.len()
                };
                Estimate::dense(storage, method, tableau, self.points.len(), unknowns)
            }
        };
        Ok(Plan {
            storage,
            method,
            estimate,
        })
    }

    /// Builds the problem: the separations and the loading validated
    /// before any O(N^2) work, the storage resolved ([`plan`](Self::plan)),
    /// then S assembled (dense or folded) or its lattice operator made.
    ///
    /// # Errors
    /// [`AnalysisError`] naming the field: separations of the wrong size or
    /// not finite, a bad loading, a surface that does not fit the points;
    /// [`AnalysisError::Influence`] when the bodies do not fit the points
    /// or (matrix-free) the points are not a lattice or a body is a beam.
    pub fn build(self) -> Result<ContactProblem, AnalysisError> {
        let storage = match self.storage {
            Storage::Auto => self.plan()?.storage,
            Storage::Folded if !self.fold => Storage::Dense,
            given => given,
        };
        let (along_x, along_y) = self.body_edges;
        let problem = match storage {
            Storage::Lattice => self.lattice()?,
            _ => self.dense(storage == Storage::Folded)?,
        };
        Ok(problem.with_body_edges(along_x, along_y))
    }

    /// The problem with S dense, folded when `fold` and symmetric: the
    /// separations and the loading are validated before the O(N^2)
    /// assembly, then, if asked, the largest symmetry group the separations
    /// (shifted by the prescribed motions) and the free rigid motions
    /// respect too is looked for (`crate::rigid`), and the folded or the
    /// full matrix is assembled.
    fn dense(self, fold: bool) -> Result<ContactProblem, AnalysisError> {
        let start = Instant::now();
        let layout = Layout::of(
            &self.points,
            self.bodies,
            self.geometry,
            &self.loading,
            fold,
        )?;
        let influence = match &layout.folding {
            Some(f) => assemble_folded(&self.points, &self.bodies, f)?,
            None => assemble(&self.points, &self.bodies)?,
        };
        Ok(ContactProblem {
            points: self.points,
            influence: Influence::Dense(Arc::new(influence)),
            separation: layout.separation,
            loading: self.loading,
            rigid: layout.rigid,
            assembly_seconds: start.elapsed().as_secs_f64(),
            body_edges: (false, false),
            folding: layout.folding.map(Arc::new),
            groups: Some(Arc::new(layout.groups)),
            edge: EdgeLaw::of(self.bodies),
        })
    }

    /// The problem with S matrix-free, not folded (a tilt that symmetry
    /// makes zero is still dropped from the unknowns): as
    /// [`Layout::of`] unfolded, the mirror groups tried one at a time and
    /// none kept, since at 10^5 points and more their orbits would outweigh
    /// the operator.
    fn lattice(self) -> Result<ContactProblem, AnalysisError> {
        let start = Instant::now();
        let separation = separations(&self.points, self.geometry)?;
        let rigid = check(
            &self.points,
            &separation,
            &self.loading,
            load_point(&self.bodies),
        )?;
        let rigid = unfolded_rigid(&self.points, &self.bodies, &separation, rigid);
        let operator = LatticeKernel::new(&self.points, &self.bodies)?;
        Ok(ContactProblem {
            points: self.points,
            influence: Influence::Lattice(Arc::new(operator)),
            separation,
            loading: self.loading,
            rigid,
            assembly_seconds: start.elapsed().as_secs_f64(),
            body_edges: (false, false),
            folding: None,
            groups: None,
            edge: EdgeLaw::of(self.bodies),
        })
    }
}
