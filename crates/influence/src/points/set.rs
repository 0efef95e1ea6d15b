//! The point set: the validated constructors (a line, a disk or a rectangle
//! of lattice cells, or points as given), and what a set answers about its
//! points. A grid stores no coordinates but its lattice runs and a rule per
//! axis, `x_k = x(i_k)`, `y_k = y(j_k)`, with
//!
//! ```text
//!     x(i) = i h   (node-centred)   or   x(i) = mid + (2 i + 1 - n) h / 2   (n cells centred on mid)
//! ```

use std::borrow::Cow;

use elcon_num::Num;

use super::boundary::{boundary_by_cells, lattice_boundary};
use super::cell::Cell;
use super::lattice::{GridRuns, Lattice, LatticeIndex, LatticeIter, Run};
use crate::dimension::Dimension;
use crate::error::InfluenceError;

/// The largest number of points a set may hold (about 4.2 million: a
/// lattice operator's FFT grid of that many points takes about 1 GB). The
/// dense influence matrix has its own, lower limit, [`MAX_DENSE_POINTS`].
pub const MAX_POINTS: usize = 1 << 22;

/// The largest number of points (or folded unknowns) whose dense influence
/// matrix [`assemble`](crate::assemble) builds: N x N doubles, 34 GB at
/// this size. Larger grids are solved matrix-free
/// ([`LatticeOperator`](crate::LatticeOperator)).
pub const MAX_DENSE_POINTS: usize = 1 << 16;

/// Relative tolerance on the radius of [`PointSet::grid_disk`], so that a
/// radius of exactly m spacings keeps the boundary points despite rounding.
const DISK_RADIUS_TOLERANCE: f64 = 1e-9;

/// A set of candidate contact points, each the centre of a cell of the same
/// shape; see the [module documentation](super).
///
/// Built only by the validated constructors, so a `PointSet` is never empty,
/// holds finite distinct coordinates and at most [`MAX_POINTS`] points.
/// A grid constructor's set stores no coordinates: they follow from the
/// lattice indices, which it stores as runs (a few bytes a lattice row, and
/// 4 bytes per 64 points that find a point's run), so a grid takes 2 bytes
/// a point (its boundary flags).
#[derive(Debug, Clone)]
pub struct PointSet {
    dimension: Dimension,
    cell: Cell,
    layout: Layout,
    /// Whether an adjacent cell along x (x +- dx), resp. along y (y +- dy),
    /// holds no point of the set.
    boundary: Vec<(bool, bool)>,
}

/// Where the points are.
#[derive(Debug, Clone)]
enum Layout {
    /// Coordinates as given, with lattice indices `(i, j)` when the set
    /// lies on a lattice of the cell's spacing: `x_k - x_l = (i_k - i_l) dx`
    /// and `y_k - y_l = (j_k - j_l) dy` (to rounding).
    Listed {
        xs: Vec<f64>,
        ys: Vec<f64>,
        lattice: Option<Vec<(i64, i64)>>,
    },
    /// A grid: the lattice indices by runs, the coordinates by a rule per
    /// axis, `x_k = x(i_k)`, `y_k = y(j_k)`. The runs are one per lattice
    /// row, along j (step (0, 1)), in increasing i; or one run along i (a
    /// line).
    Grid {
        x: AxisRule,
        y: AxisRule,
        runs: GridRuns,
    },
}

/// The coordinate of lattice index `i` along one axis of a grid.
#[derive(Debug, Clone, Copy, PartialEq)]
enum AxisRule {
    /// `i h`: node-centred, the origin on a point.
    Scaled { h: f64 },
    /// `mid + (2 i + 1 - n) h / 2`: `n` cells of length `h` centred on
    /// `mid`, i = 0..n.
    Centred { mid: f64, n: usize, h: f64 },
}

impl AxisRule {
    fn at(self, i: i64) -> f64 {
        match self {
            Self::Scaled { h } => i as f64 * h,
            Self::Centred { mid, n, h } => mid + (2.0 * i as f64 + 1.0 - n as f64) * (0.5 * h),
        }
    }
}

