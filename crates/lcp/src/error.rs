//! Errors of the pivoting engine: what went wrong, at which size and step, and
//! what the caller can do about it.

use crate::certificate::Certificate;
use elcon_num::Num;

/// Everything that can stop a solve of the engine.
///
/// Every message states the problem size and, where it applies, the pivot
/// step at which the engine stopped, so a failure can be reproduced.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LcpError {
    /// An input array has the wrong size.
    #[error("`{field}` has {found} {unit}, expected {expected}")]
    DimensionMismatch {
        /// The argument or field that is mis-sized.
        field: &'static str,
        /// The size the other inputs imply.
        expected: usize,
        /// The size that was given.
        found: usize,
        /// What is counted ("rows", "columns", "entries").
        unit: &'static str,
    },
    /// An input holds NaN or an infinity.
    #[error("`{field}` has a non-finite entry ({}) at index {index}", Num(*value))]
    NonFinite {
        /// The argument or field.
        field: &'static str,
        /// Flat index (row-major `i * ncols + j` for matrices) of the first bad entry.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// The columns of a border are linearly dependent: each free unknown
    /// must move the gaps differently (a rigid-body mode given twice).
    #[error(
        "column {column} of `{field}` depends linearly on the ones before it: each free unknown must move the gaps differently"
    )]
    RankDeficient {
        /// The argument.
        field: &'static str,
        /// The first dependent column.
        column: usize,
    },
    /// The problem has no unknowns.
    #[error("the problem is empty: `{field}` has size 0")]
    Empty {
        /// The argument that is empty.
        field: &'static str,
    },
    /// An option is out of its range.
    #[error("option `{field}` = {value}: {reason}")]
    InvalidOption {
        /// The option's name.
        field: &'static str,
        /// The given value, printed (a number in its shortest form, as
        /// [`Num`] shows it).
        value: String,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// A method was asked for a problem form it does not handle.
    #[error("{method} cannot solve this problem: {reason}")]
    Unsupported {
        /// The method asked for.
        method: &'static str,
        /// What in the problem it does not support, and what to use instead.
        reason: String,
    },
    /// Lemke's method ended on a secondary ray: for a copositive-plus matrix
    /// (e.g. positive semidefinite) this proves the problem has no solution.
    #[error(
        "ray termination at pivot {pivot} (size {size}): the entering variable `{entering}` is unbounded; \
         the problem has no solution if its matrix is copositive-plus (e.g. positive semidefinite)"
    )]
    RayTermination {
        /// Number of unknowns.
        size: usize,
        /// Pivot step at which the ray was found.
        pivot: usize,
        /// Name of the entering variable.
        entering: String,
    },
    /// Phase 1 of the restricted-entry simplex stopped with a positive
    /// artificial sum and no admissible entering variable.
    #[error(
        "no feasible complementary solution found (size {size}, after {pivot} pivots): \
         the artificial sum stays at {residual:.3e} relative and no admissible variable can enter"
    )]
    Infeasible {
        /// Number of rows of the tableau.
        size: usize,
        /// Pivot step at which the method stopped.
        pivot: usize,
        /// Remaining sum of artificial variables, relative to the right-hand side's scale.
        residual: f64,
    },
    /// The phase-2 objective decreases without bound along an admissible edge.
    #[error(
        "the objective is unbounded below along `{entering}` (size {size}, pivot {pivot}): add a bound on it"
    )]
    Unbounded {
        /// Number of rows of the tableau.
        size: usize,
        /// Pivot step.
        pivot: usize,
        /// The variable along which the objective decreases without bound.
        entering: String,
    },
    /// The caller's pivot limit was reached before a solution.
    #[error("pivot limit {limit} reached (size {size}); raise `max_pivots` or check the problem")]
    PivotLimit {
        /// Number of unknowns or rows.
        size: usize,
        /// The limit that was reached.
        limit: usize,
    },
    /// A basis met during the solve is numerically singular.
    #[error(
        "the basis at pivot {pivot} is numerically singular (size {size}, smallest/largest LU pivot {ratio:.2e}); \
         the problem is too ill-conditioned for the dense tableau"
    )]
    SingularBasis {
        /// Number of rows.
        size: usize,
        /// Pivot step.
        pivot: usize,
        /// Smallest over largest magnitude of U's diagonal.
        ratio: f64,
    },
    /// The arithmetic broke down: a value overflowed or became NaN (data
    /// spanning more than double precision can hold).
    #[error("numerical breakdown at pivot {pivot} (size {size}): {reason}")]
    NumericalBreakdown {
        /// Number of unknowns or rows.
        size: usize,
        /// Pivot step.
        pivot: usize,
        /// What broke, and what to do.
        reason: &'static str,
    },
    /// The only attempt allowed (an explicit tableau, the conjugate
    /// gradient of a problem given by its products) broke down without an
    /// answer.
    #[error(
        "{method} broke down after {} (size {size}): {reason}; {advice}",
        Spent { pivots: *pivots, iterations: *iterations }
    )]
    BrokeDown {
        /// The method and tableau that ran.
        method: String,
        /// Number of unknowns.
        size: usize,
        /// Pivots spent (over all attempts).
        pivots: usize,
        /// Conjugate-gradient iterations spent (over all attempts).
        iterations: usize,
        /// What happened.
        reason: String,
        /// What to do: let the engine choose the tableau, or use another
        /// method (for a linear system, give `M` densely).
        advice: &'static str,
    },
    /// The conjugate gradient of a linear system reached its iteration cap
    /// before its residual met the target: it returns no unconverged answer.
    #[error(
        "the conjugate gradient reached its iteration limit {limit} on right-hand side {column} \
         (size {size}) at a relative residual {residual:.2e}: raise `max_pivots` (its iteration cap) \
         or give M densely (a factorization needs no iterations)"
    )]
    IterationLimit {
        /// Number of unknowns.
        size: usize,
        /// The right-hand side (column of `R`) that did not converge.
        column: usize,
        /// The cap that was reached ([`Options::max_pivots`](crate::Options::max_pivots)).
        limit: usize,
        /// Its relative residual when the cap was reached.
        residual: f64,
    },
    /// The conjugate gradient of an LCP reached its iteration cap before
    /// its residuals met its stopping rule: it returns no unconverged
    /// answer.
    #[error(
        "iteration limit {limit} of the conjugate gradient reached (size {size}) at a worst relative \
         residual {residual:.3e} (tolerance {tolerance:.1e}); raise `max_pivots` (its iteration cap) \
         or check the problem"
    )]
    ConjugateGradientLimit {
        /// Number of unknowns.
        size: usize,
        /// The cap that was reached ([`Options::max_pivots`](crate::Options::max_pivots)).
        limit: usize,
        /// The worst of the residuals the certificate measures, relative to
        /// their scale, at the last iterate.
        residual: f64,
        /// The certificate's tolerance.
        tolerance: f64,
    },
    /// The final solution does not satisfy its certificate to the tolerance
    /// even after refactorization and refinement: it is not returned as solved.
    #[error(
        "the solution's certificate does not hold after {} (size {size}): worst relative residual \
         {:.3e} > tolerance {:.1e} ({certificate})",
        Spent { pivots: *pivots, iterations: *iterations },
        certificate.worst(),
        certificate.tolerance
    )]
    Inaccurate {
        /// Number of unknowns.
        size: usize,
        /// Pivots spent (over all attempts).
        pivots: usize,
        /// Conjugate-gradient iterations spent (over all attempts).
        iterations: usize,
        /// The certificate that failed.
        certificate: Box<Certificate>,
    },
    /// A matrix of the method (a tableau, a factor) could not be allocated:
    /// the problem is too big for the memory this process may use.
    #[error(
        "could not allocate {bytes} bytes for {what}: the problem is too big for the memory \
         available; use block pivoting (fewer matrices), fold by symmetry, a coarser grid, or \
         the matrix-free conjugate gradient"
    )]
    AllocationFailed {
        /// What the matrix was for.
        what: &'static str,
        /// The size asked for (saturated at usize::MAX on overflow).
        bytes: usize,
    },
    /// The solve was cancelled through its [`Cancel`](crate::Cancel) token
    /// (an interrupt: Ctrl-C, SIGTERM) before it found an answer.
    #[error("the solve was cancelled (interrupted) before it finished")]
    Cancelled,
}

