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
//! - [`elements`] (`elcon-elements`): machine elements as systems of
//!   contacts: radial ball and cylindrical roller bearings, with their
//!   reference models and rating life;
//! - with the default `cli` feature, the application behind the `elcon`
//!   command line: `scene` (`elcon-scene`: TOML scenes and batch files, read
//!   and validated), `runner` (`elcon-runner`: runs, design stages, error
//!   estimates, batches, shards and merge), `report` (`elcon-report`: the
//!   result schema and its writers) and `process` (`elcon-process`: memory
//!   ceiling, isolation, files written whole, thread and job policy).

pub use elcon_analysis as analysis;
pub use elcon_design as design;
pub use elcon_elements as elements;
pub use elcon_influence as influence;
pub use elcon_lcp as lcp;
/// Process plumbing: memory ceiling, isolation, files, threads (with the
/// default `cli` feature).
#[cfg(feature = "cli")]
pub use elcon_process as process;
/// The result schema and its writers (with the default `cli` feature).
#[cfg(feature = "cli")]
pub use elcon_report as report;
/// Runs, design stages, estimates, batches (with the default `cli` feature).
#[cfg(feature = "cli")]
pub use elcon_runner as runner;
/// TOML scenes and batch files, read and validated (with the default `cli`
/// feature).
#[cfg(feature = "cli")]
pub use elcon_scene as scene;
