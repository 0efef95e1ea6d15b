//! The radial ball bearing as a system of contacts.
//!
//! Z balls of diameter D at the angles `psi_j = 2 pi j / Z` from the load's
//! direction (x), each between the inner raceway (diameter `d_i` at the
//! groove's bottom, groove radius `r_i`) and the outer one (`d_o`, `r_o`).
//! The inner ring is free in the bearing's plane (x, y) under the radial
//! load `F_r` along x; the outer ring is fixed; every ball is a free
//! element that moves along its own radius `e_r(psi_j)` with no load of its
//! own (quasi-static, no centrifugal force). Ball j has two zones, each
//! an elliptical contact on its own grid in the frame `(e1, e2, n) =
//! (e_psi, z, e_r)`:
//!
//! ```text
//!     inner: ring (quadric, R_x = d_i / 2 along the rolling direction, R_y = -r_i across)
//!            against the ball (sphere D / 2), at d_i / 2 e_r
//!     outer: the ball against the ring (R_x = -d_o / 2, R_y = -r_o), at d_o / 2 e_r,
//!            separated by the radial clearance P_d / 2
//! ```
//!
//! so the inner zone's approach is `u_ring . e_r - s_j` and the outer's
//! `s_j` (`s_j` the ball's radial motion): the two contacts in series, and
//! the ring's equilibrium `sum_j Q_j cos psi_j = F_r`. The rings are rigid;
//! every contact is an exact half-space contact (Love's patches), not a
//! Hertz spring. The candidate grid of every zone is laid around the
//! Hertz ellipse of the load `5 F_r / Z` (Stribeck's estimate of the most
//! loaded ball with clearance), `across` points over each of its axes, out
//! to `zone` times them: a ball loaded three times more still fits.

use std::f64::consts::PI;

use elcon_analysis::grid::{EllipseExtent, hertz_ellipse_family};
use elcon_analysis::references::HertzEllipse;
use elcon_analysis::system::{
    Frame, Motion, RigidBody, System, SystemSettings, SystemSolution, SystemZone,
};
use elcon_analysis::{
    Body, ContactProblem, Geometry, Loading, Material, PointSet, Storage, Surface, combined_modulus,
};

use crate::ElementsError;
use crate::springs::HertzSprings;

/// A deep-groove radial ball bearing under a radial load on its inner ring.
#[derive(Debug, Clone, PartialEq)]
pub struct BallBearing {
    /// The balls' diameter D (length).
    pub ball_diameter: f64,
    /// The inner raceway's diameter at the groove's bottom, `d_i` (length).
    pub inner_raceway_diameter: f64,
    /// The outer raceway's diameter at the groove's bottom, `d_o` (length).
    pub outer_raceway_diameter: f64,
    /// The inner groove's cross radius `r_i = f_i D` (length; more than D / 2).
    pub inner_groove_radius: f64,
    /// The outer groove's cross radius `r_o = f_o D` (length; more than D / 2).
    pub outer_groove_radius: f64,
    /// The number of balls Z.
    pub balls: usize,
    /// The diametral clearance `P_d` (length; negative: a preload). `None`:
    /// the raceways' own, `d_o - d_i - 2 D`.
    pub diametral_clearance: Option<f64>,
    /// The rings' and the balls' material.
    pub material: Material,
    /// The radial load on the inner ring, along x (force).
    pub radial_load: f64,
}

/// How each contact is discretized.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BearingGrid {
    /// Points over each axis of the Hertz ellipse of the load `5 F_r / Z`
    /// (odd; default 21).
    pub across: usize,
    /// How far the grid reaches, in those semi-axes (default 1.5).
    pub zone: f64,
}

impl Default for BearingGrid {
    fn default() -> Self {
        Self {
            across: 21,
            zone: 1.5,
        }
    }
}

/// One rolling element's answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementLoad {
    /// The element's angle from the load's direction (degrees).
    pub angle: f64,
    /// The element's load Q (force): its inner contact's, equal to its
    /// outer's at equilibrium.
    pub load: f64,
    /// The inner contact's largest pressure (pressure).
    pub max_pressure_inner: f64,
    /// The outer contact's largest pressure (pressure).
    pub max_pressure_outer: f64,
    /// The element's radial motion (length, outward).
    pub displacement: f64,
    /// The element's tilt in the bearing's axial plane (radians, about its
    /// rolling direction; 0 for a ball).
    pub tilt: f64,
}

