//! # elcon-influence: influence coefficients of elastic bodies in contact
//!
//! Materials, candidate contact points and influence-coefficient models, and
//! the assembly of the influence matrix of Conry & Seireg (1971): with N
//! candidate points k, the influence coefficient `a_kj^(b)` of body b is its
//! deflection at point k due to a unit force at point j, and for the two
//! bodies in contact
//!
//! ```text
//!     S = A(1) + A(2),      S_kj = a_kj^(1) + a_kj^(2)      (the paper's eqs. 5-6)
//! ```
//!
//! so that `S F` is the total deflection of the two surfaces under the
//! contact forces F. For every model here S is symmetric positive definite.
//!
//! - [`Material`]: E and nu, the compliance `(1 - nu^2)/E` and the combined
//!   modulus `1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2` ([`combined_modulus`]);
//! - [`PointSet`]: the candidate points and the measure A_k (area, or length
//!   per unit width) each one stands for, `F_k = p_k A_k`;
//! - [`Model`] / [`Body`]: Boussinesq point forces, Love's uniform pressure on
//!   rectangular cells, plane-strain strips, a Winkler foundation, an
//!   Euler-Bernoulli beam referenced at its loaded point, a rigid body; the
//!   unit kernels are in [`kernels`];
//! - [`assemble`]: S as a dense faer matrix (column-major), one kernel
//!   evaluation per lattice offset on a grid, half-space bodies of the same
//!   kernel summed into one combined compliance;
//! - [`Folding`] / [`assemble_folded`]: for a mirror-symmetric problem, one
//!   unknown per orbit and the folded matrix, never forming the full S;
//! - [`LatticeOperator`]: the product `S x` on a lattice grid (disk,
//!   rectangle, line) by a zero-padded FFT convolution of the same kernel
//!   table, in O(N) memory and O(N log N) time, for iterative solvers on
//!   grids too large for the dense S; [`LatticeKernel`] is the same without
//!   a workspace of its own, shared between threads or problems.
//!
//! Units: any consistent set. With lengths in inches and E in psi, S is in
//! inches per pound; with metres and pascals, metres per newton. On a line
//! (2D, plane strain) forces are per unit width and S is in length per
//! (force per unit width). Nothing here assumes a unit system.
//!
//! ```
//! use elcon_influence::{Body, Material, PointSet, assemble, combined_modulus};
//! use faer::Side;
//!
//! // Conry & Seireg's Example 1: two steel spheres (E = 30e6 psi, nu = 0.3),
//! // Hertz contact radius about 0.016 in under 100 lb.
//! let steel = Material::new(30e6, 0.3).unwrap();
//! let h = 0.016 / 5.0; // 5 cells per contact radius
//! let points = PointSet::grid_disk(h, 1.3 * 0.016).unwrap();
//! let sphere = Body::uniform_patch(steel);
//! let s = assemble(&points, &[&sphere, &sphere]).unwrap(); // S = A(1) + A(2)
//!
//! assert_eq!(s.nrows(), points.len());
//! // Self-term: both bodies' centre deflection of a square cell of side h
//! // under a unit force, 4 ln(1 + sqrt 2) / (pi E* h).
//! let e_star = combined_modulus(&steel, &steel);
//! let expected = 4.0 * (1.0 + 2f64.sqrt()).ln() / (std::f64::consts::PI * e_star * h);
//! assert!((s[(0, 0)] / expected - 1.0).abs() < 1e-14);
//! assert_eq!(s[(0, 7)], s[(7, 0)]); // symmetric
//! assert!(s.llt(Side::Lower).is_ok()); // positive definite
//! ```
//!
//! Without forming S, on a 101 x 101 grid (N = 10,201; the dense S would
//! take 830 MB):
//!
//! ```
//! use elcon_influence::{Body, LatticeOperator, Material, PointSet, combined_modulus};
//!
//! let steel = Material::new(30e6, 0.3).unwrap(); // psi
//! let points = PointSet::grid_rectangle(0.05, 0.05, 101, 101).unwrap(); // inches
//! let sphere = Body::uniform_patch(steel);
//! let mut s = LatticeOperator::new(&points, &[&sphere, &sphere]).unwrap();
//!
//! // A uniform pressure p on the whole 0.1 in square: by superposition, the
//! // centre deflects by 4 ln(1 + sqrt 2) p L / (pi E*) (Love).
//! let p = 1e5; // psi
//! let forces: Vec<f64> = (0..points.len()).map(|k| p * points.measure(k)).collect();
//! let mut deflection = vec![0.0; points.len()]; // inches
//! s.apply(&forces, &mut deflection);
//! let centre = points.len() / 2;
//! let e_star = combined_modulus(&steel, &steel);
//! let love = 4.0 * (1.0 + 2f64.sqrt()).ln() * p * 0.1 / (std::f64::consts::PI * e_star);
//! assert!((deflection[centre] / love - 1.0).abs() < 1e-12);
//! assert!(s.memory_bytes() < 50 * points.len());
//! ```
//!
//! References: Conry, T. F. and Seireg, A. (1971), "A Mathematical
//! Programming Method for Design of Elastic Bodies in Contact", J. Appl.
//! Mech. 38, 387-392; Love, A. E. H. (1929), "The stress produced in a
//! semi-infinite solid by pressure on part of the boundary", Phil. Trans. R.
//! Soc. A 228, 377-420; Johnson, K. L. (1985), Contact Mechanics, ch. 2-3.

pub mod assembly;
mod dimension;
mod error;
#[cfg(test)]
mod fixtures;
pub mod kernels;
pub mod lattice_operator;
pub mod material;
pub mod models;
pub mod points;
pub mod stress;
pub mod stress_layers;
pub mod symmetry;
mod terms;

pub use assembly::{assemble, assemble_direct, assemble_folded, influence};
pub use error::InfluenceError;
pub use kernels::{boussinesq, love_rectangle, plane_strain_strip};
pub use lattice_operator::{
    LatticeKernel, LatticeOperator, LatticePreconditioner, LatticeWorkspace,
};
pub use material::{Material, combined_modulus, combined_modulus_of};
pub use models::{Beam, Body, Model};
pub use points::{
    Cell, Dimension, Lattice, LatticeIndex, LatticeIter, MAX_DENSE_POINTS, MAX_POINTS, PointSet,
};
pub use stress::{Stress, love_rectangle_stress, point_force, strip_stress};
pub use stress_layers::{StressKernel, StressLayers};
pub use symmetry::Folding;
