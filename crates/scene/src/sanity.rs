//! Checks of a scene as a whole, beyond each value's own range: what the
//! solve or the design would otherwise refuse (or answer meaninglessly)
//! only once it runs, so that `elcon check` refuses the same scenes as
//! `elcon run` before the solve; the bounds on the knobs that cost time or
//! memory; and the warnings for a grid too coarse for the contact.
//!
//! Geometry: the initial separation of two paraboloids is
//! `eps(x, y) = (k_x x^2 + k_y y^2) / 2` with the summed curvatures
//! `k_x = 1/R1 + 1/R2` (spheres and cylinders, axis along y) and
//! `k_y = 1/R1 + 1/R2` (spheres only); a negative k means the bodies
//! interpenetrate more the farther from the first point of contact, which
//! no contact solution describes. Two curvatures of opposite signs whose
//! sum is rounding (`|k_1 + k_2| < CANCELLING_CURVATURE max(|k_1|, |k_2|)`)
//! describe no gap at all: the relative curvature is the difference of two
//! nearly equal numbers.
//!
//! Small strain: every influence model is linear elasticity under small
//! strain (or small deflection, for a beam), so a load whose mean pressure
//! over the candidate zone `p = P / A` is not small against the combined
//! modulus (`p / E* <= MAX_STRAIN`), that compresses a Winkler foundation by
//! more than [`MAX_STRAIN`] of the zone's size (`p / k <= MAX_STRAIN L`),
//! or bends a beam by a slope beyond [`MAX_STRAIN`] rad, and an approach
//! beyond [`MAX_STRAIN`] of the zone's size, are refused: the answer would
//! be a number of a model that does not hold there (and at extreme
//! magnitudes the solve overflows). The zone's size there is its smaller
//! extent: an approach of half a roller's length strains it however wide
//! the zone is across the roller.
//!
//! Resolvability: a load (or an approach) whose largest elastic
//! deformation `w` (the whole load on one cell: its pressure against E*
//! times the cell's side, a Winkler foundation's compression under it, a
//! free beam's tip deflection `P l^3 / (3 E I)`; an approach is its own)
//! is below
//! [`MIN_RESOLVED_DEFORMATION`] of the largest initial separation over the
//! candidate zone, or below [`MIN_DEFORMATION`], is refused: the contact it
//! makes is lost in the rounding of the separations (or, below
//! [`MIN_DEFORMATION`], the squares of its residuals among the subnormal
//! numbers). A deformation or a mean force per point above
//! [`MAX_DEFORMATION`] is refused too: the squares the solve sums
//! overflow.

use elcon_analysis::{Curvature, Geometry, Loading, Normal};
use elcon_design::{Axis, Family, GridSequence, axial_stations};
use elcon_influence::{Body, Dimension, Model, PointSet, combined_modulus_of};
use toml::Spanned;

use crate::ctx::{Ctx, Num, at_most, rounded};
use crate::error::SceneError;
use crate::schema::{BodyToml, DesignToml, GeometryToml, LoadingToml, SolverToml};
use crate::zone::{OpenEdge, Zone};

/// The most iterative-refinement steps (each an N x N product;
/// refinement settles in one to three).
pub const MAX_REFINEMENT_STEPS: usize = 20;

/// The most design cases, each load at each misalignment (every descent
/// iteration analyses each case; the memory estimate refuses what does not
/// fit, this bounds the time).
pub const MAX_DESIGN_CASES: usize = 1000;

/// The highest polynomial degree of a design (monomials of the normalized
/// axial coordinate: past about 12 the basis is too ill-conditioned for
/// the design program's pivots).
pub const MAX_DEGREE: usize = 12;

/// The largest rotation of a body (rad), prescribed (`loading.tilt_x`,
/// `tilt_y`) or solved under a moment: the rigid rotation is linearized
/// (`theta x`), which holds to 0.5 % of the angle up to 0.1 rad, as for a
/// design's misalignments (elcon-analysis's, which refuses the solved
/// rotation beyond it).
pub use elcon_analysis::rotation::MAX_ROTATION;

/// A grid with fewer points than this across the Hertz contact (or the
/// candidate disk) gets a warning.
pub const MIN_POINTS_ACROSS: usize = 5;

/// A grid with fewer points than this across the contact's expected size
/// (the Hertz contact's diameter or width, a candidate disk's diameter) is
/// refused: three points (a centre and one on each side, as
/// `points.across` asks at least) are the fewest that tell the pressure's
/// profile from its mean; with one point the answer is the load over one
/// cell (a flat punch of radius 0.01 on one cell of spacing 1 carried
/// 44.6 times its closed form's load).
pub const MIN_POINTS_RESOLVED: usize = 3;

/// The most a design's cells may be longer than wide (on a surface grid):
/// a roller 131 km long on 40 cells, each 4.5e6 times longer than wide,
/// designs on its first grids and then fails the certificate of an
/// analysis on a finer one; the crowned roller of docs/design.md has
/// cells about 10 times longer than wide.
pub const MAX_DESIGN_CELL_ASPECT: f64 = 1e4;

/// `design.max_constant` is at most this many times the candidate zone's
/// size: a uniform drop a million times the zone is no profile of these
/// bodies, and values near the floating-point range overflow the design
/// program's sums.
pub const MAX_CONSTANT_OVER_ZONE: f64 = 1e6;

/// The largest strain a scene may ask of the linear models: the mean
/// pressure over the candidate zone against the combined modulus E*, a
/// Winkler foundation's compression and an approach or a separation
/// against the zone's size, a beam's bending slope (rad). Linear elasticity
/// and the rigid rotation's linearization (`MAX_ROTATION`, also 0.1) hold
/// to a few percent up to it; every example scene is well within it.
pub const MAX_STRAIN: f64 = 0.1;

/// Two curvatures of opposite signs cancel when their sum is below this
/// fraction of the larger one: a thousand times the rounding of one f64
/// (`f64::EPSILON`), so that the relative curvature keeps at least a few
/// significant digits. (A radius -1.0000000000001 against 1 leaves 1e-13.)
pub const CANCELLING_CURVATURE: f64 = 1e3 * f64::EPSILON;

/// The smallest elastic deformation a solve resolves, as a fraction of the
/// largest initial separation over the candidate zone. Each separation is
/// exact to about `f64::EPSILON` (2.2e-16) of the largest, and the gaps
/// near the contact are differences of separations and deformations: a
/// deformation of 1e-8 of the largest separation keeps about seven
/// significant digits above that rounding (4.5e7 times it), the most a
/// certificate relative to the data's scale can tell from noise. Below it
/// the contact is rounding: the conjugate gradient wanders, a pivoting
/// method's certificate fails, or the answer is the separations' noise.
pub const MIN_RESOLVED_DEFORMATION: f64 = 1e-8;

/// The smallest elastic deformation (length), and the smallest mean force
/// a candidate point carries (force), a solve is given:
/// `sqrt(f64::MIN_POSITIVE) / f64::EPSILON` (6.718e-139) rounded up. The
/// solvers' certificates and the conjugate gradient measure residuals of
/// about the tolerance (`f64::EPSILON` times the data's scale) by their
/// squared norms: below this bound the square of (deformation x
/// tolerance) falls below the smallest normal number, among the subnormal
/// numbers (fewer than 16 digits, then zero), and the conjugate gradient
/// stalls or breaks down (Example 1 at 1e-250 lbf, its grid sized by its
/// own Hertz contact, or at E = 1e153 psi under 100 lbf, ran out of
/// iterations or broke down).
pub const MIN_DEFORMATION: f64 = 6.72e-139;

/// The largest elastic deformation (length), and the largest mean force a
/// candidate point carries (force), a solve is given: `1 /
/// MIN_DEFORMATION`, about 1.5e138, so that their squares and the sums of
/// their squares over a grid (the solvers' norms) stay far below the
/// largest f64 (1.8e308) rather than overflowing to infinity.
pub const MAX_DEFORMATION: f64 = 1.0 / MIN_DEFORMATION;

/// The length the strain bounds measure the zone by: its smaller extent on
/// a surface (an approach or a separation large against the zone's width
/// strains it however long it is), a line's length.
pub(crate) fn strain_length(points: &PointSet) -> f64 {
    let (a, b) = points.extent();
    if points.dimension() == Dimension::Line {
        a
    } else {
        a.min(b)
    }
}

/// The size of the candidate zone: its larger extent (a line's length).
pub(crate) fn zone_size(points: &PointSet) -> f64 {
    let (a, b) = points.extent();
    if points.dimension() == Dimension::Line {
        a
    } else {
        a.max(b)
    }
}

/// The largest `solver.max_pivots` for N points: `100 N + 10,000`, well
/// above every method's default (about 40 N for the tableau methods); a
/// pivoting path that has not ended by then is cycling.
pub fn max_pivots_bound(points: usize) -> usize {
    points.saturating_mul(100).saturating_add(10_000)
}

