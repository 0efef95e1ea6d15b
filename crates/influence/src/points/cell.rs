//! The rectangular cell every point of a set stands for, and its measure
//!
//! ```text
//!     A_k = dx dy (Surface, area)   or   A_k = dx (Line, length per unit width)
//! ```
//!
//! the same for every point of a set (`F_k = p_k A_k`).

use crate::dimension::Dimension;

/// The rectangular cell every point of a set stands for, centred on the
/// point: `dx` along x, `dy` along y (length units).
///
/// For a [`Dimension::Line`] set `dy` is the unit width and is stored as 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// Cell size along x (length).
    pub dx: f64,
    /// Cell size along y (length); 1 (unit width) for a line set.
    pub dy: f64,
}

impl Cell {
    /// A square cell of side `h`.
    pub fn square(h: f64) -> Self {
        Self { dx: h, dy: h }
    }

    /// The measure A_k of the cell: the area `dx dy` (Surface) or the length
    /// `dx` (Line, per unit width).
    pub fn measure(&self, dimension: Dimension) -> f64 {
        match dimension {
            Dimension::Line => self.dx,
            Dimension::Surface => self.dx * self.dy,
        }
    }
}