impl PartialEq for PointSet {
    /// The same points (coordinates, boundary flags, lattice indices
    /// relative to point 0's: only their differences mean anything) in the
    /// same order, on the same cells, however they are stored.
    fn eq(&self, other: &Self) -> bool {
        let lattice = |p: &Self| {
            p.lattice().map(|l| {
                let (i0, j0) = l.get(0);
                l.iter().map(|(i, j)| (i - i0, j - j0)).collect::<Vec<_>>()
            })
        };
        self.dimension == other.dimension
            && self.cell == other.cell
            && self.len() == other.len()
            && self.boundary == other.boundary
            && self.xs() == other.xs()
            && self.ys() == other.ys()
            && lattice(self) == lattice(other)
    }
}

/// `value` if finite and positive, else an InvalidPoints error for `field`.
fn positive(field: &str, value: f64) -> Result<f64, InfluenceError> {
    if !value.is_finite() {
        Err(InfluenceError::points(field, Num(value), "must be finite"))
    } else if value <= 0.0 {
        Err(InfluenceError::points(
            field,
            Num(value),
            "must be positive",
        ))
    } else {
        Ok(value)
    }
}

/// `n` if 1 <= n <= MAX_POINTS.
fn count(field: &str, n: usize) -> Result<usize, InfluenceError> {
    if n == 0 {
        Err(InfluenceError::points(field, n, "must be at least 1"))
    } else if n > MAX_POINTS {
        Err(InfluenceError::points(
            field,
            n,
            format!("is more than {MAX_POINTS} points, the most elcon lays out in one problem"),
        ))
    } else {
        Ok(n)
    }
}

impl PointSet {
    /// `n` cells tiling the segment `[start, end]` of the x axis (a 2D, line
    /// problem): cell length `h = (end - start) / n`, points at the cell
    /// centres `(start + end)/2 + (i - (n - 1)/2) h`, i = 0..n. With
    /// `start = -end` the set is symmetric about 0 and the origin is a point
    /// exactly when `n` is odd.
    ///
    /// # Errors
    /// [`InfluenceError::InvalidPoints`] when `start` or `end` is not finite,
    /// `end <= start`, `n == 0` or `n > MAX_POINTS`.
    pub fn line(start: f64, end: f64, n: usize) -> Result<Self, InfluenceError> {
        for (field, v) in [("start", start), ("end", end)] {
            if !v.is_finite() {
                return Err(InfluenceError::points(field, Num(v), "must be finite"));
            }
        }
        if end <= start {
            return Err(InfluenceError::points(
                "end",
                Num(end),
                format!("must exceed start = {}", Num(start)),
            ));
        }
        let n = count("n", n)?;
        let h = positive("(end - start) / n", (end - start) / n as f64)?;
        let mid = 0.5 * (start + end);
        let run = Run {
            start: 0,
            first: (0, 0),
            step: (1, 0),
        };
        Ok(Self::grid(
            Dimension::Line,
            Cell { dx: h, dy: 1.0 },
            AxisRule::Centred { mid, n, h },
            AxisRule::Scaled { h: 1.0 },
            vec![run],
            n,
        ))
    }

    /// The square lattice `(i h, j h)`, i and j integers, origin on a point,
    /// clipped to the disk `i^2 + j^2 <= (radius / h)^2` (a 3D, surface
    /// problem), `h = spacing`; cells `h x h`. A relative tolerance of 1e-9
    /// on the radius keeps the boundary points of `radius = m h` despite
    /// rounding. Points are ordered by i, then j.
    ///
    /// # Errors
    /// [`InfluenceError::InvalidPoints`] when `spacing` or `radius` is not
    /// finite and positive, or the disk holds more than [`MAX_POINTS`].
    pub fn grid_disk(spacing: f64, radius: f64) -> Result<Self, InfluenceError> {
        let h = positive("spacing", spacing)?;
        let radius = positive("radius", radius)?;
        let m_f = radius / h * (1.0 + DISK_RADIUS_TOLERANCE);
        // pi m^2 points: refuse before looping over a huge square.
        if !(std::f64::consts::PI * m_f * m_f <= 2.0 * MAX_POINTS as f64) {
            return Err(InfluenceError::points(
                "radius / spacing",
                Num(radius / h),
                format!(
                    "the disk would hold about {} points, more than {MAX_POINTS}, the most elcon \
                     lays out in one problem",
                    Num((std::f64::consts::PI * m_f * m_f).round())
                ),
            ));
        }
        let r2 = m_f * m_f;
        let m = m_f.floor() as i64;
        // Row i holds the j with i^2 + j^2 <= r2: -jm..=jm (j = 0 always,
        // as i^2 <= m^2 <= r2).
        let mut runs = Vec::with_capacity(2 * m as usize + 1);
        let mut n = 0;
        for i in -m..=m {
            let jm = (0..=m)
                .take_while(|&j| ((i * i + j * j) as f64) <= r2)
                .last()
                .unwrap_or(0);
            runs.push(Run {
                start: n,
                first: (i, -jm),
                step: (0, 1),
            });
            n += 2 * jm as usize + 1;
        }
        count("number of points in the disk", n)?;
        Ok(Self::grid(
            Dimension::Surface,
            Cell::square(h),
            AxisRule::Scaled { h },
            AxisRule::Scaled { h },
            runs,
            n,
        ))
    }

