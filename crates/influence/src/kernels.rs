//! Unit kernels of the half-space models: the geometric factor of each
//! influence coefficient, without the material.
//!
//! For a 3D half-space (Boussinesq) the normal deflection at distance r from
//! a unit normal point force is `(1 - nu^2) / (pi E r)`. Spread uniformly
//! over a rectangle of sides dx x dy centred at the origin, the deflection at
//! (x, y) is (Love 1929)
//!
//! ```text
//!     u(x, y) = (1 - nu^2) / (pi E) * love_rectangle(x, y, dx, dy)
//!     love_rectangle = 1 / (dx dy) * [G(X+a, Y+b) - G(X-a, Y+b) - G(X+a, Y-b) + G(X-a, Y-b)]
//!     G(x, y) = x asinh(y / |x|) + y asinh(x / |y|),   a = dx/2, b = dy/2
//! ```
//!
//! the mean of 1/r over the rectangle. For a 2D (plane-strain) half-space the
//! surface displacement under a line load is only defined relative to a datum
//! at distance d0; under a uniform pressure of unit resultant on the strip
//! `[-h/2, h/2]`
//!
//! ```text
//!     u(x) = 2 (1 - nu^2) / (pi E) * plane_strain_strip(x, h, d0)
//!     plane_strain_strip = 1/h * integral_{-h/2}^{h/2} ln(d0 / |x - s|) ds
//!                        = 1 + [ (x - c) ln(|x - c| / d0) - (x + c) ln(|x + c| / d0) ] / h,   c = h/2
//! ```
//!
//! (t ln|t| = 0 at t = 0). Lengths in any unit; `love_rectangle` and
//! `boussinesq` are in 1/length, `plane_strain_strip` is dimensionless.

/// The point-force (Boussinesq) kernel `1 / r`, r the distance from the
/// force (1/length). Infinite at r = 0: the point-force model replaces its
/// self-term by the centre value of [`love_rectangle`].
pub fn boussinesq(x: f64, y: f64) -> f64 {
    1.0 / x.hypot(y)
}

/// The mean of `1 / r` over the rectangle `[-dx/2, dx/2] x [-dy/2, dy/2]`,
/// r the distance from the field point (x, y) (1/length): Love's (1929)
/// uniform-pressure kernel, see the [module documentation](self).
///
/// Multiplied by `(1 - nu^2) / (pi E)` it is the deflection at (x, y) of a
/// half-space under a unit force spread uniformly over the rectangle. At the
/// centre of a square of side h it is `4 ln(1 + sqrt 2) / h`; far away it
/// tends to `1 / r` with a relative excess `(dx^2 + dy^2) / (24 r^2)`.
///
/// The four-corner formula is evaluated with each pair of `asinh` terms
/// combined analytically (`asinh p - asinh q = asinh((p^2 - q^2) / (p
/// sqrt(1 + q^2) + q sqrt(1 + p^2)))` for p, q of one sign), so that the
/// cancellation far from the patch costs a relative error of about
/// `1e-16 r / h` instead of `1e-16 (r / h)^2`.
///
/// The arguments are not validated: dx and dy must be positive and all four
/// finite for a meaningful (finite) result.
pub fn love_rectangle(x: f64, y: f64, dx: f64, dy: f64) -> f64 {
    // The rectangle is symmetric: fold the field point into the first quadrant.
    let (x, y) = (x.abs(), y.abs());
    let (a, b) = (0.5 * dx, 0.5 * dy);
    let (x1, x2) = (x - a, x + a);
    let (y1, y2) = (y - b, y + b);
    let integral = corner_pairs(x1, x2, y1, y2, dy) + corner_pairs(y1, y2, x1, x2, dx);
    integral / (dx * dy)
}

