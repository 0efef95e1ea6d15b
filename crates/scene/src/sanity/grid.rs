//! The grids against the contact and the bodies: a grid with too few
//! points across the Hertz contact (or an absolute candidate disk) is
//! refused below [`MIN_POINTS_RESOLVED`] and warned of below
//! [`MIN_POINTS_ACROSS`]; why points relative to the Hertz contact cannot
//! be laid out; and the bodies against every grid they are solved on (a
//! plane-strain datum beyond them, a beam's loaded point on them).

use elcon_analysis::{Geometry, Loading, Normal};
use elcon_influence::{Body, Dimension, Model, PointSet};
use toml::Spanned;

use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::schema::BodyToml;

/// A grid with fewer points than this across the Hertz contact (or the
/// candidate disk) gets a warning.
pub const MIN_POINTS_ACROSS: usize = 5;

/// A grid with fewer points than this across the contact's expected size
/// (the Hertz contact's diameter or width, a candidate disk's diameter) is
/// refused: three points (a centre and one on each side, as
/// `points.across` asks at least) are the fewest that tell the pressure's
/// profile from its mean; with one point the answer is the load over one
/// cell (a flat punch of radius 0.01 on one cell of spacing 1 carried
/// 44.6 times its closed form's load).
pub const MIN_POINTS_RESOLVED: usize = 3;

/// Warnings for a grid too coarse for the contact: fewer than
/// [`MIN_POINTS_ACROSS`] points across the Hertz contact where a closed
/// form gives one, or across an absolute candidate disk.
///
/// `hertz` is the contact's name for its size ("diameter", "width") and
/// its half-size (radius or half-width), where a closed form gives one;
/// `disk` the spacing and radius of an absolute candidate disk.
pub(crate) fn coarse_grid(
    points: &PointSet,
    hertz: Option<(&str, f64)>,
    disk: Option<(f64, f64)>,
) -> Vec<String> {
    let h = points.cell().dx;
    let mut warnings = Vec::new();
    // Points on a size laid out at `size / (n - 1)` count n, not n - 1
    // when the quotient rounds just below n - 1.
    let count =
        |size: f64, spacing: f64| (size / spacing * (1.0 + 8.0 * f64::EPSILON)).floor() + 1.0;
    if let Some((what, a)) = hertz {
        let across = count(2.0 * a, h);
        if across < MIN_POINTS_ACROSS as f64 {
            warnings.push(format!(
                "the grid has about {across:.0} points across the Hertz contact {what} \
                 ({:.4e}, spacing {h:.4e}): fewer than {MIN_POINTS_ACROSS}, so expect an answer far \
                 from Hertz (tens of percent); refine the grid (points.across, or a smaller spacing)",
                2.0 * a
            ));
        }
        return warnings;
    }
    if let Some((spacing, radius)) = disk {
        let across = count(2.0 * radius, spacing);
        if across < MIN_POINTS_ACROSS as f64 {
            warnings.push(format!(
                "the candidate disk has about {across:.0} points across (spacing {spacing} against \
                 radius {radius}), {} in all: too coarse to resolve a contact",
                points.len()
            ));
        }
    }
    warnings
}

/// A grid too coarse to resolve the contact at all: fewer than
/// [`MIN_POINTS_RESOLVED`] points across the contact's expected size (the
/// Hertz contact's `(what, half-size)`, or the candidate disk's `(spacing,
/// radius)`, as [`coarse_grid`] takes them). Gives the points across, the
/// size across and the largest spacing that resolves it.
pub(crate) fn unresolved_grid(
    points: &PointSet,
    hertz: Option<(&str, f64)>,
    disk: Option<(f64, f64)>,
) -> Option<Unresolved> {
    let (h, size, what) = match (hertz, disk) {
        (Some((what, a)), _) => (
            points.cell().dx,
            2.0 * a,
            format!("the Hertz contact {what}"),
        ),
        (None, Some((spacing, radius))) => (
            spacing,
            2.0 * radius,
            "the candidate disk's diameter".to_string(),
        ),
        (None, None) => return None,
    };
    // A grid laid out with exactly `across` points over the contact
    // (`points.across`) lands there up to rounding.
    let across = (size / h * (1.0 + 1e-9)).floor() + 1.0;
    (across < MIN_POINTS_RESOLVED as f64).then(|| Unresolved {
        across: across as usize,
        size,
        what,
        spacing: size / (MIN_POINTS_RESOLVED - 1) as f64,
    })
}

/// A grid that cannot resolve the contact ([`unresolved_grid`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Unresolved {
    /// The points across the contact's size.
    pub across: usize,
    /// The contact's size across (length).
    pub size: f64,
    /// What the size is ("the Hertz contact width").
    pub what: String,
    /// The largest spacing that puts [`MIN_POINTS_RESOLVED`] points across.
    pub spacing: f64,
}

