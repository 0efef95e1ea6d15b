//! A validated scene: the TOML file turned into the objects of the solver
//! crates, every value checked against its physical range with a message
//! that names the file, the line and column, and the field. Each section
//! is validated by its own module; this one puts them together and checks
//! the scene as a whole.
//!
//! The scene's equations are those of elcon-analysis (compatibility
//! `Y = S F + eps - alpha e`, equilibrium `e^T F = P`, the contact
//! criterion) and, with a `[design]` section, elcon-design. What a scene
//! does not ask for is neither read nor computed: no design stage without
//! `[design]`, no reference where no closed form applies, no plot not asked.

mod body;
mod bounds;
mod design;
mod factors;
mod files;
mod geometry;
mod grids;
mod hertz;
mod loading;
mod npy;
mod outputs;
mod parts;
mod points;
mod solver;
mod units;

use std::path::{Path, PathBuf};

use elcon_analysis::references::HertzCylinders;
use elcon_analysis::{
    ContactProblem, Geometry, GridFamily, Loading, Method, Options, Plan, ProblemBuilder, Storage,
};
use elcon_influence::{Dimension, PointSet};
use toml::Spanned;

pub use crate::schema::MethodChoice;
pub use body::{BodySpec, ModelKind};
use design::DesignContext;
pub use design::{DesignFamily, DesignSpec, RelativeTo};
pub use files::MAX_DATA_BYTES;
pub use hertz::{DesignLayoutParts, Reference};
use hertz::{Hertz, Layout};
pub use outputs::{Outputs, Plot};
pub use parts::{ProblemParts, design_over, problem_parts, scene_with_design};
pub use points::PointsSpec;
use points::build_points;
pub use units::Units;

pub(crate) use files::drop_rows;

/// The units of a `[units]` table (a bearing scene's: no beam).
pub(crate) fn units_of(
    ctx: &crate::ctx::Ctx<'_>,
    u: &crate::schema::UnitsToml,
) -> Result<Units, SceneError> {
    units::units(ctx, u, false)
}

use crate::ctx::{Ctx, parse};
use crate::error::SceneError;
use crate::inputs::DataInput;
use crate::sanity;
use crate::schema::{BodyToml, Grid, LoadingToml, PointsToml, SceneFile};

/// A validated scene. Each field is read through its accessor, which says
/// what it is.
#[derive(Debug, Clone)]
pub struct Scene {
    name: String,
    file: PathBuf,
    description: Option<String>,
    units: Units,
    bodies: [BodySpec; 2],
    geometry: Geometry,
    points_spec: PointsSpec,
    points: PointSet,
    loading: Loading,
    choice: MethodChoice,
    plan: Plan,
    options: Options,
    fold: bool,
    error_estimate: bool,
    design: Option<DesignSpec>,
    outputs: Outputs,
    reference: Option<Reference>,
    body_edges: (bool, bool),
    warnings: Vec<String>,
    inputs: Vec<DataInput>,
}

impl Scene {
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

    /// The two bodies.
    pub fn bodies(&self) -> &[BodySpec; 2] {
        &self.bodies
    }

    /// The initial separations' source: two surfaces, or given values.
    pub fn geometry(&self) -> &Geometry {
        &self.geometry
    }

    /// The point layout.
    pub fn points_spec(&self) -> &PointsSpec {
        &self.points_spec
    }

    /// The candidate points for the scene's loading.
    pub fn points(&self) -> &PointSet {
        &self.points
    }

    /// Load or approach, and the rotations.
    pub fn loading(&self) -> Loading {
        self.loading
    }

    /// The engine's method (`solver.method`; `"auto"` resolved by the
    /// problem's [`Plan`]).
    pub fn method(&self) -> Method {
        self.plan.method
    }

    /// How the contact problem holds S ([`Storage`]: dense, folded, or
    /// matrix-free on the lattice), as elcon-analysis decided it from
    /// `solver.method` and `solver.symmetry`.
    pub fn storage(&self) -> Storage {
        self.plan.storage
    }

