//! The cylindrical roller bearing as a system of contacts, and the slicing
//! model it improves on.
//!
//! Z crowned rollers of diameter D and length l at `psi_j = 2 pi j / Z`,
//! each between the inner raceway (diameter `d_i`) and the outer one
//! (`d_o`). As for the ball bearing (`crate::bearing`), the inner ring is
//! free in its plane under the radial load along x, the outer ring fixed,
//! and each roller a free element along its radius; a misalignment turns
//! the inner ring about y by a prescribed angle, and each roller then also
//! tilts freely about its rolling direction. Each contact is a rectangle of
//! cells along the roller in the zone's frame `(e1, e2, n) = (e_psi, z,
//! e_r)`, its separations
//!
//! ```text
//!     eps(x, y) = x^2 / (2 R) + crown(y),   1 / R = 2 / D + 2 / d_i  (inner),  2 / D - 2 / d_o  (outer)
//! ```
//!
//! with the roller's ends the bodies' own edges: the contact may end there,
//! and a straight or lightly crowned roller loads its ends with the edge
//! pressure that a slicing model (each slice an independent line contact)
//! cannot see.
//!
//! The slicing model ([`Slicing`]) is ISO/TS 16281's: slices of width w,
//! each contact's slice compressed by `delta = 3.84e-5 q^0.9 / w^0.8` (mm,
//! N; Palmgren's line contact of steel), the roller's crown and the ring's
//! misalignment shifting each slice, the two contacts alike (so the roller
//! tilts by half the misalignment), the ring in equilibrium.

use std::f64::consts::PI;

use elcon_analysis::references::HertzCylinders;
use elcon_analysis::{
    Body, ContactProblem, Geometry, Loading, Material, Options, PointSet, Storage, combined_modulus,
};

use crate::ElementsError;
use crate::bearing::{BearingSystem, Ring, RingSizes};
use crate::springs::HertzSprings;

/// A roller's crown: how far its surface falls from the straight line at
/// each point along it (length).
#[derive(Debug, Clone, PartialEq)]
pub enum Crown {
    /// Straight: the ends cut the contact sharply.
    Straight,
    /// Straight over `flat` in the middle, then falling as a parabola to
    /// `drop` at the ends.
    Circular {
        /// The fall at each end (length).
        drop: f64,
        /// The straight length in the middle (length; 0: crowned all along).
        flat: f64,
    },
    /// Lundberg's logarithmic profile for the roller load `load`,
    /// `drop(y) = 2 Q / (pi l E*) ln(1 / (1 - (2 y / l)^2))`, taken at each
    /// cell's centre (finite: the profile is infinite at the very end).
    Logarithmic {
        /// The load it is designed for (force).
        load: f64,
    },
    /// A table of `(position along the roller, drop)` (lengths, positions
    /// increasing), read linearly between its rows and held at its end
    /// rows beyond them: a designed crown, or a measured one.
    Table(std::sync::Arc<Vec<(f64, f64)>>),
}

impl Crown {
    /// The fall at `y` along a roller of `length` (combined modulus
    /// `modulus` for Lundberg's profile).
    pub fn drop_at(&self, y: f64, length: f64, modulus: f64) -> f64 {
        let half = 0.5 * length;
        match *self {
            Crown::Straight => 0.0,
            Crown::Circular { drop, flat } => {
                let start = 0.5 * flat;
                let beyond = (y.abs() - start).max(0.0) / (half - start);
                drop * beyond * beyond
            }
            Crown::Logarithmic { load } => {
                let u = (2.0 * y / length).min(1.0 - 1e-12);
                2.0 * load / (PI * length * modulus) * (1.0 / (1.0 - u * u)).ln()
            }
            Crown::Table(ref rows) => linear(rows, y),
        }
    }
}

/// The table `rows` read linearly at `y`, held at its end rows beyond them.
fn linear(rows: &[(f64, f64)], y: f64) -> f64 {
    let i = rows.partition_point(|&(s, _)| s < y);
    match (i, rows.len()) {
        (_, 0) => 0.0,
        (0, _) => rows[0].1,
        (i, n) if i == n => rows[n - 1].1,
        (i, _) => {
            let ((s0, d0), (s1, d1)) = (rows[i - 1], rows[i]);
            d0 + (d1 - d0) * (y - s0) / (s1 - s0)
        }
    }
}

