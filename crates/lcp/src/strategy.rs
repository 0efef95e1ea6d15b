//! The one owner of routing: which attempts a solve makes, in which order,
//! and which retry follows. The methods (`crate::methods`) only attempt.
//!
//! A solve of `method` with [`Options::tableau`] follows a route:
//!
//! | method | route (`Tableau::Auto`) |
//! |---|---|
//! | Lemke | symmetric tableau (a symmetric `M` with a positive diagonal, standard or bordered), then the general tableau |
//! | restricted simplex | symmetric tableau (a border of one row, `q >= 0`), then the general tableau; a general attempt that stalls in phase 1 with non-negative extra unknowns is followed by one with them free; with a border of several rows, Lemke's route after a stall |
//! | block pivoting | block pivoting, then Lemke's route (a principal block not positive definite, a singular border, the iteration cap) |
//!
//! `Tableau::Symmetric` keeps only the symmetric attempts (an error where
//! they do not apply), `Tableau::General` only the general ones. The first
//! attempt that answers is certified from the original data. Then, once:
//! when its certificate does not hold, or the route ended at a singular
//! basis or a phase ending infeasible or unbounded (which the tableau's
//! drift can fake), the method's general tableau solves again, refactoring
//! from the data every 10 pivots and refining harder ([`Options::retry`],
//! not on an explicit symmetric tableau, nor where the options already are
//! the retry's); of two answers the better certified is kept. An answer
//! whose certificate does not hold is [`LcpError::Inaccurate`]; without
//! an answer, the error of the route's last attempt that ended in one (which says
//! what is wrong) stands. Every attempt is in [`Statistics::attempts`].
//!
//! Programs with complementarity constraints
//! ([`ComplementaryProgram`]) take the route of
//! the restricted simplex's general tableau, with the same retry.
//!
//! A linear system `M X = R` ([`LinearSystem`]) has a
//! route of its own, with no retry:
//!
//! | `M` | route |
//! |---|---|
//! | dense | Cholesky factorization, then (where `M` is not numerically symmetric positive definite) LU factorization |
//! | operator | conjugate gradient (no fallback: `p · M p <= 0` and its iteration cap are errors) |
//!
//! and its answer is certified like the others: every column's residual
//! from products of the original data.

use std::time::Instant;

use faer::{Col, MatRef};

use crate::LcpError;
use crate::certificate::Certificate;
use crate::linear::{LinearSystem, Matrix};
use crate::methods::{
    Answer, Failure, LinearAnswer, LinearAttempted, NotApplicable, block, cholesky,
    conjugate_gradient, lemke_general, lemke_symmetric, lu, restricted_general,
    restricted_symmetric,
};
use crate::operator::OperatorLcp;
use crate::options::{AnyMethod, LinearMethod, Method, Options, Tableau};
use crate::problem::{BorderedLcp, BorderedLcpRef, Bound, Lcp, MixedBorder, MixedLcp, Problem};
use crate::program::ComplementaryProgram;
use crate::solution::{LcpSolution, LinearSolution, ProgramSolution};
use crate::statistics::{Attempt, Breakdown, Outcome, Reason, Statistics, Work};

/// One kind of attempt: a method on a tableau.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    LemkeSymmetric,
    LemkeGeneral,
    RestrictedSymmetric,
    RestrictedGeneral,
    BlockPivoting,
    /// The constrained conjugate gradient of an LCP.
    ConjugateGradient,
    /// A linear system's factorizations and its plain conjugate gradient.
    Cholesky,
    Lu,
    LinearConjugateGradient,
}

impl Kind {
    fn method(self) -> AnyMethod {
        match self {
            Kind::LemkeSymmetric | Kind::LemkeGeneral => Method::Lemke.into(),
            Kind::RestrictedSymmetric | Kind::RestrictedGeneral => Method::RestrictedSimplex.into(),
            Kind::BlockPivoting => Method::BlockPivoting.into(),
            Kind::ConjugateGradient => Method::ConjugateGradient.into(),
            Kind::Cholesky => LinearMethod::Cholesky.into(),
            Kind::Lu => LinearMethod::Lu.into(),
            Kind::LinearConjugateGradient => LinearMethod::ConjugateGradient.into(),
        }
    }

