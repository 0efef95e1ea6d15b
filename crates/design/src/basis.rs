//! The basis of a linear profile family at the axial stations, and the
//! least-squares fit of drops to it.
//!
//! A family linear in its parameters theta has drops `y(s) = sum_i theta_i
//! phi_i(s)`; at the stations `s_st` they are `Phi theta` with
//! `Phi[st, i] = phi_i(s_st)`. Polynomials use the normalized coordinate
//! `s / scale` (scale the largest |s|), so that every parameter is a length
//! of the same size and the monomial basis stays well conditioned; the free
//! family has one parameter per station (`Phi = I`), or, given knots
//! `t_0 < ... < t_m` (a profile that is a function of position, whatever
//! the grid), one per knot, the natural cubic spline through them:
//!
//! ```text
//!     Phi[st, i] = c_i(s_st),   c_i the natural cubic spline with c_i(t_j) = delta_ij, its end slopes carried on beyond
//! ```

use crate::dense;
use faer::{Col, Mat};

use crate::profile::{spline_at, spline_curvatures};
use crate::{DesignError, Family, Profile};

/// The basis of a family at the stations: `Phi[st, i] = phi_i(s_st)`, in the
/// normalized coordinate `s / scale` for polynomials.
pub(crate) struct Basis {
    pub(crate) phi: Mat<f64>,
    /// Index of the constant parameter (polynomials).
    pub(crate) constant: Option<usize>,
    /// The length that normalizes s.
    scale: f64,
    /// The free family's nodes (its parameters are the drops there) in the
    /// normalized coordinate, or the polynomials' stations.
    normalized: Vec<f64>,
    /// The free family's knots, when given (else the stations are its
    /// nodes).
    knots: Option<Vec<f64>>,
}

impl Basis {
    /// The basis of `family` at `stations`; a free family's nodes are
    /// `knots` when given (strictly increasing), else the stations.
    pub(crate) fn new(
        family: Family,
        stations: &[f64],
        knots: Option<&[f64]>,
    ) -> Result<Self, DesignError> {
        let n = stations.len();
        let scale = stations.iter().fold(0.0f64, |a, s| a.max(s.abs()));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        match family {
            Family::Quadratic | Family::Polynomial { .. } => {
                let degree = match family {
                    Family::Polynomial { degree } => degree,
                    _ => 2,
                };
                if degree + 1 > n {
                    return Err(DesignError::Incompatible {
                        field: "family.degree",
                        reason: format!(
                            "degree {degree} needs at least {} axial stations, the cases have {n}",
                            degree + 1
                        ),
                    });
                }
                Ok(Self::polynomial(degree, stations, scale))
            }
            Family::Free => match knots {
                None => Ok(Self {
                    phi: Mat::identity(n, n),
                    constant: None,
                    scale,
                    normalized: stations.iter().map(|s| s / scale).collect(),
                    knots: None,
                }),
                Some(knots) => Self::spline(stations, knots),
            },
        }
    }

