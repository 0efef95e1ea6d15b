//! Problem forms, options, statistics and solutions.
//!
//! Standard LCP: find `z`, `w` with
//!
//! ```text
//!     w = M z + q,   z >= 0,   w >= 0,   z^T w = 0
//! ```
//!
//! Mixed LCP: `n` complementary pairs, `m_e` equality rows and `k` extra
//! unknowns `u` that are free or non-negative (but not complementary):
//!
//! ```text
//!     w = M z + B u + q,   z >= 0, w >= 0, z^T w = 0
//!     0 = C z + D u + r
//! ```
//!
//! The contact problem of Conry & Seireg is the mixed form with `z = F`,
//! `w = Y`, `M = S`, `u = alpha` (free), `B = -e`, `q = eps`, `C = e^T`,
//! `D = 0`, `r = -P`.

use std::time::Instant;

use faer::{Col, ColRef, Mat, MatRef, Par};

use crate::certificate::Certificate;
use crate::system::{check_finite_col, check_finite_mat};
use crate::tolerance::Tolerances;
use crate::{LcpError, block, lemke, restricted};

/// Sign restriction of an unknown that has no complementary partner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// Any real value.
    Free,
    /// `>= 0`.
    NonNegative,
}

/// Refactorization interval (pivots) of the retry after a failed certificate.
const RETRY_REFACTOR: usize = 10;

/// Refinement steps of the retry after a failed certificate.
const RETRY_REFINEMENT: usize = 10;

/// A pivoting method of the engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Method {
    /// The restricted-entry (complementary) simplex of Wolfe (1959) as used by
    /// Conry & Seireg (1971): phase 1 minimizes the sum of artificial
    /// variables, and a variable may enter only if its complement is
    /// non-basic or leaves at the same pivot. The contact form with a
    /// symmetric `M` and no initial interference (`q >= 0`) runs first on
    /// the symmetric tableau of Lemke's method below, whose bases are the
    /// simplex's own (a contact set and one point pinning the approach):
    /// the same rule at half the update work, and a Cholesky of the contact
    /// block for the final basic solution.
    RestrictedSimplex,
    /// Lemke's complementary pivoting method with a covering vector and a
    /// lexicographic minimum-ratio test (Lemke 1965). Mixed forms are solved
    /// as the equivalent standard LCP with each free unknown split in two.
    /// A symmetric `M` (the standard form, or the contact form with one load
    /// row) runs first on a symmetric tableau, as the parametric principal
    /// pivoting form of the same path, with the approach's column as the
    /// covering vector: half the update work, and a Cholesky of the contact
    /// block for the final basic solution.
    Lemke,
    /// Block principal pivoting (Júdice & Pires 1994) for a symmetric
    /// positive definite `M`: guess the active set, solve the equilibrium on
    /// it with a faer Cholesky, exchange every infeasible index at once;
    /// safeguarded by single principal pivots and, past an iteration cap, by
    /// Lemke's method. Not a tableau method: it needs `M` symmetric (an
    /// asymmetric M is refused); when a principal block turns out not to be
    /// positive definite (a beam's clamped point alone has a zero row) it
    /// falls back to Lemke's method.
    BlockPivoting,
}

impl Method {
    /// Every method, in a stable order.
    pub const ALL: [Method; 3] = [
        Method::RestrictedSimplex,
        Method::Lemke,
        Method::BlockPivoting,
    ];

    /// The dense-tableau methods (they work for any matrix of their class).
    pub const TABLEAU: [Method; 2] = [Method::RestrictedSimplex, Method::Lemke];

    /// A short lower-case name ("restricted-simplex", "lemke", "block-pivoting").
    pub fn name(self) -> &'static str {
        match self {
            Method::RestrictedSimplex => "restricted-simplex",
            Method::Lemke => "lemke",
            Method::BlockPivoting => "block-pivoting",
        }
    }

    /// The method of a name given by [`Method::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Options of a solve. `Options::default()` suits well-posed problems.
