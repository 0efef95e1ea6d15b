//! [`ContactProblem`]: the candidate points, the influence matrix S as
//! its storage holds it (dense, folded or matrix-free: `crate::influence`),
//! the initial separations eps, the loading and its rigid unknowns; and the
//! same problem under another loading or separation, S shared.
//!
//! What a caller needs of S is offered whatever the storage: the products
//! `S F`, the restricted solve `S_JJ X = R` on a contact set J, S's entries
//! where a method truly reads them (a typed error naming the storage where
//! they are not held), and the method the storage is solved by.

use std::sync::Arc;

use elcon_influence::{Folding, PointSet};
use elcon_lcp::{LinearSolution, Method, Operator, Options, PodBuffer, PodStack};
use faer::MatRef;

use super::layout::{check, symmetric_rigid, unfolded_rigid};
use crate::AnalysisError;
use crate::edge::EdgeLaw;
use crate::influence::{Influence, Products};
use crate::loading::Loading;
use crate::rigid::Rigid;
use crate::storage::Storage;

/// A discrete contact problem: points, influence matrix, separations, loading.
#[derive(Debug, Clone)]
pub struct ContactProblem {
    pub(super) points: PointSet,
    /// Shared between problems that differ only in loading or separation.
    pub(super) influence: Influence,
    pub(super) separation: Vec<f64>,
    pub(super) loading: Loading,
    /// The rigid-body unknowns of `loading` (folded with the problem).
    pub(super) rigid: Rigid,
    pub(super) assembly_seconds: f64,
    pub(super) body_edges: (bool, bool),
    /// The orbits of a mirror-symmetric problem, when it was folded.
    pub(super) folding: Option<Arc<Folding>>,
    /// The mirror groups the points and the models respect, largest first:
    /// a free rotation that is odd under one the separations respect too
    /// is zero at the solution and not an unknown, folded or not. `None`
    /// for a matrix-free problem: its orbits (8.5 bytes a point each) are
    /// found again when a new loading or separation asks.
    pub(super) groups: Option<Arc<Vec<Folding>>>,
    /// How the pressure falls at the contact's edge (crate::edge).
    pub(super) edge: EdgeLaw,
}

impl ContactProblem {
    /// The orbits the problem was folded with ([`ContactProblem::symmetric`]),
    /// or `None` for a problem solved in full.
    pub fn folding(&self) -> Option<&Folding> {
        self.folding.as_deref()
    }

    /// How S is held: [`Storage::Dense`], [`Storage::Folded`] (one unknown
    /// per orbit of a mirror-symmetric problem) or [`Storage::Lattice`]
    /// (matrix-free); never [`Storage::Auto`], which is resolved when the
    /// problem is built.
    pub fn storage(&self) -> Storage {
        self.influence.storage(self.folding.is_some())
    }

    /// The method this problem is solved by when the caller has no
    /// preference: block principal pivoting on a dense or folded S, the
    /// conjugate gradient on a matrix-free one.
    pub fn default_method(&self) -> Method {
        self.storage().default_method()
    }

    /// Whether the problem can be solved by `method`: every method on a
    /// dense or folded S; only the conjugate gradient matrix-free (the
    /// pivoting methods read S's entries).
    ///
    /// # Errors
    /// [`AnalysisError::NeedsEntries`] naming the method when it cannot.
    pub fn check_method(&self, method: Method) -> Result<(), AnalysisError> {
        match method {
            Method::ConjugateGradient => Ok(()),
            _ => self.entries(method.name()).map(|_| ()),
        }
    }

