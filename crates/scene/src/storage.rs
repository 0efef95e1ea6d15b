//! How a scene holds its influence matrix, and which method `auto` picks.
//!
//! A dense S costs 8 N^2 bytes and an exact method about N^3 flops; the
//! matrix-free lattice operator costs O(N) memory and the conjugate
//! gradient O(N log N) a product. `solver.method = "auto"` (the default)
//! takes block pivoting on the dense S while the unknowns (after folding)
//! are at most [`AUTO_DENSE_LIMIT`], and the conjugate gradient on the
//! lattice operator above it when the points are a lattice and no body is
//! a beam (else block pivoting, which the memory estimate may refuse). An
//! explicit `"conjugate-gradient"` runs matrix-free whenever the lattice
//! operator applies and the scene does not fold (a folded problem is
//! smaller dense); an explicit pivoting method always holds S.

use elcon_analysis::{Layout, Method};
use elcon_influence::{Body, LatticeOperator, PointSet};

/// Above this many unknowns `auto` solves matrix-free (docs/performance.md,
/// "Dense or matrix-free": where the conjugate gradient on the lattice
/// operator overtakes block pivoting on the dense S).
pub const AUTO_DENSE_LIMIT: usize = 2000;

/// How S is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Storage {
    /// Every entry (or the folded matrix's).
    Dense,
    /// By its products: an FFT convolution on the lattice.
    MatrixFree,
}

impl Storage {
    /// "dense" or "matrix-free".
    pub fn name(self) -> &'static str {
        match self {
            Storage::Dense => "dense",
            Storage::MatrixFree => "matrix-free",
        }
    }
}

/// The method asked for in `solver.method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodChoice {
    /// `"auto"`: see the module documentation.
    Auto,
    /// A method by name.
    Given(Method),
}

/// The method and the storage of a scene's contact solve.
pub(crate) fn choose(
    choice: MethodChoice,
    points: &PointSet,
    bodies: [&Body; 2],
    layout: Option<&Layout>,
    fold: bool,
) -> (Method, Storage) {
    let lattice = || LatticeOperator::estimate_bytes(points, &bodies).is_ok();
    let folds = fold && layout.is_some_and(|l| l.folding.is_some());
    let unknowns = layout.map_or(points.len(), Layout::unknowns);
    match choice {
        MethodChoice::Given(Method::ConjugateGradient) if !folds && lattice() => {
            (Method::ConjugateGradient, Storage::MatrixFree)
        }
        MethodChoice::Given(method) => (method, Storage::Dense),
        MethodChoice::Auto if unknowns > AUTO_DENSE_LIMIT && lattice() => {
            (Method::ConjugateGradient, Storage::MatrixFree)
        }
        MethodChoice::Auto => (Method::BlockPivoting, Storage::Dense),
    }
}
