//! The integration tests of analysis, gathered into one test binary (one link
//! instead of one a file): each module is what a file of tests/ was.

mod common;
mod contact_edge;
mod discretization;
mod errors;
mod matrix_free;
mod misalignment;
mod properties;
mod references;
mod stability;
mod subsurface;
mod system;
