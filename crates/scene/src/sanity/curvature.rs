//! The surfaces' curvatures. The initial separation of two paraboloids is
//! `eps(x, y) = (k_x x^2 + k_y y^2) / 2` with the summed curvatures
//! `k_x = 1/R1 + 1/R2` (spheres and cylinders, axis along y) and
//! `k_y = 1/R1 + 1/R2` (spheres only); a negative k means the bodies
//! interpenetrate more the farther from the first point of contact, which
//! no contact solution describes. Two curvatures of opposite signs whose
//! sum is rounding (`|k_1 + k_2| < CANCELLING_CURVATURE max(|k_1|, |k_2|)`)
//! describe no gap at all: the relative curvature is the difference of two
//! nearly equal numbers. Quadrics at an angle are checked the same way
//! along the gap's principal directions.

use std::ops::Range;

use elcon_analysis::{Curvature, Geometry};
use toml::Spanned;

use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::schema::{GeometryToml, SurfaceToml};

/// Two curvatures of opposite signs cancel when their sum is below this
/// fraction of the larger one: a thousand times the rounding of one f64
/// (`f64::EPSILON`), so that the relative curvature keeps at least a few
/// significant digits. (A radius -1.0000000000001 against 1 leaves 1e-13.)
pub const CANCELLING_CURVATURE: f64 = 1e3 * f64::EPSILON;

/// A concave surface must have the larger radius: the summed curvature
/// along x and along y must not be negative, whether or not tabulated
/// departures (a height map, a profile) are added to the surfaces.
pub(crate) fn curvatures(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
) -> Result<(), SceneError> {
    let Some((a, b)) = geometry.surfaces() else {
        return Ok(());
    };
    let (ka, kb) = (a.curvatures(), b.curvatures());
    for (axis, k1, k2) in [("x", ka.0, kb.0), ("y", ka.1, kb.1)] {
        let sum = k1 + k2;
        if k1 * k2 < 0.0 && sum.abs() < CANCELLING_CURVATURE * k1.abs().max(k2.abs()) {
            return Err(cancelling(ctx, raw, axis, (k1, k2), sum));
        }
        if sum >= 0.0 {
            continue;
        }
        // Blame the concave surface (the first, if both are).
        let (field, raw_surface) = concave(raw, k1 < 0.0);
        let (surface, other) = if k1 < 0.0 { (a, b) } else { (b, a) };
        let radius = surface.radius().unwrap_or(0.0);
        let span = raw_surface
            .and_then(|s| s.get_ref().radius.as_ref())
            .map_or(table(raw), |r| r.span());
        let against = match other.radius() {
            None => "a plane".to_string(),
            Some(radius) if radius < 0.0 => {
                format!("another concave surface (radius {})", Num(radius))
            }
            Some(radius) => format!("the convex radius {}", Num(radius)),
        };
        return Err(ctx.invalid(
            span,
            format!("{field}.radius"),
            Num(radius),
            format!(
                "a concave surface must have the larger radius: against {against} the summed \
                 curvature along {axis}, 1/R1 + 1/R2 = {sum:.4e}, is negative, so the bodies would \
                 interpenetrate more and more away from the first point of contact; give the \
                 concave surface a radius larger in magnitude than the convex one's"
            ),
        ));
    }
    quadric_curvatures(ctx, raw, geometry)
}

/// The concave surface a refusal blames, the first (`first`) or the
/// second: its field and, where the scene writes it, its table.
fn concave(
    raw: Option<&Spanned<GeometryToml>>,
    first: bool,
) -> (&'static str, Option<&Spanned<SurfaceToml>>) {
    let g = raw.map(Spanned::get_ref);
    if first {
        ("geometry.surface1", g.and_then(|g| g.surface1.as_ref()))
    } else {
        ("geometry.surface2", g.and_then(|g| g.surface2.as_ref()))
    }
}

/// Where `[geometry]` is written: a refusal without a key of its own
/// points there.
fn table(raw: Option<&Spanned<GeometryToml>>) -> Range<usize> {
    raw.map_or(0..0, |g| g.span())
}

