//! The gather order: the points grouped by lattice row as segments of
//! consecutive points on consecutive lattice columns, to spread the forces
//! on the box, `X[i_k, j_k] = x_k`, and gather the product back,
//! `(S x)_k = Y[i_k, j_k]`, a slice at a time.

use std::ops::Range;

use crate::error::InfluenceError;
use crate::error::try_vec;
use crate::points::{Lattice, LatticeBox, MAX_POINTS, PointSet};

// Point indices, lattice columns and row starts are stored as u32: a box
// holds at most `LatticeBox::cell_limit(MAX_POINTS)` cells.
const _: () = assert!(LatticeBox::cell_limit(MAX_POINTS) <= u32::MAX as usize);

/// The points grouped by lattice row, as segments of consecutive points on
/// consecutive lattice columns (a grid's row is one segment): to spread x
/// on the box row by row and gather y back, a slice at a time.
pub(super) struct GatherOrder {
    /// Segments by lattice row: row i holds
    /// `segments[row_start[i]..row_start[i + 1]]`.
    segments: Vec<Segment>,
    row_start: Vec<u32>,
    /// The points in lattice-row order: row 0's first, then row 1's, ...
    /// (a grid's order), so that the rows' points are consecutive slices.
    in_row_order: bool,
}

/// Points `point..point + len` on the lattice columns `column..column +
/// len` of one row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Segment {
    column: u32,
    point: u32,
    len: u32,
}

impl Segment {
    pub(super) fn columns(&self) -> Range<usize> {
        self.column as usize..(self.column + self.len) as usize
    }

    pub(super) fn points(&self) -> Range<usize> {
        self.point as usize..(self.point + self.len) as usize
    }
}

/// The segments of a point set on a lattice box, in the points' order,
/// each with its lattice row.
pub(super) fn segments(
    points: &PointSet,
    bounds: &LatticeBox,
) -> impl Iterator<Item = (usize, Segment)> {
    let lattice = points.lattice().expect("Setup checked the lattice");
    let mut cells = lattice.iter().map(|l| bounds.local(l)).enumerate();
    let mut current: Option<(usize, Segment)> = None;
    std::iter::from_fn(move || {
        loop {
            let Some((k, (i, j))) = cells.next() else {
                return current.take();
            };
            // Bounded by the box and MAX_POINTS (the const assertion above).
            let (k, j) = (k as u32, j as u32);
            match &mut current {
                Some((row, s)) if *row == i && s.column + s.len == j && s.point + s.len == k => {
                    s.len += 1;
                }
                _ => {
                    let next = Segment {
                        column: j,
                        point: k,
                        len: 1,
                    };
                    if let Some(done) = current.replace((i, next)) {
                        return Some(done);
                    }
                }
            }
        }
    })
}

impl GatherOrder {
    /// # Errors
    /// [`InfluenceError::LatticeRequired`] when two points fall on one
    /// lattice cell (possible for [`PointSet::from_points`] within its
    /// lattice tolerance); [`InfluenceError::AllocationFailed`].
    pub(super) fn new(points: &PointSet, bounds: &LatticeBox) -> Result<Self, InfluenceError> {
        let mut row_start = try_vec(bounds.ni + 1, 0u32, "lattice row starts")?;
        for (i, _) in segments(points, bounds) {
            row_start[i + 1] += 1;
        }
        for i in 0..bounds.ni {
            row_start[i + 1] += row_start[i];
        }
        let count = row_start[bounds.ni] as usize;
        let mut next = row_start.clone();
        let empty = Segment {
            column: 0,
            point: 0,
            len: 0,
        };
        let mut placed = try_vec(count, empty, "lattice gather order")?;
        for (i, s) in segments(points, bounds) {
            placed[next[i] as usize] = s;
            next[i] += 1;
        }
        let mut next_point = 0;
        let in_row_order = placed.iter().all(|s| {
            let ok = s.point == next_point;
            next_point = s.point + s.len;
            ok
        });
        let gather = Self {
            segments: placed,
            row_start,
            in_row_order,
        };
        let lattice = points.lattice().expect("Setup checked the lattice");
        gather.check_distinct_cells(lattice, bounds.nj)?;
        Ok(gather)
    }

    /// Bytes of an order of `segments` segments on `rows` lattice rows.
    pub(super) fn bytes_for(segments: usize, rows: usize) -> usize {
        std::mem::size_of::<Segment>() * segments + 4 * (rows + 1)
    }

    /// Two points on one cell would be summed into one value of the grid:
    /// an error naming them.
    fn check_distinct_cells(&self, lattice: Lattice<'_>, nj: usize) -> Result<(), InfluenceError> {
        // The last row that filled each column, and the point that did.
        let mut seen = try_vec(nj, (u32::MAX, 0u32), "lattice row occupancy")?;
        for i in 0..self.row_start.len() - 1 {
            for s in self.row(i) {
                for (j, k) in s.columns().zip(s.points()) {
                    let (row, a) = seen[j];
                    if row == i as u32 {
                        return Err(InfluenceError::LatticeRequired {
                            reason: format!(
                                "points {a} and {k} fall on one lattice cell (i, j) = {:?}",
                                lattice.get(k)
                            ),
                        });
                    }
                    seen[j] = (i as u32, k as u32);
                }
            }
        }
        Ok(())
    }

    /// The number of segments.
    pub(super) fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// The segments of lattice row `i`.
    pub(super) fn row(&self, i: usize) -> &[Segment] {
        &self.segments[self.row_start[i] as usize..self.row_start[i + 1] as usize]
    }

    /// `y` cut into the slices of each lattice row's points, when the
    /// points are in lattice-row order (else `None`).
    pub(super) fn row_slices<'y>(&self, y: &'y mut [f64]) -> Option<Vec<&'y mut [f64]>> {
        if !self.in_row_order {
            return None;
        }
        let mut rest = y;
        let mut slices = Vec::with_capacity(self.row_start.len() - 1);
        for i in 0..self.row_start.len() - 1 {
            let len: usize = self.row(i).iter().map(|s| s.len as usize).sum();
            let (row, tail) = std::mem::take(&mut rest).split_at_mut(len);
            slices.push(row);
            rest = tail;
        }
        Some(slices)
    }

    /// Bytes held.
    pub(super) fn bytes(&self) -> usize {
        std::mem::size_of::<Segment>() * self.segments.capacity() + 4 * self.row_start.capacity()
    }
}