    /// The `nx x ny` cell-centred grid on the rectangle
    /// `[-half_x, half_x] x [-half_y, half_y]` (a 3D, surface problem):
    /// cells `dx = 2 half_x / nx` by `dy = 2 half_y / ny` (for a roller, long
    /// in y). Points are ordered by x, then y.
    ///
    /// # Errors
    /// [`InfluenceError::InvalidPoints`] when a half-size is not finite and
    /// positive, a count is 0, or `nx ny > MAX_POINTS`.
    pub fn grid_rectangle(
        half_x: f64,
        half_y: f64,
        nx: usize,
        ny: usize,
    ) -> Result<Self, InfluenceError> {
        let half_x = positive("half_x", half_x)?;
        let half_y = positive("half_y", half_y)?;
        let nx = count("nx", nx)?;
        let ny = count("ny", ny)?;
        let n = nx.saturating_mul(ny);
        count("nx * ny", n)?;
        let dx = positive("2 half_x / nx", 2.0 * half_x / nx as f64)?;
        let dy = positive("2 half_y / ny", 2.0 * half_y / ny as f64)?;
        let runs = (0..nx)
            .map(|i| Run {
                start: i * ny,
                first: (i as i64, 0),
                step: (0, 1),
            })
            .collect();
        let centred = |n: usize, h: f64| AxisRule::Centred { mid: 0.0, n, h };
        Ok(Self::grid(
            Dimension::Surface,
            Cell { dx, dy },
            centred(nx, dx),
            centred(ny, dy),
            runs,
            n,
        ))
    }

    /// Points at arbitrary positions `(xs[k], ys[k])`, all standing for the
    /// same `cell`. For a [`Dimension::Line`] set the points lie on the x
    /// axis: `ys` is either empty or all zeros, and `cell.dy` is ignored
    /// (stored as the unit width 1).
    ///
    /// If every point lies (to a relative 1e-12) on the lattice
    /// `(xs[0] + i dx, ys[0] + j dy)`, the set records its lattice indices
    /// and the assembly uses the same translation-invariance speed-up as for
    /// the grid constructors.
    ///
    /// # Errors
    /// [`InfluenceError::EmptyPointSet`] for no point;
    /// [`InfluenceError::InvalidPoints`] for lengths that differ, a
    /// non-finite coordinate, a non-zero y on a line, a cell size that is not
    /// finite and positive, two equal points, or more than [`MAX_POINTS`].
    pub fn from_points(
        dimension: Dimension,
        xs: Vec<f64>,
        ys: Vec<f64>,
        cell: Cell,
    ) -> Result<Self, InfluenceError> {
        let ys = if dimension == Dimension::Line && ys.is_empty() {
            vec![0.0; xs.len()]
        } else {
            ys
        };
        if xs.len() != ys.len() {
            return Err(InfluenceError::points(
                "ys.len()",
                ys.len(),
                format!("must equal xs.len() = {}", xs.len()),
            ));
        }
        if xs.is_empty() {
            return Err(InfluenceError::EmptyPointSet {
                reason: "xs and ys hold no point; give at least one candidate point".into(),
            });
        }
        count("xs.len()", xs.len())?;
        let dx = positive("cell.dx", cell.dx)?;
        let dy = match dimension {
            Dimension::Line => 1.0,
            Dimension::Surface => positive("cell.dy", cell.dy)?,
        };
        for (k, (&x, &y)) in xs.iter().zip(&ys).enumerate() {
            if !x.is_finite() {
                return Err(InfluenceError::points(
                    format!("xs[{k}]"),
                    Num(x),
                    "must be finite",
                ));
            }
            if !y.is_finite() {
                return Err(InfluenceError::points(
                    format!("ys[{k}]"),
                    Num(y),
                    "must be finite",
                ));
            }
            if dimension == Dimension::Line && y != 0.0 {
                return Err(InfluenceError::points(
                    format!("ys[{k}]"),
                    Num(y),
                    "must be 0: the points of a line set lie on the x axis",
                ));
            }
        }
        let mut order: Vec<usize> = (0..xs.len()).collect();
        order.sort_by(|&a, &b| xs[a].total_cmp(&xs[b]).then(ys[a].total_cmp(&ys[b])));
        for w in order.windows(2) {
            let (a, b) = (w[0].min(w[1]), w[0].max(w[1]));
            if xs[a] == xs[b] && ys[a] == ys[b] {
                return Err(InfluenceError::points(
                    format!("(xs[{b}], ys[{b}])"),
                    format!("({}, {})", Num(xs[b]), Num(ys[b])),
                    format!("repeats point {a}: the points must be distinct"),
                ));
            }
        }
        let cell = Cell { dx, dy };
        let lattice = detect_lattice(&xs, &ys, cell);
        let boundary = match &lattice {
            Some(l) => lattice_boundary(dimension, Lattice::listed(l)),
            None => boundary_by_cells(dimension, cell, &xs, &ys),
        };
        Ok(Self {
            dimension,
            cell,
            layout: Layout::Listed { xs, ys, lattice },
            boundary,
        })
    }