    /// The contact problem's storage, method and estimated cost.
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// The builder of this scene's contact problem on `points` under
    /// `loading`: its bodies, geometry, method, storage and the zone's
    /// edges that are the bodies' own. A design's load case adds
    /// `.fold(false)` (the design reads every point).
    pub fn builder(&self, points: PointSet, loading: Loading) -> ProblemBuilder<'_> {
        let (along_x, along_y) = self.body_edges;
        planner(
            points,
            &self.bodies,
            &self.geometry,
            loading,
            self.choice,
            self.fold,
        )
        .storage(self.plan.storage)
        .body_edges(along_x, along_y)
    }

    /// The engine's options (`solver.max_pivots`,
    /// `certificate_tolerance`, `refinement_steps`).
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Whether a mirror-symmetric problem is folded (`solver.symmetry`,
    /// "auto" (default) or "none").
    pub fn fold(&self) -> bool {
        self.fold
    }

    /// Whether the run estimates its discretization error on coarser grids
    /// (`solver.error_estimate`, default true).
    pub fn error_estimate(&self) -> bool {
        self.error_estimate
    }

    /// The grid family of the scene's points (`elcon_analysis::GridFamily`:
    /// the same zone at any spacing), laid out at the scene's load as its
    /// points are.
    ///
    /// # Errors
    /// [`SceneError::Points`]: why the layout has no family (relative to a
    /// Hertz contact that does not apply).
    pub fn grid_family(&self) -> Result<GridFamily, SceneError> {
        let scale = self
            .loading
            .load_value()
            .and_then(|p| self.layout().scale(p));
        self.points_spec.family(scale)
    }

    /// The grid family of the points for a load case of `load` at
    /// `fineness` (spacing h / fineness; 1: the points of
    /// [`Scene::points_for`]).
    ///
    /// # Errors
    /// [`SceneError::Points`]: why the layout has no family, or the refined
    /// grid is invalid.
    pub fn grid_for(&self, load: f64, fineness: f64) -> Result<GridFamily, SceneError> {
        self.points_spec
            .family(self.layout().scale(load))?
            .refined(fineness)
            .map_err(SceneError::points)
    }

    /// `solver.method` as given: "auto", or a method.
    pub fn method_choice(&self) -> MethodChoice {
        self.choice
    }

    /// The design stage, if the scene asks for one.
    pub fn design(&self) -> Option<&DesignSpec> {
        self.design.as_ref()
    }

    /// What to write.
    pub fn outputs(&self) -> &Outputs {
        &self.outputs
    }

    /// The closed form that applies, if any.
    pub fn reference(&self) -> Option<&Reference> {
        self.reference.as_ref()
    }

    /// The zone's edges that are the bodies' own (along x, along y):
    /// contact reaching them raises no truncation warning. Inferred: a
    /// beam's ends (x), a roller's ends on a rectangle grid (y), a flat
    /// punch's rim (both).
    pub fn body_edges(&self) -> (bool, bool) {
        self.body_edges
    }

    /// What validation found doubtful but not wrong (a grid coarser than
    /// the contact): printed by `elcon check` and `elcon run`, and written
    /// to result.json's warnings.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The data files it read (height maps, profiles, separation files),
    /// with the SHA-256 of the bytes read.
    pub fn inputs(&self) -> &[DataInput] {
        &self.inputs
    }

    /// The same scene under another name (a batch's run is named after
    /// its sweep values).
    pub fn renamed(mut self, name: String) -> Self {
        self.name = name;
        self
    }

    /// Reads and validates a scene file.
    ///
    /// # Errors
    /// [`SceneError::Io`] if it cannot be read; [`SceneError::Syntax`] for
    /// invalid TOML, unknown or missing keys and wrong types;
    /// [`SceneError::Invalid`] for values out of their physical range.
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = crate::ctx::read_text(path)?;
        Self::from_str(path, &text)
    }

    /// Validates a scene given as text; `file` names it in messages and
    /// gives the default name.
    ///
    /// # Errors
    /// As [`Scene::from_file`], without the I/O.
    pub fn from_str(file: &Path, text: &str) -> Result<Self, SceneError> {
        let raw: SceneFile = parse(file, text)?;
        let ctx = Ctx::new(file, text);
        validate(&ctx, raw)
    }

    /// The candidate points for a load case of `load` (the scene's own
    /// points unless they are laid out relative to the Hertz contact).
    pub fn points_for(&self, load: f64) -> Result<PointSet, SceneError> {
        let scale = self.layout().scale(load);
        build_points(&self.points_spec, scale).map_err(|e| SceneError::Layout {
            scene: self.name.clone(),
            reason: e.to_string(),
        })
    }

    /// The bodies, surfaces and layout the closed forms come from.
    fn layout(&self) -> Layout<'_> {
        Layout {
            bodies: &self.bodies,
            geometry: &self.geometry,
            points_spec: &self.points_spec,
        }
    }

    /// The length the run's bound on the solved approach measures the
    /// candidate zone by (on an ellipse grid the zone across the Hertz
    /// ellipse's minor axis, whatever its turn).
    pub fn approach_extent(&self) -> crate::sanity::StrainExtent {
        let contact = self.loading.load_value().and_then(|p| self.hertz(p));
        self.layout()
            .approach_extent(contact.as_ref(), &self.points)
    }

    /// The peak pressure of the Hertz contact at `load` (intensity unit),
    /// where one applies (the layout, bodies and surfaces of a Hertz
    /// contact): a design's reference intensity `relative_to = "hertz"`.
    pub fn hertz_peak_pressure(&self, load: f64) -> Option<f64> {
        self.hertz(load).map(|h| h.peak_pressure())
    }

    /// The Hertz contact at `load`, where one applies (the layout, bodies
    /// and surfaces of a Hertz contact).
    pub(crate) fn hertz(&self, load: f64) -> Option<Hertz> {
        self.layout().hertz(load)
    }

    /// How far a roller design's largest misalignment lifts the roller's
    /// end against the lightest design load's approach ([`EndLift`]), for
    /// a design along y (the roller's axis) of a Hertz line contact on a
    /// rectangle grid with `design.misalignments`; `None` otherwise.
    pub fn end_lift(&self) -> Option<EndLift> {
        let design = self.design.as_ref()?;
        let misalignment = design
            .misalignments()
            .iter()
            .copied()
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))?;
        let load = design.loads().iter().copied().reduce(f64::min)?;
        let (hertz, half_length) = self.roller_contact(load)?;
        Some(EndLift {
            misalignment,
            half_length,
            load,
            approach: hertz.approach(hertz.radius).ok()?,
        })
    }

    /// A roller design's contact at `load`: its Hertz line contact and
    /// half the roller's length, for a design along y (the roller's axis)
    /// of a Hertz line contact on a rectangle grid; `None` otherwise.
    pub(crate) fn roller_contact(&self, load: f64) -> Option<(HertzCylinders, f64)> {
        let design = self.design.as_ref()?;
        if design.axis() != elcon_design::Axis::Y || self.points.dimension() != Dimension::Surface {
            return None;
        }
        let Some(Hertz::Cylinders(hertz)) = self.hertz(load) else {
            return None;
        };
        let ys = self.points.ys();
        let (lo, hi) = ys
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &y| {
                (lo.min(y), hi.max(y))
            });
        Some((hertz, 0.5 * (hi - lo + self.points.cell().dy)))
    }
}

