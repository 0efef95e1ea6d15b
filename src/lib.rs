//! # elcon: elastic bodies in contact by mathematical programming
//!
//! The root crate re-exports the workspace's layers, so a user can depend on
//! `elcon` alone (or on any single crate below it):
//!
//! - [`lcp`] (`elcon-lcp`): the dense tableau pivoting engine: LCPs, mixed
//!   LCPs and programs with complementarity constraints, certified;
//! - [`influence`] (`elcon-influence`): materials, candidate points and
//!   influence-coefficient models, assembled into `S = A(1) + A(2)`;
//! - [`analysis`] (`elcon-analysis`): the contact problem of Conry & Seireg
//!   (1971) and the closed-form references it is checked against;
//! - [`design`] (`elcon-design`): profile corrections, min-max load
//!   intensity designs and target-pressure separations;
//! - `scene` (`elcon-scene`, with the default `cli` feature): TOML scenes,
//!   batch sweeps and their reports, behind the `elcon` command line.

pub use elcon_analysis as analysis;
pub use elcon_design as design;
pub use elcon_influence as influence;
pub use elcon_lcp as lcp;
/// TOML scenes, batches and reports (with the default `cli` feature).
#[cfg(feature = "cli")]
pub use elcon_scene as scene;
