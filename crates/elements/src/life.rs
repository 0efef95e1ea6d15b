//! The basic reference rating life of a radial ball bearing from its balls'
//! loads: Lundberg & Palmgren's raceway capacities, as ISO 281 rests on them
//! and ISO/TS 16281 applies them to computed element loads, without the
//! life modification factor (Harris & Kotzalas, *Advanced Concepts of
//! Bearing Technology*, ch. 8).
//!
//! For point contact at the contact angle 0, with `gamma = D / d_m` and the
//! conformities `f = r / D`, the raceways' basic dynamic capacities
//! (newton, with lengths in millimetres) are
//!
//! ```text
//!     Q_c = 98.1 (2 f / (2 f - 1))^0.41 (1 -+ gamma)^1.39 / (1 +- gamma)^(1/3) gamma^0.3 D^1.8 Z^(-1/3)
//! ```
//!
//! (upper signs for the inner raceway). The inner raceway turns under the
//! load, so each point of it meets every ball's load: its equivalent load is
//! `Q_ei = (sum Q_j^3 / Z)^(1/3)`; the outer one stands still, and its most
//! loaded points set its life: `Q_eo = (sum Q_j^(10/3) / Z)^(3/10)`. Each
//! raceway lives `L = (Q_c / Q_e)^3` million revolutions (90 % survive),
//! and the bearing `L10 = (L_i^(-10/9) + L_o^(-10/9))^(-9/10)`.
//!
//! For line contact (a cylindrical roller bearing, [`RatingLife::of_rollers`]),
//! with `gamma = D / d_m` and the roller's effective length l,
//!
//! ```text
//!     Q_c = 552 (1 -+ gamma)^(29/27) / (1 +- gamma)^(1/4) gamma^(2/9) D^(29/27) l^(7/9) Z^(-1/4),
//! ```
//!
//! `Q_ei = (sum Q_j^4 / Z)^(1/4)`, `Q_eo = (sum Q_j^4.5 / Z)^(1/4.5)`, each
//! raceway's life `(Q_c / Q_e)^4` and `L10 = (L_i^(-9/8) + L_o^(-9/8))^(-8/9)`;
//! the reduction factor for edge loading is taken as 1 (what the slicing
//! of ISO/TS 16281 accounts for, elcon's pressures show directly).

use crate::ElementsError;
use crate::bearing::BallBearing;
use crate::roller::RollerBearing;

/// A ball bearing's basic rating life from its balls' loads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatingLife {
    /// The inner raceway's capacity `Q_ci` (N).
    pub inner_capacity: f64,
    /// The outer raceway's capacity `Q_co` (N).
    pub outer_capacity: f64,
    /// The inner raceway's equivalent load `Q_ei` (N).
    pub inner_equivalent: f64,
    /// The outer raceway's equivalent load `Q_eo` (N).
    pub outer_equivalent: f64,
    /// The inner raceway's life (millions of revolutions).
    pub inner_life: f64,
    /// The outer raceway's life (millions of revolutions).
    pub outer_life: f64,
    /// The bearing's basic rating life `L10` (millions of revolutions).
    pub l10: f64,
}

impl RatingLife {
    /// The life of a ball `bearing` (lengths in mm) whose balls carry
    /// `loads` (N, one per ball): point contact.
    ///
    /// # Errors
    /// [`ElementsError::InvalidInput`] naming `loads` when there is not one
    /// per ball, one is negative or not finite, or none is positive.
    pub fn of(bearing: &BallBearing, loads: &[f64]) -> Result<Self, ElementsError> {
        bearing.validate()?;
        let z = bearing.balls as f64;
        if loads.len() != bearing.balls {
            return Err(ElementsError::invalid(
                "loads",
                loads.len() as f64,
                format!("one load per ball ({}) is needed", bearing.balls),
            ));
        }
        if let Some(q) = loads.iter().find(|q| !(q.is_finite() && **q >= 0.0)) {
            return Err(ElementsError::invalid(
                "loads",
                *q,
                "a ball's load must be finite and >= 0",
            ));
        }
        if loads.iter().all(|q| *q == 0.0) {
            return Err(ElementsError::invalid("loads", 0.0, "no ball carries load"));
        }
        let d = bearing.ball_diameter;
        let gamma = d / bearing.pitch_diameter();
        let capacity = |groove: f64, inner: bool| {
            let f = groove / d;
            let sign = if inner { 1.0 } else { -1.0 };
            98.1 * (2.0 * f / (2.0 * f - 1.0)).powf(0.41) * (1.0 - sign * gamma).powf(1.39)
                / (1.0 + sign * gamma).powf(1.0 / 3.0)
                * gamma.powf(0.3)
                * d.powf(1.8)
                * z.powf(-1.0 / 3.0)
        };
        let capacities = [
            capacity(bearing.inner_groove_radius, true),
            capacity(bearing.outer_groove_radius, false),
        ];
        Ok(Self::rated(
            capacities,
            loads,
            [3.0, 10.0 / 3.0],
            3.0,
            10.0 / 9.0,
        ))
    }

