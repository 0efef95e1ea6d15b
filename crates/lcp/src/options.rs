//! The choices of a solve: the method, the tableau, limits and tolerances.
//!
//! Every choice is explicit: the tableau a method runs on is
//! [`Options::tableau`], never a side effect of another option.

use faer::Par;

use crate::LcpError;
use crate::problem::check_size;
use crate::tolerance::Tolerances;
use elcon_num::Num;

/// Each method's name (a scene's word: `name`, public, with `named!`'s
/// traits and, with the `serde` feature, `named_serde!`'s) and how a
/// message describes it (`described`), from one table.
macro_rules! words {
    (
        $(#[doc = $doc:literal])+
        $ty:ident, $kind:literal:
        $($choice:ident => $name:literal, $described:literal;)+
    ) => {
        impl $ty {
            $(#[doc = $doc])+
            pub const fn name(self) -> &'static str {
                match self {
                    $($ty::$choice => $name,)+
                }
            }

            /// The method in an error message ("Lemke's method", "the LU
            /// factorization").
            pub(crate) fn described(self) -> &'static str {
                match self {
                    $($ty::$choice => $described,)+
                }
            }
        }

        elcon_num::named!($ty, $kind);
        #[cfg(feature = "serde")]
        elcon_num::named_serde!($ty);
    };
}

/// A method of complementarity problems, the engine's four
/// ([`Method::ALL`]). A linear system's are [`LinearMethod`]s; the
/// statistics' log records either ([`AnyMethod`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Method {
    /// The restricted-entry (complementary) simplex of Wolfe (1959) as used by
    /// Conry & Seireg (1971): phase 1 minimizes the sum of artificial
    /// variables, and a variable may enter only if its complement is
    /// non-basic or leaves at the same pivot. On the symmetric tableau
    /// (a symmetric `M`, a border of one row, no initial interference) its
    /// bases are a contact set and one point pinning the approach: the same
    /// rule at half the update work, and a Cholesky of the contact block for
    /// the final basic solution. Otherwise on the general tableau, which
    /// also solves non-negative extra unknowns and any border.
    RestrictedSimplex,
    /// Lemke's complementary pivoting method (Lemke 1965). On the symmetric
    /// tableau (a symmetric `M` with a positive diagonal, the standard form
    /// or a border of k rigid-body rows): the parametric principal-pivoting
    /// form of the path, half the update work and a Cholesky of the contact
    /// block at the end. On the general tableau: a covering vector and a
    /// lexicographic minimum-ratio test on the standard LCP with each free
    /// unknown split in two.
    Lemke,
    /// Block principal pivoting (Júdice & Pires 1994) for a symmetric
    /// positive definite `M`: guess the active set, solve the equilibrium on
    /// it with a faer Cholesky, exchange every infeasible index at once,
    /// safeguarded by single principal pivots. Not a tableau method; where
    /// it breaks down (a principal block that is not positive definite, its
    /// iteration cap) the strategy finishes by Lemke's method.
    BlockPivoting,
    /// The constrained conjugate gradient of Polonsky & Keer (1999),
    /// generalized to a border of k rows: iterative, it needs only products
    /// `M x`, so it also solves problems whose `M` is an operator
    /// ([`OperatorLcp`](crate::OperatorLcp): an FFT convolution on a large
    /// grid). For a symmetric positive definite `M`; it stops when the
    /// certificate's residuals are below a fraction of its tolerance
    /// ([`ITERATIVE_STOP`](crate::tolerance::ITERATIVE_STOP)). No fallback:
    /// an answer whose certificate does not hold is an error.
    ConjugateGradient,
}

impl Method {
    /// Every method of complementarity problems, in a stable order.
    pub const ALL: [Method; 4] = [
        Method::RestrictedSimplex,
        Method::Lemke,
        Method::BlockPivoting,
        Method::ConjugateGradient,
    ];

    /// The exact (pivoting) methods: they finish in finitely many pivots on
    /// a dense `M` and agree to rounding.
    pub const PIVOTING: [Method; 3] = [
        Method::RestrictedSimplex,
        Method::Lemke,
        Method::BlockPivoting,
    ];

    /// The dense-tableau methods (they work for any matrix of their class).
    pub const TABLEAU: [Method; 2] = [Method::RestrictedSimplex, Method::Lemke];
}

words! {
    /// A short lower-case name, a scene's `solver.method`
    /// ("restricted-simplex", "lemke", "block-pivoting",
    /// "conjugate-gradient"); [`FromStr`](std::str::FromStr) reads it back.
    Method, "method":
    RestrictedSimplex => "restricted-simplex", "the restricted-entry simplex";
    Lemke => "lemke", "Lemke's method";
    BlockPivoting => "block-pivoting", "block principal pivoting";
    ConjugateGradient => "conjugate-gradient", "the conjugate gradient";
}

