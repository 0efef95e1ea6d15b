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
//! the mean of 1/r over the rectangle. Each edge of the rectangle
//! contributes a pair of corner terms; on a lattice, neighbouring cells
//! share their edges and the kernel table evaluates each once. For a 2D
//! (plane-strain) half-space the surface displacement under a line load is
//! only defined relative to a datum at distance d0; under a uniform pressure of unit resultant on the strip
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
/// sqrt(1 + q^2) + q sqrt(1 + p^2)))` for p, q of one sign, one edge of the
/// rectangle at a time), so that the
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
    // The corners' distances from the field point, r[i][j] at (xi, yj).
    let r = [[x1.hypot(y1), x1.hypot(y2)], [x2.hypot(y1), x2.hypot(y2)]];
    let integral = (love_edge(x2, (y1, y2), (r[1][0], r[1][1]), dy)
        - love_edge(x1, (y1, y2), (r[0][0], r[0][1]), dy))
        + (love_edge(y2, (x1, x2), (r[0][1], r[1][1]), dx)
            - love_edge(y1, (x1, x2), (r[0][0], r[1][0]), dx));
    integral / (dx * dy)
}

/// One edge's share of the four-corner sum, `x [asinh(t2 / |x|) - asinh(t1
/// / |x|)]`, for the edge of the rectangle at abscissa `x` (relative to the
/// field point) from `t1` to `t2 = t1 + width` along the other axis, given
/// its corners' distances `r1 = hypot(x, t1)`, `r2 = hypot(x, t2)`. For t1,
/// t2 of one sign the difference is combined analytically,
///
/// ```text
///     asinh(p) - asinh(q) = asinh((width / |x|) (p + q) / (p s1' + q s2')),
///     p = |t2| / |x|, q = |t1| / |x|, s1' = r1 / |x|, s2' = r2 / |x|
/// ```
///
/// (`sqrt(1 + p^2) = r2 / |x|`), accurate when the two are close; 0 for x
/// = 0 (its factor x makes the term vanish). Edges shared by neighbouring
/// cells of a lattice are evaluated once by [`LoveRows`].
fn love_edge(x: f64, (t1, t2): (f64, f64), (r1, r2): (f64, f64), width: f64) -> f64 {
    let ax = x.abs();
    // x asinh(t/|x|) -> 0 as x -> 0; below 1e-100 of the other lengths the
    // term is negligible and p s' below could overflow.
    if ax <= 1e-100 * (t1.abs() + t2.abs()) {
        return 0.0;
    }
    let (p, q) = (t2 / ax, t1 / ax);
    if p * q <= 0.0 {
        // Opposite signs (or a zero): the difference adds magnitudes.
        return x * (p.asinh() - q.asinh());
    }
    // Same sign; by oddness asinh(p) - asinh(q) = asinh(hi) - asinh(lo) with
    // hi = max(|p|, |q|), lo the other, hi - lo = width / |x|, and
    // hi sqrt(1 + lo^2) + lo sqrt(1 + hi^2) the same sum either way.
    let (p, q) = (p.abs(), q.abs());
    let ratio = (p + q) / (p * (r1 / ax) + q * (r2 / ax));
    x * ((width / ax) * ratio).asinh()
}

