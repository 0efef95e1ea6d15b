//! Candidate points laid out relative to a Hertz contact, as a scene's
//! `across` and `zone` do.
//!
//! With the Hertz contact radius a (or half-width b on a line), `across`
//! points span the contact's diameter, so the spacing is
//!
//! ```text
//!     h = 2 a / (across - 1)
//! ```
//!
//! and the outermost points of a diameter sit on the Hertz circle; the
//! candidate zone reaches `zone` times a (or b) from the centre. A zone
//! above 1 leaves room for a contact larger than Hertz's (a coarse grid, a
//! misalignment, a load centre off the middle).

use elcon_influence::PointSet;

use crate::AnalysisError;

/// Checks `across` (at least 2) and `zone` (finite, at least 1) and the
/// size (finite, > 0); the spacing `2 size / (across - 1)`.
fn spacing(size: f64, across: usize, zone: f64) -> Result<f64, AnalysisError> {
    if !(size.is_finite() && size > 0.0) {
        return Err(AnalysisError::InvalidInput {
            field: "contact size",
            value: size,
            reason: "the Hertz radius or half-width must be finite and > 0",
        });
    }
    if across < 2 {
        return Err(AnalysisError::InvalidInput {
            field: "across",
            value: across as f64,
            reason: "at least 2 points across the contact",
        });
    }
    if !(zone.is_finite() && zone >= 1.0) {
        return Err(AnalysisError::InvalidInput {
            field: "zone",
            value: zone,
            reason: "the candidate zone must be finite and at least the contact (zone >= 1)",
        });
    }
    Ok(2.0 * size / (across - 1) as f64)
}

/// A square grid on a disk around the origin: `across` points over the
/// diameter of a Hertz contact of radius `contact_radius`, out to
/// `zone * contact_radius` (the scenes' `grid = "disk"` with `across`,
/// `zone`).
///
/// # Errors
/// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the contact
/// size; [`AnalysisError::Influence`] when the grid has too many points.
///
/// ```
/// use elcon_analysis::grid;
/// let points = grid::hertz_disk(0.0134, 21, 1.2).unwrap();
/// // The spacing is 2 a / 20; the outermost points of a diameter lie on the circle.
/// assert!((points.xs().iter().cloned().fold(0.0, f64::max) / 0.0134 - 1.2).abs() < 0.1);
/// ```
pub fn hertz_disk(
    contact_radius: f64,
    across: usize,
    zone: f64,
) -> Result<PointSet, AnalysisError> {
    let h = spacing(contact_radius, across, zone)?;
    Ok(PointSet::grid_disk(h, zone * contact_radius)?)
}

/// Points on a line, centred: `across` over the width `2 half_width` of a
/// Hertz line contact, a whole number of spacings out to about
/// `zone * half_width` on each side (the scenes' `grid = "line"` with
/// `across`, `zone`).
///
/// # Errors
/// As [`hertz_disk`].
pub fn hertz_line(half_width: f64, across: usize, zone: f64) -> Result<PointSet, AnalysisError> {
    let h = spacing(half_width, across, zone)?;
    let m = (zone * half_width / h).round().max(1.0);
    if !(m <= elcon_influence::MAX_POINTS as f64) {
        return Err(AnalysisError::InvalidInput {
            field: "across",
            value: across as f64,
            reason: "more than MAX_POINTS points along the line",
        });
    }
    Ok(PointSet::line(
        -(m + 0.5) * h,
        (m + 0.5) * h,
        2 * m as usize + 1,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spacing_puts_the_outermost_points_of_a_diameter_on_the_circle() {
        let a = 2.0;
        let points = hertz_disk(a, 11, 1.0).unwrap();
        // h = 2 a / 10: points at multiples of 0.4 out to the radius.
        let on_axis: Vec<f64> = (0..points.len())
            .filter(|&k| points.y(k).abs() < 1e-12)
            .map(|k| points.x(k))
            .collect();
        let largest = on_axis.iter().cloned().fold(0.0, f64::max);
        assert!((largest - a).abs() < 1e-12, "{largest}");
        assert_eq!(on_axis.len(), 11);
        let line = hertz_line(1.0, 21, 1.5).unwrap();
        assert_eq!(line.len(), 31);
    }

    #[test]
    fn bad_layouts_name_the_field() {
        for (e, field) in [
            (hertz_disk(1.0, 1, 1.2), "across"),
            (hertz_disk(1.0, 11, 0.5), "zone"),
            (hertz_disk(f64::NAN, 11, 1.2), "contact size"),
            (hertz_line(-1.0, 11, 1.2), "contact size"),
        ] {
            match e {
                Err(AnalysisError::InvalidInput { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: {other:?}"),
            }
        }
    }
}
