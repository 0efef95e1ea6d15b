//! Departures of a surface from its quadric given as tables of numbers: a
//! height map on a regular grid (a profilometer's measurement, a rough
//! surface) and an axial profile (position, drop) along x or y (a roller's
//! crown, a beam's profile). A departure is a height like the quadric's:
//! positive away from the other body, so it adds to the initial
//! separation. A point outside the table (beyond a billionth of its
//! spacing) has no departure: the separations refuse it, naming the table.
//!
//! Each table is interpolated one of two ways ([`Interpolation`]), both
//! returning a node's own value at the node (bit for bit, but for a cubic
//! map's rounding):
//!
//! - **linear** (the default): a height map bilinearly,
//!
//!   ```text
//!       d(x, y) = (1 - s)(1 - t) h[j][i] + s (1 - t) h[j][i+1] + (1 - s) t h[j+1][i] + s t h[j+1][i+1]
//!       x = x0 + (i + s) dx,   y = y0 + (j + t) dy,   0 <= s, t <= 1
//!   ```
//!
//!   a profile linearly, `d = (1 - t) d_i + t d_(i+1)`. Its slope jumps at
//!   every node, and each such kink puts a logarithmic peak of pressure
//!   under it that every finer grid resolves higher: the peak pressure
//!   does not converge under refinement.
//! - **cubic**: a slope continuous across the nodes, so the pressure under
//!   it is bounded and its peak converges. A profile is the natural cubic
//!   spline through its rows (continuous slope and curvature; no curvature
//!   at the end rows),
//!
//!   ```text
//!       d(u) = a d_i + b d_(i+1) + ((a^3 - a) m_i + (b^3 - b) m_(i+1)) h_i^2 / 6
//!       a = (p_(i+1) - u) / h_i,   b = 1 - a,   h_i = p_(i+1) - p_i
//!       h_(i-1) m_(i-1) + 2 (h_(i-1) + h_i) m_i + h_i m_(i+1) = 6 (g_i - g_(i-1)),   m_0 = m_(n-1) = 0
//!   ```
//!
//!   (`g_i = (d_(i+1) - d_i) / h_i`), its second derivatives `m_i` solved
//!   once, when the interpolation is chosen, in O(n), and kept: one double
//!   per row beside the row's two (1.5 times the table). A height map is
//!   the tensor-product natural cubic spline (bicubic): the natural spline
//!   along x through each row, then along y through those, continuous in
//!   slope and curvature across every grid line, exact at the nodes, no
//!   curvature across the edges. It is held as cubic B-spline coefficients
//!   `c[j][i]` in place of the heights (1 times the map: a map of up to
//!   5792 x 5792 doubles, 256 MiB, gains nothing but `nx + ny` doubles,
//!   where the spline's second derivatives along x, along y and across
//!   beside the heights would make it 1 GiB), and evaluated over the 4 x 4
//!   coefficients around the point,
//!
//!   ```text
//!       d(x, y) = sum_(a, b = -1..2) w_a(s) w_b(t) c[j+b][i+a]
//!       w_(-1) = (1 - s)^3 / 6               w_0 = (3 s^3 - 6 s^2 + 4) / 6
//!       w_1    = (-3 s^3 + 3 s^2 + 3 s + 1) / 6    w_2 = s^3 / 6
//!       c[j][i-1] + 4 c[j][i] + c[j][i+1] = 6 h[j][i]  (interior nodes; then alike along y)
//!       c[j][0] = h[j][0],  c[j][-1] = 2 c[j][0] - c[j][1]  (natural ends; alike at each edge)
//!   ```
//!
//!   It returns a node's height to rounding (a few units in the last
//!   place of the map's largest height) rather than bit for bit. A
//!   continuous curvature matters on a map: a cubic whose curvature jumps
//!   at the nodes (Catmull-Rom's, which needs no coefficients) bounds the
//!   pressure too, but on examples/scenes/rough-sphere.toml its peak's
//!   changes under refinement grew again at the finest grids where this
//!   spline's shrink (docs/scenes.md).

use super::spline;
use crate::{AnalysisError, Num};

/// How far outside a table, in its spacings, a point still counts as on
/// its edge (the rounding of coordinates computed two ways).
const EDGE_TOLERANCE: f64 = 1e-9;

/// How a table (a height map, an axial profile) is interpolated between
/// its nodes (see the module documentation); both return a node's value
/// at the node (a cubic map to rounding). A scene's `interpolation` key,
/// by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Bilinear on a map, linear on a profile (the default): the slope
    /// jumps at every node.
    #[default]
    Linear,
    /// The natural cubic spline: on a profile through its rows, on a map
    /// along x and then along y (bicubic): the slope and the curvature are
    /// continuous across the nodes.
    Cubic,
}

