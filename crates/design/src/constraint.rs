//! One linear constraint of the descent's step program,
//! `a . d + t_coefficient t <= b` (docs/design.md §2): a case's model row
//! (an intensity or a stress below the objective t) or a bound on the
//! step d.

/// One linear constraint of a step, `a . d + t_coefficient t <= b`.
pub(crate) struct Constraint {
    pub(crate) a: Vec<f64>,
    /// -1 for a model row (an intensity below t), 0 for a bound.
    pub(crate) t_coefficient: f64,
    pub(crate) b: f64,
}

impl Constraint {
    /// Its largest value of `a . d - b` over the trust region at t = 0
    /// (model rows) or at all (bounds).
    pub(crate) fn reach(&self, radius: f64) -> f64 {
        self.a.iter().map(|v| v.abs()).sum::<f64>() * radius - self.b
    }

    /// The size of its terms at `(d, t)`: `sum |a_i d_i| + |b| + |t_coefficient t|`
    /// (at least the smallest positive double).
    pub(crate) fn size(&self, d: &[f64], t: f64) -> f64 {
        let size: f64 = self
            .a
            .iter()
            .zip(d)
            .map(|(a, d)| (a * d).abs())
            .sum::<f64>()
            + self.b.abs()
            + (self.t_coefficient * t).abs();
        size.max(f64::MIN_POSITIVE)
    }

    /// How far `(d, t)` violates it, relative to its terms' size.
    pub(crate) fn violation(&self, d: &[f64], t: f64) -> f64 {
        let ad: f64 = self.a.iter().zip(d).map(|(a, d)| a * d).sum();
        (ad + self.t_coefficient * t - self.b) / self.size(d, t)
    }
}