/// `sum_{x in {x1, x2}} sign * x [asinh(y2 / |x|) - asinh(y1 / |x|)]`, sign
/// + for x2 and - for x1: the `x asinh(y/|x|)` half of the four-corner sum,
///   with `y2 - y1 = width`.
fn corner_pairs(x1: f64, x2: f64, y1: f64, y2: f64, width: f64) -> f64 {
    x2 * asinh_difference(y2, y1, width, x2) - x1 * asinh_difference(y2, y1, width, x1)
}

/// `asinh(u / |x|) - asinh(v / |x|)` for `u - v = width > 0`, accurate when
/// the two are close; 0 for x = 0 (its factor x makes the term vanish).
fn asinh_difference(u: f64, v: f64, width: f64, x: f64) -> f64 {
    let ax = x.abs();
    // x asinh(y/|x|) -> 0 as x -> 0; below 1e-100 of the other lengths the
    // term is negligible and p^2 below could overflow.
    if ax <= 1e-100 * (u.abs() + v.abs()) {
        return 0.0;
    }
    let (p, q) = (u / ax, v / ax);
    if p * q <= 0.0 {
        // Opposite signs (or a zero): the difference adds magnitudes.
        return p.asinh() - q.asinh();
    }
    // Same sign; by oddness, asinh(p) - asinh(q) = asinh(hi) - asinh(lo) with
    // hi > lo > 0 and hi - lo = width / |x|.
    let (hi, lo) = if p > 0.0 { (p, q) } else { (-q, -p) };
    let ratio = (hi + lo) / (hi * lo.hypot(1.0) + lo * hi.hypot(1.0));
    ((width / ax) * ratio).asinh()
}

/// The mean over the strip `[-h/2, h/2]` of `ln(d0 / |x - s|)`
/// (dimensionless): the 2D half-space kernel of a uniform pressure of unit
/// resultant, relative to a datum at distance `d0`; see the
/// [module documentation](self).
///
/// Multiplied by `2 (1 - nu^2) / (pi E)` it is the plane-strain surface
/// displacement at x. At the centre it is `1 + ln(2 d0 / h)`.
///
/// The arguments are not validated: h and d0 must be positive and all three
/// finite for a meaningful result.
pub fn plane_strain_strip(x: f64, h: f64, reference_distance: f64) -> f64 {
    let c = 0.5 * h;
    let t_log_t = |t: f64| {
        if t == 0.0 {
            0.0
        } else {
            t * (t.abs() / reference_distance).ln()
        }
    };
    1.0 + (t_log_t(x - c) - t_log_t(x + c)) / h
}

#[cfg(test)]
// The references are printed to 20 digits, more than a double holds, on purpose.
#[allow(clippy::excessive_precision)]
mod tests {
    use super::*;