    fn tableau(self) -> Option<Tableau> {
        match self {
            Kind::LemkeSymmetric | Kind::RestrictedSymmetric => Some(Tableau::Symmetric),
            Kind::LemkeGeneral | Kind::RestrictedGeneral => Some(Tableau::General),
            Kind::BlockPivoting
            | Kind::ConjugateGradient
            | Kind::Cholesky
            | Kind::Lu
            | Kind::LinearConjugateGradient => None,
        }
    }

    /// The general-tableau attempt of a method (the retry's); `None` for
    /// the conjugate gradient and a linear system's methods, which have no
    /// tableau and no retry.
    fn general(method: AnyMethod) -> Option<Self> {
        match method {
            AnyMethod::Complementarity(Method::RestrictedSimplex) => Some(Kind::RestrictedGeneral),
            AnyMethod::Complementarity(Method::Lemke | Method::BlockPivoting) => {
                Some(Kind::LemkeGeneral)
            }
            AnyMethod::Complementarity(Method::ConjugateGradient) | AnyMethod::Linear(_) => None,
        }
    }

    fn name(self) -> String {
        match self.tableau() {
            Some(t) => format!("{} on the {} tableau", self.method(), t.name()),
            None => self.method().to_string(),
        }
    }
}

/// What the strategy drives: a problem whose attempts it can run and
/// certify.
trait Routed {
    /// A certified-to-be answer: the method's answer and what its
    /// certificate computed along with it.
    type Answer;

    /// Runs one attempt.
    fn attempt(
        &self,
        kind: Kind,
        options: &Options,
        relaxed: bool,
    ) -> Result<Self::Answer, Failure>;

    /// The answer's certificate, from the original data.
    fn certify(&self, answer: &mut Self::Answer, tolerance: f64) -> Certificate;

    /// The answer's counts.
    fn work(answer: &Self::Answer) -> Work;

    /// Whether an attempt that stalled in phase 1 may be repeated with the
    /// extra unknowns free (only a mixed form's non-negative ones).
    fn relaxable(&self) -> bool {
        false
    }

    /// Number of unknowns (for error messages).
    fn size(&self) -> usize;

    /// What to do when the route broke down without an answer or an
    /// engine error ([`LcpError::BrokeDown`]'s advice).
    fn advice(&self) -> &'static str {
        crate::TABLEAU_ADVICE
    }
}

/// An LCP's answer with `w`, filled by its certificate.
struct Solved {
    answer: Answer,
    w: Col<f64>,
}

impl From<Answer> for Solved {
    fn from(answer: Answer) -> Self {
        Self {
            answer,
            w: Col::zeros(0),
        }
    }
}

impl Solved {
    /// Keeps `w` of a certificate's `(certificate, w)`; returns the certificate.
    fn keep_w(&mut self, (certificate, w): (Certificate, Col<f64>)) -> Certificate {
        self.w = w;
        certificate
    }

    /// The solution: this answer with its certificate and statistics.
    fn solution(self, certificate: Certificate, statistics: Statistics) -> LcpSolution {
        let Solved { answer, w } = self;
        LcpSolution {
            z: answer.z,
            w,
            u: answer.u,
            basic: answer.basic,
            certificate,
            statistics,
        }
    }
}

impl Routed for Problem<'_> {
    type Answer = Solved;

    fn attempt(&self, kind: Kind, options: &Options, relaxed: bool) -> Result<Solved, Failure> {
        let answer = match kind {
            Kind::LemkeSymmetric => lemke_symmetric::attempt(self, options),
            Kind::LemkeGeneral => lemke_general::attempt(self, options),
            Kind::RestrictedSymmetric => restricted_symmetric::attempt(self, options),
            Kind::RestrictedGeneral => restricted_general::attempt(self, options, relaxed),
            Kind::BlockPivoting => block::attempt(self, options),
            Kind::ConjugateGradient => match conjugate_gradient::applies(self) {
                Ok(form) => conjugate_gradient::attempt(&form, options),
                Err(e) => Err(Failure::error(
                    LcpError::Unsupported {
                        method: "the conjugate gradient",
                        reason: e.reason,
                    },
                    Work::default(),
                )),
            },
            Kind::Cholesky | Kind::Lu | Kind::LinearConjugateGradient => {
                Err(foreign(kind, LINEAR_ONLY))
            }
        };
        answer.map(Solved::from)
    }

    fn certify(&self, solved: &mut Solved, tolerance: f64) -> Certificate {
        let (z, u) = (solved.answer.z.as_ref(), solved.answer.u.as_ref());
        solved.keep_w(self.mixed.certify(z, u, tolerance))
    }

    fn work(solved: &Solved) -> Work {
        solved.answer.work
    }

    fn relaxable(&self) -> bool {
        self.mixed.bounds.contains(&Bound::NonNegative)
    }

    fn size(&self) -> usize {
        Problem::size(self)
    }
}

