//! The geometric dimension of a contact problem: a line (2D, plane strain,
//! forces per unit width) or a surface (3D). No equation here; it selects
//! the measure `A_k` of a cell (length `dx` or area `dx dy`) and which
//! influence models apply. Its own module so that the error type can name it
//! without depending on the point sets.

use std::fmt;

/// The geometric dimension of a contact problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dimension {
    /// A 2D plane (plane-strain) problem: points on the x axis, each standing
    /// for a length `dx`; forces are per unit width (force / length).
    Line,
    /// A 3D problem: points in the x-y plane, each standing for an area
    /// `dx dy`; forces are forces.
    Surface,
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Line => "line (2D)",
            Self::Surface => "surface (3D)",
        })
    }
}
