//! The tableaus and their pivots, and the dense solves on an active set
//! that finish the methods; the methods only drive them.
//!
//! - [`system`]: the linear system `A x = b` the general tableau pivots on,
//!   its equilibration and a factorization of a basis;
//! - [`general`]: the compact (Tucker) tableau `x_B = b̄ + T x_N` with
//!   delayed rank-1 updates and a lexicographic ratio test;
//! - [`basic`]: the final basic solution of the general tableau from the
//!   original data, refined;
//! - [`swept`]: the symmetric (swept) tableau of principal pivots on a
//!   symmetric `M`, and the parametric path's state;
//! - [`active_set`]: the Cholesky factor of an active block `M_JJ` and the
//!   solution on an active set with the border's Schur complement;
//! - [`border`]: the first contact of a bordered problem (a linear program
//!   with k rows), where the symmetric tableau's path starts.

pub(crate) mod active_set;
pub(crate) mod basic;
pub(crate) mod border;
pub(crate) mod general;
pub(crate) mod swept;
pub(crate) mod system;
