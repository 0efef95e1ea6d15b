//! `[solver]`: the method (or "auto"), its limits and tolerance, and
//! whether a mirror-symmetric problem is folded.

use elcon_analysis::{Method, Options};

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::{SolverMethod, SolverToml, Symmetry};
use crate::storage::MethodChoice;

/// `solver.symmetry`: "auto" (fold when symmetric, the default) or "none".
pub(super) fn symmetry(solver: Option<&SolverToml>) -> bool {
    solver
        .and_then(|s| s.symmetry.as_ref())
        .is_none_or(|v| *v.get_ref() == Symmetry::Auto)
}

pub(super) fn solver(
    ctx: &Ctx<'_>,
    s: Option<&SolverToml>,
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