    /// The free family on `knots`: the natural cubic spline through a
    /// drop at each knot (`Profile::Spline`), so `Phi[st, i]` is the spline
    /// through the unit drop at knot i, at station st.
    fn spline(stations: &[f64], knots: &[f64]) -> Result<Self, DesignError> {
        if knots.len() < 2 || knots.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(DesignError::Incompatible {
                field: "knots",
                reason:
                    "a free profile's knots must be at least two, finite and strictly increasing"
                        .into(),
            });
        }
        let scale = knots.iter().fold(0.0f64, |a, s| a.max(s.abs()));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        let mut phi = Mat::<f64>::zeros(stations.len(), knots.len());
        let mut unit = vec![0.0; knots.len()];
        for i in 0..knots.len() {
            unit[i] = 1.0;
            let m = spline_curvatures(knots, &unit);
            for (st, &s) in stations.iter().enumerate() {
                phi[(st, i)] = spline_at(knots, &unit, &m, s);
            }
            unit[i] = 0.0;
        }
        Ok(Self {
            phi,
            constant: None,
            scale,
            normalized: knots.iter().map(|s| s / scale).collect(),
            knots: Some(knots.to_vec()),
        })
    }

    fn polynomial(degree: usize, stations: &[f64], scale: f64) -> Self {
        Self {
            phi: Mat::from_fn(stations.len(), degree + 1, |st, i| {
                (stations[st] / scale).powi(i as i32)
            }),
            constant: Some(0),
            scale,
            normalized: stations.iter().map(|s| s / scale).collect(),
            knots: None,
        }
    }

    /// theta less the straight line `a + b u` (u = s / scale) that fits its
    /// drops best in least squares: what a free rotation about the axis
    /// across the profile and the approach absorb (a profile and the same
    /// profile plus a line give the same forces when both are free). For
    /// the free family and polynomials of degree >= 1; a constant alone is
    /// left as it is.
    pub(crate) fn without_line(&self, theta: &[f64]) -> Vec<f64> {
        let n = self.normalized.len() as f64;
        if self.constant.is_some() && self.params() < 2 {
            return theta.to_vec();
        }
        // The drops at the nodes: the free family's parameters themselves,
        // a polynomial's values at the stations.
        let y = match self.constant {
            None => theta.to_vec(),
            Some(_) => self.drops(theta),
        };
        let u = &self.normalized;
        let (mean_u, mean_y) = (u.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let spread: f64 = u.iter().map(|v| (v - mean_u).powi(2)).sum();
        let slope = if spread > 0.0 {
            u.iter()
                .zip(&y)
                .map(|(v, w)| (v - mean_u) * (w - mean_y))
                .sum::<f64>()
                / spread
        } else {
            0.0
        };
        let intercept = mean_y - slope * mean_u;
        let mut theta = theta.to_vec();
        match self.constant {
            None => theta
                .iter_mut()
                .zip(u)
                .for_each(|(t, v)| *t -= intercept + slope * v),
            Some(c) => {
                theta[c] -= intercept;
                theta[c + 1] -= slope;
            }
        }
        theta
    }

    pub(crate) fn params(&self) -> usize {
        self.phi.ncols()
    }

    /// The drops at the stations for parameters theta.
    pub(crate) fn drops(&self, theta: &[f64]) -> Vec<f64> {
        (0..self.phi.nrows())
            .map(|st| (0..theta.len()).map(|i| self.phi[(st, i)] * theta[i]).sum())
            .collect()
    }

    /// The profile of parameters theta, shifted so its smallest drop is 0.
    pub(crate) fn profile(&self, family: Family, stations: &[f64], theta: &[f64]) -> Profile {
        let mut theta = theta.to_vec();
        if let Family::Free = family {
            // A free profile's smallest drop is at a node.
            let lowest = theta.iter().copied().fold(f64::INFINITY, f64::min);
            let drops = theta.iter().map(|t| t - lowest).collect();
            return match &self.knots {
                Some(knots) => Profile::Spline {
                    positions: knots.clone(),
                    drops,
                },
                None => Profile::Free {
                    positions: stations.to_vec(),
                    drops,
                },
            };
        }
        let lowest = self.drops(&theta).into_iter().fold(f64::INFINITY, f64::min);
        theta[0] -= lowest;
        let coefficients: Vec<f64> = theta
            .iter()
            .enumerate()
            .map(|(i, t)| t / self.scale.powi(i as i32))
            .collect();
        match family {
            Family::Quadratic => Profile::Quadratic {
                a: coefficients[2],
                b: coefficients[1],
                c: coefficients[0],
            },
            _ => Profile::Polynomial { coefficients },
        }
    }

    /// Least-squares parameters of drops `y` at the stations, shifted up so
    /// every drop is >= 0.
    pub(crate) fn fit(&self, y: &[f64]) -> Vec<f64> {
        match (self.constant, &self.knots) {
            (None, None) => y.iter().map(|v| v.max(0.0)).collect(),
            (None, Some(_)) => {
                let rhs = Col::from_fn(y.len(), |st| y[st]);
                let theta: Vec<f64> = dense::lstsq(self.phi.as_ref(), rhs.as_mat())
                    .col(0)
                    .iter()
                    .copied()
                    .collect();
                let lowest = theta.iter().copied().fold(f64::INFINITY, f64::min);
                theta.iter().map(|t| t - lowest.min(0.0)).collect()
            }
            (Some(c), _) => {
                let rhs = Col::from_fn(y.len(), |st| y[st]);
                let sol = dense::lstsq(self.phi.as_ref(), rhs.as_mat());
                let mut theta: Vec<f64> = sol.col(0).iter().copied().collect();
                let lowest = self.drops(&theta).into_iter().fold(f64::INFINITY, f64::min);
                theta[c] -= lowest.min(0.0);
                theta
            }
        }
    }
}

