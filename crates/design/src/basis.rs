//! The basis of a linear profile family at the axial stations, and the
//! least-squares fit of drops to it.
//!
//! A family linear in its parameters theta has drops `y(s) = sum_i theta_i
//! phi_i(s)`; at the stations `s_st` they are `Phi theta` with
//! `Phi[st, i] = phi_i(s_st)`. Polynomials use the normalized coordinate
//! `s / scale` (scale the largest |s|), so that every parameter is a length
//! of the same size and the monomial basis stays well conditioned; the free
//! family has one parameter per station (`Phi = I`).

use faer::linalg::solvers::SolveLstsq;
use faer::{Col, Mat};

use crate::{DesignError, Family, Profile};

/// The basis of a family at the stations: `Phi[st, i] = phi_i(s_st)`, in the
/// normalized coordinate `s / scale` for polynomials.
pub(crate) struct Basis {
    pub(crate) phi: Mat<f64>,
    /// Index of the constant parameter (polynomials).
    pub(crate) constant: Option<usize>,
    /// The length that normalizes s.
    scale: f64,
}

impl Basis {
    pub(crate) fn new(family: Family, stations: &[f64]) -> Result<Self, DesignError> {
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
            Family::Free => Ok(Self {
                phi: Mat::identity(n, n),
                constant: None,
                scale,
            }),
        }
    }

    fn polynomial(degree: usize, stations: &[f64], scale: f64) -> Self {
        Self {
            phi: Mat::from_fn(stations.len(), degree + 1, |st, i| {
                (stations[st] / scale).powi(i as i32)
            }),
            constant: Some(0),
            scale,
        }
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
        let lowest = self.drops(theta).into_iter().fold(f64::INFINITY, f64::min);
        let mut theta = theta.to_vec();
        match family {
            Family::Free => {
                return Profile::Free {
                    positions: stations.to_vec(),
                    drops: theta.iter().map(|t| t - lowest).collect(),
                };
            }
            _ => theta[0] -= lowest,
        }
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
        match self.constant {
            None => y.iter().map(|v| v.max(0.0)).collect(),
            Some(c) => {
                let rhs = Col::from_fn(y.len(), |st| y[st]);
                let sol = self.phi.qr().solve_lstsq(&rhs);
                let mut theta: Vec<f64> = sol.iter().copied().collect();
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
    let basis = Basis::new(family, &stations)?;
    Ok(basis.profile(family, &stations, &basis.fit(&y)))
}
