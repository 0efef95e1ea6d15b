//! The loading against the candidate zone: a moment whose load centre
//! lies outside the zone, and prescribed tilts that move the Hertz contact
//! past the zone's open edge, are refused (the run would find the contact
//! against the zone's edge, or no balance at all).

use elcon_analysis::Loading;
use elcon_influence::PointSet;
use toml::Spanned;

use crate::ctx::{Ctx, Num, at_most, rounded};
use crate::error::SceneError;
use crate::schema::LoadingToml;
use elcon_analysis::zone::{OpenEdge, Zone};

/// The largest rotation of a body (rad), prescribed (`loading.tilt_x`,
/// `tilt_y`) or solved under a moment: the rigid rotation is linearized
/// (`theta x`), which holds to 0.5 % of the angle up to 0.1 rad, as for a
/// design's misalignments (elcon-analysis's, which refuses the solved
/// rotation beyond it).
pub use elcon_analysis::rotation::MAX_ROTATION;

/// A moment whose load centre lies outside the candidate zone is refused:
/// the contact forces, all at the zone's points, balance the moment only
/// when their centre, the load centre `(-M_y / P, M_x / P)`, lies within
/// the points' convex hull (`crate::zone`). (Under displacement control
/// the load, and with it the centre, is known only after the solve, whose
/// rotation is bounded then: `crate::run`.)
pub(crate) fn load_centre(
    ctx: &Ctx<'_>,
    raw: &Spanned<LoadingToml>,
    loading: Loading,
    points: &PointSet,
) -> Result<(), SceneError> {
    let Some(load) = loading.load_value() else {
        return Ok(());
    };
    let t = raw.get_ref();
    let given = (t.moment_x.as_ref().map(|m| (m, "loading.moment_x")))
        .or_else(|| t.moment_y.as_ref().map(|m| (m, "loading.moment_y")));
    let Some((blamed, blamed_field)) = given else {
        return Ok(());
    };
    let value = |m: &Option<Spanned<f64>>| m.as_ref().map_or(0.0, |m| *m.get_ref());
    // `0.0 -`: no moment about y puts the centre at x = 0, not -0.
    let centre = (0.0 - value(&t.moment_y) / load, value(&t.moment_x) / load);
    let zone = Zone::of(points);
    if zone.holds(centre) {
        return Ok(());
    }
    let other = match (&t.moment_x, &t.moment_y) {
        (Some(_), Some(my)) => format!("with `loading.moment_y` = {}", Num(*my.get_ref())),
        _ => String::new(),
    };
    Err(ctx.invalid(
        blamed.span(),
        blamed_field,
        Num(*blamed.get_ref()),
        format!(
            "{other}{}puts the load centre (the moment over the load) at (x, y) = ({}, {}), {} \
             outside the candidate zone ({}): no contact inside the zone balances it. Give a \
             smaller moment, or a larger zone (points.zone or points.radius)",
            if other.is_empty() { "" } else { ", " },
            rounded(centre.0),
            rounded(centre.1),
            rounded(-zone.depth(centre)),
            zone.describe()
        ),
    ))
}

/// Prescribed tilts that move the gap's minimum of spheres of combined
/// radius `radius` to `R (tilt_y, -tilt_x)` (a rotation about x moves it
/// along y) so far that the Hertz contact of radius `contact` around it
/// reaches past the candidate zone's open edge ([`OpenEdge`]: a boundary
/// point's cell, half a cell out, as the run tests it): the field to name
/// (the larger tilt) and why. The run would find the contact against the
/// zone's edge.
pub(crate) fn tilt_off_zone(
    (radius, contact): (f64, f64),
    loading: Loading,
    points: &PointSet,
    length: &str,
) -> Option<(&'static str, String)> {
    let (tx, ty) = prescribed_tilts(loading);
    let shift = (radius * ty, -radius * tx);
    let distance = shift.0.hypot(shift.1);
    let (most, _) = reach(shift, |d: (f64, f64)| d.0.hypot(d.1) < contact, points)?;
    Some((
        larger_tilt(tx, ty),
        format!(
            "the tilts (tilt_x {}, tilt_y {} rad) move the gap's minimum by R tilt = {} {length} \
             (R = {} {length}, the spheres' combined radius); with the Hertz contact's radius, \
             {} {length}, the contact reaches beyond the candidate zone's boundary points by \
             half a cell or more: the contact would lie against the zone's edge. Give tilts of \
             at most {} rad together, or a larger zone (points.zone or points.radius)",
            Num(tx),
            Num(ty),
            rounded(distance),
            rounded(radius),
            rounded(contact),
            at_most(most * tx.hypot(ty))
        ),
    ))
}