    /// A grid constructor's validated set: computes the boundary flags
    /// from the lattice indices.
    fn grid(
        dimension: Dimension,
        cell: Cell,
        x: AxisRule,
        y: AxisRule,
        runs: Vec<Run>,
        len: usize,
    ) -> Self {
        let runs = GridRuns::new(runs, len);
        let boundary = lattice_boundary(dimension, runs.lattice());
        Self {
            dimension,
            cell,
            layout: Layout::Grid { x, y, runs },
            boundary,
        }
    }

    /// The number of points N (at least 1).
    pub fn len(&self) -> usize {
        match &self.layout {
            Layout::Listed { xs, .. } => xs.len(),
            Layout::Grid { runs, .. } => runs.len(),
        }
    }

    /// Always false: a point set holds at least one point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Line (2D) or surface (3D).
    pub fn dimension(&self) -> Dimension {
        self.dimension
    }

    /// The cell every point stands for.
    pub fn cell(&self) -> Cell {
        self.cell
    }

    /// x coordinate of point `k` (length). Panics if `k >= len()`.
    pub fn x(&self, k: usize) -> f64 {
        match &self.layout {
            Layout::Listed { xs, .. } => xs[k],
            Layout::Grid { x, .. } => x.at(self.lattice_at(k).0),
        }
    }

    /// y coordinate of point `k` (length; 0 on a line). Panics if `k >= len()`.
    pub fn y(&self, k: usize) -> f64 {
        match &self.layout {
            Layout::Listed { ys, .. } => ys[k],
            Layout::Grid { y, .. } => y.at(self.lattice_at(k).1),
        }
    }

    /// The points' coordinates `(x, y)` in order (y = 0 on a line): the
    /// values of [`PointSet::x`] and [`PointSet::y`], walked along a grid's
    /// runs rather than looked up point by point, and nothing allocated.
    pub fn positions(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        match &self.layout {
            Layout::Listed { xs, ys, .. } => Positions::Listed { xs, ys, next: 0 },
            Layout::Grid { x, y, runs } => Positions::Grid {
                x: *x,
                y: *y,
                lattice: runs.lattice().iter(),
            },
        }
    }

    /// `value` at every point's coordinates, in order, as a new vector:
    /// `positions().map(value).collect()`, filled by one walk of a grid's
    /// runs (a `collect` would take the points one `next` at a time).
    pub fn map_positions<T>(&self, mut value: impl FnMut((f64, f64)) -> T) -> Vec<T> {
        let mut values = Vec::with_capacity(self.len());
        self.positions().for_each(|at| values.push(value(at)));
        values
    }