    /// The entries of the matrix the problem holds: S (N x N, length per
    /// force), or for a folded problem the folded matrix of the
    /// representatives (see [`ContactProblem::folding`]). For a method that
    /// reads S's entries (the paper's design program); `what` names it in
    /// the error.
    ///
    /// # Errors
    /// [`AnalysisError::NeedsEntries`] when S is held matrix-free.
    pub fn entries(&self, what: &'static str) -> Result<MatRef<'_, f64>, AnalysisError> {
        self.influence.entries().ok_or(AnalysisError::NeedsEntries {
            what,
            storage: self.storage(),
        })
    }

    /// The candidate points.
    pub fn points(&self) -> &PointSet {
        &self.points
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
        let products = self.products();
        let request = products.apply_scratch();
        let mut scratch = PodBuffer::try_new(request).map_err(|_| {
            AnalysisError::Influence(elcon_influence::InfluenceError::AllocationFailed {
                what: "the product's scratch (an FFT workspace)",
                bytes: request.unaligned_bytes_required(),
            })
        })?;
        let mut y = vec![0.0; n];
        products.apply(forces, &mut y, PodStack::new(&mut scratch));
        Ok(y)
    }

    /// The products `S F` as an [`elcon_lcp::Operator`] (length per force;
    /// one entry per unknown), for many applications: the caller allocates
    /// the scratch they declare ([`Operator::apply_scratch`], a matrix-free
    /// problem's FFT workspace) once and lends it to each, where
    /// [`ContactProblem::deflection`] allocates it per product.
    pub fn products(&self) -> Products<'_> {
        Products::of(&self.influence)
    }

    /// The restricted solve `S_JJ X = R` on the contact set J (`contact`,
    /// point indices) for the right-hand sides R (`rhs`, `|J|` rows): the
    /// derivative of the contact forces while J holds (a design's
    /// sensitivities). Solved and certified by the engine
    /// (`elcon_lcp::LinearSystem`, with `options`' tolerance): dense by a
    /// Cholesky factor of `S_JJ`, matrix-free by the conjugate gradient on
    /// the products; X in force per unit of R's length, with its residual
    /// and the engine's log of attempts.
    ///
    /// # Errors
    /// [`AnalysisError::Incompatible`] for a folded problem (its unknowns
    /// are orbits, not points), an index out of range or `rhs` of another
    /// height; [`AnalysisError::Engine`] when the solve breaks down,
    /// reaches its iteration limit or is not certified, or its memory (a
    /// matrix-free problem's FFT scratch) cannot be allocated.
    pub fn restricted_solve(
        &self,
        contact: &[usize],
        rhs: MatRef<'_, f64>,
        options: &Options,
    ) -> Result<LinearSolution, AnalysisError> {
        if let Some(f) = &self.folding {
            return Err(AnalysisError::Incompatible {
                field: "contact",
                reason: format!(
                    "the problem is folded by its symmetry ({}): its unknowns are orbits, not \
                     points; build it unfolded for a restricted solve",
                    f.group()
                ),
            });
        }
        if rhs.nrows() != contact.len() {
            return Err(AnalysisError::SizeMismatch {
                field: "rhs",
                expected: contact.len(),
                found: rhs.nrows(),
            });
        }
        let n = self.points.len();
        if let Some(&k) = contact.iter().find(|&&k| k >= n) {
            return Err(AnalysisError::Incompatible {
                field: "contact",
                reason: format!("point {k} is out of range (the problem has {n} points)"),
            });
        }
        self.influence.restricted(contact).solve(rhs, options)
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
    /// by the zone, and raises no [`Warning::ContactAtEdge`](super::Warning::ContactAtEdge). By default
    /// every edge of the zone is an open one.
    pub fn with_body_edges(mut self, along_x: bool, along_y: bool) -> Self {
        self.body_edges = (along_x, along_y);
        self
    }

    /// The points on the bodies' own edges (declared by
    /// [`ContactProblem::with_body_edges`]) where an elastic half-space's
    /// pressure becomes singular if the contact reaches them: a roller's
    /// ends, a punch's rim. Contact there makes the peak pressure depend on
    /// the grid (it grows without bound as the grid refines), so a design
    /// that must hold on any grid keeps them out of contact. None on a
    /// foundation or a beam (their pressure is bounded at an edge).
    pub fn singular_edge_points(&self) -> Vec<usize> {
        crate::edge::singular_edge_points(&self.points, self.body_edges, self.edge)
    }

    /// The edges declared by [`ContactProblem::with_body_edges`].
    pub fn body_edges(&self) -> (bool, bool) {
        self.body_edges
    }

    /// Seconds spent assembling S and eps.
    pub fn assembly_seconds(&self) -> f64 {
        self.assembly_seconds
    }
}
