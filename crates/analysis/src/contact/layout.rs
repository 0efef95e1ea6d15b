//! What a contact problem will be, decided before its O(N^2) assembly:
//! the initial separations eps, the rigid unknowns of the loading (the
//! border of the engine's problem, `crate::rigid`) and the mirror symmetry
//! the points, the bodies and the shifted separations
//! `eps_k + sum_prescribed value m_k` share (`elcon_influence::Folding`):
//! a free rotation odd under it is zero at the solution and no unknown,
//! and a folded problem has one unknown per orbit.

use std::borrow::Cow;

use elcon_influence::{Body, Folding, Model, PointSet};

use super::geometry::{Geometry, separations};
use crate::AnalysisError;
use crate::loading::Loading;
use crate::rigid::Rigid;

/// Separations equal to this fraction of their largest magnitude count as
/// symmetric (they come from the same formula at mirrored points, so they
/// are equal to rounding).
const SYMMETRY_TOLERANCE: f64 = 1e-14;

/// What a problem will be, decided before its O(N^2) assembly: the
/// initial separations, the rigid unknowns and, when folded, the orbits.
/// [`ProblemBuilder`](super::ProblemBuilder) builds on it, and its
/// [`plan`](super::ProblemBuilder::plan) reads it without assembling
/// anything.
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
    /// The layout of the problem built from these arguments unfolded
    /// (`fold` false) or folded when symmetric (`fold` true), with the
    /// build's errors.
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
pub(crate) fn check(
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
pub(crate) fn load_point(bodies: &[&Body]) -> (f64, f64) {
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
pub(crate) fn symmetric_rigid<'g>(
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
pub(crate) fn unfolded_rigid(
    points: &PointSet,
    bodies: &[&Body],
    separation: &[f64],
    rigid: Rigid,
) -> Rigid {
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
pub(crate) fn respected(
    group: &Folding,
    points: &PointSet,
    shifted: &[f64],
    rigid: &Rigid,
) -> Option<Rigid> {
    let folded = rigid.folded(group, points)?;
    group
        .is_invariant(shifted, SYMMETRY_TOLERANCE)
        .then_some(folded)
}

/// The separations shifted by the prescribed rigid motions (what the
/// engine's `q` holds at every point): borrowed when nothing is
/// prescribed (a shift of zero everywhere).
pub(crate) fn shifted<'s>(
    points: &PointSet,
    separation: &'s [f64],
    rigid: &Rigid,
) -> Cow<'s, [f64]> {
    if rigid.prescribed.is_empty() {
        return Cow::Borrowed(separation);
    }
    let mut q = separation.to_vec();
    points
        .positions()
        .enumerate()
        .for_each(|(k, at)| q[k] += rigid.shift(at));
    Cow::Owned(q)
}
