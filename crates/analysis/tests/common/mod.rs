//! Shared cases and checks of the per-crate tests.

pub mod checks;
pub mod stability_cases;

// Not every test uses the builders.
#[allow(unused_imports)]
pub use stability_cases::scenes;
