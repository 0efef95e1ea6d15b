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
use crate::ctx::{Ctx, Num, at_most, rounded};
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
    misalignments_on_the_roller(ctx, raw_design, scene)?;
    beam_reach(ctx, raw, scene)?;
    crown_keeps_the_end_clear(ctx, raw_design, spec, scene)?;
    free_profile_on_a_line_contact(ctx, raw_design, spec, scene)?;
    tables_without_kinks(ctx, raw, spec)?;
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

/// A roller's misalignments against its lightest design load
/// ([`Scene::end_lift`]): beyond [`sanity::MAX_END_LIFT`] times the
/// approach of the lightest load's Hertz line contact the tilted roller
/// bears on a short part of its length at one end (about
/// `sqrt(approach / lift)` of it), and a crown deep enough to relieve
/// that end at the heaviest load leaves the lightest load's contact too
/// short for the design's grids to agree on.
fn misalignments_on_the_roller(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    scene: &Scene,
) -> Result<(), SceneError> {
    let (Some(lift), Some(raw_list)) = (scene.end_lift(), &raw.get_ref().misalignments) else {
        return Ok(());
    };
    if !(lift.ratio() > sanity::MAX_END_LIFT) {
        return Ok(());
    }
    let span = raw_list
        .get_ref()
        .iter()
        .find(|m| *m.get_ref() == lift.misalignment)
        .map_or(raw_list.span(), |m| m.span());
    let length = scene.units.length();
    Err(ctx.invalid(
        span,
        "design.misalignments",
        Num(lift.misalignment),
        format!(
            "lifts the roller's end by {} {length} (the misalignment times half the roller's \
             length, {} {length}), {:.0} times the contact's approach at the lightest design \
             load ({} {length} at {} {}, the Hertz line contact's, measured a roller's radius \
             away): beyond {} times it the tilted roller bears only near one end, a crown that \
             relieves that end leaves the lightest load's contact too short for the design's \
             grids to agree, and the design runs on without converging; give misalignments of \
             at most {} rad, or a heavier lightest load (design.loads)",
            rounded(lift.lift()),
            rounded(lift.half_length),
            lift.ratio(),
            rounded(lift.approach),
            Num(lift.load),
            scene.units.force(),
            sanity::MAX_END_LIFT,
            at_most(sanity::MAX_END_LIFT * lift.approach / lift.half_length),
        ),
    ))
}

/// A circular crown searched up to radii that leave the heaviest load's
/// contact on the roller's end is refused, naming `design.radius_range`:
/// the end's pressure there is singular and grows with every finer grid,
/// and the search, which compares a coarse grid's cell averages, may
/// choose such a radius (the crowned roller searched over 50 to 5000 mm
/// did not hold on five grids, its worst p_max / p0 1.35 to 1.62; over 50
/// to 500 mm it holds on 18 x 80 cells). The largest radius must drop
/// the end, `R - sqrt(R^2 - t^2)` at `t` = half the length less half the
/// flat, by at least the heaviest load's approach (as
/// [`Scene::end_lift`] measures it).
fn crown_keeps_the_end_clear(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignSpec,
    scene: &Scene,
) -> Result<(), SceneError> {
    let DesignFamily::CircularCrown {
        radius_range: (_, largest),
        flat_length,
    } = *spec.family()
    else {
        return Ok(());
    };
    let Some(load) = spec.loads().iter().copied().reduce(f64::max) else {
        return Ok(());
    };
    let Some((hertz, half_length)) = scene.roller_contact(load) else {
        return Ok(());
    };
    let t = half_length - 0.5 * flat_length;
    let Ok(approach) = hertz.approach(hertz.radius) else {
        return Ok(());
    };
    if !(t > 0.0 && largest > t) {
        return Ok(());
    }
    let drop = largest - (largest * largest - t * t).sqrt();
    if drop >= approach {
        return Ok(());
    }
    let span = raw.get_ref().radius_range.as_ref().map_or(raw.span(), |r| {
        r.get_ref().last().map_or(r.span(), |v| v.span())
    });
    let length = scene.units.length();
    Err(ctx.invalid(
        span,
        "design.radius_range",
        Num(largest),
        format!(
            "a crown of this radius drops the roller's end by {} {length}, less than the \
             contact's approach at the heaviest design load ({} {length} at {} {}): it leaves \
             the contact on the roller's end, where the pressure is singular and grows with \
             every finer grid, and the search, comparing a coarse grid's cell averages, may \
             choose it, so the design never holds; give a largest radius of at most {} {length}",
            rounded(drop),
            rounded(approach),
            Num(load),
            scene.units.force(),
            at_most((t * t + approach * approach) / (2.0 * approach)),
        ),
    ))
}

