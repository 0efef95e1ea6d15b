//! `[geometry]`: the two surfaces (plane, sphere, cylinder, quadric) or a
//! given separation, and the combined curvature radius of two surfaces.
//! A quadric `{ shape = "quadric", radius_x, radius_y, angle }` has its
//! principal radii along the direction `angle` degrees from x and across
//! it (an omitted radius is straight; a negative one concave), its height
//! `(u^2 / R_x + v^2 / R_y) / 2` in those axes (`elcon_analysis::Surface`).

use elcon_analysis::{Geometry, Surface};
use elcon_influence::Dimension;
use toml::Spanned;

use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::schema::{GeometryToml, Shape, SurfaceToml};

/// The largest size of a quadric's `angle` (degrees): one turn either way.
pub(crate) const MAX_ANGLE: f64 = 360.0;

fn surface(
    ctx: &Ctx<'_>,
    s: &Spanned<SurfaceToml>,
    field: &str,
    dimension: Dimension,
) -> Result<Surface, SceneError> {
    let t = s.get_ref();
    let shape = *t.shape.get_ref();
    if shape == Shape::Quadric {
        let why = "a quadric has radius_x and radius_y";
        ctx.forbid(&t.radius, &format!("{field}.radius"), why)?;
    } else {
        for (v, key) in [
            (&t.radius_x, "radius_x"),
            (&t.radius_y, "radius_y"),
            (&t.angle, "angle"),
        ] {
            ctx.forbid(v, &format!("{field}.{key}"), "only a quadric has it")?;
        }
    }
    if dimension == Dimension::Line && matches!(shape, Shape::Sphere | Shape::Quadric) {
        return Err(ctx.invalid(
            t.shape.span(),
            format!("{field}.shape"),
            format!("\"{shape}\""),
            format!("a {shape} needs a surface grid; on a line use a cylinder"),
        ));
    }
    let radius = |ctx: &Ctx<'_>| -> Result<f64, SceneError> {
        let key = format!("{field}.radius");
        let r = ctx.required(&t.radius, s.span(), &key, "for a curved surface")?;
        let v = ctx.finite(r, &key)?;
        let why = "must be non-zero (negative for a concave surface)";
        let v = ctx.ensure(v, v != 0.0, r.span(), &key, why)?;
        curved(ctx, v, r, &key)
    };
    match shape {
        Shape::Plane => {
            ctx.forbid(
                &t.radius,
                &format!("{field}.radius"),
                "a plane has no radius",
            )?;
            Ok(Surface::Plane)
        }
        Shape::Sphere => Ok(Surface::Sphere {
            radius: radius(ctx)?,
        }),
        Shape::Cylinder => Ok(Surface::Cylinder {
            radius: radius(ctx)?,
        }),
        Shape::Quadric => quadric(ctx, s, field),
    }
}

/// A non-zero radius `v` (written at `r`, under `key`) whose curvature
/// `1 / v` is a number: a radius below 1 / f64::MAX (5.6e-309) in
/// magnitude has an infinite curvature, which no gap can be made of.
fn curved(ctx: &Ctx<'_>, v: f64, r: &Spanned<f64>, key: &str) -> Result<f64, SceneError> {
    ctx.ensure(
        v,
        (1.0 / v).is_finite(),
        r.span(),
        key,
        format!(
            "is too small: its curvature 1 / radius is beyond the largest number (a radius \
             must be at least {} in magnitude; check the length unit)",
            Num(1.0 / f64::MAX)
        ),
    )
}

