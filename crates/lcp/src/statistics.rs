//! What a solve cost, attempt by attempt.
//!
//! A solve is a sequence of attempts chosen by the strategy
//! (the `strategy` module): a method on one tableau, possibly a fallback after a
//! breakdown, possibly a retry refactoring from the data after a failed
//! certificate. [`Statistics`] keeps the log of those attempts, each with its
//! own counts and [`Outcome`]; the totals (pivots, refactorizations, ...)
//! are derived from the log, never kept by hand.

use std::fmt;

use crate::error::LcpError;
use crate::options::{AnyMethod, Tableau};

/// Why an attempt was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Reason {
    /// The first attempt of the method asked for.
    First,
    /// The attempt before it broke down: the next one on the route (the
    /// general tableau after the symmetric one, Lemke's method after block
    /// pivoting).
    Fallback,
    /// The restricted-entry simplex stalled in phase 1 with non-negative
    /// extra unknowns: solved with them free, kept only when the answer
    /// certifies against the original bounds.
    RelaxedBounds,
    /// A numerical failure (a certificate that did not hold, a singular
    /// basis, a phase ending infeasible or unbounded, which rounding drift
    /// can fake): solved once more on the general tableau, refactoring from
    /// the original data every few pivots and refining harder.
    Retry,
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Reason::First => "first",
            Reason::Fallback => "fallback",
            Reason::RelaxedBounds => "relaxed-bounds",
            Reason::Retry => "retry",
        })
    }
}

/// How an attempt broke down (it returned no answer).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Breakdown {
    /// A principal pivot or block that a positive definite `M` would not
    /// give (a semidefinite influence matrix: a beam's clamped point), or a
    /// load that stopped rising with the approach.
    NotPositiveDefinite,
    /// The border's Schur complement `C_J M_JJ^{-1} B_J` (k x k) is singular
    /// on the active set: the contact set cannot carry the resultants.
    SingularBorder,
    /// No rigid position touches without interference under the given
    /// resultants (the first-contact linear program has no solution), so
    /// the parametric path has no start.
    NoStart,
    /// More steps of length zero in a row than the cap.
    DegenerateRun,
    /// A step, a value or a load that is not finite (data spanning more than
    /// double precision).
    NonFinite,
    /// Nothing limits the path and it never reaches its end.
    Ray,
    /// No admissible entering candidate is left.
    NoCandidate,
    /// The final active set does not solve the problem from the original data.
    ActiveSetRejected,
    /// Block pivoting's iteration cap was reached.
    IterationCap,
    /// The solve was cancelled ([`Cancel`](crate::Cancel)).
    Cancelled,
    /// The engine's own error (pivot limit, singular basis, infeasible,
    /// unbounded, ray termination).
    Error(Box<LcpError>),
}

impl fmt::Display for Breakdown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Breakdown::NotPositiveDefinite => {
                f.write_str("a pivot a positive definite matrix would not give")
            }
            Breakdown::SingularBorder => {
                f.write_str("the border's Schur complement is singular on the active set")
            }
            Breakdown::NoStart => f.write_str("no first contact: the path has no start"),
            Breakdown::DegenerateRun => f.write_str("too many steps of length zero in a row"),
            Breakdown::NonFinite => f.write_str("a step, value or load that is not finite"),
            Breakdown::Ray => f.write_str("nothing limits the path"),
            Breakdown::NoCandidate => f.write_str("no admissible candidate left"),
            Breakdown::ActiveSetRejected => {
                f.write_str("the final active set does not solve the problem from the data")
            }
            Breakdown::IterationCap => f.write_str("the iteration cap was reached"),
            Breakdown::Cancelled => f.write_str("cancelled"),
            Breakdown::Error(e) => write!(f, "{e}"),
        }
    }
}

/// How an attempt ended.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Outcome {
    /// Its answer is the solution returned.
    Returned,
    /// It answered, but its answer was not returned: its certificate's
    /// worst relative residual `worst` did not hold, or a later attempt's
    /// certified better.
    Rejected {
        /// The worst relative residual of its certificate.
        worst: f64,
    },
    /// It broke down without an answer.
    Breakdown(Breakdown),
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Returned => f.write_str("returned"),
            Outcome::Rejected { worst } => write!(f, "rejected (certificate {worst:.1e})"),
            Outcome::Breakdown(b) => write!(f, "breakdown: {b}"),
        }
    }
}

