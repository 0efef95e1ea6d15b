//! `[solver]`: the method (or "auto"), its limits and tolerance,
//! whether a mirror-symmetric problem is folded, and whether the run
//! estimates its discretization error.

use elcon_analysis::{Method, Options};

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::{SolverMethod, SolverToml, Symmetry};

/// The method asked for in `solver.method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodChoice {
    /// `"auto"`: the method of the storage elcon-analysis picks
    /// (`elcon_analysis::Storage`): block pivoting on a dense or folded S,
    /// the conjugate gradient matrix-free above
    /// `elcon_analysis::AUTO_DENSE_LIMIT` unknowns on a lattice.
    Auto,
    /// A method by name.
    Given(Method),
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
        .map_or(MethodChoice::Auto, |m| choice(*m.get_ref()));
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
        if v < f64::EPSILON {
            return Err(ctx.invalid(
                t.span(),
                "solver.certificate_tolerance",
                v,
                "must be at least 2.2e-16 (the rounding of a double): residuals recomputed \
                 in doubles cannot be smaller than their rounding, so no solve could meet it",
            ));
        }
        options.tolerances.certificate = v;
    }
    if let Some(r) = &s.refinement_steps {
        options.refinement_steps = ctx.count(r, "solver.refinement_steps", 0)?;
    }
    Ok((method, options))
}

/// The engine's method a `solver.method` name stands for.
fn choice(method: SolverMethod) -> MethodChoice {
    match method {
        SolverMethod::Auto => MethodChoice::Auto,
        SolverMethod::RestrictedSimplex => MethodChoice::Given(Method::RestrictedSimplex),
        SolverMethod::Lemke => MethodChoice::Given(Method::Lemke),
        SolverMethod::BlockPivoting => MethodChoice::Given(Method::BlockPivoting),
        SolverMethod::ConjugateGradient => MethodChoice::Given(Method::ConjugateGradient),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_method_name_is_the_engines_name_for_it() {
        for m in [
            SolverMethod::RestrictedSimplex,
            SolverMethod::Lemke,
            SolverMethod::BlockPivoting,
            SolverMethod::ConjugateGradient,
        ] {
            assert_eq!(
                choice(m),
                MethodChoice::Given(m.name().parse::<Method>().unwrap())
            );
        }
        assert_eq!(choice(SolverMethod::Auto), MethodChoice::Auto);
    }
}
