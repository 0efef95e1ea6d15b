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
mod design;
mod factors;
mod files;
mod geometry;
mod hertz;
mod loading;
mod outputs;
mod parts;
mod points;
mod solver;
mod units;

use std::path::{Path, PathBuf};

use elcon_analysis::{
    ContactProblem, Geometry, GridFamily, Loading, Method, Normal, Options, Plan, ProblemBuilder,
    Storage,
};
use elcon_design::DesignMethod;
use elcon_influence::{Dimension, PointSet};
use toml::Spanned;

pub use body::{BodySpec, ModelKind};
pub use design::{DesignFamily, DesignSpec, RelativeTo};
pub(crate) use hertz::Hertz;
pub use hertz::Reference;
pub use outputs::{Outputs, Plot};
pub use parts::{DesignLayoutParts, ProblemParts, design_over, problem_parts, scene_with_design};
pub(crate) use points::build_points;
pub use points::{HalfX, PointsSpec};
pub use solver::MethodChoice;
pub use units::Units;

use crate::ctx::{Ctx, parse};
use crate::error::SceneError;
use crate::sanity;
use crate::schema::{BodyToml, GeometryToml, LoadingToml, PointsToml, SceneFile};

/// A validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The scene's name (default: the file's stem).
    name: String,
    /// The file it came from.
    file: PathBuf,
    /// Its description.
    description: Option<String>,
    /// Unit labels.
    units: Units,
    /// The two bodies.
    bodies: [BodySpec; 2],
    /// The initial separations' source.
    geometry: Geometry,
    /// The point layout.
    points_spec: PointsSpec,
    /// The candidate points for the scene's loading.
    points: PointSet,
    /// Load or approach.
    loading: Loading,
    /// `solver.method` as given ("auto" or a method).
    choice: MethodChoice,
    /// The contact problem's storage, method and cost, decided by
    /// elcon-analysis from `solver.method` and `solver.symmetry`.
    plan: Plan,
    /// The engine's options.
    options: Options,
    /// Whether to fold a mirror-symmetric problem (`solver.symmetry`,
    /// "auto" (default) or "none").
    fold: bool,
    /// Whether the run estimates its discretization error on coarser
    /// grids (`solver.error_estimate`, default true).
    error_estimate: bool,
    /// The design stage, if asked for.
    design: Option<DesignSpec>,
    /// The outputs.
    outputs: Outputs,
    /// The closed form that applies, if any.
    reference: Option<Reference>,
    /// The zone's edges that are the bodies' own (along x, along y):
    /// contact reaching them raises no truncation warning. Inferred: a
    /// beam's ends (x), a roller's ends on a rectangle grid (y), a flat
    /// punch's rim (both).
    body_edges: (bool, bool),
    /// What validation found doubtful but not wrong (a grid coarser than
    /// the contact): printed by `elcon check` and `elcon run`, and written
    /// to result.json's warnings.
    warnings: Vec<String>,
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

    /// Whether a mirror-symmetric problem is folded (`solver.symmetry`).
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
        let scale = self.loading.load_value().and_then(|p| self.hertz_scale(p));
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
            .family(self.hertz_scale(load))?
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
    /// contact reaching them raises no truncation warning.
    pub fn body_edges(&self) -> (bool, bool) {
        self.body_edges
    }

    /// What validation found doubtful but not wrong (a grid coarser than
    /// the contact).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
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
        let ctx = Ctx { file, text };
        validate(&ctx, raw)
    }

    /// The candidate points for a load case of `load` (the scene's own
    /// points unless they are laid out relative to the Hertz contact).
    pub fn points_for(&self, load: f64) -> Result<PointSet, SceneError> {
        let scale = self.hertz_scale(load);
        build_points(&self.points_spec, scale).map_err(|e| SceneError::Layout {
            scene: self.name.clone(),
            reason: e.to_string(),
        })
    }

    /// The Hertz length scale (contact radius or half-width) at `load`.
    fn hertz_scale(&self, load: f64) -> Option<f64> {
        hertz::hertz_scale(&self.bodies, &self.geometry, &self.points_spec, load)
    }

    /// The length the run's bound on the solved approach measures the
    /// candidate zone by (`hertz::approach_extent`: on an ellipse grid the
    /// zone across the Hertz ellipse's minor axis, whatever its turn).
    pub fn approach_extent(&self) -> crate::sanity::StrainExtent {
        let contact = self.loading.load_value().and_then(|p| self.hertz(p));
        hertz::approach_extent(&self.points_spec, contact.as_ref(), &self.points)
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
        hertz::hertz(&self.bodies, &self.geometry, &self.points_spec, load)
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
    let units = units::units(
        ctx,
        raw.units.get_ref(),
        bodies.iter().any(|b| b.model() == ModelKind::Beam),
    )?;
    let loading = loading::loading(ctx, &raw.loading)?;
    let (points_spec, dimension) = points::points_spec(ctx, &raw.points)?;
    grid_fits_models(
        ctx,
        &raw.points,
        Some(raw.loading.get_ref()),
        dimension,
        line_models,
        surface_models,
    )?;
    let geometry = geometry::geometry(ctx, raw.geometry.as_ref(), dimension)?;
    sanity::curvatures(ctx, raw.geometry.as_ref(), &geometry)?;
    let points_spec = hertz::shaped(points_spec, &bodies, &geometry);
    let points = lay_out(ctx, &raw, &bodies, &geometry, &points_spec, loading)?;
    let geometry = files::on_points(ctx, raw.geometry.as_ref(), geometry, &points)?;
    small_strain(
        ctx,
        &raw,
        (&bodies, &points_spec),
        &geometry,
        &points,
        loading,
        &units,
    )?;
    hertz_bounds(
        ctx,
        &raw,
        (&bodies, &geometry, &points_spec),
        &points,
        loading,
        units.length(),
    )?;
    sanity::load_centre(ctx, &raw.loading, loading, &points)?;
    let reference = hertz::reference(&bodies, &geometry, &points_spec, &points, loading);
    check_zone(ctx, &raw.points, reference.as_ref(), &points)?;
    // The zone's edges are a punch's rim whatever its approach.
    let body_edges = body_edges(&bodies, reference.as_ref(), &points_spec);
    let (reference, note) = hertz::pressing(reference, loading, &geometry);
    let (choice, options) = solver::solver(ctx, raw.solver.as_ref())?;
    sanity::solver_bounds(ctx, raw.solver.as_ref(), points.len())?;
    let fold = solver::symmetry(raw.solver.as_ref());
    let error_estimate = solver::error_estimate(raw.solver.as_ref());
    let plan = planner(points.clone(), &bodies, &geometry, loading, choice, fold)
        .plan()
        .map_err(|e| SceneError::Layout {
            scene: name.clone(),
            reason: e.to_string(),
        })?;
    let design = match &raw.design {
        Some(d) => Some(design::design(
            ctx,
            d,
            &design::DesignContext {
                loading,
                dimension,
                layout: Some(design::DesignLayout {
                    bodies: &bodies,
                    geometry: &geometry,
                    points_spec: &points_spec,
                }),
                roller: None,
            },
        )?),
        None => None,
    };
    program_reads_entries(ctx, &raw, design.as_ref(), &plan)?;
    let outputs = outputs::outputs(
        ctx,
        raw.outputs.as_ref(),
        design.is_some(),
        crate::sanity::zone_size(&points),
    )?;
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
        error_estimate,
        design,
        outputs,
        reference,
        body_edges,
        warnings: Vec::new(),
    };
    scene.warnings = whole_scene(ctx, &raw, &scene)?;
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
    if let (Some(d), Some(raw_design)) = (design, &raw.design)
        && d.method() == DesignMethod::Program
        && !plan.storage.holds_entries()
    {
        let span = raw_design
            .get_ref()
            .method
            .as_ref()
            .map_or(raw_design.span(), |m| m.span());
        return Err(ctx.invalid(
            span,
            "design.method",
            "\"program\"",
            "the program reads S's entries and this scene holds S matrix-free (solver.method); \
             use \"descent\" or \"auto\"",
        ));
    }
    Ok(())
}