/// Curvatures along `axis` of opposite signs (`k`) whose sum is rounding:
/// the refusal, naming both surfaces' radii along that axis.
fn cancelling(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    axis: &str,
    k: (f64, f64),
    sum: f64,
) -> SceneError {
    // Blame the concave surface: the one of negative curvature.
    let first = k.0 < 0.0;
    let (field, surface) = concave(raw, first);
    // The value as the file writes it (at an angle, the radius along the
    // axis is not the one written).
    let (key, span, written) = surface.map_or_else(
        || ("radius", table(raw), None),
        |s| {
            let t = s.get_ref();
            let (key, value) = match (&t.radius, axis) {
                (Some(r), _) => ("radius", Some(r)),
                (None, "x") => ("radius_x", t.radius_x.as_ref()),
                (None, _) => ("radius_y", t.radius_y.as_ref()),
            };
            (
                key,
                value.map_or(s.span(), |r| r.span()),
                value.map(|r| *r.get_ref()),
            )
        },
    );
    ctx.invalid(
        span,
        format!("{field}.{key}"),
        Num(written.unwrap_or(1.0 / if first { k.0 } else { k.1 })),
        format!(
            "cancels the other surface: geometry.surface1's radius along {axis} is {} and \
             geometry.surface2's {}, so the relative curvature 1/R1 + 1/R2 = {sum:.3e} is below \
             {CANCELLING_CURVATURE:.1e} of the larger curvature, within rounding of zero: the gap \
             along {axis} is no number the solve can use (a conforming contact, which the \
             half-space models do not describe). Give radii whose curvatures differ by more than that",
            Num(1.0 / k.0),
            Num(1.0 / k.1),
        ),
    )
}

/// Quadrics at an angle: the gap's principal curvatures (its form's
/// eigenvalues, `elcon_analysis::Curvature::principal_values`) must not be
/// negative, as the sums along x and y must not be.
fn quadric_curvatures(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
) -> Result<(), SceneError> {
    let (Some(form), Some((a, b))) = (geometry.curvature(), geometry.surfaces()) else {
        return Ok(());
    };
    let p = form.principal_values();
    // Along the sum's smaller principal direction, each surface's own
    // curvature: of opposite signs and summing to rounding, they cancel
    // (as along x or y, `curvatures`), whatever the angle.
    let (c, s) = (p.angle.cos(), p.angle.sin());
    let along = |k: Curvature| 2.0 * k.height(c, s);
    let (k1, k2) = (along(Curvature::of(&a)), along(Curvature::of(&b)));
    if k1 * k2 < 0.0 && p.smaller.abs() < CANCELLING_CURVATURE * k1.abs().max(k2.abs()) {
        let (field, raw_surface) = concave(raw, k1 < 0.0);
        let (key, span) = raw_surface.map_or(("", table(raw)), |t| {
            let r = t.get_ref();
            match (&r.angle, &r.radius) {
                (Some(v), _) => (".angle", v.span()),
                (None, Some(v)) => (".radius", v.span()),
                _ => ("", t.span()),
            }
        });
        return Err(ctx.invalid(
            span,
            format!("{field}{key}"),
            "",
            format!(
                "cancels the other surface along the gap's principal direction at {:.2} degrees \
                 from x: there geometry.surface1's curvature is {k1:.4e} and geometry.surface2's \
                 {k2:.4e}, so the relative curvature, {:.3e}, is below \
                 {CANCELLING_CURVATURE:.1e} of the larger, within rounding of zero: the gap along \
                 that direction is no number the solve can use (a conforming contact, which the \
                 half-space models do not describe). Give radii or angles whose curvatures there \
                 differ by more than that",
                p.angle.to_degrees(),
                p.smaller
            ),
        ));
    }
    let size = form.xx.abs() + form.yy.abs() + 2.0 * form.xy.abs();
    if p.smaller >= -CANCELLING_CURVATURE * size {
        return Ok(());
    }
    Err(ctx.invalid(
        table(raw),
        "geometry",
        Num(p.smaller),
        format!(
            "the gap's smaller principal curvature, {:.4e} along {:.2} degrees from x, is \
             negative: the bodies would interpenetrate more and more away from the first point \
             of contact; a concave direction needs a radius larger in magnitude than the convex \
             one it meets",
            p.smaller,
            p.angle.to_degrees()
        ),
    ))
}
