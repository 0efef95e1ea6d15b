//! What a contact solve will cost, known before anything of size N x N is
//! allocated: its peak memory and rough seconds, from the storage
//! ([`Storage`]), the method and the unknowns n (N, or one per orbit when
//! folded). Dense, the solve keeps `m` matrices of n x n, 8 bytes an
//! entry, S included ([`matrices`]); matrix-free, the lattice operator
//! (`elcon_influence::LatticeOperator::estimate_bytes`) and a few vectors
//! of N:
//!
//! ```text
//!     dense        m 8 n^2 bytes,                  c_method n^3 seconds
//!     matrix-free  operator + 6 x 8 N bytes,       1e-4 N seconds
//! ```
//!
//! The factors were measured through `elcon run` on the reference machine
//! (docs/reliability.md, docs/performance.md) and rounded up.

use elcon_influence::PointSet;
use elcon_lcp::Method;

use crate::storage::Storage;

/// Bytes of one matrix entry (f64).
const ENTRY: f64 = 8.0;

/// Vectors of N doubles a matrix-free solve holds besides the operator:
/// the separations, the border, then the conjugate gradient's iterate, its
/// product `M z`, the direction and its product `M t`, or at the end the
/// answer and the certificate's two columns; a grid's point set holds a
/// quarter of one; rounded up.
const CG_VECTORS: f64 = 7.0;

/// Vectors of N doubles a matrix-free problem solved again and again (a
/// design's load case) holds besides its operator: its solve's
/// ([`CG_VECTORS`]) and its restricted solves' with the descent's model
/// rows, rounded up (docs/reliability.md's matrix-free design row: 169 MiB
/// measured against 220 MiB estimated, the plot included).
const HELD_VECTORS: f64 = 14.0;

/// Seconds per point of a matrix-free solve (a few hundred iterations of
/// about one FFT product each; docs/performance.md, "Dense or
/// matrix-free"), rounded up.
const CG_SECONDS_PER_POINT: f64 = 1e-4;

/// Seconds per n^3 of a tableau method's solve on the symmetric tableau
/// (Lemke's method; the restricted simplex under load without initial
/// interference): 3.2 s at N = 3745.
const TABLEAU_SECONDS_PER_CUBE: f64 = 7e-11;

/// Seconds per n^3 of the restricted simplex on the general tableau
/// (displacement control, or initial interference): 17.7 s at N = 3729.
const GENERAL_SECONDS_PER_CUBE: f64 = 3.5e-10;

/// Seconds per n^3 of block principal pivoting: 1.7 s at N = 3745.
const BLOCK_SECONDS_PER_CUBE: f64 = 3.5e-11;

/// Which tableau a tableau method works on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tableau {
    /// The symmetric tableau (Lemke's method on the contact form; the
    /// restricted simplex under load control without initial interference),
    /// or block pivoting.
    Symmetric,
    /// The general tableau: the restricted simplex under displacement
    /// control or with initial interference.
    General,
}

/// The N x N matrices a contact solve of `method` on `tableau` holds at its
/// peak, S included (measured peaks over n^2 doubles, rounded up; the
/// measurements are in docs/reliability.md). With every point in contact (a
/// beam on a foundation, a flat punch), the worst case the estimate
/// assumes: block pivoting 3.13 (S, its Cholesky factor of the whole
/// contact set, whose capacity doubles in place, and the blocks of the
/// last update), the symmetric tableau 3.16 (S, the swept tableau, then
/// the contact block's factor); a Hertz contact takes less (1.96, 2.19);
/// the conjugate gradient S alone (rounded up to 1.25 for its vectors);
/// the restricted simplex's general tableau 7.3 to 7.6 (S, the constraint
/// data, a tableau of twice S's width when most rows start with an
/// artificial, and the basis matrices of its refactorizations).
pub fn matrices(method: Method, tableau: Tableau) -> f64 {
    match (method, tableau) {
        // S itself; the iteration's vectors are O(N).
        (Method::ConjugateGradient, _) => 1.25,
        (Method::RestrictedSimplex, Tableau::General) => 7.75,
        _ => 3.25,
    }
}

/// Seconds per n^3 of a dense solve.
fn per_cube(method: Method, tableau: Tableau) -> f64 {
    match (method, tableau) {
        (Method::BlockPivoting, _) => BLOCK_SECONDS_PER_CUBE,
        (Method::RestrictedSimplex, Tableau::General) => GENERAL_SECONDS_PER_CUBE,
        _ => TABLEAU_SECONDS_PER_CUBE,
    }
}

