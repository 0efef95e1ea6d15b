//! The methods. Each one only attempts: it takes a prepared problem
//! ([`Problem`]) and the options, and returns its raw answer ([`Answer`],
//! before any certificate) or a typed breakdown ([`Failure`]), with the
//! counts of its work either way. No method calls another: which attempts
//! are made, in which order, and which retries follow is the strategy's
//! (the `strategy` module).
//!
//! - [`lemke_symmetric`]: Lemke's path as parametric principal pivoting on
//!   the symmetric tableau (standard LCPs and borders of k rows);
//! - [`lemke_general`]: Lemke's method with a covering vector on the
//!   general tableau (any LCP, mixed forms with free unknowns split);
//! - [`restricted_symmetric`]: the restricted-entry simplex on the
//!   symmetric tableau (a border of one row, no initial interference);
//! - [`restricted_general`]: the restricted-entry simplex on the general
//!   tableau (any mixed form, and programs with complementarity
//!   constraints);
//! - [`block`]: block principal pivoting on Cholesky factors of active blocks;
//! - [`conjugate_gradient`]: the constrained conjugate gradient (products
//!   `M x` only: dense problems and matrix-free ones alike), and the plain
//!   one of a linear system given by its products;
//! - [`cholesky`]: a linear system's Cholesky factorization;
//! - [`lu`]: a linear system's LU factorization.

pub(crate) mod block;
pub(crate) mod cholesky;
pub(crate) mod conjugate_gradient;
pub(crate) mod lemke_general;
pub(crate) mod lemke_symmetric;
pub(crate) mod lu;
pub(crate) mod restricted_general;
pub(crate) mod restricted_symmetric;

use faer::{Col, Mat, MatRef};

use crate::LcpError;
use crate::linalg::try_mat;
use crate::options::Options;
use crate::problem::Problem;
use crate::statistics::{Breakdown, Work};
use crate::tableau::active_set::solve_active_set;
use crate::tableau::border::{FirstContact, first_contact};
use crate::tableau::swept::Stop;

/// A method's answer before certification.
#[derive(Debug, Clone)]
pub(crate) struct Answer {
    /// The complementary unknowns `z`.
    pub z: Col<f64>,
    /// The extra unknowns `u` (the mixed form's; `λ` of a bordered problem).
    pub u: Col<f64>,
    /// Which `z_i` are basic (the active set).
    pub basic: Vec<bool>,
    /// The attempt's counts.
    pub work: Work,
}

/// A method's breakdown: what happened, and the work done until then.
#[derive(Debug, Clone)]
pub(crate) struct Failure {
    /// What happened.
    pub breakdown: Breakdown,
    /// The attempt's counts.
    pub work: Work,
}

impl Failure {
    /// A breakdown after `work`.
    pub fn new(breakdown: Breakdown, work: Work) -> Self {
        Self { breakdown, work }
    }

    /// The engine's error `error` after `work`.
    pub fn error(error: LcpError, work: Work) -> Self {
        Self::new(Breakdown::Error(Box::new(error)), work)
    }
}

/// What an attempt returns.
pub(crate) type Attempted = Result<Answer, Failure>;

/// A linear system's answer before certification: `X` and the counts.
#[derive(Debug, Clone)]
pub(crate) struct LinearAnswer {
    /// `X` (n x m).
    pub x: Mat<f64>,
    /// The attempt's counts.
    pub work: Work,
}

/// What an attempt on a linear system returns.
pub(crate) type LinearAttempted = Result<LinearAnswer, Failure>;

/// A copy of `a` to factor or solve in place (named `what` when it cannot
/// be allocated, after `work`).
pub(crate) fn copied(
    a: MatRef<'_, f64>,
    what: &'static str,
    work: Work,
) -> Result<Mat<f64>, Failure> {
    try_mat(a.nrows(), a.ncols(), what, |i, j| a[(i, j)])
        .map_err(|e| Failure::error(e.into(), work))
}

/// Why a method does not apply to a problem (the user's error when the
/// method or the tableau was asked for explicitly).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct NotApplicable {
    /// What in the problem it does not support, and what to use instead.
    pub reason: String,
}

impl NotApplicable {
    pub fn new(reason: impl Into<String>) -> Self {
        Self {
            reason: reason.into(),
        }
    }
}

/// The final basic solution on the active set `into` (in positions of
/// `order`) from the original data: a Cholesky of `M_JJ`, the border's
/// Schur complement, refinement. A breakdown when the set does not solve
/// the problem.
pub(crate) fn finish_on_active_set(
    problem: &Problem<'_>,
    options: &Options,
    order: &[usize],
    into: &[bool],
    mut work: Work,
) -> Attempted {
    let mut basic = vec![false; problem.size()];
    for (t, &i) in order.iter().enumerate() {
        basic[i] = into[t];
    }
    match solve_active_set(&problem.mixed, &basic, options, &mut work) {
        Some((z, u)) => Ok(Answer { z, u, basic, work }),
        None => Err(Failure::new(Breakdown::ActiveSetRejected, work)),
    }
}

/// How the symmetric tableau's path of a bordered problem starts.
pub(crate) enum PathStart {
    /// From the first contact along the first border column (the
    /// approach): the other free unknowns held at zero until the first
    /// resultant is met, then all free (see `lemke_symmetric`); when the
    /// other resultants are zero.
    Approach,
    /// From the first contact of all the rows (a linear program with k
    /// rows), with the order in which the indices would touch from there.
    FirstContact(FirstContact, Vec<f64>),
}