#[derive(Debug, Clone)]
pub struct Options {
    /// The tableau methods stop with [`LcpError::PivotLimit`] when a solve
    /// needs more than this many pivots (default: `20 (rows + unknowns) +
    /// 100`); block pivoting takes at most this many iterations (default
    /// `3 n + 50`) and then finishes by Lemke's method.
    pub max_pivots: Option<usize>,
    /// Recompute the tableau from the original data every this many pivots
    /// (default: `max(100, rows)`; 0 disables periodic refactorization; the
    /// final basic solution is always recomputed from the data).
    pub refactor_interval: Option<usize>,
    /// Iterative-refinement steps of the final basic solution (default 3).
    pub refinement_steps: usize,
    /// The engine's relative tolerances.
    pub tolerances: Tolerances,
    /// Equilibrate rows and columns by powers of two before pivoting (default true).
    pub equilibrate: bool,
    /// Lemke's covering vector `d > 0` (default: all ones in the equilibrated problem).
    pub covering_vector: Option<Vec<f64>>,
    /// Parallelism of the pivots' rank-1 updates and of the factorizations
    /// (default: `Par::Seq` below 250,000 tableau entries, all threads above).
    pub parallelism: Option<Par>,
    /// A warm start for block pivoting: `warm_start[i]` = `z_i` is expected
    /// basic (e.g. [`LcpSolution::basic`] of a previous, similar solve).
    pub warm_start: Option<Vec<bool>>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            max_pivots: None,
            refactor_interval: None,
            refinement_steps: 3,
            tolerances: Tolerances::default(),
            equilibrate: true,
            covering_vector: None,
            parallelism: None,
            warm_start: None,
        }
    }
}

