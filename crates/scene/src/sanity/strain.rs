//! Small strain: every influence model is linear elasticity under small
//! strain (or small deflection, for a beam), so a load whose mean pressure
//! over the candidate zone `p = P / A` is not small against the combined
//! modulus (`p / E* <= MAX_STRAIN`), that compresses a Winkler foundation by
//! more than [`MAX_STRAIN`] of the zone's size (`p / k <= MAX_STRAIN L`),
//! or bends a beam by a slope beyond [`MAX_STRAIN`] rad, and an approach
//! beyond [`MAX_STRAIN`] of the zone's size, are refused: the answer would
//! be a number of a model that does not hold there (and at extreme
//! magnitudes the solve overflows). The zone's size there is its smaller
//! extent: an approach of half a roller's length strains it however wide
//! the zone is across the roller. Given separations, Hertz's approach and a
//! plane-strain datum are held to the same bound.

use elcon_analysis::{Loading, Normal};
use elcon_influence::{Body, Dimension, Model, PointSet, combined_modulus_of};
use toml::Spanned;

use crate::ctx::{Ctx, Num, rounded};
use crate::error::SceneError;
use crate::schema::LoadingToml;

/// The largest strain a scene may ask of the linear models: the mean
/// pressure over the candidate zone against the combined modulus E*, a
/// Winkler foundation's compression and an approach or a separation
/// against the zone's size, a beam's bending slope (rad). Linear elasticity
/// and the rigid rotation's linearization (`MAX_ROTATION`, also 0.1) hold
/// to a few percent up to it; every example scene is well within it.
pub const MAX_STRAIN: f64 = 0.1;

/// The length the strain bounds measure the zone by: its smaller extent on
/// a surface (an approach or a separation large against the zone's width
/// strains it however long it is), a line's length.
pub(crate) fn strain_length(points: &PointSet) -> f64 {
    let (a, b) = points.extent();
    if points.dimension() == Dimension::Line {
        a
    } else {
        a.min(b)
    }
}

/// The size of the candidate zone: its larger extent (a line's length).
pub(crate) fn zone_size(points: &PointSet) -> f64 {
    let (a, b) = points.extent();
    if points.dimension() == Dimension::Line {
        a
    } else {
        a.max(b)
    }
}

/// The unit labels a strain refusal quotes (the scene's `[units]`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Labels<'a> {
    /// Length.
    pub length: &'a str,
    /// Force.
    pub force: &'a str,
    /// The load intensity: pressure, or force per length on a beam.
    pub intensity: &'a str,
}

/// Why `normal` (a load, or an approach) on `points` strains the bodies
/// beyond [`MAX_STRAIN`], if it does: the mean pressure `P / A` over the
/// zone against E* (half-space models), a Winkler foundation's mean
/// compression `P / (A k)` against the zone's size, a beam's bending slope
/// (the larger of its arms from the loaded point as a cantilever under the
/// mean intensity, `q l^3 / (6 E I)`, or on a Winkler foundation
/// Hetenyi's `0.32 P beta^2 / k`, `beta = (k / (4 E I))^(1/4)`, whichever is
/// smaller), an approach against the zone's size.
pub(crate) fn strain(
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
    labels: Labels<'_>,
) -> Option<String> {
    let Labels {
        length,
        intensity: pressure,
        ..
    } = labels;
    let size = strain_length(points);
    let small = "beyond the small strain (at most 0.1) of the linear elasticity the influence \
                 models rest on";
    let load = match normal {
        Normal::Load(p) => p,
        Normal::Approach(d) => {
            let s = d.abs() / size;
            return beyond(s).then(|| {
                format!(
                    "the approach is {s:.1e} times the candidate zone's smaller extent, {} \
                     {length}: {small}; \
                     give an approach below {} {length}, or check its units",
                    Num(size),
                    rounded(MAX_STRAIN * size)
                )
            });
        }
    };
    let measure = points.total_measure();
    let mean = load / measure;
    let area = match points.dimension() {
        Dimension::Surface => format!("{} {length}^2", rounded(measure)),
        Dimension::Line => format!("{} {length} long", rounded(measure)),
    };
    if let Some(e) = combined_modulus(bodies) {
        let s = mean / e;
        if beyond(s) {
            return Some(format!(
                "the mean pressure over the candidate zone ({area}), {} {pressure}, is {s:.1e} \
                 times E* = {} {pressure} (of the bodies' youngs_modulus and poissons_ratio): \
                 {small}; {FIX}",
                rounded(mean),
                rounded(e)
            ));
        }
    }
    let foundation = foundation(bodies);
    if let Some(k) = foundation {
        let s = mean / k / size;
        if beyond(s) {
            return Some(format!(
                "the foundation's mean compression under the load over the candidate zone \
                 ({area}), {} {length} (the mean intensity over the modulus k = {}), is {s:.1e} \
                 times the zone's smaller extent, {} {length}: {small}; {FIX}",
                rounded(mean / k),
                Num(k),
                Num(size)
            ));
        }
    }
    bodies
        .iter()
        .find_map(|b| beam_slope(b, (load, mean), points, foundation, labels))
}

