//! Resolvability: a load (or an approach) whose largest elastic
//! deformation `w` (the whole load on one cell: its pressure against E*
//! times the cell's side, a Winkler foundation's compression under it, a
//! free beam's tip deflection `P l^3 / (3 E I)`; an approach is its own)
//! is below [`MIN_RESOLVED_DEFORMATION`] of the largest initial separation
//! over the candidate zone, or below [`MIN_DEFORMATION`], is refused: the
//! contact it makes is lost in the rounding of the separations (or, below
//! [`MIN_DEFORMATION`], the squares of its residuals among the subnormal
//! numbers). A deformation or a mean force per point above
//! [`MAX_DEFORMATION`] is refused too: the squares the solve sums
//! overflow. So is a cell's compliance whose product with the squared
//! residuals leaves the doubles' range.
//!
//! A refusal names the input out of scale ([`Factor`]): of the load, the
//! moduli and the radii the quantity grows with (each as a power,
//! `crate::scene::factors`), the one farthest out of scale in that
//! direction, and the range of it that brings the quantity back, the other
//! inputs held.

use elcon_analysis::Normal;
use elcon_influence::{Body, Dimension, Model, PointSet};

use super::strain::{
    Labels, MAX_STRAIN, StrainExtent, beam_arm, combined_modulus, foundation, strain_length,
};
use crate::ctx::{Ctx, Num, rounded};
use crate::error::SceneError;

/// The smallest elastic deformation a solve resolves, as a fraction of the
/// largest initial separation over the candidate zone. Each separation is
/// exact to about `f64::EPSILON` (2.2e-16) of the largest, and the gaps
/// near the contact are differences of separations and deformations: a
/// deformation of 1e-8 of the largest separation keeps about seven
/// significant digits above that rounding (4.5e7 times it), the most a
/// certificate relative to the data's scale can tell from noise. Below it
/// the contact is rounding: the conjugate gradient wanders, a pivoting
/// method's certificate fails, or the answer is the separations' noise.
pub const MIN_RESOLVED_DEFORMATION: f64 = 1e-8;

/// The smallest elastic deformation (length), and the smallest mean force
/// a candidate point carries (force), a solve is given:
/// `sqrt(f64::MIN_POSITIVE) / f64::EPSILON` (6.718e-139) rounded up. The
/// solvers' certificates and the conjugate gradient measure residuals of
/// about the tolerance (`f64::EPSILON` times the data's scale) by their
/// squared norms: below this bound the square of (deformation x
/// tolerance) falls below the smallest normal number, among the subnormal
/// numbers (fewer than 16 digits, then zero), and the conjugate gradient
/// stalls or breaks down (Example 1 at 1e-250 lbf, its grid sized by its
/// own Hertz contact, or at E = 1e153 psi under 100 lbf, ran out of
/// iterations or broke down).
pub const MIN_DEFORMATION: f64 = 6.72e-139;

/// The largest elastic deformation (length), and the largest mean force a
/// candidate point carries (force), a solve is given: `1 /
/// MIN_DEFORMATION`, about 1.5e138, so that their squares and the sums of
/// their squares over a grid (the solvers' norms) stay far below the
/// largest f64 (1.8e308) rather than overflowing to infinity.
pub const MAX_DEFORMATION: f64 = 1.0 / MIN_DEFORMATION;

/// The largest elastic deformation `normal` can make on `points`
/// (length): an approach is its own; a load's is the largest of the whole
/// load on one cell (the contact is at least one cell): its pressure
/// against E* times the cell's smaller side (half-space models), a Winkler
/// foundation's compression under it `P / (A_cell k)`, and, without a
/// foundation, a beam's tip deflection under it as a cantilever over its
/// longer arm, `P l^3 / (3 E I)`. An upper bound, so that a refusal never
/// blames a load whose contact is resolved.
pub(crate) fn deformation(bodies: [&Body; 2], normal: Normal, points: &PointSet) -> f64 {
    match normal {
        Normal::Approach(d) => d.abs(),
        Normal::Load(p) => compliances(bodies, points)
            .into_iter()
            .fold(0.0f64, |w, (_, c)| w.max(p * c)),
    }
}

