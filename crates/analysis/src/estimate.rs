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
//! A pivot of a dense method costs about `c n^2` and a path takes about a
//! pivot per point in contact, so `c_method n^3` is the case of every point
//! in contact (a beam on a foundation, a flat punch): an upper-ish bound,
//! which a Hertz contact (some of the points in contact, pivots that skip
//! what they never read) stays below by up to about 2 times. The factors
//! were measured through `elcon run` on the reference machine
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
/// about one FFT product each, growing a little faster than N): Example 1
/// unfolded on the lattice, 1.9 s at N = 68,085 and 16.6 s at N = 272,321
/// for the whole run (2.8e-5 and 6.1e-5 a point), rounded up.
const CG_SECONDS_PER_POINT: f64 = 1e-4;

/// Seconds per n^3 of a tableau method's solve on the symmetric tableau
/// (Lemke's method; the restricted simplex under load without initial
/// interference). A pivot costs about c n^2 and a path takes a pivot per
/// contact point, so n^3 is the case of every point in contact: Example
/// 2's beam unfolded, Lemke's method 5.7 s at N = 4000 and 14.7 s at
/// N = 6000 (8.8e-11 and 6.8e-11 n^3), the restricted simplex 4.1 and
/// 11.7 s, rounded up. A Hertz contact takes fewer and cheaper pivots:
/// Example 1 unfolded at N = 6625, 5057 in contact, 12.1 s (docs/reliability.md).
const TABLEAU_SECONDS_PER_CUBE: f64 = 1e-10;

/// Seconds per n^3 of the restricted simplex on the general tableau
/// (displacement control, or initial interference): about a pivot per
/// point of a tableau up to twice as wide. Example 2's beam unfolded under
/// an approach, every point in contact: 9.3 s at N = 3000 and 49 s at
/// N = 4500 (3.4e-10 and 5.4e-10 n^3), rounded up; Example 1 under an
/// approach, 5.9 s of CPU at N = 2933 and 14.5 s at N = 3801 (2.3e-10 and
/// 2.6e-10 n^3; docs/reliability.md).
const GENERAL_SECONDS_PER_CUBE: f64 = 6e-10;

/// Seconds per n^3 of block principal pivoting (a few factorizations of
/// the contact set's block): Example 2's beam unfolded, 1.9 s at N = 4000
/// and 5.3 s at N = 6000 (2.9e-11 and 2.5e-11 n^3), rounded up.
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
/// the contact block's factor); a Hertz contact takes less (1.96; the
/// symmetric tableau 3.0, with the updates its blocks skip kept);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn seconds(method: Method, tableau: Tableau, n: usize) -> f64 {
        Estimate::dense(Storage::Dense, method, tableau, n, n).seconds
    }

    #[test]
    fn a_dense_solve_s_seconds_grow_like_the_cube_of_its_unknowns() {
        let cases = [
            (Method::BlockPivoting, Tableau::Symmetric),
            (Method::Lemke, Tableau::Symmetric),
            (Method::RestrictedSimplex, Tableau::Symmetric),
            (Method::RestrictedSimplex, Tableau::General),
        ];
        for (method, tableau) in cases {
            let mut last = 0.0;
            for n in [1, 10, 100, 1000, 4000, 6000, 65_536] {
                let s = seconds(method, tableau, n);
                assert!(s > last, "{method:?} {tableau:?} {n}: {s}");
                last = s;
            }
            // Twice the unknowns, eight times the pivots' work.
            let ratio = seconds(method, tableau, 4000) / seconds(method, tableau, 2000);
            assert!((ratio - 8.0).abs() < 8.0 * f64::EPSILON * 16.0, "{ratio}");
        }
    }

    #[test]
    fn the_methods_are_ordered_by_their_measured_cost() {
        let n = 4000;
        let block = seconds(Method::BlockPivoting, Tableau::Symmetric, n);
        let lemke = seconds(Method::Lemke, Tableau::Symmetric, n);
        let simplex = seconds(Method::RestrictedSimplex, Tableau::Symmetric, n);
        let general = seconds(Method::RestrictedSimplex, Tableau::General, n);
        assert!(block < lemke && lemke == simplex && simplex < general);
        // Lemke's method on a beam of 4000 points, every one in contact,
        // runs in seconds (5.7 s measured), not under a second or minutes.
        assert!((1.0..60.0).contains(&lemke), "{lemke}");
        // The general tableau on the beam of 4500 points under an
        // approach (49 s measured, 61 s the whole run) is estimated above it.
        let general = seconds(Method::RestrictedSimplex, Tableau::General, 4500);
        assert!(general > 49.0, "{general}");
    }
}