/// Declares [`Work`], one `usize` count a field, and beside each count
/// the accessor of [`Statistics`] that reads it from the log: `total`, the
/// sum over every attempt, or `of_returned`, the returned attempt's (0
/// when none was). One list, so that no count goes without its accessor.
macro_rules! counts {
    ($(
        $(#[doc = $doc:literal])+
        $name:ident => $how:ident $accessor:literal,
    )+) => {
        /// The counts of one attempt's work.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
        pub struct Work {
            $($(#[doc = $doc])+ pub $name: usize,)+
        }

        impl Statistics {
            $(
                #[doc = $accessor]
                pub fn $name(&self) -> usize {
                    self.$how(|w| w.$name)
                }
            )+
        }
    };
}

counts! {
    /// Pivots (basis exchanges; index exchanges for block pivoting).
    pivots => total "Pivots of every attempt.",
    /// Pivots whose step length was zero.
    degenerate_pivots => total "Degenerate pivots of every attempt.",
    /// Recomputations of the whole tableau from the original data.
    refactorizations => total "Refactorizations of every attempt.",
    /// Iterative-refinement steps of the final basic solution.
    refinement_steps => total "Refinement steps of every attempt.",
    /// Iterations: block pivoting's blocks, the conjugate gradient's steps
    /// (of every right-hand side of a linear system).
    iterations => total "Iterations of every attempt (blocks, conjugate-gradient steps).",
    /// Matrix factorizations (Cholesky factors of active blocks; 1 for a
    /// symmetric-tableau attempt, whose final solution is one Cholesky of
    /// the contact block; 0 for the general tableau; 1 for a linear
    /// system's Cholesky or LU).
    factorizations => total "Factorizations of every attempt.",
    /// Rows of the tableau pivoted on (0 for block pivoting).
    tableau_rows => of_returned "Rows of the tableau of the returned attempt (0 for block pivoting).",
    /// Columns of the tableau: non-basic unknowns plus the right-hand side.
    tableau_columns => of_returned "Columns of the tableau of the returned attempt.",
    /// Products `M x` of an operator (the conjugate gradient's, and its
    /// certificate's): the unit of a matrix-free solve's cost.
    products => total "Products `M x` of an operator by every attempt and its certificate \
        (0 for the methods that read `M`'s entries).",
    /// Applications of the operator's preconditioner (the preconditioned
    /// conjugate gradient's, one an iteration; each cheaper than a
    /// product: [`Preconditioner::precondition`](crate::Preconditioner::precondition)).
    preconditionings => total "Applications of an operator's preconditioner by every attempt.",
    /// Steps of the conjugate gradient after which `M z` was kept by
    /// adding columns of `M` ([`Operator::add_columns`](crate::Operator::add_columns):
    /// the points the step let in or clipped) instead of a product.
    corrections => total "Steps of every attempt whose `M z` was kept by columns instead of a product.",
    /// Columns of `M` added by those steps (each about
    /// `1 / Operator::columns_per_product` of a product's work).
    columns => total "Columns of `M` added by every attempt's corrections.",
}

/// One attempt of a solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Attempt {
    /// The method that ran (a complementarity problem's or a linear
    /// system's).
    pub method: AnyMethod,
    /// The tableau it ran on ([`Tableau::Symmetric`] or
    /// [`Tableau::General`]; `None` for the methods without one: block
    /// pivoting, the conjugate gradient, a linear system's factorizations).
    pub tableau: Option<Tableau>,
    /// Why it ran.
    pub reason: Reason,
    /// Its counts.
    pub work: Work,
    /// Wall-clock seconds of the attempt (and of its certificate).
    pub seconds: f64,
    /// How it ended.
    pub outcome: Outcome,
}

/// What a solve cost: the method asked for and the log of its attempts.
#[derive(Debug, Clone, PartialEq)]
pub struct Statistics {
    /// The method asked for (a linear system's: the first of its route).
    pub method: AnyMethod,
    /// Every attempt, in order.
    pub attempts: Vec<Attempt>,
    /// Wall-clock seconds of the whole solve (setup, attempts, certificates).
    pub seconds: f64,
}

impl Statistics {
    /// An empty log for `method`.
    pub(crate) fn new(method: AnyMethod) -> Self {
        Self {
            method,
            attempts: Vec::new(),
            seconds: 0.0,
        }
    }

    /// The sum of a count over every attempt.
    fn total(&self, count: impl Fn(&Work) -> usize) -> usize {
        self.attempts.iter().map(|a| count(&a.work)).sum()
    }

    /// A count of the returned attempt (0 when none was).
    fn of_returned(&self, count: impl Fn(&Work) -> usize) -> usize {
        self.returned().map_or(0, |a| count(&a.work))
    }

    /// The attempt whose answer was returned.
    pub fn returned(&self) -> Option<&Attempt> {
        self.attempts
            .iter()
            .find(|a| a.outcome == Outcome::Returned)
    }

    /// Whether the answer came from an attempt on the symmetric tableau.
    pub fn symmetric_tableau(&self) -> bool {
        self.returned()
            .is_some_and(|a| a.tableau == Some(Tableau::Symmetric))
    }

    /// Whether the answer came from another method than the one asked for
    /// (block pivoting finished by Lemke's method, a linear system's
    /// Cholesky factorization by its LU).
    pub fn fell_back(&self) -> bool {
        self.returned().is_some_and(|a| a.method != self.method)
    }

    /// Whether a retry ran (after a failed certificate or a numerical
    /// breakdown).
    pub fn retried(&self) -> bool {
        self.attempts.iter().any(|a| a.reason == Reason::Retry)
    }
}

impl fmt::Display for Attempt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let tableau = match self.tableau {
            Some(t) => format!(" ({} tableau)", t.name()),
            None => String::new(),
        };
        write!(
            f,
            "{}{tableau}, {}: {} pivots, {}",
            self.method, self.reason, self.work.pivots, self.outcome
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Method;

    fn attempt(
        method: Method,
        tableau: Option<Tableau>,
        pivots: usize,
        outcome: Outcome,
    ) -> Attempt {
        Attempt {
            method: method.into(),
            tableau,
            reason: Reason::First,
            work: Work {
                pivots,
                ..Work::default()
            },
            seconds: 0.0,
            outcome,
        }
    }

    #[test]
    fn totals_and_flags_derive_from_the_log() {
        let mut s = Statistics::new(Method::BlockPivoting.into());
        s.attempts.push(attempt(
            Method::BlockPivoting,
            None,
            7,
            Outcome::Breakdown(Breakdown::NotPositiveDefinite),
        ));
        let mut lemke = attempt(
            Method::Lemke,
            Some(Tableau::Symmetric),
            5,
            Outcome::Returned,
        );
        lemke.reason = Reason::Fallback;
        s.attempts.push(lemke);
        assert_eq!(s.pivots(), 12);
        assert!(s.fell_back() && s.symmetric_tableau() && !s.retried());
        assert_eq!(s.returned().unwrap().work.pivots, 5);
        assert_eq!(
            s.attempts[1].to_string(),
            "lemke (symmetric tableau), fallback: 5 pivots, returned"
        );
    }
}