/// A concave surface must have the larger radius: the summed curvature
/// along x and along y must not be negative, whether or not tabulated
/// departures (a height map, a profile) are added to the surfaces.
pub(crate) fn curvatures(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
) -> Result<(), SceneError> {
    let Some((a, b)) = geometry.surfaces() else {
        return Ok(());
    };
    let (ka, kb) = (a.curvatures(), b.curvatures());
    for (axis, k1, k2) in [("x", ka.0, kb.0), ("y", ka.1, kb.1)] {
        let sum = k1 + k2;
        if k1 * k2 < 0.0 && sum.abs() < CANCELLING_CURVATURE * k1.abs().max(k2.abs()) {
            return Err(cancelling(ctx, raw, axis, (k1, k2), sum));
        }
        if sum >= 0.0 {
            continue;
        }
        // Blame the concave surface (the first, if both are).
        let (field, surface, other) = if k1 < 0.0 {
            ("geometry.surface1", a, b)
        } else {
            ("geometry.surface2", b, a)
        };
        let radius = surface.radius().unwrap_or(0.0);
        let raw_surface = raw.and_then(|g| {
            if field.ends_with('1') {
                g.get_ref().surface1.as_ref()
            } else {
                g.get_ref().surface2.as_ref()
            }
        });
        let span = raw_surface
            .and_then(|s| s.get_ref().radius.as_ref().map(|r| r.span()))
            .or_else(|| raw.map(|g| g.span()))
            .unwrap_or(0..0);
        let against = match other.radius() {
            None => "a plane".to_string(),
            Some(radius) if radius < 0.0 => {
                format!("another concave surface (radius {})", Num(radius))
            }
            Some(radius) => format!("the convex radius {}", Num(radius)),
        };
        return Err(ctx.invalid(
            span,
            format!("{field}.radius"),
            Num(radius),
            format!(
                "a concave surface must have the larger radius: against {against} the summed \
                 curvature along {axis}, 1/R1 + 1/R2 = {sum:.4e}, is negative, so the bodies would \
                 interpenetrate more and more away from the first point of contact; give the \
                 concave surface a radius larger in magnitude than the convex one's"
            ),
        ));
    }
    quadric_curvatures(ctx, raw, geometry)
}

/// Curvatures along `axis` of opposite signs (`k`) whose sum is rounding:
/// the refusal, naming both surfaces' radii along that axis.
fn cancelling(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    axis: &str,
    k: (f64, f64),
    sum: f64,
) -> SceneError {
    // Blame the concave surface: the one of negative curvature.
    let (field, first) = if k.0 < 0.0 {
        ("geometry.surface1", true)
    } else {
        ("geometry.surface2", false)
    };
    let surface = raw.and_then(|g| {
        let g = g.get_ref();
        if first {
            g.surface1.as_ref()
        } else {
            g.surface2.as_ref()
        }
    });
    // The value as the file writes it (at an angle, the radius along the
    // axis is not the one written).
    let (key, span, written) = surface.map_or_else(
        || ("radius", raw.map_or(0..0, |g| g.span()), None),
        |s| {
            let t = s.get_ref();
            let (key, value) = match (&t.radius, axis) {
                (Some(r), _) => ("radius", Some(r)),
                (None, "x") => ("radius_x", t.radius_x.as_ref()),
                (None, _) => ("radius_y", t.radius_y.as_ref()),
            };
            (
                key,
                value.map_or(s.span(), |r| r.span()),
                value.map(|r| *r.get_ref()),
            )
        },
    );
    ctx.invalid(
        span,
        format!("{field}.{key}"),
        Num(written.unwrap_or(1.0 / if first { k.0 } else { k.1 })),
        format!(
            "cancels the other surface: geometry.surface1's radius along {axis} is {} and \
             geometry.surface2's {}, so the relative curvature 1/R1 + 1/R2 = {sum:.3e} is below \
             {CANCELLING_CURVATURE:.1e} of the larger curvature, within rounding of zero: the gap \
             along {axis} is no number the solve can use (a conforming contact, which the \
             half-space models do not describe). Give radii whose curvatures differ by more than that",
            Num(1.0 / k.0),
            Num(1.0 / k.1),
        ),
    )
}

/// Quadrics at an angle: the gap's principal curvatures (its form's
/// eigenvalues, `elcon_analysis::Curvature::principal_values`) must not be
/// negative, as the sums along x and y must not be.
fn quadric_curvatures(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
) -> Result<(), SceneError> {
    let (Some(form), Some((a, b))) = (geometry.curvature(), geometry.surfaces()) else {
        return Ok(());
    };
    let p = form.principal_values();
    // Along the sum's smaller principal direction, each surface's own
    // curvature: of opposite signs and summing to rounding, they cancel
    // (as along x or y, `curvatures`), whatever the angle.
    let (c, s) = (p.angle.cos(), p.angle.sin());
    let along = |k: Curvature| k.xx * c * c + 2.0 * k.xy * c * s + k.yy * s * s;
    let (k1, k2) = (along(Curvature::of(&a)), along(Curvature::of(&b)));
    if k1 * k2 < 0.0 && p.smaller.abs() < CANCELLING_CURVATURE * k1.abs().max(k2.abs()) {
        let (field, raw_surface) = if k1 < 0.0 {
            (
                "geometry.surface1",
                raw.and_then(|g| g.get_ref().surface1.as_ref()),
            )
        } else {
            (
                "geometry.surface2",
                raw.and_then(|g| g.get_ref().surface2.as_ref()),
            )
        };
        let (key, span) = raw_surface.map_or(("", raw.map_or(0..0, |g| g.span())), |t| {
            let r = t.get_ref();
            match (&r.angle, &r.radius) {
                (Some(v), _) => (".angle", v.span()),
                (None, Some(v)) => (".radius", v.span()),
                _ => ("", t.span()),
            }
        });
        return Err(ctx.invalid(
            span,
            format!("{field}{key}"),
            "",
            format!(
                "cancels the other surface along the gap's principal direction at {:.2} degrees \
                 from x: there geometry.surface1's curvature is {k1:.4e} and geometry.surface2's \
                 {k2:.4e}, so the relative curvature, {:.3e}, is below \
                 {CANCELLING_CURVATURE:.1e} of the larger, within rounding of zero: the gap along \
                 that direction is no number the solve can use (a conforming contact, which the \
                 half-space models do not describe). Give radii or angles whose curvatures there \
                 differ by more than that",
                p.angle.to_degrees(),
                p.smaller
            ),
        ));
    }
    let size = form.xx.abs() + form.yy.abs() + 2.0 * form.xy.abs();
    if p.smaller >= -CANCELLING_CURVATURE * size {
        return Ok(());
    }
    Err(ctx.invalid(
        raw.map_or(0..0, |g| g.span()),
        "geometry",
        Num(p.smaller),
        format!(
            "the gap's smaller principal curvature, {:.4e} along {:.2} degrees from x, is \
             negative: the bodies would interpenetrate more and more away from the first point \
             of contact; a concave direction needs a radius larger in magnitude than the convex \
             one it meets",
            p.smaller,
            p.angle.to_degrees()
        ),
    ))
}