    #[test]
    fn love_square_centre_is_closed_form() {
        // 4 ln(1 + sqrt 2) / h: the centre deflection of a square patch.
        for h in [1e-3, 1.0, 7.5] {
            let expected = 4.0 * (1.0 + 2f64.sqrt()).ln() / h;
            assert!((love_rectangle(0.0, 0.0, h, h) / expected - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn love_matches_the_peers_square_patch_and_high_precision() {
        // Reference values of the four-corner formula evaluated in 40-digit
        // arithmetic (mpmath); hertz.py love_square(x, y, 1, 1/pi) agrees with
        // the first four to its double-precision rounding (~1e-16).
        // Tolerance 1e-14: a few ulps of the asinh/hypot evaluations.
        let cases = [
            ((0.0, 0.0, 1.0, 1.0), 3.525_494_348_078_172_1),
            ((1.0, 0.0, 1.0, 1.0), 1.038_049_735_904_756_1),
            ((2.0, 1.0, 1.0, 1.0), 0.451_088_988_349_219_85),
            ((0.25, 0.4, 1.0, 1.0), 2.822_902_579_456_066_8),
            ((0.1, 0.05, 1.0, 3.0), 1.854_107_923_726_166_98),
            ((37.3, 52.1, 1.0, 3.0), 0.015_607_935_903_257_654_6),
            ((700.0, -1300.0, 0.4, 0.9), 6.772_854_747_045_273_2e-4),
        ];
        for ((x, y, dx, dy), expected) in cases {
            let got = love_rectangle(x, y, dx, dy);
            // Far from the patch the paired formula keeps a relative error of
            // about u r / h (u = 1.1e-16; see love_far_field_is_accurate):
            // measured 6e-17 r/h at r/h = 3700.
            let tolerance = 1e-14f64.max(4e-16 * x.hypot(y) / dx.min(dy));
            assert!(
                (got / expected - 1.0).abs() < tolerance,
                "({x}, {y}, {dx}, {dy}): {got} vs {expected}"
            );
        }
    }

    #[test]
    fn love_is_symmetric_and_scales_as_one_over_length() {
        let v = love_rectangle(0.7, -1.3, 0.4, 0.9);
        assert_eq!(v, love_rectangle(-0.7, 1.3, 0.4, 0.9));
        // Swapping the axes swaps the rectangle's sides.
        assert!((v / love_rectangle(-1.3, 0.7, 0.9, 0.4) - 1.0).abs() < 1e-15);
        // Halving every length doubles the kernel (exact: powers of two).
        assert_eq!(love_rectangle(0.35, -0.65, 0.2, 0.45), 2.0 * v);
    }

    #[test]
    fn love_far_field_is_accurate() {
        // 40-digit references (mpmath). The naive four-corner formula (as in
        // hertz.py) is off by 1e-12 relative at r = 1000 h and 3.5e-10 at
        // r = 5000 h, (r/h)^2 eps; the paired form keeps ~ (r/h) eps.
        let cases = [
            ((1000.0, 0.0), 1.000_000_041_666_663_020_8e-3),
            ((3000.0, 4000.0), 2.000_000_003_333_333_337_5e-4),
        ];
        for ((x, y), expected) in cases {
            let got = love_rectangle(x, y, 1.0, 1.0);
            // The paired form's cancellation bound, about u r / h with a
            // margin: measured 4e-14 at r/h = 1000 and 9e-13 at r/h = 5000.
            let tolerance = 4e-16 * x.hypot(y);
            assert!(
                (got / expected - 1.0).abs() < tolerance,
                "({x}, {y}): {got} vs {expected}"
            );
        }
        // Further out, the multipole series of the mean of 1/r over a square of
        // half-side c, 1/r (1 + c^2/(6 r^2) - 7 c^4/(120 r^4) + O(c^6/r^6)) on the
        // x axis, is exact to 1e-20 here; tolerance 2e-16 r/h, the paired
        // form's cancellation bound (the naive form would be off by ~1e-6 at 1e5).
        let c = 0.5_f64;
        for r in [1e4_f64, 1e5] {
            let series = (1.0 + c * c / (6.0 * r * r) - 7.0 * c.powi(4) / (120.0 * r.powi(4))) / r;
            let got = love_rectangle(r, 0.0, 1.0, 1.0);
            assert!(
                (got / series - 1.0).abs() < 2e-16 * r,
                "r = {r}: {got} vs {series}"
            );
        }
    }

    #[test]
    fn strip_centre_and_symmetry() {
        let (h, d0) = (0.2_f64, 10.0_f64);
        let centre = 1.0 + (2.0 * d0 / h).ln();
        assert!((plane_strain_strip(0.0, h, d0) / centre - 1.0).abs() < 1e-15);
        assert_eq!(
            plane_strain_strip(0.3, h, d0),
            plane_strain_strip(-0.3, h, d0)
        );
        // On the strip's edge the t ln t = 0 branch is taken: 1 - ln(h / d0).
        let edge = 1.0 - (h / d0).ln();
        assert!((plane_strain_strip(0.1, h, d0) / edge - 1.0).abs() < 1e-15);
        // Far away: ln(d0 / |x|) plus O((h/x)^2).
        let far = plane_strain_strip(5.0, h, d0);
        assert!((far - (d0 / 5.0).ln()).abs() < (h / 5.0f64).powi(2));
    }
}