impl Interpolation {
    /// Every interpolation, in the order messages list them.
    pub const ALL: [Interpolation; 2] = [Interpolation::Linear, Interpolation::Cubic];

    /// Its name: "linear", "cubic" (a scene's `interpolation`);
    /// [`FromStr`](std::str::FromStr) reads it back.
    pub const fn name(self) -> &'static str {
        match self {
            Interpolation::Linear => "linear",
            Interpolation::Cubic => "cubic",
        }
    }
}

elcon_num::named!(Interpolation, "interpolation");
#[cfg(feature = "serde")]
elcon_num::named_serde!(Interpolation);

/// The largest height a cubic map takes: its B-spline coefficients are at
/// most 3 times the largest height in size along an axis (the inverse of
/// the system `(1, 4, 1) / 6` has a norm of at most 3), an edge's
/// extrapolation 3 times that, so a value at most 81 times it in two
/// dimensions, which must stay within the range of a double.
const CUBIC_HEIGHT_LIMIT: f64 = f64::MAX / 128.0;

/// A height map: heights on a regular `nx x ny` grid, `h[j][i]` at
/// `(x0 + i dx, y0 + j dy)` (rows along y, as numpy's `meshgrid` lays
/// `Z[j, i]` out), at least 2 x 2, every height finite, interpolated
/// bilinearly or by the natural bicubic spline ([`Interpolation`]). It
/// holds one double per node either way: the heights, or the spline's
/// coefficients in their place.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    label: String,
    nx: usize,
    ny: usize,
    spacing: (f64, f64),
    origin: (f64, f64),
    /// The heights (linear), or the spline's B-spline coefficients in
    /// their place (cubic), row by row.
    heights: Vec<f64>,
    interpolation: Interpolation,
}

/// `value` if finite and > 0, else a [`AnalysisError::Table`].
fn positive(label: &str, what: &str, value: f64) -> Result<f64, AnalysisError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(AnalysisError::table(
            label,
            format!("{what} = {}: must be finite and > 0", Num(value)),
        ))
    }
}