/// Love's kernel [`love_rectangle`] on the lattice offsets `(di dx, dj
/// dy)`, row di after row di, `0 <= dj < nj`: the four-corner sum of each
/// cell from edge terms shared with its neighbours. The cells of row di
/// have their corners on the lines `X_m = (m - 1/2) dx` (m = di, di + 1)
/// and `Y_n = (n - 1/2) dy`; each corner's distance `hypot(X_m, Y_n)`
/// and each edge's [`love_edge`] term is evaluated once and serves the two
/// cells on either side, so a cell costs one `hypot` and two `asinh`
/// instead of eight and four. The corners are the lattice's, one rounding
/// of `(m - 1/2) dx` each where [`love_rectangle`] rounds `di dx` and then
/// `di dx - dx/2`: the two agree to the formula's own rounding (a few ulps
/// relative, up to about `u r / h` at distance r, u the unit roundoff,
/// through the cancellation between a cell's opposite edges). On square
/// cells (`dx == dy`) the offsets (di, dj) and (dj, di) sum the same four
/// edge terms in the other order: equal bit for bit.
pub(crate) struct LoveRows {
    dx: f64,
    dy: f64,
    /// `Y_n`, `0 <= n <= nj`.
    ys: Vec<f64>,
    /// The next row's high line m (`X_m = (m - 1/2) dx`).
    line: usize,
    /// The first corner n filled on the high line.
    high_from: usize,
    /// `hypot(X_m, Y_n)` on lines m = di (`low`) and di + 1 (`high`).
    low_radii: Vec<f64>,
    high_radii: Vec<f64>,
    /// The vertical edges' terms `love_edge(X_m, (Y_n, Y_n+1))` on lines m =
    /// di and di + 1, `0 <= n < nj`.
    low_edges: Vec<f64>,
    high_edges: Vec<f64>,
    /// The horizontal edges' terms `love_edge(Y_n, (X_di, X_di+1))` of the
    /// current row, `0 <= n <= nj`.
    across: Vec<f64>,
}

impl LoveRows {
    /// The rows of a box `nj` offsets wide on cells of `dx x dy`; the
    /// first [`LoveRows::next_row`] is row 0.
    pub(crate) fn new(dx: f64, dy: f64, nj: usize) -> Self {
        let ys: Vec<f64> = (0..=nj).map(|n| corner(n, dy)).collect();
        let mut rows = Self {
            dx,
            dy,
            ys,
            line: 0,
            high_from: 0,
            low_radii: vec![0.0; nj + 1],
            high_radii: vec![0.0; nj + 1],
            low_edges: vec![0.0; nj],
            high_edges: vec![0.0; nj],
            across: vec![0.0; nj + 1],
        };
        // Line 0 enters as the high line, which the first row moves low.
        let x = corner(0, dx);
        fill_line(
            x,
            dy,
            &rows.ys,
            0..nj + 1,
            &mut rows.high_radii,
            &mut rows.high_edges,
        );
        rows
    }

    /// Advances to the next row di and returns it: its cells dj `>= from`
    /// are then [`LoveRows::cell`]'s.
    pub(crate) fn next_row(&mut self, from: usize) -> usize {
        let di = self.line;
        std::mem::swap(&mut self.low_radii, &mut self.high_radii);
        std::mem::swap(&mut self.low_edges, &mut self.high_edges);
        // Line di was filled from the previous row's `from` on: fill the
        // columns this row starts before (a row wider than the last).
        if from < self.high_from {
            let x = corner(di, self.dx);
            let to = self.high_from;
            fill_line(
                x,
                self.dy,
                &self.ys,
                from..to,
                &mut self.low_radii,
                &mut self.low_edges,
            );
        }
        self.line += 1;
        self.high_from = from;
        let x = corner(self.line, self.dx);
        let all = from..self.ys.len();
        fill_line(
            x,
            self.dy,
            &self.ys,
            all,
            &mut self.high_radii,
            &mut self.high_edges,
        );
        let (x1, x2) = (corner(di, self.dx), corner(di + 1, self.dx));
        for n in from..self.ys.len() {
            let radii = (self.low_radii[n], self.high_radii[n]);
            self.across[n] = love_edge(self.ys[n], (x1, x2), radii, self.dx);
        }
        di
    }

    /// `love_rectangle(di dx, dj dy, dx, dy)` of the current row di, for
    /// dj at least the row's `from`.
    pub(crate) fn cell(&self, dj: usize) -> f64 {
        let integral =
            (self.high_edges[dj] - self.low_edges[dj]) + (self.across[dj + 1] - self.across[dj]);
        integral / (self.dx * self.dy)
    }
}

/// The corners' radii `hypot(x, ys[n])` on the line at abscissa x for n in
/// `corners` (those past it up to `ys.len()` already filled), and the
/// vertical edges' terms `love_edge(x, (ys[n], ys[n + 1]))` for the edges
/// n in `corners` that the line has (`n < ys.len() - 1`).
fn fill_line(
    x: f64,
    dy: f64,
    ys: &[f64],
    corners: std::ops::Range<usize>,
    radii: &mut [f64],
    edges: &mut [f64],
) {
    for n in corners.clone() {
        radii[n] = x.hypot(ys[n]);
    }
    for n in corners.start..corners.end.min(edges.len()) {
        edges[n] = love_edge(x, (ys[n], ys[n + 1]), (radii[n], radii[n + 1]), dy);
    }
}