/// The plane-strain datum must lie beyond every grid the scene solves on
/// (its own and each design load's), and a beam's loaded point on the beam.
pub(crate) fn bodies_on_grid(
    ctx: &Ctx<'_>,
    raw: [&Spanned<BodyToml>; 2],
    bodies: [&Body; 2],
    own: &PointSet,
    design_sets: &[PointSet],
) -> Result<(), SceneError> {
    for (section, (raw, body)) in ["body1", "body2"].iter().zip(raw.iter().zip(bodies)) {
        let t = raw.get_ref();
        match *body.model() {
            Model::PlaneStrainStrip {
                reference_distance, ..
            } => {
                let widest = std::iter::once(own)
                    .chain(design_sets)
                    .map(|p| p.extent().0)
                    .fold(0.0f64, f64::max);
                if reference_distance < widest {
                    let span = t
                        .reference_distance
                        .as_ref()
                        .map_or(t.model.span(), |v| v.span());
                    return Err(ctx.invalid(
                        span,
                        format!("{section}.reference_distance"),
                        Num(reference_distance),
                        format!(
                            "must be at least the extent of the grid, {widest:.4e} (the strips' \
                             displacements are measured from a datum beyond the candidate zone{})",
                            if widest > own.extent().0 {
                                "; the widest grid is a design load's"
                            } else {
                                ""
                            }
                        ),
                    ));
                }
            }
            Model::Beam { loaded_point, .. } => {
                // The contact forces act at the points: a load beyond the
                // last of them is balanced by none (the solve ends in a ray).
                let (lo, hi) = (own.x(0), own.x(own.len() - 1));
                if !(lo..=hi).contains(&loaded_point) {
                    let span = t.loaded_point.as_ref().map_or(t.model.span(), |v| v.span());
                    return Err(ctx.invalid(
                        span,
                        format!("{section}.loaded_point"),
                        Num(loaded_point),
                        format!(
                            "is outside the beam's points, not between its first and last, {} \
                             and {}: the contact forces act at the points, and no forces there \
                             balance a load beyond them; give a point between them (default 0)",
                            Num(lo),
                            Num(hi)
                        ),
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Bounds on the solver's knobs: refinement steps and the pivot limit.
pub(crate) fn solver_bounds(
    ctx: &Ctx<'_>,
    s: Option<&SolverToml>,
    points: usize,
) -> Result<(), SceneError> {
    let Some(s) = s else { return Ok(()) };
    if let Some(r) = &s.refinement_steps
        && *r.get_ref() > MAX_REFINEMENT_STEPS as i64
    {
        return Err(ctx.invalid(
            r.span(),
            "solver.refinement_steps",
            r.get_ref(),
            format!(
                "at most {MAX_REFINEMENT_STEPS} (each step is an N x N product; refinement \
                 settles in one to three)"
            ),
        ));
    }
    let bound = max_pivots_bound(points);
    if let Some(p) = &s.max_pivots
        && *p.get_ref() > i64::try_from(bound).unwrap_or(i64::MAX)
    {
        return Err(ctx.invalid(
            p.span(),
            "solver.max_pivots",
            p.get_ref(),
            format!(
                "at most 100 N + 10000 = {bound} for N = {points} points (a pivoting path that \
                 has not ended by then is cycling; the defaults are about 40 N)"
            ),
        ));
    }
    Ok(())
}

/// A validated design section, as the checks against its grids need it.
pub(crate) struct DesignView {
    /// The family, when it is linear in its parameters.
    pub family: Option<Family>,
    /// The axial coordinate.
    pub axis: Axis,
    /// The bound on the constant, if given.
    pub max_constant: Option<f64>,
    /// The design loads (force), one grid of `sets` each.
    pub loads: Vec<f64>,
    /// Whether each load counts against its own reference intensity
    /// (`design.relative_to` = "hertz" or "mean"), not the worst p_max.
    pub relative: bool,
    /// The grids the design is carried over and verified on
    /// (`design.refine`, `design.max_points`); none on the scene's grid
    /// alone.
    pub sequence: Option<GridSequence>,
}

/// The number of design cases (each load at each misalignment), before any
/// of their grids is built.
pub(crate) fn design_cases(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    cases: usize,
) -> Result<(), SceneError> {
    let t = raw.get_ref();
    if cases > MAX_DESIGN_CASES {
        let (span, field) = match (&t.misalignments, &t.loads) {
            (Some(m), _) => (m.span(), "design.misalignments"),
            (None, Some(l)) => (l.span(), "design.loads"),
            (None, None) => (raw.span(), "design.loads"),
        };
        return Err(ctx.invalid(
            span,
            field,
            format!("{} cases", cases),
            format!(
                "at most {MAX_DESIGN_CASES} design cases (each load at each misalignment): every \
                 descent iteration analyses each one"
            ),
        ));
    }
    Ok(())
}

/// The design section against the grids of its load cases: the degree
/// against the axial stations, the bound on the constant.
pub(crate) fn design(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignView,
    sets: &[PointSet],
) -> Result<(), SceneError> {
    let t = raw.get_ref();
    if let Some(family) = &spec.family {
        let (stations, _) = axial_stations(sets.iter(), spec.axis);
        let degree = family.degree().unwrap_or(0);
        let (field, span) = match family {
            Family::Polynomial { .. } => (
                "design.degree",
                t.degree.as_ref().map_or(raw.span(), |d| d.span()),
            ),
            _ => ("design.family", t.family.span()),
        };
        if degree > MAX_DEGREE {
            return Err(ctx.invalid(
                span,
                field,
                degree,
                format!(
                    "at most {MAX_DEGREE} (a polynomial basis of higher degree is too \
                     ill-conditioned for the design program)"
                ),
            ));
        }
        if degree + 1 > stations.len() {
            return Err(ctx.invalid(
                span,
                field,
                if field == "design.family" {
                    "\"quadratic\"".to_string()
                } else {
                    degree.to_string()
                },
                format!(
                    "degree {degree} needs at least {} axial stations (distinct positions along \
                     {}), the grid has {}",
                    degree + 1,
                    match spec.axis {
                        Axis::X => "x",
                        Axis::Y => "y",
                    },
                    stations.len()
                ),
            ));
        }
    }
    load_range(ctx, raw, spec, sets)?;
    if let (Some(c), Some(raw_c)) = (spec.max_constant, &t.max_constant) {
        let zone = sets.iter().map(zone_size).fold(0.0f64, f64::max);
        let bound = MAX_CONSTANT_OVER_ZONE * zone;
        if c > bound {
            return Err(ctx.invalid(
                raw_c.span(),
                "design.max_constant",
                Num(c),
                format!(
                    "at most {MAX_CONSTANT_OVER_ZONE:e} times the candidate zone's size \
                     ({zone:.4e}), that is {bound:.4e} (a uniform drop only shifts the approach)"
                ),
            ));
        }
    }
    Ok(())
}

/// The lightest load a design relative to each load's own reference can
/// be verified at, on a grid whose axial extent is the same at every load
/// (a roller's length, an absolute grid): a crown that relieves the
/// heaviest load P_max leaves a load P a contact that ends where the crown
/// leaves P's approach, and approaches grow with the load, so the drop
/// turns from P's to P_max's over about `sqrt(P / P_max)` of the profile's
/// length. With fewer than [`MIN_POINTS_ACROSS`] axial stations there on
/// the finest grid a design can be made on (`n` stations: the scene's grid
/// at the last but one fineness whose cases keep within
/// `design.max_points`, the last verifying it), P's
/// pressure at its contact's ends is a cell's average of a peak a finer
/// grid resolves higher: its `p_max / r` grows with the grid, and the
/// design never holds on a finer one. So a relative design needs
/// `P_min / P_max >= (MIN_POINTS_ACROSS / n)^2`. (The crowned roller of
/// docs/design.md, 40 stations and 20,000 points a case, designed with 5
/// and 10 kN: at 20 N it holds, at 5 N and 2 N it does not; the bound is
/// 9.77 N.)
fn load_range(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignView,
    sets: &[PointSet],
) -> Result<(), SceneError> {
    let Some(sequence) = &spec.sequence else {
        return Ok(());
    };
    if !spec.relative || sets.len() != spec.loads.len() || sets.len() < 2 {
        return Ok(());
    }
    let by_load = |a: &usize, b: &usize| spec.loads[*a].total_cmp(&spec.loads[*b]);
    let (Some(lightest), Some(heaviest)) = (
        (0..sets.len()).min_by(by_load),
        (0..sets.len()).max_by(by_load),
    ) else {
        return Ok(());
    };
    let extent = |set: &PointSet| {
        spec.axis
            .positions(set)
            .into_iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                (lo.min(s), hi.max(s))
            })
    };
    let ((a, b), (c, d)) = (extent(&sets[lightest]), extent(&sets[heaviest]));
    let span = (d - c).abs().max(f64::MIN_POSITIVE);
    if (a - c).abs() + (b - d).abs() > 1e-9 * span {
        // Each load's grid is sized by its own contact along the axis.
        return Ok(());
    }
    let (stations, _) = axial_stations(std::iter::once(&sets[lightest]), spec.axis);
    // The finest grid a design can be made on: the last but one of the
    // sequence's grids whose largest case keeps within max_points (the
    // last only verifies it; points grow as f^2 on a surface, f on a line).
    let largest = sets.iter().map(PointSet::len).max().unwrap_or(0) as f64;
    let power = if sets[lightest].dimension() == Dimension::Line {
        1
    } else {
        2
    };
    let within: Vec<f64> = sequence
        .fineness
        .iter()
        .copied()
        .filter(|f| largest * f.powi(power) <= sequence.max_points as f64)
        .collect();
    let finest = within.iter().rev().nth(1).copied().unwrap_or(1.0);
    let n = (stations.len() as f64 * finest).round();
    let resolved = (MIN_POINTS_ACROSS as f64 / n).powi(2);
    let (light, heavy) = (spec.loads[lightest], spec.loads[heaviest]);
    // The smallest load resolved, rounded up to three digits.
    let smallest = {
        let digits = 10f64.powi(2 - (resolved * heavy).log10().floor() as i32);
        (resolved * heavy * digits).ceil() / digits
    };
    if light >= resolved * heavy {
        return Ok(());
    }
    let t = raw.get_ref();
    Err(ctx.invalid(
        t.loads.as_ref().map_or(raw.span(), |l| l.span()),
        "design.loads",
        Num(light),
        format!(
            "the lightest design load is {:.1e} of the heaviest ({}): a crown that relieves the \
             heaviest load's ends turns from the lightest load's approach to the heaviest's over \
             about {:.1e} of the profile's length, fewer than {MIN_POINTS_ACROSS} of the {n} axial \
             stations of the finest grid a design can be made on (within design.max_points = {} \
             a case), so the lightest load's p_max over its reference grows as the grids refine and \
             the design cannot hold on a finer grid. These grids resolve design loads down to {} \
             ({resolved:.1e} of the heaviest): raise the lightest load, give more points along the \
             axis or a larger design.max_points, or design.relative_to = \"absolute\"",
            light / heavy,
            Num(heavy),
            (light / heavy).sqrt(),
            sequence.max_points,
            Num(smallest),
        ),
    ))
}

/// Warnings for a grid too coarse for the contact: fewer than
/// [`MIN_POINTS_ACROSS`] points across the Hertz contact where a closed
/// form gives one, or across an absolute candidate disk.
///
/// `hertz` is the contact's name for its size ("diameter", "width") and
/// its half-size (radius or half-width), where a closed form gives one;
/// `disk` the spacing and radius of an absolute candidate disk.
pub(crate) fn coarse_grid(
    points: &PointSet,
    hertz: Option<(&str, f64)>,
    disk: Option<(f64, f64)>,
) -> Vec<String> {
    let h = points.cell().dx;
    let scale = hertz;
    let mut warnings = Vec::new();
    // Points on a size laid out at `size / (n - 1)` count n, not n - 1
    // when the quotient rounds just below n - 1.
    let count =
        |size: f64, spacing: f64| (size / spacing * (1.0 + 8.0 * f64::EPSILON)).floor() + 1.0;
    if let Some((what, a)) = scale {
        let across = count(2.0 * a, h);
        if across < MIN_POINTS_ACROSS as f64 {
            warnings.push(format!(
                "the grid has about {across:.0} points across the Hertz contact {what} \
                 ({:.4e}, spacing {h:.4e}): fewer than {MIN_POINTS_ACROSS}, so expect an answer far \
                 from Hertz (tens of percent); refine the grid (points.across, or a smaller spacing)",
                2.0 * a
            ));
        }
        return warnings;
    }
    if let Some((spacing, radius)) = disk {
        let across = count(2.0 * radius, spacing);
        if across < MIN_POINTS_ACROSS as f64 {
            warnings.push(format!(
                "the candidate disk has about {across:.0} points across (spacing {spacing} against \
                 radius {radius}), {} in all: too coarse to resolve a contact",
                points.len()
            ));
        }
    }
    warnings
}

/// A grid too coarse to resolve the contact at all: fewer than
/// [`MIN_POINTS_RESOLVED`] points across the contact's expected size (the
/// Hertz contact's `(what, half-size)`, or the candidate disk's `(spacing,
/// radius)`, as [`coarse_grid`] takes them). Gives the points across, the
/// size across and the largest spacing that resolves it.
pub(crate) fn unresolved_grid(
    points: &PointSet,
    hertz: Option<(&str, f64)>,
    disk: Option<(f64, f64)>,
) -> Option<Unresolved> {
    let (h, size, what) = match (hertz, disk) {
        (Some((what, a)), _) => (
            points.cell().dx,
            2.0 * a,
            format!("the Hertz contact {what}"),
        ),
        (None, Some((spacing, radius))) => (
            spacing,
            2.0 * radius,
            "the candidate disk's diameter".to_string(),
        ),
        (None, None) => return None,
    };
    // A grid laid out with exactly `across` points over the contact
    // (`points.across`) lands there up to rounding.
    let across = (size / h * (1.0 + 1e-9)).floor() + 1.0;
    (across < MIN_POINTS_RESOLVED as f64).then(|| Unresolved {
        across: across as usize,
        size,
        what,
        spacing: size / (MIN_POINTS_RESOLVED - 1) as f64,
    })
}

/// A grid that cannot resolve the contact ([`unresolved_grid`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Unresolved {
    /// The points across the contact's size.
    pub across: usize,
    /// The contact's size across (length).
    pub size: f64,
    /// What the size is ("the Hertz contact width").
    pub what: String,
    /// The largest spacing that puts [`MIN_POINTS_RESOLVED`] points across.
    pub spacing: f64,
}

/// Why points relative to the Hertz contact (across, zone) cannot be laid
/// out: the first condition the scene misses.
pub(crate) fn no_hertz_reason(
    models: [&str; 2],
    geometry: &Geometry,
    loading: Loading,
    dimension: Dimension,
) -> String {
    let fix = "; or give absolute sizes (spacing and radius, half_x, start, end and n)";
    if matches!(loading.normal, Normal::Approach(_)) {
        return format!(
            "points relative to the Hertz contact (across, zone) need loading.load: under \
             displacement control the contact's size is not known before the solve{fix}"
        );
    }
    let curved = geometry
        .surfaces()
        .is_some_and(|(a, b)| a.is_curved() || b.is_curved());
    if !curved {
        return format!(
            "points relative to the Hertz contact (across, zone) need curved surfaces (a sphere or \
             a cylinder): between two planes, or a given separation, there is no Hertz contact{fix}"
        );
    }
    let half_space: &[&str] = match dimension {
        Dimension::Surface => &["point-force", "uniform-patch"],
        Dimension::Line => &["plane-strain"],
    };
    if let Some(model) = models
        .iter()
        .find(|m| !(**m == "rigid" || half_space.contains(m)))
    {
        return format!(
            "points relative to the Hertz contact (across, zone) need half-space bodies ({}) or \
             rigid ones: the \"{}\" model has no Hertz contact{fix}",
            half_space.join(", "),
            model
        );
    }
    format!(
        "points relative to the Hertz contact (across, zone) need a Hertz contact: spheres on a \
         disk, cylinders (axis along y) on a line or a rectangle, quadrics whose gap curves both \
         ways on an ellipse{fix}"
    )
}

/// A Hertz length scale that is not a finite positive number: the load,
/// moduli and radii are outside floating-point range together.
pub(crate) fn scale_out_of_range(scale: Option<f64>) -> bool {
    scale.is_some_and(|a| !(a.is_finite() && a > 0.0))
}

/// A moment whose load centre lies outside the candidate zone is refused:
/// the contact forces, all at the zone's points, balance the moment only
/// when their centre, the load centre `(-M_y / P, M_x / P)`, lies within
/// the points' convex hull (`crate::zone`). (Under displacement control
/// the load, and with it the centre, is known only after the solve, whose
/// rotation is bounded then: `crate::run`.)
pub(crate) fn load_centre(
    ctx: &Ctx<'_>,
    raw: &Spanned<LoadingToml>,
    loading: Loading,
    points: &PointSet,
) -> Result<(), SceneError> {
    let Some(load) = loading.load_value() else {
        return Ok(());
    };
    let t = raw.get_ref();
    let given = (t.moment_x.as_ref().map(|m| (m, "loading.moment_x")))
        .or_else(|| t.moment_y.as_ref().map(|m| (m, "loading.moment_y")));
    let Some((blamed, blamed_field)) = given else {
        return Ok(());
    };
    let value = |m: &Option<Spanned<f64>>| m.as_ref().map_or(0.0, |m| *m.get_ref());
    // `0.0 -`: no moment about y puts the centre at x = 0, not -0.
    let centre = (0.0 - value(&t.moment_y) / load, value(&t.moment_x) / load);
    let zone = Zone::of(points);
    if zone.holds(centre) {
        return Ok(());
    }
    let other = match (&t.moment_x, &t.moment_y) {
        (Some(_), Some(my)) => format!("with `loading.moment_y` = {}", Num(*my.get_ref())),
        _ => String::new(),
    };
    Err(ctx.invalid(
        blamed.span(),
        blamed_field,
        Num(*blamed.get_ref()),
        format!(
            "{other}{}puts the load centre (the moment over the load) at (x, y) = ({}, {}), {} \
             outside the candidate zone ({}): no contact inside the zone balances it. Give a \
             smaller moment, or a larger zone (points.zone or points.radius)",
            if other.is_empty() { "" } else { ", " },
            rounded(centre.0),
            rounded(centre.1),
            rounded(-zone.depth(centre)),
            zone.describe()
        ),
    ))
}

/// The unit labels a strain refusal quotes (the scene's `[units]`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Labels<'a> {
    /// Length.
    pub length: &'a str,
    /// Force.
    pub force: &'a str,
    /// The load intensity: pressure, or force per length on a beam.
    pub intensity: &'a str,
}

/// Why `normal` (a load, or an approach) on `points` strains the bodies
/// beyond [`MAX_STRAIN`], if it does: the mean pressure `P / A` over the
/// zone against E* (half-space models), a Winkler foundation's mean
/// compression `P / (A k)` against the zone's size, a beam's bending slope
/// (the larger of its arms from the loaded point as a cantilever under the
/// mean intensity, `q l^3 / (6 E I)`, or on a Winkler foundation
/// Hetenyi's `0.32 P beta^2 / k`, `beta = (k / (4 E I))^(1/4)`, whichever is
/// smaller), an approach against the zone's size.
pub(crate) fn strain(
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
    labels: Labels<'_>,
) -> Option<String> {
    let Labels {
        length,
        intensity: pressure,
        ..
    } = labels;
    let size = strain_length(points);
    let small = "beyond the small strain (at most 0.1) of the linear elasticity the influence \
                 models rest on";
    let load = match normal {
        Normal::Load(p) => p,
        Normal::Approach(d) => {
            let s = d.abs() / size;
            return beyond(s).then(|| {
                format!(
                    "the approach is {s:.1e} times the candidate zone's smaller extent, {} \
                     {length}: {small}; \
                     give an approach below {} {length}, or check its units",
                    Num(size),
                    rounded(MAX_STRAIN * size)
                )
            });
        }
    };
    let measure = points.total_measure();
    let mean = load / measure;
    let area = match points.dimension() {
        Dimension::Surface => format!("{} {length}^2", rounded(measure)),
        Dimension::Line => format!("{} {length} long", rounded(measure)),
    };
    let fix = "give a smaller load, or check the units of the load and the moduli";
    if bodies.iter().any(|b| b.material().is_some()) {
        let e = combined_modulus_of(bodies[0].material(), bodies[1].material());
        let s = mean / e;
        if beyond(s) {
            return Some(format!(
                "the mean pressure over the candidate zone ({area}), {} {pressure}, is {s:.1e} \
                 times E* = {} {pressure} (of the bodies' youngs_modulus and poissons_ratio): \
                 {small}; {fix}",
                rounded(mean),
                rounded(e)
            ));
        }
    }
    let foundation = bodies.iter().find_map(|b| match *b.model() {
        Model::Winkler { modulus } => Some(modulus),
        _ => None,
    });
    if let Some(k) = foundation {
        let s = mean / k / size;
        if beyond(s) {
            return Some(format!(
                "the foundation's mean compression under the load over the candidate zone \
                 ({area}), {} {length} (the mean intensity over the modulus k = {}), is {s:.1e} \
                 times the zone's smaller extent, {} {length}: {small}; {fix}",
                rounded(mean / k),
                Num(k),
                Num(size)
            ));
        }
    }
    bodies
        .iter()
        .find_map(|b| beam_slope(b, (load, mean), points, foundation, labels))
}

/// The length an approach is measured against for the small strain, and
/// its name in messages: the candidate zone's smaller extent
/// (its shortest side), or on an ellipse grid the zone across the Hertz
/// ellipse's minor axis in the ellipse's own frame, whatever its turn
/// (`crate::scene` lays both out).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrainExtent {
    /// The length (length unit).
    pub length: f64,
    /// What it is, for messages ("the candidate zone's smaller extent").
    pub what: &'static str,
}

impl StrainExtent {
    /// The candidate zone's smaller extent ([`strain_length`]).
    pub(crate) fn of(points: &PointSet) -> Self {
        Self {
            length: strain_length(points),
            what: "the candidate zone's smaller extent",
        }
    }
}

/// An approach beyond the small strain: `|approach|` over `extent` above
/// [`MAX_STRAIN`], or not finite: `Some(strain)`. The bound `run` applies
/// to a solved approach and `check` to Hertz's approach at the scene's
/// load.
pub fn approach_strain(approach: f64, extent: StrainExtent) -> Option<f64> {
    let s = approach.abs() / extent.length;
    (!(s.is_finite() && s <= MAX_STRAIN)).then_some(s)
}

/// Why Hertz's approach at `load`, `approach`, is beyond the small strain
/// against `extent` ([`approach_strain`]), if it is: the run would refuse
/// the solved approach. A point contact's approach grows as `P^(2/3)`, and
/// a grid sized by the Hertz contact (`sized_by_hertz`) as `P^(1/3)`: the
/// strain as `P^(2/3)` or `P^(1/3)`, so the message gives the load at the
/// bound.
pub(crate) fn hertz_approach_strain(
    (load, approach): (f64, f64),
    sized_by_hertz: bool,
    extent: StrainExtent,
    length: &str,
) -> Option<String> {
    let s = approach_strain(approach, extent)?;
    let power = if sized_by_hertz { 3.0 } else { 1.5 };
    Some(format!(
        "Hertz's approach at this load, {} {length}, is {s:.4} times {}, {} {length}: beyond \
         the small strain (at most {MAX_STRAIN}) of the linear elasticity the influence models \
         rest on, so the run would refuse the solved approach; give a load of at most {}, \
         stiffer bodies (youngs_modulus), or check their units",
        rounded(approach),
        extent.what,
        rounded(extent.length),
        rounded(load * (MAX_STRAIN / s).powf(power) * 0.999)
    ))
}

/// Prescribed tilts that move the gap's minimum of spheres of combined
/// radius `radius` to `R (tilt_y, -tilt_x)` (a rotation about x moves it
/// along y) so far that the Hertz contact of radius `contact` around it
/// reaches past the candidate zone's open edge ([`OpenEdge`]: a boundary
/// point's cell, half a cell out, as the run tests it): the field to name
/// (the larger tilt) and why. The run would find the contact against the
/// zone's edge.
pub(crate) fn tilt_off_zone(
    (radius, contact): (f64, f64),
    loading: Loading,
    points: &PointSet,
    length: &str,
) -> Option<(&'static str, String)> {
    let (tx, ty) = prescribed_tilts(loading);
    let shift = (radius * ty, -radius * tx);
    let distance = shift.0.hypot(shift.1);
    if !(distance > 0.0) {
        return None;
    }
    let edge = OpenEdge::of(points);
    let most = edge.largest_shift(shift, |d: (f64, f64)| d.0.hypot(d.1) < contact);
    if most >= 1.0 {
        return None;
    }
    Some((
        larger_tilt(tx, ty),
        format!(
            "the tilts (tilt_x {}, tilt_y {} rad) move the gap's minimum by R tilt = {} {length} \
             (R = {} {length}, the spheres' combined radius); with the Hertz contact's radius, \
             {} {length}, the contact reaches beyond the candidate zone's boundary points by \
             half a cell or more: the contact would lie against the zone's edge. Give tilts of \
             at most {} rad together, or a larger zone (points.zone or points.radius)",
            Num(tx),
            Num(ty),
            rounded(distance),
            rounded(radius),
            rounded(contact),
            at_most(most * tx.hypot(ty))
        ),
    ))
}

/// The prescribed tilts about x and y (rad; 0 where free).
fn prescribed_tilts(loading: Loading) -> (f64, f64) {
    (
        loading.tilt_x.prescribed_angle(),
        loading.tilt_y.prescribed_angle(),
    )
}

/// The field of the larger of the tilts about x and y.
fn larger_tilt(tx: f64, ty: f64) -> &'static str {
    if tx.abs() >= ty.abs() {
        "loading.tilt_x"
    } else {
        "loading.tilt_y"
    }
}

/// A line contact whose approach, Hertz's measured from the plane-strain
/// bodies' datums, is beyond the small strain of the candidate line's
/// length because of one body's `reference_distance`: each body's
/// compression is `(2 P' / pi) (1 - nu^2) / E (ln(2 d0 / b) + 1/2)`
/// (their sum is `HertzCylinders::approach` for a common d0), so a datum
/// far beyond the contact adds its logarithm to the approach the run then
/// refuses. The body to name (0 or 1: the farther datum) and why, with
/// the range of its datum that keeps the approach within the bound:
/// from `widest`, the grid's extent (the datum lies beyond the grid), to
/// the largest the other body's compression leaves room for. `None` when
/// the approach is within the bound, or no datum in that range brings it
/// there (then the load strains the bodies, refused by the run).
pub(crate) fn datum_strain(
    h: &elcon_analysis::references::HertzCylinders,
    bodies: [&Body; 2],
    points: &PointSet,
    length: &str,
) -> Option<(usize, String)> {
    let (p, b) = (h.load_per_length, h.half_width());
    // Each plane-strain body's compliance and datum.
    let strips: Vec<(usize, f64, f64)> = bodies
        .iter()
        .enumerate()
        .filter_map(|(i, body)| match *body.model() {
            Model::PlaneStrainStrip {
                material,
                reference_distance,
            } => Some((i, material.compliance(), reference_distance)),
            _ => None,
        })
        .collect();
    let compression =
        |c: f64, d0: f64| 2.0 * p / std::f64::consts::PI * c * ((2.0 * d0 / b).ln() + 0.5);
    let approach: f64 = strips.iter().map(|&(_, c, d0)| compression(c, d0)).sum();
    let extent = StrainExtent::of(points);
    let s = approach_strain(approach, extent)?;
    let &(i, c, d0) = strips.iter().max_by(|a, b| a.2.total_cmp(&b.2))?;
    let others: f64 = strips
        .iter()
        .filter(|s| s.0 != i)
        .map(|&(_, c, d0)| compression(c, d0))
        .sum();
    let room = MAX_STRAIN * extent.length - others;
    let farthest = 0.5 * b * (room * std::f64::consts::PI / (2.0 * p * c) - 0.5).exp();
    let widest = points.extent().0;
    if !(farthest >= widest && farthest < d0) {
        return None;
    }
    Some((
        i,
        format!(
            "the line contact's approach measured from the bodies' datums, Hertz's at this load, \
             is {} {length}, {s:.1e} times {}, {} {length}: beyond the small strain (at most \
             {MAX_STRAIN}) of the linear elasticity the influence models rest on, so the run \
             would refuse the solved approach; this datum adds {} {length} of it (its compression \
             grows as the logarithm of the datum over the Hertz half-width, {} {length}). Give \
             a reference_distance from {} (the grid's extent) to {} {length}, or check its units",
            rounded(approach),
            extent.what,
            rounded(extent.length),
            rounded(compression(c, d0)),
            rounded(b),
            rounded(widest),
            rounded(farthest * 0.999)
        ),
    ))
}

/// Prescribed tilts that move the minimum of an elliptical Hertz
/// contact's gap (`h`, of the gap's curvature form K) so far that the
/// contact ellipse around it reaches past the candidate zone's open edge
/// ([`OpenEdge`], as the run tests it): the gap
/// `K(x, x) / 2 + tilt_x y - tilt_y x` has its minimum at
/// `s = K^-1 (tilt_y, -tilt_x)` (for spheres `R (tilt_y, -tilt_x)`,
/// [`tilt_off_zone`]), and the contact is Hertz's ellipse moved there.
/// The field to name (the larger tilt) and why, as [`tilt_off_zone`] says
/// it. The run would find the contact against the zone's edge.
pub(crate) fn tilt_off_zone_ellipse(
    h: &elcon_analysis::references::HertzEllipse,
    loading: Loading,
    points: &PointSet,
    length: &str,
) -> Option<(&'static str, String)> {
    let (tx, ty) = prescribed_tilts(loading);
    let k = h.curvature();
    let det = k.xx * k.yy - k.xy * k.xy;
    let shift = (
        (k.yy * ty + k.xy * tx) / det,
        -(k.xy * ty + k.xx * tx) / det,
    );
    let distance = shift.0.hypot(shift.1);
    if !(distance > 0.0) {
        return None;
    }
    let (a, b) = (h.semi_major(), h.semi_minor());
    let (s, c) = h.angle().sin_cos();
    // A point at d from the centre, in the ellipse's axes.
    let inside = |d: (f64, f64)| {
        let (u, v) = (d.0 * c + d.1 * s, d.1 * c - d.0 * s);
        (u / a).powi(2) + (v / b).powi(2) < 1.0
    };
    let edge = OpenEdge::of(points);
    let most = edge.largest_shift(shift, inside);
    if most >= 1.0 {
        return None;
    }
    Some((
        larger_tilt(tx, ty),
        format!(
            "the tilts (tilt_x {}, tilt_y {} rad) move the gap's minimum by K^-1 tilt = {} \
             {length} to (x, y) = ({}, {}) (K the gap's curvature); with the Hertz ellipse's \
             semi-axes, {} and {} {length}, the contact reaches beyond the candidate zone's \
             boundary points ({}) by half a cell or more: the contact would lie against the \
             zone's edge. Give tilts of at most {} rad together, or a larger zone (points.zone \
             or points.radius)",
            Num(tx),
            Num(ty),
            rounded(distance),
            rounded(shift.0),
            rounded(shift.1),
            rounded(a),
            rounded(b),
            edge.describe(),
            at_most(most * tx.hypot(ty))
        ),
    ))
}

/// The largest elastic deformation `normal` can make on `points`
/// (length): an approach is its own; a load's is the largest of the whole
/// load on one cell (the contact is at least one cell): its pressure
/// against E* times the cell's smaller side (half-space models), a Winkler
/// foundation's compression under it `P / (A_cell k)`, and, without a
/// foundation, a beam's tip deflection under it as a cantilever over its
/// longer arm, `P l^3 / (3 E I)`. An upper bound, so that a refusal never
/// blames a load whose contact is resolved.
pub(crate) fn deformation(bodies: [&Body; 2], normal: Normal, points: &PointSet) -> f64 {
    match normal {
        Normal::Approach(d) => d.abs(),
        Normal::Load(p) => compliances(bodies, points)
            .into_iter()
            .fold(0.0f64, |w, (_, c)| w.max(p * c)),
    }
}

/// Each mechanism's deflection under a unit force on one cell of
/// `points` (length per force, [`deformation`]): the half-space bodies'
/// `h / (A_cell E*)`, a Winkler foundation's `1 / (A_cell k)`, and,
/// without a foundation, a free beam's `l^3 / (3 E I)`.
fn compliances(bodies: [&Body; 2], points: &PointSet) -> Vec<(Mechanism, f64)> {
    let cell = points.cell();
    let measure = cell.measure(points.dimension());
    let side = match points.dimension() {
        Dimension::Line => cell.dx,
        Dimension::Surface => cell.dx.min(cell.dy),
    };
    let foundation = bodies.iter().find_map(|b| match *b.model() {
        Model::Winkler { modulus } => Some(modulus),
        _ => None,
    });
    let mut terms = Vec::new();
    if bodies.iter().any(|b| b.material().is_some()) {
        let e = combined_modulus_of(bodies[0].material(), bodies[1].material());
        terms.push((Mechanism::HalfSpace, side / (measure * e)));
    }
    if let Some(k) = foundation {
        terms.push((Mechanism::Foundation, 1.0 / (measure * k)));
    }
    for b in bodies {
        if let (
            None,
            Model::Beam {
                flexural_rigidity: ei,
                loaded_point,
            },
        ) = (foundation, *b.model())
        {
            terms.push((
                Mechanism::Beam,
                beam_arm(points, loaded_point).powi(3) / (3.0 * ei),
            ));
        }
    }
    terms
}

/// An input a magnitude bound depends on, as the scene writes it (the
/// load, a modulus, a radius): the bound's quantity grows as `value^power`
/// with the other inputs held, so the input that takes the quantity out of
/// its range is the one whose contribution `power log10(value)` is the
/// most extreme in that direction ([`extreme`]), and its accepted range
/// follows ([`Factor::range`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Factor {
    /// The field, as the user writes it (`body2.modulus`).
    pub field: String,
    /// Where the value is written.
    pub span: std::ops::Range<usize>,
    /// The value.
    pub value: f64,
    /// The power the quantity grows with.
    pub power: f64,
    /// What it is, for the message ("a modulus").
    pub what: &'static str,
    /// `(k, o)`: the quantity grows as a power of `1 / (k / value + o)`,
    /// the value combined with the other body's or surface's term `o`
    /// (E* of two half-space bodies, `k = 1 - nu^2` and `o` the other's
    /// compliance; the spheres' combined radius, `k = 1`, `o = 1 / R_2`);
    /// `(1, 0)`: of the value alone.
    pub combined: (f64, f64),
}

