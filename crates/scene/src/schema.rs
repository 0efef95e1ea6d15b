//! The TOML schema of a scene and of a batch, as serde types. Every key is
//! documented in docs/scenes.md; unknown keys are errors; values carry their
//! spans so that validation can say where a bad value is.

use serde::Deserialize;
use toml::Spanned;

/// A scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SceneFile {
    pub scene: Option<MetaToml>,
    pub units: Spanned<UnitsToml>,
    pub body1: Spanned<BodyToml>,
    pub body2: Spanned<BodyToml>,
    pub geometry: Option<Spanned<GeometryToml>>,
    pub points: Spanned<PointsToml>,
    pub loading: Spanned<LoadingToml>,
    pub solver: Option<SolverToml>,
    pub design: Option<Spanned<DesignToml>>,
    pub outputs: Option<OutputsToml>,
}

/// `[scene]`: name and description.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MetaToml {
    pub name: Option<Spanned<String>>,
    pub description: Option<String>,
}

/// `[units]`: labels of a consistent unit system.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct UnitsToml {
    pub length: Spanned<String>,
    pub force: Spanned<String>,
    pub pressure: Option<Spanned<String>>,
}

/// `[body1]`, `[body2]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BodyToml {
    pub model: Spanned<String>,
    pub youngs_modulus: Option<Spanned<f64>>,
    pub poissons_ratio: Option<Spanned<f64>>,
    pub reference_distance: Option<Spanned<f64>>,
    pub modulus: Option<Spanned<f64>>,
    pub second_moment: Option<Spanned<f64>>,
    pub width: Option<Spanned<f64>>,
    pub depth: Option<Spanned<f64>>,
    pub loaded_point: Option<Spanned<f64>>,
}

/// `[geometry]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct GeometryToml {
    pub surface1: Option<Spanned<SurfaceToml>>,
    pub surface2: Option<Spanned<SurfaceToml>>,
    pub separation: Option<Spanned<Vec<Spanned<f64>>>>,
}

/// A surface: `{ shape = "sphere", radius = 1.0 }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SurfaceToml {
    pub shape: Spanned<String>,
    pub radius: Option<Spanned<f64>>,
}

/// `[points]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PointsToml {
    pub grid: Spanned<String>,
    pub spacing: Option<Spanned<f64>>,
    pub radius: Option<Spanned<f64>>,
    pub across: Option<Spanned<i64>>,
    pub zone: Option<Spanned<f64>>,
    pub half_x: Option<Spanned<f64>>,
    pub half_y: Option<Spanned<f64>>,
    pub nx: Option<Spanned<i64>>,
    pub ny: Option<Spanned<i64>>,
    pub start: Option<Spanned<f64>>,
    pub end: Option<Spanned<f64>>,
    pub n: Option<Spanned<i64>>,
}

/// `[loading]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LoadingToml {
    pub load: Option<Spanned<f64>>,
    pub approach: Option<Spanned<f64>>,
    pub moment_x: Option<Spanned<f64>>,
    pub moment_y: Option<Spanned<f64>>,
    pub tilt_x: Option<Spanned<f64>>,
    pub tilt_y: Option<Spanned<f64>>,
}

/// `[solver]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SolverToml {
    pub method: Option<Spanned<String>>,
    pub max_pivots: Option<Spanned<i64>>,
    pub certificate_tolerance: Option<Spanned<f64>>,
    pub refinement_steps: Option<Spanned<i64>>,
    pub symmetry: Option<Spanned<String>>,
}

/// `[design]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct DesignToml {
    pub family: Spanned<String>,
    pub degree: Option<Spanned<i64>>,
    pub axis: Option<Spanned<String>>,
    pub loads: Option<Spanned<Vec<Spanned<f64>>>>,
    pub relative_to: Option<Spanned<String>>,
    pub max_constant: Option<Spanned<f64>>,
    pub radius_range: Option<Spanned<Vec<Spanned<f64>>>>,
    pub flat_length: Option<Spanned<f64>>,
    pub design_load: Option<Spanned<f64>>,
    pub method: Option<Spanned<String>>,
    pub end: Option<Spanned<String>>,
    pub misalignments: Option<Spanned<Vec<Spanned<f64>>>>,
}

/// `[outputs]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct OutputsToml {
    pub plots: Option<Spanned<Vec<Spanned<String>>>>,
    pub pressure_csv: Option<bool>,
}

/// A batch file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BatchFile {
    pub batch: BatchToml,
}

/// `[batch]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BatchToml {
    pub name: Option<Spanned<String>>,
    pub scene: Spanned<String>,
    pub error: Option<Spanned<String>>,
    pub group: Spanned<Vec<Spanned<toml::Table>>>,
}