/// A roller design's largest misalignment against its lightest load
/// ([`Scene::end_lift`]): a misalignment m lifts one end of a roller of
/// half-length L / 2 by `|m| L / 2` (and presses the other by as much),
/// measured against the approach of the Hertz line contact at the
/// lightest design load, `(2 P' / (pi E*)) (ln(2 R / b) + 1/2)` (a datum
/// a roller's radius R away; 0.0235 mm for the crowned roller at 10 kN,
/// whose solve gives 0.0253 mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndLift {
    /// The largest misalignment in size (rad, signed as given).
    pub misalignment: f64,
    /// Half the roller's length along its axis (the grid's extent).
    pub half_length: f64,
    /// The lightest design load.
    pub load: f64,
    /// The Hertz line contact's approach at that load.
    pub approach: f64,
}

impl EndLift {
    /// The end's lift, `|m| L / 2`.
    pub fn lift(&self) -> f64 {
        self.misalignment.abs() * self.half_length
    }

    /// The lift over the approach.
    pub fn ratio(&self) -> f64 {
        self.lift() / self.approach
    }
}

fn validate(ctx: &Ctx<'_>, raw: SceneFile) -> Result<Scene, SceneError> {
    let name = scene_name(ctx, &raw)?;
    let description = raw.scene.as_ref().and_then(|m| m.description.clone());
    let bodies = [
        body::body(ctx, raw.body1.get_ref(), "body1")?,
        body::body(ctx, raw.body2.get_ref(), "body2")?,
    ];
    let (line_models, surface_models) = model_kinds(ctx, &raw.body2, &bodies)?;
    let beam = bodies.iter().any(|b| b.model() == ModelKind::Beam);
    let units = units::units(ctx, raw.units.get_ref(), beam)?;
    let loading = loading::loading(ctx, &raw.loading)?;
    let (points_spec, dimension) = points::points_spec(ctx, &raw.points)?;
    let models = (line_models, surface_models);
    grid_fits_models(
        ctx,
        &raw.points,
        Some(raw.loading.get_ref()),
        dimension,
        models,
    )?;
    let geometry = geometry::geometry(ctx, raw.geometry.as_ref(), dimension)?;
    sanity::curvatures(ctx, raw.geometry.as_ref(), &geometry)?;
    let points_spec = hertz::shaped(points_spec, &bodies, &geometry);
    let layout = Layout {
        bodies: &bodies,
        geometry: &geometry,
        points_spec: &points_spec,
    };
    let points = grids::lay_out(ctx, &raw, layout, loading)?;
    let geometry = files::on_points(ctx, raw.geometry.as_ref(), geometry, &points)?;
    let layout = Layout {
        bodies: &bodies,
        geometry: &geometry,
        points_spec: &points_spec,
    };
    bounds::bounds(ctx, &raw, layout, &points, loading, &units)?;
    let reference = layout.reference(&points, loading);
    grids::check_zone(ctx, &raw.points, reference.as_ref(), &points)?;
    // The zone's edges are a punch's rim whatever its approach.
    let body_edges = body_edges(&bodies, reference.as_ref(), &points_spec);
    let (reference, note) = hertz::pressing(reference, loading, &geometry);
    let (choice, options) = solver::solver(ctx, raw.solver.as_ref())?;
    solver::bounds(ctx, raw.solver.as_ref(), points.len())?;
    let fold = solver::symmetry(raw.solver.as_ref());
    let plan = planner(points.clone(), &bodies, &geometry, loading, choice, fold)
        .plan()
        .map_err(|e| SceneError::Layout {
            scene: name.clone(),
            reason: e.to_string(),
        })?;
    let design = match &raw.design {
        Some(d) => {
            let layout = Some(layout);
            let scene = DesignContext {
                loading,
                dimension,
                layout,
                roller: None,
            };
            Some(design::design(ctx, d, &scene)?)
        }
        None => None,
    };
    program_reads_entries(ctx, &raw, design.as_ref(), &plan)?;
    let zone = sanity::zone_size(&points);
    let outputs = outputs::outputs(ctx, raw.outputs.as_ref(), design.is_some(), zone)?;
    let mut scene = Scene {
        name,
        file: ctx.file.to_path_buf(),
        description,
        units,
        bodies,
        geometry,
        points_spec,
        points,
        loading,
        choice,
        plan,
        options,
        fold,
        error_estimate: solver::error_estimate(raw.solver.as_ref()),
        design,
        outputs,
        reference,
        body_edges,
        warnings: Vec::new(),
        inputs: ctx.inputs.take(),
    };
    scene.warnings = grids::whole_scene(ctx, &raw, &scene)?;
    scene.warnings.extend(note);
    Ok(scene)
}