/// A method of a symmetric positive definite linear system
/// ([`LinearSystem`](crate::LinearSystem), whose strategy chooses among
/// them by how `M` is given: [`LinearMethod::ALL`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum LinearMethod {
    /// The Cholesky factorization `M = L L^T` of a dense symmetric positive
    /// definite `M`: a linear system's first attempt.
    Cholesky,
    /// The LU factorization with partial pivoting `M = P^T L U` of a dense
    /// `M`: the fallback where `M` is not numerically symmetric positive
    /// definite.
    Lu,
    /// The plain conjugate gradient of a system whose `M` is an operator
    /// (its products only).
    ConjugateGradient,
}

impl LinearMethod {
    /// Every method of a linear system: the Cholesky factorization, the LU
    /// fallback, and the conjugate gradient for an operator.
    pub const ALL: [LinearMethod; 3] = [
        LinearMethod::Cholesky,
        LinearMethod::Lu,
        LinearMethod::ConjugateGradient,
    ];
}

words! {
    /// A short lower-case name ("cholesky", "lu", "conjugate-gradient");
    /// [`FromStr`](std::str::FromStr) reads it back.
    LinearMethod, "linear method":
    Cholesky => "cholesky", "the Cholesky factorization";
    Lu => "lu", "the LU factorization";
    ConjugateGradient => "conjugate-gradient", "the conjugate gradient";
}

/// The method of a solve or of one of its attempts, as the statistics' log
/// records it ([`Statistics`](crate::Statistics)): a complementarity
/// problem's or a linear system's. It compares equal to the [`Method`] or
/// [`LinearMethod`] it holds, and its name is theirs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AnyMethod {
    /// A method of complementarity problems.
    Complementarity(Method),
    /// A method of linear systems.
    Linear(LinearMethod),
}

impl AnyMethod {
    /// Its method's name ([`Method::name`], [`LinearMethod::name`]).
    pub const fn name(self) -> &'static str {
        match self {
            AnyMethod::Complementarity(m) => m.name(),
            AnyMethod::Linear(m) => m.name(),
        }
    }

    /// The method in an error message.
    pub(crate) fn described(self) -> &'static str {
        match self {
            AnyMethod::Complementarity(m) => m.described(),
            AnyMethod::Linear(m) => m.described(),
        }
    }
}

impl std::fmt::Display for AnyMethod {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl From<Method> for AnyMethod {
    fn from(method: Method) -> Self {
        AnyMethod::Complementarity(method)
    }
}

impl From<LinearMethod> for AnyMethod {
    fn from(method: LinearMethod) -> Self {
        AnyMethod::Linear(method)
    }
}

impl PartialEq<Method> for AnyMethod {
    fn eq(&self, other: &Method) -> bool {
        *self == AnyMethod::Complementarity(*other)
    }
}

impl PartialEq<LinearMethod> for AnyMethod {
    fn eq(&self, other: &LinearMethod) -> bool {
        *self == AnyMethod::Linear(*other)
    }
}

/// Which tableau a tableau method runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum Tableau {
    /// The symmetric tableau where the method and the problem allow it,
    /// the general tableau otherwise and after a breakdown there; a retry
    /// after a numerical failure runs on the general tableau.
    #[default]
    Auto,
    /// Only the symmetric (swept) tableau: an error where it does not
    /// apply, no fallback and no retry elsewhere.
    Symmetric,
    /// Only the general (Tucker) tableau.
    General,
}

impl Tableau {
    /// A short lower-case name ("auto", "symmetric", "general").
    pub fn name(self) -> &'static str {
        match self {
            Tableau::Auto => "auto",
            Tableau::Symmetric => "symmetric",
            Tableau::General => "general",
        }
    }
}

/// Refactorization interval (pivots) of the retry after a numerical failure.
const RETRY_REFACTOR: usize = 10;

/// Refinement steps of the retry after a numerical failure.
const RETRY_REFINEMENT: usize = 10;

/// Default iteration cap of the conjugate gradient (it converges in tens to
/// hundreds of iterations on contact problems; the cap stops a stall).
const ITERATION_CAP: usize = 10_000;

