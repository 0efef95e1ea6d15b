//! The discrete Hertz-spring model of a radial ball bearing (Harris &
//! Kotzalas, *Rolling Bearing Analysis*, ch. 7): the reference a bearing's
//! system solve is checked against.
//!
//! Each ball's inner and outer contacts are Hertz's elliptical contacts
//! (`elcon_analysis::references::HertzEllipse`), load against approach
//! `Q = K delta^(3/2)`; in series they make `Q = K_n delta_n^(3/2)` with
//! `K_n = ((1 / K_i)^(2/3) + (1 / K_o)^(2/3))^(-3/2)`. The inner ring moves
//! by `delta_r` toward ball 0; ball j at `psi_j` is squeezed by
//! `delta_r cos psi_j - P_d / 2` and the ring's equilibrium is
//!
//! ```text
//!     F_r = sum_j K_n max(delta_r cos psi_j - P_d / 2, 0)^(3/2) cos psi_j,
//! ```
//!
//! solved for `delta_r` by bisection (monotone in `delta_r`). At zero
//! clearance Stribeck's `Z Q_max / F_r` is close to 4.37.

use crate::ElementsError;

/// The Hertz-spring model of a ball bearing.
#[derive(Debug, Clone, PartialEq)]
pub struct HertzSprings {
    /// The inner contact's constant `K_i` (force / length^(3/2)).
    pub inner: f64,
    /// The outer contact's `K_o`.
    pub outer: f64,
    /// The two in series, `K_n`.
    pub series: f64,
    /// The exponent n of `Q = K delta^n`: 3/2 for Hertz's point contacts
    /// (10/9, Palmgren's, for the line contacts of a roller bearing's
    /// start).
    pub exponent: f64,
    /// The balls' angles (radians).
    pub angles: Vec<f64>,
    /// The diametral clearance (length).
    pub clearance: f64,
    /// The radial load (force).
    pub radial_load: f64,
}

/// The Hertz-spring model's answer.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringLoads {
    /// The inner ring's displacement toward ball 0, `delta_r` (length).
    pub ring_displacement: f64,
    /// Each ball's load (force).
    pub loads: Vec<f64>,
}

impl SpringLoads {
    /// The number of balls that carry load.
    pub fn loaded(&self) -> usize {
        self.loads.iter().filter(|q| **q > 0.0).count()
    }
}

impl HertzSprings {
    /// The model whose inner and outer contacts carry `loads` at the
    /// approaches `approaches` and go as `Q = K delta^exponent`, on
    /// elements at `angles` with the diametral `clearance` under the
    /// `radial_load`.
    pub fn of_contacts(
        loads: [f64; 2],
        approaches: [f64; 2],
        exponent: f64,
        (angles, clearance, radial_load): (Vec<f64>, f64, f64),
    ) -> Self {
        let constant = |q: f64, delta: f64| q / delta.powf(exponent);
        let (inner, outer) = (
            constant(loads[0], approaches[0]),
            constant(loads[1], approaches[1]),
        );
        let series = (inner.powf(-1.0 / exponent) + outer.powf(-1.0 / exponent)).powf(-exponent);
        Self {
            inner,
            outer,
            series,
            exponent,
            angles,
            clearance,
            radial_load,
        }
    }

    /// The inner contact's approach under an element load `q`:
    /// `(q / K_i)^(1/n)`.
    pub fn inner_approach(&self, q: f64) -> f64 {
        (q / self.inner).powf(1.0 / self.exponent)
    }

    /// The ring's load at a displacement `delta_r`, and each ball's.
    fn loads(&self, delta: f64) -> (f64, Vec<f64>) {
        let loads: Vec<f64> = self
            .angles
            .iter()
            .map(|psi| {
                let squeeze = delta * psi.cos() - 0.5 * self.clearance;
                if squeeze > 0.0 {
                    self.series * squeeze.powf(self.exponent)
                } else {
                    0.0
                }
            })
            .collect();
        let total = loads
            .iter()
            .zip(&self.angles)
            .map(|(q, psi)| q * psi.cos())
            .sum();
        (total, loads)
    }

    /// The ring's displacement and the balls' loads at equilibrium.
    ///
    /// # Errors
    /// [`ElementsError::NoEquilibrium`] when no displacement carries the
    /// load (it overflows).
    pub fn solve(&self) -> Result<SpringLoads, ElementsError> {
        // At delta_lo the ring carries no load toward ball 0 (with
        // clearance no ball is squeezed; a preload's balls pull it back);
        // double delta_hi until it carries the load.
        let mut lo = (0.5 * self.clearance).min(self.clearance);
        let mut hi = (0.5 * self.clearance)
            .abs()
            .max((self.radial_load / self.series).powf(2.0 / 3.0));
        let mut steps = 0;
        while self.loads(hi).0 < self.radial_load {
            hi = 2.0 * hi + (0.5 * self.clearance).abs();
            steps += 1;
            if steps > 200 || !hi.is_finite() {
                return Err(ElementsError::NoEquilibrium(
                    "the Hertz springs carry no load at any ring displacement".into(),
                ));
            }
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.loads(mid).0 < self.radial_load {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let delta = 0.5 * (lo + hi);
        Ok(SpringLoads {
            ring_displacement: delta,
            loads: self.loads(delta).1,
        })
    }
}
