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

use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use elcon_analysis::Material;
use elcon_elements::ElementsError;
use elcon_elements::bearing::{BallBearing, BearingGrid};
use elcon_elements::roller::{Crown, RollerBearing, RollerGrid};

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
        /// `"roller"`: a cylindrical roller bearing.
        Roller = "roller",
    }
}

keywords! {
    /// A roller's crown `shape`.
    enum CrownShape {
        /// `"straight"`.
        Straight = "straight",
        /// `"circular"`: `drop` at the ends, straight over `flat`.
        Circular = "circular",
        /// `"logarithmic"`: Lundberg's profile for `load`.
        Logarithmic = "logarithmic",
        /// `"table"`: `(position, drop)` rows from a CSV `file`.
        Table = "table",
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
    design: Option<Spanned<BearingDesignToml>>,
    outputs: Option<BearingOutputsToml>,
}

keywords! {
    /// A bearing crown design's `family`.
    pub enum CrownFamily {
        /// `"free"`: one drop per station along the roller.
        Free = "free",
        /// `"quadratic"`: the paper's `a s^2 + b s + c`.
        Quadratic = "quadratic",
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingDesignToml {
    family: Spanned<CrownFamily>,
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
    inner_raceway_diameter: Spanned<f64>,
    outer_raceway_diameter: Spanned<f64>,
    diametral_clearance: Option<Spanned<f64>>,
    radial_load: Spanned<f64>,
    ball_diameter: Option<Spanned<f64>>,
    inner_groove_radius: Option<Spanned<f64>>,
    outer_groove_radius: Option<Spanned<f64>>,
    balls: Option<Spanned<i64>>,
    roller_diameter: Option<Spanned<f64>>,
    roller_length: Option<Spanned<f64>>,
    rollers: Option<Spanned<i64>>,
    crown: Option<Spanned<CrownToml>>,
    misalignment: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CrownToml {
    shape: Spanned<CrownShape>,
    drop: Option<Spanned<f64>>,
    flat: Option<Spanned<f64>>,
    load: Option<Spanned<f64>>,
    file: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingPointsToml {
    across: Option<Spanned<i64>>,
    along: Option<Spanned<i64>>,
    zone: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BearingOutputsToml {
    plots: Option<bool>,
    subsurface: Option<bool>,
}

/// The bearing of a scene and its contacts' grid.
#[derive(Debug, Clone, PartialEq)]
pub enum BearingSpec {
    /// A radial ball bearing.
    Ball {
        /// Its data.
        bearing: BallBearing,
        /// Each contact's grid.
        grid: BearingGrid,
    },
    /// A cylindrical roller bearing.
    Roller {
        /// Its data.
        bearing: RollerBearing,
        /// Each contact's grid.
        grid: RollerGrid,
    },
}

impl BearingSpec {
    /// The number of rolling elements.
    pub fn elements(&self) -> usize {
        match self {
            BearingSpec::Ball { bearing, .. } => bearing.balls,
            BearingSpec::Roller { bearing, .. } => bearing.rollers,
        }
    }

    /// The diametral clearance used (length).
    pub fn clearance(&self) -> f64 {
        match self {
            BearingSpec::Ball { bearing, .. } => bearing.clearance(),
            BearingSpec::Roller { bearing, .. } => bearing.clearance(),
        }
    }

    /// The radial load (force).
    pub fn radial_load(&self) -> f64 {
        match self {
            BearingSpec::Ball { bearing, .. } => bearing.radial_load,
            BearingSpec::Roller { bearing, .. } => bearing.radial_load,
        }
    }

    /// The pitch diameter (length).
    pub fn pitch_diameter(&self) -> f64 {
        match self {
            BearingSpec::Ball { bearing, .. } => bearing.pitch_diameter(),
            BearingSpec::Roller { bearing, .. } => bearing.pitch_diameter(),
        }
    }

    /// The points of one contact's grid (about).
    pub fn points(&self) -> usize {
        match self {
            BearingSpec::Ball { grid, .. } => {
                let a = grid.across as f64 * grid.zone;
                (a * a).ceil() as usize
            }
            BearingSpec::Roller { grid, .. } => {
                (grid.across as f64 * grid.zone).ceil() as usize * grid.along
            }
        }
    }
}

/// A bearing scene, validated.
#[derive(Debug, Clone)]
pub struct BearingScene {
    name: String,
    file: PathBuf,
    description: Option<String>,
    units: Units,
    spec: BearingSpec,
    crown_design: Option<CrownFamily>,
    plots: bool,
    subsurface: bool,
    inputs: Vec<crate::DataInput>,
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
        match self.spec {
            BearingSpec::Ball { .. } => BearingKind::Ball,
            BearingSpec::Roller { .. } => BearingKind::Roller,
        }
    }

    /// The bearing and its grid.
    pub fn spec(&self) -> &BearingSpec {
        &self.spec
    }

    /// The crown design asked for (`[design] family`, roller bearings):
    /// the rollers' crown designed over the bearing's own loaded rollers.
    pub fn crown_design(&self) -> Option<CrownFamily> {
        self.crown_design
    }

    /// The data files it read (a crown's table), with their hashes.
    pub fn inputs(&self) -> &[crate::DataInput] {
        &self.inputs
    }

    /// Whether the stresses below each loaded element's contacts are
    /// computed (`[outputs] subsurface`, default false).
    pub fn subsurface(&self) -> bool {
        self.subsurface
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
    /// (bytes): the two zone templates' S (dense: `8 N^2` each; a large
    /// roller contact matrix-free: its FFT kernel and buffers), per thread
    /// a zone's solve (its restricted factor and the engine's work, each at
    /// most the size of a dense S), and every zone's solution.
    pub fn memory(&self, threads: usize) -> (usize, u64) {
        let n = self.spec.points() as u64;
        let dense = match &self.spec {
            BearingSpec::Ball { .. } => true,
            BearingSpec::Roller { .. } => n as usize <= elcon_elements::roller::DENSE_ROLLER_POINTS,
        };
        let square = if dense { 8 * n * n } else { 128 * n };
        let zones = 2 * self.spec.elements() as u64;
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
        let spec = match *toml.bearing.kind.get_ref() {
            BearingKind::Ball => ball(&ctx, &toml, material)?,
            BearingKind::Roller => roller(&ctx, &toml, material)?,
        };
        let crown_design = match (&toml.design, &spec) {
            (None, _) => None,
            (Some(d), BearingSpec::Roller { .. }) => Some(*d.get_ref().family.get_ref()),
            (Some(d), BearingSpec::Ball { .. }) => {
                return Err(ctx.invalid(
                    d.span(),
                    "design",
                    "(given)",
                    "a ball bearing's raceways are not designed here: [design] designs a roller \
                     bearing's crown",
                ));
            }
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
            spec,
            crown_design,
            plots: toml.outputs.as_ref().and_then(|o| o.plots).unwrap_or(true),
            subsurface: toml
                .outputs
                .as_ref()
                .and_then(|o| o.subsurface)
                .unwrap_or(false),
            inputs: ctx.inputs.take(),
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

/// The keys of `[bearing]` that `kind` does not take.
const NOT_FOR: [(BearingKind, &[&str]); 2] = [
    (
        BearingKind::Ball,
        &[
            "roller_diameter",
            "roller_length",
            "rollers",
            "crown",
            "misalignment",
        ],
    ),
    (
        BearingKind::Roller,
        &[
            "ball_diameter",
            "inner_groove_radius",
            "outer_groove_radius",
            "balls",
        ],
    ),
];

/// A key of `[bearing]` given in the file: its value (0 for a table) and
/// where it is.
type Given = Option<(f64, Range<usize>)>;

/// `[bearing]`'s keys by name: their values and spans.
fn keys(b: &BearingToml) -> Vec<(&'static str, Given)> {
    let f = |v: &Option<Spanned<f64>>| v.as_ref().map(|v| (*v.get_ref(), v.span()));
    let i = |v: &Option<Spanned<i64>>| v.as_ref().map(|v| (*v.get_ref() as f64, v.span()));
    let c = |v: &Option<Spanned<CrownToml>>| v.as_ref().map(|v| (0.0, v.span()));
    vec![
        ("ball_diameter", f(&b.ball_diameter)),
        ("inner_groove_radius", f(&b.inner_groove_radius)),
        ("outer_groove_radius", f(&b.outer_groove_radius)),
        ("balls", i(&b.balls)),
        ("roller_diameter", f(&b.roller_diameter)),
        ("roller_length", f(&b.roller_length)),
        ("rollers", i(&b.rollers)),
        ("crown", c(&b.crown)),
        ("misalignment", f(&b.misalignment)),
        ("diametral_clearance", f(&b.diametral_clearance)),
        (
            "inner_raceway_diameter",
            Some((
                *b.inner_raceway_diameter.get_ref(),
                b.inner_raceway_diameter.span(),
            )),
        ),
        (
            "outer_raceway_diameter",
            Some((
                *b.outer_raceway_diameter.get_ref(),
                b.outer_raceway_diameter.span(),
            )),
        ),
        (
            "radial_load",
            Some((*b.radial_load.get_ref(), b.radial_load.span())),
        ),
    ]
}

/// Refuses the keys the bearing's type does not take, and returns the
/// value of each it requires.
fn required(
    ctx: &Ctx<'_>,
    toml: &BearingFileToml,
    needs: &[&'static str],
) -> Result<Vec<f64>, SceneError> {
    let b = &toml.bearing;
    let kind = *b.kind.get_ref();
    let given = keys(b);
    for (k, not) in NOT_FOR {
        if k != kind {
            continue;
        }
        if let Some((key, Some((_, span)))) =
            given.iter().find(|(n, v)| not.contains(n) && v.is_some())
        {
            return Err(ctx.invalid(
                span.clone(),
                format!("bearing.{key}"),
                "(given)",
                format!("is not a key of a {} bearing", kind.name()),
            ));
        }
    }
    needs
        .iter()
        .map(|need| match given.iter().find(|(n, _)| n == need) {
            Some((_, Some((v, _)))) => Ok(*v),
            _ => Err(ctx.invalid(
                b.kind.span(),
                format!("bearing.{need}"),
                "(missing)",
                format!("is required for a {} bearing", kind.name()),
            )),
        })
        .collect()
}

/// A ball bearing's spec.
fn ball(
    ctx: &Ctx<'_>,
    toml: &BearingFileToml,
    material: Material,
) -> Result<BearingSpec, SceneError> {
    let v = required(
        ctx,
        toml,
        &[
            "ball_diameter",
            "inner_groove_radius",
            "outer_groove_radius",
            "balls",
        ],
    )?;
    let b = &toml.bearing;
    let balls = ctx.count(b.balls.as_ref().expect("required"), "bearing.balls", 1)?;
    let bearing = BallBearing {
        ball_diameter: v[0],
        inner_raceway_diameter: *b.inner_raceway_diameter.get_ref(),
        outer_raceway_diameter: *b.outer_raceway_diameter.get_ref(),
        inner_groove_radius: v[1],
        outer_groove_radius: v[2],
        balls,
        diametral_clearance: b.diametral_clearance.as_ref().map(|c| *c.get_ref()),
        material,
        radial_load: *b.radial_load.get_ref(),
    };
    bearing.validate().map_err(|e| located(ctx, b, e))?;
    let defaults = BearingGrid::default();
    let p = toml.points.as_ref();
    if let Some(a) = p.and_then(|p| p.along.as_ref()) {
        return Err(ctx.invalid(
            a.span(),
            "points.along",
            *a.get_ref(),
            "is a key of a roller bearing's grid",
        ));
    }
    let grid = BearingGrid {
        across: across(ctx, p, defaults.across)?,
        zone: zone(ctx, p, defaults.zone)?,
    };
    Ok(BearingSpec::Ball { bearing, grid })
}

/// A roller bearing's spec.
fn roller(
    ctx: &Ctx<'_>,
    toml: &BearingFileToml,
    material: Material,
) -> Result<BearingSpec, SceneError> {
    let v = required(ctx, toml, &["roller_diameter", "roller_length", "rollers"])?;
    let b = &toml.bearing;
    let rollers = ctx.count(b.rollers.as_ref().expect("required"), "bearing.rollers", 1)?;
    let crown = match &b.crown {
        None => Crown::Straight,
        Some(c) => crown(ctx, c)?,
    };
    let bearing = RollerBearing {
        roller_diameter: v[0],
        roller_length: v[1],
        crown,
        inner_raceway_diameter: *b.inner_raceway_diameter.get_ref(),
        outer_raceway_diameter: *b.outer_raceway_diameter.get_ref(),
        rollers,
        diametral_clearance: b.diametral_clearance.as_ref().map(|c| *c.get_ref()),
        material,
        radial_load: *b.radial_load.get_ref(),
        misalignment: b.misalignment.as_ref().map_or(0.0, |m| *m.get_ref()),
    };
    bearing.validate().map_err(|e| located(ctx, b, e))?;
    let defaults = RollerGrid::default();
    let p = toml.points.as_ref();
    let along = match p.and_then(|p| p.along.as_ref()) {
        Some(a) => ctx.count(a, "points.along", 2)?,
        None => defaults.along,
    };
    let grid = RollerGrid {
        across: across(ctx, p, defaults.across)?,
        along,
        zone: zone(ctx, p, defaults.zone)?,
    };
    Ok(BearingSpec::Roller { bearing, grid })
}

/// A roller's crown.
fn crown(ctx: &Ctx<'_>, c: &Spanned<CrownToml>) -> Result<Crown, SceneError> {
    let t = c.get_ref();
    let shape = *t.shape.get_ref();
    let keys = [("drop", &t.drop), ("flat", &t.flat), ("load", &t.load)];
    let takes: &[&str] = match shape {
        CrownShape::Straight | CrownShape::Table => &[],
        CrownShape::Circular => &["drop", "flat"],
        CrownShape::Logarithmic => &["load"],
    };
    if let Some(f) = t.file.as_ref().filter(|_| shape != CrownShape::Table) {
        return Err(ctx.invalid(
            f.span(),
            "bearing.crown.file",
            format!("{:?}", f.get_ref()),
            format!(
                "is not a key of a {} crown (a \"table\" crown reads a file)",
                shape.name()
            ),
        ));
    }
    for (key, value) in keys {
        if let Some(v) = value.as_ref().filter(|_| !takes.contains(&key)) {
            return Err(ctx.invalid(
                v.span(),
                format!("bearing.crown.{key}"),
                elcon_analysis::Num(*v.get_ref()),
                format!("is not a key of a {} crown", shape.name()),
            ));
        }
    }
    let value = |v: &Option<Spanned<f64>>, key: &str| -> Result<f64, SceneError> {
        v.as_ref().map(|v| *v.get_ref()).ok_or_else(|| {
            ctx.invalid(
                c.span(),
                format!("bearing.crown.{key}"),
                "(missing)",
                format!("is required for a {} crown", shape.name()),
            )
        })
    };
    Ok(match shape {
        CrownShape::Straight => Crown::Straight,
        CrownShape::Circular => Crown::Circular {
            drop: value(&t.drop, "drop")?,
            flat: t.flat.as_ref().map_or(0.0, |f| *f.get_ref()),
        },
        CrownShape::Logarithmic => Crown::Logarithmic {
            load: value(&t.load, "load")?,
        },
        CrownShape::Table => {
            let file = t.file.as_ref().ok_or_else(|| {
                ctx.invalid(
                    c.span(),
                    "bearing.crown.file",
                    "(missing)",
                    "is required for a table crown: a CSV of (position along the roller, drop)",
                )
            })?;
            let rows = crate::scene::drop_rows(ctx, "bearing.crown.file", file)?;
            Crown::Table(std::sync::Arc::new(rows))
        }
    })
}

/// `points.across`: odd, at least 3.
fn across(
    ctx: &Ctx<'_>,
    p: Option<&BearingPointsToml>,
    default: usize,
) -> Result<usize, SceneError> {
    match p.and_then(|p| p.across.as_ref()) {
        Some(a) => {
            let n = ctx.count(a, "points.across", 3)?;
            ctx.ensure(
                n,
                !n.is_multiple_of(2),
                a.span(),
                "points.across",
                "must be odd (the centre is a point)",
            )
        }
        None => Ok(default),
    }
}

/// `points.zone`: at least 1.
fn zone(ctx: &Ctx<'_>, p: Option<&BearingPointsToml>, default: f64) -> Result<f64, SceneError> {
    match p.and_then(|p| p.zone.as_ref()) {
        Some(z) => {
            let v = ctx.positive(z, "points.zone")?;
            ctx.ensure(
                v,
                v >= 1.0,
                z.span(),
                "points.zone",
                "must be at least 1 (the grid covers the Hertz contact)",
            )
        }
        None => Ok(default),
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
    let key = field.split('.').next().unwrap_or(field);
    let span = keys(b)
        .into_iter()
        .find(|(n, _)| *n == key)
        .and_then(|(_, v)| v.map(|(_, span)| span))
        .unwrap_or_else(|| b.outer_raceway_diameter.span());
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
        let BearingSpec::Ball { bearing, grid } = s.spec() else {
            panic!("a ball bearing");
        };
        assert_eq!(bearing.balls, 9);
        assert_eq!(*grid, BearingGrid::default());
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
        let roller = |bearing: &str| {
            let text = SCENE.replace(
                "type = \"ball\"\nball_diameter = 7.938",
                &format!("type = \"roller\"\nroller_diameter = 9.0\nroller_length = 9.0\nrollers = 12\n{bearing}"),
            )
            .replace("inner_groove_radius = 4.12776\n", "")
            .replace("outer_groove_radius = 4.20714\n", "")
            .replace("balls = 9\n", "")
            .replace("outer_raceway_diameter = 46.9", "outer_raceway_diameter = 49.03");
            BearingScene::from_str(Path::new("r.toml"), &text)
        };
        let s = roller(
            "crown = { shape = \"circular\", drop = 0.008, flat = 4.5 }\nmisalignment = 0.001",
        )
        .unwrap();
        let BearingSpec::Roller { bearing, grid } = s.spec() else {
            panic!("a roller bearing");
        };
        assert_eq!(
            bearing.crown,
            Crown::Circular {
                drop: 0.008,
                flat: 4.5
            }
        );
        assert_eq!(
            (bearing.misalignment, *grid),
            (0.001, RollerGrid::default())
        );
        for (keys, field) in [
            (
                "crown = { shape = \"circular\", load = 1.0 }",
                "bearing.crown.load",
            ),
            ("crown = { shape = \"logarithmic\" }", "bearing.crown.load"),
            (
                "crown = { shape = \"circular\", drop = -1.0 }",
                "bearing.crown.drop",
            ),
            ("balls = 3", "bearing.balls"),
            ("misalignment = 0.5", "bearing.misalignment"),
        ] {
            let e = roller(keys).unwrap_err();
            assert!(e.to_string().contains(field), "{field}: {e}");
        }
        // A ball bearing without its groove radius names the missing key.
        let e = BearingScene::from_str(
            Path::new("b.toml"),
            &SCENE.replace("inner_groove_radius = 4.12776\n", ""),
        )
        .unwrap_err();
        assert!(e.to_string().contains("bearing.inner_groove_radius"), "{e}");
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
