//! The scenes through the library: read and validated (elcon-scene), run
//! (elcon-runner) and written (elcon-report). One test binary, a module per
//! concern.

mod common;

mod bodies;
mod bounds;
mod design_outcomes;
mod design_profile;
mod design_stage;
mod design_threads;
mod error_estimate;
mod errors;
mod fuzz;
mod parts;
mod plots;
mod stiff_foundation;
mod storage;
mod subsurface;
mod surface_files;
mod turned_ellipse;
mod units;
mod whole_scene;