/// Bytes of `count` matrices of n x n (saturating at infinity).
fn square_bytes(count: f64, n: usize) -> f64 {
    count * ENTRY * (n as f64) * (n as f64)
}

/// What changes to a problem would make it smaller, for a message that
/// refuses it: each a caller renders in its own terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Relief {
    /// Hold S matrix-free ([`Storage::Lattice`] with the conjugate
    /// gradient): O(N) memory on a lattice.
    MatrixFree,
    /// A method that keeps fewer matrices (block pivoting).
    FewerMatrices,
}

/// What a contact solve will cost (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// How S is held.
    pub storage: Storage,
    /// The method.
    pub method: Method,
    /// Candidate points N.
    pub points: usize,
    /// Unknowns n of the solve: N, or one per orbit when folded.
    pub unknowns: usize,
    /// The tableau a tableau method works on.
    pub tableau: Tableau,
    /// The solve's n x n matrices at its peak, S included ([`matrices`];
    /// 0 matrix-free).
    pub matrices: f64,
    /// Bytes of S as held: its entries (n x n), or the lattice operator.
    pub influence_bytes: f64,
    /// Bytes the solve holds at its peak, S included.
    pub solve_bytes: f64,
    /// Bytes the problem holds while it is solved again and again (a
    /// design's load case): S, or the operator with the vectors of its
    /// solves and restricted solves.
    pub held_bytes: f64,
    /// Bytes one solve holds beyond [`held_bytes`](Self::held_bytes):
    /// its `m - 1` working matrices (0 matrix-free: in `held_bytes`).
    pub work_bytes: f64,
    /// Bytes of a restricted solve's block `S_JJ` on every point (0
    /// matrix-free: it is solved by products).
    pub restricted_bytes: f64,
    /// Rough seconds of one solve (an order of magnitude).
    pub seconds: f64,
}

impl Estimate {
    /// A solve of `method` on a dense (or folded) S of `unknowns` unknowns.
    pub(crate) fn dense(
        storage: Storage,
        method: Method,
        tableau: Tableau,
        points: usize,
        unknowns: usize,
    ) -> Self {
        let m = matrices(method, tableau);
        Self {
            storage,
            method,
            points,
            unknowns,
            tableau,
            matrices: m,
            influence_bytes: square_bytes(1.0, unknowns),
            solve_bytes: square_bytes(m, unknowns),
            held_bytes: square_bytes(1.0, unknowns),
            work_bytes: square_bytes(m - 1.0, unknowns),
            restricted_bytes: square_bytes(1.0, unknowns),
            seconds: per_cube(method, tableau) * (unknowns as f64).powi(3),
        }
    }

    /// A solve of `method` on the lattice operator of `operator` bytes.
    pub(crate) fn matrix_free(
        storage: Storage,
        method: Method,
        operator: usize,
        points: &PointSet,
    ) -> Self {
        let n = points.len();
        let vectors = |count: f64| operator as f64 + count * ENTRY * n as f64;
        Self {
            storage,
            method,
            points: n,
            unknowns: n,
            tableau: Tableau::Symmetric,
            matrices: 0.0,
            influence_bytes: operator as f64,
            solve_bytes: vectors(CG_VECTORS),
            held_bytes: vectors(HELD_VECTORS),
            work_bytes: 0.0,
            restricted_bytes: 0.0,
            seconds: CG_SECONDS_PER_POINT * n as f64,
        }
    }

    /// What the solve holds, in words: "block-pivoting keeps about 3.25
    /// matrices of 1653 x 1653" or "conjugate-gradient matrix-free: the
    /// lattice operator and its vectors".
    pub fn holding(&self) -> String {
        if self.storage.holds_entries() {
            format!(
                "{} keeps about {:.2} matrices of {} x {}",
                self.method.name(),
                self.matrices,
                self.unknowns,
                self.unknowns
            )
        } else {
            format!(
                "{} matrix-free: the lattice operator and its vectors",
                self.method.name()
            )
        }
    }

    /// What would make the solve smaller, besides a coarser grid or
    /// folding by symmetry (the caller knows whether those apply).
    pub fn reliefs(&self) -> Vec<Relief> {
        let mut reliefs = Vec::new();
        if self.storage.holds_entries() {
            reliefs.push(Relief::MatrixFree);
            if self.method != Method::BlockPivoting {
                reliefs.push(Relief::FewerMatrices);
            }
        }
        reliefs
    }
}
