//! The discrete frictionless contact problem of Conry & Seireg (1971), its
//! reduction to a (mixed) LCP, and its certified solution.
//!
//! N candidate points k with forces `F_k >= 0` (the paper's F), gaps after
//! deformation `Y_k >= 0` (Y), initial separations `eps_k` (ε) and the
//! rigid-body approach `alpha` (α); `S = A(1) + A(2)` the influence matrix:
//!
//! ```text
//!     Y = S F + eps - alpha e        compatibility          (paper eq. 3, 6)
//!     e^T F = P                      equilibrium            (eq. 2)
//!     F >= 0, Y >= 0, F_k Y_k = 0    contact criterion      (eq. 4)
//! ```
//!
//! Load control (P given) is the engine's bordered LCP `w = S z - B λ + q`,
//! `B^T z = b` with `z = F`, `w = Y`, `λ = alpha`, `B = e`, `q = eps`,
//! `b = P`. Displacement control (alpha given, P = e^T F follows) is the
//! plain LCP `Y = S F + (eps - alpha e)`.
//!
//! The pieces, each importing only those above it:
//!
//! | module | what it holds |
//! |---|---|
//! | `spline` | the natural cubic spline of the tables: through a profile's rows, and as B-spline coefficients over a map |
//! | `tabulated` | departures from the quadrics given as tables: height maps, axial profiles, interpolated linearly or cubically |
//! | `geometry` | the surfaces (quadrics, their curvatures) and the initial separations eps they give |
//! | `layout` | what a problem will be before its O(N^2) assembly: eps, the rigid unknowns, the mirror symmetry |
//! | `problem` | [`ContactProblem`]: points, S as held, eps, loading; its variants under another loading or separation |
//! | `builder` | [`ProblemBuilder`]: the one place that decides how S is held (`crate::Storage`), and what a problem will cost |
//! | `solution` | [`ContactSolution`], its certificate and warnings, read from the engine's answer |
//! | `solve` | the reduction to the engine's (bordered) LCP and its solve |
//! | `discretize` | the same problem solved on coarser grids of its family: its discretization error (`crate::discretization`) |

mod builder;
mod discretize;
mod geometry;
mod layout;
mod problem;
mod solution;
mod solve;
mod spline;
mod tabulated;

pub use builder::{Plan, ProblemBuilder};
pub use geometry::{Curvature, Geometry, Principal, Surface, separations};
pub use layout::Layout;
pub use problem::ContactProblem;
pub use solution::{ContactCertificate, ContactSolution, Warning};
pub use tabulated::{AxialProfile, Departure, HeightMap, Interpolation, ProfileAxis};