impl HeightMap {
    /// The map named `label` in messages (its file, or the key it was
    /// given under): `heights` row by row (`heights[j * nx + i]`), `nx`
    /// values a row, `spacing` `(dx, dy)` and `origin` `(x0, y0)`, the
    /// position of `heights[0]`.
    ///
    /// # Errors
    /// [`AnalysisError::Table`] naming `label` and the row and column (from
    /// 0) of a height that is not finite (a hole), a size that does not
    /// hold `nx x ny` values, fewer than 2 values along an axis, a spacing
    /// that is not finite and > 0, or an origin that is not finite.
    pub fn new(
        label: impl Into<String>,
        heights: Vec<f64>,
        nx: usize,
        ny: usize,
        spacing: (f64, f64),
        origin: (f64, f64),
    ) -> Result<Self, AnalysisError> {
        let label = label.into();
        if nx < 2 || ny < 2 {
            return Err(AnalysisError::table(
                &label,
                format!("{ny} rows of {nx} values: interpolation needs at least 2 x 2"),
            ));
        }
        if nx.checked_mul(ny) != Some(heights.len()) {
            return Err(AnalysisError::table(
                &label,
                format!("{} values do not make {ny} rows of {nx}", heights.len()),
            ));
        }
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(AnalysisError::table(
                &label,
                format!(
                    "row {}, column {} (from 0): {} is not a height (a hole in the map); fill it",
                    k / nx,
                    k % nx,
                    Num(heights[k])
                ),
            ));
        }
        let spacing = (
            positive(&label, "dx", spacing.0)?,
            positive(&label, "dy", spacing.1)?,
        );
        for (what, v) in [("x0", origin.0), ("y0", origin.1)] {
            if !v.is_finite() {
                return Err(AnalysisError::table(
                    &label,
                    format!("{what} = {}: must be finite", Num(v)),
                ));
            }
        }
        Ok(Self {
            label,
            nx,
            ny,
            spacing,
            origin,
            heights,
            interpolation: Interpolation::Linear,
        })
    }

    /// The same map interpolated by `interpolation` (a new map is
    /// bilinear). Made cubic, its heights become the spline's coefficients
    /// in place (O(nx ny), `nx + ny` doubles beside the map while it
    /// solves); made linear again, the coefficients become the heights
    /// again, to rounding.
    ///
    /// # Errors
    /// [`AnalysisError::Table`] naming the map: the row and column of a
    /// height beyond about 1e306 in size, whose cubic interpolation would
    /// overflow a double, or the memory for those doubles not there.
    pub fn with_interpolation(
        mut self,
        interpolation: Interpolation,
    ) -> Result<Self, AnalysisError> {
        let (nx, ny) = (self.nx, self.ny);
        let done = match (self.interpolation, interpolation) {
            (Interpolation::Linear, Interpolation::Cubic) => {
                self.cubic_in_range()?;
                spline::natural_coefficients(&mut self.heights, nx, ny)
            }
            (Interpolation::Cubic, Interpolation::Linear) => {
                spline::natural_values(&mut self.heights, nx, ny)
            }
            _ => Ok(()),
        };
        done.map_err(|reason| AnalysisError::table(&self.label, reason))?;
        self.interpolation = interpolation;
        Ok(self)
    }

    /// Every height within [`CUBIC_HEIGHT_LIMIT`] in size.
    fn cubic_in_range(&self) -> Result<(), AnalysisError> {
        let too_large = |h: &f64| !(h.abs() <= CUBIC_HEIGHT_LIMIT);
        match self.heights.iter().position(too_large) {
            None => Ok(()),
            Some(k) => Err(AnalysisError::table(
                &self.label,
                format!(
                    "row {}, column {} (from 0): the height {} is too large to interpolate \
                     cubically (at most {} in size); use interpolation = \"linear\"",
                    k / self.nx,
                    k % self.nx,
                    Num(self.heights[k]),
                    Num(CUBIC_HEIGHT_LIMIT)
                ),
            )),
        }
    }

    /// How it is interpolated.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// What names the map in messages.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// Values along x and along y: `(nx, ny)`.
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The spacing `(dx, dy)`.
    pub fn spacing(&self) -> (f64, f64) {
        self.spacing
    }

    /// The position of the first height, `(x0, y0)`.
    pub fn origin(&self) -> (f64, f64) {
        self.origin
    }

    /// The region the map covers: `(x0, x0 + (nx - 1) dx)` and the same
    /// along y.
    pub fn extent(&self) -> ((f64, f64), (f64, f64)) {
        let (x0, y0) = self.origin;
        let (dx, dy) = self.spacing;
        (
            (x0, x0 + (self.nx - 1) as f64 * dx),
            (y0, y0 + (self.ny - 1) as f64 * dy),
        )
    }

    /// The height at `(x, y)`, interpolated as [`HeightMap::interpolation`]
    /// says (see the module documentation); `None` outside the map.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        let (i, s) = cell((x - self.origin.0) / self.spacing.0, self.nx)?;
        let (j, t) = cell((y - self.origin.1) / self.spacing.1, self.ny)?;
        let h = |i: usize, j: usize| self.heights[j * self.nx + i];
        Some(match self.interpolation {
            Interpolation::Linear => {
                (1.0 - s) * (1.0 - t) * h(i, j)
                    + s * (1.0 - t) * h(i + 1, j)
                    + (1.0 - s) * t * h(i, j + 1)
                    + s * t * h(i + 1, j + 1)
            }
            Interpolation::Cubic => {
                // Along x on each of the four rows of coefficients around
                // the point, then along y through the four values (a row
                // beyond an edge extrapolated from the rows' values, the
                // same as extrapolating its coefficients: both are linear).
                let (wx, wy) = (spline::bspline_weights(s), spline::bspline_weights(t));
                let row = |j: usize| spline::weigh(wx, spline::stencil(self.nx, i, |i| h(i, j)));
                spline::weigh(wy, spline::stencil(self.ny, j, row))
            }
        })
    }
}

/// The interval `i` (of `n - 1`) a position `u` (in spacings from the
/// first node) falls in, and where in it, `s` in [0, 1]; `None` outside.
fn cell(u: f64, n: usize) -> Option<(usize, f64)> {
    let last = (n - 1) as f64;
    if !(u >= -EDGE_TOLERANCE && u <= last + EDGE_TOLERANCE) {
        return None;
    }
    let u = u.clamp(0.0, last);
    let i = (u.floor() as usize).min(n - 2);
    Some((i, u - i as f64))
}

/// The axis a profile runs along.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileAxis {
    /// Along x (a beam, a line contact).
    X,
    /// Along y (a roller whose axis is y).
    Y,
}