impl Factor {
    /// The values of this factor that bring a quantity of `decades`
    /// (log10) within `lo..=hi` (log10), the other inputs held, in
    /// increasing order: the combined value `X` ([`Factor::combined`])
    /// scaled by `10^((bound - decades) / power)`, turned back into the
    /// value, `k / (1 / X - o)`. A bound no value reaches (the other term
    /// alone is beyond it) is infinite: `(low, high)` with `low` infinite
    /// or `low >= high` is an empty range.
    pub(crate) fn range(&self, decades: f64, (lo, hi): (f64, f64)) -> (f64, f64) {
        let (k, o) = self.combined;
        // In decades: the factor 10^((lo - decades) / power) alone can
        // underflow where the value it scales does not.
        let at = |bound: f64| {
            let shift = (bound - decades) / self.power;
            let alone = || self.value.signum() * 10f64.powf(self.value.abs().log10() + shift);
            if o == 0.0 || !(self.value > 0.0 && k > 0.0) {
                return alone();
            }
            let inverse = (k / self.value + o) * 10f64.powf(-shift);
            let rest = inverse - o;
            match rest > 0.0 {
                // The other term is negligible where `1 / X` leaves the doubles.
                _ if !(inverse.is_finite() && inverse > 0.0) => alone(),
                true => k / rest,
                false => f64::INFINITY,
            }
        };
        let (a, b) = (at(lo), at(hi));
        (a.min(b), a.max(b))
    }
}