/// What the run would refuse that Hertz's closed form tells before it:
/// Hertz's approach at the scene's load beyond the small strain
/// ([`sanity::hertz_approach_strain`]), prescribed tilts moving the
/// spheres' or an elliptical contact off the candidate zone
/// ([`sanity::tilt_off_zone`], [`sanity::tilt_off_zone_ellipse`]), a
/// plane-strain datum so far that the line contact's approach strains
/// the zone ([`sanity::datum_strain`]).
/// The closed form comes from the bodies, the surfaces and the layout.
fn hertz_bounds(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    (bodies, geometry, spec): (&[BodySpec; 2], &Geometry, &PointsSpec),
    points: &PointSet,
    loading: Loading,
    length: &str,
) -> Result<(), SceneError> {
    let Normal::Load(load) = loading.normal else {
        return Ok(());
    };
    let t = raw.loading.get_ref();
    let contact = hertz::hertz(bodies, geometry, spec, load);
    let extent = hertz::approach_extent(spec, contact.as_ref(), points);
    let sized_by_hertz = matches!(
        spec,
        PointsSpec::DiskHertz { .. } | PointsSpec::EllipseHertz { .. }
    );
    if let Some(reason) = contact
        .and_then(|h| h.approach())
        .and_then(|d| sanity::hertz_approach_strain((load, d), sized_by_hertz, extent, length))
    {
        let span = t.load.as_ref().map_or(raw.loading.span(), |l| l.span());
        return Err(ctx.invalid(span, "loading.load", crate::ctx::Num(load), reason));
    }
    let pair = [bodies[0].body(), bodies[1].body()];
    if let Some(Hertz::Cylinders(h)) = contact
        && let Some((i, reason)) = sanity::datum_strain(&h, pair, points, length)
    {
        let (section, raw_body) = [("body1", &raw.body1), ("body2", &raw.body2)][i];
        let b = raw_body.get_ref();
        let span = b
            .reference_distance
            .as_ref()
            .map_or(b.model.span(), |v| v.span());
        let value = match *pair[i].model() {
            elcon_influence::Model::PlaneStrainStrip {
                reference_distance, ..
            } => reference_distance,
            _ => 0.0,
        };
        return Err(ctx.invalid(
            span,
            format!("{section}.reference_distance"),
            crate::ctx::Num(value),
            reason,
        ));
    }
    let off = match contact {
        Some(Hertz::Ellipse(h)) => sanity::tilt_off_zone_ellipse(&h, loading, points, length),
        _ => hertz::spheres_at(bodies, geometry, spec, load)
            .and_then(|rc| sanity::tilt_off_zone(rc, loading, points, length)),
    };
    if let Some((field, reason)) = off {
        let (given, value) = if field == "loading.tilt_x" {
            (t.tilt_x.as_ref(), loading.tilt_x)
        } else {
            (t.tilt_y.as_ref(), loading.tilt_y)
        };
        let span = given.map_or(raw.loading.span(), |v| v.span());
        let angle = crate::ctx::Num(value.prescribed_angle());
        return Err(ctx.invalid(span, field, angle, reason));
    }
    Ok(())
}

