//! The input a magnitude bound names when a quantity leaves its range: of
//! the load, the moduli and the radii the quantity grows with (each as a
//! power, `crate::scene::factors`), the one farthest out of scale in that
//! direction, and the range of it that brings the quantity back, the other
//! inputs held.

use elcon_analysis::Normal;
use elcon_influence::{Body, Model, PointSet};

use super::strain::{MAX_STRAIN, strain_length};
use crate::ctx::rounded;

/// An input a magnitude bound depends on, as the scene writes it (the
/// load, a modulus, a radius): the bound's quantity grows as `value^power`
/// with the other inputs held, so the input that takes the quantity out of
/// its range is the one whose contribution `power log10(value)` is the
/// most extreme in that direction ([`extreme`]), and its accepted range
/// follows ([`Factor::range`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Factor {
    /// The field, as the user writes it (`body2.modulus`).
    pub field: String,
    /// Where the value is written.
    pub span: std::ops::Range<usize>,
    /// The value.
    pub value: f64,
    /// The power the quantity grows with.
    pub power: f64,
    /// What it is, for the message ("a modulus").
    pub what: &'static str,
    /// `(k, o)`: the quantity grows as a power of `1 / (k / value + o)`,
    /// the value combined with the other body's or surface's term `o`
    /// (E* of two half-space bodies, `k = 1 - nu^2` and `o` the other's
    /// compliance; the spheres' combined radius, `k = 1`, `o = 1 / R_2`);
    /// `(1, 0)`: of the value alone.
    pub combined: (f64, f64),
}

impl Factor {
    /// The values of this factor that bring a quantity of `decades`
    /// (log10) within `lo..=hi` (log10), the other inputs held, in
    /// increasing order: the combined value `X` ([`Factor::combined`])
    /// scaled by `10^((bound - decades) / power)`, turned back into the
    /// value, `k / (1 / X - o)`. A bound no value reaches (the other term
    /// alone is beyond it) is infinite: `(low, high)` with `low` infinite
    /// or `low >= high` is an empty range.
    pub(crate) fn range(&self, decades: f64, (lo, hi): (f64, f64)) -> (f64, f64) {
        let (k, o) = self.combined;
        // In decades: the factor 10^((lo - decades) / power) alone can
        // underflow where the value it scales does not.
        let at = |bound: f64| {
            let shift = (bound - decades) / self.power;
            let alone = || self.value.signum() * 10f64.powf(self.value.abs().log10() + shift);
            if o == 0.0 || !(self.value > 0.0 && k > 0.0) {
                return alone();
            }
            let inverse = (k / self.value + o) * 10f64.powf(-shift);
            let rest = inverse - o;
            match rest > 0.0 {
                // The other term is negligible where `1 / X` leaves the doubles.
                _ if !(inverse.is_finite() && inverse > 0.0) => alone(),
                true => k / rest,
                false => f64::INFINITY,
            }
        };
        let (a, b) = (at(lo), at(hi));
        (a.min(b), a.max(b))
    }
}

/// The range `low..high` of an input a refusal hands back ("give a
/// modulus from ... to ..."), each end inside the range by 1e-3, or, where
/// the range is empty, why no value of that input alone will do.
pub(crate) fn range_advice(what: &str, (low, high): (f64, f64)) -> String {
    if !(low.is_finite() && low < high) {
        return format!(
            "no value of it alone brings the scene within range (the other inputs are out of \
             scale too): change them together, giving {what} of ordinary size"
        );
    }
    if high.is_infinite() {
        return format!("give {what} of at least {}", rounded(low * 1.001));
    }
    format!(
        "give {what} from {} to {}",
        rounded(low * 1.001),
        rounded(high * 0.999)
    )
}

/// Of `factors`, the one that takes a quantity out of its range the most:
/// the most negative contribution `power log10(value)` when the quantity
/// is too small (`too_small`), the most positive when it is too large;
/// `None` when none contributes in that direction.
pub(crate) fn extreme(factors: &[Factor], too_small: bool) -> Option<&Factor> {
    let toward = |f: &&Factor| {
        let c = f.power * f.value.abs().log10();
        if too_small { -c } else { c }
    };
    factors
        .iter()
        .filter(|f| f.value != 0.0 && f.value.is_finite() && toward(f) > 0.0)
        .max_by(|a, b| toward(a).total_cmp(&toward(b)))
}

/// The smallest value of a stiffness `f` (a foundation's `modulus`, a
/// half-space body's `youngs_modulus`) the small strain ([`strain`])
/// accepts under `normal` on `points`, the other body held: the mean
/// pressure over the zone at most [`MAX_STRAIN`] of E*, a foundation's
/// mean compression at most [`MAX_STRAIN`] of the zone's smaller extent.
/// 0 for any other input.
pub(crate) fn strain_floor(
    f: &Factor,
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
) -> f64 {
    let Normal::Load(load) = normal else {
        return 0.0;
    };
    let mean = load / points.total_measure();
    let index = match f.field.as_str() {
        "body1.modulus" | "body1.youngs_modulus" => 0,
        "body2.modulus" | "body2.youngs_modulus" => 1,
        _ => return 0.0,
    };
    match *bodies[index].model() {
        Model::Winkler { .. } => mean / (MAX_STRAIN * strain_length(points)),
        _ => match bodies[index].material() {
            Some(m) => {
                // 1 / E* = (1 - nu^2) / E + the other's compliance <= MAX_STRAIN / mean.
                let other = bodies[1 - index].material().map_or(0.0, |m| m.compliance());
                let room = MAX_STRAIN / mean - other;
                let nu = m.poissons_ratio();
                if room > 0.0 {
                    (1.0 - nu * nu) / room
                } else {
                    f64::INFINITY
                }
            }
            None => 0.0,
        },
    }
}
