//! Profile corrections: the initial separation `y(s)` a designer adds to the
//! geometry, as a function of the axial position `s` (the paper's eq. 14 and
//! the crowns of roller-bearing practice). At candidate point k the initial
//! separation becomes `eps_k + y(s_k)`.
//!
//! | family | y(s) | parameters |
//! |---|---|---|
//! | [`Profile::Quadratic`] (the paper's) | `a s^2 + b s + c` | a, b, c |
//! | [`Profile::Polynomial`] | `sum_i c_i s^i` | c_0 .. c_d |
//! | [`Profile::CircularCrown`] | 0 on the flat middle, `R - sqrt(R^2 - t^2)` beyond it, `t = abs(s) - l_f/2` | R, l_f |
//! | [`Profile::LogarithmicCrown`] | 0 on the flat middle, `Q / (pi l E*) ln(1 / (1 - (1 - 0.3033 b / a) (t / a)^2))` beyond it | Q, l, E*, R, l_f |
//! | [`Profile::Free`] | one value per axial station, linear between | the values |
//!
//! The logarithmic crown is Lundberg's (1939) profile `Q / (pi l E*) ln(1 /
//! (1 - (2 s / l)^2))` with the modification of Johns & Gohar (1981) that
//! keeps the end drop finite: `b` is the Hertz half-width of a cylinder of
//! length `l` under the design load `Q`, `a` the half-length of the crowned
//! part (`(l - l_f) / 2`), `t` the distance into it. Its drop grows with `Q`:
//! a logarithmic crown is designed for one load. With `l_f = 0` it is the
//! Johns-Gohar profile; with `l_f > 0` the flat-middle variant, the same
//! curve over the crowned ends only.
//!
//! Units: s, y, lengths in length; Q in force; E* in stress. Every family
//! reports its separation as a table ([`Profile::table`]).

use crate::DesignError;

/// Which coordinate of the candidate points is the axial position `s`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// `s = x` (a beam, a line contact along x).
    X,
    /// `s = y` (a roller whose axis lies along y).
    Y,
}

impl Axis {
    /// Both axes, in the order messages list them.
    pub const ALL: [Axis; 2] = [Axis::X, Axis::Y];

    /// Its name in a scene's `design.axis`: "x", "y";
    /// [`FromStr`](std::str::FromStr) reads it back.
    pub const fn name(self) -> &'static str {
        match self {
            Axis::X => "x",
            Axis::Y => "y",
        }
    }

    /// The axial positions of the points of a set.
    pub fn positions(self, points: &elcon_influence::PointSet) -> Vec<f64> {
        match self {
            Axis::X => points.xs().into_owned(),
            Axis::Y => points.ys().into_owned(),
        }
    }
}

elcon_num::named!(Axis, "axis");
#[cfg(feature = "serde")]
elcon_num::named_serde!(Axis);

/// The constant of Johns & Gohar's (1981) logarithmic crown: the end drop
/// is that of Lundberg's profile at `1 - 0.3033 b / a` of the half-length.
pub const JOHNS_GOHAR: f64 = 0.3033;

/// How a logarithmic crown ends.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub enum LogEnd {
    /// Johns & Gohar's (1981) finite end drop: `k = 1 - 0.3033 b / a`.
    #[default]
    JohnsGohar,
    /// Lundberg's (1939) own profile, `k = 1`: the drop grows without bound
    /// toward the end of the crowned length (finite at every candidate point,
    /// which stand half a cell short of it).
    Lundberg,
    /// Fujiwara & Kawase's (2007) three-parameter crown: Johns & Gohar's
    /// function scaled by a load coefficient `K1` and ending at the drop
    /// `z_m` (the crowned part `K2 l` long is the crown's length less its
    /// flat middle):
    ///
    /// ```text
    ///     y(t) = K1 A ln[1 / (1 - (1 - exp(-z_m / (K1 A))) (t / a)^2)],   A = Q / (pi l E*)
    /// ```
    ///
    /// with t the distance beyond the flat middle and a the crowned
    /// half-length. Tuned, it keeps a tilted roller's ends clear where
    /// Johns & Gohar's crown loads them.
    FujiwaraKawase {
        /// The load coefficient K1 (> 0).
        k1: f64,
        /// The drop z_m at the end of the crowned length (length, > 0).
        end_drop: f64,
    },
}

