//! The checks the per-crate tests share (the shared scenes are
//! elcon-fixtures').

pub mod checks;