/// An axial profile: drops at increasing positions along an axis,
/// interpolated between them linearly or by the natural cubic spline
/// ([`Interpolation`], the module documentation). A cubic profile keeps
/// the spline's second derivatives, one per row.
#[derive(Debug, Clone, PartialEq)]
pub struct AxialProfile {
    label: String,
    axis: ProfileAxis,
    positions: Vec<f64>,
    drops: Vec<f64>,
    /// The smallest step between two rows' positions.
    smallest_step: f64,
    interpolation: Interpolation,
    /// The natural cubic spline's second derivatives at the rows (empty
    /// when linear).
    curvatures: Vec<f64>,
}

impl AxialProfile {
    /// The profile named `label` in messages: `drops[k]` at
    /// `positions[k]` along `axis`.
    ///
    /// # Errors
    /// [`AnalysisError::Table`] naming `label` and the row (from 0) of a
    /// value that is not finite or a position not above the one before;
    /// fewer than 2 rows, or lengths that differ.
    pub fn new(
        label: impl Into<String>,
        axis: ProfileAxis,
        positions: Vec<f64>,
        drops: Vec<f64>,
    ) -> Result<Self, AnalysisError> {
        let label = label.into();
        if positions.len() != drops.len() || positions.len() < 2 {
            return Err(AnalysisError::table(
                &label,
                format!(
                    "{} positions and {} drops: give at least 2 rows of (position, drop)",
                    positions.len(),
                    drops.len()
                ),
            ));
        }
        for (k, (&p, &d)) in positions.iter().zip(&drops).enumerate() {
            if !(p.is_finite() && d.is_finite()) {
                return Err(AnalysisError::table(
                    &label,
                    format!(
                        "row {k} (from 0): ({}, {}) is not a finite position and drop",
                        Num(p),
                        Num(d)
                    ),
                ));
            }
            if k > 0 && !(p > positions[k - 1]) {
                return Err(AnalysisError::table(
                    &label,
                    format!(
                        "row {k} (from 0): position {} is not above the row before's {}; \
                         positions must increase",
                        Num(p),
                        Num(positions[k - 1])
                    ),
                ));
            }
        }
        let smallest_step = positions
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        Ok(Self {
            label,
            axis,
            positions,
            drops,
            smallest_step,
            interpolation: Interpolation::Linear,
            curvatures: Vec::new(),
        })
    }

    /// The same profile interpolated by `interpolation` (a new profile is
    /// linear): the cubic spline's second derivatives solved here, once
    /// (O(n); one double per row kept, one more while it solves).
    ///
    /// # Errors
    /// [`AnalysisError::Table`] naming the profile when the spline's
    /// memory cannot be had, or a second derivative is not finite (drops
    /// or steps near the range of a double), naming the row.
    pub fn with_interpolation(
        mut self,
        interpolation: Interpolation,
    ) -> Result<Self, AnalysisError> {
        self.curvatures = match interpolation {
            Interpolation::Linear => Vec::new(),
            Interpolation::Cubic => spline::natural_curvatures(&self.positions, &self.drops)
                .map_err(|reason| AnalysisError::table(&self.label, reason))?,
        };
        self.interpolation = interpolation;
        Ok(self)
    }

    /// How it is interpolated.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// The smallest step between the positions of two rows.
    pub fn smallest_step(&self) -> f64 {
        self.smallest_step
    }

    /// What names the profile in messages.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// The axis it runs along.
    pub fn axis(&self) -> ProfileAxis {
        self.axis
    }

    /// The first and the last position.
    pub fn extent(&self) -> (f64, f64) {
        (self.positions[0], self.positions[self.positions.len() - 1])
    }

    /// The drop at `(x, y)`, interpolated along the axis as
    /// [`AxialProfile::interpolation`] says; `None` outside the table.
    pub fn drop_at(&self, x: f64, y: f64) -> Option<f64> {
        let u = match self.axis {
            ProfileAxis::X => x,
            ProfileAxis::Y => y,
        };
        let (lo, hi) = self.extent();
        let slack = EDGE_TOLERANCE * (hi - lo) / (self.positions.len() - 1) as f64;
        if !(u >= lo - slack && u <= hi + slack) {
            return None;
        }
        let u = u.clamp(lo, hi);
        let n = self.positions.len();
        let i = self.positions.partition_point(|&p| p <= u).clamp(1, n - 1) - 1;
        Some(match self.interpolation {
            Interpolation::Linear => {
                let (p0, p1) = (self.positions[i], self.positions[i + 1]);
                let t = (u - p0) / (p1 - p0);
                (1.0 - t) * self.drops[i] + t * self.drops[i + 1]
            }
            Interpolation::Cubic => {
                spline::natural_at(&self.positions, &self.drops, &self.curvatures, i, u)
            }
        })
    }
}