/// Why points relative to the Hertz contact (across, zone) cannot be laid
/// out: the first condition the scene misses.
pub(crate) fn no_hertz_reason(
    models: [&str; 2],
    geometry: &Geometry,
    loading: Loading,
    dimension: Dimension,
) -> String {
    let fix = "; or give absolute sizes (spacing and radius, half_x, start, end and n)";
    if matches!(loading.normal, Normal::Approach(_)) {
        return format!(
            "points relative to the Hertz contact (across, zone) need loading.load: under \
             displacement control the contact's size is not known before the solve{fix}"
        );
    }
    let curved = geometry
        .surfaces()
        .is_some_and(|(a, b)| a.is_curved() || b.is_curved());
    if !curved {
        return format!(
            "points relative to the Hertz contact (across, zone) need curved surfaces (a sphere or \
             a cylinder): between two planes, or a given separation, there is no Hertz contact{fix}"
        );
    }
    let half_space: &[&str] = match dimension {
        Dimension::Surface => &["point-force", "uniform-patch"],
        Dimension::Line => &["plane-strain"],
    };
    if let Some(model) = models
        .iter()
        .find(|m| !(**m == "rigid" || half_space.contains(m)))
    {
        return format!(
            "points relative to the Hertz contact (across, zone) need half-space bodies ({}) or \
             rigid ones: the \"{}\" model has no Hertz contact{fix}",
            half_space.join(", "),
            model
        );
    }
    format!(
        "points relative to the Hertz contact (across, zone) need a Hertz contact: spheres on a \
         disk, cylinders (axis along y) on a line or a rectangle, quadrics whose gap curves both \
         ways on an ellipse{fix}"
    )
}

/// A Hertz length scale that is not a finite positive number: the load,
/// moduli and radii are outside floating-point range together.
pub(crate) fn scale_out_of_range(scale: Option<f64>) -> bool {
    scale.is_some_and(|a| !(a.is_finite() && a > 0.0))
}

/// How far, relative to the spacing, a step between listed points of a
/// line may differ from it (rounding of coordinates computed and written
/// by the caller), besides the rounding of the coordinates themselves.
const STEP_TOLERANCE: f64 = 1e-9;

/// Points given as coordinates for line models (plane-strain, beam) must be
/// what a scene's `grid = "line"` lays out: x increasing by the spacing from
/// one point to the next. Each point stands for a cell of the spacing's
/// width; points closer or farther apart would make cells that overlap or
/// leave gaps, which the models' influence and the pressures would take
/// for the spacing's. The first step that is not the spacing is named.
pub(crate) fn listed_line(ctx: &Ctx<'_>, points: &PointSet) -> Result<(), SceneError> {
    let dx = points.cell().dx;
    let step_off = |k: usize| {
        let (a, b) = (points.x(k - 1), points.x(k));
        let tolerance = STEP_TOLERANCE * dx + 1e-12 * (a.abs() + b.abs());
        !((b - a - dx).abs() <= tolerance)
    };
    // Order first: a swap reads as such, not as the uneven steps it makes.
    let unsorted = (1..points.len()).find(|&k| !(points.x(k) > points.x(k - 1)));
    if let Some(k) = unsorted.or_else(|| (1..points.len()).find(|&k| step_off(k))) {
        let (a, b) = (points.x(k - 1), points.x(k));
        let what = if unsorted.is_some() {
            format!("is not above x[{}] = {}", k - 1, Num(a))
        } else {
            format!(
                "is {} after x[{}] = {}, not the spacing {}",
                Num(b - a),
                k - 1,
                Num(a),
                Num(dx)
            )
        };
        return Err(ctx.invalid(
            0..0,
            "points",
            format!("x[{k}] = {}", Num(b)),
            format!(
                "{what}: the points of line models (plane-strain, beam) are a line grid, as \
                 grid = \"line\" lays them out: x increasing by the spacing from one point to \
                 the next (each point stands for a cell of the spacing's width); sort them, or \
                 give the spacing they are laid out at"
            ),
        ));
    }
    Ok(())
}

/// The plane-strain datum must lie beyond every grid the scene solves on
/// (its own and each design load's), and a beam's loaded point on the beam.
pub(crate) fn bodies_on_grid(
    ctx: &Ctx<'_>,
    raw: [&Spanned<BodyToml>; 2],
    bodies: [&Body; 2],
    own: &PointSet,
    design_sets: &[PointSet],
) -> Result<(), SceneError> {
    for (section, (raw, body)) in ["body1", "body2"].iter().zip(raw.iter().zip(bodies)) {
        let t = raw.get_ref();
        match *body.model() {
            Model::PlaneStrainStrip {
                reference_distance, ..
            } => {
                let widest = std::iter::once(own)
                    .chain(design_sets)
                    .map(|p| p.extent().0)
                    .fold(0.0f64, f64::max);
                if reference_distance < widest {
                    let span = t
                        .reference_distance
                        .as_ref()
                        .map_or(t.model.span(), |v| v.span());
                    return Err(ctx.invalid(
                        span,
                        format!("{section}.reference_distance"),
                        Num(reference_distance),
                        format!(
                            "must be at least the extent of the grid, {widest:.4e} (the strips' \
                             displacements are measured from a datum beyond the candidate zone{})",
                            if widest > own.extent().0 {
                                "; the widest grid is a design load's"
                            } else {
                                ""
                            }
                        ),
                    ));
                }
            }
            Model::Beam { loaded_point, .. } => {
                // The contact forces act at the points: a load beyond the
                // last of them is balanced by none (the solve ends in a ray).
                let (lo, hi) = (own.x(0), own.x(own.len() - 1));
                if !(lo..=hi).contains(&loaded_point) {
                    let span = t.loaded_point.as_ref().map_or(t.model.span(), |v| v.span());
                    return Err(ctx.invalid(
                        span,
                        format!("{section}.loaded_point"),
                        Num(loaded_point),
                        format!(
                            "is outside the beam's points, not between its first and last, {} \
                             and {}: the contact forces act at the points, and no forces there \
                             balance a load beyond them; give a point between them (default 0)",
                            Num(lo),
                            Num(hi)
                        ),
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}
