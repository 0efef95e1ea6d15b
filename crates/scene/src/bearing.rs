//! A bearing scene: a rolling bearing's data (a `[bearing]` table) in place
//! of a single contact's bodies, surfaces and points. elcon-elements turns
//! it into a system of contacts (two zones per rolling element, sharing the
//! rings); docs/scenes.md documents the keys.
//!
//! ```toml
//! [units]
//! length = "mm"
//! force = "N"
//! pressure = "MPa"
//!
//! [material]                  # rings and balls
//! youngs_modulus = 210e3
//! poissons_ratio = 0.3
//!
//! [bearing]
//! type = "ball"
//! ball_diameter = 7.938
//! inner_raceway_diameter = 31.0
//! outer_raceway_diameter = 46.9
//! inner_groove_radius = 4.128
//! outer_groove_radius = 4.207
//! balls = 9
//! radial_load = 2000.0
//! ```

use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use elcon_analysis::Material;
use elcon_elements::ElementsError;
use elcon_elements::bearing::{BallBearing, BearingGrid};

use crate::SceneError;
use crate::ctx::{Ctx, keywords, parse};
use crate::scene::Units;
use crate::schema::{MetaToml, UnitsToml};

/// Whether a scene text is a bearing's (it has a `[bearing]` table).
pub fn is_bearing_text(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("bearing"))
}

