//! The command-line tests (cli: the commands as a user runs them; faults:
//! failures, kills and interrupts), gathered into one test binary (one link
//! instead of one a file): each module is what a file of tests/ was.

mod cli;
mod common;
mod faults;
