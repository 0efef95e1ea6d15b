//! # elcon-report: the result schema and its writers
//!
//! One typed schema for what a run gives: result.json (the header, the
//! solution's fields, the discretization error estimate, the stresses below
//! the surface, the closed-form comparison and the design, its profile
//! typed), and a batch's table; the same types serialize the files, build
//! the Python package's dicts, and read results back (a resumed batch,
//! `elcon merge`). Its writers put them on disk whole or not at all:
//! result.json, pressure.csv, a design's profile.csv, the subsurface
//! sections, SVG plots, and a batch's results.json, results.csv,
//! results.md and error-time.svg.
//!
//! docs/results.md documents every field.

mod bearing;
mod design;
mod discretization;
mod error;
mod output;
mod plot;
mod plot_parts;
mod plot_subsurface;
mod profile;
mod reference;
mod result;
mod solve;
mod subsurface;
mod tables;

pub use bearing::{
    BearingGridJson, BearingResult, BearingRun, BearingSeconds, CrownCaseJson, CrownDesignJson,
    ElementJson, LifeJson, ReferenceModel, ReferenceModelJson, StressPeaksJson,
    SystemCertificateJson, Xyz, write_bearing_files,
};
pub use design::{
    DesignCaseJson, DesignGridJson, DesignJson, DesignOf, DesignRun, FoundBy, RelativeTo,
};
pub use discretization::{DiscretizationJson, GridJson, QuantitiesJson, QuantityJson, VerdictJson};
pub use error::ReportError;
pub use output::{write_run, write_run_files};
pub use plot::error_time;
pub use profile::{Beyond, CrownEnd, Interpolation, ProfileJson};
pub use reference::{Errors, ReferenceJson, XY};
pub use result::{
    Header, InputsJson, ProblemResult, Run, RunResult, Seconds, SolutionJson, SymmetryJson,
};
pub use solve::{AttemptJson, CertificateJson, Holding, StatisticsJson};
pub use subsurface::{BodySubsurfaceJson, PeakJson, SubsurfaceJson};
pub use tables::{BatchOutcome, Row, write_tables};
