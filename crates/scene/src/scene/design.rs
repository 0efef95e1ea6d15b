//! `[design]`: the profile family and its own keys, the load cases and
//! misalignments, the axis, what the design is relative to and how a
//! linear family's problem is solved, checked against the scene's bodies,
//! grid and surfaces (elcon-design).

use elcon_analysis::{Loading, Method, Normal, Options};
pub use elcon_design::DesignFamily;
use elcon_design::{
    Axis, DesignError, DesignMethod, DesignRequest, Family, FamilyKind, GridSequence, LogCrown,
    LogEnd, Objective, Profile, Roller,
};
use elcon_influence::{Body, Dimension};
use toml::Spanned;

use super::hertz::{Hertz, Layout};
use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::sanity::DesignView;
use crate::schema::DesignToml;
pub use crate::schema::RelativeTo;

/// A validated `[design]` section; its fields are read through their
/// accessors, and the objective and the bodies it measures through
/// [`DesignSpec::request`].
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpec {
    family: DesignFamily,
    axis: Axis,
    loads: Vec<f64>,
    relative_to: RelativeTo,
    max_constant: Option<f64>,
    method: DesignMethod,
    /// What the design minimizes (`design.objective`).
    objective: Objective,
    /// The bodies a stress objective measures (those with a field).
    bodies: Vec<Body>,
    misalignments: Vec<f64>,
    sequence: Option<GridSequence>,
    profile_spacing: Option<f64>,
}

impl DesignSpec {
    /// The profile family.
    pub fn family(&self) -> &DesignFamily {
        &self.family
    }

    /// The axial coordinate (`design.axis`).
    pub fn axis(&self) -> Axis {
        self.axis
    }

    /// The load cases (force).
    pub fn loads(&self) -> &[f64] {
        &self.loads
    }

    /// What the worst p_max is relative to, per load case.
    pub fn relative_to(&self) -> RelativeTo {
        self.relative_to
    }

    /// The bound c_max (length), if given.
    pub fn max_constant(&self) -> Option<f64> {
        self.max_constant
    }

    /// How a linear family's problem is solved (`design.method`, "auto"
    /// not yet resolved).
    pub fn method(&self) -> DesignMethod {
        self.method
    }

    /// Misalignments (rad): every load is a case at each, a prescribed
    /// rotation about the axis across the profile (`tilt_x` when the
    /// profile runs along y, `tilt_y` along x); empty: the loads alone,
    /// their rotations free without a moment.
    pub fn misalignments(&self) -> &[f64] {
        &self.misalignments
    }

    /// The grid sequence the design is carried over until it holds on a
    /// finer grid (`elcon_design::sequence`): `design.grid_tolerance`
    /// (default 0.01) and `design.max_points` (default 20,000 a case);
    /// `None` with `design.refine = false`: the design is made on the
    /// scene's grid alone and not verified on a finer one.
    pub fn sequence(&self) -> Option<&GridSequence> {
        self.sequence.as_ref()
    }

    /// The spacing of profile.csv's samples along the axis
    /// (`design.profile_spacing`, length); `None`: the default,
    /// `elcon_design::SAMPLES_PER_STATION` samples to a station of the
    /// design's grid.
    pub fn profile_spacing(&self) -> Option<f64> {
        self.profile_spacing
    }

    /// The request elcon-design runs: the family, axis, method and bound
    /// of this section, the cases measured against `references` (one per
    /// case; none: the worst p_max itself), analysed by `reanalysis` (none:
    /// each grid's cases by their own default method) with `options`.
    pub fn request(
        &self,
        references: Option<Vec<f64>>,
        reanalysis: Option<Method>,
        options: &Options,
    ) -> DesignRequest {
        DesignRequest {
            method: self.method,
            max_constant: self.max_constant,
            reference_intensities: references,
            reanalysis,
            reanalysis_options: options.clone(),
            objective: self.objective,
            bodies: self.bodies.clone(),
            ..DesignRequest::new(self.family.clone(), self.axis)
        }
    }

    /// The section as the checks against its grids read it.
    pub(crate) fn view(&self) -> DesignView {
        DesignView {
            family: match &self.family {
                DesignFamily::Linear(f) => Some(*f),
                _ => None,
            },
            axis: self.axis,
            max_constant: self.max_constant,
            loads: self.loads.clone(),
            relative: self.relative_to != RelativeTo::Absolute,
            sequence: self.sequence.clone(),
            profile_spacing: self.profile_spacing,
        }
    }

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

/// The scene's parts a `[design]` section is checked against.
pub(super) struct DesignContext<'a> {
    /// The scene's loading (a design needs a load).
    pub(super) loading: Loading,
    /// The grid's dimension.
    pub(super) dimension: Dimension,
    /// The bodies, the surfaces and the layout the Hertz contact (a
    /// logarithmic crown's roller, `relative_to = "hertz"`) comes from;
    /// `None` for problems given whole (from Python's arrays), which have
    /// no layout.
    pub(super) layout: Option<Layout<'a>>,
    /// The roller a logarithmic crown is set for when it is given rather
    /// than derived from `layout` (Python's `roller=`).
    pub(super) roller: Option<Roller>,
}