impl Options {
    /// Checks the options against a problem with `rows` rows and `unknowns` unknowns.
    pub(crate) fn validate(&self) -> Result<(), LcpError> {
        self.tolerances.validate()?;
        if let Some(0) = self.max_pivots {
            return Err(LcpError::InvalidOption {
                field: "max_pivots",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        Ok(())
    }

    pub(crate) fn pivot_limit(&self, rows: usize, unknowns: usize) -> usize {
        self.max_pivots.unwrap_or(20 * (rows + unknowns) + 100)
    }

    /// The options of the one retry after a numerical failure (a singular
    /// basis, a certificate that does not hold): the tableau refactored
    /// from the original data every `RETRY_REFACTOR` pivots, refined harder.
    /// `None` when these options already are that (the retry would repeat
    /// the same computation).
    pub(crate) fn retry(&self) -> Option<Options> {
        let refactor = self
            .refactor_interval
            .map_or(RETRY_REFACTOR, |r| r.min(RETRY_REFACTOR));
        let steps = self.refinement_steps.max(RETRY_REFINEMENT);
        (self.refactor_interval != Some(refactor) || self.refinement_steps != steps).then(|| {
            Options {
                refactor_interval: Some(refactor),
                refinement_steps: steps,
                ..self.clone()
            }
        })
    }

    pub(crate) fn refactor_every(&self, rows: usize) -> usize {
        self.refactor_interval.unwrap_or(rows.max(100))
    }

    pub(crate) fn par(&self, rows: usize, cols: usize) -> Par {
        self.parallelism.unwrap_or(if rows * cols > 250_000 {
            Par::rayon(0)
        } else {
            Par::Seq
        })
    }
}

/// What a solve cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Statistics {
    /// The method that ran.
    pub method: Method,
    /// Pivots (basis exchanges) done.
    pub pivots: usize,
    /// Pivots whose step length was zero.
    pub degenerate_pivots: usize,
    /// Recomputations of the whole tableau from the original data.
    pub refactorizations: usize,
    /// Iterative-refinement steps of the final basic solution.
    pub refinement_steps: usize,
    /// Block iterations (block pivoting; 0 for the tableau methods).
    pub iterations: usize,
    /// Matrix factorizations (Cholesky of block systems; 0 for the general
    /// tableau; 1 for a tableau method on the symmetric tableau, whose
    /// final basic solution is solved by a Cholesky of the contact block).
    pub factorizations: usize,
    /// Whether a tableau method finished on the symmetric tableau (see
    /// [`Method::Lemke`], [`Method::RestrictedSimplex`]); `false` when it
    /// ran on the general tableau, also after an attempt on the symmetric
    /// one that broke down (whose pivots and factorization are counted).
    pub symmetric_tableau: bool,
    /// Whether block pivoting fell back to Lemke's method.
    pub fell_back: bool,
    /// Whether the first attempt's certificate failed and the solve was
    /// repeated (tableau methods: frequent refactorization from the data;
    /// block pivoting: Lemke's method). The counts above add both attempts
    /// when the second one reached an answer.
    pub retried: bool,
    /// Rows of the tableau that was pivoted on.
    pub tableau_rows: usize,
    /// Columns of the tableau (non-basic unknowns plus the right-hand side).
    pub tableau_columns: usize,
    /// Wall-clock seconds of the solve (setup, pivoting, refinement, certificate).
    pub seconds: f64,
}

impl Statistics {
    /// Adds the work of another attempt at the same problem (a fallback, a
    /// retry): its counts are summed and its flags kept; the method, the
    /// tableau's shape and the seconds stay this attempt's.
    pub(crate) fn absorb(&mut self, other: &Statistics) {
        self.pivots += other.pivots;
        self.degenerate_pivots += other.degenerate_pivots;
        self.refactorizations += other.refactorizations;
        self.refinement_steps += other.refinement_steps;
        self.iterations += other.iterations;
        self.factorizations += other.factorizations;
        self.fell_back |= other.fell_back;
        self.retried |= other.retried;
    }

    pub(crate) fn new(method: Method) -> Self {
        Self {
            method,
            pivots: 0,
            degenerate_pivots: 0,
            refactorizations: 0,
            refinement_steps: 0,
            iterations: 0,
            factorizations: 0,
            symmetric_tableau: false,
            fell_back: false,
            retried: false,
            tableau_rows: 0,
            tableau_columns: 0,
            seconds: 0.0,
        }
    }
}

/// A certified solution of an LCP or mixed LCP.
#[derive(Debug, Clone)]
pub struct LcpSolution {
    /// The complementary unknowns `z`.
    pub z: Col<f64>,
    /// `w = M z + B u + q`, computed from the original data.
    pub w: Col<f64>,
    /// The extra unknowns `u` (empty for a standard LCP).
    pub u: Col<f64>,
    /// `basic[i]` is true when `z_i` (rather than `w_i`) is basic in the
    /// final complementary basis: the active set, for warm starts.
    pub basic: Vec<bool>,
    /// Residuals from the original data.
    pub certificate: Certificate,
    /// What the solve cost.
    pub statistics: Statistics,
}

/// The standard LCP `w = M z + q, z >= 0, w >= 0, z^T w = 0`.
#[derive(Debug, Clone)]
pub struct Lcp {
    m: Mat<f64>,
    q: Col<f64>,
}

impl Lcp {
    /// A standard LCP; `m` must be square with the size of `q`, all finite.
    pub fn new(m: Mat<f64>, q: Col<f64>) -> Result<Self, LcpError> {
        let n = q.nrows();
        if n == 0 {
            return Err(LcpError::Empty { field: "q" });
        }
        check_dims("m", m.nrows(), m.ncols(), n, n)?;
        check_finite_mat("m", m.as_ref())?;
        check_finite_col("q", q.as_ref())?;
        Ok(Self { m, q })
    }

    /// Number of complementary pairs.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }

    /// The matrix `M`.
    pub fn matrix(&self) -> MatRef<'_, f64> {
        self.m.as_ref()
    }

    /// The vector `q`.
    pub fn q(&self) -> ColRef<'_, f64> {
        self.q.as_ref()
    }