/// The lattice's corner line `(m - 1/2) h`.
fn corner(m: usize, h: f64) -> f64 {
    (m as f64 - 0.5) * h
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

    /// Love's kernel at offset (di dx, dj dy) of rows `ni x nj` evaluated by
    /// [`LoveRows`], every offset of each row.
    fn rows(dx: f64, dy: f64, ni: usize, nj: usize) -> Vec<f64> {
        let mut rows = LoveRows::new(dx, dy, nj);
        let mut cells = Vec::with_capacity(ni * nj);
        for di in 0..ni {
            assert_eq!(rows.next_row(0), di);
            cells.extend((0..nj).map(|dj| rows.cell(dj)));
        }
        cells
    }

    #[test]
    fn shared_edges_on_exact_corners_equal_each_cell_evaluated_bit_for_bit() {
        // Cells whose corner lines (m - 1/2) h and di h +- h/2 are exact:
        // the shared edge terms are the per-cell ones, the same operations.
        for (dx, dy, ni, nj) in [(1.0, 1.0, 60, 60), (0.5, 2.0, 40, 70), (4.0, 0.25, 9, 1)] {
            let cells = rows(dx, dy, ni, nj);
            for (k, cell) in cells.iter().enumerate() {
                let (di, dj) = (k / nj, k % nj);
                let direct = love_rectangle(di as f64 * dx, dj as f64 * dy, dx, dy);
                assert_eq!(*cell, direct, "{dx} x {dy} cells, offset ({di}, {dj})");
            }
        }
    }

    #[test]
    fn shared_edges_agree_with_each_cell_evaluated_to_its_rounding() {
        // Where `(m - 1/2) h` and `di h - h/2` round differently, the two
        // evaluate the four-corner sum at corners an ulp of r apart; the
        // cancellation between a cell's opposite edges (terms of order h
        // summing to h^2 / r) turns that into a relative difference of
        // order u r / h, the paired formula's own rounding bound (see
        // love_far_field_is_accurate). Measured at most 5.3 u (1 + r/h)
        // on these boxes (thousands of ulps at r = 480 h); bound 16 u (1 +
        // r/h). The box of 340 x 340 cells of a / 128 is large_grid's.
        let u = f64::EPSILON;
        let cases = [
            (0.0117, 0.0117, 340, 340),
            (1e-3 / 128.0, 1e-3 / 128.0, 340, 340),
            (0.3, 1.7, 200, 120),
            (3.1e-7, 1.3e-7, 50, 90),
        ];
        for (dx, dy, ni, nj) in cases {
            let cells = rows(dx, dy, ni, nj);
            let mut worst: f64 = 0.0;
            for (k, cell) in cells.iter().enumerate() {
                let (x, y) = ((k / nj) as f64 * dx, (k % nj) as f64 * dy);
                let direct = love_rectangle(x, y, dx, dy);
                let relative = (cell / direct - 1.0).abs() / (u * (1.0 + x.hypot(y) / dx.min(dy)));
                worst = worst.max(relative);
            }
            assert!(worst < 16.0, "{dx} x {dy}: {worst} u (1 + r/h)");
        }
    }

    #[test]
    fn shared_edges_from_a_column_on_equal_the_full_rows() {
        // Rows started at a growing column (the mirrored table's upper
        // triangle), then full again past the box's width (a taller box),
        // give the same cells as full rows.
        let (dx, ni, nj) = (0.0117, 45, 30);
        let full = rows(dx, dx, ni, nj);
        let mut rows = LoveRows::new(dx, dx, nj);
        for di in 0..ni {
            let from = if di < nj { di } else { 0 };
            rows.next_row(from);
            for dj in from..nj {
                assert_eq!(rows.cell(dj), full[di * nj + dj], "({di}, {dj})");
            }
        }
    }
}
