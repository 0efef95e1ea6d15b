//! # elcon-lcp: a dense tableau pivoting engine for complementarity problems
//!
//! Solves the linear complementarity problem
//!
//! ```text
//!     w = M z + q,   z >= 0,   w >= 0,   z^T w = 0
//! ```
//!
//! its bordered form with `k` free unknowns and as many equality rows
//! ([`BorderedLcp`], [`BorderedLcpRef`]: `w = M z - B λ + q`, `B^T z = b`;
//! the contact problem with its approach and tilts), the general mixed form
//! with equality rows and extra free or non-negative unknowns
//! ([`MixedLcp`]: `w = M z + B u + q`, `0 = C z + D u + r`), and linear
//! programs with complementarity constraints ([`ComplementaryProgram`]), by
//! pivoting on a dense tableau held in a faer matrix. It knows nothing of
//! contact mechanics: any LCP or convex QP of this kind is welcome.
//!
//! Methods ([`Method`]), each on the tableau [`Options::tableau`] allows:
//! - the restricted-entry (complementary) simplex of Wolfe (1959), the
//!   method of Conry & Seireg (1971): on the symmetric tableau for a
//!   symmetric `M` with a border of one row and no initial interference,
//!   on the general tableau otherwise;
//! - Lemke's method: on the symmetric tableau for a symmetric `M` (the
//!   standard form or a border of k rows, as its parametric
//!   principal-pivoting form), on the general tableau with a covering
//!   vector and a lexicographic ratio test otherwise;
//! - block principal pivoting for a symmetric positive definite `M` (not a
//!   tableau method: one Cholesky of the active block per iteration);
//! - the constrained conjugate gradient of Polonsky & Keer (1999) for a
//!   symmetric positive definite `M`: iterative, it needs only products
//!   `M x`, and so also solves problems whose `M` is an [`Operator`]
//!   ([`OperatorLcp`]: an FFT convolution on a grid too large to store),
//!   preconditioned where the problem has a [`Preconditioner`]. An
//!   operator declares the scratch memory its products need and the
//!   caller lends it (faer's `LinOp` idiom, [`StackReq`], with a
//!   [`PodStack`] of initialized bytes).
//!
//! It also solves, certified, a symmetric positive definite linear system
//! `M X = R` with several right-hand sides ([`LinearSystem`]: a Cholesky
//! factorization of a dense `M`, an LU where `M` is not numerically
//! positive definite, the conjugate gradient for an [`Operator`]: its
//! [`LinearMethod`]s), the
//! contact solution's sensitivities `S_JJ X = R` on its contact set.
//!
//! One strategy routes every solve (the module `strategy`, drawn in
//! docs/theory.md): the attempts in order, a fallback after a breakdown,
//! one retry refactoring from the data after a numerical failure.
//!
//! Every solution carries a [`Certificate`] computed from the ORIGINAL data
//! (smallest `z`, smallest `w`, largest `|z_i w_i|`, equality residual, each
//! relative to the data's scale) and [`Statistics`] (the log of its
//! attempts: method, an [`AnyMethod`] of either kind, tableau, pivots,
//! outcome). A solution whose
//! certificate does not hold is not returned: the solve ends with
//! [`LcpError::Inaccurate`].
//!
//! With the `serde` feature, [`Method`] and [`LinearMethod`] serialize
//! and deserialize as their names (`"lemke"`), which they also parse
//! (`FromStr`, an [`UnknownName`] listing the names there are).
//!
//! ```
//! use elcon_lcp::{BorderedLcp, Lcp, Method, Options};
//! use faer::{col, mat};
//!
//! // M symmetric positive definite: a unique solution.
//! let m = mat![[2.0, 1.0], [1.0, 2.0]];
//! let q = col![-5.0, -6.0];
//! let lcp = Lcp::new(m.clone(), q).unwrap();
//! for method in Method::ALL {
//!     let sol = lcp.solve(method, &Options::default()).unwrap();
//!     assert!(sol.certificate.holds());
//!     // z = M^{-1}(-q) = (4/3, 7/3), w = 0
//!     assert!((sol.z[0] - 4.0 / 3.0).abs() < 1e-10 && (sol.z[1] - 7.0 / 3.0).abs() < 1e-10);
//! }
//!
//! // A border: two points pressed by a load 3 (B = ones, b = 3) with gaps
//! // (0, 1): w = M z - λ e + q, z_0 + z_1 = 3, λ the approach.
//! let contact = BorderedLcp::new(m, col![0.0, 1.0])
//!     .unwrap()
//!     .with_border(mat![[1.0], [1.0]], col![3.0])
//!     .unwrap();
//! let sol = contact.solve(Method::Lemke, &Options::default()).unwrap();
//! // Both touch: M z + q = λ e with z_0 + z_1 = 3, so z = (2, 1), λ = 5.
//! assert!((sol.z[0] - 2.0).abs() < 1e-12 && (sol.z[1] - 1.0).abs() < 1e-12);
//! assert!((sol.u[0] - 5.0).abs() < 1e-12);
//! ```

mod cancel;
mod certificate;
mod certify;
mod error;
mod linalg;
mod linear;
mod methods;
mod operator;
mod options;
mod problem;
mod program;
mod solution;
mod statistics;
mod strategy;
mod tableau;
pub mod tolerance;

pub use cancel::Cancel;
pub use certificate::Certificate;
pub use elcon_num::{Num, UnknownName};
pub use error::{LcpError, TABLEAU_ADVICE};
pub use linalg::condition_estimate;
pub use linear::LinearSystem;
pub use operator::{MatrixFree, Operator, OperatorLcp, Preconditioner};
pub use options::{AnyMethod, LinearMethod, Method, Options, Tableau};
pub use problem::{Bordered, BorderedLcp, BorderedLcpRef, Bound, Lcp, MixedLcp, MixedLcpParts};
pub use program::{ComplementaryProgram, ProgramBuilder};
pub use solution::{LcpSolution, LinearSolution, ProgramSolution};
pub use statistics::{Attempt, Breakdown, Outcome, Reason, Statistics, Work};
pub use tolerance::Tolerances;

/// faer's parallelism setting, re-exported for [`Options::parallelism`].
pub use faer::Par;
/// faer's scratch memory (dyn-stack), re-exported for [`Operator`] and
/// [`Preconditioner`]: a request, the buffer of initialized bytes that
/// meets it, the stack an application carves its buffers from.
pub use faer::dyn_stack::{PodBuffer, PodStack, StackReq};
