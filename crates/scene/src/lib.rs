//! # elcon-scene: the scene model
//!
//! Makes elcon usable without writing Rust. A scene file states its units,
//! the two bodies, the surfaces, the candidate points, the load or
//! approach, the method, and only when wanted a design stage and plots.
//! This crate reads it (TOML, and the data files it names: height maps,
//! profiles, separations) into a typed [`Scene`], validated: every message
//! names the file, the line and column, and the field, and says what is
//! admissible. It runs nothing; elcon-runner does.
//!
//! The contact problem solved is that of elcon-analysis,
//! `Y = S F + eps - alpha e`, `e^T F = P`, `F, Y >= 0`, `F_k Y_k = 0`; the
//! schema is documented in docs/scenes.md, the outputs in docs/results.md
//! and the behaviour under faults and limits in docs/reliability.md.

mod batch;
mod bearing;
mod ctx;
mod error;
mod inputs;
mod sanity;
mod scene;
mod schema;

pub use batch::{Batch, BatchRun, is_batch_text};
pub use bearing::{BearingKind, BearingScene, BearingSpec, CrownFamily, is_bearing_text};
pub use ctx::{MAX_INPUT_BYTES, read_text};
pub use error::{Location, SceneError};
pub use inputs::{DataInput, confine_data_files, file_sha256, sha256_hex};
pub use sanity::{
    MAX_BEAM_REACH, MAX_END_LIFT, MAX_ROTATION, MAX_STRAIN, MIN_POINTS_RESOLVED, StrainExtent,
    approach_strain,
};
pub use scene::{
    BodySpec, DesignFamily, DesignLayoutParts, DesignSpec, EndLift, MAX_DATA_BYTES, MethodChoice,
    ModelKind, Outputs, Plot, PointsSpec, ProblemParts, Reference, RelativeTo, Scene, Units,
    design_over, problem_parts, scene_with_design,
};
pub use schema::ErrorMetric;