pub(super) fn design(
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
            ctx.ensure(v, v >= 0.0, f.span(), "design.flat_length", "must be >= 0")?
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
    let max_constant = (t.max_constant.as_ref())
        .map(|c| ctx.positive(c, "design.max_constant"))
        .transpose()?;
    let method = design_method(ctx, t, &family)?;
    let (objective, bodies) = design_objective(ctx, t, (&family, method), scene)?;
    let misalignments = misalignments(ctx, t)?;
    let sequence = grid_sequence(ctx, t, dimension)?;
    let profile_spacing = (t.profile_spacing.as_ref())
        .map(|h| ctx.positive(h, "design.profile_spacing"))
        .transpose()?;
    Ok(DesignSpec {
        family,
        axis,
        loads,
        relative_to,
        max_constant,
        method,
        objective,
        bodies,
        misalignments,
        sequence,
        profile_spacing,
    })
}

/// `design.objective` (default "pressure"): a stress below the surface
/// for a linear family by the descent, over the bodies with a field
/// (elastic half-spaces); refused, naming the key and why, otherwise.
fn design_objective(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    (family, method): (&DesignFamily, DesignMethod),
    scene: &DesignContext<'_>,
) -> Result<(Objective, Vec<Body>), SceneError> {
    let Some(o) = &t.objective else {
        return Ok((Objective::Pressure, Vec::new()));
    };
    let objective = *o.get_ref();
    if objective == Objective::Pressure {
        return Ok((objective, Vec::new()));
    }
    let refuse = |why: &str| {
        ctx.invalid(
            o.span(),
            "design.objective",
            format!("\"{}\"", o.get_ref()),
            why,
        )
    };
    if !matches!(family, DesignFamily::Linear(_)) {
        return Err(refuse(
            "only for the families quadratic, polynomial and free (a crown is searched or set for the worst intensity)",
        ));
    }
    if method == DesignMethod::Program {
        return Err(refuse(
            "the design program's objective is linear in the forces: a stress below the surface needs design.method = \"descent\" or \"auto\"",
        ));
    }
    let Some(layout) = scene.layout else {
        return Err(refuse(
            "a stress below the surface needs the bodies' materials: give the problem as a scene's bodies",
        ));
    };
    let bodies: Vec<Body> = layout
        .bodies
        .iter()
        .filter(|b| b.material().is_some())
        .map(|b| *b.body())
        .collect();
    if bodies.is_empty() {
        return Err(refuse(
            "needs an elastic half-space body (a stress field below its surface): rigid bodies, beams and Winkler foundations have none",
        ));
    }
    Ok((objective, bodies))
}

/// The keys of `[design]` that belong to other families than `family_name`
/// are refused, naming the key and the family it belongs to.
fn design_keys(ctx: &Ctx<'_>, t: &DesignToml, family_name: FamilyKind) -> Result<(), SceneError> {
    let only = |family: &str| format!("only for family = \"{family}\"");
    if family_name != FamilyKind::Polynomial {
        ctx.forbid(&t.degree, "design.degree", &only("polynomial"))?;
    }
    if family_name != FamilyKind::CircularCrown {
        ctx.forbid(
            &t.radius_range,
            "design.radius_range",
            &only("circular-crown"),
        )?;
    }
    if family_name != FamilyKind::LogarithmicCrown {
        ctx.forbid(
            &t.design_load,
            "design.design_load",
            &only("logarithmic-crown"),
        )?;
        ctx.forbid(&t.end, "design.end", &only("logarithmic-crown"))?;
    }
    if family_name.is_linear() {
        ctx.forbid(&t.flat_length, "design.flat_length", "only for the crowns")?;
    } else {
        let why = "only for the polynomial families";
        ctx.forbid(&t.max_constant, "design.max_constant", why)?;
    }
    Ok(())
}