/// Each mechanism's deflection under a unit force on one cell of
/// `points` (length per force, [`deformation`]): the half-space bodies'
/// `h / (A_cell E*)`, a Winkler foundation's `1 / (A_cell k)`, and,
/// without a foundation, a free beam's `l^3 / (3 E I)`.
fn compliances(bodies: [&Body; 2], points: &PointSet) -> Vec<(Mechanism, f64)> {
    let cell = points.cell();
    let measure = cell.measure(points.dimension());
    let side = match points.dimension() {
        Dimension::Line => cell.dx,
        Dimension::Surface => cell.dx.min(cell.dy),
    };
    let foundation = foundation(bodies);
    let mut terms = Vec::new();
    if let Some(e) = combined_modulus(bodies) {
        terms.push((Mechanism::HalfSpace, side / (measure * e)));
    }
    if let Some(k) = foundation {
        terms.push((Mechanism::Foundation, 1.0 / (measure * k)));
    }
    for b in bodies {
        if let (
            None,
            Model::Beam {
                flexural_rigidity: ei,
                loaded_point,
            },
        ) = (foundation, *b.model())
        {
            terms.push((
                Mechanism::Beam,
                beam_arm(points, loaded_point).powi(3) / (3.0 * ei),
            ));
        }
    }
    terms
}

/// What makes a load's deformation on a grid ([`deformation`]): the
/// mechanism whose term is the largest under a unit load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mechanism {
    /// The half-space bodies' `P / (E* h)`.
    HalfSpace,
    /// A Winkler foundation's `P / (k A_cell)`.
    Foundation,
    /// A free beam's `P l^3 / (3 E I)`.
    Beam,
}

/// The mechanism of [`deformation`] on `points`, `None` without an
/// elastic body.
pub(crate) fn mechanism(bodies: [&Body; 2], points: &PointSet) -> Option<Mechanism> {
    compliances(bodies, points)
        .into_iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(m, _)| m)
}

/// The bodies' compliance on one cell, `c`, the [`deformation`] a unit
/// force on one cell makes (about `1 / (E* h)` on a half-space, `1 / (k
/// A_cell)` on a foundation, `l^3 / (3 E I)` on a cantilevered beam, length
/// per force), against the size of the solve's residuals, `r`, the larger
/// of the load's deformation and the largest initial separation, `largest`:
/// the conjugate gradient's step divides squared residuals by `t . S t`
/// for a direction `t` of the residuals' size, about `r^2 c`. That must
/// stay between [`MIN_DEFORMATION`]^2 and [`MAX_DEFORMATION`]^2 (about
/// 4.5e-277 and 2.2e276), or it underflows or overflows whatever the
/// method. Names the stiffness key (a foundation's `modulus`, else the
/// first `youngs_modulus`).
pub(crate) fn compliance_in_range(
    ctx: &Ctx<'_>,
    factors: &dyn Fn(bool) -> Vec<Factor>,
    bodies: [&Body; 2],
    points: &PointSet,
    (normal, largest): (Normal, f64),
    labels: Labels<'_>,
) -> Result<(), SceneError> {
    let c = deformation(bodies, Normal::Load(1.0), points);
    let w = deformation(bodies, normal, points);
    let r = w.max(largest.abs());
    // In decades: the product itself can underflow to 0 or overflow.
    let decades = 2.0 * r.log10() + c.log10();
    let range = MIN_DEFORMATION * MIN_DEFORMATION..=MAX_DEFORMATION * MAX_DEFORMATION;
    let bounds = (range.start().log10(), range.end().log10());
    // 0: no elastic body or nothing pressed (said elsewhere); in range:
    // nothing to say.
    if c == 0.0 || r == 0.0 || (bounds.0..=bounds.1).contains(&decades) {
        return Ok(());
    }
    // The input farthest out of scale in the product's direction (the
    // residuals are the load's deformation, or the largest separation).
    let candidates = factors(w >= largest.abs());
    let Some(f) = extreme(&candidates, decades < bounds.0) else {
        return Ok(());
    };
    let (low, high) = f.range(decades, bounds);
    let low = low.max(strain_floor(f, bodies, normal, points));
    // An approach is bounded by the small strain of the zone too.
    let high = match normal {
        Normal::Approach(_) if f.field == "loading.approach" => {
            high.min(MAX_STRAIN * StrainExtent::of(points).length)
        }
        _ => high,
    };
    let Labels { length, force, .. } = labels;
    Err(ctx.invalid(
        f.span.clone(),
        f.field.clone(),
        Num(f.value),
        format!(
            "the bodies' compliance on one cell of the grid, about {c:.2e} {length} per \
             {force} (a unit force's deflection there), times the square of the solve's \
             residuals, about {r:.2e} {length} (the load's deformation or the largest \
             separation), is about 1e{decades:.0}, outside {:.1e} to {:.1e}: the solve's products \
             of them underflow or overflow among doubles. Of the load, the moduli and the radii \
             this product grows with, {} is the farthest out of scale; with the others as they \
             are, {}, or check the units of the moduli, the lengths and the load",
            range.start(),
            range.end(),
            f.field,
            range_advice(f.what, (low, high)),
        ),
    ))
}