/// What a load strained beyond the bodies is told to do.
const FIX: &str = "give a smaller load, or check the units of the load and the moduli";

/// E* of the bodies, where one of them is a half-space (`None` for none).
pub(super) fn combined_modulus(bodies: [&Body; 2]) -> Option<f64> {
    bodies
        .iter()
        .any(|b| b.material().is_some())
        .then(|| combined_modulus_of(bodies[0].material(), bodies[1].material()))
}

/// The modulus k of the bodies' Winkler foundation, if one is.
pub(super) fn foundation(bodies: [&Body; 2]) -> Option<f64> {
    bodies.iter().find_map(|b| match *b.model() {
        Model::Winkler { modulus } => Some(modulus),
        _ => None,
    })
}

/// The length an approach is measured against for the small strain, and
/// its name in messages: the candidate zone's smaller extent
/// (its shortest side), or on an ellipse grid the zone across the Hertz
/// ellipse's minor axis in the ellipse's own frame, whatever its turn
/// (`crate::scene` lays both out).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrainExtent {
    /// The length (length unit).
    pub length: f64,
    /// What it is, for messages ("the candidate zone's smaller extent").
    pub what: &'static str,
}

impl StrainExtent {
    /// The candidate zone's smaller extent ([`strain_length`]).
    pub(crate) fn of(points: &PointSet) -> Self {
        Self {
            length: strain_length(points),
            what: "the candidate zone's smaller extent",
        }
    }
}

/// An approach beyond the small strain: `|approach|` over `extent` above
/// [`MAX_STRAIN`], or not finite: `Some(strain)`. The bound `run` applies
/// to a solved approach and `check` to Hertz's approach at the scene's
/// load.
pub fn approach_strain(approach: f64, extent: StrainExtent) -> Option<f64> {
    let s = approach.abs() / extent.length;
    (!(s.is_finite() && s <= MAX_STRAIN)).then_some(s)
}

/// Why Hertz's approach at `load`, `approach`, is beyond the small strain
/// against `extent` ([`approach_strain`]), if it is: the run would refuse
/// the solved approach. A point contact's approach grows as `P^(2/3)`, and
/// a grid sized by the Hertz contact (`sized_by_hertz`) as `P^(1/3)`: the
/// strain as `P^(2/3)` or `P^(1/3)`, so the message gives the load at the
/// bound.
pub(crate) fn hertz_approach_strain(
    (load, approach): (f64, f64),
    sized_by_hertz: bool,
    extent: StrainExtent,
    length: &str,
) -> Option<String> {
    let s = approach_strain(approach, extent)?;
    let power = if sized_by_hertz { 3.0 } else { 1.5 };
    Some(format!(
        "Hertz's approach at this load, {} {length}, is {s:.4} times {}, {} {length}: beyond \
         the small strain (at most {MAX_STRAIN}) of the linear elasticity the influence models \
         rest on, so the run would refuse the solved approach; give a load of at most {}, \
         stiffer bodies (youngs_modulus), or check their units",
        rounded(approach),
        extent.what,
        rounded(extent.length),
        rounded(load * (MAX_STRAIN / s).powf(power) * 0.999)
    ))
}