/// The design program reads S's entries: not of a scene that holds S
/// matrix-free.
fn program_reads_entries(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    design: Option<&DesignSpec>,
    plan: &Plan,
) -> Result<(), SceneError> {
    let (Some(d), Some(raw_design)) = (design, &raw.design) else {
        return Ok(());
    };
    d.method()
        .admits(plan.storage.holds_entries())
        .map_err(|e| {
            let span = raw_design
                .get_ref()
                .method
                .as_ref()
                .map_or(raw_design.span(), |m| m.span());
            let why = match e {
                elcon_design::DesignError::Incompatible { reason, .. } => reason,
                other => other.to_string(),
            };
            ctx.invalid(
                span,
                "design.method",
                "\"program\"",
                format!("{why} (solver.method)"),
            )
        })
        .map(|_| ())
}

/// The builder of a scene's problem before its storage is decided: the
/// bodies, the geometry, the method asked for (none for "auto") and
/// whether a symmetric problem may fold.
fn planner<'a>(
    points: PointSet,
    bodies: &'a [BodySpec; 2],
    geometry: &'a Geometry,
    loading: Loading,
    choice: MethodChoice,
    fold: bool,
) -> ProblemBuilder<'a> {
    let builder = ContactProblem::builder(
        points,
        bodies[0].body(),
        bodies[1].body(),
        geometry,
        loading,
    )
    .fold(fold);
    match choice {
        MethodChoice::Given(method) => builder.method(method),
        MethodChoice::Auto => builder,
    }
}

/// The most bytes of a name that becomes a directory: a scene's name, a
/// batch run's directory (longer ones keep their first part and a hash of
/// the whole), leaving room under NAME_MAX (255) for the lock's and the
/// temporary sibling's additions.
pub(crate) const MAX_SLUG: usize = 120;