    /// Solves with `method`; the solution carries its certificate, and an
    /// uncertified solution is an error ([`LcpError::Inaccurate`]).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        MixedLcpRef::standard(self.m.as_ref(), self.q.as_ref()).solve(method, options)
    }
}

/// The mixed LCP (see the module documentation).
#[derive(Debug, Clone)]
pub struct MixedLcp {
    m: Mat<f64>,
    b: Mat<f64>,
    q: Col<f64>,
    c: Mat<f64>,
    d: Mat<f64>,
    r: Col<f64>,
    bounds: Vec<Bound>,
}

impl MixedLcp {
    /// A mixed LCP. Sizes: `m` n x n, `b` n x k, `q` n, `c` m_e x n, `d`
    /// m_e x k, `r` m_e, `bounds` k. All entries finite.
    pub fn new(
        m: Mat<f64>,
        b: Mat<f64>,
        q: Col<f64>,
        c: Mat<f64>,
        d: Mat<f64>,
        r: Col<f64>,
        bounds: Vec<Bound>,
    ) -> Result<Self, LcpError> {
        let n = q.nrows();
        let k = bounds.len();
        let me = r.nrows();
        if n == 0 {
            return Err(LcpError::Empty { field: "q" });
        }
        check_dims("m", m.nrows(), m.ncols(), n, n)?;
        check_dims("b", b.nrows(), b.ncols(), n, k)?;
        check_dims("c", c.nrows(), c.ncols(), me, n)?;
        check_dims("d", d.nrows(), d.ncols(), me, k)?;
        check_finite_mat("m", m.as_ref())?;
        check_finite_mat("b", b.as_ref())?;
        check_finite_col("q", q.as_ref())?;
        check_finite_mat("c", c.as_ref())?;
        check_finite_mat("d", d.as_ref())?;
        check_finite_col("r", r.as_ref())?;
        Ok(Self {
            m,
            b,
            q,
            c,
            d,
            r,
            bounds,
        })
    }

    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }

    /// A borrowed view of the problem's data.
    pub fn as_ref(&self) -> MixedLcpRef<'_> {
        MixedLcpRef {
            m: self.m.as_ref(),
            b: self.b.as_ref(),
            q: self.q.as_ref(),
            c: self.c.as_ref(),
            d: self.d.as_ref(),
            r: self.r.as_ref(),
            bounds: &self.bounds,
        }
    }

    /// Solves with `method` (see [`Lcp::solve`]).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        self.as_ref().solve(method, options)
    }

    /// The certificate of a candidate `(z, u)` against this problem's data,
    /// with `w = M z + B u + q`.
    pub fn certify(
        &self,
        z: ColRef<'_, f64>,
        u: ColRef<'_, f64>,
        tolerance: f64,
    ) -> (Certificate, Col<f64>) {
        self.as_ref().certify(z, u, tolerance)
    }
}

/// A borrowed mixed LCP: what the methods read. Build one with
/// [`MixedLcpRef::new`] to solve without copying large matrices.
#[derive(Debug, Clone, Copy)]
pub struct MixedLcpRef<'a> {
    pub(crate) m: MatRef<'a, f64>,
    pub(crate) b: MatRef<'a, f64>,
    pub(crate) q: ColRef<'a, f64>,
    pub(crate) c: MatRef<'a, f64>,
    pub(crate) d: MatRef<'a, f64>,
    pub(crate) r: ColRef<'a, f64>,
    pub(crate) bounds: &'a [Bound],
}