/// A line contact whose approach, Hertz's measured from the plane-strain
/// bodies' datums, is beyond the small strain of the candidate line's
/// length because of one body's `reference_distance`: each body's
/// compression is `(2 P' / pi) (1 - nu^2) / E (ln(2 d0 / b) + 1/2)`
/// (their sum is `HertzCylinders::approach` for a common d0), so a datum
/// far beyond the contact adds its logarithm to the approach the run then
/// refuses. The body to name (0 or 1: the farther datum) and why, with
/// the range of its datum that keeps the approach within the bound:
/// from `widest`, the grid's extent (the datum lies beyond the grid), to
/// the largest the other body's compression leaves room for. `None` when
/// the approach is within the bound, or no datum in that range brings it
/// there (then the load strains the bodies, refused by the run).
pub(crate) fn datum_strain(
    h: &elcon_analysis::references::HertzCylinders,
    bodies: [&Body; 2],
    points: &PointSet,
    length: &str,
) -> Option<(usize, String)> {
    let (p, b) = (h.load_per_length, h.half_width());
    // Each plane-strain body's compliance and datum.
    let strips: Vec<(usize, f64, f64)> = bodies
        .iter()
        .enumerate()
        .filter_map(|(i, body)| match *body.model() {
            Model::PlaneStrainStrip {
                material,
                reference_distance,
            } => Some((i, material.compliance(), reference_distance)),
            _ => None,
        })
        .collect();
    let compression =
        |c: f64, d0: f64| 2.0 * p / std::f64::consts::PI * c * ((2.0 * d0 / b).ln() + 0.5);
    let approach: f64 = strips.iter().map(|&(_, c, d0)| compression(c, d0)).sum();
    let extent = StrainExtent::of(points);
    let s = approach_strain(approach, extent)?;
    let &(i, c, d0) = strips.iter().max_by(|a, b| a.2.total_cmp(&b.2))?;
    let others: f64 = strips
        .iter()
        .filter(|s| s.0 != i)
        .map(|&(_, c, d0)| compression(c, d0))
        .sum();
    let room = MAX_STRAIN * extent.length - others;
    let farthest = 0.5 * b * (room * std::f64::consts::PI / (2.0 * p * c) - 0.5).exp();
    let widest = points.extent().0;
    if !(farthest >= widest && farthest < d0) {
        return None;
    }
    Some((
        i,
        format!(
            "the line contact's approach measured from the bodies' datums, Hertz's at this load, \
             is {} {length}, {s:.1e} times {}, {} {length}: beyond the small strain (at most \
             {MAX_STRAIN}) of the linear elasticity the influence models rest on, so the run \
             would refuse the solved approach; this datum adds {} {length} of it (its compression \
             grows as the logarithm of the datum over the Hertz half-width, {} {length}). Give \
             a reference_distance from {} (the grid's extent) to {} {length}, or check its units",
            rounded(approach),
            extent.what,
            rounded(extent.length),
            rounded(compression(c, d0)),
            rounded(b),
            rounded(widest),
            rounded(farthest * 0.999)
        ),
    ))
}

/// A beam's longer arm from its loaded point to the far edge of the last
/// cell on either side.
pub(super) fn beam_arm(points: &PointSet, loaded_point: f64) -> f64 {
    let h = points.cell().dx;
    (loaded_point - points.x(0) + 0.5 * h).max(points.x(points.len() - 1) + 0.5 * h - loaded_point)
}

/// A beam body `b` bent beyond [`MAX_STRAIN`] rad by `load` spread over
/// `points` (mean intensity `mean`), on a Winkler `foundation` if there is
/// one ([`strain`]).
fn beam_slope(
    b: &Body,
    (load, mean): (f64, f64),
    points: &PointSet,
    foundation: Option<f64>,
    Labels { length, force, .. }: Labels<'_>,
) -> Option<String> {
    let Model::Beam {
        flexural_rigidity: ei,
        loaded_point,
    } = *b.model()
    else {
        return None;
    };
    let arm = beam_arm(points, loaded_point);
    let cantilever = mean * arm.powi(3) / (6.0 * ei);
    let slope = foundation.map_or(cantilever, |k| {
        let beta = (k / (4.0 * ei)).powf(0.25);
        cantilever.min(0.32 * load * beta * beta / k)
    });
    if beyond(slope) {
        return Some(format!(
            "bends the beam (E I = {} {force} {length}^2) by a slope of about {} rad (its \
             longer arm from the loaded point, {} {length}, under the mean intensity{}): \
             beyond the small slope (at most 0.1 rad) of the linear beam theory the beam \
             model rests on; {FIX}",
            rounded(ei),
            rounded(slope),
            rounded(arm),
            if foundation.is_some() {
                ", or Hetenyi's beam on the foundation"
            } else {
                ""
            }
        ));
    }
    None
}