/// Options of a solve. `Options::default()` suits well-posed problems.
#[derive(Debug, Clone)]
pub struct Options {
    /// The tableau of the tableau methods, and of block pivoting's
    /// fallback (default [`Tableau::Auto`]).
    pub tableau: Tableau,
    /// The tableau methods stop with [`LcpError::PivotLimit`] when a solve
    /// needs more than this many pivots (default: `20 (rows + unknowns) +
    /// 100`); block pivoting takes at most this many iterations (default
    /// `3 n + 50`) before it breaks down; the conjugate gradient at most
    /// this many iterations (default `ITERATION_CAP`, 10,000), after which
    /// the solve ends with [`LcpError::ConjugateGradientLimit`]; a linear system's
    /// conjugate gradient at most this many per right-hand side, after
    /// which the solve ends with [`LcpError::IterationLimit`] (it returns no
    /// unconverged answer).
    pub max_pivots: Option<usize>,
    /// The general tableau is recomputed from the original data every this
    /// many pivots (default: `max(100, rows)`; 0 disables periodic
    /// refactorization; the final basic solution is always recomputed from
    /// the data). The symmetric tableau does not refactor: its final
    /// solution is computed from the data on the active set.
    pub refactor_interval: Option<usize>,
    /// Iterative-refinement steps of the final basic solution (default 3).
    pub refinement_steps: usize,
    /// The engine's relative tolerances.
    pub tolerances: Tolerances,
    /// Equilibrate rows and columns by powers of two before pivoting (default true).
    pub equilibrate: bool,
    /// Lemke's covering vector `d > 0` on the general tableau (default: all
    /// ones in the equilibrated problem). Needs [`Tableau::General`]: the
    /// symmetric tableau's covering vector is the approach's column.
    pub covering_vector: Option<Vec<f64>>,
    /// Parallelism of the pivots' rank-1 updates and of the factorizations
    /// (default: `Par::Seq` below 250,000 tableau entries, all threads above).
    pub parallelism: Option<Par>,
    /// A warm start for block pivoting: `warm_start[i]` = `z_i` is expected
    /// basic (e.g. [`LcpSolution::basic`](crate::LcpSolution::basic) of a
    /// previous, similar solve).
    pub warm_start: Option<Vec<bool>>,
    /// A warm start for the conjugate gradient: its first iterate `z`
    /// (clipped to `z >= 0` and restored to the border's rows), e.g. the
    /// `z` of a previous, similar solve. Length `n`.
    pub initial_z: Option<Vec<f64>>,
    /// The conjugate gradient applies its problem's preconditioner where
    /// it has one ([`OperatorLcp::with_preconditioner`](crate::OperatorLcp::with_preconditioner);
    /// default true).
    pub preconditioner: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            tableau: Tableau::Auto,
            max_pivots: None,
            refactor_interval: None,
            refinement_steps: 3,
            tolerances: Tolerances::default(),
            equilibrate: true,
            covering_vector: None,
            parallelism: None,
            warm_start: None,
            initial_z: None,
            preconditioner: true,
        }
    }
}