keywords! {
    /// A bearing's `type`.
    pub enum BearingKind {
        /// `"ball"`: a deep-groove radial ball bearing.
        Ball = "ball",
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingFileToml {
    scene: Option<MetaToml>,
    units: UnitsToml,
    material: MaterialToml,
    bearing: BearingToml,
    points: Option<BearingPointsToml>,
    outputs: Option<BearingOutputsToml>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialToml {
    youngs_modulus: Spanned<f64>,
    poissons_ratio: Spanned<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingToml {
    #[serde(rename = "type")]
    kind: Spanned<BearingKind>,
    ball_diameter: Spanned<f64>,
    inner_raceway_diameter: Spanned<f64>,
    outer_raceway_diameter: Spanned<f64>,
    inner_groove_radius: Spanned<f64>,
    outer_groove_radius: Spanned<f64>,
    balls: Spanned<i64>,
    diametral_clearance: Option<Spanned<f64>>,
    radial_load: Spanned<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingPointsToml {
    across: Option<Spanned<i64>>,
    zone: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingOutputsToml {
    plots: Option<bool>,
}

/// A bearing scene, validated.
#[derive(Debug, Clone)]
pub struct BearingScene {
    name: String,
    file: PathBuf,
    description: Option<String>,
    units: Units,
    kind: BearingKind,
    bearing: BallBearing,
    grid: BearingGrid,
    plots: bool,
}

impl BearingScene {
    /// The scene's name (default: the file's stem): it names the output
    /// directory.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The file it came from.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// Its description, if it has one.
    pub fn description(&self) -> Option<&str> {
        self.description.as_deref()
    }

    /// The unit labels.
    pub fn units(&self) -> &Units {
        &self.units
    }

    /// The bearing's type.
    pub fn kind(&self) -> BearingKind {
        self.kind
    }

    /// The ball bearing.
    pub fn bearing(&self) -> &BallBearing {
        &self.bearing
    }

    /// Each contact's grid.
    pub fn grid(&self) -> BearingGrid {
        self.grid
    }

    /// Whether the plots are drawn (`[outputs] plots`, default true).
    pub fn plots(&self) -> bool {
        self.plots
    }

    /// Whether the rating life applies: its capacities' constant is for
    /// newtons and millimetres.
    pub fn rates_life(&self) -> bool {
        self.units.length() == "mm" && self.units.force() == "N"
    }

    /// The points of one contact's grid and the peak memory of the solve
    /// (bytes): the two zone templates' dense S, and per thread a zone's
    /// solve (its restricted factor and the engine's work, each at most
    /// the size of S).
    pub fn memory(&self, threads: usize) -> (usize, u64) {
        let a = self.grid.across as f64 * self.grid.zone;
        let n = (a * a).ceil() as u64;
        let square = 8 * n * n;
        let zones = 2 * self.bearing.balls as u64;
        (
            n as usize,
            2 * square + threads as u64 * 2 * square + zones * 200 * n,
        )
    }

    /// Reads a bearing scene from its text (`file` names it in messages).
    ///
    /// # Errors
    /// [`SceneError::Syntax`] for text that is not TOML or not the schema
    /// (an unknown key, a missing one); [`SceneError::Invalid`] naming the
    /// field, its line and column, and why, for a value out of range.
    pub fn from_str(file: &Path, text: &str) -> Result<Self, SceneError> {
        let ctx = Ctx::new(file, text);
        let toml: BearingFileToml = parse(file, text)?;
        let units = crate::scene::units_of(&ctx, &toml.units)?;
        let m = &toml.material;
        let e = ctx.positive(&m.youngs_modulus, "material.youngs_modulus")?;
        let nu = ctx.finite(&m.poissons_ratio, "material.poissons_ratio")?;
        let material = Material::new(e, nu).map_err(|why| {
            ctx.invalid(
                m.poissons_ratio.span(),
                "material.poissons_ratio",
                elcon_analysis::Num(nu),
                why.to_string(),
            )
        })?;
        let b = &toml.bearing;
        let balls = ctx.count(&b.balls, "bearing.balls", 1)?;
        let bearing = BallBearing {
            ball_diameter: *b.ball_diameter.get_ref(),
            inner_raceway_diameter: *b.inner_raceway_diameter.get_ref(),
            outer_raceway_diameter: *b.outer_raceway_diameter.get_ref(),
            inner_groove_radius: *b.inner_groove_radius.get_ref(),
            outer_groove_radius: *b.outer_groove_radius.get_ref(),
            balls,
            diametral_clearance: b.diametral_clearance.as_ref().map(|c| *c.get_ref()),
            material,
            radial_load: *b.radial_load.get_ref(),
        };
        bearing.validate().map_err(|e| located(&ctx, b, e))?;
        let points = toml.points.as_ref();
        let defaults = BearingGrid::default();
        let across = match points.and_then(|p| p.across.as_ref()) {
            Some(a) => {
                let n = ctx.count(a, "points.across", 3)?;
                ctx.ensure(
                    n,
                    !n.is_multiple_of(2),
                    a.span(),
                    "points.across",
                    "must be odd (the centre is a point)",
                )?
            }
            None => defaults.across,
        };
        let zone = match points.and_then(|p| p.zone.as_ref()) {
            Some(z) => {
                let v = ctx.positive(z, "points.zone")?;
                ctx.ensure(
                    v,
                    v >= 1.0,
                    z.span(),
                    "points.zone",
                    "must be at least 1 (the grid covers the Hertz ellipse)",
                )?
            }
            None => defaults.zone,
        };
        let meta = toml.scene.as_ref();
        let name = meta
            .and_then(|s| s.name.as_ref())
            .map(|n| n.get_ref().clone())
            .unwrap_or_else(|| {
                file.file_stem()
                    .map_or("bearing".into(), |s| s.to_string_lossy().into_owned())
            });
        Ok(Self {
            name,
            file: file.to_path_buf(),
            description: meta.and_then(|s| s.description.clone()),
            units,
            kind: *b.kind.get_ref(),
            bearing,
            grid: BearingGrid { across, zone },
            plots: toml.outputs.as_ref().and_then(|o| o.plots).unwrap_or(true),
        })
    }

    /// Reads a bearing scene file.
    ///
    /// # Errors
    /// As [`BearingScene::from_str`], and [`SceneError::Io`] when the file
    /// cannot be read.
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = crate::read_text(path)?;
        Self::from_str(path, &text)
    }
}

/// The bearing's refusal at the line of the key it names.
fn located(ctx: &Ctx<'_>, b: &BearingToml, e: ElementsError) -> SceneError {
    let ElementsError::InvalidInput {
        field,
        value,
        reason,
    } = e
    else {
        return SceneError::Points {
            reason: e.to_string(),
        };
    };
    let span = match field {
        "ball_diameter" => b.ball_diameter.span(),
        "inner_raceway_diameter" => b.inner_raceway_diameter.span(),
        "outer_raceway_diameter" => b.outer_raceway_diameter.span(),
        "inner_groove_radius" => b.inner_groove_radius.span(),
        "outer_groove_radius" => b.outer_groove_radius.span(),
        "balls" => b.balls.span(),
        "radial_load" => b.radial_load.span(),
        _ => b
            .diametral_clearance
            .as_ref()
            .map_or(b.outer_raceway_diameter.span(), |c| c.span()),
    };
    ctx.invalid(
        span,
        format!("bearing.{field}"),
        elcon_analysis::Num(value),
        reason,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = r#"
[units]
length = "mm"
force = "N"
pressure = "MPa"

[material]
youngs_modulus = 210e3
poissons_ratio = 0.3

[bearing]
type = "ball"
ball_diameter = 7.938
inner_raceway_diameter = 31.0
outer_raceway_diameter = 46.9
inner_groove_radius = 4.12776
outer_groove_radius = 4.20714
balls = 9
radial_load = 2000.0
"#;

    #[test]
    fn a_bearing_scene_reads_with_its_defaults() {
        assert!(is_bearing_text(SCENE) && !is_bearing_text("[scene]\nname = \"x\""));
        let s = BearingScene::from_str(Path::new("radial.toml"), SCENE).unwrap();
        assert_eq!(s.name(), "radial");
        assert_eq!(s.bearing().balls, 9);
        assert_eq!(s.grid(), BearingGrid::default());
        assert!(s.plots() && s.rates_life());
    }

    #[test]
    fn each_bad_value_is_named_at_its_line() {
        for (from, to, field) in [
            ("balls = 9", "balls = 0", "bearing.balls"),
            ("balls = 9", "balls = 30", "bearing.balls"),
            (
                "inner_groove_radius = 4.12776",
                "inner_groove_radius = 3.0",
                "bearing.inner_groove_radius",
            ),
            (
                "radial_load = 2000.0",
                "radial_load = -1.0",
                "bearing.radial_load",
            ),
            (
                "radial_load = 2000.0",
                "radial_load = 2000.0\ndiametral_clearance = -5.0",
                "bearing.diametral_clearance",
            ),
            ("type = \"ball\"", "type = \"needle\"", "type"),
            (
                "poissons_ratio = 0.3",
                "poissons_ratio = 0.7",
                "material.poissons_ratio",
            ),
            ("balls = 9", "balls = 9\nspeed = 3000", "speed"),
        ] {
            let text = SCENE.replace(from, to);
            let e = BearingScene::from_str(Path::new("b.toml"), &text).unwrap_err();
            assert!(e.to_string().contains(field), "{field}: {e}");
        }
        let e = BearingScene::from_str(
            Path::new("b.toml"),
            &format!("{SCENE}\n[points]\nacross = 20\n"),
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("points.across") && e.to_string().contains("odd"),
            "{e}"
        );
    }
}