impl Routed for ComplementaryProgram {
    type Answer = restricted_general::ProgramAnswer;

    fn attempt(
        &self,
        _kind: Kind,
        options: &Options,
        _relaxed: bool,
    ) -> Result<Self::Answer, Failure> {
        restricted_general::attempt_program(self, options)
    }

    fn certify(&self, answer: &mut Self::Answer, tolerance: f64) -> Certificate {
        let x = Col::from_fn(self.unknowns(), |j| answer.x[j]);
        ComplementaryProgram::certify(self, x.as_ref(), tolerance)
    }

    fn work(answer: &Self::Answer) -> Work {
        answer.work
    }

    fn size(&self) -> usize {
        self.rows()
    }
}

impl Routed for OperatorLcp<'_> {
    type Answer = Solved;

    fn attempt(&self, _kind: Kind, options: &Options, _relaxed: bool) -> Result<Solved, Failure> {
        conjugate_gradient::attempt(self, options).map(Solved::from)
    }

    fn certify(&self, solved: &mut Solved, tolerance: f64) -> Certificate {
        let (z, lambda) = (&solved.answer.z, &solved.answer.u);
        let (certificate, w, products) = OperatorLcp::certify(self, z, lambda, tolerance);
        solved.answer.work.products += products;
        solved.keep_w((certificate, w))
    }

    fn work(solved: &Solved) -> Work {
        solved.answer.work
    }

    fn size(&self) -> usize {
        OperatorLcp::size(self)
    }
}

impl Routed for LinearSystem<'_> {
    type Answer = LinearAnswer;

    fn attempt(&self, kind: Kind, options: &Options, _relaxed: bool) -> LinearAttempted {
        // A dense factorization's parallelism, by M's size.
        let par = |m: MatRef<'_, f64>| options.par(m.nrows(), m.nrows());
        match (kind, self.matrix) {
            (Kind::Cholesky, Matrix::Dense(m)) => cholesky::attempt(m, self.rhs, par(m)),
            (Kind::Lu, Matrix::Dense(m)) => lu::attempt(m, self.rhs, par(m)),
            (Kind::LinearConjugateGradient, matrix) => {
                conjugate_gradient::attempt_linear(matrix.operator(), self.rhs, options)
            }
            _ => Err(foreign(
                kind,
                "a linear system is solved by a factorization of its dense M or by the conjugate gradient",
            )),
        }
    }

    fn certify(&self, answer: &mut LinearAnswer, tolerance: f64) -> Certificate {
        if let Matrix::Operator(_) = self.matrix {
            // M x and |M| |x| for every column.
            answer.work.products += 2 * self.columns();
        }
        LinearSystem::certify(self, answer.x.as_ref(), tolerance)
    }

    fn work(answer: &LinearAnswer) -> Work {
        answer.work
    }

    fn size(&self) -> usize {
        LinearSystem::size(self)
    }

    fn advice(&self) -> &'static str {
        "the conjugate gradient needs a symmetric positive definite M: give M densely \
         (as a matrix, not by its products), whose LU factorization takes any nonsingular M"
    }
}

/// Why a factorization of a linear system does not solve a complementarity
/// problem.
const LINEAR_ONLY: &str = "it solves a linear system (`LinearSystem`), not a complementarity \
     problem: use Lemke's method, the restricted-entry simplex, block pivoting or the conjugate gradient";

/// The failure of an attempt of `kind` on a problem it does not solve (no
/// route makes one; a guard).
fn foreign(kind: Kind, reason: &str) -> Failure {
    let error = LcpError::Unsupported {
        method: kind.method().described(),
        reason: reason.into(),
    };
    Failure::error(error, Work::default())
}

