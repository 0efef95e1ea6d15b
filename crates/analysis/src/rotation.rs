//! Whether a moment-loaded answer lies within the small-rotation theory
//! the contact model rests on: the rigid rotation of body 1 enters the gap
//! linearized, `y_k = ... + theta_x y_k - theta_y x_k`, valid for rotations
//! of a few hundredths of a radian, and the candidate zone must hold the
//! contact so that the bodies, not the zone's edge, balance the moment.
//!
//! Scenes and Python refuse an answer that fails [`small_rotation`]; a
//! prescribed tilt or misalignment is bounded by [`MAX_ROTATION`] when it
//! is given.

use crate::contact::{ContactSolution, Warning};
use crate::loading::{Loading, Tilt};

/// The largest rotation (rad) of the small-rotation theory: a prescribed
/// tilt or misalignment, and a solved one under a moment.
pub const MAX_ROTATION: f64 = 0.1;

/// Why a moment-loaded answer lies outside the small-rotation theory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RotationRefusal {
    /// The solved rotation exceeds [`MAX_ROTATION`] (rad).
    Beyond {
        /// The larger solved rotation, about x or y (rad).
        rotation: f64,
    },
    /// The contact reaches the candidate zone's edge: the zone, not the
    /// bodies, balances the moment.
    AtEdge {
        /// The larger solved rotation, about x or y (rad).
        rotation: f64,
    },
    /// A prescribed tilt pushes the contact against the candidate zone's
    /// edge: the zone, not the bodies, ends the contact, and the answer
    /// (peak, approach) depends on where the zone ends.
    TiltAtEdge {
        /// The larger prescribed tilt, about x or y (rad).
        tilt: f64,
    },
}

impl std::fmt::Display for RotationRefusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // Four significant digits, shown plainly (0.04457, 3.467).
        let short = |r: f64| -> f64 { format!("{r:.3e}").parse().unwrap_or(r) };
        match *self {
            RotationRefusal::Beyond { rotation } => write!(
                f,
                "the moment turns the body by {} rad, beyond the small-rotation theory's \
                 {MAX_ROTATION} rad (the rigid rotation is linearized)",
                short(rotation)
            ),
            RotationRefusal::AtEdge { rotation } => write!(
                f,
                "the moment pushes the contact against the candidate zone's edge (a rotation \
                 of {} rad): the zone's edge, not the bodies, balances it, and the answer \
                 depends on where the zone ends",
                short(rotation)
            ),
            RotationRefusal::TiltAtEdge { tilt } => {
                return write!(
                    f,
                    "the prescribed tilt of {} rad pushes the contact against the candidate \
                     zone's edge: the zone's edge, not the bodies, ends the contact, and the \
                     answer depends on where the zone ends. Give a smaller tilt, or a larger zone",
                    short(tilt)
                );
            }
        }?;
        f.write_str(
            ". The load centre (the moment over the load) must lie well inside the contact: \
             give a smaller moment, or a larger zone",
        )
    }
}

/// Checks a solution of a problem under `loading`: when a moment is given
/// about x or y, its solved rotation must be within [`MAX_ROTATION`] and
/// the contact clear of the zone's open edge; under a prescribed tilt
/// (bounded where it is given) the contact must be clear of that edge too.
/// Without a moment or a tilt it always holds.
///
/// # Errors
/// The [`RotationRefusal`] that says why.
pub fn small_rotation(
    loading: &Loading,
    solution: &ContactSolution,
) -> Result<(), RotationRefusal> {
    let moment = |t: Tilt| matches!(t, Tilt::Free { moment } if moment != 0.0);
    let at_edge = solution
        .warnings
        .iter()
        .any(|w| matches!(w, Warning::ContactAtEdge { .. }));
    if !moment(loading.tilt_x) && !moment(loading.tilt_y) {
        let tilt =
            (loading.tilt_x.prescribed_angle().abs()).max(loading.tilt_y.prescribed_angle().abs());
        return if tilt > 0.0 && at_edge {
            Err(RotationRefusal::TiltAtEdge { tilt })
        } else {
            Ok(())
        };
    }
    let rotation = solution.tilt_x.abs().max(solution.tilt_y.abs());
    if !(rotation <= MAX_ROTATION) {
        return Err(RotationRefusal::Beyond { rotation });
    }
    if at_edge {
        return Err(RotationRefusal::AtEdge { rotation });
    }
    Ok(())
}