/// The range `low..high` of an input a refusal hands back ("give a
/// modulus from ... to ..."), each end inside the range by 1e-3, or, where
/// the range is empty, why no value of that input alone will do.
pub(crate) fn range_advice(what: &str, (low, high): (f64, f64)) -> String {
    if !(low.is_finite() && low < high) {
        return format!(
            "no value of it alone brings the scene within range (the other inputs are out of \
             scale too): change them together, giving {what} of ordinary size"
        );
    }
    if high.is_infinite() {
        return format!("give {what} of at least {}", rounded(low * 1.001));
    }
    format!(
        "give {what} from {} to {}",
        rounded(low * 1.001),
        rounded(high * 0.999)
    )
}

/// Of `factors`, the one that takes a quantity out of its range the most:
/// the most negative contribution `power log10(value)` when the quantity
/// is too small (`too_small`), the most positive when it is too large;
/// `None` when none contributes in that direction.
pub(crate) fn extreme(factors: &[Factor], too_small: bool) -> Option<&Factor> {
    let toward = |f: &&Factor| {
        let c = f.power * f.value.abs().log10();
        if too_small { -c } else { c }
    };
    factors
        .iter()
        .filter(|f| f.value != 0.0 && f.value.is_finite() && toward(f) > 0.0)
        .max_by(|a, b| toward(a).total_cmp(&toward(b)))
}