impl LogEnd {
    /// The ends a name alone selects (Fujiwara & Kawase's needs its
    /// parameters), in the order messages list them.
    pub const NAMED: [LogEnd; 2] = [LogEnd::JohnsGohar, LogEnd::Lundberg];

    /// The names of [`NAMED`](Self::NAMED): a scene's `design.end`.
    pub const NAMES: [&'static str; 2] = ["johns-gohar", "lundberg"];

    /// Its name: "johns-gohar", "lundberg", "fujiwara-kawase".
    pub fn name(&self) -> &'static str {
        match self {
            LogEnd::JohnsGohar => Self::NAMES[0],
            LogEnd::Lundberg => Self::NAMES[1],
            LogEnd::FujiwaraKawase { .. } => "fujiwara-kawase",
        }
    }
}

impl std::str::FromStr for LogEnd {
    type Err = elcon_num::UnknownName;

    /// One of the [`NAMED`](Self::NAMED) ends by its name.
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        Self::NAMED
            .into_iter()
            .find(|e| e.name() == name)
            .ok_or_else(|| elcon_num::UnknownName::new("end", name, &Self::NAMES))
    }
}

/// A named end ([`LogEnd::NAMED`]) by its name.
#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for LogEnd {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse()
            .map_err(|_| serde::de::Error::unknown_variant(&name, &Self::NAMES))
    }
}

/// A logarithmic crown (Lundberg 1939, Johns & Gohar 1981); see the
/// [module documentation](self).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogCrown {
    /// Design load Q (force): the crown evens the pressure at this load.
    pub design_load: f64,
    /// Effective length l of the roller (length).
    pub length: f64,
    /// Combined modulus E* of roller and raceway (stress).
    pub combined_modulus: f64,
    /// Combined transverse radius R of roller and raceway (length), for the
    /// Hertz half-width `b = sqrt(4 (Q / l) R / (pi E*))`.
    pub radius: f64,
    /// Length of the flat middle l_f (0 for the Johns-Gohar profile).
    pub flat_length: f64,
    /// How the profile ends (Johns-Gohar's finite drop, or Lundberg's).
    pub end: LogEnd,
}

impl LogCrown {
    /// The Hertz half-width `b` at the design load.
    pub fn half_width(&self) -> f64 {
        (4.0 * self.design_load / self.length * self.radius
            / (std::f64::consts::PI * self.combined_modulus))
            .sqrt()
    }

    /// The drop at the end of the crowned length (length; infinite for
    /// Lundberg's end).
    pub fn end_drop(&self) -> f64 {
        self.drop_at(0.5 * self.length)
    }

    fn drop_at(&self, s: f64) -> f64 {
        let a = 0.5 * (self.length - self.flat_length);
        let t = (s.abs() - 0.5 * self.flat_length).max(0.0);
        if t == 0.0 {
            return 0.0;
        }
        let scale = self.design_load / (std::f64::consts::PI * self.length * self.combined_modulus);
        let (coefficient, k) = match self.end {
            LogEnd::JohnsGohar => (scale, 1.0 - JOHNS_GOHAR * self.half_width() / a),
            LogEnd::Lundberg => (scale, 1.0),
            LogEnd::FujiwaraKawase { k1, end_drop } => {
                let c = k1 * scale;
                (c, -(-end_drop / c).exp_m1())
            }
        };
        let u = (t / a).min(1.0);
        coefficient * -(1.0 - k * u * u).ln()
    }