/// The family of `[design]`, its own keys checked.
fn design_family(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    family_name: FamilyKind,
    flat: f64,
    loads: &[f64],
    scene: &DesignContext<'_>,
) -> Result<DesignFamily, SceneError> {
    Ok(match family_name {
        FamilyKind::Quadratic => DesignFamily::Linear(Family::Quadratic),
        FamilyKind::Free => DesignFamily::Linear(Family::Free),
        FamilyKind::Polynomial => {
            let why = "for family = \"polynomial\"";
            let deg = ctx.required(&t.degree, t.family.span(), "design.degree", why)?;
            DesignFamily::Linear(Family::Polynomial {
                degree: ctx.count(deg, "design.degree", 0)?,
            })
        }
        FamilyKind::CircularCrown => DesignFamily::CircularCrown {
            radius_range: radius_range(ctx, t)?,
            flat_length: flat,
        },
        FamilyKind::LogarithmicCrown => log_crown(ctx, t, flat, loads, scene)?,
    })
}

/// A circular crown's `design.radius_range`, the bracket of its search:
/// `[smallest, largest]`, both > 0.
fn radius_range(ctx: &Ctx<'_>, t: &DesignToml) -> Result<(f64, f64), SceneError> {
    let why = "for family = \"circular-crown\" (the search bracket)";
    let r = ctx.required(&t.radius_range, t.family.span(), "design.radius_range", why)?;
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
    let why = "must exceed the smallest radius";
    let hi = ctx.ensure(hi, hi > lo, v[1].span(), "design.radius_range[1]", why)?;
    Ok((lo, hi))
}