/// The scene within the small strain of the linear models
/// ([`sanity::MAX_STRAIN`]): its separations against the zone's size, its
/// load or approach against the bodies' stiffness.
fn small_strain(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    (bodies, spec): (&[BodySpec; 2], &PointsSpec),
    geometry: &Geometry,
    points: &PointSet,
    loading: Loading,
    units: &Units,
) -> Result<(), SceneError> {
    small_separations(ctx, raw.geometry.as_ref(), geometry, points, units.length())?;
    let pair = [bodies[0].body(), bodies[1].body()];
    sanity::small_strain(
        ctx,
        &raw.loading,
        pair,
        loading,
        points,
        strain_labels(units),
    )?;
    let largest = largest_separation(ctx, raw.geometry.as_ref(), geometry, points)?;
    let factors = |quantity| factors::factors(raw, pair, spec, loading.normal, points, quantity);
    // The load's own bounds first: a user who mistyped the load is told
    // so; a deformation out of the doubles' range blames the input out of
    // scale (a foundation's modulus of 1e307, not the load).
    let Some(reason) = sanity::unresolved(pair, loading.normal, points, largest, units.length())
    else {
        return sanity::compliance_in_range(
            ctx,
            &|load| factors(factors::Quantity::Product { load }),
            pair,
            points,
            (loading.normal, largest),
            strain_labels(units),
        );
    };
    if let Some((f, reason)) = sanity::deformation_out_of_scale(
        pair,
        loading.normal,
        points,
        largest,
        (
            &factors(factors::Quantity::Deformation),
            &factors(factors::Quantity::Product {
                load: sanity::deformation(pair, loading.normal, points) >= largest.abs(),
            }),
        ),
        units.length(),
    ) {
        return Err(ctx.invalid(f.span, f.field, crate::ctx::Num(f.value), reason));
    }
    let t = raw.loading.get_ref();
    let (field, given, value) = match loading.normal {
        Normal::Load(v) => ("loading.load", t.load.as_ref(), v),
        Normal::Approach(v) => ("loading.approach", t.approach.as_ref(), v),
    };
    Err(ctx.invalid(
        given.map_or(raw.loading.span(), |v| v.span()),
        field,
        crate::ctx::Num(value),
        reason,
    ))
}

