//! Shared cases of the per-crate tests.

pub mod stability_cases;
