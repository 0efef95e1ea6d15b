//! `[body1]`, `[body2]`: a body's model and the parameters that model
//! takes, checked against their physical ranges, into an elcon-influence
//! [`Body`] (and the material the references need).

use std::ops::Range;

use elcon_influence::{Beam, Body, Material};
use toml::Spanned;

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::BodyToml;
pub use crate::schema::ModelKind;

/// One body of a scene: the model it names and the body for
/// elcon-influence (whose half-space models hold the material the
/// references need).
#[derive(Debug, Clone)]
pub struct BodySpec {
    model: ModelKind,
    body: Body,
}

impl BodySpec {
    /// The model (`body.model`).
    pub fn model(&self) -> ModelKind {
        self.model
    }

    /// The body for elcon-influence.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// The material of a half-space model (none for a rigid body, a
    /// Winkler foundation or a beam).
    pub fn material(&self) -> Option<&Material> {
        self.body.material()
    }
}

/// The keys a body of `model` takes.
fn model_keys(model: ModelKind) -> &'static [&'static str] {
    match model {
        ModelKind::Rigid => &[],
        ModelKind::PointForce | ModelKind::UniformPatch => &["youngs_modulus", "poissons_ratio"],
        ModelKind::PlaneStrain => &["youngs_modulus", "poissons_ratio", "reference_distance"],
        ModelKind::Winkler => &["modulus"],
        ModelKind::Beam => &[
            "youngs_modulus",
            "second_moment",
            "width",
            "depth",
            "loaded_point",
        ],
    }
}

pub(super) fn body(ctx: &Ctx<'_>, b: &BodyToml, section: &str) -> Result<BodySpec, SceneError> {
    let kind = *b.model.get_ref();
    let model = kind.name();
    let given: [(&str, Option<&Spanned<f64>>); 8] = [
        ("youngs_modulus", b.youngs_modulus.as_ref()),
        ("poissons_ratio", b.poissons_ratio.as_ref()),
        ("reference_distance", b.reference_distance.as_ref()),
        ("modulus", b.modulus.as_ref()),
        ("second_moment", b.second_moment.as_ref()),
        ("width", b.width.as_ref()),
        ("depth", b.depth.as_ref()),
        ("loaded_point", b.loaded_point.as_ref()),
    ];
    ctx.allowed_keys(
        section,
        &format!("the {model} model"),
        model_keys(kind),
        given
            .into_iter()
            .filter_map(|(k, v)| v.map(|v| (k, v.span(), v.get_ref().to_string()))),
    )?;
    let s = Section {
        ctx,
        b,
        name: section,
        span: b.model.span(),
    };
    let body = match kind {
        ModelKind::Rigid => Body::rigid(),
        ModelKind::PointForce => Body::point_force(s.material()?),
        ModelKind::UniformPatch => Body::uniform_patch(s.material()?),
        ModelKind::PlaneStrain => {
            let m = s.material()?;
            let d0 = s.positive(
                &b.reference_distance,
                "reference_distance",
                "by the plane-strain model (the datum distance d0 of the 2D displacements)",
            )?;
            Body::plane_strain(m, d0)
        }
        ModelKind::Winkler => {
            Body::winkler(s.positive(&b.modulus, "modulus", "by the Winkler model")?)
        }
        ModelKind::Beam => s.beam()?,
    };
    Ok(BodySpec { model: kind, body })
}

/// A body's section being read: its keys, its name (`body1`, `body2`) and
/// the span its missing keys are reported at (the model's).
struct Section<'a, 'c> {
    ctx: &'a Ctx<'c>,
    b: &'a BodyToml,
    name: &'a str,
    span: Range<usize>,
}

impl Section<'_, '_> {
    /// The field `key` of this section (`body1.youngs_modulus`).
    fn field(&self, key: &str) -> String {
        format!("{}.{key}", self.name)
    }

    /// The value of `key` (`v`), required (`why`: by which model).
    fn required<'v>(
        &self,
        v: &'v Option<Spanned<f64>>,
        key: &str,
        why: &str,
    ) -> Result<&'v Spanned<f64>, SceneError> {
        self.ctx
            .required(v, self.span.clone(), &self.field(key), why)
    }

    /// The value of `key` (`v`), required (`why`) and positive.
    fn positive(&self, v: &Option<Spanned<f64>>, key: &str, why: &str) -> Result<f64, SceneError> {
        let value = self.required(v, key, why)?;
        self.ctx.positive(value, &self.field(key))
    }

    /// A half-space model's material: E > 0 and nu in (-1, 0.5).
    fn material(&self) -> Result<Material, SceneError> {
        let (ctx, b) = (self.ctx, self.b);
        let e = self.required(&b.youngs_modulus, "youngs_modulus", "by this model")?;
        let nu = self.required(&b.poissons_ratio, "poissons_ratio", "by this model")?;
        let e_value = ctx.positive(e, &self.field("youngs_modulus"))?;
        let nu_value = *nu.get_ref();
        if !(nu_value.is_finite() && nu_value > -1.0 && nu_value < 0.5) {
            return Err(ctx.invalid(
                nu.span(),
                self.field("poissons_ratio"),
                nu_value,
                "must be in (-1, 0.5): outside it the elastic energy is not positive definite",
            ));
        }
        Material::new(e_value, nu_value).map_err(|err| {
            ctx.invalid(
                e.span(),
                self.field("youngs_modulus"),
                e_value,
                err.to_string(),
            )
        })
    }

    /// A beam: E, and I or a rectangular section's width and depth, and
    /// the loaded point (default 0).
    fn beam(&self) -> Result<Body, SceneError> {
        let (ctx, b) = (self.ctx, self.b);
        let e = self.positive(&b.youngs_modulus, "youngs_modulus", "by the beam model")?;
        let field = |key: &str| self.field(key);
        let i = match (&b.second_moment, &b.width, &b.depth) {
            (Some(i), None, None) => ctx.positive(i, &field("second_moment"))?,
            (None, Some(w), Some(d)) => {
                ctx.positive(w, &field("width"))? * ctx.positive(d, &field("depth"))?.powi(3) / 12.0
            }
            _ => {
                return Err(ctx.invalid(
                    self.span.clone(),
                    field("second_moment"),
                    "",
                    "give either second_moment, or width and depth (a rectangular section, I = w d^3 / 12)",
                ));
            }
        };
        let x0 = match &b.loaded_point {
            Some(v) => ctx.finite(v, &field("loaded_point"))?,
            None => 0.0,
        };
        let beam = Beam {
            youngs_modulus: e,
            second_moment: i,
            loaded_point: x0,
        };
        // E, I (or w and d) and x0 are checked above; what is left is I or
        // E I overflowing or underflowing, which the error names.
        Body::beam(beam).map_err(|err| {
            ctx.invalid(
                self.span.clone(),
                field("second_moment"),
                i,
                err.to_string(),
            )
        })
    }
}