/// A cylindrical roller bearing under a radial load on its inner ring.
#[derive(Debug, Clone, PartialEq)]
pub struct RollerBearing {
    /// The rollers' diameter D (length).
    pub roller_diameter: f64,
    /// The rollers' effective length l (length).
    pub roller_length: f64,
    /// The rollers' crown.
    pub crown: Crown,
    /// The inner raceway's diameter `d_i` (length).
    pub inner_raceway_diameter: f64,
    /// The outer raceway's diameter `d_o` (length).
    pub outer_raceway_diameter: f64,
    /// The number of rollers Z.
    pub rollers: usize,
    /// The diametral clearance (length); `None`: `d_o - d_i - 2 D`.
    pub diametral_clearance: Option<f64>,
    /// The rings' and rollers' material.
    pub material: Material,
    /// The radial load on the inner ring, along x (force).
    pub radial_load: f64,
    /// The inner ring's misalignment, a rotation about y (radians).
    pub misalignment: f64,
}

/// How each roller contact is discretized.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollerGrid {
    /// Points across the Hertz line contact's width at the load
    /// `5 F_r / Z` (odd; default 11).
    pub across: usize,
    /// Cells along the roller (default 60).
    pub along: usize,
    /// How far the grid reaches across, in that half-width (default 1.5).
    pub zone: f64,
}

impl Default for RollerGrid {
    fn default() -> Self {
        Self {
            across: 11,
            along: 60,
            zone: 1.5,
        }
    }
}

impl RollerBearing {
    /// The diametral clearance: as given, or the raceways' own.
    pub fn clearance(&self) -> f64 {
        self.rings().clearance()
    }

    /// The pitch diameter (length).
    pub fn pitch_diameter(&self) -> f64 {
        self.rings().pitch_diameter()
    }

    /// The rollers' angles (radians).
    pub fn angles(&self) -> Vec<f64> {
        self.rings().angles()
    }

    /// The rings and rollers as every radial bearing has them.
    fn rings(&self) -> RingSizes {
        RingSizes {
            element: "roller",
            count_field: "rollers",
            diameter: self.roller_diameter,
            count: self.rollers,
            inner: self.inner_raceway_diameter,
            outer: self.outer_raceway_diameter,
            clearance: self.diametral_clearance,
        }
    }

    /// The combined radii of the inner and outer contacts across the roller.
    pub fn radii(&self) -> [f64; 2] {
        let d = self.roller_diameter;
        [
            1.0 / (2.0 / d + 2.0 / self.inner_raceway_diameter),
            1.0 / (2.0 / d - 2.0 / self.outer_raceway_diameter),
        ]
    }

