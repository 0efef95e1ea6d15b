//! The rigid-body unknowns of a contact problem and the border they give
//! the engine's problem (`elcon_lcp::BorderedLcpRef`).
//!
//! Each rigid motion of body 1 (the approach and the two rotations about
//! the load point, `crate::loading`) moves the gap at point k by its lever
//! `m_k`: 1 for the approach, `y_k - y0` for `θ_x`, `-(x_k - x0)` for `θ_y`.
//! A prescribed motion shifts the separations, `eps_k - value m_k`; a free
//! one is a column `m` of the border `B` in `Y = S F + eps - B λ`, with its
//! resultant (the load, a moment) in `B^T F = b`.
//!
//! Folded by a mirror group (`elcon_influence::Folding`), a free mode whose
//! lever is the same on every orbit stays a column (`m_a / s_a` at each
//! representative); one whose lever sums to zero on every orbit (odd under
//! a reflection) has a zero moment from every symmetric force and a zero
//! rotation at the symmetric solution: with a zero moment it drops out, and
//! with another the problem is not symmetric under that group.

use elcon_influence::{Dimension, Folding, PointSet};

use crate::AnalysisError;
use crate::loading::{Loading, Normal, Tilt};

/// Levers equal (or summing to zero) to this fraction of their largest
/// magnitude count as symmetric (they come from mirrored coordinates).
const LEVER_SYMMETRY: f64 = 1e-14;

/// A rigid-body motion of body 1 toward body 2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RigidMode {
    /// The approach `alpha` (lever 1; resultant the load P).
    Approach,
    /// The rotation `θ_x` about the x axis through the load point (lever
    /// `y - y0`; resultant the moment `M_x`).
    TiltX,
    /// The rotation `θ_y` about the y axis through the load point (lever
    /// `-(x - x0)`; resultant the moment `M_y`).
    TiltY,
}

impl RigidMode {
    /// Whether the lever is the same at every point (the approach's 1):
    /// its column needs no points and any group leaves it invariant.
    pub fn is_uniform(self) -> bool {
        self == RigidMode::Approach
    }

    /// The lever of this motion at `(x, y)` about the load point `(x0, y0)`.
    pub fn lever(self, (x, y): (f64, f64), (x0, y0): (f64, f64)) -> f64 {
        match self {
            RigidMode::Approach => 1.0,
            RigidMode::TiltX => y - y0,
            RigidMode::TiltY => -(x - x0),
        }
    }
}

/// The rigid-body unknowns of a problem: which are free (the border's
/// columns, in order, with their resultants), which are prescribed, and
/// which free ones are zero without being unknowns (dropped by symmetry,
/// or absent: a line's rotation about its own axis).
#[derive(Debug, Clone, PartialEq)]
pub struct Rigid {
    /// The point the moments are taken about and the rotations act
    /// around: a beam's loaded point, else the origin.
    pub load_point: (f64, f64),
    /// The free motions (the border's columns) and their resultants.
    pub free: Vec<(RigidMode, f64)>,
    /// The prescribed motions and their values.
    pub prescribed: Vec<(RigidMode, f64)>,
    /// Free motions that are zero at the solution without being unknowns.
    pub dropped: Vec<RigidMode>,
}

impl Rigid {
    /// The rigid unknowns of `loading` on `points` about `load_point`. A
    /// line has one rotation (`θ_y`); `θ_x` must then be free without a
    /// moment. A free rotation whose lever is zero at every point carries
    /// nothing: dropped without a moment, an error with one. (On a line
    /// `θ_x` may also be prescribed zero, as [`Loading::aligned`] does.)
    pub(crate) fn of(
        loading: &Loading,
        points: &PointSet,
        load_point: (f64, f64),
    ) -> Result<Self, AnalysisError> {
        let mut rigid = Self {
            load_point,
            free: Vec::new(),
            prescribed: Vec::new(),
            dropped: Vec::new(),
        };
        match loading.normal {
            Normal::Load(p) => rigid.free.push((RigidMode::Approach, p)),
            Normal::Approach(a) => rigid.prescribed.push((RigidMode::Approach, a)),
        }
        let line = points.dimension() == Dimension::Line;
        for (mode, tilt, field) in [
            (RigidMode::TiltX, loading.tilt_x, "moment_x"),
            (RigidMode::TiltY, loading.tilt_y, "moment_y"),
        ] {
            if line && mode == RigidMode::TiltX {
                if !(tilt.is_free_without_moment() || tilt == (Tilt::Prescribed { angle: 0.0 })) {
                    return Err(AnalysisError::Incompatible {
                        field: if matches!(tilt, Tilt::Free { .. }) {
                            "moment_x"
                        } else {
                            "tilt_x"
                        },
                        reason:
                            "a line contact has one rotation, about the y axis (tilt_y, moment_y)"
                                .into(),
                    });
                }
                rigid.dropped.push(mode);
                continue;
            }
            match tilt {
                Tilt::Prescribed { angle } => rigid.prescribed.push((mode, angle)),
                Tilt::Free { moment } => {
                    let carries =
                        (0..points.len()).any(|k| mode.lever(point(points, k), load_point) != 0.0);
                    if carries {
                        rigid.free.push((mode, moment));
                    } else if moment == 0.0 {
                        rigid.dropped.push(mode);
                    } else {
                        return Err(AnalysisError::Incompatible {
                            field,
                            reason: "every candidate point lies on the axis of this rotation, so no contact force can balance the moment".into(),
                        });
                    }
                }
            }
        }
        Ok(rigid)
    }

