//! The scene's grids: its candidate points laid out at its load (relative
//! to the Hertz contact, or absolute and able to hold it) and each design
//! load's; the checks of the scene as a whole against them ([`sanity`]:
//! the design against its load cases' grids, the bodies against every
//! grid, the contact resolved), and the warnings for a grid too coarse for
//! the contact.

use elcon_analysis::{Geometry, GridFamily, Loading, Normal};
use elcon_influence::{Dimension, PointSet};
use toml::Spanned;

use super::design::{DesignFamily, DesignSpec};
use super::hertz::{Hertz, Layout, Reference};
use super::points::{self, PointsSpec, build_points};
use super::{Scene, bounds};
use crate::ctx::{Ctx, Num, rounded};
use crate::error::SceneError;
use crate::sanity;
use crate::schema::{DesignToml, Grid, PointsToml, SceneFile};

/// The candidate points: absolute, or relative to the Hertz contact at the
/// scene's load (which must then exist, at a size in floating-point range).
pub(super) fn lay_out(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    layout: Layout<'_>,
    loading: Loading,
) -> Result<PointSet, SceneError> {
    let Layout {
        bodies,
        geometry,
        points_spec,
    } = layout;
    // The load that sizes Hertz-relative grids (under displacement control
    // there is none: the contact's size is not known before the solve).
    let scale = loading.load_value().and_then(|p| layout.scale(p));
    let relative = matches!(points_spec, PointsSpec::Hertz(_));
    if relative && scale.is_none() {
        let dimension = match points_spec.grid() {
            Grid::Line => Dimension::Line,
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
        let reason = format!(
            "the Hertz contact at this load has a size of {:e}, outside floating-point range: the \
             load, the moduli and the radii are not in one consistent unit system",
            scale.unwrap_or(f64::NAN)
        );
        return Err(sanity::refuse_normal(
            ctx,
            &raw.loading,
            loading.normal,
            reason,
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
pub(super) fn whole_scene(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    scene: &Scene,
) -> Result<Vec<String>, SceneError> {
    let sets = match (&scene.design, &raw.design) {
        (Some(spec), Some(raw_design)) => design_grids(ctx, raw, raw_design, spec, scene)?,
        _ => Vec::new(),
    };
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
            (Normal::Load(p), spec) if spec.grid() == Grid::Rectangle => {
                scene.hertz(p).map(|h| ("width", h.scale()))
            }
            _ => None,
        },
    };
    let disk = match scene.points_spec {
        PointsSpec::Fixed(GridFamily::Disk { spacing, radius }) => Some((spacing, radius)),
        _ => None,
    };
    if let Some(u) = sanity::unresolved_grid(&scene.points, hertz, disk) {
        return Err(unresolved_grid(ctx, &raw.points, scene, &u));
    }
    let mut warnings = sanity::coarse_grid(&scene.points, hertz, disk);
    warnings.extend(points::turned_note(&scene.points_spec, &scene.points));
    Ok(warnings)
}

/// The grids of the design's load cases, each load's laid out as the
/// scene's is at its load, and the design checked against them: its cases,
/// their loads' strain and resolution, a logarithmic crown's design load,
/// the contact resolved on each grid, `design.max_points`, the degree and
/// the constant.
fn design_grids(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    raw_design: &Spanned<DesignToml>,
    spec: &DesignSpec,
    scene: &Scene,
) -> Result<Vec<PointSet>, SceneError> {
    // The number of cases first: every load's grid is built below.
    sanity::design_cases(ctx, raw_design, spec.case_loadings().len())?;
    let mut sets = Vec::new();
    for &load in spec.loads() {
        let scale = scene.layout().scale(load);
        sets.push(build_points(&scene.points_spec, scale).map_err(|e| {
            ctx.invalid(
                raw_design.span(),
                "design.loads",
                load,
                format!("the grid of this load case: {e}"),
            )
        })?);
    }
    design_loads_small(ctx, raw_design, spec, scene, &sets)?;
    log_crown_resolved(ctx, raw_design, spec, scene)?;
    design_grids_resolve(ctx, raw, spec, scene, &sets)?;
    design_grids_fit(ctx, raw_design, spec, scene)?;
    sanity::design(ctx, raw_design, &spec.view(), &sets)?;
    Ok(sets)
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
    let cells = (t.nx.as_ref().map(|n| ("points.nx", n))).or(t.n.as_ref().map(|n| ("points.n", n)));
    let (field, span, value, needed) = match (&t.spacing, cells) {
        (None, Some((field, n))) => (
            field,
            n.span(),
            n.get_ref().to_string(),
            format!("at least {} cells", count(*n.get_ref())),
        ),
        (spacing, _) => (
            if spacing.is_some() {
                "points.spacing"
            } else {
                "points"
            },
            spacing.as_ref().map_or(raw.span(), |s| s.span()),
            spacing
                .as_ref()
                .map_or(String::new(), |s| Num(*s.get_ref()).to_string()),
            format!("a spacing of at most {}", rounded(u.spacing)),
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
            rounded(u.size),
            scene.units.length(),
            rounded(h),
            sanity::MIN_POINTS_RESOLVED,
        ),
    )
}

/// Every design load within [`sanity::MAX_STRAIN`] on its grid
/// ([`sanity::strain`]), as the scene's own load is.
fn design_loads_small(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignSpec,
    scene: &Scene,
    sets: &[PointSet],
) -> Result<(), SceneError> {
    let bodies = [scene.bodies[0].body(), scene.bodies[1].body()];
    let units = &scene.units;
    let labels = bounds::strain_labels(units);
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
            return Err(ctx.invalid(span, field, Num(load), reason));
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
    raw: &Spanned<DesignToml>,
    spec: &DesignSpec,
    scene: &Scene,
) -> Result<(), SceneError> {
    let DesignFamily::LogarithmicCrown { design_load, .. } = spec.family() else {
        return Ok(());
    };
    let bodies = [scene.bodies[0].body(), scene.bodies[1].body()];
    let largest = bounds::largest_separation(ctx, None, &scene.geometry, &scene.points)?;
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
    Err(ctx.invalid(span, "design.design_load", Num(*design_load), reason))
}

/// `design.max_points` admits every load case on the sequence's second
/// grid: a design made on the first holds only once verified on a finer
/// one, and a case beyond `max_points` ends the sequence before that.
fn design_grids_fit(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignSpec,
    scene: &Scene,
) -> Result<(), SceneError> {
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
    spec: &DesignSpec,
    scene: &Scene,
    sets: &[PointSet],
) -> Result<(), SceneError> {
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
                    Num(load),
                    cell.dx,
                    cell.dy,
                    sanity::MAX_DESIGN_CELL_ASPECT
                ),
            ));
        }
        let Some((what, size)) = scene.hertz(load).map(|h| match h {
            Hertz::Cylinders(c) => ("width", 2.0 * c.half_width()),
            other => ("diameter", 2.0 * other.scale()),
        }) else {
            continue;
        };
        let h = set.cell().dx;
        let across = (size / h).floor() + 1.0;
        if across >= sanity::MIN_POINTS_ACROSS as f64 {
            continue;
        }
        let keys = match (&scene.points_spec, scene.points_spec.grid()) {
            (_, Grid::Rectangle) => "more points.nx, or a smaller points.zone or points.half_x",
            (PointsSpec::Fixed(_), Grid::Disk) => "a smaller points.spacing",
            (PointsSpec::Fixed(_), Grid::Line) => "more points.n, or a shorter line",
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
                Num(load),
                sanity::MIN_POINTS_ACROSS
            ),
        ));
    }
    Ok(())
}

/// An absolute grid that cannot hold the Hertz contact is an error.
pub(super) fn check_zone(
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
