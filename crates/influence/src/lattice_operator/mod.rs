//! The matrix-free influence operator on a lattice: `y = S x` by a
//! zero-padded (non-periodic, "DC-FFT") convolution, in O(N) memory and
//! O(N log N) time, never forming the N x N matrix S.
//!
//! On a lattice grid (the points at `(i_k dx, j_k dy)` up to a shift,
//! [`PointSet::lattice`](crate::PointSet::lattice)) the half-space part of
//! S depends only on the offset between two points,
//! `S_kj = K(i_k - i_j, j_k - j_j)`, with K the
//! bodies' kernels summed with their compliances, the self-term at (0, 0)
//! (see [`assemble`](crate::assemble) and [`crate::models`]); a Winkler
//! foundation adds `1 / (k A_k)` on the diagonal. With the forces spread on
//! the lattice's bounding box, `X[i, j] = x_k` at `(i, j) = (i_k, j_k)` and 0
//! on the cells that hold no point, the product is the linear (aperiodic)
//! convolution
//!
//! ```text
//!     Y[i, j] = sum_{i' < n1} sum_{j' < n2} K(i - i', j - j') X[i', j'],     (S x)_k = Y[i_k, j_k] + x_k / (k_w A_k)
//! ```
//!
//! over the `n1 x n2` box. K is even in both offsets and only
//! `|i - i'| <= n1 - 1`, `|j - j'| <= n2 - 1` occur, so K embedded in a
//! `P1 x P2` circulant with `P_a >= 2 n_a - 1`,
//!
//! ```text
//!     Kc[a, b] = K(a*, b*),   a* = a (a < n1), a - P1 (a > P1 - n1), no term otherwise (Kc = 0)
//! ```
//!
//! and X zero-padded to `P1 x P2` give the same Y on the box through the
//! circular convolution theorem, `Y = IDFT(DFT(Kc) . DFT(X))`, without
//! wrap-around: the padding keeps the images of the box out of it. The
//! padded lengths are the smallest even 5-smooth numbers `>= 2 n - 1`, fast
//! for the FFT. Kc is real and even, so `DFT(Kc)` is real and even: it is
//! stored on `(P1/2 + 1) x (P2/2 + 1)` frequencies, scaled by `1/(P1 P2)`.
//!
//! The kernel table is the one the dense assembly gathers from (one kernel
//! evaluation per lattice offset, the same functions and self-term), so the
//! operator reproduces `assemble`'s S to the FFT's rounding (about 1e-15 of
//! the largest `|S x|`).
//!
//! Each product, in two bands of the row frequencies (`BANDS`): for each
//! band, `n1` real-to-complex row transforms of length P2 (the rows beyond
//! the box are zero and skipped) of which the band's frequencies are kept,
//! the band's complex column transforms of length P1 forward and back with
//! the product by `DFT(Kc)` between, and `n1` complex-to-real row
//! transforms of the band (the others zero), added into y: the inverse is
//! linear, so the bands add up to the whole (realfft over rustfft, planned
//! once). The second band costs a second pass of row transforms, about a
//! third more work, and halves the workspace. The row transforms and the
//! batches of column transforms are shared among the threads of the
//! current rayon pool (on a pool of one thread, done on the caller's);
//! nothing is summed across them, so a product is the same to the bit on
//! any number of threads.
//! Memory: the stored spectrum (`8 (P1/2 + 1)(P2/2 + 1)` bytes, about
//! `8 n1 n2`), the gather order (12 bytes per segment of consecutive points
//! in a lattice row: one a row on a surface grid, one a point on a line,
//! whose rows hold a point each) and one workspace of a band,
//! `n1 ceil((P2/2 + 1) / 2)` complex values (about `8 n1 n2` bytes), plus
//! a batch of columns per thread (`COLUMN_BATCH P1` complex values) and
//! plans of O(P1 + P2), on one thread: 19 bytes per point on a 256 x 256
//! grid, 27 on a disk of 51,433 points (its bounding box holds 4/pi as many
//! cells). A grid's point set takes 2 bytes per point.
//! [`LatticeOperator::estimate_bytes`] gives the figure before anything is
//! built; the construction holds nothing of the box's size but the
//! spectrum (the kernel table is made a row at a time).
//!
//! Units: as S. With x the forces F (force; per unit width on a line), y is
//! the deflection (length); S's entries are in length per force.
//!
//! Models: the point-force and uniform-patch half-spaces on a surface grid,
//! the plane-strain strip on a line, any of them with a Winkler foundation
//! (a diagonal term), rigid bodies (nothing). Beams are refused
//! ([`InfluenceError::NotTranslationInvariant`](crate::InfluenceError::NotTranslationInvariant)).
//! The periodic convolution (periodic surfaces) is not provided: the
//! half-space kernels' lattice sums
//! diverge, so it needs a different kernel (the spectral `2 / (E* |q|)` with
//! the mean load set apart), not a different padding.
//!
//! A column of S is the kernel table shifted to its point
//! ([`LatticeKernel::add_columns`]): `y += S d` for a `d` with a few
//! non-zero entries in O(N) a column, what the conjugate gradient takes in
//! place of a product where a step changed the contact set at a few
//! points. The table (`n1 x n2` values, 8 bytes a cell of the box) is kept
//! for them.
//!
//! The module's parts: the operator and its kernel (`operator`), the
//! convolution's banded transforms and their workspace (`convolution`),
//! the columns from the table (`columns`), the
//! kernel's spectrum (`spectrum`), an approximate inverse for a
//! preconditioned conjugate gradient (`preconditioner`), the gather order of the points on the
//! box (`gather`), and the padded grid with its byte counts (`grid`).

mod columns;
mod convolution;
mod gather;
mod grid;
mod operator;
mod preconditioner;
mod spectrum;
#[cfg(test)]
mod tests;

pub use convolution::LatticeWorkspace;
pub(crate) use grid::padded_length;
pub use operator::{LatticeKernel, LatticeOperator};
pub use preconditioner::{LatticePreconditioner, SYMBOL_FLOOR};