/// A bearing's system, ready to solve.
#[derive(Debug, Clone)]
pub struct BearingSystem {
    /// The system: bodies "inner ring", "outer ring", "ball 0" (or
    /// "roller 0") ...; zones "ball j inner", "ball j outer".
    pub system: System,
    /// The elements' angles (radians).
    pub angles: Vec<f64>,
    /// A spring model's answer as the solve's start.
    pub start: Vec<f64>,
    /// The free motions of each element (1 for a ball: radial; 2 for a
    /// roller: radial and tilt).
    pub element_motions: usize,
}

/// A solved bearing.
#[derive(Debug, Clone)]
pub struct BearingSolution {
    /// Element by element, from element 0 at the load's direction.
    pub elements: Vec<ElementLoad>,
    /// The inner ring's displacement (x, y, z; length).
    pub ring_displacement: [f64; 3],
    /// The elements that carry load.
    pub loaded: usize,
    /// The system's solution: every zone's contact solution (element j's
    /// inner zone is `2 j`, its outer `2 j + 1`) and the certificate.
    pub system: SystemSolution,
}

impl BallBearing {
    /// The diametral clearance: as given, or the raceways' own.
    pub fn clearance(&self) -> f64 {
        self.rings().clearance()
    }

    /// The pitch diameter `(d_i + d_o) / 2` (length).
    pub fn pitch_diameter(&self) -> f64 {
        self.rings().pitch_diameter()
    }

    /// The balls' angles `2 pi j / Z` (radians).
    pub fn angles(&self) -> Vec<f64> {
        self.rings().angles()
    }

    /// The rings and balls as every radial bearing has them.
    fn rings(&self) -> RingSizes {
        RingSizes {
            element: "ball",
            count_field: "balls",
            diameter: self.ball_diameter,
            count: self.balls,
            inner: self.inner_raceway_diameter,
            outer: self.outer_raceway_diameter,
            clearance: self.diametral_clearance,
        }
    }

    /// The inner and outer contacts' surfaces (in their zones' frames).
    pub fn geometries(&self) -> [Geometry; 2] {
        let ball = Surface::Sphere {
            radius: 0.5 * self.ball_diameter,
        };
        let race = |diameter: f64, groove: f64| Surface::Quadric {
            radius_x: 0.5 * diameter,
            radius_y: -groove,
            angle: 0.0,
        };
        [
            Geometry::Surfaces(
                race(self.inner_raceway_diameter, self.inner_groove_radius),
                ball,
            ),
            Geometry::Surfaces(
                ball,
                race(-self.outer_raceway_diameter, self.outer_groove_radius),
            ),
        ]
    }

    /// The inner and outer contacts' Hertz ellipses under a ball load `q`.
    ///
    /// # Errors
    /// [`ElementsError::Analysis`] for a load that is not finite and > 0.
    pub fn hertz(&self, q: f64) -> Result<[HertzEllipse; 2], ElementsError> {
        let e = combined_modulus(&self.material, &self.material);
        let [inner, outer] = self.geometries();
        let ellipse = |g: &Geometry| -> Result<HertzEllipse, ElementsError> {
            let curvature = g.curvature().expect("two surfaces have a curvature");
            Ok(HertzEllipse::new(e, curvature, q)?)
        };
        Ok([ellipse(&inner)?, ellipse(&outer)?])
    }

    /// The discrete Hertz-spring model of this bearing (its contacts'
    /// Hertz constants from their curvatures and material, independently
    /// of any grid).
    ///
    /// # Errors
    /// As [`BallBearing::validate`].
    pub fn springs(&self) -> Result<HertzSprings, ElementsError> {
        self.validate()?;
        let [inner, outer] = self.hertz(1.0)?;
        Ok(HertzSprings::of_contacts(
            [1.0, 1.0],
            [inner.approach(), outer.approach()],
            1.5,
            (self.angles(), self.clearance(), self.radial_load),
        ))
    }