/// Why `normal` on `points` cannot be resolved against the largest initial
/// separation over the zone, `largest` (length), if it cannot: its
/// [`deformation`] below [`MIN_RESOLVED_DEFORMATION`] of `largest`, or
/// below [`MIN_DEFORMATION`]; or a deformation or a mean force per point
/// above [`MAX_DEFORMATION`]. The message gives the smallest (largest)
/// load or approach accepted: the deformation is linear in it.
pub(crate) fn unresolved(
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
    largest: f64,
    length: &str,
) -> Option<String> {
    if let Normal::Load(p) = normal
        && let Some(reason) = force_per_point(p, points)
    {
        return Some(reason);
    }
    // An approach of 0 or less presses nothing (the run says so).
    if matches!(normal, Normal::Approach(d) if d <= 0.0) {
        return None;
    }
    let w = deformation(bodies, normal, points);
    if w > MAX_DEFORMATION {
        let (value, what) = match normal {
            Normal::Load(p) => (p, "a load"),
            Normal::Approach(d) => (d, "an approach"),
        };
        return Some(format!(
            "deforms the bodies by up to about {} {length}, {}; give {what} of at most {}, or \
             check the units and the moduli",
            rounded(w),
            overflowing(length),
            rounded(value * (MAX_DEFORMATION / w) * 0.999)
        ));
    }
    let needed = (MIN_RESOLVED_DEFORMATION * largest.abs()).max(MIN_DEFORMATION);
    if w >= needed {
        return None;
    }
    let (value, what, estimate) = match normal {
        Normal::Load(p) => (
            p,
            "a load",
            "the whole load on one cell, against the bodies' stiffness",
        ),
        Normal::Approach(d) => (d.abs(), "an approach", "the approach"),
    };
    // The deformation is linear in the load: scale it up to `needed`,
    // and to where the solve's product `r^2 c` stays normal
    // ([`compliance_in_range`], `r` at least the deformation), rounded up
    // to four digits.
    let c = deformation(bodies, Normal::Load(1.0), points);
    let product_floor = if c > 0.0 && largest.abs().powi(2) * c < MIN_DEFORMATION.powi(2) {
        MIN_DEFORMATION / c.sqrt()
    } else {
        0.0
    };
    let least = if w > 0.0 && w.is_finite() {
        format!(
            "{}",
            rounded(value * (needed.max(product_floor) / w) * 1.001)
        )
    } else {
        "a larger one".to_string()
    };
    let against = if MIN_RESOLVED_DEFORMATION * largest.abs() >= MIN_DEFORMATION {
        format!(
            "{:.1e} of the largest initial separation over the candidate zone, {} {length}: \
             below {MIN_RESOLVED_DEFORMATION:.0e} of it the gaps near the contact are lost \
             among the rounding of the separations (each exact to about 2.2e-16 of the \
             largest), to which the solve's tolerances are scaled",
            w / largest.abs(),
            rounded(largest.abs())
        )
    } else {
        subnormal(length)
    };
    Some(format!(
        "deforms the bodies by at most about {} {length} ({estimate}), {against}, so no \
         contact can be resolved; give {what} of at least {least}, a smaller candidate zone or a \
         finer grid, or check the units and the moduli",
        rounded(w)
    ))
}

