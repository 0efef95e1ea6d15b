//! # elcon-scene: TOML scenes, batch runs and reports
//!
//! Makes elcon usable without writing Rust. A scene file states its units,
//! the two bodies, the surfaces, the candidate points, the load or
//! approach, the method, and only when wanted a design stage and plots; a
//! batch file sweeps keys of a scene. This crate validates them (messages
//! name the file, line, column and field), runs them (in parallel for a
//! batch), and writes the results whole or not at all: result.json,
//! pressure.csv, SVG plots, and for batches a results table in CSV and
//! Markdown with an error-against-run-time plot.
//!
//! The contact problem solved is that of elcon-analysis,
//! `Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`, `F_k Y_k = 0`; the
//! schema is documented in docs/scenes.md and the outputs in
//! docs/results.md.

mod batch;
mod error;
mod output;
mod plot;
mod run;
mod scene;
mod schema;

pub use batch::{Batch, BatchOutcome, BatchRun, Progress, Shard, merge, run_batch};
pub use error::{Location, SceneError};
pub use output::{write_atomic, write_run};
pub use run::{
    AttemptJson, CertificateJson, DesignCaseJson, DesignJson, DesignRun, Errors, ReferenceJson,
    Run, RunResult, Seconds, StatisticsJson, SymmetryJson, run,
};
pub use scene::{
    BodySpec, DesignFamily, DesignSpec, Outputs, Plot, PointsSpec, Reference, RelativeTo, Scene,
    Units,
};
