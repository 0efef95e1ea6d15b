//! # elcon-elements: machine elements as systems of contacts
//!
//! Engineering data in, a system of contact zones out
//! (`elcon_analysis::system`): the rolling bearing today ([`bearing`]: a
//! radial ball bearing, its inner ring loaded radially, every ball a free
//! element between two elliptical contacts), with the discrete
//! Hertz-spring model it is checked against ([`springs`]: Harris &
//! Kotzalas, ch. 7) and the basic rating life of its raceways ([`life`]:
//! Lundberg & Palmgren as in ISO/TS 16281, without the life modification
//! factor).
//!
//! Units: any consistent set (the examples use mm, N, MPa); angles in
//! radians unless a name says degrees.
//!
//! ```
//! use elcon_elements::bearing::{BallBearing, BearingGrid};
//! use elcon_analysis::Material;
//! use elcon_analysis::system::SystemSettings;
//!
//! // A 9-ball deep-groove bearing (mm, N, MPa) under 2000 N, 15 points
//! // across each contact ellipse.
//! let bearing = BallBearing {
//!     ball_diameter: 7.938,
//!     inner_raceway_diameter: 31.0,
//!     outer_raceway_diameter: 46.9,
//!     inner_groove_radius: 0.52 * 7.938,
//!     outer_groove_radius: 0.53 * 7.938,
//!     balls: 9,
//!     diametral_clearance: None,
//!     material: Material::new(210e3, 0.3).unwrap(),
//!     radial_load: 2000.0,
//! };
//! let grid = BearingGrid { across: 15, ..BearingGrid::default() };
//! let solution = bearing.system(&grid).unwrap().solve(&SystemSettings::default()).unwrap();
//! assert!(solution.system.certificate.holds());
//! let springs = bearing.springs().unwrap().solve().unwrap();
//! let most = solution.elements[0].load;
//! assert!((most / springs.loads[0] - 1.0).abs() < 0.02);
//! ```

pub mod bearing;
mod error;
pub mod life;
pub mod roller;
pub mod springs;

pub use error::ElementsError;