/// Why a load of `p` spread over `points` is out of the doubles' range
/// per point, if it is: below [`MIN_DEFORMATION`] or above
/// [`MAX_DEFORMATION`] per candidate point (force).
fn force_per_point(p: f64, points: &PointSet) -> Option<String> {
    let n = points.len();
    let per_point = p / n as f64;
    if per_point < MIN_DEFORMATION {
        return Some(format!(
            "is {} per candidate point (of {n}), below {MIN_DEFORMATION:.2e}, where the squares \
             of forces times the solve's tolerance (2.2e-16 of them) fall among the subnormal \
             numbers and lose their digits; give a load of at least {}, or check its units",
            rounded(per_point),
            rounded(MIN_DEFORMATION * n as f64 * 1.001)
        ));
    }
    (per_point > MAX_DEFORMATION).then(|| {
        format!(
            "is {} per candidate point (of {n}), above {MAX_DEFORMATION:.2e}, where the solve's \
             sums of squared forces overflow; give a load of at most {}, or check its units and \
             the moduli",
            rounded(per_point),
            rounded(MAX_DEFORMATION * n as f64 * 0.999)
        )
    })
}

/// Deformations below [`MIN_DEFORMATION`] (in `length`), as a refusal
/// says why they cannot be resolved.
fn subnormal(length: &str) -> String {
    format!(
        "below {MIN_DEFORMATION:.2e} {length}, where the squares of deformations times the \
         solve's tolerance (2.2e-16 of them) fall among the subnormal numbers and lose their \
         digits"
    )
}

/// Deformations above [`MAX_DEFORMATION`] (in `length`), as a refusal
/// says why they cannot be solved.
fn overflowing(length: &str) -> String {
    format!(
        "above {MAX_DEFORMATION:.2e} {length}, where the solve's sums of squared deformations \
         overflow"
    )
}

/// A load whose largest [`deformation`] on `points` is outside the
/// doubles' range ([`MIN_DEFORMATION`] to [`MAX_DEFORMATION`], where that
/// floor binds rather than [`MIN_RESOLVED_DEFORMATION`] of the largest
/// separation) because another input among `factors` is out of scale: that
/// input ([`extreme`]) and why, with its accepted range, the others held.
/// `None` when the load itself is the farthest out of scale (the load's
/// own refusal, [`unresolved`], says so), or the load's deformation is
/// resolvable.
pub(crate) fn deformation_out_of_scale(
    bodies: [&Body; 2],
    normal: Normal,
    points: &PointSet,
    largest: f64,
    (factors, product): (&[Factor], &[Factor]),
    length: &str,
) -> Option<(Factor, String)> {
    let Normal::Load(p) = normal else {
        return None;
    };
    let per_point = p / points.len() as f64;
    if !(MIN_DEFORMATION..=MAX_DEFORMATION).contains(&per_point) {
        return None;
    }
    let w = deformation(bodies, normal, points);
    let floor = (MIN_RESOLVED_DEFORMATION * largest.abs()).max(MIN_DEFORMATION);
    let too_small = w < floor && floor == MIN_DEFORMATION;
    if !(too_small || w > MAX_DEFORMATION) || !(w > 0.0 && w.is_finite()) {
        return None;
    }
    let f = extreme(factors, too_small)?;
    if f.field == "loading.load" {
        return None;
    }
    let (mut low, mut high) = f.range(w.log10(), (floor.log10(), MAX_DEFORMATION.log10()));
    // Within the solve's product's range too ([`compliance_in_range`]),
    // where it depends on the same input: the range both bounds accept.
    let c = deformation(bodies, Normal::Load(1.0), points);
    let decades = 2.0 * w.max(largest.abs()).log10() + c.log10();
    let bounds = (2.0 * MIN_DEFORMATION.log10(), 2.0 * MAX_DEFORMATION.log10());
    if let Some(g) = product.iter().find(|g| g.field == f.field) {
        let (a, b) = g.range(decades, bounds);
        (low, high) = (low.max(a), high.min(b));
    }
    low = low.max(strain_floor(f, bodies, normal, points));
    let against = if too_small {
        subnormal(length)
    } else {
        overflowing(length)
    };
    let reason = format!(
        "the load deforms the bodies by at most about {} {length} (the whole load on one cell, \
         against the bodies' stiffness), {against}, so no contact can be resolved. Of the load, \
         the moduli and the radii it grows with, {} is the farthest out of scale; with the \
         others as they are, {}, or check its units",
        rounded(w),
        f.field,
        range_advice(f.what, (low, high)),
    );
    Some((f.clone(), reason))
}

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