impl<'a> MixedLcpRef<'a> {
    /// Validates and wraps borrowed data (same rules as [`MixedLcp::new`]).
    pub fn new(
        m: MatRef<'a, f64>,
        b: MatRef<'a, f64>,
        q: ColRef<'a, f64>,
        c: MatRef<'a, f64>,
        d: MatRef<'a, f64>,
        r: ColRef<'a, f64>,
        bounds: &'a [Bound],
    ) -> Result<Self, LcpError> {
        let n = q.nrows();
        let k = bounds.len();
        let me = r.nrows();
        if n == 0 {
            return Err(LcpError::Empty { field: "q" });
        }
        check_dims("m", m.nrows(), m.ncols(), n, n)?;
        check_dims("b", b.nrows(), b.ncols(), n, k)?;
        check_dims("c", c.nrows(), c.ncols(), me, n)?;
        check_dims("d", d.nrows(), d.ncols(), me, k)?;
        check_finite_mat("m", m)?;
        check_finite_mat("b", b)?;
        check_finite_col("q", q)?;
        check_finite_mat("c", c)?;
        check_finite_mat("d", d)?;
        check_finite_col("r", r)?;
        Ok(Self {
            m,
            b,
            q,
            c,
            d,
            r,
            bounds,
        })
    }

    fn standard(m: MatRef<'a, f64>, q: ColRef<'a, f64>) -> Self {
        let n = q.nrows();
        Self {
            m,
            b: MatRef::from_column_major_slice(&[], n, 0),
            q,
            c: MatRef::from_column_major_slice(&[], 0, n),
            d: MatRef::from_column_major_slice(&[], 0, 0),
            r: ColRef::from_slice(&[]),
            bounds: &[],
        }
    }

    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }

    /// Number of extra unknowns `k`.
    pub fn extras(&self) -> usize {
        self.bounds.len()
    }

    /// Number of equality rows `m_e`.
    pub fn equalities(&self) -> usize {
        self.r.nrows()
    }

    /// The certificate of `(z, u)` and `w = M z + B u + q`.
    pub fn certify(
        &self,
        z: ColRef<'_, f64>,
        u: ColRef<'_, f64>,
        tolerance: f64,
    ) -> (Certificate, Col<f64>) {
        let nonneg: Vec<bool> = self
            .bounds
            .iter()
            .map(|b| *b == Bound::NonNegative)
            .collect();
        Certificate::mixed(
            self.m, self.b, self.q, self.c, self.d, self.r, &nonneg, z, u, tolerance,
        )
    }

    /// Solves with `method` (see [`Lcp::solve`]).
    pub fn solve(&self, method: Method, options: &Options) -> Result<LcpSolution, LcpError> {
        options.validate()?;
        if let Some(d) = &options.covering_vector {
            // Lemke's size also for block pivoting, which may fall back to it.
            let expect = match method {
                Method::Lemke | Method::BlockPivoting => lemke::split_size(self),
                _ => d.len(),
            };
            if d.len() != expect {
                return Err(LcpError::DimensionMismatch {
                    field: "covering_vector",
                    expected: expect,
                    found: d.len(),
                    unit: "entries",
                });
            }
            if let Some((index, &value)) = d
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && **v > 0.0))
            {
                return Err(LcpError::InvalidOption {
                    field: "covering_vector",
                    value: format!("entry {index} = {value}"),
                    reason: "every entry must be finite and > 0",
                });
            }
        }
        let start = Instant::now();
        let run = |options: &Options| match method {
            Method::RestrictedSimplex => restricted::solve_mixed(self, options),
            Method::Lemke => lemke::solve_mixed(self, options),
            Method::BlockPivoting => block::solve_mixed(self, options),
        };
        // A basis the tableau's drift made singular: solve once more,
        // refactoring from the data (block pivoting, whose singular bases
        // come from its Lemke fallback, by that fallback directly); the
        // first error stands if that fails. The first attempt's pivots
        // (the error's count) are added to the statistics.
        let (mut raw, retried) = match run(options) {
            Ok(raw) => (raw, false),
            Err(first @ LcpError::SingularBasis { pivot, .. }) => {
                let Some(retry) = options.retry() else {
                    return Err(first);
                };
                let second = match method {
                    Method::BlockPivoting => {
                        block::fallback(self, &retry, Statistics::new(Method::BlockPivoting))
                    }
                    _ => run(&retry),
                };
                match second {
                    Ok(mut raw) => {
                        raw.statistics.pivots += pivot;
                        (raw, true)
                    }
                    Err(_) => return Err(first),
                }
            }
            Err(e) => return Err(e),
        };
        raw.statistics.retried |= retried;
        let (mut certificate, mut w) = self.certify(
            raw.z.as_ref(),
            raw.u.as_ref(),
            options.tolerances.certificate,
        );
        if !certificate.holds() && !retried {
            // The certificate degraded (rounding drift steered a pivot or an
            // active set wrong): solve once more, the tableau methods
            // refactoring from the original data every RETRY_REFACTOR pivots
            // and refining harder, block pivoting by Lemke's method; keep the
            // better certificate. The statistics count both attempts.
            // (Options that already are the retry's: the tableau methods
            // would repeat the same computation, so only block pivoting's
            // fallback runs.)
            let second = match (method, options.retry()) {
                (Method::BlockPivoting, retry) => Some(block::fallback(
                    self,
                    retry.as_ref().unwrap_or(options),
                    Statistics::new(Method::BlockPivoting),
                )),
                (_, Some(retry)) => Some(run(&retry)),
                (_, None) => None,
            };
            // A failed second attempt leaves the first (its error is not the
            // answer: the first attempt's certificate says what went wrong).
            if let Some(Ok(second)) = second {
                let (c2, w2) = self.certify(
                    second.z.as_ref(),
                    second.u.as_ref(),
                    options.tolerances.certificate,
                );
                if c2.worst() < certificate.worst() {
                    let first = raw.statistics;
                    raw = second;
                    raw.statistics.absorb(&first);
                    certificate = c2;
                    w = w2;
                } else {
                    raw.statistics.absorb(&second.statistics);
                }
            }
            raw.statistics.method = method;
            raw.statistics.retried = true;
        }
        let mut statistics = raw.statistics;
        statistics.seconds = start.elapsed().as_secs_f64();
        if !certificate.holds() {
            return Err(LcpError::Inaccurate {
                size: self.size(),
                pivots: statistics.pivots,
                certificate: Box::new(certificate),
            });
        }
        Ok(LcpSolution {
            z: raw.z,
            w,
            u: raw.u,
            basic: raw.basic,
            certificate,
            statistics,
        })
    }
}