/// A quadric: `radius_x`, `radius_y` (at least one; an omitted one is
/// straight), `angle` in degrees (default 0), on a surface grid.
fn quadric(ctx: &Ctx<'_>, s: &Spanned<SurfaceToml>, field: &str) -> Result<Surface, SceneError> {
    let t = s.get_ref();
    if t.radius_x.is_none() && t.radius_y.is_none() {
        return Err(ctx.invalid(
            s.span(),
            format!("{field}.radius_x"),
            "",
            "a quadric needs radius_x, radius_y or both (an omitted one is straight)",
        ));
    }
    let radius = |v: &Option<Spanned<f64>>, key: &str| -> Result<f64, SceneError> {
        let Some(r) = v else {
            return Ok(f64::INFINITY);
        };
        let value = ctx.finite(r, &format!("{field}.{key}"))?;
        let value = ctx.ensure(
            value,
            value != 0.0,
            r.span(),
            &format!("{field}.{key}"),
            "must be non-zero (negative for a concave direction; omit it for a straight one)",
        )?;
        curved(ctx, value, r, &format!("{field}.{key}"))
    };
    let angle = match &t.angle {
        Some(a) => {
            let key = format!("{field}.angle");
            let degrees = ctx.finite(a, &key)?;
            ctx.ensure(
                degrees,
                degrees.abs() <= MAX_ANGLE,
                a.span(),
                &key,
                format!(
                    "must be within -{MAX_ANGLE} to {MAX_ANGLE} degrees (a quadric repeats every \
                     180 degrees; far beyond a turn the rounding of the value exceeds a degree)"
                ),
            )?
            .to_radians()
        }
        None => 0.0,
    };
    Ok(Surface::Quadric {
        radius_x: radius(&t.radius_x, "radius_x")?,
        radius_y: radius(&t.radius_y, "radius_y")?,
        angle,
    })
}

pub(super) fn geometry(
    ctx: &Ctx<'_>,
    g: Option<&Spanned<GeometryToml>>,
    dimension: Dimension,
) -> Result<Geometry, SceneError> {
    let Some(g) = g else {
        return Ok(Geometry::Surfaces(Surface::Plane, Surface::Plane));
    };
    let t: &GeometryToml = g.get_ref();
    if t.separation.is_some() || t.separation_file.is_some() {
        let why = "give either surfaces (with height_map, profile) or separations, not both";
        ctx.forbid(&t.surface1, "geometry.surface1", why)?;
        ctx.forbid(&t.surface2, "geometry.surface2", why)?;
        ctx.forbid(&t.height_map, "geometry.height_map", why)?;
        ctx.forbid(&t.profile, "geometry.profile", why)?;
    }
    if let Some(file) = &t.separation_file {
        ctx.forbid(
            &t.separation,
            "geometry.separation",
            "give separation (inline) or separation_file, not both",
        )?;
        ctx.ensure(
            file.get_ref(),
            !file.get_ref().is_empty(),
            file.span(),
            "geometry.separation_file",
            "must name a file",
        )?;
        // Matched to the candidate points once they are laid out
        // (`super::files::separations`).
        return Ok(Geometry::Surfaces(Surface::Plane, Surface::Plane));
    }
    if let Some(sep) = &t.separation {
        let values = sep
            .get_ref()
            .iter()
            .enumerate()
            .map(|(k, v)| ctx.finite(v, &format!("geometry.separation[{k}]")))
            .collect::<Result<Vec<f64>, _>>()?;
        return Ok(Geometry::Separation(values));
    }
    let s1 = match &t.surface1 {
        Some(s) => surface(ctx, s, "geometry.surface1", dimension)?,
        None => Surface::Plane,
    };
    let s2 = match &t.surface2 {
        Some(s) => surface(ctx, s, "geometry.surface2", dimension)?,
        None => Surface::Plane,
    };
    let mut departures = Vec::new();
    if let Some(m) = &t.height_map {
        if dimension == Dimension::Line {
            return Err(ctx.invalid(
                m.span(),
                "geometry.height_map",
                "",
                "a height map needs a surface grid; on a line use a profile along x",
            ));
        }
        departures.push(super::files::height_map(ctx, m)?);
    }
    if let Some(p) = &t.profile {
        departures.push(super::files::profile(ctx, p)?);
    }
    Ok(if departures.is_empty() {
        Geometry::Surfaces(s1, s2)
    } else {
        Geometry::Tabulated {
            surfaces: (s1, s2),
            departures,
        }
    })
}

/// Curvature radius of the surfaces' sum (`1/R = 1/R1 + 1/R2`) if both are
/// spheres/planes (`spheres`) or cylinders/planes, and not both planes.
pub(super) fn combined(geometry: &Geometry, spheres: bool) -> Option<f64> {
    let (a, b) = &geometry.surfaces()?;
    let curvature = |s: &Surface| match (*s, spheres) {
        (Surface::Plane, _) => Some(0.0),
        (Surface::Sphere { radius }, true) | (Surface::Cylinder { radius }, false) => {
            Some(1.0 / radius)
        }
        _ => None,
    };
    let k = curvature(a)? + curvature(b)?;
    (k > 0.0).then(|| 1.0 / k)
}
