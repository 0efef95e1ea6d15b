//! The bounds on the knobs that cost time (the solver's refinement steps
//! and pivot limit), and the bodies against the grids they are solved on
//! (a plane-strain datum beyond them, a beam's loaded point on them).

use elcon_influence::{Body, Model, PointSet};
use toml::Spanned;

use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::schema::{BodyToml, SolverToml};

/// The most iterative-refinement steps (each an N x N product;
/// refinement settles in one to three).
pub const MAX_REFINEMENT_STEPS: usize = 20;

/// The largest `solver.max_pivots` for N points: `100 N + 10,000`, well
/// above every method's default (about 40 N for the tableau methods); a
/// pivoting path that has not ended by then is cycling.
pub fn max_pivots_bound(points: usize) -> usize {
    points.saturating_mul(100).saturating_add(10_000)
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
