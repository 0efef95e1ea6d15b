//! Candidate contact points and the measure each one stands for.
//!
//! The possible contact zone is covered by N cells, one per candidate point
//! k, centred on it. A continuous pressure p is replaced by the forces
//!
//! ```text
//!     F_k = p_k A_k,      A_k = dx dy (Surface, area)   or   A_k = dx (Line, length per unit width)
//! ```
//!
//! so that `sum_k F_k` is the total load (per unit width for a line). All the
//! cells of one set have the same shape ([`Cell`]). The grid constructors
//! also record the integer lattice indices of the points, which lets the
//! assembly evaluate a translation-invariant kernel once per lattice offset.
//!
//! The module's parts: [`PointSet`] and its constructors (`set`), the cell
//! and its measure (`cell`), the lattice indices and the index back from
//! them (`lattice`), and the boundary flags (`boundary`).

mod boundary;
mod cell;
mod lattice;
mod set;

pub use crate::dimension::Dimension;
pub use cell::Cell;
pub(crate) use lattice::LatticeBox;
pub use lattice::{Lattice, LatticeIndex, LatticeIter};
pub use set::{MAX_DENSE_POINTS, MAX_POINTS, PointSet};