    fn validate(&self) -> Result<(), DesignError> {
        for (field, v) in [
            ("log_crown.design_load", self.design_load),
            ("log_crown.length", self.length),
            ("log_crown.combined_modulus", self.combined_modulus),
            ("log_crown.radius", self.radius),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(DesignError::InvalidInput {
                    field,
                    value: v,
                    reason: "must be finite and > 0",
                });
            }
        }
        if !(self.flat_length.is_finite() && (0.0..self.length).contains(&self.flat_length)) {
            return Err(DesignError::InvalidInput {
                field: "log_crown.flat_length",
                value: self.flat_length,
                reason: "must be in [0, length)",
            });
        }
        if let LogEnd::FujiwaraKawase { k1, end_drop } = self.end {
            for (field, v) in [("log_crown.k1", k1), ("log_crown.end_drop", end_drop)] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(DesignError::InvalidInput {
                        field,
                        value: v,
                        reason: "must be finite and > 0",
                    });
                }
            }
        }
        let a = 0.5 * (self.length - self.flat_length);
        if self.end == LogEnd::JohnsGohar && JOHNS_GOHAR * self.half_width() >= a {
            return Err(DesignError::InvalidInput {
                field: "log_crown.design_load",
                value: self.design_load,
                reason: "the Hertz half-width at this load exceeds the crowned half-length / 0.3033: \
                         the logarithmic profile is undefined; lengthen the crowned part or lower the load",
            });
        }
        Ok(())
    }
}

/// A profile correction `y(s)`; see the [module documentation](self).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Profile {
    /// The paper's `y = a s^2 + b s + c` (eq. 14).
    Quadratic {
        /// a (1/length).
        a: f64,
        /// b (dimensionless).
        b: f64,
        /// c (length).
        c: f64,
    },
    /// `y = sum_i coefficients[i] s^i`.
    Polynomial {
        /// c_0, c_1, ..., c_d (c_i in length^(1-i)).
        coefficients: Vec<f64>,
    },
    /// A circular arc of radius R beyond a flat middle of length l_f.
    CircularCrown {
        /// Crown radius R (length).
        radius: f64,
        /// Length of the flat middle l_f (length, >= 0).
        flat_length: f64,
    },
    /// A logarithmic crown (Lundberg, Johns-Gohar).
    LogarithmicCrown(LogCrown),
    /// One value per axial station, linear between stations, constant beyond
    /// the first and last.
    Free {
        /// Station positions, strictly increasing (length).
        positions: Vec<f64>,
        /// The drop at each station (length).
        drops: Vec<f64>,
    },
    /// A free profile through its drops at fixed knots by the natural
    /// cubic spline (continuous slope and curvature, no curvature at the
    /// end knots), carried on along its end slopes beyond them. Smooth, so
    /// the pressure under it is bounded: a kink in a profile (the linear
    /// interpolation's, at every station) puts a logarithmic peak of
    /// pressure under it that a finer grid resolves ever higher.
    Spline {
        /// The knots, strictly increasing, at least two (length).
        positions: Vec<f64>,
        /// The drop at each knot (length).
        drops: Vec<f64>,
    },
}

/// The natural cubic spline's second derivatives `m_i` at the knots `t`
/// for values `y` (`m_0 = m_n = 0`; the tridiagonal system
/// `h_(i-1) m_(i-1) + 2 (h_(i-1) + h_i) m_i + h_i m_(i+1) = 6 (d_i - d_(i-1))`,
/// `d_i = (y_(i+1) - y_i) / h_i`, solved by the Thomas algorithm).
pub(crate) fn spline_curvatures(t: &[f64], y: &[f64]) -> Vec<f64> {
    let n = t.len();
    let mut m = vec![0.0; n];
    if n < 3 {
        return m;
    }
    let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    // Forward sweep over the interior knots 1..n-1.
    let (mut diag, mut rhs) = (vec![0.0; n], vec![0.0; n]);
    for i in 1..n - 1 {
        diag[i] = 2.0 * (h[i - 1] + h[i]);
        rhs[i] = 6.0 * (d[i] - d[i - 1]);
        if i > 1 {
            let w = h[i - 1] / diag[i - 1];
            diag[i] -= w * h[i - 1];
            rhs[i] -= w * rhs[i - 1];
        }
    }
    for i in (1..n - 1).rev() {
        let next = if i + 1 < n - 1 { h[i] * m[i + 1] } else { 0.0 };
        m[i] = (rhs[i] - next) / diag[i];
    }
    m
}

