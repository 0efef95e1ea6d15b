//! `[units]`: the labels of a consistent unit system, repeated in every
//! output and never used in arithmetic.

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::UnitsToml;

/// The unit labels of a scene (any consistent system; the labels are
/// repeated in every output, never used in arithmetic), each read through
/// its accessor.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Units {
    length: String,
    force: String,
    pressure: String,
    intensity: String,
}

impl Units {
    /// Length, e.g. "in", "m", "mm".
    pub fn length(&self) -> &str {
        &self.length
    }

    /// Force, e.g. "lbf", "N".
    pub fn force(&self) -> &str {
        &self.force
    }

    /// Stress and pressure (default `force/length^2`), e.g. "psi", "Pa", "MPa".
    pub fn pressure(&self) -> &str {
        &self.pressure
    }

    /// The unit of the load intensity F_k / A_k: the pressure unit, or
    /// `force/length` on a beam.
    pub fn intensity(&self) -> &str {
        &self.intensity
    }
}

pub(super) fn units(ctx: &Ctx<'_>, u: &UnitsToml, beam: bool) -> Result<Units, SceneError> {
    for (v, field) in [(&u.length, "units.length"), (&u.force, "units.force")] {
        if v.get_ref().trim().is_empty() {
            return Err(ctx.invalid(v.span(), field, "\"\"", "must name the unit"));
        }
    }
    let length = u.length.get_ref().clone();
    let force = u.force.get_ref().clone();
    let pressure = u
        .pressure
        .as_ref()
        .map_or_else(|| format!("{force}/{length}^2"), |p| p.get_ref().clone());
    let intensity = if beam {
        format!("{force}/{length}")
    } else {
        pressure.clone()
    };
    Ok(Units {
        length,
        force,
        pressure,
        intensity,
    })
}