/// The least-squares fit of `drops` at `positions` (one per station, length)
/// by a profile of `family`, shifted up so that every drop is >= 0 and the
/// smallest is 0: the paper's curve-fitting approximation ("assume a
/// uniform load distribution, compute the necessary initial separations and
/// then fit these data to a curve"), which ignores the resulting loads.
///
/// # Errors
/// [`DesignError::Incompatible`] for mismatched lengths, fewer than two
/// positions, repeated positions or a degree the positions cannot carry;
/// [`DesignError::InvalidInput`] for a non-finite value.
pub fn fit_profile(
    family: Family,
    positions: &[f64],
    drops: &[f64],
) -> Result<Profile, DesignError> {
    if positions.len() != drops.len() || positions.len() < 2 {
        return Err(DesignError::Incompatible {
            field: "drops",
            reason: format!(
                "needs one drop per position and at least two positions ({} positions, {} drops)",
                positions.len(),
                drops.len()
            ),
        });
    }
    if let Some(&v) = positions.iter().chain(drops).find(|v| !v.is_finite()) {
        return Err(DesignError::InvalidInput {
            field: "drops",
            value: v,
            reason: "positions and drops must be finite",
        });
    }
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by(|&a, &b| positions[a].total_cmp(&positions[b]));
    let stations: Vec<f64> = order.iter().map(|&i| positions[i]).collect();
    if stations.windows(2).any(|w| w[1] <= w[0]) {
        return Err(DesignError::Incompatible {
            field: "positions",
            reason: "positions must be distinct".into(),
        });
    }
    let y: Vec<f64> = order.iter().map(|&i| drops[i]).collect();
    let basis = Basis::new(family, &stations, None)?;
    Ok(basis.profile(family, &stations, &basis.fit(&y)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_line_leaves_the_even_part_of_a_profile_on_symmetric_stations() {
        let stations: Vec<f64> = (0..9).map(|i| -4.0 + i as f64).collect();
        let even = |s: f64| 0.3 * s * s + 0.01 * s.powi(4);
        let line = |s: f64| 2.0 - 0.7 * s;
        // The free family: one drop per station.
        let free = Basis::new(Family::Free, &stations, None).unwrap();
        let theta: Vec<f64> = stations.iter().map(|&s| even(s) + line(s)).collect();
        let cleaned = free.drops(&free.without_line(&theta));
        let offset = cleaned[4] - even(0.0);
        for (st, &s) in stations.iter().enumerate() {
            assert!((cleaned[st] - offset - even(s)).abs() < 1e-12, "{s}");
        }
        // A quartic: the same profile by its coefficients (u = s / 4).
        let quartic = Basis::new(Family::Polynomial { degree: 4 }, &stations, None).unwrap();
        let theta = vec![2.0, -0.7 * 4.0, 0.3 * 16.0, 0.0, 0.01 * 256.0];
        let cleaned = quartic.without_line(&theta);
        assert!(cleaned[1].abs() < 1e-12, "{cleaned:?}");
        assert_eq!(&cleaned[2..], &theta[2..]);
        // A constant alone is left as it is.
        let constant = Basis::new(Family::Polynomial { degree: 0 }, &stations, None).unwrap();
        assert_eq!(constant.without_line(&[3.0]), vec![3.0]);
    }
}