/// Whether a strain `s` exceeds [`MAX_STRAIN`] (or is no number).
fn beyond(s: f64) -> bool {
    s.is_nan() || s > MAX_STRAIN
}

/// The scene's load or approach within [`MAX_STRAIN`] ([`strain`]).
pub(crate) fn small_strain(
    ctx: &Ctx<'_>,
    raw: &Spanned<LoadingToml>,
    bodies: [&Body; 2],
    loading: Loading,
    points: &PointSet,
    labels: Labels<'_>,
) -> Result<(), SceneError> {
    match strain(bodies, loading.normal, points, labels) {
        Some(reason) => Err(refuse_normal(ctx, raw, loading.normal, reason)),
        None => Ok(()),
    }
}

/// The scene's load or approach (`normal`) refused for `reason`: the key
/// `loading.load` or `loading.approach`, at its value (else at
/// `[loading]`).
pub(crate) fn refuse_normal(
    ctx: &Ctx<'_>,
    raw: &Spanned<LoadingToml>,
    normal: Normal,
    reason: impl Into<String>,
) -> SceneError {
    let t = raw.get_ref();
    let (field, given, value) = match normal {
        Normal::Load(v) => ("loading.load", t.load.as_ref(), v),
        Normal::Approach(v) => ("loading.approach", t.approach.as_ref(), v),
    };
    let span = given.map_or(raw.span(), |v| v.span());
    ctx.invalid(span, field, Num(value), reason)
}

/// Given separations, or surfaces with tabulated departures (a height map,
/// a profile), that vary along a row of the grid by more than
/// [`MAX_STRAIN`] of the zone's extent along that row (along x, and along
/// y on a surface): the influence models take the surfaces as nearly flat
/// against the candidate zone, and a surface's slope is its variation over
/// the extent along each axis (a roller's curvature across a zone 10^5
/// times wider than long is flat along x, whatever it does over the
/// roller's length along y).
pub(crate) fn small_separations(eps: &[f64], points: &PointSet, length: &str) -> Option<String> {
    let (ex, ey) = points.extent();
    let cell = points.cell();
    let surface = points.dimension() == Dimension::Surface;
    // Rows along x (one key per y) and, on a surface, columns along y.
    let axes = [("x", ex), ("y", ey)];
    for (axis, extent) in axes.into_iter().take(if surface { 2 } else { 1 }) {
        let key = |k: usize| match axis {
            "x" => (points.y(k) / cell.dy).round() as i64,
            _ => (points.x(k) / cell.dx).round() as i64,
        };
        // Each row's lowest and highest separation, with their points.
        let mut rows: std::collections::HashMap<i64, (usize, usize)> =
            std::collections::HashMap::new();
        for (k, e) in eps.iter().enumerate() {
            let row = rows.entry(key(k)).or_insert((k, k));
            if *e < eps[row.0] {
                row.0 = k;
            }
            if *e > eps[row.1] {
                row.1 = k;
            }
        }
        let worst = rows
            .values()
            .map(|&(lo, hi)| (lo, hi, eps[hi] - eps[lo]))
            .max_by(|a, b| a.2.total_cmp(&b.2));
        let Some((lo, hi, range)) = worst else {
            continue;
        };
        let s = range / extent;
        if !beyond(s) {
            continue;
        }
        let at = |k: usize| {
            if surface {
                format!("({}, {})", rounded(points.x(k)), rounded(points.y(k)))
            } else {
                format!("x = {}", rounded(points.x(k)))
            }
        };
        return Some(format!(
            "the separation varies along {axis} by {} {length}, from {} at {} to {} at {}, {s:.1e} \
             times the candidate zone's extent along {axis}, {} {length}: the influence models \
             take the surfaces as nearly flat against the candidate zone (a variation along each \
             axis at most {MAX_STRAIN} of the zone's extent along it); check the values and \
             their units",
            rounded(range),
            Num(eps[lo]),
            at(lo),
            Num(eps[hi]),
            at(hi),
            Num(extent)
        ));
    }
    None
}
