//! What the run would refuse that the scene tells before it: the load or
//! approach within the small strain of the linear models
//! ([`sanity::MAX_STRAIN`]) and resolved against the separations and the
//! doubles' range; given separations nearly flat against the zone; Hertz's
//! approach, a plane-strain datum's and prescribed tilts against the zone;
//! a moment's load centre inside it. Each refusal names the field a user
//! changes ([`super::factors`]: the input out of scale, not always the
//! load).

use elcon_analysis::{Geometry, Loading, Normal};
use elcon_influence::PointSet;
use toml::Spanned;

use super::factors::{self, Quantity};
use super::files;
use super::hertz::{Hertz, Layout};
use super::points::{HertzLayout, PointsSpec};
use super::units::Units;
use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::sanity;
use crate::schema::{GeometryToml, SceneFile};

/// The scene's load or approach, separations and tilts within what the
/// run accepts: [`small_strain`], [`hertz_bounds`], and a moment's load
/// centre inside the zone ([`sanity::load_centre`]).
pub(super) fn bounds(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    layout: Layout<'_>,
    points: &PointSet,
    loading: Loading,
    units: &Units,
) -> Result<(), SceneError> {
    small_strain(ctx, raw, layout, points, loading, units)?;
    hertz_bounds(ctx, raw, layout, points, loading, units.length())?;
    sanity::load_centre(ctx, &raw.loading, loading, points)
}

/// What the run would refuse that Hertz's closed form tells before it:
/// Hertz's approach at the scene's load beyond the small strain
/// ([`sanity::hertz_approach_strain`]), prescribed tilts moving the
/// spheres' or an elliptical contact off the candidate zone
/// ([`sanity::tilt_off_zone`], [`sanity::tilt_off_zone_ellipse`]), a
/// plane-strain datum so far that the line contact's approach strains
/// the zone ([`sanity::datum_strain`]).
/// The closed form comes from the bodies, the surfaces and the layout.
fn hertz_bounds(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    layout: Layout<'_>,
    points: &PointSet,
    loading: Loading,
    length: &str,
) -> Result<(), SceneError> {
    let Normal::Load(load) = loading.normal else {
        return Ok(());
    };
    let t = raw.loading.get_ref();
    let contact = layout.hertz(load);
    let extent = layout.approach_extent(contact.as_ref(), points);
    let sized_by_hertz = matches!(
        layout.points_spec,
        PointsSpec::Hertz(HertzLayout::Disk { .. } | HertzLayout::Ellipse { .. })
    );
    if let Some(reason) = contact
        .and_then(|h| h.approach())
        .and_then(|d| sanity::hertz_approach_strain((load, d), sized_by_hertz, extent, length))
    {
        return Err(sanity::refuse_normal(
            ctx,
            &raw.loading,
            loading.normal,
            reason,
        ));
    }
    let pair = pair(layout);
    if let Some(Hertz::Cylinders(h)) = contact
        && let Some((i, reason)) = sanity::datum_strain(&h, pair, points, length)
    {
        let (section, raw_body) = [("body1", &raw.body1), ("body2", &raw.body2)][i];
        let b = raw_body.get_ref();
        let span = b
            .reference_distance
            .as_ref()
            .map_or(b.model.span(), |v| v.span());
        let value = match *pair[i].model() {
            elcon_influence::Model::PlaneStrainStrip {
                reference_distance, ..
            } => reference_distance,
            _ => 0.0,
        };
        return Err(ctx.invalid(
            span,
            format!("{section}.reference_distance"),
            Num(value),
            reason,
        ));
    }
    let off = match contact {
        Some(Hertz::Ellipse(h)) => sanity::tilt_off_zone_ellipse(&h, loading, points, length),
        _ => layout
            .spheres_at(load)
            .and_then(|rc| sanity::tilt_off_zone(rc, loading, points, length)),
    };
    if let Some((field, reason)) = off {
        let (given, value) = if field == "loading.tilt_x" {
            (t.tilt_x.as_ref(), loading.tilt_x)
        } else {
            (t.tilt_y.as_ref(), loading.tilt_y)
        };
        let span = given.map_or(raw.loading.span(), |v| v.span());
        let angle = Num(value.prescribed_angle());
        return Err(ctx.invalid(span, field, angle, reason));
    }
    Ok(())
}

