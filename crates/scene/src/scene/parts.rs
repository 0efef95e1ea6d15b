//! A scene's sections one at a time, for callers that build a contact
//! problem or a design piece by piece rather than from a whole scene (the
//! Python package's `ContactProblem` and `design`): `[body1]`, `[body2]`,
//! `[geometry]`, `[points]` and `[design]` given as the TOML a scene would
//! hold, parsed by the scene's own schema (an unknown key is refused) and
//! validated by the scene's own checks, with the scene's messages (the
//! field named, `body1.youngs_modulus`). And a scene whose `[design]` is
//! replaced, for a design stage asked for over a scene.

use std::path::Path;

use elcon_analysis::{ContactProblem, Geometry, Loading, Normal};
use elcon_design::{FamilyKind, Roller};
use elcon_influence::{Dimension, PointSet};
use serde::Deserialize;
use toml::Spanned;

use super::body::{self, BodySpec};
use super::design::{self, DesignContext, DesignSpec};
use super::hertz::{self, DesignLayoutParts, Layout};
use super::points::{self, PointsSpec, build_points};
use super::{Scene, grid_fits_models, loading, model_kinds};
use super::{files, geometry};
use crate::ctx::{Ctx, parse};
use crate::error::SceneError;
use crate::sanity;
use crate::schema::{BodyToml, DesignToml, GeometryToml, LoadingToml, PointsToml};

/// The sections of a contact problem given piece by piece.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProblemFile {
    body1: Option<Spanned<BodyToml>>,
    body2: Option<Spanned<BodyToml>>,
    geometry: Option<Spanned<GeometryToml>>,
    points: Option<Spanned<PointsToml>>,
    loading: Option<Spanned<LoadingToml>>,
}

/// A `[design]` section alone.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DesignFile {
    design: Spanned<DesignToml>,
}

/// A contact problem's parts, each validated as a scene validates its
/// section.
#[derive(Debug, Clone)]
pub struct ProblemParts {
    /// The two bodies (`[body1]`, `[body2]`), when given.
    pub bodies: Option<[BodySpec; 2]>,
    /// The initial separations' source (`[geometry]`), when given.
    pub geometry: Option<Geometry>,
    /// The layout (`[points]`), when given.
    pub points_spec: Option<PointsSpec>,
    /// The candidate points: laid out from `[points]`, or those given.
    pub points: PointSet,
    /// The load or approach and the rotations (`[loading]`), bounded as a
    /// scene's are (a prescribed tilt at most `MAX_ROTATION`).
    pub loading: Loading,
}

/// The two bodies with which of them is a line or a surface model, when
/// both are given; one alone is refused.
type Bodies = Option<((bool, bool), [BodySpec; 2])>;