    /// Checks the data, naming the field.
    ///
    /// # Errors
    /// [`ElementsError::InvalidInput`] for a size or load not finite and
    /// positive, raceways that do not hold the roller, no rollers or more
    /// than fit, a crown that is negative or longer than the roller, a
    /// misalignment beyond the small-rotation bound (0.01 rad), or a
    /// preload deeper than a tenth of the roller.
    pub fn validate(&self) -> Result<(), ElementsError> {
        let d = self.roller_diameter;
        for (field, value) in [
            ("roller_diameter", d),
            ("roller_length", self.roller_length),
            ("inner_raceway_diameter", self.inner_raceway_diameter),
            ("outer_raceway_diameter", self.outer_raceway_diameter),
            ("radial_load", self.radial_load),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ElementsError::invalid(
                    field,
                    value,
                    "must be finite and > 0",
                ));
            }
        }
        self.rings().check()?;
        if !(self.misalignment.is_finite() && self.misalignment.abs() <= 0.01) {
            return Err(ElementsError::invalid(
                "misalignment",
                self.misalignment,
                "must be within +-0.01 rad: the zones' rigid motions are small rotations",
            ));
        }
        match self.crown {
            Crown::Straight => {}
            Crown::Table(ref rows) => {
                let ordered = rows.windows(2).all(|w| w[1].0 > w[0].0);
                let finite = rows
                    .iter()
                    .all(|(s, d)| s.is_finite() && d.is_finite() && *d >= 0.0);
                if rows.is_empty() || !ordered || !finite {
                    return Err(ElementsError::invalid(
                        "crown",
                        rows.len() as f64,
                        "a crown's table needs rows of increasing positions and finite drops >= 0",
                    ));
                }
            }
            Crown::Circular { drop, flat } => {
                if !(drop.is_finite() && drop >= 0.0) {
                    return Err(ElementsError::invalid(
                        "crown.drop",
                        drop,
                        "must be finite and >= 0",
                    ));
                }
                if !(flat.is_finite() && flat >= 0.0 && flat < self.roller_length) {
                    return Err(ElementsError::invalid(
                        "crown.flat",
                        flat,
                        "must be >= 0 and shorter than the roller",
                    ));
                }
            }
            Crown::Logarithmic { load } => {
                if !(load.is_finite() && load > 0.0) {
                    return Err(ElementsError::invalid(
                        "crown.load",
                        load,
                        "must be finite and > 0",
                    ));
                }
            }
        }
        Ok(())
    }

    /// The inner and outer contacts' points and problems on `grid` (in the
    /// zones' frames: x across the roller, y along it), unfolded (dense or
    /// matrix-free above [`DENSE_ROLLER_POINTS`]), the roller's ends the
    /// bodies' edges, under no load (give them one with
    /// `ContactProblem::with_loading`).
    ///
    /// # Errors
    /// [`ElementsError::InvalidInput`] naming `across` for an even or too
    /// small count; [`ElementsError::Analysis`] when a grid is refused.
    pub fn templates(&self, grid: &RollerGrid) -> Result<Vec<ContactProblem>, ElementsError> {
        let modulus = combined_modulus(&self.material, &self.material);
        let design = 5.0 * self.radial_load / self.rollers as f64;
        let body = Body::uniform_patch(self.material);
        self.radii()
            .into_iter()
            .map(|radius| {
                let b =
                    HertzCylinders::new(modulus, radius, design / self.roller_length)?.half_width();
                if grid.across < 3 || grid.across.is_multiple_of(2) {
                    return Err(ElementsError::invalid(
                        "across",
                        grid.across as f64,
                        "must be odd and at least 3",
                    ));
                }
                let h = 2.0 * b / (grid.across - 1) as f64;
                let m = (grid.zone * b / h).round().max(1.0);
                let nx = 2 * m as usize + 1;
                let points = PointSet::grid_rectangle(
                    (m + 0.5) * h,
                    0.5 * self.roller_length,
                    nx,
                    grid.along,
                )
                .map_err(elcon_analysis::AnalysisError::from)?;
                let eps: Vec<f64> = points
                    .positions()
                    .map(|(x, y)| {
                        x * x / (2.0 * radius) + self.crown.drop_at(y, self.roller_length, modulus)
                    })
                    .collect();
                Ok(ContactProblem::builder(
                    points,
                    &body,
                    &body,
                    &Geometry::Separation(eps),
                    Loading::approach(0.0).aligned(),
                )
                .storage(storage(nx * grid.along))
                .fold(false)
                .body_edges(false, true)
                .build()?)
            })
            .collect()
    }

    /// The bearing as a system (module documentation).
    ///
    /// # Errors
    /// [`ElementsError::InvalidInput`] as [`RollerBearing::validate`], and
    /// naming `across` for an even or too small count;
    /// [`ElementsError::Analysis`] when a grid or the system is refused.
    pub fn system(&self, grid: &RollerGrid) -> Result<BearingSystem, ElementsError> {
        self.validate()?;
        let templates = self.templates(grid)?;
        let angles = self.angles();
        let system = Ring {
            element: "roller",
            angles: &angles,
            pitch_radius: 0.5 * self.pitch_diameter(),
            inner_radius: 0.5 * self.inner_raceway_diameter,
            outer_radius: 0.5 * self.outer_raceway_diameter,
            radial_clearance: 0.5 * self.clearance(),
            radial_load: self.radial_load,
            misalignment: Some(self.misalignment),
        }
        .system(&templates)?;
        let start = self.start(&templates)?;
        Ok(BearingSystem {
            system,
            angles,
            start,
            element_motions: 2,
        })
    }

    /// The start: each template solved once under the load `5 F_r / Z`
    /// gives its approach, and springs `Q = K delta^(10/9)` through it the
    /// ring's displacement and each roller's; each roller tilted by half
    /// the ring's misalignment there.
    fn start(&self, templates: &[ContactProblem]) -> Result<Vec<f64>, ElementsError> {
        let design = 5.0 * self.radial_load / self.rollers as f64;
        let mut approaches = [0.0; 2];
        for (a, t) in approaches.iter_mut().zip(templates) {
            let loaded = t.with_loading(Loading::load(design).aligned())?;
            *a = loaded
                .solve(loaded.default_method(), &Options::default())?
                .approach;
        }
        let springs = HertzSprings::of_contacts(
            [design; 2],
            approaches,
            10.0 / 9.0,
            (self.angles(), self.clearance(), self.radial_load),
        );
        let answer = springs.solve()?;
        let mut start = vec![answer.ring_displacement, 0.0];
        for (psi, q) in self.angles().into_iter().zip(&answer.loads) {
            let reach = answer.ring_displacement * psi.cos();
            start.push(if *q > 0.0 {
                reach - springs.inner_approach(*q)
            } else {
                0.5 * (reach + 0.5 * self.clearance())
            });
            start.push(0.5 * self.misalignment * psi.cos());
        }
        Ok(start)
    }
}