/// The largest initial separation (in magnitude) over `points`: what a
/// load's deformation must be resolved against
/// ([`sanity::MIN_RESOLVED_DEFORMATION`]).
pub(crate) fn largest_separation(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
    points: &PointSet,
) -> Result<f64, SceneError> {
    let eps = elcon_analysis::separations(points, geometry).map_err(|e| match raw {
        Some(g) => {
            let (field, span, value) = files::data_file(g);
            ctx.invalid(span, field, value, e.to_string())
        }
        None => ctx.invalid(0..0, "geometry", "", e.to_string()),
    })?;
    Ok(eps.iter().fold(0.0f64, |m, e| m.max(e.abs())))
}

/// The unit labels the small-strain refusals quote.
pub(crate) fn strain_labels(units: &Units) -> sanity::Labels<'_> {
    sanity::Labels {
        length: units.length(),
        force: units.force(),
        intensity: units.intensity(),
    }
}

/// Given separations, or surfaces with tabulated departures, within
/// [`sanity::MAX_STRAIN`] of the zone's size at every candidate point
/// ([`sanity::small_separations`]); the quadrics alone are bounded by
/// their radii and the small strain of the load.
fn small_separations(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
    points: &PointSet,
    length: &str,
) -> Result<(), SceneError> {
    let (Some(g), Geometry::Separation(_) | Geometry::Tabulated { .. }) = (raw, geometry) else {
        return Ok(());
    };
    let eps = elcon_analysis::separations(points, geometry).map_err(|e| {
        let (field, span, value) = files::data_file(g);
        ctx.invalid(span, field, value, e.to_string())
    })?;
    let Some(reason) = sanity::small_separations(&eps, points, length) else {
        return Ok(());
    };
    let t = g.get_ref();
    let (field, span) = if let Some(f) = &t.separation_file {
        ("geometry.separation_file", f.span())
    } else if let Some(v) = &t.separation {
        ("geometry.separation", v.span())
    } else if let Some(m) = &t.height_map {
        ("geometry.height_map", m.span())
    } else if let Some(p) = &t.profile {
        ("geometry.profile", p.span())
    } else {
        ("geometry", g.span())
    };
    Err(ctx.invalid(span, field, "", reason))
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
pub const MAX_SLUG: usize = 120;

/// `scene.name` (default: the file's stem): it names an output directory.
fn scene_name(ctx: &Ctx<'_>, raw: &SceneFile) -> Result<String, SceneError> {
    let name = match raw.scene.as_ref().and_then(|m| m.name.as_ref()) {
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
    if name.contains(['/', '\\'])
        || name.starts_with('.')
        || name.len() > MAX_SLUG
        || name.chars().any(char::is_control)
    {
        let span = raw
            .scene
            .as_ref()
            .and_then(|m| m.name.as_ref())
            .map_or(0..0, |n| n.span());
        return Err(ctx.invalid(
            span,
            "scene.name",
            &name,
            format!(
                "names an output directory: at most {} bytes, no control characters, no path \
                 separators, and no leading '.' (elcon's temporary siblings and locks start \
                 with one)",
                MAX_SLUG
            ),
        ));
    }
    Ok(name)
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
    line_models: bool,
    surface_models: bool,
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
    } else if matches!(points_spec, PointsSpec::Rectangle { .. }) {
        (false, true)
    } else {
        (false, false)
    }
}

/// The candidate points: absolute, or relative to the Hertz contact at the
/// scene's load (which must then exist, at a size in floating-point range).
fn lay_out(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    bodies: &[BodySpec; 2],
    geometry: &Geometry,
    points_spec: &PointsSpec,
    loading: Loading,
) -> Result<PointSet, SceneError> {
    // The load that sizes Hertz-relative grids (under displacement control
    // there is none: the contact's size is not known before the solve).
    let sizing_load = loading.load_value();
    let scale = sizing_load.and_then(|p| hertz::hertz_scale(bodies, geometry, points_spec, p));
    let relative = matches!(
        points_spec,
        PointsSpec::DiskHertz { .. }
            | PointsSpec::LineHertz { .. }
            | PointsSpec::EllipseHertz { .. }
    ) || matches!(
        points_spec,
        PointsSpec::Rectangle {
            half_x: HalfX::Zone(_),
            ..
        }
    );
    if relative && scale.is_none() {
        let dimension = match points_spec {
            PointsSpec::Line { .. } | PointsSpec::LineHertz { .. } => Dimension::Line,
            _ => Dimension::Surface,
        };
        return Err(ctx.invalid(
            raw.points.span(),
            "points",
            "across/zone",
            sanity::no_hertz_reason(
                [bodies[0].model().name(), bodies[1].model().name()],
                geometry,
                loading,
                dimension,
            ),
        ));
    }
    if relative && sanity::scale_out_of_range(scale) {
        return Err(ctx.invalid(
            raw.loading
                .get_ref()
                .load
                .as_ref()
                .map_or(raw.loading.span(), |l| l.span()),
            "loading.load",
            crate::ctx::Num(sizing_load.unwrap_or(0.0)),
            format!(
                "the Hertz contact at this load has a size of {:e}, outside floating-point range: \
                 the load, the moduli and the radii are not in one consistent unit system",
                scale.unwrap_or(f64::NAN)
            ),
        ));
    }
    let points = build_points(points_spec, scale)
        .map_err(|e| ctx.invalid(raw.points.span(), "points", "", e.to_string()))?;
    if let Geometry::Separation(eps) = geometry
        && eps.len() != points.len()
    {
        let span = raw
            .geometry
            .as_ref()
            .and_then(|g| g.get_ref().separation.as_ref())
            .map_or(0..0, |s| s.span());
        return Err(ctx.invalid(
            span,
            "geometry.separation",
            format!("{} values", eps.len()),
            format!(
                "needs one value per candidate point: the grid has {}",
                points.len()
            ),
        ));
    }
    Ok(points)
}

/// The checks of the scene as a whole ([`sanity`]): the design against its
/// load cases' grids, the bodies against every grid; and the warnings for
/// a grid too coarse for the contact.
fn whole_scene(ctx: &Ctx<'_>, raw: &SceneFile, scene: &Scene) -> Result<Vec<String>, SceneError> {
    let mut sets = Vec::new();
    if let (Some(spec), Some(raw_design)) = (&scene.design, &raw.design) {
        // The number of cases first: every load's grid is built below.
        sanity::design_cases(ctx, raw_design, spec.case_loadings().len())?;
        for &load in spec.loads() {
            let scale =
                hertz::hertz_scale(&scene.bodies, &scene.geometry, &scene.points_spec, load);
            sets.push(build_points(&scene.points_spec, scale).map_err(|e| {
                ctx.invalid(
                    raw_design.span(),
                    "design.loads",
                    load,
                    format!("the grid of this load case: {e}"),
                )
            })?);
        }
        design_loads_small(ctx, raw_design, scene, &sets)?;
        log_crown_resolved(ctx, raw_design, scene)?;
        design_grids_resolve(ctx, raw, scene, &sets)?;
        design_grids_fit(ctx, raw_design, scene)?;
        let view = sanity::DesignView {
            family: match spec.family() {
                DesignFamily::Linear(f) => Some(*f),
                _ => None,
            },
            axis: spec.axis(),
            max_constant: spec.max_constant(),
            loads: spec.loads().to_vec(),
            relative: spec.relative_to() != RelativeTo::Absolute,
            sequence: spec.sequence().cloned(),
        };
        sanity::design(ctx, raw_design, &view, &sets)?;
    }
    sanity::bodies_on_grid(
        ctx,
        [&raw.body1, &raw.body2],
        [scene.bodies[0].body(), scene.bodies[1].body()],
        &scene.points,
        &sets,
    )?;
    let hertz = match &scene.reference {
        Some(Reference::HertzSpheres(h)) => Some(("diameter", h.contact_radius())),
        Some(Reference::HertzCylinders { hertz, .. }) => Some(("width", hertz.half_width())),
        _ => match (scene.loading.normal, &scene.points_spec) {
            (Normal::Load(p), PointsSpec::Rectangle { .. }) => {
                scene.hertz(p).map(|h| ("width", h.scale()))
            }
            _ => None,
        },
    };
    let disk = match scene.points_spec {
        PointsSpec::Disk { spacing, radius } => Some((spacing, radius)),
        _ => None,
    };
    if let Some(u) = sanity::unresolved_grid(&scene.points, hertz, disk) {
        return Err(unresolved_grid(ctx, &raw.points, scene, &u));
    }
    let mut warnings = sanity::coarse_grid(&scene.points, hertz, disk);
    warnings.extend(points::turned_note(&scene.points_spec, &scene.points));
    Ok(warnings)
}

/// The refusal of a grid too coarse to resolve the contact
/// ([`sanity::unresolved_grid`]), naming the field that sets its spacing
/// and the value that would resolve it.
fn unresolved_grid(
    ctx: &Ctx<'_>,
    raw: &Spanned<PointsToml>,
    scene: &Scene,
    u: &sanity::Unresolved,
) -> SceneError {
    let t = raw.get_ref();
    let h = scene.points.cell().dx;
    // The count that brings the spacing below `u.spacing` (strictly: at
    // exactly it, rounding may leave one point fewer across).
    let count = |n: i64| ((n as f64) * h / u.spacing * (1.0 + 1e-6)).ceil() as i64;
    let (field, span, value, needed) = match (&t.spacing, &t.nx, &t.n) {
        (Some(s), _, _) => (
            "points.spacing",
            s.span(),
            crate::ctx::Num(*s.get_ref()).to_string(),
            format!("a spacing of at most {}", crate::ctx::rounded(u.spacing)),
        ),
        (None, Some(nx), _) => (
            "points.nx",
            nx.span(),
            nx.get_ref().to_string(),
            format!("at least {} cells", count(*nx.get_ref())),
        ),
        (None, None, Some(n)) => (
            "points.n",
            n.span(),
            n.get_ref().to_string(),
            format!("at least {} cells", count(*n.get_ref())),
        ),
        _ => (
            "points",
            raw.span(),
            String::new(),
            format!("a spacing of at most {}", crate::ctx::rounded(u.spacing)),
        ),
    };
    ctx.invalid(
        span,
        field,
        value,
        format!(
            "puts {} point(s) across {} ({} {}, spacing {}): fewer than {}, the fewest that tell \
             the pressure's profile from its mean (a contact on one point is the load over one \
             cell); give {needed}",
            u.across,
            u.what,
            crate::ctx::rounded(u.size),
            scene.units.length(),
            crate::ctx::rounded(h),
            sanity::MIN_POINTS_RESOLVED,
        ),
    )
}

/// Every design load within [`sanity::MAX_STRAIN`] on its grid
/// ([`sanity::strain`]), as the scene's own load is.
fn design_loads_small(
    ctx: &Ctx<'_>,
    raw: &Spanned<crate::schema::DesignToml>,
    scene: &Scene,
    sets: &[PointSet],
) -> Result<(), SceneError> {
    let Some(spec) = &scene.design else {
        return Ok(());
    };
    let bodies = [scene.bodies[0].body(), scene.bodies[1].body()];
    let units = &scene.units;
    let labels = strain_labels(units);
    for (i, (&load, set)) in spec.loads().iter().zip(sets).enumerate() {
        // A geometry tabulated on the scene's own points has no separations
        // on another grid: the run refuses that, naming it.
        let largest = elcon_analysis::separations(set, &scene.geometry)
            .ok()
            .map(|eps| eps.iter().fold(0.0f64, |m, e| m.max(e.abs())));
        let reason = sanity::strain(bodies, Normal::Load(load), set, labels).or_else(|| {
            largest.and_then(|largest| {
                sanity::unresolved(bodies, Normal::Load(load), set, largest, units.length())
            })
        });
        if let Some(reason) = reason {
            let loads = raw.get_ref().loads.as_ref();
            let (field, span) = match loads.and_then(|l| l.get_ref().get(i)) {
                Some(v) => (format!("design.loads[{i}]"), v.span()),
                None => ("loading.load".to_string(), raw.span()),
            };
            return Err(ctx.invalid(span, field, crate::ctx::Num(load), reason));
        }
    }
    Ok(())
}

/// A logarithmic crown's `design.design_load` resolved on the scene's grid
/// ([`sanity::unresolved`]): the crown's depth is the deformation of its
/// design load, and a crown within the rounding of the separations
/// relieves nothing, so the design never converges.
fn log_crown_resolved(
    ctx: &Ctx<'_>,
    raw: &Spanned<crate::schema::DesignToml>,
    scene: &Scene,
) -> Result<(), SceneError> {
    let Some(DesignFamily::LogarithmicCrown { design_load, .. }) =
        scene.design.as_ref().map(|d| d.family())
    else {
        return Ok(());
    };
    let bodies = [scene.bodies[0].body(), scene.bodies[1].body()];
    let largest = largest_separation(ctx, None, &scene.geometry, &scene.points)?;
    let Some(reason) = sanity::unresolved(
        bodies,
        Normal::Load(*design_load),
        &scene.points,
        largest,
        scene.units.length(),
    ) else {
        return Ok(());
    };
    let span = raw
        .get_ref()
        .design_load
        .as_ref()
        .map_or(raw.span(), |q| q.span());
    Err(ctx.invalid(
        span,
        "design.design_load",
        crate::ctx::Num(*design_load),
        reason,
    ))
}

/// `design.max_points` admits every load case on the sequence's second
/// grid: a design made on the first holds only once verified on a finer
/// one, and a case beyond `max_points` ends the sequence before that.
fn design_grids_fit(
    ctx: &Ctx<'_>,
    raw: &Spanned<crate::schema::DesignToml>,
    scene: &Scene,
) -> Result<(), SceneError> {
    let Some(spec) = &scene.design else {
        return Ok(());
    };
    let Some(sequence) = spec.sequence() else {
        return Ok(());
    };
    let Some(&fineness) = sequence.fineness.get(1) else {
        return Ok(());
    };
    // A layout without a family is refused by the run, naming its reason.
    let largest = spec
        .loads()
        .iter()
        .filter_map(|&load| scene.grid_for(load, fineness).ok())
        .filter_map(|g| g.points().ok())
        .map(|p| p.len())
        .max()
        .unwrap_or(0);
    if largest <= sequence.max_points {
        return Ok(());
    }
    let t = raw.get_ref();
    Err(ctx.invalid(
        t.max_points.as_ref().map_or(raw.span(), |m| m.span()),
        "design.max_points",
        sequence.max_points,
        format!(
            "admits no grid to verify a design on: the largest load case has {largest} points on \
             the second grid (spacing h / {fineness}), where a design made on the scene's grid is \
             verified; give at least {largest}, or a coarser grid"
        ),
    ))
}

/// Every design load's grid resolves its Hertz contact (where a closed
/// form gives one) with [`sanity::MIN_POINTS_ACROSS`] points across: what
/// a scene's analysis only warns of refuses a design, whose objective
/// compares each load's `p_max` over grids and cannot be met on a grid
/// that averages the contact over a cell or two.
fn design_grids_resolve(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    scene: &Scene,
    sets: &[PointSet],
) -> Result<(), SceneError> {
    let Some(spec) = &scene.design else {
        return Ok(());
    };
    for (&load, set) in spec.loads().iter().zip(sets) {
        let cell = set.cell();
        let aspect = (cell.dx / cell.dy).max(cell.dy / cell.dx);
        if set.dimension() == Dimension::Surface && aspect > sanity::MAX_DESIGN_CELL_ASPECT {
            return Err(ctx.invalid(
                raw.points.span(),
                "points",
                "",
                format!(
                    "the design load {} has cells {aspect:.1e} times longer than wide ({:.4e} by \
                     {:.4e}), more than {:.0e}: the influence coefficients of such cells resolve \
                     too few digits for the certified analyses a design makes on finer and finer \
                     grids. Give cells closer to square (points.half_y and points.ny against the \
                     contact's width and points.nx)",
                    crate::ctx::Num(load),
                    cell.dx,
                    cell.dy,
                    sanity::MAX_DESIGN_CELL_ASPECT
                ),
            ));
        }
        let Some((what, size)) = scene.hertz(load).map(|h| match h {
            hertz::Hertz::Cylinders(c) => ("width", 2.0 * c.half_width()),
            other => ("diameter", 2.0 * other.scale()),
        }) else {
            continue;
        };
        let h = set.cell().dx;
        let across = (size / h).floor() + 1.0;
        if across >= sanity::MIN_POINTS_ACROSS as f64 {
            continue;
        }
        let keys = match scene.points_spec {
            PointsSpec::Rectangle { .. } => {
                "more points.nx, or a smaller points.zone or points.half_x"
            }
            PointsSpec::Disk { .. } => "a smaller points.spacing",
            PointsSpec::Line { .. } => "more points.n, or a shorter line",
            _ => "more points.across, or a smaller points.zone",
        };
        return Err(ctx.invalid(
            raw.points.span(),
            "points",
            "",
            format!(
                "the design load {} has about {across:.0} points across its Hertz contact {what} \
                 ({size:.4e}, spacing {h:.4e}), fewer than {}: a design compares each load's \
                 p_max over grids and needs its contact resolved. Give {keys}",
                crate::ctx::Num(load),
                sanity::MIN_POINTS_ACROSS
            ),
        ));
    }
    Ok(())
}

/// An absolute grid that cannot hold the Hertz contact is an error.
fn check_zone(
    ctx: &Ctx<'_>,
    p: &Spanned<PointsToml>,
    reference: Option<&Reference>,
    points: &PointSet,
) -> Result<(), SceneError> {
    let t = p.get_ref();
    match reference {
        Some(Reference::HertzSpheres(h)) => {
            if let Some(r) = &t.radius
                && *r.get_ref() <= h.contact_radius()
            {
                return Err(ctx.invalid(
                    r.span(),
                    "points.radius",
                    r.get_ref(),
                    format!(
                        "the candidate disk cannot hold the contact: the Hertz contact radius is {:.4e}; \
                         give a radius beyond it (1.2 to 1.5 times)",
                        h.contact_radius()
                    ),
                ));
            }
        }
        Some(Reference::HertzCylinders { hertz, .. }) => {
            let (lo, hi) = (points.x(0), points.x(points.len() - 1));
            let b = hertz.half_width();
            if let (Some(s), true) = (&t.start, lo > -b || hi < b) {
                return Err(ctx.invalid(
                    s.span(),
                    "points.start",
                    s.get_ref(),
                    format!("the line [{lo:.4e}, {hi:.4e}] cannot hold the contact: the Hertz half-width is {b:.4e}"),
                ));
            }
        }
        _ => {}
    }
    Ok(())
}