/// The smallest value of a stiffness `f` (a foundation's `modulus`, a
/// half-space body's `youngs_modulus`) the small strain ([`strain`])
/// accepts under `normal` on `points`, the other body held: the mean
/// pressure over the zone at most [`MAX_STRAIN`] of E*, a foundation's
/// mean compression at most [`MAX_STRAIN`] of the zone's smaller extent.
/// 0 for any other input.
pub(crate) fn strain_floor(
    f: &Factor,
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
) -> f64 {
    let Normal::Load(load) = normal else {
        return 0.0;
    };
    let mean = load / points.total_measure();
    let index = match f.field.as_str() {
        "body1.modulus" | "body1.youngs_modulus" => 0,
        "body2.modulus" | "body2.youngs_modulus" => 1,
        _ => return 0.0,
    };
    match *bodies[index].model() {
        Model::Winkler { .. } => mean / (MAX_STRAIN * strain_length(points)),
        _ => match bodies[index].material() {
            Some(m) => {
                // 1 / E* = (1 - nu^2) / E + the other's compliance <= MAX_STRAIN / mean.
                let other = bodies[1 - index].material().map_or(0.0, |m| m.compliance());
                let room = MAX_STRAIN / mean - other;
                let nu = m.poissons_ratio();
                if room > 0.0 {
                    (1.0 - nu * nu) / room
                } else {
                    f64::INFINITY
                }
            }
            None => 0.0,
        },
    }
}