/// Parses and validates the sections of a contact problem given piece by
/// piece: `text` is TOML holding `[loading]` and any of `[body1]` with
/// `[body2]`, `[geometry]` and `[points]` as a scene holds them (`file`
/// names it in messages); `listed` are the candidate points when
/// `[points]` is not given. The checks are the scene's: the loading and
/// its rotation bound, each body's model and parameters, the two bodies
/// together, the surfaces against the grid's dimension, the layout's keys,
/// and the bodies against the grid (a plane-strain datum beyond it, a
/// beam's loaded point on it).
///
/// # Errors
/// [`SceneError::Syntax`] for an unknown key or a value of the wrong type;
/// [`SceneError::Invalid`] naming the field otherwise, also when neither or
/// both of `[points]` and `listed` are given, one body without the other,
/// or no `[loading]`.
pub fn problem_parts(
    file: &Path,
    text: &str,
    listed: Option<PointSet>,
) -> Result<ProblemParts, SceneError> {
    let raw: ProblemFile = parse(file, text)?;
    let ctx = Ctx::new(file, text);
    let loading = match &raw.loading {
        Some(l) => loading::loading(&ctx, l)?,
        None => {
            return Err(ctx.invalid(0..0, "loading", "(missing)", "give a load or an approach"));
        }
    };
    let bodies = problem_bodies(&ctx, &raw)?;
    let (points_spec, dimension) = problem_layout(&ctx, &raw, listed.as_ref(), &bodies)?;
    let geometry = (raw.geometry.as_ref())
        .map(|g| {
            let geometry = geometry::geometry(&ctx, Some(g), dimension)?;
            sanity::curvatures(&ctx, Some(g), &geometry).map(|()| geometry)
        })
        .transpose()?;
    // An ellipse grid's shape, from the surfaces (as a scene sets it).
    let points_spec = match (points_spec, &bodies, &geometry) {
        (Some(spec), Some((_, b)), Some(g)) => Some(hertz::shaped(spec, b, g)),
        (spec, _, _) => spec,
    };
    let laid_out = points_spec.as_ref().zip(raw.points.as_ref());
    let points = match (laid_out, listed) {
        (Some((spec, p)), _) => {
            let scale = match (&bodies, &geometry, loading.normal) {
                (Some((_, bodies)), Some(geometry), Normal::Load(load)) => Layout {
                    bodies,
                    geometry,
                    points_spec: spec,
                }
                .scale(load),
                _ => None,
            };
            build_points(spec, scale).map_err(|e| {
                let why = "a layout relative to the Hertz contact needs two bodies, curved \
                           surfaces and a load";
                ctx.invalid(p.span(), "points", "", format!("{e} ({why})"))
            })?
        }
        (None, Some(l)) => l,
        (None, None) => return Err(no_points(&ctx)),
    };
    if let (Some(((true, _), _)), None) = (&bodies, &raw.points) {
        sanity::listed_line(&ctx, &points)?;
    }
    if let (Some((_, b)), Some(b1), Some(b2)) = (&bodies, &raw.body1, &raw.body2) {
        sanity::bodies_on_grid(&ctx, [b1, b2], [b[0].body(), b[1].body()], &points, &[])?;
    }
    // A separation file matched to the points, tables checked to cover
    // them, as a scene does.
    let geometry = geometry
        .map(|g| files::on_points(&ctx, raw.geometry.as_ref(), g, &points))
        .transpose()?;
    Ok(ProblemParts {
        bodies: bodies.map(|(_, b)| b),
        geometry,
        points_spec,
        points,
        loading,
    })
}

/// Neither a layout nor coordinates.
fn no_points(ctx: &Ctx<'_>) -> SceneError {
    ctx.invalid(
        0..0,
        "points",
        "(missing)",
        "give the points as a layout or as coordinates",
    )
}

/// The two bodies of a problem given piece by piece (see [`Bodies`]).
fn problem_bodies(ctx: &Ctx<'_>, raw: &ProblemFile) -> Result<Bodies, SceneError> {
    Ok(match (&raw.body1, &raw.body2) {
        (Some(b1), Some(b2)) => {
            let bodies = [
                body::body(ctx, b1.get_ref(), "body1")?,
                body::body(ctx, b2.get_ref(), "body2")?,
            ];
            Some((model_kinds(ctx, b2, &bodies)?, bodies))
        }
        (Some(b), None) | (None, Some(b)) => {
            let missing = if raw.body1.is_none() {
                "body1"
            } else {
                "body2"
            };
            return Err(ctx.invalid(
                b.span(),
                missing,
                "(missing)",
                "both bodies are needed to assemble S",
            ));
        }
        (None, None) => None,
    })
}

/// The layout (`[points]`, checked against the bodies' models) or the
/// points listed, one of them, and the grid's dimension.
fn problem_layout(
    ctx: &Ctx<'_>,
    raw: &ProblemFile,
    listed: Option<&PointSet>,
    bodies: &Bodies,
) -> Result<(Option<PointsSpec>, Dimension), SceneError> {
    match (&raw.points, listed) {
        (Some(p), None) => {
            let (spec, dimension) = points::points_spec(ctx, p)?;
            if let Some(((line, surface), _)) = bodies {
                grid_fits_models(ctx, p, None, dimension, (*line, *surface))?;
            }
            Ok((Some(spec), dimension))
        }
        (None, Some(l)) => Ok((None, l.dimension())),
        (Some(p), Some(_)) => Err(ctx.invalid(
            p.span(),
            "points",
            "",
            "give the points as a layout or as coordinates, not both",
        )),
        (None, None) => Err(no_points(ctx)),
    }
}