/// `scene.name` (default: the file's stem): it names an output directory.
fn scene_name(ctx: &Ctx<'_>, raw: &SceneFile) -> Result<String, SceneError> {
    let given = raw.scene.as_ref().and_then(|m| m.name.as_ref());
    let name = match given {
        Some(n) if n.get_ref().trim().is_empty() => {
            return Err(ctx.invalid(n.span(), "scene.name", "\"\"", "must not be empty"));
        }
        Some(n) => n.get_ref().clone(),
        None => ctx
            .file
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned()),
    };
    // A directory's name is at most 255 bytes, and the lock beside it adds a
    // '.' and ".lock"; control characters make names no terminal shows.
    let fits = !(name.contains(['/', '\\'])
        || name.starts_with('.')
        || name.len() > MAX_SLUG
        || name.chars().any(char::is_control));
    let why = format!(
        "names an output directory: at most {MAX_SLUG} bytes, no control characters, no path \
         separators, and no leading '.' (elcon's temporary siblings and locks start with one)"
    );
    let span = given.map_or(0..0, |n| n.span());
    ctx.ensure(name, fits, span, "scene.name", why)
}

/// The bodies' models: not both rigid, and all of one kind (line models:
/// plane-strain, beam; surface models: point-force, uniform-patch).
/// Returns (line models present, surface models present).
fn model_kinds(
    ctx: &Ctx<'_>,
    body2: &Spanned<BodyToml>,
    bodies: &[BodySpec; 2],
) -> Result<(bool, bool), SceneError> {
    if bodies.iter().all(|b| b.body().is_rigid()) {
        return Err(ctx.invalid(
            body2.get_ref().model.span(),
            "body2.model",
            "\"rigid\"",
            "both bodies are rigid: there is no elasticity to solve for; give one an elastic model",
        ));
    }
    let line_models = bodies.iter().any(|b| b.model().is_line());
    let surface_models = bodies.iter().any(|b| b.model().is_surface());
    if line_models && surface_models {
        return Err(ctx.invalid(
            body2.get_ref().model.span(),
            "body2.model",
            format!("\"{}\"", bodies[1].model()),
            format!(
                "does not go with body1's \"{}\": line models (plane-strain, beam) and surface models \
                 (point-force, uniform-patch) cannot share a point set",
                bodies[0].model()
            ),
        ));
    }
    Ok((line_models, surface_models))
}

/// The grid's dimension matches the models', and a line takes no rotation
/// about x.
fn grid_fits_models(
    ctx: &Ctx<'_>,
    points: &Spanned<PointsToml>,
    loading: Option<&LoadingToml>,
    dimension: Dimension,
    (line_models, surface_models): (bool, bool),
) -> Result<(), SceneError> {
    if line_models && dimension != Dimension::Line {
        return Err(ctx.invalid(
            points.get_ref().grid.span(),
            "points.grid",
            format!("\"{}\"", points.get_ref().grid.get_ref()),
            "the bodies' models (plane-strain, beam) need grid = \"line\"",
        ));
    }
    if surface_models && dimension != Dimension::Surface {
        return Err(ctx.invalid(
            points.get_ref().grid.span(),
            "points.grid",
            "\"line\"",
            "the bodies' models (point-force, uniform-patch) need grid = \"disk\" or \"rectangle\"",
        ));
    }
    if let (Dimension::Line, Some(l)) = (dimension, loading) {
        // A line has one rotation, about the y axis.
        for (value, field) in [
            (&l.moment_x, "loading.moment_x"),
            (&l.tilt_x, "loading.tilt_x"),
        ] {
            if let Some(v) = value
                && *v.get_ref() != 0.0
            {
                return Err(ctx.invalid(
                    v.span(),
                    field,
                    v.get_ref().to_string(),
                    "a line contact has one rotation, about the y axis: use loading.moment_y or loading.tilt_y",
                ));
            }
        }
    }
    Ok(())
}

/// The edges of the candidate zone that are the bodies' own: a punch's rim,
/// a beam's ends, a roller's ends.
fn body_edges(
    bodies: &[BodySpec; 2],
    reference: Option<&Reference>,
    points_spec: &PointsSpec,
) -> (bool, bool) {
    if matches!(reference, Some(Reference::FlatPunch(_))) {
        (true, true)
    } else if bodies.iter().any(|b| b.model() == ModelKind::Beam) {
        (true, false)
    } else if points_spec.grid() == Grid::Rectangle {
        (false, true)
    } else {
        (false, false)
    }
}