/// The attempts of `method` on `problem` before any retry, in order.
fn route(problem: &Problem<'_>, method: Method, options: &Options) -> Result<Vec<Kind>, LcpError> {
    let unsupported = |kind: Kind, e: NotApplicable| LcpError::Unsupported {
        method: kind.method().described(),
        reason: e.reason,
    };
    let tableau_route = |symmetric: Kind, general: Kind| -> Result<Vec<Kind>, LcpError> {
        let sym = match symmetric {
            Kind::LemkeSymmetric => lemke_symmetric::applies(problem).map(|_| ()),
            _ => restricted_symmetric::applies(problem),
        };
        let general_ok = match general {
            Kind::LemkeGeneral => lemke_general::applies(problem),
            _ => Ok(()),
        };
        match options.tableau {
            Tableau::Symmetric => sym
                .map(|()| vec![symmetric])
                .map_err(|e| unsupported(symmetric, e)),
            Tableau::General => general_ok
                .map(|()| vec![general])
                .map_err(|e| unsupported(general, e)),
            Tableau::Auto => {
                general_ok.map_err(|e| unsupported(general, e))?;
                Ok(sym
                    .is_ok()
                    .then_some(symmetric)
                    .into_iter()
                    .chain([general])
                    .collect())
            }
        }
    };
    match method {
        Method::Lemke => tableau_route(Kind::LemkeSymmetric, Kind::LemkeGeneral),
        Method::RestrictedSimplex => {
            let mut route = tableau_route(Kind::RestrictedSymmetric, Kind::RestrictedGeneral)?;
            // The restricted-entry rule's theory is for one free multiplier
            // (Wolfe's short form): with a border of several rows its phase
            // 1 can stall, and Lemke's method finishes.
            if problem.border.is_some_and(|b| b.columns.ncols() >= 2) {
                route.extend(tableau_route(Kind::LemkeSymmetric, Kind::LemkeGeneral)?);
            }
            Ok(route)
        }
        Method::BlockPivoting => {
            block::applies(problem).map_err(|e| unsupported(Kind::BlockPivoting, e))?;
            // The tableau option chooses the fallback's tableau; block
            // pivoting itself has none, so a fallback the chosen tableau
            // cannot take is left out rather than refusing the method.
            let mut route = vec![Kind::BlockPivoting];
            route.extend(
                tableau_route(Kind::LemkeSymmetric, Kind::LemkeGeneral).unwrap_or_default(),
            );
            Ok(route)
        }
        // No tableau and no fallback: the method asked for is the answer's.
        Method::ConjugateGradient => conjugate_gradient::applies(problem)
            .map(|_| vec![Kind::ConjugateGradient])
            .map_err(|e| unsupported(Kind::ConjugateGradient, e)),
    }
}

/// A certified answer and its attempt's place in the log.
struct Kept<A> {
    answer: A,
    certificate: Certificate,
    index: usize,
}

/// The solve's progress: the log and the best answer so far.
struct Ladder<'r, R: Routed> {
    problem: &'r R,
    options: &'r Options,
    statistics: Statistics,
    best: Option<Kept<R::Answer>>,
    /// The engine error of the route's last attempt that ended in one (a
    /// fallback's or the first's, never a retry's), reported when nothing
    /// answers: it says what is wrong with the problem.
    error: Option<LcpError>,
    /// The kind of the last attempt.
    last: Option<Kind>,
}

impl<'r, R: Routed> Ladder<'r, R> {
    /// Runs and logs one attempt; keeps its answer when it certifies better
    /// than the best so far. Returns whether an answer now certifies.
    fn run(&mut self, kind: Kind, reason: Reason, options: &Options, relaxed: bool) -> bool {
        // A cancelled solve makes no further attempt (`finish` says why).
        if crate::cancel::requested() {
            return self.certified();
        }
        let start = Instant::now();
        let result = self.problem.attempt(kind, options, relaxed);
        let index = self.statistics.attempts.len();
        let (work, outcome) = match result {
            Ok(mut answer) => {
                let certificate = self
                    .problem
                    .certify(&mut answer, self.options.tolerances.certificate);
                let worst = certificate.worst();
                let work = R::work(&answer);
                // A relaxed attempt's answer counts only when it certifies
                // against the original bounds; otherwise the stall stands.
                let admissible = reason != Reason::RelaxedBounds || certificate.holds();
                let better = admissible
                    && self
                        .best
                        .as_ref()
                        .is_none_or(|b| worst < b.certificate.worst());
                if better {
                    if let Some(old) = &self.best {
                        let previous = old.certificate.worst();
                        self.statistics.attempts[old.index].outcome =
                            Outcome::Rejected { worst: previous };
                    }
                    self.best = Some(Kept {
                        answer,
                        certificate,
                        index,
                    });
                    (work, Outcome::Returned)
                } else {
                    (work, Outcome::Rejected { worst })
                }
            }
            Err(Failure { breakdown, work }) => {
                if let Breakdown::Error(e) = &breakdown
                    && reason != Reason::Retry
                    && reason != Reason::RelaxedBounds
                {
                    self.error = Some((**e).clone());
                }
                (work, Outcome::Breakdown(breakdown))
            }
        };
        self.statistics.attempts.push(Attempt {
            method: kind.method(),
            tableau: kind.tableau(),
            reason,
            work,
            seconds: start.elapsed().as_secs_f64(),
            outcome,
        });
        self.last = Some(kind);
        self.certified()
    }

