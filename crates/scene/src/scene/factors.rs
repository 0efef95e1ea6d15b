//! The inputs a magnitude bound of `check` depends on, with the powers its
//! quantity grows with, so that a refusal names the input that is out of
//! scale ([`crate::sanity::extreme`]) rather than the load. The largest
//! deformation of a load `P` on one cell ([`crate::sanity::deformation`])
//! and the solve's product `r^2 c` ([`crate::sanity::compliance_in_range`],
//! `c` a cell's compliance, `r` the residuals' size) grow as powers of the
//! load, the stiffness and the radius `R` (Hertz's contact radius
//! `a ~ (P R / E)^(1/3)` sizes a surface grid relative to it, the
//! half-width `b ~ (P R / E)^(1/2)` a line's; the largest separation is
//! `a^2 / R` over a Hertz grid, `~ 1 / R` over an absolute one):
//!
//! ```text
//!                              deformation w          r^2 c (r = w)       r^2 c (r = separation)
//!   half-space, Hertz surface  P^2/3 E^-2/3 R^-1/3    P E^-2 R^-1         P E^-2 R^-1
//!   half-space, Hertz line     P E^-1                 P^2 E^-3            P^2 E^-3
//!   absolute grid              P S^-1                 P^2 S^-3            S^-1 R^-2
//! ```
//!
//! with S the stiffness of the mechanism that deforms most (E* of the
//! half-space bodies, a foundation's k, a free beam's E).

use elcon_analysis::Normal;
use elcon_influence::{Body, Model, PointSet};

use super::points::{HertzLayout, PointsSpec};
use crate::sanity::{Factor, Mechanism, mechanism};
use crate::schema::SceneFile;
use toml::Spanned;

/// The quantity a bound limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Quantity {
    /// The load's largest deformation on one cell.
    Deformation,
    /// The solve's product `r^2 c`; `load`: its residuals are the load's
    /// deformation (else the largest separation).
    Product {
        /// Whether the residuals are the load's deformation.
        load: bool,
    },
}

/// How the grid is sized.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Sizing {
    HertzSurface,
    HertzLine,
    Absolute,
}

/// The inputs `quantity` depends on under `normal` on `points` (laid out
/// by `spec`), each with its field, value and power (see the module
/// documentation): the load or approach, the stiffness of the mechanism
/// that deforms most, the radius of the surface that curves most.
pub(super) fn factors(
    raw: &SceneFile,
    pair: [&Body; 2],
    spec: &PointsSpec,
    normal: Normal,
    points: &PointSet,
    quantity: Quantity,
) -> Vec<Factor> {
    let Some(mechanism) = mechanism(pair, points) else {
        return Vec::new();
    };
    let sizing = match spec {
        PointsSpec::Hertz(HertzLayout::Disk { .. } | HertzLayout::Ellipse { .. }) => {
            Sizing::HertzSurface
        }
        PointsSpec::Hertz(HertzLayout::Line { .. } | HertzLayout::Rectangle { .. }) => {
            Sizing::HertzLine
        }
        _ => Sizing::Absolute,
    };
    // The powers of the load, the stiffness and the radius.
    let (p, s, r) = match (sizing, quantity) {
        (Sizing::HertzSurface, Quantity::Deformation) => (2.0 / 3.0, -2.0 / 3.0, -1.0 / 3.0),
        (Sizing::HertzSurface, Quantity::Product { .. }) => (1.0, -2.0, -1.0),
        (Sizing::HertzLine, Quantity::Deformation) => (1.0, -1.0, 0.0),
        (Sizing::HertzLine, Quantity::Product { .. }) => (2.0, -3.0, 0.0),
        (Sizing::Absolute, Quantity::Deformation) => (1.0, -1.0, 0.0),
        (Sizing::Absolute, Quantity::Product { load: true }) => (2.0, -3.0, 0.0),
        (Sizing::Absolute, Quantity::Product { load: false }) => (0.0, -1.0, -2.0),
    };
    // An approach is its own deformation, whatever the stiffness: the
    // product's r^2 c then grows as the compliance c alone, 1 / S.
    let s = match (normal, quantity) {
        (Normal::Approach(_), Quantity::Deformation) => 0.0,
        (Normal::Approach(_), Quantity::Product { load: true }) => -1.0,
        _ => s,
    };
    let mut out = Vec::new();
    let t = raw.loading.get_ref();
    let (field, given, what) = match normal {
        Normal::Load(_) => ("loading.load", t.load.as_ref(), "a load"),
        Normal::Approach(_) => ("loading.approach", t.approach.as_ref(), "an approach"),
    };
    if let Some(v) = given {
        out.push(Factor {
            field: field.to_string(),
            span: v.span(),
            value: *v.get_ref(),
            power: p,
            what,
            combined: (1.0, 0.0),
        });
    }
    if let Some(f) = stiffness(raw, pair, mechanism, s) {
        out.push(f);
    }
    if r != 0.0
        && let Some(f) = radius(raw, r)
    {
        out.push(f);
    }
    out.retain(|f| f.power != 0.0);
    out
}

