//! The TOML schema of a scene and of a batch, as serde types. Every key is
//! documented in docs/scenes.md; unknown keys are errors; values carry their
//! spans so that validation can say where a bad value is.

use serde::Deserialize;
use toml::Spanned;

use elcon_analysis::{Interpolation, Method};
use elcon_design::{Axis, DesignMethod, FamilyKind, LogEnd, Objective};

use crate::ctx::{Shown, keywords};

keywords! {
    /// A body's model, as a scene names it in `model = "..."`.
    pub enum ModelKind {
        /// `"rigid"`.
        Rigid = "rigid",
        /// `"point-force"`: Boussinesq point forces on a half-space (surfaces).
        PointForce = "point-force",
        /// `"uniform-patch"`: Love's uniform pressure patches (surfaces).
        UniformPatch = "uniform-patch",
        /// `"plane-strain"`: 2D strips (lines).
        PlaneStrain = "plane-strain",
        /// `"winkler"`: a Winkler foundation (either).
        Winkler = "winkler",
        /// `"beam"`: an Euler-Bernoulli beam (lines).
        Beam = "beam",
    }
}

impl ModelKind {
    /// Every model, in the order messages list them.
    pub const ALL: [ModelKind; 6] = [
        ModelKind::Rigid,
        ModelKind::PointForce,
        ModelKind::UniformPatch,
        ModelKind::PlaneStrain,
        ModelKind::Winkler,
        ModelKind::Beam,
    ];

    /// The model of a name, if it is one.
    pub fn of(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// A model of a line only (plane-strain strips, a beam).
    pub fn is_line(self) -> bool {
        matches!(self, ModelKind::PlaneStrain | ModelKind::Beam)
    }

    /// A model of a surface only (point forces, uniform patches).
    pub fn is_surface(self) -> bool {
        matches!(self, ModelKind::PointForce | ModelKind::UniformPatch)
    }
}

keywords! {
    /// `batch.error`: the error a batch plots against run time (each a
    /// column of results.csv, `error_<name>`).
    #[derive(serde::Serialize, Default)]
    pub enum ErrorMetric {
        /// `"approach"` (the default): relative error of the approach.
        #[default]
        Approach = "approach",
        /// `"max_pressure"`: relative error of the peak pressure.
        MaxPressure = "max_pressure",
        /// `"contact_extent"`: relative error of the contact radius or half-width.
        ContactExtent = "contact_extent",
        /// `"pressure_l2"`: L2 error of the pressure.
        PressureL2 = "pressure_l2",
        /// `"load"`: relative error of the load.
        Load = "load",
    }
}

keywords! {
    /// A surface's `shape`.
    pub(crate) enum Shape {
        /// `"plane"`.
        Plane = "plane",
        /// `"sphere"`.
        Sphere = "sphere",
        /// `"cylinder"` (axis along y).
        Cylinder = "cylinder",
        /// `"quadric"`: principal radii `radius_x`, `radius_y`, turned by
        /// `angle` degrees.
        Quadric = "quadric",
    }
}

keywords! {
    /// `points.grid`.
    pub(crate) enum Grid {
        /// `"disk"`.
        Disk = "disk",
        /// `"rectangle"`.
        Rectangle = "rectangle",
        /// `"line"`.
        Line = "line",
        /// `"ellipse"`: a rectangle of cells around the Hertz ellipse
        /// (`across`, `zone`).
        Ellipse = "ellipse",
    }
}

/// The method asked for in `solver.method`: "auto" or one of the engine's
/// methods by its name ([`Method`]'s names).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodChoice {
    /// `"auto"`: the method of the storage elcon-analysis picks
    /// (`elcon_analysis::Storage`): block pivoting on a dense or folded S,
    /// the conjugate gradient matrix-free above
    /// `elcon_analysis::AUTO_DENSE_LIMIT` unknowns on a lattice.
    Auto,
    /// A method by name.
    Given(Method),
}

impl MethodChoice {
    /// The names a scene may write: "auto", then the engine's methods.
    const NAMES: [&'static str; 1 + Method::NAMES.len()] = {
        let mut names = ["auto"; 1 + Method::NAMES.len()];
        let mut i = 0;
        while i < Method::NAMES.len() {
            names[i + 1] = Method::NAMES[i];
            i += 1;
        }
        names
    };

    /// The method given, `None` for "auto".
    pub fn given(self) -> Option<Method> {
        match self {
            MethodChoice::Auto => None,
            MethodChoice::Given(m) => Some(m),
        }
    }
}

impl<'de> Deserialize<'de> for MethodChoice {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        match name.as_str() {
            "auto" => Ok(MethodChoice::Auto),
            other => other
                .parse()
                .map(MethodChoice::Given)
                .map_err(|_| serde::de::Error::unknown_variant(&name, &Self::NAMES)),
        }
    }
}

keywords! {
    /// `solver.symmetry`.
    pub(crate) enum Symmetry {
        /// `"auto"`: fold a mirror-symmetric problem.
        Auto = "auto",
        /// `"none"`: never fold.
        None = "none",
    }
}

