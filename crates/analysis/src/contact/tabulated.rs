//! Departures of a surface from its quadric given as tables of numbers: a
//! height map on a regular grid (a profilometer's measurement, a rough
//! surface), interpolated bilinearly,
//!
//! ```text
//!     d(x, y) = (1 - s)(1 - t) h[j][i] + s (1 - t) h[j][i+1] + (1 - s) t h[j+1][i] + s t h[j+1][i+1]
//!     x = x0 + (i + s) dx,   y = y0 + (j + t) dy,   0 <= s, t <= 1
//! ```
//!
//! and an axial profile (position, drop) along x or y (a roller's crown, a
//! beam's profile), interpolated linearly, `d = (1 - t) d_i + t d_{i+1}`.
//! A departure is a height like the quadric's: positive away from the
//! other body, so it adds to the initial separation. Both forms return a
//! node's own value exactly at the node. A point outside the table (beyond
//! a billionth of its spacing) has no departure: the separations refuse it,
//! naming the table.

use crate::{AnalysisError, Num};

/// How far outside a table, in its spacings, a point still counts as on
/// its edge (the rounding of coordinates computed two ways).
const EDGE_TOLERANCE: f64 = 1e-9;

/// A height map: heights on a regular `nx x ny` grid, `h[j][i]` at
/// `(x0 + i dx, y0 + j dy)` (rows along y, as numpy's `meshgrid` lays
/// `Z[j, i]` out), at least 2 x 2, every height finite.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    label: String,
    nx: usize,
    ny: usize,
    spacing: (f64, f64),
    origin: (f64, f64),
    heights: Vec<f64>,
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
                format!("{ny} rows of {nx} values: bilinear interpolation needs at least 2 x 2"),
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
        })
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

    /// The height at `(x, y)`, interpolated bilinearly (see the module
    /// documentation); `None` outside the map.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        let (i, s) = cell((x - self.origin.0) / self.spacing.0, self.nx)?;
        let (j, t) = cell((y - self.origin.1) / self.spacing.1, self.ny)?;
        let h = |i: usize, j: usize| self.heights[j * self.nx + i];
        Some(
            (1.0 - s) * (1.0 - t) * h(i, j)
                + s * (1.0 - t) * h(i + 1, j)
                + (1.0 - s) * t * h(i, j + 1)
                + s * t * h(i + 1, j + 1),
        )
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
/// interpolated linearly between them (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct AxialProfile {
    label: String,
    axis: ProfileAxis,
    positions: Vec<f64>,
    drops: Vec<f64>,
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
        Ok(Self {
            label,
            axis,
            positions,
            drops,
        })
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

    /// The drop at `(x, y)`, interpolated linearly along the axis; `None`
    /// outside the table.
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
        let (p0, p1) = (self.positions[i], self.positions[i + 1]);
        let t = (u - p0) / (p1 - p0);
        Some((1.0 - t) * self.drops[i] + t * self.drops[i + 1])
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
}
