//! The integration tests of lcp, gathered into one test binary (one link
//! instead of one a file): each module is what a file of tests/ was.

mod border;
mod common;
mod complementarity;
mod errors;
mod linear;
mod nonnegative;
mod stopping;
mod threads;