/// The stiffness of `mechanism` as written: the more compliant half-space
/// body's `youngs_modulus`, a foundation's `modulus`, a beam's
/// `youngs_modulus`.
fn stiffness(
    raw: &SceneFile,
    pair: [&Body; 2],
    mechanism: Mechanism,
    power: f64,
) -> Option<Factor> {
    let sections = [
        ("body1", raw.body1.get_ref()),
        ("body2", raw.body2.get_ref()),
    ];
    let index = match mechanism {
        Mechanism::HalfSpace => {
            (0..2)
                .filter(|&i| pair[i].material().is_some())
                .max_by(|&a, &b| {
                    let c = |i: usize| pair[i].material().map_or(0.0, |m| m.compliance());
                    c(a).total_cmp(&c(b))
                })?
        }
        Mechanism::Foundation => {
            (0..2).find(|&i| matches!(pair[i].model(), Model::Winkler { .. }))?
        }
        Mechanism::Beam => (0..2).find(|&i| matches!(pair[i].model(), Model::Beam { .. }))?,
    };
    let (section, t) = sections[index];
    // Two half-space bodies deform by E*: `1 / E* = (1 - nu^2) / E + the
    // other's compliance`.
    let combined = match (mechanism, pair[index].material()) {
        (Mechanism::HalfSpace, Some(m)) => {
            let nu = m.poissons_ratio();
            let other = pair[1 - index].material().map_or(0.0, |m| m.compliance());
            (1.0 - nu * nu, other)
        }
        _ => (1.0, 0.0),
    };
    let (key, value, what) = match mechanism {
        Mechanism::Foundation => ("modulus", t.modulus.as_ref()?, "a modulus"),
        _ => (
            "youngs_modulus",
            t.youngs_modulus.as_ref()?,
            "a youngs_modulus",
        ),
    };
    Some(Factor {
        field: format!("{section}.{key}"),
        span: value.span(),
        value: *value.get_ref(),
        power,
        what,
        combined,
    })
}

/// The radius of the surface that curves most (the smallest in
/// magnitude of the spheres' and cylinders' `radius`), which sets the
/// gap's curvature with the other surface's (`1 / R = 1 / R_1 + 1 /
/// R_2`, a plane's 0).
fn radius(raw: &SceneFile, power: f64) -> Option<Factor> {
    let g = raw.geometry.as_ref()?.get_ref();
    let radii: Vec<(&str, &Spanned<f64>)> = [
        ("geometry.surface1", &g.surface1),
        ("geometry.surface2", &g.surface2),
    ]
    .into_iter()
    .filter_map(|(field, s)| {
        let r = s.as_ref()?.get_ref().radius.as_ref()?;
        Some((field, r))
    })
    .collect();
    let (i, &(field, r)) = radii
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.1.get_ref().abs().total_cmp(&b.1.1.get_ref().abs()))?;
    let other = radii
        .iter()
        .enumerate()
        .find(|&(j, _)| j != i)
        .map_or(0.0, |(_, (_, r))| 1.0 / *r.get_ref());
    Some(Factor {
        field: format!("{field}.radius"),
        span: r.span(),
        value: *r.get_ref(),
        power,
        what: "a radius",
        combined: (1.0, other),
    })
}
