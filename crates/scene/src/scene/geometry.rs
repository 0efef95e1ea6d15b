//! `[geometry]`: the two surfaces (plane, sphere, cylinder) or a given
//! separation, and the combined curvature radius of two surfaces.

use elcon_analysis::{Geometry, Surface};
use elcon_influence::Dimension;
use toml::Spanned;

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::{GeometryToml, Shape, SurfaceToml};

fn surface(
    ctx: &Ctx<'_>,
    s: &Spanned<SurfaceToml>,
    field: &str,
    dimension: Dimension,
) -> Result<Surface, SceneError> {
    let t = s.get_ref();
    let radius = |ctx: &Ctx<'_>| -> Result<f64, SceneError> {
        let r = ctx.required(
            &t.radius,
            s.span(),
            &format!("{field}.radius"),
            "for a curved surface",
        )?;
        let v = ctx.finite(r, &format!("{field}.radius"))?;
        if v == 0.0 {
            return Err(ctx.invalid(
                r.span(),
                format!("{field}.radius"),
                v,
                "must be non-zero (negative for a concave surface)",
            ));
        }
        Ok(v)
    };
    match *t.shape.get_ref() {
        Shape::Plane => {
            ctx.forbid(
                &t.radius,
                &format!("{field}.radius"),
                "a plane has no radius",
            )?;
            Ok(Surface::Plane)
        }
        Shape::Sphere => {
            if dimension == Dimension::Line {
                return Err(ctx.invalid(
                    t.shape.span(),
                    format!("{field}.shape"),
                    "\"sphere\"",
                    "a sphere needs a surface grid; on a line use a cylinder",
                ));
            }
            Ok(Surface::Sphere {
                radius: radius(ctx)?,
            })
        }
        Shape::Cylinder => Ok(Surface::Cylinder {
            radius: radius(ctx)?,
        }),
    }
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
    match &t.separation {
        Some(sep) => {
            for (f, name) in [
                (&t.surface1, "geometry.surface1"),
                (&t.surface2, "geometry.surface2"),
            ] {
                ctx.forbid(f, name, "give either surfaces or a separation, not both")?;
            }
            let values = sep
                .get_ref()
                .iter()
                .enumerate()
                .map(|(k, v)| ctx.finite(v, &format!("geometry.separation[{k}]")))
                .collect::<Result<Vec<f64>, _>>()?;
            Ok(Geometry::Separation(values))
        }
        None => {
            let s1 = match &t.surface1 {
                Some(s) => surface(ctx, s, "geometry.surface1", dimension)?,
                None => Surface::Plane,
            };
            let s2 = match &t.surface2 {
                Some(s) => surface(ctx, s, "geometry.surface2", dimension)?,
                None => Surface::Plane,
            };
            Ok(Geometry::Surfaces(s1, s2))
        }
    }
}

/// Curvature radius of the surfaces' sum (`1/R = 1/R1 + 1/R2`) if both are
/// spheres/planes (`spheres`) or cylinders/planes, and not both planes.
pub(super) fn combined(geometry: &Geometry, spheres: bool) -> Option<f64> {
    let Geometry::Surfaces(a, b) = geometry else {
        return None;
    };
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