    /// The coordinates of point `k`, whose lattice indices are `ij` (from
    /// the set's [`PointSet::lattice_index`]): [`PointSet::x`] and
    /// [`PointSet::y`] without looking the indices up again.
    pub(crate) fn position_at(&self, k: usize, (i, j): (i64, i64)) -> (f64, f64) {
        match &self.layout {
            Layout::Listed { xs, ys, .. } => (xs[k], ys[k]),
            Layout::Grid { x, y, .. } => (x.at(i), y.at(j)),
        }
    }

    /// All x coordinates (length): borrowed for a set built from
    /// coordinates, computed (N values) for a grid.
    pub fn xs(&self) -> Cow<'_, [f64]> {
        match &self.layout {
            Layout::Listed { xs, .. } => Cow::Borrowed(xs),
            Layout::Grid { .. } => Cow::Owned(self.map_positions(|(x, _)| x)),
        }
    }

    /// All y coordinates (length; zeros on a line): borrowed for a set
    /// built from coordinates, computed (N values) for a grid.
    pub fn ys(&self) -> Cow<'_, [f64]> {
        match &self.layout {
            Layout::Listed { ys, .. } => Cow::Borrowed(ys),
            Layout::Grid { .. } => Cow::Owned(self.map_positions(|(_, y)| y)),
        }
    }

    /// Distance of point `k` from the origin (length). Panics if `k >= len()`.
    pub fn radius(&self, k: usize) -> f64 {
        self.x(k).hypot(self.y(k))
    }

    /// The measure A_k of point `k`: area (Surface) or length per unit width
    /// (Line). The same for every point of a set. Panics if `k >= len()`.
    pub fn measure(&self, k: usize) -> f64 {
        assert!(k < self.len(), "point {k} of {}", self.len());
        self.cell.measure(self.dimension)
    }

    /// The measures A_k of all points.
    pub fn measures(&self) -> Vec<f64> {
        vec![self.cell.measure(self.dimension); self.len()]
    }

    /// The total measure `sum_k A_k` of the candidate zone.
    pub fn total_measure(&self) -> f64 {
        self.cell.measure(self.dimension) * self.len() as f64
    }

    /// The size of the smallest axis-aligned box holding every cell:
    /// `(max x - min x + dx, max y - min y + dy)` (length); for a line the
    /// second value is the unit width 1.
    pub fn extent(&self) -> (f64, f64) {
        let span = |v: &dyn Fn(usize) -> f64| {
            let (lo, hi) = (0..self.len())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| {
                    (lo.min(v(k)), hi.max(v(k)))
                });
            hi - lo
        };
        let width = span(&|k| self.x(k)) + self.cell.dx;
        match self.dimension {
            Dimension::Line => (width, 1.0),
            Dimension::Surface => (width, span(&|k| self.y(k)) + self.cell.dy),
        }
    }

    /// Integer lattice indices `(i, j)` of the points (j = 0 on a line), when
    /// the set lies on a lattice of spacing (dx, dy): then
    /// `x_k - x_l = (i_k - i_l) dx` and `y_k - y_l = (j_k - j_l) dy`, to
    /// rounding. The grid constructors always set it; [`PointSet::from_points`]
    /// sets it when it detects a lattice.
    pub fn lattice(&self) -> Option<Lattice<'_>> {
        match &self.layout {
            Layout::Listed { lattice, .. } => lattice.as_deref().map(Lattice::listed),
            Layout::Grid { runs, .. } => Some(runs.lattice()),
        }
    }

    /// The lattice indices of point `k` of a grid. Panics if `k >= len()`
    /// or the set is not a grid.
    fn lattice_at(&self, k: usize) -> (i64, i64) {
        self.lattice().expect("a grid has a lattice").get(k)
    }

    /// Whether every point has lattice indices of its own (`index` is the
    /// set's [`lattice_index`](Self::lattice_index)): a grid's runs, one a
    /// lattice row, never share one; a listed set is checked point by point.
    pub(crate) fn lattice_is_distinct(&self, index: &LatticeIndex) -> bool {
        match (&self.layout, self.lattice()) {
            (Layout::Grid { .. }, _) => true,
            (_, Some(lattice)) => lattice
                .iter()
                .enumerate()
                .all(|(k, ij)| index.get(ij) == Some(k)),
            (_, None) => false,
        }
    }

    /// The point at each lattice coordinate, or `None` for a set without a
    /// lattice: built on each call (O(N) for a listed lattice, O(rows) for
    /// a grid), for a caller that walks the lattice's neighbours.
    pub fn lattice_index(&self) -> Option<LatticeIndex> {
        self.lattice().map(LatticeIndex::of)
    }

    /// Whether point `k` lies on the edge of the candidate zone: one of the
    /// adjacent cells, centred at `(x +- dx, y)` or `(x, y +- dy)` (on a
    /// line: `x +- dx`), holds no point of the set. On a lattice this is the
    /// lattice neighbour test; otherwise a point "holds" an adjacent cell when
    /// its centre lies in that cell (closed, to a relative 1e-9).
    /// Contact that reaches such a point may be cut off by the zone.
    /// Panics if `k >= len()`.
    pub fn is_on_boundary(&self, k: usize) -> bool {
        let (x, y) = self.boundary[k];
        x || y
    }

    /// Which sides of point `k` are open (see [`PointSet::is_on_boundary`]):
    /// `(along x, along y)`, true when the adjacent cell at `x +- dx`, resp.
    /// `y +- dy`, holds no point. Lets a caller tell an edge of the
    /// candidate zone that is a body's own edge (a beam's end, a roller's
    /// end) from one that truncates the contact. Panics if `k >= len()`.
    pub fn open_sides(&self, k: usize) -> (bool, bool) {
        self.boundary[k]
    }
}