impl Options {
    /// Checks the options on their own; `split_size` is the size of the
    /// standard LCP Lemke's general tableau pivots on (the covering
    /// vector's length).
    pub(crate) fn validate(&self, split_size: usize) -> Result<(), LcpError> {
        self.tolerances.validate()?;
        if let Some(0) = self.max_pivots {
            return Err(LcpError::InvalidOption {
                field: "max_pivots",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        if let Some((index, &value)) = self
            .initial_z
            .iter()
            .flatten()
            .enumerate()
            .find(|(_, v)| !v.is_finite())
        {
            return Err(LcpError::InvalidOption {
                field: "initial_z",
                value: format!("entry {index} = {}", Num(value)),
                reason: "every entry must be finite",
            });
        }
        let Some(d) = &self.covering_vector else {
            return Ok(());
        };
        if self.tableau != Tableau::General {
            return Err(LcpError::InvalidOption {
                field: "covering_vector",
                value: format!("given with tableau = {}", self.tableau.name()),
                reason: "a covering vector applies to the general tableau only: set `tableau` to General",
            });
        }
        check_size("covering_vector", d.len(), split_size, "entries")?;
        if let Some((index, &value)) = d
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v > 0.0))
        {
            return Err(LcpError::InvalidOption {
                field: "covering_vector",
                value: format!("entry {index} = {}", Num(value)),
                reason: "every entry must be finite and > 0",
            });
        }
        Ok(())
    }

    /// The pivot limit of a tableau with `rows` rows and `unknowns` unknowns.
    pub(crate) fn pivot_limit(&self, rows: usize, unknowns: usize) -> usize {
        self.max_pivots.unwrap_or(20 * (rows + unknowns) + 100)
    }

    /// The options of the one retry after a numerical failure: the general
    /// tableau, refactored from the original data every `RETRY_REFACTOR`
    /// pivots, refined harder. `None` when these options already are that
    /// (the retry would repeat the same computation).
    pub(crate) fn retry(&self) -> Option<Options> {
        let refactor = self
            .refactor_interval
            .map_or(RETRY_REFACTOR, |r| r.min(RETRY_REFACTOR));
        let steps = self.refinement_steps.max(RETRY_REFINEMENT);
        let same = self.tableau == Tableau::General
            && self.refactor_interval == Some(refactor)
            && self.refinement_steps == steps;
        (!same).then(|| Options {
            tableau: Tableau::General,
            refactor_interval: Some(refactor),
            refinement_steps: steps,
            ..self.clone()
        })
    }

    /// The conjugate gradient's iteration cap.
    pub(crate) fn iteration_cap(&self) -> usize {
        self.max_pivots.unwrap_or(ITERATION_CAP)
    }

    /// Pivots between refactorizations of a general tableau of `rows` rows.
    pub(crate) fn refactor_every(&self, rows: usize) -> usize {
        self.refactor_interval.unwrap_or(rows.max(100))
    }

    /// The parallelism of work on a `rows x cols` matrix.
    pub(crate) fn par(&self, rows: usize, cols: usize) -> Par {
        self.parallelism.unwrap_or(if rows * cols > 250_000 {
            Par::rayon(0)
        } else {
            Par::Seq
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_method_parses_its_name_and_an_attempt_compares_to_it() {
        assert_eq!(elcon_num::unparsed(&Method::ALL), None);
        assert_eq!(elcon_num::unparsed(&LinearMethod::ALL), None);
        for method in Method::ALL {
            assert_eq!(AnyMethod::from(method), method);
            assert_eq!(AnyMethod::from(method).to_string(), method.name());
        }
        for method in LinearMethod::ALL {
            assert_eq!(AnyMethod::from(method), method);
            assert_eq!(AnyMethod::from(method).name(), method.name());
        }
        assert_eq!(
            Method::NAMES,
            [
                "restricted-simplex",
                "lemke",
                "block-pivoting",
                "conjugate-gradient"
            ]
        );
        assert_eq!(
            LinearMethod::NAMES,
            ["cholesky", "lu", "conjugate-gradient"]
        );
        // The two conjugate gradients share a name, not a kind.
        assert_ne!(
            AnyMethod::from(Method::ConjugateGradient),
            AnyMethod::from(LinearMethod::ConjugateGradient)
        );
        let e = "fastest".parse::<Method>().unwrap_err();
        assert_eq!((e.kind, e.given.as_str()), ("method", "fastest"));
        assert_eq!(
            e.to_string(),
            "unknown method `fastest`, expected one of `restricted-simplex`, `lemke`, \
             `block-pivoting`, `conjugate-gradient`"
        );
    }

    #[cfg(feature = "serde")]
    #[test]
    fn a_method_deserializes_from_its_name() {
        let read = elcon_num::from_name::<Method>;
        assert_eq!(read("block-pivoting").unwrap(), Method::BlockPivoting);
        let e = read("cholesky").unwrap_err().to_string();
        assert!(
            e.starts_with("unknown variant `cholesky`, expected one of"),
            "{e}"
        );
        assert_eq!(
            elcon_num::from_name::<LinearMethod>("lu").unwrap(),
            LinearMethod::Lu
        );
    }

    #[test]
    fn the_retry_is_the_general_tableau_refactored_or_none() {
        let retry = Options::default().retry().expect("the defaults are looser");
        assert_eq!(retry.tableau, Tableau::General);
        assert_eq!(retry.refactor_interval, Some(RETRY_REFACTOR));
        assert!(retry.refinement_steps >= RETRY_REFINEMENT);
        // Options that already are the retry's: nothing to repeat.
        assert!(retry.retry().is_none());
        let tighter = Options {
            tableau: Tableau::General,
            refactor_interval: Some(5),
            refinement_steps: 20,
            ..Options::default()
        };
        assert!(tighter.retry().is_none());
        // The same numbers on the symmetric tableau: the retry moves to the general one.
        let symmetric = Options {
            tableau: Tableau::Auto,
            ..tighter.clone()
        };
        assert_eq!(symmetric.retry().unwrap().tableau, Tableau::General);
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

    #[test]
    fn a_covering_vector_needs_the_general_tableau() {
        let auto = Options {
            covering_vector: Some(vec![1.0]),
            ..Options::default()
        };
        let e = auto.validate(1).unwrap_err();
        assert!(e.to_string().contains("set `tableau` to General"), "{e}");
        let general = Options {
            tableau: Tableau::General,
            ..auto
        };
        general.validate(1).unwrap();
        assert!(matches!(
            general.validate(2),
            Err(LcpError::DimensionMismatch {
                field: "covering_vector",
                ..
            })
        ));
    }
}