    /// Checks the data, naming the field.
    ///
    /// # Errors
    /// [`ElementsError::InvalidInput`] for a size that is not finite and
    /// positive, grooves no wider than the ball, raceways that do not hold
    /// the ball, no balls or more than fit on the pitch circle, a load not
    /// finite and positive, or a preload deeper than the contact could
    /// take (a tenth of the ball's diameter).
    pub fn validate(&self) -> Result<(), ElementsError> {
        let d = self.ball_diameter;
        for (field, value) in [
            ("ball_diameter", d),
            ("inner_raceway_diameter", self.inner_raceway_diameter),
            ("outer_raceway_diameter", self.outer_raceway_diameter),
            ("inner_groove_radius", self.inner_groove_radius),
            ("outer_groove_radius", self.outer_groove_radius),
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
        for (field, value) in [
            ("inner_groove_radius", self.inner_groove_radius),
            ("outer_groove_radius", self.outer_groove_radius),
        ] {
            if !(value > 0.5 * d) {
                return Err(ElementsError::invalid(
                    field,
                    value,
                    format!(
                        "a groove's cross radius must exceed the ball's radius {} (a conformity f > 0.5)",
                        0.5 * d
                    ),
                ));
            }
        }
        self.rings().check()
    }

    /// The bearing as a system (module documentation), each contact on
    /// `grid`, held dense and unfolded (the two zone templates' S are
    /// shared by every ball).
    ///
    /// # Errors
    /// [`ElementsError::InvalidInput`] as [`BallBearing::validate`];
    /// [`ElementsError::Analysis`] when a grid or the system is refused.
    pub fn system(&self, grid: &BearingGrid) -> Result<BearingSystem, ElementsError> {
        self.validate()?;
        let design_load = 5.0 * self.radial_load / self.balls as f64;
        let body = Body::uniform_patch(self.material);
        let templates = self
            .geometries()
            .into_iter()
            .zip(self.hertz(design_load)?)
            .map(
                |(geometry, hertz)| -> Result<ContactProblem, ElementsError> {
                    let (half_x, half_y) = hertz.half_extents();
                    let extent = EllipseExtent {
                        half_x,
                        half_y,
                        semi_minor: hertz.semi_minor(),
                    };
                    let points: PointSet =
                        hertz_ellipse_family(extent, grid.across, grid.zone)?.points()?;
                    Ok(ContactProblem::builder(
                        points,
                        &body,
                        &body,
                        &geometry,
                        Loading::approach(0.0),
                    )
                    .storage(Storage::Dense)
                    .fold(false)
                    .build()?)
                },
            )
            .collect::<Result<Vec<_>, _>>()?;
        let angles = self.angles();
        let system = Ring {
            element: "ball",
            angles: &angles,
            pitch_radius: 0.5 * self.pitch_diameter(),
            inner_radius: 0.5 * self.inner_raceway_diameter,
            outer_radius: 0.5 * self.outer_raceway_diameter,
            radial_clearance: 0.5 * self.clearance(),
            radial_load: self.radial_load,
            misalignment: None,
        }
        .system(&templates)?;
        let start = self.start()?;
        Ok(BearingSystem {
            system,
            angles,
            start,
            element_motions: 1,
        })
    }

    /// The Hertz-spring model's motions as the solve's start: the ring's
    /// (x, y), then each ball's radial motion (a loaded ball where its
    /// inner contact's Hertz approach puts it, an unloaded one halfway
    /// between its raceways).
    fn start(&self) -> Result<Vec<f64>, ElementsError> {
        let springs = self.springs()?;
        let answer = springs.solve()?;
        let mut start = vec![answer.ring_displacement, 0.0];
        let half = 0.5 * self.clearance();
        for (psi, q) in self.angles().into_iter().zip(&answer.loads) {
            let reach = answer.ring_displacement * psi.cos();
            start.push(if *q > 0.0 {
                reach - springs.inner_approach(*q)
            } else {
                0.5 * (reach + half)
            });
        }
        Ok(start)
    }
}

impl BearingSystem {
    /// Solves the bearing, starting from its spring model's answer unless
    /// `settings` gives a start.
    ///
    /// # Errors
    /// [`ElementsError::Analysis`] when the system's solve fails;
    /// [`ElementsError::NoEquilibrium`] when no ball carries the load.
    pub fn solve(&self, settings: &SystemSettings) -> Result<BearingSolution, ElementsError> {
        let mut settings = settings.clone();
        if settings.initial.is_none() {
            settings.initial = Some(self.start.clone());
        }
        let system = self.system.solve(&settings)?;
        let elements: Vec<ElementLoad> = self
            .angles
            .iter()
            .enumerate()
            .map(|(j, psi)| {
                let (inner, outer) = (&system.zones[2 * j], &system.zones[2 * j + 1]);
                let motion = system.displacements[2 + j];
                ElementLoad {
                    angle: psi.to_degrees(),
                    load: inner.load,
                    max_pressure_inner: inner.max_pressure,
                    max_pressure_outer: outer.max_pressure,
                    displacement: motion[0],
                    tilt: motion[4],
                }
            })
            .collect();
        let loaded = elements.iter().filter(|e| e.load > 0.0).count();
        if loaded == 0 {
            return Err(ElementsError::NoEquilibrium(
                "no rolling element carries the load: the rings part".into(),
            ));
        }
        let ring = system.displacements[0];
        Ok(BearingSolution {
            elements,
            ring_displacement: [ring[0], ring[1], ring[2]],
            loaded,
            system,
        })
    }
}

/// What every radial bearing's rings and elements have: the raceways'
/// diameters, the elements' diameter and number, the clearance; and the
/// checks they share.
pub(crate) struct RingSizes {
    /// "ball" or "roller", for messages.
    pub(crate) element: &'static str,
    /// The key of the elements' number ("balls", "rollers").
    pub(crate) count_field: &'static str,
    /// The elements' diameter (length).
    pub(crate) diameter: f64,
    /// The elements' number.
    pub(crate) count: usize,
    /// The inner raceway's diameter (length).
    pub(crate) inner: f64,
    /// The outer raceway's diameter (length).
    pub(crate) outer: f64,
    /// The diametral clearance given, if any (length).
    pub(crate) clearance: Option<f64>,
}

impl RingSizes {
    /// The diametral clearance: as given, or the raceways' own,
    /// `d_o - d_i - 2 D`.
    pub(crate) fn clearance(&self) -> f64 {
        self.clearance
            .unwrap_or(self.outer - self.inner - 2.0 * self.diameter)
    }

