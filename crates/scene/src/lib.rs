//! # elcon-scene: TOML scenes, batch runs and reports
//!
//! Makes elcon usable without writing Rust. A scene file states its units,
//! the two bodies, the surfaces, the candidate points, the load or
//! approach, the method, and only when wanted a design stage and plots; a
//! batch file sweeps keys of a scene. This crate validates them (messages
//! name the file, line, column and field), estimates what each will cost
//! and refuses what will not fit in memory, runs them (in parallel for a
//! batch; a failure or a panic in one is reported and the others go on),
//! and writes the results whole or not at all: result.json, pressure.csv,
//! SVG plots, and for batches a results table in CSV and Markdown with an
//! error-against-run-time plot.
//!
//! The contact problem solved is that of elcon-analysis,
//! `Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`, `F_k Y_k = 0`; the
//! schema is documented in docs/scenes.md, the outputs in docs/results.md
//! and the behaviour under faults and limits in docs/reliability.md.

mod batch;
mod batch_run;
mod compare;
mod ctx;
mod design_stage;
mod error;
mod error_estimate;
mod estimate;
mod faults;
mod isolate;
mod journal;
mod memory;
mod output;
mod plot;
mod plot_subsurface;
mod prepare;
mod run;
mod sanity;
mod scene;
mod schema;
mod shard;
mod subsurface;
mod tables;
mod zone;

pub use batch::{Batch, BatchRun, MAX_RUNS, is_batch_text, thousands};
pub use batch_run::{BatchDone, BatchOptions, Progress, run_batch};
pub use compare::{Errors, ReferenceJson, XY};
pub use ctx::{MAX_INPUT_BYTES, read_text};
pub use design_stage::{
    DesignCaseJson, DesignGridJson, DesignJson, DesignKey, DesignRun, design_reason,
    scene_design_key,
};
pub use elcon_analysis::{AUTO_DENSE_LIMIT, Storage};
pub use elcon_lcp::Cancel;
pub use error::{Location, SceneError};
pub use error_estimate::{DiscretizationJson, GridJson, QuantitiesJson, QuantityJson};
pub use estimate::{BASELINE, DesignEstimate, Estimate, TimeClass, TimeFigure};
pub use isolate::{install_panic_hook, interruptible, isolated};
pub use journal::JOURNAL;
pub use memory::{
    ADDRESS_SPACE_RESERVE, Ceiling, LIMIT_VARIABLE, Limit, MARGIN, gemm_reserve, human, parse_size,
};
pub use output::{Staging, write_atomic, write_run, write_run_files};
pub use plot::error_time;
pub use prepare::{BatchCheck, CHECK_EVERY_RUN, Prepared, REPORTED_FAILURES, check_batch, prepare};
pub use run::{Run, RunResult, Seconds, SolutionJson, SymmetryJson, run};
pub use sanity::{
    CANCELLING_CURVATURE, MAX_CONSTANT_OVER_ZONE, MAX_DEFORMATION, MAX_DEGREE, MAX_DESIGN_CASES,
    MAX_REFINEMENT_STEPS, MAX_ROTATION, MAX_STRAIN, MIN_DEFORMATION, MIN_POINTS_ACROSS,
    MIN_POINTS_RESOLVED, MIN_RESOLVED_DEFORMATION, max_pivots_bound,
};
pub use scene::{
    BodySpec, DesignFamily, DesignLayoutParts, DesignSpec, EllipseShape, HalfX, MAX_SLUG,
    MethodChoice, ModelKind, Outputs, Plot, PointsSpec, ProblemParts, Reference, RelativeTo, Scene,
    Units, design_over, problem_parts, scene_with_design,
};
pub use schema::ErrorMetric;
pub use shard::{SHARD_COUNT_VARIABLE, Shard};
pub use subsurface::{BodySubsurfaceJson, PeakJson, SubsurfaceJson};
pub use tables::{BatchOutcome, Row, merge};
