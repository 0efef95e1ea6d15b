//! `[solver]`: the method (or "auto"), its limits and tolerance (bounded
//! on the scene's points), whether a mirror-symmetric problem is folded,
//! and whether the run estimates its discretization error.

use elcon_analysis::Options;

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::{MethodChoice, SolverToml, Symmetry};

/// The most iterative-refinement steps (each an N x N product;
/// refinement settles in one to three).
pub const MAX_REFINEMENT_STEPS: usize = 20;

/// The largest `solver.max_pivots` for N points: `100 N + 10,000`, well
/// above every method's default (about 40 N for the tableau methods); a
/// pivoting path that has not ended by then is cycling.
pub fn max_pivots_bound(points: usize) -> usize {
    points.saturating_mul(100).saturating_add(10_000)
}

/// `solver.symmetry`: "auto" (fold when symmetric, the default) or "none".
pub(super) fn symmetry(solver: Option<&SolverToml>) -> bool {
    solver
        .and_then(|s| s.symmetry.as_ref())
        .is_none_or(|v| *v.get_ref() == Symmetry::Auto)
}

/// `solver.error_estimate`: whether the run estimates its discretization
/// error on coarser grids (default true).
pub(super) fn error_estimate(solver: Option<&SolverToml>) -> bool {
    solver.and_then(|s| s.error_estimate).unwrap_or(true)
}

pub(super) fn solver(
    ctx: &Ctx<'_>,
    s: Option<&SolverToml>,
) -> Result<(MethodChoice, Options), SceneError> {
    let mut options = Options::default();
    let Some(s) = s else {
        return Ok((MethodChoice::Auto, options));
    };
    let method = s
        .method
        .as_ref()
        .map_or(MethodChoice::Auto, |m| *m.get_ref());
    if let Some(p) = &s.max_pivots {
        options.max_pivots = Some(ctx.count(p, "solver.max_pivots", 1)?);
    }
    if let Some(t) = &s.certificate_tolerance {
        let field = "solver.certificate_tolerance";
        let v = ctx.positive(t, field)?;
        let v = ctx.ensure(
            v,
            v < 1.0,
            t.span(),
            field,
            "a relative tolerance must be < 1",
        )?;
        let why = "must be at least 2.2e-16 (the rounding of a double): residuals recomputed in \
                   doubles cannot be smaller than their rounding, so no solve could meet it";
        options.tolerances.certificate = ctx.ensure(v, v >= f64::EPSILON, t.span(), field, why)?;
    }
    if let Some(r) = &s.refinement_steps {
        options.refinement_steps = ctx.count(r, "solver.refinement_steps", 0)?;
    }
    Ok((method, options))
}

/// Bounds on the solver's knobs: refinement steps and the pivot limit.
pub(super) fn bounds(
    ctx: &Ctx<'_>,
    s: Option<&SolverToml>,
    points: usize,
) -> Result<(), SceneError> {
    let Some(s) = s else { return Ok(()) };
    if let Some(r) = &s.refinement_steps {
        let why = format!(
            "at most {MAX_REFINEMENT_STEPS} (each step is an N x N product; refinement settles in \
             one to three)"
        );
        let within = *r.get_ref() <= MAX_REFINEMENT_STEPS as i64;
        ctx.ensure(
            r.get_ref(),
            within,
            r.span(),
            "solver.refinement_steps",
            why,
        )?;
    }
    let bound = max_pivots_bound(points);
    if let Some(p) = &s.max_pivots {
        let why = format!(
            "at most 100 N + 10000 = {bound} for N = {points} points (a pivoting path that has not \
             ended by then is cycling; the defaults are about 40 N)"
        );
        let within = *p.get_ref() <= i64::try_from(bound).unwrap_or(i64::MAX);
        ctx.ensure(p.get_ref(), within, p.span(), "solver.max_pivots", why)?;
    }
    Ok(())
}