/// How a roller contact of `n` points holds S: dense up to
/// [`DENSE_ROLLER_POINTS`], where the exact pivoting of each zone is
/// quickest; matrix-free above (the conjugate gradient on the FFT lattice:
/// each zone's solve and stiffness cost products, not factorizations).
fn storage(n: usize) -> Storage {
    if n <= DENSE_ROLLER_POINTS {
        Storage::Dense
    } else {
        Storage::Lattice
    }
}

/// The largest roller contact held dense (points).
pub const DENSE_ROLLER_POINTS: usize = 1500;

/// The largest pressure in the end cells of a roller contact of `along`
/// cells along the roller (its points ordered by x, then y): the edge
/// pressure.
pub fn end_pressure(pressures: &[f64], along: usize) -> f64 {
    pressures
        .chunks(along.max(1))
        .flat_map(|row| [row[0], row[row.len() - 1]])
        .fold(0.0f64, f64::max)
}

/// The slicing model's answer.
#[derive(Debug, Clone, PartialEq)]
pub struct SlicingLoads {
    /// The inner ring's displacement toward roller 0 (mm).
    pub ring_displacement: f64,
    /// Each roller's load (N).
    pub loads: Vec<f64>,
    /// Each roller's largest slice pressure (Hertz's line contact on the
    /// slice's load per length; MPa), on the inner raceway.
    pub max_pressures: Vec<f64>,
}

/// ISO/TS 16281's slicing model of a roller bearing (module documentation),
/// in mm and N.
#[derive(Debug, Clone, PartialEq)]
pub struct Slicing {
    /// The bearing.
    pub bearing: RollerBearing,
    /// Slices along each roller.
    pub slices: usize,
}

impl Slicing {
    /// Each roller's load and largest inner slice pressure at the ring's
    /// displacement `delta`, and the ring's load.
    fn at(&self, delta: f64) -> (f64, Vec<f64>, Vec<f64>) {
        let b = &self.bearing;
        let modulus = combined_modulus(&b.material, &b.material);
        let w = b.roller_length / self.slices as f64;
        let [inner_radius, _] = b.radii();
        let mut loads = Vec::with_capacity(b.rollers);
        let mut peaks = Vec::with_capacity(b.rollers);
        for psi in b.angles() {
            let (mut total, mut peak) = (0.0, 0.0f64);
            for s in 0..self.slices {
                let y = -0.5 * b.roller_length + (s as f64 + 0.5) * w;
                let squeeze = delta * psi.cos() - 0.5 * b.clearance()
                    + b.misalignment * psi.cos() * y
                    - 2.0 * b.crown.drop_at(y, b.roller_length, modulus);
                if squeeze > 0.0 {
                    let q = (0.5 * squeeze * w.powf(0.8) / 3.84e-5).powf(1.0 / 0.9);
                    total += q;
                    peak = peak.max((q / w * modulus / (PI * inner_radius)).sqrt());
                }
            }
            loads.push(total);
            peaks.push(peak);
        }
        let ring = loads
            .iter()
            .zip(b.angles())
            .map(|(q, psi)| q * psi.cos())
            .sum();
        (ring, loads, peaks)
    }

    /// The ring's displacement and the rollers' loads at equilibrium.
    ///
    /// # Errors
    /// [`ElementsError::NoEquilibrium`] when no displacement carries the
    /// load.
    pub fn solve(&self) -> Result<SlicingLoads, ElementsError> {
        let target = self.bearing.radial_load;
        let mut lo = -self.bearing.roller_diameter;
        let mut hi = self.bearing.roller_diameter;
        if self.at(hi).0 < target {
            return Err(ElementsError::NoEquilibrium(
                "the slicing model carries no load at any ring displacement".into(),
            ));
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.at(mid).0 < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let delta = 0.5 * (lo + hi);
        let (_, loads, max_pressures) = self.at(delta);
        Ok(SlicingLoads {
            ring_displacement: delta,
            loads,
            max_pressures,
        })
    }
}