/// The iterator of [`PointSet::positions`].
enum Positions<'a> {
    Listed {
        xs: &'a [f64],
        ys: &'a [f64],
        next: usize,
    },
    Grid {
        x: AxisRule,
        y: AxisRule,
        lattice: LatticeIter<'a>,
    },
}

impl Iterator for Positions<'_> {
    type Item = (f64, f64);

    #[inline]
    fn next(&mut self) -> Option<(f64, f64)> {
        match self {
            Self::Listed { xs, ys, next } => {
                let k = *next;
                let at = (*xs.get(k)?, ys[k]);
                *next += 1;
                Some(at)
            }
            Self::Grid { x, y, lattice } => lattice.next().map(|(i, j)| (x.at(i), y.at(j))),
        }
    }

    /// Exact: a `collect` allocates its vector once.
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = match self {
            Self::Listed { xs, next, .. } => xs.len().saturating_sub(*next),
            Self::Grid { lattice, .. } => lattice.len(),
        };
        (left, Some(left))
    }

    /// The same coordinates in the same order as [`next`](Self::next), a
    /// grid's walked run by run ([`LatticeIter`]'s `fold`).
    fn fold<B, F>(self, init: B, mut f: F) -> B
    where
        F: FnMut(B, (f64, f64)) -> B,
    {
        match self {
            Self::Listed { xs, ys, next } => {
                let from = next.min(xs.len());
                xs[from..]
                    .iter()
                    .zip(&ys[from..])
                    .fold(init, |acc, (&x, &y)| f(acc, (x, y)))
            }
            Self::Grid { x, y, lattice } => {
                lattice.fold(init, |acc, (i, j)| f(acc, (x.at(i), y.at(j))))
            }
        }
    }
}

/// Lattice indices relative to the first point, if every point lies on the
/// lattice `(x0 + i dx, y0 + j dy)` to a relative 1e-12.
fn detect_lattice(xs: &[f64], ys: &[f64], cell: Cell) -> Option<Vec<(i64, i64)>> {
    let index = |v: f64, v0: f64, d: f64| -> Option<i64> {
        let f = (v - v0) / d;
        // Beyond 1e12 cells the lattice is useless (and i d loses digits).
        if !(f.abs() <= 1e12) {
            return None;
        }
        let i = f.round();
        let tolerance = 1e-12 * (d + v.abs() + v0.abs());
        ((v - (v0 + i * d)).abs() <= tolerance).then_some(i as i64)
    };
    let (x0, y0) = (xs[0], ys[0]);
    xs.iter()
        .zip(ys)
        .map(|(&x, &y)| Some((index(x, x0, cell.dx)?, index(y, y0, cell.dy)?)))
        .collect()
}

#[cfg(test)]
mod tests;