    /// The life of a cylindrical roller `bearing` (lengths in mm) whose
    /// rollers carry `loads` (N, one per roller): line contact.
    ///
    /// # Errors
    /// As [`RatingLife::of`].
    pub fn of_rollers(bearing: &RollerBearing, loads: &[f64]) -> Result<Self, ElementsError> {
        bearing.validate()?;
        check_loads(loads, bearing.rollers)?;
        let z = bearing.rollers as f64;
        let (d, l) = (bearing.roller_diameter, bearing.roller_length);
        let gamma = d / bearing.pitch_diameter();
        let capacity = |inner: bool| {
            let sign = if inner { 1.0 } else { -1.0 };
            552.0 * (1.0 - sign * gamma).powf(29.0 / 27.0) / (1.0 + sign * gamma).powf(0.25)
                * gamma.powf(2.0 / 9.0)
                * d.powf(29.0 / 27.0)
                * l.powf(7.0 / 9.0)
                * z.powf(-0.25)
        };
        Ok(Self::rated(
            [capacity(true), capacity(false)],
            loads,
            [4.0, 4.5],
            4.0,
            9.0 / 8.0,
        ))
    }

    /// The lives from the raceways' `capacities`, the elements' `loads`
    /// averaged with the raceways' `means` exponents, the life exponent
    /// and the raceways' combining exponent.
    fn rated(
        capacities: [f64; 2],
        loads: &[f64],
        means: [f64; 2],
        life: f64,
        combine: f64,
    ) -> Self {
        let z = loads.len() as f64;
        let mean = |p: f64| (loads.iter().map(|q| q.powf(p)).sum::<f64>() / z).powf(1.0 / p);
        let [inner_capacity, outer_capacity] = capacities;
        let (inner_equivalent, outer_equivalent) = (mean(means[0]), mean(means[1]));
        let inner_life = (inner_capacity / inner_equivalent).powf(life);
        let outer_life = (outer_capacity / outer_equivalent).powf(life);
        let l10 = (inner_life.powf(-combine) + outer_life.powf(-combine)).powf(-1.0 / combine);
        Self {
            inner_capacity,
            outer_capacity,
            inner_equivalent,
            outer_equivalent,
            inner_life,
            outer_life,
            l10,
        }
    }
}

/// One finite, non-negative load per element, one of them positive.
fn check_loads(loads: &[f64], elements: usize) -> Result<(), ElementsError> {
    if loads.len() != elements {
        return Err(ElementsError::invalid(
            "loads",
            loads.len() as f64,
            format!("one load per rolling element ({elements}) is needed"),
        ));
    }
    if let Some(q) = loads.iter().find(|q| !(q.is_finite() && **q >= 0.0)) {
        return Err(ElementsError::invalid(
            "loads",
            *q,
            "an element's load must be finite and >= 0",
        ));
    }
    if loads.iter().all(|q| *q == 0.0) {
        return Err(ElementsError::invalid(
            "loads",
            0.0,
            "no element carries load",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use elcon_analysis::Material;

    #[test]
    fn the_life_falls_as_the_cube_of_the_load_and_refuses_bad_loads() {
        let b = BallBearing {
            ball_diameter: 7.938,
            inner_raceway_diameter: 31.0,
            outer_raceway_diameter: 46.9,
            inner_groove_radius: 0.52 * 7.938,
            outer_groove_radius: 0.53 * 7.938,
            balls: 9,
            diametral_clearance: None,
            material: Material::new(210e3, 0.3).unwrap(),
            radial_load: 2000.0,
        };
        let loads = [800.0, 600.0, 200.0, 0.0, 0.0, 0.0, 0.0, 200.0, 600.0];
        let one = RatingLife::of(&b, &loads).unwrap();
        let twice: Vec<f64> = loads.iter().map(|q| 2.0 * q).collect();
        let two = RatingLife::of(&b, &twice).unwrap();
        assert!((one.l10 / two.l10 - 8.0).abs() < 1e-9);
        // The inner raceway is the more curved: it has the lower capacity.
        assert!(one.inner_capacity < one.outer_capacity && one.l10 < one.inner_life);
        // A 6203-class bearing's inner raceway capacity is some kN.
        assert!(
            one.inner_capacity > 1e3 && one.inner_capacity < 2e4,
            "{}",
            one.inner_capacity
        );
        for bad in [&loads[..3], &[-1.0; 9][..], &[0.0; 9][..]] {
            let e = RatingLife::of(&b, bad).unwrap_err();
            assert!(e.to_string().contains("loads"), "{e}");
        }
    }
}