/// The natural cubic spline through `(t, y)` with second derivatives `m`
/// at `s`; beyond the end knots, the end slopes carried on.
pub(crate) fn spline_at(t: &[f64], y: &[f64], m: &[f64], s: f64) -> f64 {
    let n = t.len();
    if n == 1 {
        return y[0];
    }
    let i = t.partition_point(|&p| p <= s).clamp(1, n - 1);
    let (t0, t1, h) = (t[i - 1], t[i], t[i] - t[i - 1]);
    if s < t[0] || s > t[n - 1] {
        // The slope at the end knot (no curvature there).
        let (end, slope) = if s < t[0] {
            (0, (y[1] - y[0]) / h - h * (2.0 * m[0] + m[1]) / 6.0)
        } else {
            (
                n - 1,
                (y[n - 1] - y[n - 2]) / h + h * (m[n - 2] + 2.0 * m[n - 1]) / 6.0,
            )
        };
        return y[end] + slope * (s - t[end]);
    }
    let (a, b) = ((t1 - s) / h, (s - t0) / h);
    a * y[i - 1] + b * y[i] + ((a * a * a - a) * m[i - 1] + (b * b * b - b) * m[i]) * h * h / 6.0
}

impl Profile {
    /// No correction: `y = 0`.
    pub fn none() -> Self {
        Profile::Polynomial {
            coefficients: vec![0.0],
        }
    }

    /// The parameters by name, as result.json's design block lists them:
    /// a, b, c (quadratic); c0, c1, ... (polynomial); radius and
    /// flat_length (circular crown); design_load, end_drop and flat_length
    /// (logarithmic crown); max_drop (free).
    pub fn parameters(&self) -> std::collections::BTreeMap<String, f64> {
        let list: Vec<(String, f64)> = match self {
            Profile::Quadratic { a, b, c } => {
                vec![("a".into(), *a), ("b".into(), *b), ("c".into(), *c)]
            }
            Profile::Polynomial { coefficients } => coefficients
                .iter()
                .enumerate()
                .map(|(i, c)| (format!("c{i}"), *c))
                .collect(),
            Profile::CircularCrown {
                radius,
                flat_length,
            } => vec![
                ("radius".into(), *radius),
                ("flat_length".into(), *flat_length),
            ],
            Profile::LogarithmicCrown(c) => vec![
                ("design_load".into(), c.design_load),
                ("end_drop".into(), c.end_drop()),
                ("flat_length".into(), c.flat_length),
            ],
            Profile::Free { drops, .. } | Profile::Spline { drops, .. } => {
                vec![("max_drop".into(), drops.iter().cloned().fold(0.0, f64::max))]
            }
        };
        list.into_iter().collect()
    }

