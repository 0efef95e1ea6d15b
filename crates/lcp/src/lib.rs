//! # elcon-lcp: a dense tableau pivoting engine for complementarity problems
//!
//! Solves the linear complementarity problem
//!
//! ```text
//!     w = M z + q,   z >= 0,   w >= 0,   z^T w = 0
//! ```
//!
//! its mixed form with equality rows and extra free or non-negative unknowns
//! ([`MixedLcp`]: `w = M z + B u + q`, `0 = C z + D u + r`), and linear
//! programs with complementarity constraints ([`ComplementaryProgram`]), by
//! pivoting on a dense tableau held in a faer matrix. It knows nothing of
//! contact mechanics: any LCP or convex QP of this kind is welcome.
//!
//! Methods ([`Method`]):
//! - the restricted-entry (complementary) simplex of Wolfe (1959), the
//!   method of Conry & Seireg (1971) (for the contact form with a
//!   symmetric `M`, on the symmetric tableau of Lemke's method below);
//! - Lemke's method with a covering vector and a lexicographic ratio test
//!   (for a symmetric `M`, in its parametric principal-pivoting form on a
//!   symmetric tableau);
//! - block principal pivoting for symmetric positive definite `M` (not a
//!   tableau method: one Cholesky of the active block per iteration).
//!
//! Every solution carries a [`Certificate`] computed from the ORIGINAL data
//! (smallest `z`, smallest `w`, largest `|z_i w_i|`, equality residual, each
//! relative to the data's scale) and [`Statistics`] (pivots, degenerate
//! pivots, refactorizations, seconds). A solution whose certificate does not
//! hold is not returned: the solve ends with [`LcpError::Inaccurate`].
//!
//! ```
//! use elcon_lcp::{Lcp, Method, Options};
//! use faer::{col, mat};
//!
//! // M symmetric positive definite: a unique solution.
//! let m = mat![[2.0, 1.0], [1.0, 2.0]];
//! let q = col![-5.0, -6.0];
//! let lcp = Lcp::new(m, q).unwrap();
//! for method in Method::ALL {
//!     let sol = lcp.solve(method, &Options::default()).unwrap();
//!     assert!(sol.certificate.holds());
//!     // z = M^{-1}(-q) = (4/3, 7/3), w = 0
//!     assert!((sol.z[0] - 4.0 / 3.0).abs() < 1e-12 && (sol.z[1] - 7.0 / 3.0).abs() < 1e-12);
//! }
//! ```

mod block;
mod certificate;
mod conditioning;
mod dense;
mod error;
mod lemke;
mod problem;
mod program;
mod restricted;
mod sweep;
mod swept_simplex;
mod system;
mod tableau;
pub mod tolerance;

pub use certificate::Certificate;
pub use conditioning::condition_estimate;
pub use error::LcpError;
pub use problem::{Bound, Lcp, LcpSolution, Method, MixedLcp, MixedLcpRef, Options, Statistics};
pub use program::{ComplementaryProgram, ProgramBuilder, ProgramSolution};
pub use tolerance::Tolerances;

/// faer's parallelism setting, re-exported for [`Options::parallelism`].
pub use faer::Par;