/// A tabulated departure of a surface from its quadric.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Departure {
    /// A height map over the surface.
    HeightMap(std::sync::Arc<HeightMap>),
    /// An axial profile.
    Profile(std::sync::Arc<AxialProfile>),
}

impl Departure {
    /// The departure at `(x, y)`; `None` outside its table.
    pub fn at(&self, x: f64, y: f64) -> Option<f64> {
        match self {
            Departure::HeightMap(m) => m.height(x, y),
            Departure::Profile(p) => p.drop_at(x, y),
        }
    }

    /// What names it in messages.
    pub fn label(&self) -> &str {
        match self {
            Departure::HeightMap(m) => m.label(),
            Departure::Profile(p) => p.label(),
        }
    }

    /// How its table is interpolated between the nodes.
    pub fn interpolation(&self) -> Interpolation {
        match self {
            Departure::HeightMap(m) => m.interpolation(),
            Departure::Profile(p) => p.interpolation(),
        }
    }

    /// The smallest spacing between its table's nodes along its axes
    /// (length): `min(dx, dy)` of a map, the smallest step between a
    /// profile's positions. Linear interpolation kinks the surface at
    /// this spacing.
    pub fn node_spacing(&self) -> f64 {
        match self {
            Departure::HeightMap(m) => {
                let (dx, dy) = m.spacing();
                dx.min(dy)
            }
            Departure::Profile(p) => p.smallest_step(),
        }
    }

