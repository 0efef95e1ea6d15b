//! Checks of a scene as a whole, beyond each value's own range: what the
//! solve or the design would otherwise refuse (or answer meaninglessly)
//! only once it runs, so that `elcon check` refuses the same scenes as
//! `elcon run` before the solve; the bounds on the knobs that cost time or
//! memory; and the warnings for a grid too coarse for the contact. By
//! concern:
//!
//! - `curvature`: the surfaces' summed curvatures, along x and y and along
//!   a quadric gap's principal directions;
//! - `strain`: the small strain of the linear models (a load, an approach,
//!   separations, a beam's slope, a plane-strain datum);
//! - `deformation`: a load's deformation resolved against the separations
//!   and within the doubles' range, and the input out of scale a refusal
//!   names;
//! - `grid`: the grid's resolution of the contact, and the bodies against
//!   the grids;
//! - `loading`: a moment's load centre and prescribed tilts against the
//!   candidate zone;
//! - `design`: a design's cases, degree, constant and loads against its
//!   grids.

mod curvature;
mod deformation;
mod design;
mod grid;
mod loading;
mod strain;

pub(crate) use curvature::curvatures;
pub(crate) use deformation::{
    Factor, Mechanism, compliance_in_range, deformation, deformation_out_of_scale, mechanism,
    unresolved,
};
pub(crate) use design::{DesignView, MAX_DESIGN_CELL_ASPECT, design, design_cases};
pub use design::{MAX_BEAM_REACH, MAX_DEGREE, MAX_END_LIFT};
pub use grid::MIN_POINTS_RESOLVED;
pub(crate) use grid::{
    MIN_POINTS_ACROSS, Unresolved, bodies_on_grid, coarse_grid, listed_line, no_hertz_reason,
    scale_out_of_range, unresolved_grid,
};
pub use loading::MAX_ROTATION;
pub(crate) use loading::{load_centre, tilt_off_zone, tilt_off_zone_ellipse};
pub(crate) use strain::{
    Labels, datum_strain, hertz_approach_strain, refuse_normal, small_separations, small_strain,
    strain, zone_size,
};
pub use strain::{MAX_STRAIN, StrainExtent, approach_strain};