    /// The shift of the separation at `(x, y)` by the prescribed motions:
    /// `-sum value m(x, y)`.
    pub(crate) fn shift(&self, at: (f64, f64)) -> f64 {
        -self
            .prescribed
            .iter()
            .map(|&(mode, value)| value * mode.lever(at, self.load_point))
            .sum::<f64>()
    }

    /// Whether [`Rigid::folded`] could drop a free motion under some group:
    /// only a rotation without a moment can be (the approach's lever is 1
    /// everywhere, and a motion with a resultant is kept or refuses the
    /// group). Without one, no group changes the free motions.
    pub(crate) fn may_drop(&self) -> bool {
        self.free
            .iter()
            .any(|&(mode, resultant)| !mode.is_uniform() && resultant == 0.0)
    }

    /// The rigid unknowns of the problem folded by `folding`, or `None`
    /// when a free motion with a non-zero resultant is not symmetric under
    /// it (see the module documentation).
    pub(crate) fn folded(&self, folding: &Folding, points: &PointSet) -> Option<Self> {
        let mut rigid = self.clone();
        rigid.free.clear();
        for &(mode, resultant) in &self.free {
            if mode.is_uniform() {
                rigid.free.push((mode, resultant));
                continue;
            }
            let levers = points.map_positions(|at| mode.lever(at, self.load_point));
            let scale = levers.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if folding.is_invariant(&levers, LEVER_SYMMETRY) {
                rigid.free.push((mode, resultant));
            } else if resultant == 0.0
                && (0..folding.len()).all(|a| {
                    let sum: f64 = folding.orbit(a).map(|k| levers[k]).sum();
                    sum.abs() <= LEVER_SYMMETRY * scale
                })
            {
                rigid.dropped.push(mode);
            } else {
                return None;
            }
        }
        Some(rigid)
    }

    /// The value of `mode` at the solution: free ones from the engine's
    /// `lambda` (in the order of [`Rigid::free`]), prescribed ones as
    /// given, dropped ones 0.
    pub(crate) fn value(&self, mode: RigidMode, lambda: &[f64]) -> f64 {
        if let Some(i) = self.free.iter().position(|&(m, _)| m == mode) {
            return lambda[i];
        }
        self.prescribed
            .iter()
            .find(|&&(m, _)| m == mode)
            .map_or(0.0, |&(_, v)| v)
    }
}

/// Point `k` as `(x, y)`.
pub(crate) fn point(points: &PointSet, k: usize) -> (f64, f64) {
    (points.x(k), points.y(k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_prescribed_and_dropped_motions() {
        let points = PointSet::grid_disk(0.25, 1.0).unwrap();
        let loading = Loading::load(2.0).with_moment_y(0.5).with_tilt_x(1e-3);
        let rigid = Rigid::of(&loading, &points, (0.0, 0.0)).unwrap();
        assert_eq!(
            rigid.free,
            vec![(RigidMode::Approach, 2.0), (RigidMode::TiltY, 0.5)]
        );
        assert_eq!(rigid.prescribed, vec![(RigidMode::TiltX, 1e-3)]);
        // The prescribed θ_x lowers the gap where y > 0.
        assert_eq!(rigid.shift((0.3, 0.5)), -1e-3 * 0.5);
        // A line drops θ_x, and refuses a moment about x.
        let line = PointSet::line(-1.0, 1.0, 9).unwrap();
        let rigid = Rigid::of(&Loading::load(1.0), &line, (0.0, 0.0)).unwrap();
        assert_eq!(rigid.dropped, vec![RigidMode::TiltX]);
        let e = Rigid::of(&Loading::load(1.0).with_moment_x(1.0), &line, (0.0, 0.0)).unwrap_err();
        assert!(e.to_string().contains("moment_x"), "{e}");
    }

    #[test]
    fn only_a_free_rotation_without_a_moment_may_be_dropped() {
        let points = PointSet::grid_disk(0.25, 1.0).unwrap();
        let of = |loading: Loading| Rigid::of(&loading, &points, (0.0, 0.0)).unwrap();
        assert!(of(Loading::load(1.0)).may_drop());
        assert!(!of(Loading::load(1.0).with_moment_y(0.5).with_tilt_x(0.0)).may_drop());
        assert!(!of(Loading::load(1.0).aligned()).may_drop());
        // Every group leaves such motions as they are.
        for loading in [
            Loading::load(1.0).aligned(),
            Loading::load(1.0).with_moment_y(0.5).with_tilt_x(0.0),
        ] {
            let rigid = of(loading);
            for folding in Folding::detect_all(&points, &[]) {
                if let Some(folded) = rigid.folded(&folding, &points) {
                    assert_eq!((folded.free, folded.dropped), (rigid.free.clone(), vec![]));
                }
            }
        }
    }

    #[test]
    fn folding_keeps_even_motions_and_drops_odd_ones_without_a_moment() {
        let points = PointSet::grid_disk(0.25, 1.0).unwrap();
        let folding = Folding::detect(&points, &[]).expect("a disk grid is symmetric");
        let rigid = Rigid::of(&Loading::load(1.0), &points, (0.0, 0.0)).unwrap();
        let folded = rigid.folded(&folding, &points).unwrap();
        assert_eq!(folded.free, vec![(RigidMode::Approach, 1.0)]);
        assert_eq!(folded.dropped, vec![RigidMode::TiltX, RigidMode::TiltY]);
        // A moment about y: not symmetric under the mirror about x = 0.
        let moment =
            Rigid::of(&Loading::load(1.0).with_moment_y(0.1), &points, (0.0, 0.0)).unwrap();
        assert!(moment.folded(&folding, &points).is_none());
    }
}