/// What makes a load's deformation on a grid ([`deformation`]): the
/// mechanism whose term is the largest under a unit load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mechanism {
    /// The half-space bodies' `P / (E* h)`.
    HalfSpace,
    /// A Winkler foundation's `P / (k A_cell)`.
    Foundation,
    /// A free beam's `P l^3 / (3 E I)`.
    Beam,
}

/// The mechanism of [`deformation`] on `points`, `None` without an
/// elastic body.
pub(crate) fn mechanism(bodies: [&Body; 2], points: &PointSet) -> Option<Mechanism> {
    compliances(bodies, points)
        .into_iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(m, _)| m)
}

/// The bodies' compliance on one cell, `c`, the [`deformation`] a unit
/// force on one cell makes (about `1 / (E* h)` on a half-space, `1 / (k
/// A_cell)` on a foundation, `l^3 / (3 E I)` on a cantilevered beam, length
/// per force), against the size of the solve's residuals, `r`, the larger
/// of the load's deformation and the largest initial separation, `largest`:
/// the conjugate gradient's step divides squared residuals by `t . S t`
/// for a direction `t` of the residuals' size, about `r^2 c`. That must
/// stay between [`MIN_DEFORMATION`]^2 and [`MAX_DEFORMATION`]^2 (about
/// 4.5e-277 and 2.2e276), or it underflows or overflows whatever the
/// method. Names the stiffness key (a foundation's `modulus`, else the
/// first `youngs_modulus`).
pub(crate) fn compliance_in_range(
    ctx: &Ctx<'_>,
    factors: &dyn Fn(bool) -> Vec<Factor>,
    bodies: [&Body; 2],
    points: &PointSet,
    (normal, largest): (Normal, f64),
    labels: Labels<'_>,
) -> Result<(), SceneError> {
    let c = deformation(bodies, Normal::Load(1.0), points);
    let w = deformation(bodies, normal, points);
    let r = w.max(largest.abs());
    // In decades: the product itself can underflow to 0 or overflow.
    let decades = 2.0 * r.log10() + c.log10();
    let range = MIN_DEFORMATION * MIN_DEFORMATION..=MAX_DEFORMATION * MAX_DEFORMATION;
    let bounds = (range.start().log10(), range.end().log10());
    // 0: no elastic body or nothing pressed (said elsewhere); in range:
    // nothing to say.
    if c == 0.0 || r == 0.0 || (bounds.0..=bounds.1).contains(&decades) {
        return Ok(());
    }
    // The input farthest out of scale in the product's direction (the
    // residuals are the load's deformation, or the largest separation).
    let candidates = factors(w >= largest.abs());
    let Some(f) = extreme(&candidates, decades < bounds.0) else {
        return Ok(());
    };
    let (low, high) = f.range(decades, bounds);
    let low = low.max(strain_floor(f, bodies, normal, points));
    // An approach is bounded by the small strain of the zone too.
    let high = match normal {
        Normal::Approach(_) if f.field == "loading.approach" => {
            high.min(MAX_STRAIN * StrainExtent::of(points).length)
        }
        _ => high,
    };
    let Labels { length, force, .. } = labels;
    Err(ctx.invalid(
        f.span.clone(),
        f.field.clone(),
        Num(f.value),
        format!(
            "the bodies' compliance on one cell of the grid, about {c:.2e} {length} per \
             {force} (a unit force's deflection there), times the square of the solve's \
             residuals, about {r:.2e} {length} (the load's deformation or the largest \
             separation), is about 1e{decades:.0}, outside {:.1e} to {:.1e}: the solve's products \
             of them underflow or overflow among doubles. Of the load, the moduli and the radii \
             this product grows with, {} is the farthest out of scale; with the others as they \
             are, {}, or check the units of the moduli, the lengths and the load",
            range.start(),
            range.end(),
            f.field,
            range_advice(f.what, (low, high)),
        ),
    ))
}

/// Why `normal` on `points` cannot be resolved against the largest initial
/// separation over the zone, `largest` (length), if it cannot: its
/// [`deformation`] below [`MIN_RESOLVED_DEFORMATION`] of `largest`, or
/// below [`MIN_DEFORMATION`]; or a deformation or a mean force per point
/// above [`MAX_DEFORMATION`]. The message gives the smallest (largest)
/// load or approach accepted: the deformation is linear in it.
pub(crate) fn unresolved(
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
    largest: f64,
    length: &str,
) -> Option<String> {
    if let Normal::Load(p) = normal {
        let per_point = p / points.len() as f64;
        if per_point < MIN_DEFORMATION {
            return Some(format!(
                "is {} per candidate point (of {}), below {MIN_DEFORMATION:.2e}, where the \
                 squares of forces times the solve's tolerance (2.2e-16 of them) fall among \
                 the subnormal numbers and lose their digits; give a load of at least {}, or \
                 check its units",
                rounded(per_point),
                points.len(),
                rounded(MIN_DEFORMATION * points.len() as f64 * 1.001)
            ));
        }
        if per_point > MAX_DEFORMATION {
            return Some(format!(
                "is {} per candidate point (of {}), above {MAX_DEFORMATION:.2e}, where the \
                 solve's sums of squared forces overflow; give a load of at most {}, or check \
                 its units and the moduli",
                rounded(per_point),
                points.len(),
                rounded(MAX_DEFORMATION * points.len() as f64 * 0.999)
            ));
        }
    }
    // An approach of 0 or less presses nothing (the run says so).
    if matches!(normal, Normal::Approach(d) if d <= 0.0) {
        return None;
    }
    let w = deformation(bodies, normal, points);
    if w > MAX_DEFORMATION {
        let (value, what) = match normal {
            Normal::Load(p) => (p, "a load"),
            Normal::Approach(d) => (d, "an approach"),
        };
        return Some(format!(
            "deforms the bodies by up to about {} {length}, above {MAX_DEFORMATION:.2e} \
             {length}, where the solve's sums of squared deformations overflow; give {what} of \
             at most {}, or check the units and the moduli",
            rounded(w),
            rounded(value * (MAX_DEFORMATION / w) * 0.999)
        ));
    }
    let needed = (MIN_RESOLVED_DEFORMATION * largest.abs()).max(MIN_DEFORMATION);
    if w >= needed {
        return None;
    }
    let (value, what, estimate) = match normal {
        Normal::Load(p) => (
            p,
            "a load",
            "the whole load on one cell, against the bodies' stiffness",
        ),
        Normal::Approach(d) => (d.abs(), "an approach", "the approach"),
    };
    // The deformation is linear in the load: scale it up to `needed`,
    // and to where the solve's product `r^2 c` stays normal
    // ([`compliance_in_range`], `r` at least the deformation), rounded up
    // to four digits.
    let c = deformation(bodies, Normal::Load(1.0), points);
    let product_floor = if c > 0.0 && largest.abs().powi(2) * c < MIN_DEFORMATION.powi(2) {
        MIN_DEFORMATION / c.sqrt()
    } else {
        0.0
    };
    let least = if w > 0.0 && w.is_finite() {
        format!(
            "{}",
            rounded(value * (needed.max(product_floor) / w) * 1.001)
        )
    } else {
        "a larger one".to_string()
    };
    let against = if MIN_RESOLVED_DEFORMATION * largest.abs() >= MIN_DEFORMATION {
        format!(
            "{:.1e} of the largest initial separation over the candidate zone, {} {length}: \
             below {MIN_RESOLVED_DEFORMATION:.0e} of it the gaps near the contact are lost \
             among the rounding of the separations (each exact to about 2.2e-16 of the \
             largest), to which the solve's tolerances are scaled",
            w / largest.abs(),
            rounded(largest.abs())
        )
    } else {
        format!(
            "below {MIN_DEFORMATION:.2e} {length}, where the squares of deformations times \
             the solve's tolerance (2.2e-16 of them) fall among the subnormal numbers and lose \
             their digits"
        )
    };
    Some(format!(
        "deforms the bodies by at most about {} {length} ({estimate}), {against}, so no \
         contact can be resolved; give {what} of at least {least}, a smaller candidate zone or a \
         finer grid, or check the units and the moduli",
        rounded(w)
    ))
}