/// What a complementarity problem's [`LcpError::BrokeDown`] advises: an
/// explicit tableau is the one attempt; the automatic choice retries on
/// another, and another method may not break down at all.
pub const TABLEAU_ADVICE: &str =
    "let the engine choose the tableau (the automatic choice, the default) or use another method";

/// The work a failed solve spent, as a message names it: pivots for the
/// pivoting methods, iterations for the conjugate gradient, both when a
/// solve tried both.
struct Spent {
    pivots: usize,
    iterations: usize,
}

impl std::fmt::Display for Spent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let count = |n: usize, what: &str| {
            let s = if n == 1 { "" } else { "s" };
            format!("{n} {what}{s}")
        };
        match (self.pivots, self.iterations) {
            (p, 0) => write!(f, "{}", count(p, "pivot")),
            (0, i) => write!(f, "{}", count(i, "iteration")),
            (p, i) => write!(f, "{} and {}", count(p, "pivot"), count(i, "iteration")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inaccurate(pivots: usize, iterations: usize) -> String {
        LcpError::Inaccurate {
            size: 3,
            pivots,
            iterations,
            certificate: Box::new(Certificate {
                min_z: 0.0,
                min_w: -0.5,
                min_u: 0.0,
                complementarity: 0.0,
                equality: 0.0,
                z_scale: 1.0,
                w_scale: 1.0,
                tolerance: 1e-12,
                finite: true,
            }),
        }
        .to_string()
    }

    #[test]
    fn a_breakdown_names_the_work_its_method_spent() {
        let broke = |pivots, iterations| {
            LcpError::BrokeDown {
                method: "conjugate-gradient".into(),
                size: 4,
                pivots,
                iterations,
                reason: "a direction of non-positive curvature".into(),
                advice: crate::TABLEAU_ADVICE,
            }
            .to_string()
        };
        let cg = broke(0, 3);
        assert!(cg.contains("after 3 iterations (size 4)"), "{cg}");
        assert!(!cg.contains("::") && !cg.contains('`'), "{cg}");
        assert!(broke(2, 0).contains("after 2 pivots (size 4)"));
    }

    #[test]
    fn an_inaccurate_answer_names_the_work_its_method_spent() {
        assert!(inaccurate(7, 0).contains("after 7 pivots (size 3)"));
        assert!(inaccurate(0, 40).contains("after 40 iterations (size 3)"));
        assert!(inaccurate(7, 40).contains("after 7 pivots and 40 iterations (size 3)"));
        assert!(inaccurate(1, 1).contains("after 1 pivot and 1 iteration (size 3)"));
    }
}
