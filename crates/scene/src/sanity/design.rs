//! A design section against the grids of its load cases: the number of
//! cases, the degree against the axial stations, the bound on the
//! constant, and the lightest load a relative design can be verified at.

use elcon_design::{Axis, Family, GridSequence, Sampling, axial_stations};
use elcon_influence::{Dimension, PointSet};
use toml::Spanned;

use super::grid::MIN_POINTS_ACROSS;
use super::strain::zone_size;
use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::schema::DesignToml;

/// The most design cases, each load at each misalignment (every descent
/// iteration analyses each case; the memory estimate refuses what does not
/// fit, this bounds the time).
pub const MAX_DESIGN_CASES: usize = 1000;

/// The highest polynomial degree of a design (monomials of the normalized
/// axial coordinate: past about 12 the basis is too ill-conditioned for
/// the design program's pivots).
pub const MAX_DEGREE: usize = 12;

/// The most a design's cells may be longer than wide (on a surface grid):
/// on such cells the influence coefficients resolve too few digits for the
/// certified analyses a design makes on finer and finer grids. The crowned
/// roller of docs/design.md (cells about 10 times longer than wide) with
/// half_y = 250 and 359.9999 mm (cells 3300 and 5800 times longer than
/// wide at 1 kN) failed an analysis's conjugate gradient on 27 x 120 cells
/// (its residual stalled at 6.3e-13 and 6.6e-13, above the stopping
/// target of 5e-13, until the iteration limit); with 100, 200 and 300 mm
/// (850, 2400 and 4400) it designed and held; 131 km (4.5e6) failed a
/// certificate.
pub const MAX_DESIGN_CELL_ASPECT: f64 = 2500.0;

/// The most a design's misalignment may lift the roller's end, in the
/// lightest design load's approach: `|misalignment| x half the length`
/// against the Hertz line contact's approach at that load (measured a
/// roller's radius from the contact). The crowned roller of
/// docs/reliability.md (5 mm long a side, 1, 5 and 10 kN, approach 0.0030
/// mm at 1 kN) designs and holds with misalignments of +-0.001 to +-0.01
/// rad (lifts of 1.7 to 17 approaches, 4 to 20 s); at +-0.02 (34
/// approaches) its first finer grid took 137 descent iterations and the run
/// did not end in 400 s; at +-0.1 (168) not in 300 s.
pub const MAX_END_LIFT: f64 = 20.0;

/// The longest a beam on a Winkler foundation may be for a design, in its
/// characteristic lengths `1 / beta = (4 E I / k)^(1/4)`: a load bends the
/// beam over a few of them beside it and the rest carries nothing, so a
/// design over the whole beam cannot spread the load. Example 2's beam
/// (L beta = 3.1) designs and holds at lengths up to L beta = 37 (100 in);
/// at 55, 90 and 110 (150, 250 and 300 in) its peak grew as the grid on
/// every finer grid, at 143 (400 in) the program and its re-analysis
/// disagreed beyond rounding, and on a foundation of 1e20 lbf/in^2 (L beta
/// = 5600) the peak grew as the grid.
pub const MAX_BEAM_REACH: f64 = 40.0;

/// `design.max_constant` is at most this many times the candidate zone's
/// size: a uniform drop a million times the zone is no profile of these
/// bodies, and values near the floating-point range overflow the design
/// program's sums.
pub const MAX_CONSTANT_OVER_ZONE: f64 = 1e6;

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
    /// The spacing of profile.csv's samples, if given
    /// (`design.profile_spacing`).
    pub profile_spacing: Option<f64>,
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
        if *family == (Family::Polynomial { degree: 0 }) {
            return Err(ctx.invalid(
                span,
                field,
                degree,
                "a polynomial of degree 0 is a constant drop, which under a load only moves the \
                 approach: it changes no pressure, so nothing is designed (a roller's uncrowned \
                 ends keep their peaks, which grow with every finer grid); give a degree of at \
                 least 1 (2 or more for a crown)",
            ));
        }
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
    profile_samples(ctx, raw, spec, sets)?;
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

/// `design.profile_spacing` against the grids' extent along the axis: the
/// samples of profile.csv at that spacing within
/// `elcon_design::MAX_PROFILE_SAMPLES` (the extent is the same on every
/// grid the design goes over: they refine the scene's).
fn profile_samples(
    ctx: &Ctx<'_>,
    raw: &Spanned<DesignToml>,
    spec: &DesignView,
    sets: &[PointSet],
) -> Result<(), SceneError> {
    let (Some(spacing), Some(given)) = (spec.profile_spacing, &raw.get_ref().profile_spacing)
    else {
        return Ok(());
    };
    let (stations, _) = axial_stations(sets.iter(), spec.axis);
    match Sampling::new(&stations, Some(spacing)) {
        Err(elcon_design::DesignError::InvalidInput { reason, .. }) => {
            Err(ctx.invalid(given.span(), "design.profile_spacing", Num(spacing), reason))
        }
        _ => Ok(()),
    }
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