    fn certified(&self) -> bool {
        self.best.as_ref().is_some_and(|b| b.certificate.holds())
    }

    /// The route, until an attempt answers; a general attempt that stalls
    /// in phase 1 with non-negative extra unknowns is repeated with them free.
    fn follow(&mut self, route: &[Kind]) {
        for (i, &kind) in route.iter().enumerate() {
            let reason = if i == 0 {
                Reason::First
            } else {
                Reason::Fallback
            };
            self.run(kind, reason, self.options, false);
            if self.best.is_some() {
                return;
            }
            let stalled = matches!(self.error, Some(LcpError::Infeasible { .. }))
                && kind == Kind::RestrictedGeneral
                && self.problem.relaxable();
            if stalled {
                self.run(kind, Reason::RelaxedBounds, self.options, true);
                if self.certified() {
                    return;
                }
            }
        }
    }

    /// The one retry after a numerical failure (see the module documentation).
    fn retry(&mut self, method: AnyMethod) {
        let drift = matches!(
            self.error,
            Some(
                LcpError::SingularBasis { .. }
                    | LcpError::Infeasible { .. }
                    | LcpError::Unbounded { .. }
            )
        );
        let failed = match &self.best {
            Some(kept) => !kept.certificate.holds(),
            None => drift,
        };
        if !failed || self.options.tableau == Tableau::Symmetric {
            return;
        }
        let Some(kind) = Kind::general(method) else {
            return;
        };
        let options = match self.options.retry() {
            Some(retry) => retry,
            // Options that already are the retry's: only a different
            // attempt is worth running.
            None if self.last != Some(kind) => self.options.clone(),
            None => return,
        };
        self.run(kind, Reason::Retry, &options, false);
    }

    /// The certified answer, or the error that says why there is none.
    fn finish(
        mut self,
        started: Instant,
    ) -> Result<(R::Answer, Certificate, Statistics), LcpError> {
        self.statistics.seconds = started.elapsed().as_secs_f64();
        if !self.certified() && crate::cancel::requested() {
            return Err(LcpError::Cancelled);
        }
        match self.best {
            Some(kept) if kept.certificate.holds() => {
                Ok((kept.answer, kept.certificate, self.statistics))
            }
            Some(kept) => {
                if let Some(a) = self.statistics.attempts.get_mut(kept.index) {
                    a.outcome = Outcome::Rejected {
                        worst: kept.certificate.worst(),
                    };
                }
                Err(LcpError::Inaccurate {
                    size: self.problem.size(),
                    pivots: self.statistics.pivots(),
                    iterations: self.statistics.iterations(),
                    certificate: Box::new(kept.certificate),
                })
            }
            None => Err(self.error.unwrap_or_else(|| {
                let last = self.statistics.attempts.last();
                LcpError::BrokeDown {
                    method: self.last.map_or_else(String::new, Kind::name),
                    size: self.problem.size(),
                    pivots: self.statistics.pivots(),
                    iterations: self.statistics.iterations(),
                    reason: last.map_or_else(String::new, |a| match &a.outcome {
                        Outcome::Breakdown(b) => b.to_string(),
                        other => other.to_string(),
                    }),
                    advice: self.problem.advice(),
                }
            })),
        }
    }
}

/// Runs `route` for `method`, then the retry, on `problem`.
fn solve_routed<R: Routed>(
    problem: &R,
    method: AnyMethod,
    route: &[Kind],
    options: &Options,
) -> Result<(R::Answer, Certificate, Statistics), LcpError> {
    let started = Instant::now();
    let mut ladder = Ladder {
        problem,
        options,
        statistics: Statistics::new(method),
        best: None,
        error: None,
        last: None,
    };
    ladder.follow(route);
    ladder.retry(method);
    ladder.finish(started)
}

/// Solves a prepared problem by `method`.
fn solve_problem(
    problem: &Problem<'_>,
    method: Method,
    options: &Options,
) -> Result<LcpSolution, LcpError> {
    options.validate(lemke_general::split_size(&problem.mixed))?;
    let route = route(problem, method, options)?;
    let (solved, certificate, statistics) = solve_routed(problem, method.into(), &route, options)?;
    Ok(solved.solution(certificate, statistics))
}