    /// A short name of the family ("quadratic", "circular crown", ...).
    pub fn family(&self) -> &'static str {
        match self {
            Profile::Quadratic { .. } => "quadratic",
            Profile::Polynomial { .. } => "polynomial",
            Profile::CircularCrown { .. } => "circular crown",
            Profile::LogarithmicCrown(_) => "logarithmic crown",
            Profile::Free { .. } => "free",
            Profile::Spline { .. } => "free (cubic spline)",
        }
    }

    /// Checks the parameters (finite; positive radii and loads; stations
    /// increasing and matched by drops).
    pub fn validate(&self) -> Result<(), DesignError> {
        let finite = |field: &'static str, v: f64| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(DesignError::InvalidInput {
                    field,
                    value: v,
                    reason: "must be finite",
                })
            }
        };
        match self {
            Profile::Quadratic { a, b, c } => {
                finite("quadratic.a", *a)?;
                finite("quadratic.b", *b)?;
                finite("quadratic.c", *c)
            }
            Profile::Polynomial { coefficients } => {
                if coefficients.is_empty() {
                    return Err(DesignError::Incompatible {
                        field: "polynomial.coefficients",
                        reason: "needs at least one coefficient".into(),
                    });
                }
                coefficients
                    .iter()
                    .try_for_each(|&c| finite("polynomial.coefficients", c))
            }
            Profile::CircularCrown {
                radius,
                flat_length,
            } => {
                if !(radius.is_finite() && *radius > 0.0) {
                    return Err(DesignError::InvalidInput {
                        field: "circular_crown.radius",
                        value: *radius,
                        reason: "must be finite and > 0",
                    });
                }
                if !(flat_length.is_finite() && *flat_length >= 0.0) {
                    return Err(DesignError::InvalidInput {
                        field: "circular_crown.flat_length",
                        value: *flat_length,
                        reason: "must be finite and >= 0",
                    });
                }
                Ok(())
            }
            Profile::LogarithmicCrown(crown) => crown.validate(),
            Profile::Free { positions, drops } | Profile::Spline { positions, drops } => {
                if positions.is_empty() || positions.len() != drops.len() {
                    return Err(DesignError::Incompatible {
                        field: "free.drops",
                        reason: format!(
                            "needs one drop per station and at least one station (got {} stations, {} drops)",
                            positions.len(),
                            drops.len()
                        ),
                    });
                }
                positions
                    .iter()
                    .try_for_each(|&p| finite("free.positions", p))?;
                drops.iter().try_for_each(|&d| finite("free.drops", d))?;
                if positions.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(DesignError::Incompatible {
                        field: "free.positions",
                        reason: "stations must be strictly increasing".into(),
                    });
                }
                Ok(())
            }
        }
    }

    /// The drop `y(s)` at axial position `s` (length).
    ///
    /// # Errors
    /// [`DesignError::InvalidInput`] for invalid parameters, and when a
    /// circular crown is asked beyond its radius (`abs(s) - l_f/2 >= R`).
    pub fn separation(&self, s: f64) -> Result<f64, DesignError> {
        self.validate()?;
        self.drop_unchecked(s)
    }

    /// The drop at `s` of a validated profile (the one check left is the
    /// circular crown's reach).
    fn drop_unchecked(&self, s: f64) -> Result<f64, DesignError> {
        Ok(match self {
            Profile::Quadratic { a, b, c } => a * s * s + b * s + c,
            Profile::Polynomial { coefficients } => {
                coefficients.iter().rev().fold(0.0, |acc, &c| acc * s + c)
            }
            Profile::CircularCrown {
                radius,
                flat_length,
            } => {
                let t = (s.abs() - 0.5 * flat_length).max(0.0);
                if t >= *radius {
                    return Err(DesignError::InvalidInput {
                        field: "circular_crown.radius",
                        value: *radius,
                        reason: "the crown is asked beyond its radius: the radius must exceed the crowned half-length",
                    });
                }
                // R - sqrt(R^2 - t^2) = t^2 / (R + sqrt(R^2 - t^2)), without cancellation.
                t * t / (radius + (radius * radius - t * t).sqrt())
            }
            Profile::LogarithmicCrown(crown) => crown.drop_at(s),
            Profile::Spline { positions, drops } => {
                spline_at(positions, drops, &spline_curvatures(positions, drops), s)
            }
            Profile::Free { positions, drops } => {
                let i = positions.partition_point(|&p| p <= s);
                if i == 0 {
                    drops[0]
                } else if i == positions.len() {
                    drops[drops.len() - 1]
                } else {
                    let (p0, p1) = (positions[i - 1], positions[i]);
                    let w = (s - p0) / (p1 - p0);
                    drops[i - 1] * (1.0 - w) + drops[i] * w
                }
            }
        })
    }

    /// The separation at each position: `(position, drop)` rows, the table a
    /// designer hands to manufacturing.
    ///
    /// # Errors
    /// As [`Profile::separation`].
    pub fn table(&self, positions: &[f64]) -> Result<Vec<(f64, f64)>, DesignError> {
        self.validate()?;
        positions
            .iter()
            .map(|&s| Ok((s, self.drop_unchecked(s)?)))
            .collect()
    }

    /// The separations at the axial positions of `positions` (one per point).
    ///
    /// # Errors
    /// As [`Profile::separation`].
    pub fn separations(&self, positions: &[f64]) -> Result<Vec<f64>, DesignError> {
        self.validate()?;
        if let Profile::Spline {
            positions: t,
            drops,
        } = self
        {
            let m = spline_curvatures(t, drops);
            return Ok(positions
                .iter()
                .map(|&s| spline_at(t, drops, &m, s))
                .collect());
        }
        positions.iter().map(|&s| self.drop_unchecked(s)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_and_polynomial_agree() {
        let q = Profile::Quadratic {
            a: 2.0,
            b: -1.0,
            c: 0.5,
        };
        let p = Profile::Polynomial {
            coefficients: vec![0.5, -1.0, 2.0],
        };
        for s in [-1.5, 0.0, 0.3, 4.0] {
            assert_eq!(q.separation(s).unwrap(), p.separation(s).unwrap());
        }
        assert_eq!(q.separation(2.0).unwrap(), 8.0 - 2.0 + 0.5);
    }

    #[test]
    fn circular_crown_is_flat_then_an_arc() {
        let c = Profile::CircularCrown {
            radius: 100.0,
            flat_length: 4.0,
        };
        assert_eq!(c.separation(1.9).unwrap(), 0.0);
        let t: f64 = 3.0;
        let exact = 100.0 - (100.0f64 * 100.0 - t * t).sqrt();
        assert!((c.separation(-5.0).unwrap() / exact - 1.0).abs() < 1e-12);
        assert!(c.separation(150.0).is_err());
        let rows = c.table(&[0.0, 5.0]).unwrap();
        assert_eq!(rows[0], (0.0, 0.0));
    }

    #[test]
    fn log_crown_has_the_lundberg_shape_and_a_finite_end_drop() {
        let crown = LogCrown {
            design_load: 10e3,
            length: 10.0,
            combined_modulus: 115_384.6,
            radius: 5.0,
            flat_length: 0.0,
            end: LogEnd::JohnsGohar,
        };
        let b = crown.half_width();
        assert!((b / 0.23487 - 1.0).abs() < 1e-3, "{b}");
        let p = Profile::LogarithmicCrown(crown);
        assert_eq!(p.separation(0.0).unwrap(), 0.0);
        // Mid-way it follows Lundberg's ln(1 / (1 - k u^2)).
        let k = 1.0 - JOHNS_GOHAR * b / 5.0;
        let lundberg = 10e3 / (std::f64::consts::PI * 10.0 * 115_384.6) * -(1.0 - k * 0.25).ln();
        assert!((p.separation(2.5).unwrap() / lundberg - 1.0).abs() < 1e-14);
        // The end drop is finite: ln(a / (0.3033 b)).
        let end = 10e3 / (std::f64::consts::PI * 10.0 * 115_384.6) * (5.0 / (JOHNS_GOHAR * b)).ln();
        assert!((crown.end_drop() / end - 1.0).abs() < 1e-12);
        // Symmetric and monotone in |s|.
        assert_eq!(p.separation(-3.0).unwrap(), p.separation(3.0).unwrap());
        assert!(p.separation(4.0).unwrap() > p.separation(3.0).unwrap());
        // Lundberg's own end: k = 1, unbounded at the end of the length.
        let lundberg_crown = LogCrown {
            end: LogEnd::Lundberg,
            ..crown
        };
        let q = Profile::LogarithmicCrown(lundberg_crown);
        let own = 10e3 / (std::f64::consts::PI * 10.0 * 115_384.6) * -(1.0f64 - 0.25).ln();
        assert!((q.separation(2.5).unwrap() / own - 1.0).abs() < 1e-14);
        assert_eq!(lundberg_crown.end_drop(), f64::INFINITY);
        assert!(q.separation(4.9).unwrap() > p.separation(4.9).unwrap());
    }

    #[test]
    fn fujiwara_kawase_with_unit_coefficient_and_johns_gohars_end_drop_is_johns_gohars_crown() {
        let johns_gohar = LogCrown {
            design_load: 5e3,
            length: 10.0,
            combined_modulus: 115_384.6,
            radius: 5.0,
            flat_length: 0.0,
            end: LogEnd::JohnsGohar,
        };
        let fujiwara_kawase = LogCrown {
            end: LogEnd::FujiwaraKawase {
                k1: 1.0,
                end_drop: johns_gohar.end_drop(),
            },
            ..johns_gohar
        };
        for s in [0.0, 1.0, 3.3, 4.9, 5.0] {
            let (a, b) = (johns_gohar.drop_at(s), fujiwara_kawase.drop_at(s));
            assert!((a - b).abs() <= 1e-14 * a.abs().max(1e-300), "{s}: {a} {b}");
        }
        // K1 scales the crown's shape, z_m sets its end; K2 is the crowned
        // share of the length (a flat middle of (1 - K2) l).
        let scaled = LogCrown {
            end: LogEnd::FujiwaraKawase {
                k1: 2.0,
                end_drop: 0.02,
            },
            flat_length: 2.0,
            ..johns_gohar
        };
        assert!((scaled.end_drop() - 0.02).abs() < 1e-15);
        assert_eq!(scaled.drop_at(0.9), 0.0);
        assert!(scaled.validate().is_ok());
        let bad = LogCrown {
            end: LogEnd::FujiwaraKawase {
                k1: -1.0,
                end_drop: 0.02,
            },
            ..johns_gohar
        };
        assert!(bad.validate().is_err());
    }

    #[test]
    fn a_spline_profile_goes_through_its_knots_smoothly_and_on_along_its_end_slopes() {
        let knots = vec![-2.0, -1.0, 0.0, 1.5, 3.0];
        let drops = vec![4.0, 1.0, 0.0, 0.5, 2.0];
        let p = Profile::Spline {
            positions: knots.clone(),
            drops: drops.clone(),
        };
        for (t, y) in knots.iter().zip(&drops) {
            assert!((p.separation(*t).unwrap() - y).abs() < 1e-14);
        }
        // Continuous slope at an interior knot, and no kink at the end knot
        // where the line carries on.
        let slope = |s: f64, h: f64| {
            (p.separation(s + h).unwrap() - p.separation(s - h).unwrap()) / (2.0 * h)
        };
        let (left, right) = (slope(-0.001, 1e-6), slope(0.001, 1e-6));
        assert!((left - right).abs() < 1e-2, "{left} {right}");
        let inside = (p.separation(3.0).unwrap() - p.separation(3.0 - 1e-6).unwrap()) / 1e-6;
        let beyond = (p.separation(4.0).unwrap() - p.separation(3.0).unwrap()) / 1.0;
        assert!(
            (inside - beyond).abs() < 1e-4 * inside.abs(),
            "{inside} {beyond}"
        );
        // The table at many positions equals the one-by-one values.
        let at: Vec<f64> = (0..50).map(|i| -2.5 + 0.13 * i as f64).collect();
        let bulk = p.separations(&at).unwrap();
        for (s, v) in at.iter().zip(bulk) {
            assert_eq!(p.separation(*s).unwrap(), v);
        }
        assert_eq!(p.family(), "free (cubic spline)");
    }

    #[test]
    fn free_profile_interpolates() {
        let f = Profile::Free {
            positions: vec![-1.0, 0.0, 2.0],
            drops: vec![3.0, 0.0, 1.0],
        };
        assert_eq!(f.separation(-2.0).unwrap(), 3.0);
        assert_eq!(f.separation(-0.5).unwrap(), 1.5);
        assert_eq!(f.separation(1.0).unwrap(), 0.5);
        assert_eq!(f.separation(9.0).unwrap(), 1.0);
    }

    #[test]
    fn invalid_parameters_are_named() {
        let e = Profile::CircularCrown {
            radius: -1.0,
            flat_length: 0.0,
        }
        .validate()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "`circular_crown.radius` = -1: must be finite and > 0"
        );
        let e = Profile::Free {
            positions: vec![0.0, 0.0],
            drops: vec![1.0, 1.0],
        }
        .validate()
        .unwrap_err();
        assert!(e.to_string().contains("strictly increasing"), "{e}");
        let e = Profile::Quadratic {
            a: f64::NAN,
            b: 0.0,
            c: 0.0,
        }
        .separation(0.0)
        .unwrap_err();
        assert!(e.to_string().starts_with("`quadratic.a` = NaN"), "{e}");
    }
}