/// A free profile on a point contact (a Hertz contact of spheres or an
/// ellipse) is refused, naming `design.family`: its contact ends inside
/// the grid along the axis, so the drops at the stations beyond it bear
/// no load in any case and the design leaves them free, and the spline
/// through them swings into the contact on a finer grid. Measured: the
/// ball bearing's worst p_max went 2093, 81,979 and 137,228 MPa over three
/// grids; Example 1's spheres ended at a step program with no feasible
/// basis. A polynomial (design.degree, up to 12) designs both.
fn free_profile_on_a_line_contact(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignSpec,
    scene: &Scene,
) -> Result<(), SceneError> {
    if *spec.family() != DesignFamily::Linear(elcon_design::Family::Free) {
        return Ok(());
    }
    let point = spec
        .loads()
        .iter()
        .find_map(|&load| match scene.hertz(load) {
            Some(Hertz::Spheres(_)) => Some("spheres"),
            Some(Hertz::Ellipse(_)) => Some("an elliptical contact"),
            _ => None,
        });
    let Some(what) = point else {
        return Ok(());
    };
    Err(ctx.invalid(
        raw.get_ref().family.span(),
        "design.family",
        "\"free\"",
        format!(
            "a free profile (a drop per axial station) needs a contact along the whole axis, a \
             roller's or a beam's; this is a point contact ({what}), which ends inside the grid \
             along the axis: the drops at the stations beyond it bear no load, the design leaves \
             them free, and the profile through them swings into the contact on a finer grid, so \
             the design never holds. Use family = \"polynomial\" (with design.degree, up to {})",
            sanity::MAX_DEGREE
        ),
    ))
}

/// A design carried over finer grids needs a profile or height map
/// interpolated without kinks: linearly between its rows (the default)
/// its slope jumps at every row, and each kink puts a logarithmic peak of
/// pressure under it that every finer grid resolves higher, so no grid
/// verifies the design (examples/scenes/measured-crown.toml with a free
/// profile designed for 1 and 5 kN ran through four grids and on past
/// 300 s; with `interpolation = "cubic"` it holds).
fn tables_without_kinks(
    ctx: &Ctx<'_>,
    raw: &SceneFile,
    spec: &DesignSpec,
) -> Result<(), SceneError> {
    let Some(geometry) = raw.geometry.as_ref().map(Spanned::get_ref) else {
        return Ok(());
    };
    if spec.sequence().is_none() {
        return Ok(());
    }
    let tables = [
        (
            "geometry.profile.interpolation",
            geometry
                .profile
                .as_ref()
                .map(|p| (p.span(), &p.get_ref().interpolation)),
            "row",
        ),
        (
            "geometry.height_map.interpolation",
            geometry
                .height_map
                .as_ref()
                .map(|m| (m.span(), &m.get_ref().interpolation)),
            "node",
        ),
    ];
    for (field, table, node) in tables {
        let Some((span, interpolation)) = table else {
            continue;
        };
        let linear = interpolation
            .as_ref()
            .is_none_or(|i| *i.get_ref() == elcon_analysis::Interpolation::Linear);
        if !linear {
            continue;
        }
        let span = interpolation.as_ref().map_or(span, |i| i.span());
        return Err(ctx.invalid(
            span,
            field,
            "\"linear\"",
            format!(
                "a design compares its peak pressure over finer and finer grids, and a table \
                 interpolated linearly kinks at every {node}: each kink puts a peak of pressure \
                 under it that every finer grid resolves higher, so no grid verifies the design. \
                 Give interpolation = \"cubic\" (the natural cubic spline through the table), \
                 or design on the scene's grid alone (design.refine = false)"
            ),
        ));
    }
    Ok(())
}

/// A designed beam on a Winkler foundation no longer than
/// [`sanity::MAX_BEAM_REACH`] of its characteristic lengths
/// `(4 E I / k)^(1/4)`, named by the foundation's modulus.
fn beam_reach(ctx: &Ctx<'_>, raw: &SceneFile, scene: &Scene) -> Result<(), SceneError> {
    let bodies = [scene.bodies[0].body(), scene.bodies[1].body()];
    let beam = bodies.iter().find_map(|b| match *b.model() {
        elcon_influence::Model::Beam {
            flexural_rigidity, ..
        } => Some(flexural_rigidity),
        _ => None,
    });
    let foundation = (0..2).find_map(|i| match *bodies[i].model() {
        elcon_influence::Model::Winkler { modulus } => Some((i, modulus)),
        _ => None,
    });
    let (Some(ei), Some((i, k))) = (beam, foundation) else {
        return Ok(());
    };
    let points = &scene.points;
    let h = points.cell().dx;
    let length = points.x(points.len() - 1) - points.x(0) + h;
    let reach = (4.0 * ei / k).powf(0.25);
    if !(length / reach > sanity::MAX_BEAM_REACH) {
        return Ok(());
    }
    let raw_body = if i == 0 { &raw.body1 } else { &raw.body2 };
    let span = raw_body
        .get_ref()
        .modulus
        .as_ref()
        .map_or(raw_body.span(), |m| m.span());
    let (units, length_unit) = (&scene.units, scene.units.length());
    Err(ctx.invalid(
        span,
        format!("body{}.modulus", i + 1),
        Num(k),
        format!(
            "the beam (E I = {} {} {length_unit}^2) bends on this foundation over a \
             characteristic length (4 E I / k)^(1/4) = {} {length_unit}, and the beam is {:.0} \
             of them long ({} {length_unit}), more than {}: a load bends it over a few of them \
             beside it and the rest carries nothing, so a design over the whole beam cannot \
             spread the load (its peak grows with every finer grid). Give a softer foundation, \
             a stiffer beam, or a beam at most {} {length_unit} long (points.start, points.end)",
            rounded(ei),
            units.force(),
            rounded(reach),
            length / reach,
            rounded(length),
            sanity::MAX_BEAM_REACH,
            at_most(sanity::MAX_BEAM_REACH * reach),
        ),
    ))
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
                    "the design load {} has cells {aspect:.0} times longer than wide ({:.4e} by \
                     {:.4e}), more than {}: the influence coefficients of such cells resolve \
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
