//! # elcon-design: profile corrections for elastic bodies in contact
//!
//! The design half of Conry & Seireg (1971): the initial separation (a
//! crown, a profile correction) that makes the load distribution as uniform
//! as possible, and what an engineer crowning a roller, a gear tooth or a
//! beam on a foundation needs beyond it.
//!
//! - [`Profile`]: the families of corrections `y(s)` along the axial
//!   position s (the paper's quadratic, polynomials, circular and
//!   logarithmic crowns, a free profile), each reporting its separation as a
//!   table;
//! - [`design`]: the paper's problem, the correction of a linear family that
//!   minimizes the maximum load intensity `p_max = max F_k / A_k`, for one
//!   or several load cases (eq. 16), on the engine's restricted-entry
//!   simplex, with every design re-analysed and certified;
//! - [`target_separation`] / [`uniform_target`]: the correction that makes
//!   the forces exactly a target distribution (the seed's Fig. 6 curve);
//! - [`evaluate()`]: the certified analysis of any profile under every load
//!   case; [`Sampling`]: where a designed profile is sampled for the
//!   workshop (profile.csv); [`crown_search`]: the best parameter of a one-parameter crown;
//! - [`Objective`]: the worst intensity (the paper's), or the worst von
//!   Mises or largest shear stress below the surface (`subsurface`),
//!   minimized by the case-decomposed descent;
//! - [`bearing::roller_crown`]: a roller bearing's crown designed over its
//!   own rollers' loads and tilts, and the bearing re-solved with it;
//! - [`DesignRequest`]: a design as a scene or Python asks for it (any
//!   family, linear or a crown), routed to the one of the above that finds
//!   it.
//!
//! The request's choices ([`Axis`], [`DesignMethod`], [`Objective`]) parse
//! the names scenes write (`FromStr`), and with the `serde` feature
//! serialize and deserialize as them.
//!
//! ```
//! use elcon_analysis::{ContactProblem, Geometry, Loading};
//! use elcon_design::{Axis, DesignOptions, Family, design, uniform_target};
//! use elcon_influence::{Beam, Body, PointSet};
//!
//! // A steel beam (E I = 1.6e8 lb in^2) on a Winkler foundation (1e7 lb/in/in),
//! // 8.9 in long, 10 points per half, central load 50,000 lb.
//! let points = PointSet::line(-4.45, 4.45, 20).unwrap();
//! let case = ContactProblem::new(
//!     points,
//!     &Body::beam(Beam {
//!         youngs_modulus: 30e6,
//!         second_moment: 16.0 / 3.0,
//!         loaded_point: 0.0,
//!     })
//!     .unwrap(),
//!     &Body::winkler(1e7),
//!     &Geometry::Separation(vec![0.0; 20]),
//!     Loading::load(5e4),
//! )
//! .unwrap();
//! let d = design(std::slice::from_ref(&case), Axis::X, Family::Quadratic, &DesignOptions::default()).unwrap();
//! let mean = 5e4 / 8.9;
//! assert!(d.max_intensity >= mean && d.max_intensity < 1.5 * mean);
//! assert!(d.evaluation.solutions[0].certificate.holds());
//! // The uniform-pressure correction reaches p = P / L exactly.
//! let target = uniform_target(&case).unwrap();
//! assert!(target.correction.iter().all(|&y| y >= 0.0));
//! ```

mod basis;
pub mod bearing;
mod constraint;
pub mod crown;
mod dense;
mod descent;
mod error;
pub mod estimate;
pub mod evaluate;
mod found;
mod lpcc;
mod objective;
pub mod optimize;
pub mod options;
mod prepared;
pub mod profile;
pub mod request;
pub mod sampling;
pub mod sequence;
pub mod subsurface;
pub mod target;

pub use basis::fit_profile;
pub use crown::{CrownSearch, SearchOptions, crown_search};
pub use error::DesignError;
pub use estimate::DesignEstimate;
pub use evaluate::{Analysis, Evaluation, evaluate};
pub use objective::Objective;
pub use optimize::{Design, StartOutcome, design};
pub use options::{DesignMethod, DesignOptions, Family, ITERATIVE_AGREEMENT, PROGRAM_LIMIT};
pub use prepared::{EDGE_WEIGHT, Solver, Stop, axial_stations};
pub use profile::{Axis, JOHNS_GOHAR, LogCrown, LogEnd, Profile};
pub use request::{DesignFamily, DesignRequest, FamilyKind, Found, Outcome, Roller};
pub use sampling::{MAX_PROFILE_SAMPLES, SAMPLES_PER_STATION, Sampling};
pub use sequence::{Converged, GridSequence, Level};
pub use target::{TargetSeparation, target_separation, uniform_target};