/// How much of `shift` a contact (`inside(d)`: the point at `d` from its
/// centre lies in it) moves before it reaches past the open edge of
/// `points` ([`OpenEdge::largest_shift`]), and that edge; `None` when the
/// whole shift keeps clear of it, or nothing moves.
fn reach(
    shift: (f64, f64),
    inside: impl Fn((f64, f64)) -> bool,
    points: &PointSet,
) -> Option<(f64, OpenEdge)> {
    if !(shift.0.hypot(shift.1) > 0.0) {
        return None;
    }
    let edge = OpenEdge::of(points);
    let most = edge.largest_shift(shift, inside);
    (most < 1.0).then_some((most, edge))
}

/// The prescribed tilts about x and y (rad; 0 where free).
fn prescribed_tilts(loading: Loading) -> (f64, f64) {
    (
        loading.tilt_x.prescribed_angle(),
        loading.tilt_y.prescribed_angle(),
    )
}

/// The field of the larger of the tilts about x and y.
fn larger_tilt(tx: f64, ty: f64) -> &'static str {
    if tx.abs() >= ty.abs() {
        "loading.tilt_x"
    } else {
        "loading.tilt_y"
    }
}

/// Prescribed tilts that move the minimum of an elliptical Hertz
/// contact's gap (`h`, of the gap's curvature form K) so far that the
/// contact ellipse around it reaches past the candidate zone's open edge
/// ([`OpenEdge`], as the run tests it): the gap
/// `K(x, x) / 2 + tilt_x y - tilt_y x` has its minimum at
/// `s = K^-1 (tilt_y, -tilt_x)` (for spheres `R (tilt_y, -tilt_x)`,
/// [`tilt_off_zone`]), and the contact is Hertz's ellipse moved there.
/// The field to name (the larger tilt) and why, as [`tilt_off_zone`] says
/// it. The run would find the contact against the zone's edge.
pub(crate) fn tilt_off_zone_ellipse(
    h: &elcon_analysis::references::HertzEllipse,
    loading: Loading,
    points: &PointSet,
    length: &str,
) -> Option<(&'static str, String)> {
    let (tx, ty) = prescribed_tilts(loading);
    let k = h.curvature();
    let det = k.xx * k.yy - k.xy * k.xy;
    let shift = (
        (k.yy * ty + k.xy * tx) / det,
        -(k.xy * ty + k.xx * tx) / det,
    );
    let (a, b) = (h.semi_major(), h.semi_minor());
    let (s, c) = h.angle().sin_cos();
    // A point at d from the centre, in the ellipse's axes.
    let inside = |d: (f64, f64)| {
        let (u, v) = (d.0 * c + d.1 * s, d.1 * c - d.0 * s);
        (u / a).powi(2) + (v / b).powi(2) < 1.0
    };
    let (most, edge) = reach(shift, inside, points)?;
    Some((
        larger_tilt(tx, ty),
        format!(
            "the tilts (tilt_x {}, tilt_y {} rad) move the gap's minimum by K^-1 tilt = {} \
             {length} to (x, y) = ({}, {}) (K the gap's curvature); with the Hertz ellipse's \
             semi-axes, {} and {} {length}, the contact reaches beyond the candidate zone's \
             boundary points ({}) by half a cell or more: the contact would lie against the \
             zone's edge. Give tilts of at most {} rad together, or a larger zone (points.zone \
             or points.radius)",
            Num(tx),
            Num(ty),
            rounded(shift.0.hypot(shift.1)),
            rounded(shift.0),
            rounded(shift.1),
            rounded(a),
            rounded(b),
            edge.describe(),
            at_most(most * tx.hypot(ty))
        ),
    ))
}