impl BorderedLcpRef<'_> {
    /// Solves with `method`; the solution carries its certificate from the
    /// original data, and an uncertified solution is an error
    /// ([`LcpError::Inaccurate`]). See the crate documentation for the
    /// route each method takes.
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        let parts = MixedBorder::of(self);
        solve_problem(&Problem::bordered(self, &parts), method, options)
    }
}

impl BorderedLcp {
    /// Solves with `method` (see [`BorderedLcpRef::solve`]).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        self.as_ref().solve(method, options)
    }
}

impl Lcp {
    /// Solves with `method` (see [`BorderedLcpRef::solve`]).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        self.as_ref().solve(method, options)
    }
}

impl MixedLcp {
    /// Solves with `method` (see [`BorderedLcpRef::solve`]): the general
    /// tableau or block pivoting (a mixed form has no symmetric tableau;
    /// write a symmetric border as a [`BorderedLcp`] for it).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        solve_problem(&Problem::mixed(self.view()), method, options)
    }
}

impl OperatorLcp<'_> {
    /// Solves with `method`, which must be [`Method::ConjugateGradient`]
    /// (the pivoting methods need `M`'s entries); the certificate is
    /// computed from products of the original operator and the original
    /// data, and an uncertified answer is an error
    /// ([`LcpError::Inaccurate`]).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        options.validate(0)?;
        if method != Method::ConjugateGradient {
            return Err(LcpError::Unsupported {
                method: method.described(),
                reason: "this problem's M is an operator (its products only): use the conjugate gradient".into(),
            });
        }
        let route = [Kind::ConjugateGradient];
        let (solved, certificate, statistics) = solve_routed(self, method.into(), &route, options)?;
        Ok(solved.solution(certificate, statistics))
    }
}

impl LinearSystem<'_> {
    /// Solves `M X = R`, certified: a dense `M` by its Cholesky
    /// factorization, and where `M` is not numerically symmetric positive
    /// definite by an LU (a fallback in the statistics' log); an operator
    /// by the conjugate gradient, whose
    /// breakdown (`p · M p <= 0`: [`LcpError::BrokeDown`]) and iteration cap
    /// ([`LcpError::IterationLimit`]) are errors. The answer's residual is
    /// recomputed from products of the original data; one above the
    /// certificate's tolerance is [`LcpError::Inaccurate`].
    pub fn solve(&self, options: &Options) -> Result<LinearSolution, LcpError> {
        options.validate(0)?;
        let route: &[Kind] = match self.matrix {
            Matrix::Dense(_) => &[Kind::Cholesky, Kind::Lu],
            Matrix::Operator(_) => &[Kind::LinearConjugateGradient],
        };
        let (answer, certificate, statistics) =
            solve_routed(self, route[0].method(), route, options)?;
        Ok(LinearSolution {
            x: answer.x,
            residual: certificate.equality,
            statistics,
        })
    }
}

impl ComplementaryProgram {
    /// Solves by the restricted-entry simplex: phase 1 finds a feasible
    /// complementary basic solution, phase 2 (when there is an objective)
    /// lowers `c^T x` while keeping complementarity. Phase 2 ends at a point
    /// no admissible pivot improves: a local optimum of the complementarity-
    /// constrained program, not necessarily a global one. The retry after a
    /// numerical failure is the strategy's (see the module documentation).
    pub fn solve(&self, options: &Options) -> Result<ProgramSolution, LcpError> {
        options.validate(0)?;
        if options.tableau == Tableau::Symmetric {
            return Err(LcpError::Unsupported {
                method: "the restricted-entry simplex",
                reason: "a program with complementarity constraints has no symmetric tableau: use Tableau::Auto or Tableau::General".into(),
            });
        }
        let route = [Kind::RestrictedGeneral];
        let options = Options {
            tableau: Tableau::General,
            ..options.clone()
        };
        let (answer, certificate, statistics) =
            solve_routed(self, Method::RestrictedSimplex.into(), &route, &options)?;
        let x = Col::from_fn(self.unknowns(), |j| answer.x[j]);
        let objective = self.objective(x.as_ref());
        Ok(ProgramSolution {
            x,
            objective,
            basis: answer.basis,
            certificate,
            statistics,
        })
    }
}

#[cfg(test)]
mod tests;