/// What a method returns before certification.
pub(crate) struct RawSolution {
    pub z: Col<f64>,
    pub u: Col<f64>,
    pub basic: Vec<bool>,
    pub statistics: Statistics,
}

fn check_dims(
    field: &'static str,
    rows: usize,
    cols: usize,
    er: usize,
    ec: usize,
) -> Result<(), LcpError> {
    if rows != er {
        return Err(LcpError::DimensionMismatch {
            field,
            expected: er,
            found: rows,
            unit: "rows",
        });
    }
    if cols != ec {
        return Err(LcpError::DimensionMismatch {
            field,
            expected: ec,
            found: cols,
            unit: "columns",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_retry_tightens_the_options_or_is_none() {
        let retry = Options::default().retry().expect("the defaults are looser");
        assert_eq!(retry.refactor_interval, Some(RETRY_REFACTOR));
        assert!(retry.refinement_steps >= RETRY_REFINEMENT);
        // Options that already are the retry's: nothing to repeat.
        assert!(retry.retry().is_none());
        let tighter = Options {
            refactor_interval: Some(5),
            refinement_steps: 20,
            ..Options::default()
        };
        assert!(tighter.retry().is_none());
        // A tighter refactorization is kept, the refinement raised.
        let mixed = Options {
            refactor_interval: Some(5),
            refinement_steps: 1,
            ..Options::default()
        };
        let retry = mixed.retry().expect("more refinement");
        assert_eq!(retry.refactor_interval, Some(5));
        assert_eq!(retry.refinement_steps, RETRY_REFINEMENT);
    }
}