/// A logarithmic crown: its design load (default the heaviest), and the
/// roller it is set for, given or derived from the roller's Hertz line
/// contact (its radius and modulus; its length twice `points.half_y`).
fn log_crown(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    flat: f64,
    loads: &[f64],
    scene: &DesignContext<'_>,
) -> Result<DesignFamily, SceneError> {
    let q = match &t.design_load {
        Some(q) => ctx.positive(q, "design.design_load")?,
        None => loads.iter().cloned().fold(0.0, f64::max),
    };
    let derived =
        scene.layout.and_then(
            |layout| match (layout.hertz(q), layout.points_spec.half_y()) {
                (Some(Hertz::Cylinders(h)), Some(half_y)) => Some(Roller {
                    combined_modulus: h.combined_modulus,
                    radius: h.radius,
                    length: 2.0 * half_y,
                }),
                _ => None,
            },
        );
    let Some(roller) = scene.roller.or(derived) else {
        return Err(ctx.invalid(
            t.family.span(),
            "design.family",
            "\"logarithmic-crown\"",
            "a logarithmic crown is for a roller: half-space bodies on a rectangle grid, a \
             cylinder (axis along y) on a plane or a cylinder",
        ));
    };
    let end = log_end(t);
    log_crown_valid(ctx, t, q, flat, end, (&roller, scene.roller.is_some()))?;
    Ok(DesignFamily::LogarithmicCrown {
        design_load: q,
        flat_length: flat,
        end,
        roller,
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
        Some(a) => *a.get_ref(),
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
    let t = d.get_ref();
    let relative_to = t
        .relative_to
        .as_ref()
        .map_or(RelativeTo::Absolute, |r| *r.get_ref());
    if relative_to == RelativeTo::Hertz
        && let Some(&load) = loads
            .iter()
            .find(|&&p| scene.layout.and_then(|l| l.hertz(p)).is_none())
    {
        let span = t.relative_to.as_ref().map_or(d.span(), |r| r.span());
        return Err(ctx.invalid(
            span,
            "design.relative_to",
            "\"hertz\"",
            format!(
                "needs a Hertz contact at every design load ({} has none): sphere or cylinder \
                 surfaces (not both planes) and elastic half-space bodies, spheres on a disk grid, \
                 cylinders on a line or a rectangle grid; use \"mean\" or \"absolute\"",
                Num(load)
            ),
        ));
    }
    Ok(relative_to)
}

/// `design.end` of a logarithmic crown: "johns-gohar" (the default) or
/// "lundberg".
/// The logarithmic crown the design stage will set, checked as elcon-design
/// checks it (`Profile::validate`: a flat part shorter than the roller, a
/// Hertz half-width that leaves Johns and Gohar's profile defined), its
/// parameters named by the scene's keys; the roller's length by
/// `roller.length` when the roller was `given` with the design.
fn log_crown_valid(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    design_load: f64,
    flat_length: f64,
    end: LogEnd,
    (roller, given): (&Roller, bool),
) -> Result<(), SceneError> {
    let crown = Profile::LogarithmicCrown(LogCrown {
        design_load,
        length: roller.length,
        combined_modulus: roller.combined_modulus,
        radius: roller.radius,
        flat_length,
        end,
    });
    let Err(e) = crown.validate() else {
        return Ok(());
    };
    let (field, value, span) = match &e {
        DesignError::InvalidInput { field, .. } if field.ends_with("flat_length") => (
            "design.flat_length",
            flat_length,
            t.flat_length.as_ref().map(|f| f.span()),
        ),
        DesignError::InvalidInput { field, .. } if field.ends_with("design_load") => (
            "design.design_load",
            design_load,
            t.design_load.as_ref().map(|q| q.span()),
        ),
        _ => ("design.family", design_load, None),
    };
    let reason = match e {
        DesignError::InvalidInput { reason, .. } => reason.to_string(),
        other => other.to_string(),
    };
    Err(ctx.invalid(
        span.unwrap_or(t.family.span()),
        field,
        value,
        format!(
            "{reason} (the logarithmic crown of a roller {} long, {})",
            Num(roller.length),
            // The roller given with the design (Python's `roller=`), or
            // derived from the scene's grid.
            if given {
                "roller.length"
            } else {
                "twice points.half_y"
            }
        ),
    ))
}

fn log_end(t: &DesignToml) -> LogEnd {
    t.end.as_ref().map_or(LogEnd::JohnsGohar, |e| *e.get_ref())
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
    Ok(*m.get_ref())
}

/// `design.grid_tolerance` (in (0, 0.5], default 0.01, and not finer than
/// the grids within `design.max_points` resolve: [`finest_grid_tolerance`])
/// and `design.max_points` (at least 4, default 20,000); none with
/// `design.refine = false` (which takes neither key).
fn grid_sequence(
    ctx: &Ctx<'_>,
    t: &DesignToml,
    dimension: Dimension,
) -> Result<Option<GridSequence>, SceneError> {
    if t.refine.as_ref().is_some_and(|r| !*r.get_ref()) {
        let why = "goes with design.refine = true: the grids a design is carried over";
        ctx.forbid(&t.grid_tolerance, "design.grid_tolerance", why)?;
        ctx.forbid(&t.max_points, "design.max_points", why)?;
        return Ok(None);
    }
    let mut sequence = GridSequence::default();
    if let Some(v) = &t.max_points {
        sequence.max_points = ctx.count(v, "design.max_points", 4)?;
    }
    if let Some(v) = &t.grid_tolerance {
        let tolerance = ctx.positive(v, "design.grid_tolerance")?;
        let why = format!("at most {MAX_GRID_TOLERANCE} (a relative agreement between two grids)");
        let within = tolerance <= MAX_GRID_TOLERANCE;
        sequence.tolerance =
            ctx.ensure(tolerance, within, v.span(), "design.grid_tolerance", why)?;
        let line = dimension == Dimension::Line;
        let finest = finest_grid_tolerance(sequence.max_points, line);
        let remedy = match line {
            true => "the grids of the sequence, to 16 times the scene's cells, resolve no finer",
            false => "or raise design.max_points",
        };
        let why = format!(
            "finer than the design's grids resolve within design.max_points = {} a case: a \
             design's worst objective still changes by about {} between successive grids of \
             that size (docs/design.md), so the design would run through every grid and fail; \
             give at least {} ({remedy})",
            sequence.max_points,
            Num(finest),
            Num(finest)
        );
        ctx.ensure(
            tolerance,
            tolerance >= finest,
            v.span(),
            "design.grid_tolerance",
            why,
        )?;
    }
    Ok(Some(sequence))
}

/// The finest `design.grid_tolerance` the grids of the sequence resolve
/// within `max_points` a case: [`FINEST_GRID_TOLERANCE`] at the default
/// 20,000 points. On a surface, where `max_points` ends the sequence,
/// more points allow a finer one, falling with the spacing (the changes
/// between grids fall about as h, h as 1 / sqrt(N)); on a line the
/// sequence's last grid (16 times the scene's cells) ends it first.
pub fn finest_grid_tolerance(max_points: usize, line: bool) -> f64 {
    let ratio = GridSequence::default().max_points as f64 / max_points.max(1) as f64;
    match line {
        true => FINEST_GRID_TOLERANCE,
        false => FINEST_GRID_TOLERANCE * ratio.sqrt(),
    }
}

/// The finest `design.grid_tolerance` at the default 20,000 points a case,
/// measured: the crowned roller's worst objective changes by 4e-4 between
/// the last two grids within 20,000 points (6 times its 9 x 40 cells) and
/// Example 2's beam's by 1.3e-4 between its last two (16 times its 80
/// cells); a tolerance of 1e-4 fails on both after the whole sequence (3
/// minutes on the roller), 1e-3 holds on both.
pub const FINEST_GRID_TOLERANCE: f64 = 1e-3;

/// The loosest `design.grid_tolerance`: half the objective.
pub const MAX_GRID_TOLERANCE: f64 = 0.5;

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
            let why = format!(
                "at most {MAX_MISALIGNMENT} rad in size (the rigid rotation is linearized)"
            );
            ctx.ensure(
                angle,
                angle.abs() <= MAX_MISALIGNMENT,
                v.span(),
                &field,
                why,
            )
        })
        .collect()
}
