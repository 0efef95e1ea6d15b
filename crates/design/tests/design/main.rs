//! The integration tests of design, gathered into one test binary (one link
//! instead of one a file): each module is what a file of tests/ was.

mod common;
mod descent;
mod design;
mod errors;
mod names;
mod properties;
mod sequence;
mod stress_objective;
