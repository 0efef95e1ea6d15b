//! # elcon-analysis: the contact analysis of Conry & Seireg (1971)
//!
//! Two elastic bodies, a set of candidate contact points, and either a load
//! or an approach: assemble the influence matrix `S = A(1) + A(2)` and the
//! initial separations `eps`, reduce the contact conditions
//!
//! ```text
//!     Y = S F + eps - alpha e,   e^T F = P,   F >= 0,  Y >= 0,  F_k Y_k = 0
//! ```
//!
//! to a (mixed) LCP, solve it with the pivoting engine of `elcon-lcp`, and
//! return forces, pressures, gaps, the approach, the contact set and its
//! extent, with a certificate computed from the original S, eps and P.
//! [`references`] holds the closed forms (Hertz, flat punch) the results are
//! checked against.
//!
//! Units: any consistent set (say inch, pound, psi; or metre, newton,
//! pascal); forces are per unit length and pressures per unit length per
//! unit width for a 2D line contact.
//!
//! Everything the API takes is re-exported here (the bodies, materials and
//! point sets of `elcon-influence`, the methods and options of `elcon-lcp`),
//! so this crate alone is enough; [`grid`] lays points out relative to a
//! Hertz contact as a scene's `across` and `zone` do.
//!
//! ```
//! use elcon_analysis::references::HertzSpheres;
//! use elcon_analysis::{
//!     Body, ContactProblem, Geometry, Loading, Material, Method, Options, PointSet, Surface,
//!     combined_modulus, grid,
//! };
//!
//! // Two steel spheres, R1 = 1 in, R2 = 10 in, P = 100 lb (Conry & Seireg, Example 1).
//! let steel = Material::new(30e6, 0.3).unwrap();
//! let hertz = HertzSpheres::new(combined_modulus(&steel, &steel), 1.0 / (1.0 + 0.1), 100.0).unwrap();
//! let a = hertz.contact_radius();
//! // 17 points across the contact's diameter (spacing a / 8), out to 1.3 a.
//! let points = grid::hertz_disk(a, 17, 1.3).unwrap();
//! let body = Body::uniform_patch(steel);
//! let geometry = Geometry::Surfaces(Surface::Sphere { radius: 1.0 }, Surface::Sphere { radius: 10.0 });
//! let problem = ContactProblem::new(points, &body, &body, &geometry, Loading::load(100.0)).unwrap();
//! let sol = problem.solve(Method::Lemke, &Options::default()).unwrap();
//! assert!(sol.certificate.holds());
//! assert!((sol.approach / hertz.approach() - 1.0).abs() < 0.01);
//!
//! // The same problem with S held matrix-free (an FFT convolution, O(N)
//! // memory: grids of 10^4 to 10^6 points), solved by the conjugate gradient.
//! let points: PointSet = grid::hertz_disk(a, 17, 1.3).unwrap();
//! let large = ContactProblem::lattice(points, &body, &body, &geometry, Loading::load(100.0)).unwrap();
//! let iterative = large.solve(Method::ConjugateGradient, &Options::default()).unwrap();
//! assert!(iterative.certificate.holds());
//! assert!((iterative.approach / sol.approach - 1.0).abs() < 1e-9);
//! ```

pub mod contact;
pub mod discretization;
mod edge;
mod ellipse;
mod error;
pub mod estimate;
pub mod grid;
mod influence;
pub mod loading;
pub mod references;
pub mod rigid;
pub mod rotation;
mod storage;
pub mod subsurface;
pub mod system;
pub mod zone;

pub use contact::{
    AxialProfile, ContactCertificate, ContactProblem, ContactSolution, Curvature, Departure,
    Geometry, HeightMap, Interpolation, Layout, Plan, Principal, ProblemBuilder, ProfileAxis,
    Surface, Warning, separations,
};
pub use elcon_influence::{
    Body, Dimension, Material, Model, PointSet, combined_modulus, combined_modulus_of,
};
pub use elcon_lcp::{Method, Options};
pub use ellipse::ContactEllipse;
pub use error::{AnalysisError, Num};
pub use estimate::{Estimate, Relief, Tableau};
pub use grid::GridFamily;
pub use influence::Products;
pub use loading::{Loading, Normal, Tilt};
pub use rigid::{Rigid, RigidMode};
pub use storage::{AUTO_DENSE_LIMIT, Storage};
