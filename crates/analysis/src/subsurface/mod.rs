//! Stresses below the surface of each elastic half-space body, from a
//! solved contact's forces: where a contact fails (pitting starts near the
//! depth of the largest shear stress).
//!
//! Each body's stress at `(x, y, z)`, z its depth, is the sum over the
//! points in contact of their pressure times the body's stress influence
//! coefficient (`elcon_influence::stress`), with that body's own Poisson's
//! ratio (dissimilar bodies have different fields; E does not enter):
//!
//! ```text
//!     sigma(x, y, z) = sum_k p_k T(x - x_k, y - y_k, z; cell_k, nu)
//! ```
//!
//! T is Love's uniform pressure on the cell (the uniform-patch model), the
//! point force's (the point-force model's: valid a cell or more below the
//! surface, where a cell looks like a point), or the uniform strip's in
//! plane strain (a line contact). A rigid body has no stresses; beams and
//! Winkler foundations are not half-spaces: not applicable. Reported per
//! body: the maxima of the von Mises stress, the largest shear (Tresca) and
//! the orthogonal shears `tau_xz`, `tau_yz`, each with its position and
//! depth (found on a grid of depths below the contact, then refined by a
//! pattern search, not only on the grid); the section x against depth
//! through the point of largest von Mises stress; and the profile along
//! depth below the peak pressure.

mod field;
pub mod reference;

pub use field::{
    BodyStresses, DEPTH_SPAN, Peak, Section, StressField, Subsurface, SubsurfaceOptions,
    contact_half_width, depth_grid,
};