keywords! {
    /// What the design is relative to, per load case.
    pub enum RelativeTo {
        /// `"absolute"`: the worst p_max itself.
        Absolute = "absolute",
        /// `"mean"`: p_max over the mean intensity P / (sum of A_k) of each load.
        Mean = "mean",
        /// `"hertz"`: p_max over each load's Hertz peak (line contact for a roller).
        Hertz = "hertz",
    }
}

keywords! {
    /// A plot a scene asks for.
    pub enum Plot {
        /// `"pressure"`: pressure against position, with the closed form overlaid.
        Pressure = "pressure",
        /// `"design"`: separations and pressures before and after the design.
        Design = "design",
        /// `"subsurface"`: each body's section (x against depth) through its
        /// largest von Mises stress, and the stresses along depth below the
        /// peak pressure (needs `outputs.subsurface = true`).
        Subsurface = "subsurface",
    }
}

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
    pub model: Spanned<ModelKind>,
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
    pub separation_file: Option<Spanned<String>>,
    pub height_map: Option<Spanned<HeightMapToml>>,
    pub profile: Option<Spanned<ProfileToml>>,
}

/// `geometry.height_map`: `{ file = "rough.npy", spacing = [dx, dy],
/// origin = [x0, y0], interpolation = "linear" }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct HeightMapToml {
    pub file: Spanned<String>,
    pub spacing: Spanned<Vec<f64>>,
    pub origin: Option<Spanned<Vec<f64>>>,
    pub interpolation: Option<Spanned<Interpolation>>,
}

/// `geometry.profile`: `{ file = "crown.csv", axis = "y", interpolation =
/// "linear" }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ProfileToml {
    pub file: Spanned<String>,
    pub axis: Option<Spanned<String>>,
    pub interpolation: Option<Spanned<Interpolation>>,
}

impl Shown for HeightMapToml {
    fn shown(&self) -> String {
        format!("{{ file = {:?} }}", self.file.get_ref())
    }
}

impl Shown for ProfileToml {
    fn shown(&self) -> String {
        format!("{{ file = {:?} }}", self.file.get_ref())
    }
}

/// A surface: `{ shape = "sphere", radius = 1.0 }`, or a quadric
/// `{ shape = "quadric", radius_x = 15.5, radius_y = -4.128, angle = 0 }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SurfaceToml {
    pub shape: Spanned<Shape>,
    pub radius: Option<Spanned<f64>>,
    pub radius_x: Option<Spanned<f64>>,
    pub radius_y: Option<Spanned<f64>>,
    pub angle: Option<Spanned<f64>>,
}

impl Shown for SurfaceToml {
    fn shown(&self) -> String {
        String::new()
    }
}

/// `[points]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PointsToml {
    pub grid: Spanned<Grid>,
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
    pub method: Option<Spanned<MethodChoice>>,
    pub max_pivots: Option<Spanned<i64>>,
    pub certificate_tolerance: Option<Spanned<f64>>,
    pub refinement_steps: Option<Spanned<i64>>,
    pub symmetry: Option<Spanned<Symmetry>>,
    pub error_estimate: Option<bool>,
}

/// `[design]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct DesignToml {
    pub family: Spanned<FamilyKind>,
    pub degree: Option<Spanned<i64>>,
    pub axis: Option<Spanned<Axis>>,
    pub loads: Option<Spanned<Vec<Spanned<f64>>>>,
    pub relative_to: Option<Spanned<RelativeTo>>,
    pub max_constant: Option<Spanned<f64>>,
    pub radius_range: Option<Spanned<Vec<Spanned<f64>>>>,
    pub flat_length: Option<Spanned<f64>>,
    pub design_load: Option<Spanned<f64>>,
    pub method: Option<Spanned<DesignMethod>>,
    pub objective: Option<Spanned<Objective>>,
    pub end: Option<Spanned<LogEnd>>,
    pub misalignments: Option<Spanned<Vec<Spanned<f64>>>>,
    pub grid_tolerance: Option<Spanned<f64>>,
    pub max_points: Option<Spanned<i64>>,
    pub refine: Option<Spanned<bool>>,
    pub profile_spacing: Option<Spanned<f64>>,
}

/// `[outputs]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct OutputsToml {
    pub plots: Option<Spanned<Vec<Spanned<Plot>>>>,
    pub pressure_csv: Option<bool>,
    pub subsurface: Option<Spanned<bool>>,
    pub subsurface_depths: Option<Spanned<Vec<Spanned<f64>>>>,
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
    pub error: Option<Spanned<ErrorMetric>>,
    pub group: Spanned<Vec<Spanned<toml::Table>>>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_method_choice_is_auto_or_the_engine_s_name() {
        let read = |text: &str| {
            toml::from_str::<SolverToml>(text).map(|s| s.method.map(|m| m.into_inner()))
        };
        assert_eq!(read("method = \"auto\"").unwrap(), Some(MethodChoice::Auto));
        for m in Method::ALL {
            let text = format!("method = \"{m}\"");
            assert_eq!(read(&text).unwrap(), Some(MethodChoice::Given(m)));
        }
        let e = read("method = \"fastest\"").unwrap_err().to_string();
        assert!(
            e.contains(
                "unknown variant `fastest`, expected one of `auto`, `restricted-simplex`, \
                 `lemke`, `block-pivoting`, `conjugate-gradient`"
            ),
            "{e}"
        );
    }
}