/// Parses and validates a `[design]` section (`text`, TOML, `file` naming
/// it in messages) for a design over `cases`, contact problems built
/// elsewhere: the scene's checks of the family and its keys, the axis
/// against the cases' dimension, the method, and the degree and bound
/// against the cases' grids. The cases are the load cases, so the keys
/// that make cases (`loads`, `misalignments`) and `relative_to` (the
/// caller gives reference intensities instead) are refused, and so is
/// `profile_spacing` (no profile.csv is written). A logarithmic
/// crown's roller is `roller` when given, else derived as a scene derives
/// it from `layout` (the bodies, surfaces and rectangle grid the cases
/// were built from).
///
/// # Errors
/// [`SceneError::Syntax`] for an unknown key; [`SceneError::Invalid`]
/// naming the field, also when the cases are not all lines or all
/// surfaces (named as Python's `design` names them, `problems`).
pub fn design_over(
    file: &Path,
    text: &str,
    cases: &[ContactProblem],
    layout: Option<DesignLayoutParts<'_>>,
    roller: Option<Roller>,
) -> Result<DesignSpec, SceneError> {
    let raw: DesignFile = parse(file, text)?;
    let ctx = Ctx::new(file, text);
    let d = &raw.design;
    let t = d.get_ref();
    for (list, field) in [
        (&t.loads, "design.loads"),
        (&t.misalignments, "design.misalignments"),
    ] {
        ctx.forbid(
            list,
            field,
            "the problems given are the load cases (each with its load and tilt)",
        )?;
    }
    ctx.forbid(
        &t.relative_to,
        "design.relative_to",
        "the problems given are the load cases: give their reference intensities instead",
    )?;
    ctx.forbid(
        &t.profile_spacing,
        "design.profile_spacing",
        "profile.csv is a scene's output: a design over problems writes no file (evaluate its \
         profile where you need it)",
    )?;
    let dimensions: Vec<Dimension> = cases.iter().map(|c| c.points().dimension()).collect();
    let dimension = match dimensions.first() {
        Some(&first) => first,
        None => {
            return Err(ctx.invalid(d.span(), "problems", "[]", "give at least one load case"));
        }
    };
    if let Some(other) = dimensions.iter().position(|&k| k != dimension) {
        let kind = |k: Dimension| match k {
            Dimension::Line => "a line (beam, plane strain)",
            Dimension::Surface => "a surface (half-space bodies)",
        };
        return Err(ctx.invalid(
            d.span(),
            format!("problems[{other}]"),
            "",
            format!(
                "is {} and problems[0] is {}: one design runs along one kind of problem",
                kind(dimensions[other]),
                kind(dimension)
            ),
        ));
    }
    if *t.family.get_ref() == FamilyKind::LogarithmicCrown && layout.is_none() && roller.is_none() {
        return Err(ctx.invalid(
            t.family.span(),
            "design.family",
            "\"logarithmic-crown\"",
            "a logarithmic crown is set for a roller: give it (its combined modulus, radius and \
             length), or build the cases from two half-space bodies, a cylinder on a plane or a \
             cylinder, and a rectangle grid",
        ));
    }
    // The loads of the cases under load control; a displacement-controlled
    // case is refused by elcon-design, naming it.
    let loads: Vec<f64> = cases
        .iter()
        .filter_map(|c| match c.loading().normal {
            Normal::Load(p) => Some(p),
            Normal::Approach(_) => None,
        })
        .collect();
    let largest = loads.iter().copied().fold(0.0, f64::max);
    let spec = design::design(
        &ctx,
        d,
        &DesignContext {
            loading: Loading::load(if largest > 0.0 { largest } else { 1.0 }),
            dimension,
            layout,
            roller,
        },
    )?;
    let sets: Vec<PointSet> = cases.iter().map(|c| c.points().clone()).collect();
    sanity::design(&ctx, d, &spec.view(), &sets)?;
    Ok(spec)
}

/// A scene (`text`, named `file`) with its `[design]` section replaced by
/// `design` (TOML holding a `[design]` table), validated whole as a scene
/// file: what a design stage asked for over a scene runs.
///
/// # Errors
/// As [`Scene::from_str`]; the scene's text is located in its own
/// messages when it is not valid TOML.
pub fn scene_with_design(file: &Path, text: &str, design: &str) -> Result<Scene, SceneError> {
    let mut table: toml::Table = parse(file, text)?;
    let replacement: toml::Table = parse(file, design)?;
    table.remove("design");
    table.extend(replacement);
    let joined = toml::to_string(&table).map_err(|e| SceneError::Syntax {
        file: file.to_path_buf(),
        at: crate::error::Location { line: 1, column: 1 },
        message: format!("the scene with its design replaced cannot be written as TOML: {e}"),
    })?;
    Scene::from_str(file, &joined)
}