    /// The region it covers, for messages.
    pub(crate) fn describe_extent(&self) -> String {
        match self {
            Departure::HeightMap(m) => {
                let ((x0, x1), (y0, y1)) = m.extent();
                format!(
                    "it covers x in [{}, {}], y in [{}, {}]",
                    Num(x0),
                    Num(x1),
                    Num(y0),
                    Num(y1)
                )
            }
            Departure::Profile(p) => {
                let (lo, hi) = p.extent();
                let axis = match p.axis() {
                    ProfileAxis::X => "x",
                    ProfileAxis::Y => "y",
                };
                format!("it covers {axis} in [{}, {}]", Num(lo), Num(hi))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane_map() -> HeightMap {
        // h = 2 x + 3 y + 1 on x in {-1, 0, 1}, y in {0, 0.5}: bilinear is exact on it.
        let (xs, ys) = ([-1.0, 0.0, 1.0], [0.0, 0.5]);
        let heights = ys
            .iter()
            .flat_map(|&y| xs.iter().map(move |&x| 2.0 * x + 3.0 * y + 1.0))
            .collect();
        HeightMap::new("plane", heights, 3, 2, (1.0, 0.5), (-1.0, 0.0)).unwrap()
    }

    #[test]
    fn bilinear_interpolation_is_exact_on_a_plane_and_at_the_nodes() {
        let m = plane_map();
        for (x, y) in [(-1.0, 0.0), (0.3, 0.2), (1.0, 0.5), (-0.75, 0.4999)] {
            let h = m.height(x, y).unwrap();
            assert!(
                (h - (2.0 * x + 3.0 * y + 1.0)).abs() < 1e-14,
                "({x}, {y}): {h}"
            );
        }
        assert_eq!(m.height(0.0, 0.5), Some(2.5));
        assert_eq!(m.height(1.0 + 1e-12, 0.0), Some(3.0));
        assert_eq!(m.height(1.01, 0.0), None);
        assert_eq!(m.height(0.0, -0.1), None);
        assert_eq!(m.height(f64::NAN, 0.0), None);
    }

    #[test]
    fn a_map_with_a_hole_or_the_wrong_size_names_itself_and_where() {
        let mut heights = vec![0.0; 6];
        heights[4] = f64::NAN;
        let e = HeightMap::new("rough.npy", heights, 3, 2, (1.0, 1.0), (0.0, 0.0)).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("rough.npy: row 1, column 1"), "{text}");
        let e = HeightMap::new("m.csv", vec![0.0; 5], 3, 2, (1.0, 1.0), (0.0, 0.0)).unwrap_err();
        assert!(
            e.to_string().contains("5 values do not make 2 rows of 3"),
            "{e}"
        );
        let e = HeightMap::new("m.csv", vec![0.0; 3], 3, 1, (1.0, 1.0), (0.0, 0.0)).unwrap_err();
        assert!(e.to_string().contains("at least 2 x 2"), "{e}");
        let e = HeightMap::new("m.csv", vec![0.0; 4], 2, 2, (0.0, 1.0), (0.0, 0.0)).unwrap_err();
        assert!(e.to_string().contains("dx = 0"), "{e}");
    }

    #[test]
    fn a_profile_interpolates_linearly_and_returns_its_nodes_exactly() {
        let p = AxialProfile::new(
            "crown.csv",
            ProfileAxis::Y,
            vec![-1.0, 0.1, 1.0],
            vec![0.3, 0.0, 0.7],
        )
        .unwrap();
        assert_eq!(p.drop_at(5.0, 0.1), Some(0.0));
        assert_eq!(p.drop_at(5.0, 1.0), Some(0.7));
        assert_eq!(p.drop_at(5.0, -1.0), Some(0.3));
        let mid = p.drop_at(0.0, 0.55).unwrap();
        assert!((mid - 0.35).abs() < 1e-15, "{mid}");
        assert_eq!(p.drop_at(0.0, 1.5), None);
        let e = AxialProfile::new("c.csv", ProfileAxis::X, vec![0.0, 0.0], vec![1.0, 1.0]);
        assert!(e.unwrap_err().to_string().contains("row 1"));
        let e = AxialProfile::new("c.csv", ProfileAxis::X, vec![0.0, 1.0], vec![1.0, f64::NAN]);
        assert!(e.unwrap_err().to_string().starts_with("c.csv: row 1"));
        let e = AxialProfile::new("c.csv", ProfileAxis::X, vec![0.0], vec![1.0]);
        assert!(e.unwrap_err().to_string().contains("at least 2 rows"));
    }

    /// A bumpy map `sin(3x) cos(2y) + x y` on `nx x ny` nodes over
    /// [0, 1] x [0, 1], interpolated by `interpolation`, with its
    /// heights' range.
    fn bumpy(nx: usize, ny: usize, interpolation: Interpolation) -> (HeightMap, f64) {
        let (dx, dy) = (1.0 / (nx - 1) as f64, 1.0 / (ny - 1) as f64);
        let heights: Vec<f64> = (0..ny)
            .flat_map(|j| {
                (0..nx).map(move |i| {
                    let (x, y) = (i as f64 * dx, j as f64 * dy);
                    (3.0 * x).sin() * (2.0 * y).cos() + x * y
                })
            })
            .collect();
        let range = heights.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
            - heights.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        let map = HeightMap::new("bumpy", heights, nx, ny, (dx, dy), (0.0, 0.0))
            .unwrap()
            .with_interpolation(interpolation)
            .unwrap();
        (map, range)
    }

    /// The one-sided slopes of `f` at `u`, over `step` to the left and to
    /// the right.
    fn one_sided(f: impl Fn(f64) -> f64, u: f64, step: f64) -> (f64, f64) {
        ((f(u) - f(u - step)) / step, (f(u + step) - f(u)) / step)
    }

    #[test]
    fn interpolations_read_their_names_and_an_unknown_one_lists_them() {
        assert_eq!(elcon_num::unparsed(&Interpolation::ALL), None);
        assert_eq!(Interpolation::default(), Interpolation::Linear);
        let e = "spline".parse::<Interpolation>().unwrap_err();
        assert_eq!(
            e.to_string(),
            "unknown interpolation `spline`, expected one of `linear`, `cubic`"
        );
    }

    /// The one-sided second derivatives of `f` at `u`, over two steps of
    /// `step` to the left and to the right.
    fn one_sided_curvatures(f: impl Fn(f64) -> f64, u: f64, step: f64) -> (f64, f64) {
        let second = |a: f64, b: f64, c: f64| (a - 2.0 * b + c) / (step * step);
        (
            second(f(u), f(u - step), f(u - 2.0 * step)),
            second(f(u), f(u + step), f(u + 2.0 * step)),
        )
    }

    #[test]
    fn a_cubic_map_is_exact_at_its_nodes_with_a_continuous_slope_and_curvature() {
        let (cubic, range) = bumpy(7, 5, Interpolation::Cubic);
        let (linear, _) = bumpy(7, 5, Interpolation::Linear);
        let (dx, dy) = cubic.spacing();
        // The heights back to rounding (the coefficients hold them; the
        // heights are at most 2 in size).
        let largest = 2.0;
        for j in 0..5 {
            for i in 0..7 {
                let (x, y) = (i as f64 * dx, j as f64 * dy);
                let (c, l) = (cubic.height(x, y).unwrap(), linear.height(x, y).unwrap());
                assert!(
                    (c - l).abs() < 8.0 * f64::EPSILON * largest,
                    "({i}, {j}): {c} {l}"
                );
            }
        }
        // Across the interior node (3, 2), off the grid lines too: the
        // one-sided slopes over a millionth of a cell agree to a few
        // millionths of the slope scale `range / dx`, and the one-sided
        // curvatures over a thousandth of a cell to a hundredth of
        // `range / dx^2`; the bilinear map's kink does not.
        let scale = range / dx;
        for y in [2.0 * dy, 2.3 * dy] {
            let along = |x: f64| cubic.height(x, y).unwrap();
            let (l, r) = one_sided(along, 3.0 * dx, 1e-6 * dx);
            assert!((l - r).abs() < 1e-5 * scale, "y = {y}: {l} {r}");
            let (l, r) = one_sided_curvatures(along, 3.0 * dx, 1e-3 * dx);
            assert!((l - r).abs() < 1e-2 * scale / dx, "y = {y}: {l} {r}");
            let (l, r) = one_sided(|x| linear.height(x, y).unwrap(), 3.0 * dx, 1e-6 * dx);
            assert!((l - r).abs() > 1e-2 * scale, "y = {y}: {l} {r}");
        }
        for x in [3.0 * dx, 3.6 * dx] {
            let across = |y: f64| cubic.height(x, y).unwrap();
            let (l, r) = one_sided(across, 2.0 * dy, 1e-6 * dy);
            assert!((l - r).abs() < 1e-5 * range / dy, "x = {x}: {l} {r}");
            let (l, r) = one_sided_curvatures(across, 2.0 * dy, 1e-3 * dy);
            assert!((l - r).abs() < 1e-2 * range / (dy * dy), "x = {x}: {l} {r}");
        }
        assert_eq!(cubic.height(1.01, 0.0), None);
        assert_eq!(cubic.height(1.0 + 1e-12, 0.5), cubic.height(1.0, 0.5));
        // Made linear again, its heights come back to rounding.
        let back = cubic.with_interpolation(Interpolation::Linear).unwrap();
        for (x, y) in [(0.0, 0.0), (0.31, 0.77), (1.0, 1.0)] {
            let (b, l) = (back.height(x, y).unwrap(), linear.height(x, y).unwrap());
            assert!(
                (b - l).abs() < 8.0 * f64::EPSILON * largest,
                "({x}, {y}): {b} {l}"
            );
        }
    }

    #[test]
    fn a_cubic_map_reproduces_a_quadratic_inside_and_converges_on_a_smooth_surface() {
        // The natural ends differ from a quadratic's curvature there; the
        // difference fades by about 0.27 a node inward, so the middle of a
        // map of 21 x 21 nodes is the quadratic to a millionth of its
        // range (about 2.6).
        let q = |x: f64, y: f64| 0.3 * x * x - 1.2 * x * y + 0.7 * y * y + 0.5 * x - 0.2 * y + 1.0;
        let (n, h) = (21, 0.1);
        let heights = (0..n)
            .flat_map(|j| (0..n).map(move |i| q(i as f64 * h - 1.0, j as f64 * h - 1.0)))
            .collect();
        let map = HeightMap::new("q", heights, n, n, (h, h), (-1.0, -1.0))
            .unwrap()
            .with_interpolation(Interpolation::Cubic)
            .unwrap();
        for k in 0..=20 {
            let (x, y) = (-0.3 + 0.03 * k as f64, 0.25 - 0.027 * k as f64);
            let d = map.height(x, y).unwrap();
            assert!(
                (d - q(x, y)).abs() < 1e-6 * 2.6,
                "({x}, {y}): {d} {}",
                q(x, y)
            );
        }
        // A smooth surface: inside, the error falls about 16 times as the
        // spacing halves (fourth order); over the whole map (second order
        // at the natural edges) it stays below the bilinear map's.
        let error = |n: usize, interpolation, inside: bool| {
            let (m, range) = bumpy(n, n, interpolation);
            let (lo, step) = if inside {
                (0.25, 0.5 / 40.0)
            } else {
                (0.0, 1.0 / 40.0)
            };
            let worst = (0..=40)
                .flat_map(|a| (0..=40).map(move |b| (lo + a as f64 * step, lo + b as f64 * step)))
                .map(|(x, y)| {
                    (m.height(x, y).unwrap() - ((3.0 * x).sin() * (2.0 * y).cos() + x * y)).abs()
                })
                .fold(0.0, f64::max);
            worst / range
        };
        let cubic = Interpolation::Cubic;
        let (coarse, fine) = (error(9, cubic, true), error(17, cubic, true));
        assert!(coarse / fine > 10.0, "{coarse} {fine}");
        let linear = error(17, Interpolation::Linear, false);
        assert!(error(17, cubic, false) < linear, "{linear}");
    }

    #[test]
    fn a_cubic_map_of_two_nodes_along_an_axis_is_linear_along_it() {
        let map = HeightMap::new(
            "two",
            vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0],
            3,
            2,
            (1.0, 1.0),
            (0.0, 0.0),
        )
        .unwrap()
        .with_interpolation(Interpolation::Cubic)
        .unwrap();
        // h = x + 3 y: linear along y (two rows), exact along x.
        let h = map.height(1.5, 0.25).unwrap();
        assert!((h - 2.25).abs() < 1e-15 * 5.0, "{h}");
        let e = HeightMap::new(
            "big",
            vec![0.0, 0.0, 1e307, 0.0],
            2,
            2,
            (1.0, 1.0),
            (0.0, 0.0),
        )
        .unwrap()
        .with_interpolation(Interpolation::Cubic)
        .unwrap_err();
        assert!(e.to_string().starts_with("big: row 1, column 0"), "{e}");
    }

    /// A cubic polynomial sampled at 41 uneven positions over [-2, 2] as a
    /// cubic profile, with the polynomial and the samples' range.
    fn cubic_profile() -> (AxialProfile, fn(f64) -> f64, f64) {
        let p: fn(f64) -> f64 = |u| 0.2 * u * u * u - 0.5 * u * u + u - 0.3;
        let positions: Vec<f64> = (0..41)
            .map(|k| {
                let v = -2.0 + 0.1 * k as f64;
                v + 0.02 * (7.0 * v).sin()
            })
            .collect();
        let drops: Vec<f64> = positions.iter().map(|&u| p(u)).collect();
        let range = drops.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
            - drops.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        let profile = AxialProfile::new("crown.csv", ProfileAxis::X, positions, drops)
            .unwrap()
            .with_interpolation(Interpolation::Cubic)
            .unwrap();
        (profile, p, range)
    }

    #[test]
    fn a_cubic_profile_is_exact_at_its_rows_and_smooth_across_them() {
        let (profile, p, range) = cubic_profile();
        let positions = profile.positions.clone();
        for (k, &u) in positions.iter().enumerate() {
            let d = profile.drop_at(u, 0.0).unwrap();
            assert!(
                (d - p(u)).abs() <= 2.0 * f64::EPSILON * range,
                "row {k}: {d} {}",
                p(u)
            );
        }
        // Slope (and curvature) continuous across an interior row.
        let h = profile.smallest_step();
        let at = |u: f64| profile.drop_at(u, 0.0).unwrap();
        for &u in &positions[1..40] {
            let (l, r) = one_sided(at, u, 1e-6 * h);
            assert!((l - r).abs() < 1e-5 * range / h, "{u}: {l} {r}");
        }
        // Natural ends (no curvature at the end rows, where the cubic has
        // some) perturb the spline near them only: in the middle half it
        // is the cubic to a millionth of the data's range.
        for k in 0..=100 {
            let u = -1.0 + 0.02 * k as f64;
            let d = at(u);
            assert!((d - p(u)).abs() < 1e-6 * range, "{u}: {d} {}", p(u));
        }
        assert_eq!(profile.drop_at(0.0, 5.0), profile.drop_at(0.0, -5.0));
        assert_eq!(profile.drop_at(2.5, 0.0), None);
    }

    #[test]
    fn a_linear_profile_is_unchanged_and_the_departure_says_how_and_how_fine() {
        let rows = || (vec![-1.0, 0.1, 1.0], vec![0.3, 0.0, 0.7]);
        let (positions, drops) = rows();
        let plain = AxialProfile::new("c.csv", ProfileAxis::Y, positions, drops).unwrap();
        let (positions, drops) = rows();
        let linear = AxialProfile::new("c.csv", ProfileAxis::Y, positions, drops)
            .unwrap()
            .with_interpolation(Interpolation::Linear)
            .unwrap();
        assert_eq!(plain, linear);
        assert_eq!(linear.drop_at(0.0, 0.55), plain.drop_at(0.0, 0.55));
        let cubic = linear
            .clone()
            .with_interpolation(Interpolation::Cubic)
            .unwrap();
        let d = Departure::Profile(std::sync::Arc::new(cubic));
        assert_eq!(d.interpolation(), Interpolation::Cubic);
        assert!((d.node_spacing() - 0.9).abs() < 1e-15);
        let m = Departure::HeightMap(std::sync::Arc::new(plane_map()));
        assert_eq!(m.interpolation(), Interpolation::Linear);
        assert_eq!(m.node_spacing(), 0.5);
    }
}