    /// The pitch diameter `(d_i + d_o) / 2`.
    pub(crate) fn pitch_diameter(&self) -> f64 {
        0.5 * (self.inner + self.outer)
    }

    /// The elements' angles `2 pi j / Z` (radians).
    pub(crate) fn angles(&self) -> Vec<f64> {
        (0..self.count)
            .map(|j| 2.0 * PI * j as f64 / self.count as f64)
            .collect()
    }

    /// Raceways that hold the elements, a preload at most a tenth of an
    /// element's diameter, and between 1 and as many elements as fit on
    /// the pitch circle; the field named.
    pub(crate) fn check(&self) -> Result<(), ElementsError> {
        let (d, e) = (self.diameter, self.element);
        if !(self.outer > self.inner + d) {
            return Err(ElementsError::invalid(
                "outer_raceway_diameter",
                self.outer,
                format!("must exceed the inner raceway's diameter by about two {e}s' diameters"),
            ));
        }
        let clearance = self.clearance();
        if !(clearance.is_finite() && clearance > -0.1 * d) {
            return Err(ElementsError::invalid(
                "diametral_clearance",
                clearance,
                format!(
                    "a preload deeper than a tenth of the {e}'s diameter ({}) is not a rolling contact",
                    0.1 * d
                ),
            ));
        }
        let fit = (PI * self.pitch_diameter() / d).floor();
        if self.count == 0 || self.count as f64 > fit {
            return Err(ElementsError::invalid(
                self.count_field,
                self.count as f64,
                format!("between 1 and {fit} {e}s of this diameter fit on the pitch circle"),
            ));
        }
        Ok(())
    }
}

/// The rings and elements of a radial bearing as a system: the inner ring
/// free in its plane under the radial load along x (and turned about y by
/// a prescribed misalignment, if any), the outer ring fixed, each element
/// free along its radius (and, with a misalignment, in its tilt about its
/// rolling direction), two zones per element on the two templates.
pub(crate) struct Ring<'a> {
    /// "ball" or "roller": names the bodies and zones.
    pub(crate) element: &'a str,
    /// The elements' angles (radians).
    pub(crate) angles: &'a [f64],
    /// The pitch radius, where the elements' centres are (length).
    pub(crate) pitch_radius: f64,
    /// The inner raceway's radius (length).
    pub(crate) inner_radius: f64,
    /// The outer raceway's radius (length).
    pub(crate) outer_radius: f64,
    /// Half the diametral clearance, each outer zone's clearance (length).
    pub(crate) radial_clearance: f64,
    /// The radial load on the inner ring (force).
    pub(crate) radial_load: f64,
    /// The inner ring's rotation about y (radians), for elements that tilt.
    pub(crate) misalignment: Option<f64>,
}

