//! A validated scene: the TOML file turned into the objects of the solver
//! crates, every value checked against its physical range with a message
//! that names the file, the line and column, and the field.
//!
//! The scene's equations are those of elcon-analysis (compatibility
//! `Y = S F + eps - alpha e`, equilibrium `e^T F = P`, the contact
//! criterion) and, with a `[design]` section, elcon-design. What a scene
//! does not ask for is neither read nor computed: no design stage without
//! `[design]`, no reference where no closed form applies, no plot not asked.

use std::path::{Path, PathBuf};

use elcon_analysis::references::{FlatPunch, HertzCylinders, HertzSpheres, HetenyiBeam};
use elcon_analysis::{Geometry, Layout, Loading, Method, Normal, Options, Surface};
use elcon_design::{Axis, DesignMethod, Family, LogEnd};
use elcon_influence::{Body, Dimension, Material, PointSet, combined_modulus_of};
use toml::Spanned;

use crate::ctx::{Ctx, parse};
use crate::error::SceneError;
use crate::sanity;
use crate::schema::{
    AxisName, BodyToml, DesignMethodName, DesignToml, EndName, FamilyName, GeometryToml, Grid,
    LoadingToml, PointsToml, SceneFile, Shape, SolverMethod, SurfaceToml, Symmetry,
};
pub use crate::schema::{ModelKind, Plot, RelativeTo};
use crate::storage::{self, MethodChoice, Storage};

/// The unit labels of a scene (any consistent system; the labels are
/// repeated in every output, never used in arithmetic).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Units {
    /// Length, e.g. "in", "m", "mm".
    pub length: String,
    /// Force, e.g. "lbf", "N".
    pub force: String,
    /// Stress and pressure (default `force/length^2`), e.g. "psi", "Pa", "MPa".
    pub pressure: String,
    /// The unit of the load intensity F_k / A_k of this scene: the pressure
    /// unit, or `force/length` on a beam.
    pub intensity: String,
}

/// One body of a scene: the influence model and, for the half-space
/// models, the material (the references need it).
#[derive(Debug, Clone)]
pub struct BodySpec {
    /// The model (`body.model`).
    pub model: ModelKind,
    /// The body for elcon-influence.
    pub body: Body,
    /// The material of a half-space model.
    pub material: Option<Material>,
}

/// How the candidate points are laid out.
#[derive(Debug, Clone, PartialEq)]
pub enum PointsSpec {
    /// Square grid of `spacing`, clipped to a disk of `radius`.
    Disk {
        /// Spacing (length).
        spacing: f64,
        /// Radius of the candidate zone (length).
        radius: f64,
    },
    /// Square grid with `across` points across the Hertz contact diameter,
    /// clipped to `zone` Hertz radii.
    DiskHertz {
        /// Points across the Hertz diameter (odd: the centre is a point).
        across: usize,
        /// Candidate zone over the Hertz radius (> 1).
        zone: f64,
    },
    /// `nx x ny` cells on `[-half_x, half_x] x [-half_y, half_y]`;
    /// `half_x` absolute, or `zone` Hertz half-widths of the case's load.
    Rectangle {
        /// Half-size along x (length), if absolute.
        half_x: Option<f64>,
        /// Half-size along x over the Hertz half-width, if relative.
        zone: Option<f64>,
        /// Half-size along y (length).
        half_y: f64,
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
    },
    /// `n` cells on `[start, end]` of the x axis.
    Line {
        /// Start (length).
        start: f64,
        /// End (length).
        end: f64,
        /// Number of cells.
        n: usize,
    },
    /// Cells with `across` points across the Hertz contact width, out to
    /// `zone` Hertz half-widths.
    LineHertz {
        /// Points across the Hertz width.
        across: usize,
        /// Candidate zone over the Hertz half-width (> 1).
        zone: f64,
    },
}

/// The closed form a scene is compared with, when one applies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference {
    /// Hertz, two spheres or a sphere on a plane.
    HertzSpheres(HertzSpheres),
    /// Hertz line contact (plane strain); the approach is compared when the
    /// datum distance d0 is the same for the elastic bodies.
    HertzCylinders {
        /// The closed form.
        hertz: HertzCylinders,
        /// The common datum distance d0.
        datum: Option<f64>,
    },
    /// A rigid flat circular punch whose face is the candidate disk.
    FlatPunch(FlatPunch),
    /// A free-free beam on a Winkler foundation under a central load.
    Hetenyi(HetenyiBeam),
}

impl Reference {
    /// A short name: "hertz-spheres", "hertz-cylinders", "flat-punch", "hetenyi-beam".
    pub fn kind(&self) -> &'static str {
        match self {
            Reference::HertzSpheres(_) => "hertz-spheres",
            Reference::HertzCylinders { .. } => "hertz-cylinders",
            Reference::FlatPunch(_) => "flat-punch",
            Reference::Hetenyi(_) => "hetenyi-beam",
        }
    }
}

/// The profile family of a design section.
#[derive(Debug, Clone, PartialEq)]
pub enum DesignFamily {
    /// A family linear in its parameters (quadratic, polynomial, free).
    Linear(Family),
    /// A circular crown, its radius searched in `radius_range`.
    CircularCrown {
        /// The search bracket (length).
        radius_range: (f64, f64),
        /// Flat middle (length).
        flat_length: f64,
    },
    /// A logarithmic crown (Johns-Gohar) for `design_load`.
    LogarithmicCrown {
        /// The design load (force; default the largest load).
        design_load: f64,
        /// Flat middle (length).
        flat_length: f64,
        /// Lundberg's end, or Johns & Gohar's finite end drop (the default).
        end: LogEnd,
    },
}

/// A validated `[design]` section.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpec {
    /// The family.
    pub family: DesignFamily,
    /// The axial coordinate.
    pub axis: Axis,
    /// The load cases (force).
    pub loads: Vec<f64>,
    /// The reference intensities.
    pub relative_to: RelativeTo,
    /// The bound c_max (length), if given.
    pub max_constant: Option<f64>,
    /// How a linear family's problem is solved (`design.method`).
    pub method: DesignMethod,
    /// Misalignments (rad): every load is a case at each, a prescribed
    /// rotation about the axis across the profile (`tilt_x` when the
    /// profile runs along y, `tilt_y` along x); empty: the loads alone,
    /// their rotations free without a moment.
    pub misalignments: Vec<f64>,
}