/// Whether the border's first column is an approach: `B_:1 >= 0`, its
/// resultant `b_1 > 0`, and `q_i >= 0` where `B_i1 = 0` (every index
/// reached as the approach rises, none interfering at the start).
pub(crate) fn approach_column(problem: &Problem<'_>) -> bool {
    let Some(border) = problem.border else {
        return false;
    };
    let (b, q) = (border.columns, problem.mixed.q);
    b.ncols() >= 1
        && border.resultant[0] > 0.0
        && (0..b.nrows()).all(|i| b[(i, 0)] > 0.0 || (b[(i, 0)] == 0.0 && q[i] >= 0.0))
}

/// The start of the symmetric tableau's path for a bordered problem
/// (`None` without one, for a standard LCP, or when a border of several
/// rows without an approach column has no first contact).
pub(crate) fn path_start(problem: &Problem<'_>, options: &Options) -> Option<PathStart> {
    let border = problem.border?;
    if border.columns.ncols() == 0 {
        return None;
    }
    // Along the approach when the other resultants are zero (the contact
    // starts where the aligned one does); otherwise from the first contact
    // under all the resultants (an eccentric load: the contact starts
    // under it), the approach if that has none.
    let others_zero = border.resultant.iter().skip(1).all(|&b| b == 0.0);
    let approach = approach_column(problem);
    if approach && others_zero {
        return Some(PathStart::Approach);
    }
    match first_contact_order(problem, options) {
        Some((f, keys)) => Some(PathStart::FirstContact(f, keys)),
        None => approach.then_some(PathStart::Approach),
    }
}

/// The order in which the indices of a bordered problem would touch, for
/// block pivoting's prefix search: with an approach column, `q_i / B_i1`
/// (the approach at which index `i` touches, the other free unknowns held);
/// otherwise from the first contact of several rows. `None` for neither.
pub(crate) fn touch_order(problem: &Problem<'_>, options: &Options) -> Option<Vec<f64>> {
    match path_start(problem, options)? {
        PathStart::Approach => {
            let (b, q) = (problem.border?.columns, problem.mixed.q);
            Some(
                (0..problem.size())
                    .map(|i| {
                        if b[(i, 0)] > 0.0 {
                            q[i] / b[(i, 0)]
                        } else {
                            f64::INFINITY
                        }
                    })
                    .collect(),
            )
        }
        PathStart::FirstContact(_, keys) => Some(keys),
    }
}

/// The first contact of a bordered problem with several rows, and the
/// order in which its indices would touch from there: the gap at the first
/// contact `q_i - B_i λ0` over the size of the index's border row
/// `max_l |B_il|` (for one row, `q_i / B_i` less the first approach: the
/// approach at which index `i` touches). `None` for a problem without a
/// border of at least two rows, or without a first contact.
pub(crate) fn first_contact_order(
    problem: &Problem<'_>,
    options: &Options,
) -> Option<(FirstContact, Vec<f64>)> {
    let border = problem.border?;
    let b = border.columns;
    if b.ncols() < 2 {
        return None;
    }
    let q = problem.mixed.q;
    let first = first_contact(b, border.resultant, q, &options.tolerances).ok()?;
    let keys = (0..problem.size())
        .map(|i| {
            let gap = q[i]
                - (0..b.ncols())
                    .map(|l| b[(i, l)] * first.lambda[l])
                    .sum::<f64>();
            let size = (0..b.ncols()).fold(0.0f64, |a, l| a.max(b[(i, l)].abs()));
            if size > 0.0 { gap / size } else { gap }
        })
        .collect();
    Some((first, keys))
}

/// Where a path on the symmetric tableau applies: a symmetric `M` with a
/// positive diagonal, in the standard form or a bordered one; with one
/// row, an approach column ([`approach_column`]). Several rows start from
/// the approach when their first column is one, else from their first
/// contact, which the attempt computes ([`path_start`]).
pub(crate) fn symmetric_path(problem: &Problem<'_>) -> Result<Stop, NotApplicable> {
    let Some(border) = problem.border else {
        return Err(NotApplicable::new(
            "the symmetric tableau takes a standard or bordered LCP (a mixed form goes to the general tableau)",
        ));
    };
    if !problem.positive_diagonal() {
        return Err(NotApplicable::new(
            "the symmetric tableau needs M with a positive diagonal",
        ));
    }
    if !problem.symmetric() {
        return Err(NotApplicable::new(
            "the symmetric tableau needs a symmetric M",
        ));
    }
    let b = border.columns;
    match b.ncols() {
        0 => Ok(Stop::Parameter),
        1 => {
            let q = problem.mixed.q;
            let reached =
                (0..b.nrows()).all(|i| b[(i, 0)] > 0.0 || (b[(i, 0)] == 0.0 && q[i] >= 0.0));
            if reached && border.resultant[0] > 0.0 {
                Ok(Stop::Border)
            } else {
                Err(NotApplicable::new(
                    "the symmetric tableau's path with one border row needs B >= 0, a positive resultant and no interference where B is 0",
                ))
            }
        }
        _ => Ok(Stop::Border),
    }
}