impl Ring<'_> {
    /// The system on the inner and outer zone templates.
    pub(crate) fn system(&self, templates: &[ContactProblem]) -> Result<System, ElementsError> {
        let mut inner = RigidBody::free("inner ring", [0.0; 3], &[Motion::X, Motion::Y])
            .with_load(Motion::X, self.radial_load);
        let mut element_motions = vec![Motion::X];
        if let Some(angle) = self.misalignment {
            inner = inner.with_prescribed(Motion::RotY, angle);
            element_motions.push(Motion::RotY);
        }
        let mut bodies = vec![inner, RigidBody::fixed("outer ring")];
        let mut zones = Vec::with_capacity(2 * self.angles.len());
        for (j, &psi) in self.angles.iter().enumerate() {
            let (s, c) = psi.sin_cos();
            let (radial, rolling, axial) = ([c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]);
            let r = self.pitch_radius;
            bodies.push(
                RigidBody::free(
                    format!("{} {j}", self.element),
                    [r * c, r * s, 0.0],
                    &element_motions,
                )
                .with_axes(radial, rolling),
            );
            let body = bodies.len() - 1;
            let at = |r: f64| Frame {
                origin: [r * c, r * s, 0.0],
                e1: rolling,
                e2: axial,
            };
            for (side, body_a, body_b, radius, clearance) in [
                ("inner", 0, body, self.inner_radius, 0.0),
                ("outer", body, 1, self.outer_radius, self.radial_clearance),
            ] {
                zones.push(SystemZone {
                    name: format!("{} {j} {side}", self.element),
                    body_a,
                    body_b,
                    frame: at(radius),
                    problem: templates[if side == "inner" { 0 } else { 1 }].clone(),
                    clearance,
                });
            }
        }
        Ok(System::new(bodies, zones)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn bearing() -> BallBearing {
        BallBearing {
            ball_diameter: 7.938,
            inner_raceway_diameter: 31.0,
            outer_raceway_diameter: 46.9,
            inner_groove_radius: 0.52 * 7.938,
            outer_groove_radius: 0.53 * 7.938,
            balls: 9,
            diametral_clearance: None,
            material: Material::new(210e3, 0.3).unwrap(),
            radial_load: 2000.0,
        }
    }

    #[test]
    fn each_bad_field_is_named() {
        type Edit = fn(&mut BallBearing);
        let cases: Vec<(Edit, &str)> = vec![
            (|b| b.ball_diameter = -1.0, "ball_diameter"),
            (|b| b.inner_groove_radius = 3.0, "inner_groove_radius"),
            (
                |b| b.outer_raceway_diameter = 35.0,
                "outer_raceway_diameter",
            ),
            (|b| b.balls = 0, "balls"),
            (|b| b.balls = 40, "balls"),
            (|b| b.radial_load = f64::NAN, "radial_load"),
            (
                |b| b.diametral_clearance = Some(-1.0),
                "diametral_clearance",
            ),
        ];
        for (edit, field) in cases {
            let mut b = bearing();
            edit(&mut b);
            let e = b.validate().unwrap_err();
            assert!(e.to_string().contains(field), "{field}: {e}");
        }
        assert!(bearing().validate().is_ok());
        assert!((bearing().clearance() - 0.024).abs() < 1e-12);
    }

    fn with(balls: usize, clearance: f64) -> BallBearing {
        BallBearing {
            balls,
            diametral_clearance: Some(clearance),
            ..bearing()
        }
    }

    #[test]
    fn the_ring_is_in_equilibrium_and_stribeck_holds_at_zero_clearance() {
        for (balls, clearance) in [(9, 0.0), (9, 0.024), (15, 0.0), (9, -0.005)] {
            let b = with(balls, clearance);
            let s = b.springs().unwrap();
            let a = s.solve().unwrap();
            let total: f64 = a
                .loads
                .iter()
                .zip(&s.angles)
                .map(|(q, p)| q * p.cos())
                .sum();
            assert!((total / 2000.0 - 1.0).abs() < 1e-12, "{total}");
            if clearance == 0.0 {
                // Stribeck: Z Q_max / F_r = 4.37 for many balls; 9 balls
                // give 4.36, 15 balls 4.37 (the integral's limit is 4.37).
                let ratio = balls as f64 * a.loads[0] / 2000.0;
                assert!((ratio - 4.37).abs() < 0.03, "{balls}: {ratio}");
            }
        }
        // Clearance narrows the load zone.
        let tight = with(9, 0.0).springs().unwrap().solve().unwrap();
        let loose = with(9, 0.05).springs().unwrap().solve().unwrap();
        assert!(loose.loaded() < tight.loaded() && loose.loads[0] > tight.loads[0]);
    }
}