impl DesignSpec {
    /// The design's load cases: each load at each misalignment (or alone).
    pub fn case_loadings(&self) -> Vec<(f64, Option<f64>)> {
        let angles: Vec<Option<f64>> = if self.misalignments.is_empty() {
            vec![None]
        } else {
            self.misalignments.iter().copied().map(Some).collect()
        };
        self.loads
            .iter()
            .flat_map(|&load| angles.iter().map(move |&a| (load, a)))
            .collect()
    }
}

/// Misalignments a design takes at most (each load is a case at each).
pub const MAX_MISALIGNMENTS: usize = 100;
/// The largest misalignment (rad): the rigid rotation is linearized
/// (`theta x`), which holds to 0.5 % of the angle up to 0.1 rad.
pub const MAX_MISALIGNMENT: f64 = 0.1;

/// What to write.
#[derive(Debug, Clone, PartialEq)]
pub struct Outputs {
    /// The plots asked for (default none).
    pub plots: Vec<Plot>,
    /// Whether to write pressure.csv (default true).
    pub pressure_csv: bool,
}

/// A validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The scene's name (default: the file's stem).
    pub name: String,
    /// The file it came from.
    pub file: PathBuf,
    /// Its description.
    pub description: Option<String>,
    /// Unit labels.
    pub units: Units,
    /// The two bodies.
    pub bodies: [BodySpec; 2],
    /// The initial separations' source.
    pub geometry: Geometry,
    /// The point layout.
    pub points_spec: PointsSpec,
    /// The candidate points for the scene's loading.
    pub points: PointSet,
    /// Load or approach.
    pub loading: Loading,
    /// The engine's method (`solver.method`; `"auto"` resolved, see
    /// [`Storage`]).
    pub method: Method,
    /// How the contact problem holds S: dense, or matrix-free on the
    /// lattice (`solver.method`'s choice, see [`Storage`]).
    pub storage: Storage,
    /// The engine's options.
    pub options: Options,
    /// Whether to fold a mirror-symmetric problem (`solver.symmetry`,
    /// "auto" (default) or "none").
    pub fold: bool,
    /// The design stage, if asked for.
    pub design: Option<DesignSpec>,
    /// The outputs.
    pub outputs: Outputs,
    /// The closed form that applies, if any.
    pub reference: Option<Reference>,
    /// The zone's edges that are the bodies' own (along x, along y):
    /// contact reaching them raises no truncation warning. Inferred: a
    /// beam's ends (x), a roller's ends on a rectangle grid (y), a flat
    /// punch's rim (both).
    pub body_edges: (bool, bool),
    /// What validation found doubtful but not wrong (a grid coarser than
    /// the contact): printed by `elcon check` and `elcon run`, and written
    /// to result.json's warnings.
    pub warnings: Vec<String>,
}

impl Scene {
    /// Reads and validates a scene file.
    ///
    /// # Errors
    /// [`SceneError::Io`] if it cannot be read; [`SceneError::Syntax`] for
    /// invalid TOML, unknown or missing keys and wrong types;
    /// [`SceneError::Invalid`] for values out of their physical range.
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::io(path, e))?;
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
        build_points(&self.points_spec, scale).map_err(|reason| SceneError::Run {
            scene: self.name.clone(),
            reason,
        })
    }

    /// The Hertz length scale (contact radius or half-width) at `load`.
    fn hertz_scale(&self, load: f64) -> Option<f64> {
        hertz_scale(&self.bodies, &self.geometry, &self.points_spec, load)
    }

    /// The Hertz contact at `load`, where one applies (the layout, bodies
    /// and surfaces of a Hertz contact).
    pub(crate) fn hertz(&self, load: f64) -> Option<Hertz> {
        hertz(&self.bodies, &self.geometry, &self.points_spec, load)
    }
}

fn validate(ctx: &Ctx<'_>, raw: SceneFile) -> Result<Scene, SceneError> {
    let name = scene_name(ctx, &raw)?;
    let description = raw.scene.as_ref().and_then(|m| m.description.clone());
    let bodies = [
        body(ctx, raw.body1.get_ref(), "body1")?,
        body(ctx, raw.body2.get_ref(), "body2")?,
    ];
    let (line_models, surface_models) = model_kinds(ctx, &raw, &bodies)?;
    let units = units(
        ctx,
        raw.units.get_ref(),
        bodies.iter().any(|b| b.model == ModelKind::Beam),
    )?;
    let loading = loading(ctx, &raw.loading)?;
    let (points_spec, dimension) = points_spec(ctx, &raw.points)?;
    grid_fits_models(ctx, &raw, dimension, line_models, surface_models)?;
    let geometry = geometry(ctx, raw.geometry.as_ref(), dimension)?;
    sanity::curvatures(ctx, raw.geometry.as_ref(), &geometry)?;
    let points = lay_out(ctx, &raw, &bodies, &geometry, &points_spec, loading)?;
    let reference = reference(&bodies, &geometry, &points_spec, &points, loading);
    check_zone(ctx, &raw.points, reference.as_ref(), &points)?;
    let (choice, options) = solver(ctx, raw.solver.as_ref())?;
    sanity::solver_bounds(ctx, raw.solver.as_ref(), points.len())?;
    let fold = symmetry(raw.solver.as_ref());
    let scene_bodies = [&bodies[0].body, &bodies[1].body];
    let layout = Layout::of(&points, scene_bodies, &geometry, &loading, fold).ok();
    let (method, storage) = storage::choose(choice, &points, scene_bodies, layout.as_ref(), fold);
    let design = match &raw.design {
        Some(d) => Some(design(
            ctx,
            d,
            &DesignContext {
                loading,
                dimension,
                bodies: &bodies,
                geometry: &geometry,
                points_spec: &points_spec,
            },
        )?),
        None => None,
    };
    if let (Some(d), Some(raw_design), Storage::MatrixFree) = (&design, &raw.design, storage)
        && d.method == DesignMethod::Program
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
    let outputs = outputs(ctx, raw.outputs.as_ref(), design.is_some())?;
    let body_edges = body_edges(&bodies, reference.as_ref(), &points_spec);
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
        method,
        storage,
        options,
        fold,
        design,
        outputs,
        reference,
        body_edges,
        warnings: Vec::new(),
    };
    scene.warnings = whole_scene(ctx, &raw, &scene)?;
    Ok(scene)
}

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
    if name.contains(['/', '\\']) || name.starts_with('.') {
        let span = raw
            .scene
            .as_ref()
            .and_then(|m| m.name.as_ref())
            .map_or(0..0, |n| n.span());
        return Err(ctx.invalid(
            span,
            "scene.name",
            &name,
            "names an output directory: no path separators, and no leading '.' (elcon's \
             temporary siblings and locks start with one)",
        ));
    }
    Ok(name)
}

