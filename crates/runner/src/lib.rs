//! # elcon-runner: runs scenes and batches
//!
//! Takes the scenes elcon-scene reads to results elcon-report writes:
//!
//! - [`prepare`]: a scene's cost estimated ([`Estimate`]: peak memory and
//!   a class of run time) and compared with the memory ceiling before
//!   anything of size N x N is allocated; what `elcon check` prints;
//! - [`run`]: assemble `S = A(1) + A(2)` and eps, solve
//!   `Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`, `F_k Y_k = 0` with
//!   the scene's method, certified; estimate the discretization error on
//!   coarser grids; compare with the closed form that applies; the stresses
//!   below the surface; the design stage;
//! - [`run_bearing`]: a bearing scene built into a system of contacts and
//!   solved, with its Hertz-spring reference and rating life;
//! - [`run_batch`]: a batch's runs in parallel, each isolated and admitted
//!   against the memory ceiling, written whole and journaled so a killed
//!   batch resumes; shards of a sweep ([`Shard`]) and [`merge`], which joins
//!   their tables.
//!
//! The command line and the Python package both call it.

mod batch_run;
mod bearing;
mod compare;
mod design_keys;
mod design_load;
mod design_stage;
mod error;
mod error_estimate;
mod estimate;
mod journal;
mod merge;
mod prepare;
mod run;
mod shard;
mod subsurface;

pub use batch_run::{BatchDone, BatchOptions, Progress, batch_dir, run_batch};
pub use bearing::{BearingEstimate, run_bearing};
pub use design_keys::{DesignCaller, design_reason};
pub use error::RunError;
pub use estimate::{BASELINE, DesignEstimate, Estimate, TimeClass, TimeFigure};
pub use merge::merge;
pub use prepare::{BatchCheck, Prepared, check_batch, prepare};
pub use run::run;
pub use shard::{Shard, ShardError};