/// The scene within the small strain of the linear models
/// ([`sanity::MAX_STRAIN`]): its separations against the zone's size, its
/// load or approach against the bodies' stiffness.
fn small_strain(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    layout: Layout<'_>,
    points: &PointSet,
    loading: Loading,
    units: &Units,
) -> Result<(), SceneError> {
    let (geometry, spec) = (layout.geometry, layout.points_spec);
    small_separations(ctx, raw.geometry.as_ref(), geometry, points, units.length())?;
    let pair = pair(layout);
    sanity::small_strain(
        ctx,
        &raw.loading,
        pair,
        loading,
        points,
        strain_labels(units),
    )?;
    let largest = largest_separation(ctx, raw.geometry.as_ref(), geometry, points)?;
    let factors = |quantity| factors::factors(raw, pair, spec, loading.normal, points, quantity);
    // The load's own bounds first: a user who mistyped the load is told
    // so; a deformation out of the doubles' range blames the input out of
    // scale (a foundation's modulus of 1e307, not the load).
    let Some(reason) = sanity::unresolved(pair, loading.normal, points, largest, units.length())
    else {
        return sanity::compliance_in_range(
            ctx,
            &|load| factors(Quantity::Product { load }),
            pair,
            points,
            (loading.normal, largest),
            strain_labels(units),
        );
    };
    if let Some((f, reason)) = sanity::deformation_out_of_scale(
        pair,
        loading.normal,
        points,
        largest,
        (
            &factors(Quantity::Deformation),
            &factors(Quantity::Product {
                load: sanity::deformation(pair, loading.normal, points) >= largest.abs(),
            }),
        ),
        units.length(),
    ) {
        return Err(ctx.invalid(f.span, f.field, Num(f.value), reason));
    }
    Err(sanity::refuse_normal(
        ctx,
        &raw.loading,
        loading.normal,
        reason,
    ))
}

/// The largest initial separation (in magnitude) over `points`: what a
/// load's deformation must be resolved against
/// ([`sanity::MIN_RESOLVED_DEFORMATION`]).
pub(super) fn largest_separation(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
    points: &PointSet,
) -> Result<f64, SceneError> {
    let eps = files::separations_on(ctx, raw, geometry, points)?;
    Ok(eps.iter().fold(0.0f64, |m, e| m.max(e.abs())))
}

/// The unit labels the small-strain refusals quote.
pub(super) fn strain_labels(units: &Units) -> sanity::Labels<'_> {
    sanity::Labels {
        length: units.length(),
        force: units.force(),
        intensity: units.intensity(),
    }
}

/// Given separations, or surfaces with tabulated departures, within
/// [`sanity::MAX_STRAIN`] of the zone's size at every candidate point
/// ([`sanity::small_separations`]); the quadrics alone are bounded by
/// their radii and the small strain of the load.
fn small_separations(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
    points: &PointSet,
    length: &str,
) -> Result<(), SceneError> {
    let (Some(g), Geometry::Separation(_) | Geometry::Tabulated { .. }) = (raw, geometry) else {
        return Ok(());
    };
    let eps = files::separations_on(ctx, Some(g), geometry, points)?;
    let Some(reason) = sanity::small_separations(&eps, points, length) else {
        return Ok(());
    };
    let t = g.get_ref();
    let (field, span) = if let Some(f) = &t.separation_file {
        ("geometry.separation_file", f.span())
    } else if let Some(v) = &t.separation {
        ("geometry.separation", v.span())
    } else if let Some(m) = &t.height_map {
        ("geometry.height_map", m.span())
    } else if let Some(p) = &t.profile {
        ("geometry.profile", p.span())
    } else {
        ("geometry", g.span())
    };
    Err(ctx.invalid(span, field, "", reason))
}

/// The two bodies of a layout, as elcon-influence holds them.
fn pair(layout: Layout<'_>) -> [&elcon_influence::Body; 2] {
    [layout.bodies[0].body(), layout.bodies[1].body()]
}