/// The bodies' models: not both rigid, and all of one kind (line models:
/// plane-strain, beam; surface models: point-force, uniform-patch).
/// Returns (line models present, surface models present).
fn model_kinds(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    bodies: &[BodySpec; 2],
) -> Result<(bool, bool), SceneError> {
    if bodies.iter().all(|b| b.body.is_rigid()) {
        return Err(ctx.invalid(
            raw.body2.get_ref().model.span(),
            "body2.model",
            "\"rigid\"",
            "both bodies are rigid: there is no elasticity to solve for; give one an elastic model",
        ));
    }
    let line_models = bodies.iter().any(|b| b.model.is_line());
    let surface_models = bodies.iter().any(|b| b.model.is_surface());
    if line_models && surface_models {
        return Err(ctx.invalid(
            raw.body2.get_ref().model.span(),
            "body2.model",
            format!("\"{}\"", bodies[1].model),
            format!(
                "does not go with body1's \"{}\": line models (plane-strain, beam) and surface models \
                 (point-force, uniform-patch) cannot share a point set",
                bodies[0].model
            ),
        ));
    }
    Ok((line_models, surface_models))
}

/// The grid's dimension matches the models', and a line takes no rotation
/// about x.
fn grid_fits_models(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    dimension: Dimension,
    line_models: bool,
    surface_models: bool,
) -> Result<(), SceneError> {
    if line_models && dimension != Dimension::Line {
        return Err(ctx.invalid(
            raw.points.get_ref().grid.span(),
            "points.grid",
            format!("\"{}\"", raw.points.get_ref().grid.get_ref()),
            "the bodies' models (plane-strain, beam) need grid = \"line\"",
        ));
    }
    if surface_models && dimension != Dimension::Surface {
        return Err(ctx.invalid(
            raw.points.get_ref().grid.span(),
            "points.grid",
            "\"line\"",
            "the bodies' models (point-force, uniform-patch) need grid = \"disk\" or \"rectangle\"",
        ));
    }
    if dimension == Dimension::Line {
        // A line has one rotation, about the y axis.
        let l = raw.loading.get_ref();
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

/// `solver.symmetry`: "auto" (fold when symmetric, the default) or "none".
fn symmetry(solver: Option<&crate::schema::SolverToml>) -> bool {
    solver
        .and_then(|s| s.symmetry.as_ref())
        .is_none_or(|v| *v.get_ref() == Symmetry::Auto)
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
    } else if bodies.iter().any(|b| b.model == ModelKind::Beam) {
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
    let scale = sizing_load.and_then(|p| hertz_scale(bodies, geometry, points_spec, p));
    let relative = matches!(
        points_spec,
        PointsSpec::DiskHertz { .. } | PointsSpec::LineHertz { .. }
    ) || matches!(points_spec, PointsSpec::Rectangle { zone: Some(_), .. });
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
                [bodies[0].model.name(), bodies[1].model.name()],
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
        .map_err(|reason| ctx.invalid(raw.points.span(), "points", "", reason))?;
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
        for &load in &spec.loads {
            let scale = hertz_scale(&scene.bodies, &scene.geometry, &scene.points_spec, load);
            sets.push(build_points(&scene.points_spec, scale).map_err(|reason| {
                ctx.invalid(
                    raw_design.span(),
                    "design.loads",
                    load,
                    format!("the grid of this load case: {reason}"),
                )
            })?);
        }
        let view = sanity::DesignView {
            family: match &spec.family {
                DesignFamily::Linear(f) => Some(*f),
                _ => None,
            },
            axis: spec.axis,
            max_constant: spec.max_constant,
        };
        sanity::design(ctx, raw_design, &view, &sets)?;
    }
    sanity::bodies_on_grid(
        ctx,
        [&raw.body1, &raw.body2],
        [&scene.bodies[0].body, &scene.bodies[1].body],
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
    Ok(sanity::coarse_grid(&scene.points, hertz, disk))
}

fn units(ctx: &Ctx<'_>, u: &crate::schema::UnitsToml, beam: bool) -> Result<Units, SceneError> {
    for (v, field) in [(&u.length, "units.length"), (&u.force, "units.force")] {
        if v.get_ref().trim().is_empty() {
            return Err(ctx.invalid(v.span(), field, "\"\"", "must name the unit"));
        }
    }
    let length = u.length.get_ref().clone();
    let force = u.force.get_ref().clone();
    let pressure = u
        .pressure
        .as_ref()
        .map_or_else(|| format!("{force}/{length}^2"), |p| p.get_ref().clone());
    let intensity = if beam {
        format!("{force}/{length}")
    } else {
        pressure.clone()
    };
    Ok(Units {
        length,
        force,
        pressure,
        intensity,
    })
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

fn body(ctx: &Ctx<'_>, b: &BodyToml, section: &str) -> Result<BodySpec, SceneError> {
    let kind = *b.model.get_ref();
    let model = kind.name();
    let keys = model_keys(kind);
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
    for (key, v) in given {
        if let Some(v) = v
            && !keys.contains(&key)
        {
            return Err(ctx.invalid(
                v.span(),
                format!("{section}.{key}"),
                v.get_ref(),
                if keys.is_empty() {
                    format!("is not a parameter of the {model} model (it takes none)")
                } else {
                    format!(
                        "is not a parameter of the {model} model (it takes: {})",
                        keys.join(", ")
                    )
                },
            ));
        }
    }
    let section_span = b.model.span();
    let field = |k: &str| format!("{section}.{k}");
    let material = |ctx: &Ctx<'_>| -> Result<Material, SceneError> {
        let e = ctx.required(
            &b.youngs_modulus,
            section_span.clone(),
            &field("youngs_modulus"),
            "by this model",
        )?;
        let nu = ctx.required(
            &b.poissons_ratio,
            section_span.clone(),
            &field("poissons_ratio"),
            "by this model",
        )?;
        let e_value = ctx.positive(e, &field("youngs_modulus"))?;
        let nu_value = *nu.get_ref();
        if !(nu_value.is_finite() && nu_value > -1.0 && nu_value < 0.5) {
            return Err(ctx.invalid(
                nu.span(),
                field("poissons_ratio"),
                nu_value,
                "must be in (-1, 0.5): outside it the elastic energy is not positive definite",
            ));
        }
        Material::new(e_value, nu_value)
            .map_err(|err| ctx.invalid(e.span(), field("youngs_modulus"), e_value, err.to_string()))
    };
    let (body, material) = match kind {
        ModelKind::Rigid => (Body::rigid(), None),
        ModelKind::PointForce => {
            let m = material(ctx)?;
            (Body::point_force(m), Some(m))
        }
        ModelKind::UniformPatch => {
            let m = material(ctx)?;
            (Body::uniform_patch(m), Some(m))
        }
        ModelKind::PlaneStrain => {
            let m = material(ctx)?;
            let d0 = ctx.required(
                &b.reference_distance,
                section_span.clone(),
                &field("reference_distance"),
                "by the plane-strain model (the datum distance d0 of the 2D displacements)",
            )?;
            (
                Body::plane_strain(m, ctx.positive(d0, &field("reference_distance"))?),
                Some(m),
            )
        }
        ModelKind::Winkler => {
            let k = ctx.required(
                &b.modulus,
                section_span.clone(),
                &field("modulus"),
                "by the Winkler model",
            )?;
            (Body::winkler(ctx.positive(k, &field("modulus"))?), None)
        }
        ModelKind::Beam => {
            let e = ctx.required(
                &b.youngs_modulus,
                section_span.clone(),
                &field("youngs_modulus"),
                "by the beam model",
            )?;
            let e = ctx.positive(e, &field("youngs_modulus"))?;
            let i = match (&b.second_moment, &b.width, &b.depth) {
                (Some(i), None, None) => ctx.positive(i, &field("second_moment"))?,
                (None, Some(w), Some(d)) => {
                    ctx.positive(w, &field("width"))? * ctx.positive(d, &field("depth"))?.powi(3)
                        / 12.0
                }
                _ => {
                    return Err(ctx.invalid(
                        section_span,
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
            (Body::beam(e, i, x0), None)
        }
    };
    Ok(BodySpec {
        model: kind,
        body,
        material,
    })
}

fn loading(ctx: &Ctx<'_>, l: &Spanned<LoadingToml>) -> Result<Loading, SceneError> {
    let t = l.get_ref();
    let mut loading = match (&t.load, &t.approach) {
        (Some(p), None) => Loading::load(ctx.positive(p, "loading.load")?),
        (None, Some(a)) => Loading::approach(ctx.finite(a, "loading.approach")?),
        _ => {
            return Err(ctx.invalid(
                l.span(),
                "loading",
                "",
                "give exactly one of load (force; load control) and approach (length; displacement control)",
            ));
        }
    };
    // Each rotation: free with its moment (default 0) or prescribed.
    for (moment, tilt, moment_field, tilt_field) in [
        (&t.moment_x, &t.tilt_x, "loading.moment_x", "loading.tilt_x"),
        (&t.moment_y, &t.tilt_y, "loading.moment_y", "loading.tilt_y"),
    ] {
        let x_axis = moment_field.ends_with('x');
        loading = match (moment, tilt) {
            (Some(_), Some(angle)) => {
                return Err(ctx.invalid(
                    angle.span(),
                    tilt_field,
                    angle.get_ref().to_string(),
                    format!(
                        "give one of {moment_field} (a free rotation balancing that moment) and \
                         {tilt_field} (a prescribed rotation, radians), not both"
                    ),
                ));
            }
            (Some(m), None) => {
                let m = ctx.finite(m, moment_field)?;
                if x_axis {
                    loading.with_moment_x(m)
                } else {
                    loading.with_moment_y(m)
                }
            }
            (None, Some(a)) => {
                let a = ctx.finite(a, tilt_field)?;
                if x_axis {
                    loading.with_tilt_x(a)
                } else {
                    loading.with_tilt_y(a)
                }
            }
            (None, None) => loading,
        };
    }
    Ok(loading)
}

/// `[points]`: the grid and its parameters, each key checked against the grid.
fn points_spec(
    ctx: &Ctx<'_>,
    p: &Spanned<PointsToml>,
) -> Result<(PointsSpec, Dimension), SceneError> {
    let t = p.get_ref();
    let grid = *t.grid.get_ref();
    let allowed: &[&str] = match grid {
        Grid::Disk => &["spacing", "radius", "across", "zone"],
        Grid::Rectangle => &["half_x", "half_y", "nx", "ny", "zone"],
        Grid::Line => &["start", "end", "n", "across", "zone"],
    };
    grid_keys(ctx, t, grid.name(), allowed)?;
    let spec = match grid {
        Grid::Disk => disk_spec(ctx, p)?,
        Grid::Rectangle => rectangle_spec(ctx, p)?,
        Grid::Line => line_spec(ctx, p)?,
    };
    let dimension = if grid == Grid::Line {
        Dimension::Line
    } else {
        Dimension::Surface
    };
    Ok((spec, dimension))
}

/// Every key given under `[points]` must be one of `grid`'s.
fn grid_keys(
    ctx: &Ctx<'_>,
    t: &PointsToml,
    grid: &str,
    allowed: &[&str],
) -> Result<(), SceneError> {
    let floats: [(&str, Option<&Spanned<f64>>); 7] = [
        ("spacing", t.spacing.as_ref()),
        ("radius", t.radius.as_ref()),
        ("zone", t.zone.as_ref()),
        ("half_x", t.half_x.as_ref()),
        ("half_y", t.half_y.as_ref()),
        ("start", t.start.as_ref()),
        ("end", t.end.as_ref()),
    ];
    let ints: [(&str, Option<&Spanned<i64>>); 4] = [
        ("across", t.across.as_ref()),
        ("nx", t.nx.as_ref()),
        ("ny", t.ny.as_ref()),
        ("n", t.n.as_ref()),
    ];
    for (key, span) in floats
        .iter()
        .filter_map(|(k, v)| v.map(|v| (*k, v.span())))
        .chain(ints.iter().filter_map(|(k, v)| v.map(|v| (*k, v.span()))))
    {
        if !allowed.contains(&key) {
            return Err(ctx.invalid(
                span,
                format!("points.{key}"),
                "",
                format!(
                    "is not a parameter of grid = \"{grid}\" (it takes: {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// `points.zone` (required with `across`): the candidate zone over the
/// Hertz contact, above 1.
fn hertz_zone(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<f64, SceneError> {
    let t = p.get_ref();
    let s = p.span();
    let z = ctx.required(&t.zone, s.clone(), "points.zone", "with across")?;
    let v = ctx.positive(z, "points.zone")?;
    if v <= 1.0 {
        return Err(ctx.invalid(
            z.span(),
            "points.zone",
            v,
            "the candidate zone must extend beyond the Hertz contact (zone > 1), or the contact is cut off",
        ));
    }
    Ok(v)
}

/// `points.across`: odd, at least 3.
fn hertz_across(ctx: &Ctx<'_>, a: &Spanned<i64>) -> Result<usize, SceneError> {
    let n = ctx.count(a, "points.across", 3)?;
    if n % 2 == 0 {
        return Err(ctx.invalid(
            a.span(),
            "points.across",
            n,
            "must be odd (the centre is a point)",
        ));
    }
    Ok(n)
}

/// A disk: `across` and `zone`, or `spacing` and `radius`.
fn disk_spec(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<PointsSpec, SceneError> {
    let (t, s) = (p.get_ref(), p.span());
    Ok(match &t.across {
        Some(a) => {
            ctx.forbid(
                &t.spacing,
                "points.spacing",
                "give either across and zone, or spacing and radius",
            )?;
            ctx.forbid(
                &t.radius,
                "points.radius",
                "give either across and zone, or spacing and radius",
            )?;
            PointsSpec::DiskHertz {
                across: hertz_across(ctx, a)?,
                zone: hertz_zone(ctx, p)?,
            }
        }
        None => {
            ctx.forbid(
                &t.zone,
                "points.zone",
                "zone goes with across (points across the Hertz diameter)",
            )?;
            let h = ctx.required(
                &t.spacing,
                s.clone(),
                "points.spacing",
                "for a disk (or across and zone)",
            )?;
            let r = ctx.required(
                &t.radius,
                s.clone(),
                "points.radius",
                "for a disk (or across and zone)",
            )?;
            PointsSpec::Disk {
                spacing: ctx.positive(h, "points.spacing")?,
                radius: ctx.positive(r, "points.radius")?,
            }
        }
    })
}

/// A rectangle: `half_x` or `zone`, and `half_y`, `nx`, `ny`.
fn rectangle_spec(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<PointsSpec, SceneError> {
    let (t, s) = (p.get_ref(), p.span());
    Ok({
        let (half_x, zone_x) = match (&t.half_x, &t.zone) {
            (Some(h), None) => (Some(ctx.positive(h, "points.half_x")?), None),
            (None, Some(_)) => (None, Some(hertz_zone(ctx, p)?)),
            _ => {
                return Err(ctx.invalid(
                    s,
                    "points.half_x",
                    "",
                    "give either half_x (length) or zone (Hertz half-widths of the load)",
                ));
            }
        };
        let hy = ctx.required(&t.half_y, s.clone(), "points.half_y", "for a rectangle")?;
        let nx = ctx.required(&t.nx, s.clone(), "points.nx", "for a rectangle")?;
        let ny = ctx.required(&t.ny, s.clone(), "points.ny", "for a rectangle")?;
        PointsSpec::Rectangle {
            half_x,
            zone: zone_x,
            half_y: ctx.positive(hy, "points.half_y")?,
            nx: ctx.count(nx, "points.nx", 1)?,
            ny: ctx.count(ny, "points.ny", 1)?,
        }
    })
}

/// A line: `across` and `zone`, or `start`, `end` and `n`.
fn line_spec(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<PointsSpec, SceneError> {
    let (t, s) = (p.get_ref(), p.span());
    Ok(match &t.across {
        Some(a) => PointsSpec::LineHertz {
            across: hertz_across(ctx, a)?,
            zone: hertz_zone(ctx, p)?,
        },
        None => {
            ctx.forbid(
                &t.zone,
                "points.zone",
                "zone goes with across (points across the Hertz width)",
            )?;
            let a = ctx.required(
                &t.start,
                s.clone(),
                "points.start",
                "for a line (or across and zone)",
            )?;
            let b = ctx.required(
                &t.end,
                s.clone(),
                "points.end",
                "for a line (or across and zone)",
            )?;
            let n = ctx.required(
                &t.n,
                s.clone(),
                "points.n",
                "for a line (or across and zone)",
            )?;
            let (start, end) = (ctx.finite(a, "points.start")?, ctx.finite(b, "points.end")?);
            if end <= start {
                return Err(ctx.invalid(
                    b.span(),
                    "points.end",
                    end,
                    format!("must exceed points.start = {start}"),
                ));
            }
            PointsSpec::Line {
                start,
                end,
                n: ctx.count(n, "points.n", 1)?,
            }
        }
    })
}

/// Builds the point set; `scale` is the Hertz radius or half-width for the
/// relative layouts.
pub(crate) fn build_points(spec: &PointsSpec, scale: Option<f64>) -> Result<PointSet, String> {
    let need = || {
        scale.ok_or_else(|| {
            "the layout is relative to a Hertz contact that does not apply".to_string()
        })
    };
    let r = match *spec {
        PointsSpec::Disk { spacing, radius } => PointSet::grid_disk(spacing, radius),
        PointsSpec::DiskHertz { across, zone } => {
            return elcon_analysis::grid::hertz_disk(need()?, across, zone)
                .map_err(|e| e.to_string());
        }
        PointsSpec::Rectangle {
            half_x,
            zone,
            half_y,
            nx,
            ny,
        } => {
            let hx = match (half_x, zone) {
                (Some(h), _) => h,
                (None, Some(z)) => z * need()?,
                (None, None) => unreachable!("validated: half_x or zone"),
            };
            PointSet::grid_rectangle(hx, half_y, nx, ny)
        }
        PointsSpec::Line { start, end, n } => PointSet::line(start, end, n),
        PointsSpec::LineHertz { across, zone } => {
            return elcon_analysis::grid::hertz_line(need()?, across, zone)
                .map_err(|e| e.to_string());
        }
    };
    r.map_err(|e| e.to_string())
}

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

fn geometry(
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
                if let Some(f) = f {
                    return Err(ctx.invalid(
                        f.span(),
                        name,
                        "",
                        "give either surfaces or a separation, not both",
                    ));
                }
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
fn combined(geometry: &Geometry, spheres: bool) -> Option<f64> {
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

/// E* of the bodies if they are half-space models (or rigid) of `models`.
fn half_space_modulus(bodies: &[BodySpec; 2], models: &[&str]) -> Option<f64> {
    if !bodies
        .iter()
        .all(|b| b.model == ModelKind::Rigid || models.contains(&b.model.name()))
    {
        return None;
    }
    let e = combined_modulus_of(bodies[0].material.as_ref(), bodies[1].material.as_ref());
    e.is_finite().then_some(e)
}

/// The Hertz contact of a scene at one load: the closed form its layout,
/// bodies and surfaces call for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Hertz {
    /// Point contact: spheres (or a sphere on a plane) on a disk grid.
    Spheres(HertzSpheres),
    /// Line contact: cylinders (or a cylinder on a plane) on a line, or a
    /// roller along y on a rectangle grid (per unit length `2 half_y`).
    Cylinders(HertzCylinders),
}

impl Hertz {
    /// The length scale: the contact radius or the half-width.
    pub(crate) fn scale(&self) -> f64 {
        match self {
            Hertz::Spheres(h) => h.contact_radius(),
            Hertz::Cylinders(h) => h.half_width(),
        }
    }

    /// The peak pressure (intensity unit).
    pub(crate) fn peak_pressure(&self) -> f64 {
        match self {
            Hertz::Spheres(h) => h.peak_pressure(),
            Hertz::Cylinders(h) => h.peak_pressure(),
        }
    }
}

/// The Hertz contact at `load`, if one applies: spheres/planes and
/// half-space surface bodies on a disk; cylinders/planes and plane-strain
/// bodies on a line; cylinders/planes and half-space surface bodies on a
/// rectangle (a roller along y, per unit length `2 half_y`). Rigid bodies
/// count as half-spaces; the surfaces must not both be planes.
fn hertz(
    bodies: &[BodySpec; 2],
    geometry: &Geometry,
    spec: &PointsSpec,
    load: f64,
) -> Option<Hertz> {
    match spec {
        PointsSpec::Disk { .. } | PointsSpec::DiskHertz { .. } => {
            let e = half_space_modulus(bodies, &["point-force", "uniform-patch"])?;
            let r = combined(geometry, true)?;
            HertzSpheres::new(e, r, load).ok().map(Hertz::Spheres)
        }
        PointsSpec::Line { .. } | PointsSpec::LineHertz { .. } => {
            let e = half_space_modulus(bodies, &["plane-strain"])?;
            let r = combined(geometry, false)?;
            HertzCylinders::new(e, r, load).ok().map(Hertz::Cylinders)
        }
        PointsSpec::Rectangle { half_y, .. } => {
            let e = half_space_modulus(bodies, &["point-force", "uniform-patch"])?;
            let r = combined(geometry, false)?;
            HertzCylinders::new(e, r, load / (2.0 * half_y))
                .ok()
                .map(Hertz::Cylinders)
        }
    }
}

/// The Hertz length scale at `load`: the contact radius (disk) or the
/// half-width (line; rectangle of a roller, per unit length `2 half_y`).
fn hertz_scale(
    bodies: &[BodySpec; 2],
    geometry: &Geometry,
    spec: &PointsSpec,
    load: f64,
) -> Option<f64> {
    hertz(bodies, geometry, spec, load).map(|h| h.scale())
}

/// The closed form that applies to the scene, if one does.
fn reference(
    bodies: &[BodySpec; 2],
    geometry: &Geometry,
    spec: &PointsSpec,
    points: &PointSet,
    loading: Loading,
) -> Option<Reference> {
    let flat = match geometry {
        Geometry::Surfaces(Surface::Plane, Surface::Plane) => true,
        Geometry::Separation(eps) => eps.iter().all(|&e| e == eps[0]),
        _ => false,
    };
    match spec {
        PointsSpec::Disk { radius, .. } if flat => {
            // A rigid flat punch: one rigid body, the candidate disk its face.
            let rigid = bodies.iter().filter(|b| b.body.is_rigid()).count() == 1;
            let e = half_space_modulus(bodies, &["point-force", "uniform-patch"])?;
            rigid.then(|| FlatPunch::new(e, *radius).ok().map(Reference::FlatPunch))?
        }
        PointsSpec::Disk { .. } | PointsSpec::DiskHertz { .. } => {
            let e = half_space_modulus(bodies, &["point-force", "uniform-patch"])?;
            let r = combined(geometry, true)?;
            let load = match loading.normal {
                Normal::Load(p) => p,
                // The Hertz load of the approach: P = 4 E* a^3 / (3 R), a = sqrt(R delta).
                Normal::Approach(d) if d > 0.0 => 4.0 * e * (r * d).powf(1.5) / (3.0 * r),
                Normal::Approach(_) => return None,
            };
            HertzSpheres::new(e, r, load)
                .ok()
                .map(Reference::HertzSpheres)
        }
        PointsSpec::Line { .. } | PointsSpec::LineHertz { .. } => {
            if let Some(r) = combined(geometry, false) {
                let e = half_space_modulus(bodies, &["plane-strain"])?;
                let Normal::Load(p) = loading.normal else {
                    return None;
                };
                let datums: Vec<f64> = bodies
                    .iter()
                    .filter_map(|b| match b.body.model() {
                        elcon_influence::Model::PlaneStrainStrip {
                            reference_distance, ..
                        } => Some(*reference_distance),
                        _ => None,
                    })
                    .collect();
                let datum = datums.iter().all(|&d| d == datums[0]).then(|| datums[0]);
                return HertzCylinders::new(e, r, p)
                    .ok()
                    .map(|hertz| Reference::HertzCylinders { hertz, datum });
            }
            // A beam on a Winkler foundation, central load, no separation.
            if !flat {
                return None;
            }
            let Normal::Load(p) = loading.normal else {
                return None;
            };
            let (mut ei, mut k, mut x0) = (None, None, None);
            for b in bodies {
                match *b.body.model() {
                    elcon_influence::Model::Beam {
                        flexural_rigidity,
                        loaded_point,
                    } => {
                        ei = Some(flexural_rigidity);
                        x0 = Some(loaded_point);
                    }
                    elcon_influence::Model::Winkler { modulus } => k = Some(modulus),
                    _ => return None,
                }
            }
            // The beam is the zone: its cells end to end.
            let (lo, hi) = (points.xs()[0], points.xs()[points.len() - 1]);
            let length = points.extent().0;
            let centred = (x0? - 0.5 * (lo + hi)).abs() <= 1e-9 * length;
            centred
                .then(|| {
                    HetenyiBeam::new(ei?, k?, length, p)
                        .ok()
                        .map(Reference::Hetenyi)
                })
                .flatten()
        }
        PointsSpec::Rectangle { .. } => None,
    }
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
            let (lo, hi) = (points.xs()[0], points.xs()[points.len() - 1]);
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

fn solver(
    ctx: &Ctx<'_>,
    s: Option<&crate::schema::SolverToml>,
) -> Result<(MethodChoice, Options), SceneError> {
    let mut options = Options::default();
    let Some(s) = s else {
        return Ok((MethodChoice::Auto, options));
    };
    let method = match s.method.as_ref().map(|m| *m.get_ref()) {
        None | Some(SolverMethod::Auto) => MethodChoice::Auto,
        Some(SolverMethod::RestrictedSimplex) => MethodChoice::Given(Method::RestrictedSimplex),
        Some(SolverMethod::Lemke) => MethodChoice::Given(Method::Lemke),
        Some(SolverMethod::BlockPivoting) => MethodChoice::Given(Method::BlockPivoting),
        Some(SolverMethod::ConjugateGradient) => MethodChoice::Given(Method::ConjugateGradient),
    };
    if let Some(p) = &s.max_pivots {
        options.max_pivots = Some(ctx.count(p, "solver.max_pivots", 1)?);
    }
    if let Some(t) = &s.certificate_tolerance {
        let v = ctx.positive(t, "solver.certificate_tolerance")?;
        if v >= 1.0 {
            return Err(ctx.invalid(
                t.span(),
                "solver.certificate_tolerance",
                v,
                "a relative tolerance must be < 1",
            ));
        }
        options.tolerances.certificate = v;
    }
    if let Some(r) = &s.refinement_steps {
        options.refinement_steps = ctx.count(r, "solver.refinement_steps", 0)?;
    }
    Ok((method, options))
}

/// The scene's parts a `[design]` section is checked against.
struct DesignContext<'a> {
    loading: Loading,
    dimension: Dimension,
    bodies: &'a [BodySpec; 2],
    geometry: &'a Geometry,
    points_spec: &'a PointsSpec,
}

fn design(
    ctx: &Ctx<'_>,
    d: &Spanned<DesignToml>,
    scene: &DesignContext<'_>,
) -> Result<DesignSpec, SceneError> {
    let DesignContext {
        loading, dimension, ..
    } = *scene;
    let t = d.get_ref();
    let Normal::Load(load) = loading.normal else {
        return Err(ctx.invalid(
            d.span(),
            "design",
            "",
            "a design evens the pressure under a load: use loading.load",
        ));
    };
    let family_name = *t.family.get_ref();
    design_keys(ctx, t, family_name)?;
    let flat = match &t.flat_length {
        Some(f) => {
            let v = ctx.finite(f, "design.flat_length")?;
            if v < 0.0 {
                return Err(ctx.invalid(f.span(), "design.flat_length", v, "must be >= 0"));
            }
            v
        }
        None => 0.0,
    };
    let loads = match &t.loads {
        Some(l) => {
            if l.get_ref().is_empty() {
                return Err(ctx.invalid(l.span(), "design.loads", "[]", "give at least one load"));
            }
            l.get_ref()
                .iter()
                .enumerate()
                .map(|(i, v)| ctx.positive(v, &format!("design.loads[{i}]")))
                .collect::<Result<Vec<f64>, _>>()?
        }
        None => vec![load],
    };
    let family = design_family(ctx, t, family_name, flat, &loads, scene)?;
    let axis = design_axis(ctx, d, dimension)?;
    let relative_to = design_relative_to(ctx, d, &loads, scene)?;
    let max_constant = match &t.max_constant {
        Some(c) => Some(ctx.positive(c, "design.max_constant")?),
        None => None,
    };
    let method = design_method(ctx, t, &family)?;
    let misalignments = misalignments(ctx, t)?;
    Ok(DesignSpec {
        family,
        axis,
        loads,
        relative_to,
        max_constant,
        method,
        misalignments,
    })
}

/// The keys of `[design]` that belong to other families than `family_name`
/// are refused, naming the key and the family it belongs to.
fn design_keys(ctx: &Ctx<'_>, t: &DesignToml, family_name: FamilyName) -> Result<(), SceneError> {
    let only = |v: &Option<Spanned<f64>>, field: &str, fam: &str| {
        ctx.forbid(v, field, &format!("only for family = \"{fam}\""))
    };
    if family_name != FamilyName::Polynomial {
        ctx.forbid(
            &t.degree,
            "design.degree",
            "only for family = \"polynomial\"",
        )?;
    }
    if family_name != FamilyName::CircularCrown
        && let Some(r) = &t.radius_range
    {
        return Err(ctx.invalid(
            r.span(),
            "design.radius_range",
            "",
            "only for family = \"circular-crown\"",
        ));
    }
    if family_name != FamilyName::LogarithmicCrown {
        only(&t.design_load, "design.design_load", "logarithmic-crown")?;
        ctx.forbid(
            &t.end,
            "design.end",
            "only for family = \"logarithmic-crown\"",
        )?;
    }
    if !matches!(
        family_name,
        FamilyName::CircularCrown | FamilyName::LogarithmicCrown
    ) {
        ctx.forbid(&t.flat_length, "design.flat_length", "only for the crowns")?;
    } else {
        ctx.forbid(
            &t.max_constant,
            "design.max_constant",
            "only for the polynomial families",
        )?;
    }
    Ok(())
}

/// The family of `[design]`, its own keys checked.
fn design_family(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    family_name: FamilyName,
    flat: f64,
    loads: &[f64],
    scene: &DesignContext<'_>,
) -> Result<DesignFamily, SceneError> {
    let DesignContext {
        bodies,
        geometry,
        points_spec,
        ..
    } = *scene;
    Ok(match family_name {
        FamilyName::Quadratic => DesignFamily::Linear(Family::Quadratic),
        FamilyName::Free => DesignFamily::Linear(Family::Free),
        FamilyName::Polynomial => {
            let deg = ctx.required(
                &t.degree,
                t.family.span(),
                "design.degree",
                "for family = \"polynomial\"",
            )?;
            DesignFamily::Linear(Family::Polynomial {
                degree: ctx.count(deg, "design.degree", 0)?,
            })
        }
        FamilyName::CircularCrown => {
            let (lo, hi) = match &t.radius_range {
                Some(r) => {
                    let v = r.get_ref();
                    if v.len() != 2 {
                        return Err(ctx.invalid(
                            r.span(),
                            "design.radius_range",
                            format!("{} values", v.len()),
                            "give [smallest, largest] radius",
                        ));
                    }
                    let lo = ctx.positive(&v[0], "design.radius_range[0]")?;
                    let hi = ctx.positive(&v[1], "design.radius_range[1]")?;
                    if hi <= lo {
                        return Err(ctx.invalid(
                            v[1].span(),
                            "design.radius_range[1]",
                            hi,
                            "must exceed the smallest radius",
                        ));
                    }
                    (lo, hi)
                }
                None => {
                    return Err(ctx.invalid(
                        t.family.span(),
                        "design.radius_range",
                        "(missing)",
                        "is required for family = \"circular-crown\" (the search bracket)",
                    ));
                }
            };
            DesignFamily::CircularCrown {
                radius_range: (lo, hi),
                flat_length: flat,
            }
        }
        FamilyName::LogarithmicCrown => {
            let q = match &t.design_load {
                Some(q) => ctx.positive(q, "design.design_load")?,
                None => loads.iter().cloned().fold(0.0, f64::max),
            };
            // Its radius, modulus and length are those of the roller's
            // Hertz line contact.
            let roller = matches!(points_spec, PointsSpec::Rectangle { .. })
                && matches!(
                    hertz(bodies, geometry, points_spec, q),
                    Some(Hertz::Cylinders(_))
                );
            if !roller {
                return Err(ctx.invalid(
                    t.family.span(),
                    "design.family",
                    "\"logarithmic-crown\"",
                    "a logarithmic crown is for a roller: half-space bodies on a rectangle grid, \
                     a cylinder (axis along y) on a plane or a cylinder",
                ));
            }
            DesignFamily::LogarithmicCrown {
                design_load: q,
                flat_length: flat,
                end: log_end(t),
            }
        }
    })
}

/// `design.axis`: x on a line, y by default on a surface.
fn design_axis(
    ctx: &Ctx<'_>,
    d: &Spanned<DesignToml>,
    dimension: Dimension,
) -> Result<Axis, SceneError> {
    let t = d.get_ref();
    let axis = match &t.axis {
        Some(a) => match a.get_ref() {
            AxisName::X => Axis::X,
            AxisName::Y => Axis::Y,
        },
        None if dimension == Dimension::Line => Axis::X,
        None => Axis::Y,
    };
    if dimension == Dimension::Line && axis == Axis::Y {
        let span = t.axis.as_ref().map_or(d.span(), |a| a.span());
        return Err(ctx.invalid(span, "design.axis", "\"y\"", "a line grid lies along x"));
    }
    Ok(axis)
}

/// `design.relative_to`: "hertz" needs a Hertz contact at every load.
fn design_relative_to(
    ctx: &Ctx<'_>,
    d: &Spanned<DesignToml>,
    loads: &[f64],
    scene: &DesignContext<'_>,
) -> Result<RelativeTo, SceneError> {
    let DesignContext {
        bodies,
        geometry,
        points_spec,
        ..
    } = *scene;
    let t = d.get_ref();
    let relative_to = t
        .relative_to
        .as_ref()
        .map_or(RelativeTo::Absolute, |r| *r.get_ref());
    if relative_to == RelativeTo::Hertz
        && let Some(&load) = loads
            .iter()
            .find(|&&p| hertz(bodies, geometry, points_spec, p).is_none())
    {
        let span = t.relative_to.as_ref().map_or(d.span(), |r| r.span());
        return Err(ctx.invalid(
            span,
            "design.relative_to",
            "\"hertz\"",
            format!(
                "needs a Hertz contact at every design load ({load} has none): sphere or cylinder \
                 surfaces (not both planes) and elastic half-space bodies, spheres on a disk grid, \
                 cylinders on a line or a rectangle grid; use \"mean\" or \"absolute\""
            ),
        ));
    }
    Ok(relative_to)
}

/// `design.end` of a logarithmic crown: "johns-gohar" (the default) or
/// "lundberg".
fn log_end(t: &DesignToml) -> LogEnd {
    match t.end.as_ref().map(|e| *e.get_ref()) {
        None | Some(EndName::JohnsGohar) => LogEnd::JohnsGohar,
        Some(EndName::Lundberg) => LogEnd::Lundberg,
    }
}

/// `design.method`: for the linear families only.
fn design_method(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    family: &DesignFamily,
) -> Result<DesignMethod, SceneError> {
    let Some(m) = &t.method else {
        return Ok(DesignMethod::Auto);
    };
    if !matches!(family, DesignFamily::Linear(_)) {
        return Err(ctx.invalid(
            m.span(),
            "design.method",
            format!("\"{}\"", m.get_ref()),
            "only for the families quadratic, polynomial and free (a crown is searched or set)",
        ));
    }
    Ok(match m.get_ref() {
        DesignMethodName::Auto => DesignMethod::Auto,
        DesignMethodName::Program => DesignMethod::Program,
        DesignMethodName::Descent => DesignMethod::Descent,
    })
}

/// `design.misalignments` (rad), each finite and at most
/// [`MAX_MISALIGNMENT`] in size.
fn misalignments(ctx: &Ctx<'_>, t: &DesignToml) -> Result<Vec<f64>, SceneError> {
    let Some(list) = &t.misalignments else {
        return Ok(Vec::new());
    };
    let values = list.get_ref();
    if values.is_empty() || values.len() > MAX_MISALIGNMENTS {
        return Err(ctx.invalid(
            list.span(),
            "design.misalignments",
            format!("{} values", values.len()),
            format!("give 1 to {MAX_MISALIGNMENTS} angles (rad)"),
        ));
    }
    values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let field = format!("design.misalignments[{i}]");
            let angle = ctx.finite(v, &field)?;
            if angle.abs() > MAX_MISALIGNMENT {
                return Err(ctx.invalid(
                    v.span(),
                    &field,
                    angle,
                    format!(
                        "at most {MAX_MISALIGNMENT} rad in size (the rigid rotation is linearized)"
                    ),
                ));
            }
            Ok(angle)
        })
        .collect()
}

fn outputs(
    ctx: &Ctx<'_>,
    o: Option<&crate::schema::OutputsToml>,
    has_design: bool,
) -> Result<Outputs, SceneError> {
    let mut out = Outputs {
        plots: Vec::new(),
        pressure_csv: true,
    };
    let Some(o) = o else { return Ok(out) };
    if let Some(c) = o.pressure_csv {
        out.pressure_csv = c;
    }
    if let Some(plots) = &o.plots {
        for p in plots.get_ref() {
            let plot = *p.get_ref();
            if plot == Plot::Design && !has_design {
                return Err(ctx.invalid(
                    p.span(),
                    "outputs.plots",
                    "\"design\"",
                    "needs a [design] section",
                ));
            }
            if !out.plots.contains(&plot) {
                out.plots.push(plot);
            }
        }
    }
    Ok(out)
}