/// A load whose largest [`deformation`] on `points` is outside the
/// doubles' range ([`MIN_DEFORMATION`] to [`MAX_DEFORMATION`], where that
/// floor binds rather than [`MIN_RESOLVED_DEFORMATION`] of the largest
/// separation) because another input among `factors` is out of scale: that
/// input ([`extreme`]) and why, with its accepted range, the others held.
/// `None` when the load itself is the farthest out of scale (the load's
/// own refusal, [`unresolved`], says so), or the load's deformation is
/// resolvable.
pub(crate) fn deformation_out_of_scale(
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
    largest: f64,
    (factors, product): (&[Factor], &[Factor]),
    length: &str,
) -> Option<(Factor, String)> {
    let Normal::Load(p) = normal else {
        return None;
    };
    let per_point = p / points.len() as f64;
    if !(MIN_DEFORMATION..=MAX_DEFORMATION).contains(&per_point) {
        return None;
    }
    let w = deformation(bodies, normal, points);
    let floor = (MIN_RESOLVED_DEFORMATION * largest.abs()).max(MIN_DEFORMATION);
    let too_small = w < floor && floor == MIN_DEFORMATION;
    if !(too_small || w > MAX_DEFORMATION) || !(w > 0.0 && w.is_finite()) {
        return None;
    }
    let f = extreme(factors, too_small)?;
    if f.field == "loading.load" {
        return None;
    }
    let (mut low, mut high) = f.range(w.log10(), (floor.log10(), MAX_DEFORMATION.log10()));
    // Within the solve's product's range too ([`compliance_in_range`]),
    // where it depends on the same input: the range both bounds accept.
    let c = deformation(bodies, Normal::Load(1.0), points);
    let decades = 2.0 * w.max(largest.abs()).log10() + c.log10();
    let bounds = (2.0 * MIN_DEFORMATION.log10(), 2.0 * MAX_DEFORMATION.log10());
    if let Some(g) = product.iter().find(|g| g.field == f.field) {
        let (a, b) = g.range(decades, bounds);
        (low, high) = (low.max(a), high.min(b));
    }
    low = low.max(strain_floor(f, bodies, normal, points));
    let against = if too_small {
        format!(
            "below {MIN_DEFORMATION:.2e} {length}, where the squares of deformations times the solve's tolerance (2.2e-16 of them) fall among the subnormal numbers and lose their digits"
        )
    } else {
        format!(
            "above {MAX_DEFORMATION:.2e} {length}, where the solve's sums of squared deformations overflow"
        )
    };
    let reason = format!(
        "the load deforms the bodies by at most about {} {length} (the whole load on one cell, \
         against the bodies' stiffness), {against}, so no contact can be resolved. Of the load, \
         the moduli and the radii it grows with, {} is the farthest out of scale; with the \
         others as they are, {}, or check its units",
        rounded(w),
        f.field,
        range_advice(f.what, (low, high)),
    );
    Some((f.clone(), reason))
}

/// A beam's longer arm from its loaded point to the far edge of the last
/// cell on either side.
fn beam_arm(points: &PointSet, loaded_point: f64) -> f64 {
    let h = points.cell().dx;
    (loaded_point - points.x(0) + 0.5 * h).max(points.x(points.len() - 1) + 0.5 * h - loaded_point)
}

/// A beam body `b` bent beyond [`MAX_STRAIN`] rad by `load` spread over
/// `points` (mean intensity `mean`), on a Winkler `foundation` if there is
/// one ([`strain`]).
fn beam_slope(
    b: &Body,
    (load, mean): (f64, f64),
    points: &PointSet,
    foundation: Option<f64>,
    Labels { length, force, .. }: Labels<'_>,
) -> Option<String> {
    let fix = "give a smaller load, or check the units of the load and the moduli";
    let Model::Beam {
        flexural_rigidity: ei,
        loaded_point,
    } = *b.model()
    else {
        return None;
    };
    let arm = beam_arm(points, loaded_point);
    let cantilever = mean * arm.powi(3) / (6.0 * ei);
    let slope = foundation.map_or(cantilever, |k| {
        let beta = (k / (4.0 * ei)).powf(0.25);
        cantilever.min(0.32 * load * beta * beta / k)
    });
    if beyond(slope) {
        return Some(format!(
            "bends the beam (E I = {} {force} {length}^2) by a slope of about {} rad (its \
             longer arm from the loaded point, {} {length}, under the mean intensity{}): \
             beyond the small slope (at most 0.1 rad) of the linear beam theory the beam \
             model rests on; {fix}",
            rounded(ei),
            rounded(slope),
            rounded(arm),
            if foundation.is_some() {
                ", or Hetenyi's beam on the foundation"
            } else {
                ""
            }
        ));
    }
    None
}

/// Whether a strain `s` exceeds [`MAX_STRAIN`] (or is no number).
fn beyond(s: f64) -> bool {
    s.is_nan() || s > MAX_STRAIN
}

/// The scene's load or approach within [`MAX_STRAIN`] ([`strain`]).
pub(crate) fn small_strain(
    ctx: &Ctx<'_>,
    raw: &Spanned<LoadingToml>,
    bodies: [&Body; 2],
    loading: Loading,
    points: &PointSet,
    labels: Labels<'_>,
) -> Result<(), SceneError> {
    let Some(reason) = strain(bodies, loading.normal, points, labels) else {
        return Ok(());
    };
    let t = raw.get_ref();
    let (field, given) = match loading.normal {
        Normal::Load(_) => ("loading.load", t.load.as_ref()),
        Normal::Approach(_) => ("loading.approach", t.approach.as_ref()),
    };
    let value = match loading.normal {
        Normal::Load(v) | Normal::Approach(v) => v,
    };
    Err(ctx.invalid(
        given.map_or(raw.span(), |v| v.span()),
        field,
        Num(value),
        reason,
    ))
}

/// Given separations, or surfaces with tabulated departures (a height map,
/// a profile), that vary along a row of the grid by more than
/// [`MAX_STRAIN`] of the zone's extent along that row (along x, and along
/// y on a surface): the influence models take the surfaces as nearly flat
/// against the candidate zone, and a surface's slope is its variation over
/// the extent along each axis (a roller's curvature across a zone 10^5
/// times wider than long is flat along x, whatever it does over the
/// roller's length along y).
pub(crate) fn small_separations(eps: &[f64], points: &PointSet, length: &str) -> Option<String> {
    let (ex, ey) = points.extent();
    let cell = points.cell();
    let surface = points.dimension() == Dimension::Surface;
    // Rows along x (one key per y) and, on a surface, columns along y.
    let mut axes = vec![(
        "x",
        ex,
        Box::new(|k: usize| (points.y(k) / cell.dy).round() as i64) as Box<dyn Fn(usize) -> i64>,
    )];
    if surface {
        axes.push((
            "y",
            ey,
            Box::new(|k: usize| (points.x(k) / cell.dx).round() as i64),
        ));
    }
    for (axis, extent, key) in axes {
        // Each row's lowest and highest separation, with their points.
        let mut rows: std::collections::HashMap<i64, (usize, usize)> =
            std::collections::HashMap::new();
        for (k, e) in eps.iter().enumerate() {
            let row = rows.entry(key(k)).or_insert((k, k));
            if *e < eps[row.0] {
                row.0 = k;
            }
            if *e > eps[row.1] {
                row.1 = k;
            }
        }
        let worst = rows
            .values()
            .map(|&(lo, hi)| (lo, hi, eps[hi] - eps[lo]))
            .max_by(|a, b| a.2.total_cmp(&b.2));
        let Some((lo, hi, range)) = worst else {
            continue;
        };
        let s = range / extent;
        if !beyond(s) {
            continue;
        }
        let at = |k: usize| {
            if surface {
                format!("({}, {})", rounded(points.x(k)), rounded(points.y(k)))
            } else {
                format!("x = {}", rounded(points.x(k)))
            }
        };
        return Some(format!(
            "the separation varies along {axis} by {} {length}, from {} at {} to {} at {}, {s:.1e} \
             times the candidate zone's extent along {axis}, {} {length}: the influence models \
             take the surfaces as nearly flat against the candidate zone (a variation along each \
             axis at most {MAX_STRAIN} of the zone's extent along it); check the values and \
             their units",
            rounded(range),
            Num(eps[lo]),
            at(lo),
            Num(eps[hi]),
            at(hi),
            Num(extent)
        ));
    }
    None
}
