//! The lattice indices `(i, j)` of a set's points, when the set lies on a
//! lattice of its cell's spacing,
//!
//! ```text
//!     x_k - x_l = (i_k - i_l) dx,     y_k - y_l = (j_k - j_l) dy
//! ```
//!
//! listed, or as a grid's runs (a few bytes a lattice row); their bounding
//! box; and the index from lattice coordinates back to the point.
//!
//! A grid's point k is found without a search: its run is the one the
//! bucket `k / 64` starts in, or one of the few after it
//! ([`GridRuns`]); the point at `(i, j)` of a grid whose runs are the
//! consecutive lattice rows is in run `i - i_0`.

use std::collections::HashMap;

/// Points `start..` (up to the next run's start) of a grid at the lattice
/// indices `first + t step`, t = 0, 1, ...
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Run {
    pub(super) start: usize,
    pub(super) first: (i64, i64),
    pub(super) step: (i64, i64),
}

impl Run {
    fn at(&self, k: usize) -> (i64, i64) {
        let t = (k - self.start) as i64;
        (
            self.first.0 + t * self.step.0,
            self.first.1 + t * self.step.1,
        )
    }

    /// The point of this run of `count` points at `(i, j)`, if any (a
    /// grid's steps: (0, 1) or (1, 0)).
    fn find(&self, (i, j): (i64, i64), count: usize) -> Option<usize> {
        let ((along, across), (first_along, first_across)) = if self.step == (0, 1) {
            ((j, i), (self.first.1, self.first.0))
        } else {
            ((i, j), self.first)
        };
        if across != first_across {
            return None;
        }
        let t = usize::try_from(along.checked_sub(first_along)?).ok()?;
        (t < count).then_some(self.start + t)
    }
}

/// log2 of the points a bucket of [`GridRuns`] spans.
const BUCKET_SHIFT: u32 = 6;

/// A grid's runs (in increasing `start`, the first at 0), its number of
/// points, and the run each bucket of `2^BUCKET_SHIFT` points starts in
/// (4 bytes per 64 points): point k's run is found from its bucket's, not
/// by a search over all the runs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct GridRuns {
    runs: Vec<Run>,
    buckets: Vec<u32>,
    len: usize,
}

impl GridRuns {
    /// The runs of a grid of `len` points; `runs[0].start` is 0 and the
    /// starts increase.
    pub(super) fn new(runs: Vec<Run>, len: usize) -> Self {
        debug_assert!(runs.first().is_some_and(|r| r.start == 0));
        let mut buckets = Vec::with_capacity(len.div_ceil(1 << BUCKET_SHIFT));
        let mut r = 0;
        for first in (0..len).step_by(1 << BUCKET_SHIFT) {
            while r + 1 < runs.len() && runs[r + 1].start <= first {
                r += 1;
            }
            buckets.push(u32::try_from(r).expect("at most MAX_POINTS runs"));
        }
        Self { runs, buckets, len }
    }

    /// The number of points.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// The lattice indices, by the runs.
    pub(super) fn lattice(&self) -> Lattice<'_> {
        Lattice(LatticeRef::Runs {
            runs: &self.runs,
            buckets: &self.buckets,
            len: self.len,
        })
    }
}

/// The run of `runs` that holds point `k < len`: the last that starts at
/// or before k, looked for from the run k's bucket starts in up to the
/// next bucket's (usually that one run).
fn run_of(runs: &[Run], buckets: &[u32], k: usize) -> usize {
    let b = k >> BUCKET_SHIFT;
    let lo = buckets[b] as usize;
    let hi = buckets.get(b + 1).map_or(runs.len(), |&r| r as usize + 1);
    lo + runs[lo + 1..hi].partition_point(|r| r.start <= k)
}

/// The lattice indices `(i, j)` of a set's points
/// ([`PointSet::lattice`](super::PointSet::lattice)):
/// listed, or computed from a grid's runs.
#[derive(Debug, Clone, Copy)]
pub struct Lattice<'a>(LatticeRef<'a>);

#[derive(Debug, Clone, Copy)]
enum LatticeRef<'a> {
    Listed(&'a [(i64, i64)]),
    Runs {
        runs: &'a [Run],
        buckets: &'a [u32],
        len: usize,
    },
}

impl<'a> Lattice<'a> {
    /// The lattice indices as listed, point k at `indices[k]`.
    pub(super) fn listed(indices: &'a [(i64, i64)]) -> Self {
        Self(LatticeRef::Listed(indices))
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        match self.0 {
            LatticeRef::Listed(l) => l.len(),
            LatticeRef::Runs { len, .. } => len,
        }
    }

    /// Always false: a point set holds at least one point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The lattice indices of point `k`. Panics if `k >= len()`.
    pub fn get(&self, k: usize) -> (i64, i64) {
        match self.0 {
            LatticeRef::Listed(l) => l[k],
            LatticeRef::Runs { runs, buckets, len } => {
                assert!(k < len, "point {k} of {len}");
                runs[run_of(runs, buckets, k)].at(k)
            }
        }
    }

    /// The lattice indices of the points, in order, as a vector.
    pub fn to_vec(&self) -> Vec<(i64, i64)> {
        self.iter().collect()
    }

    /// The lattice indices of the points, in order.
    pub fn iter(&self) -> LatticeIter<'a> {
        LatticeIter {
            lattice: *self,
            next: 0,
            run: 0,
        }
    }
}

impl<'a> IntoIterator for Lattice<'a> {
    type Item = (i64, i64);
    type IntoIter = LatticeIter<'a>;

    fn into_iter(self) -> LatticeIter<'a> {
        self.iter()
    }
}

/// The iterator of [`Lattice::iter`].
#[derive(Debug, Clone)]
pub struct LatticeIter<'a> {
    lattice: Lattice<'a>,
    next: usize,
    run: usize,
}

impl Iterator for LatticeIter<'_> {
    type Item = (i64, i64);

    fn next(&mut self) -> Option<(i64, i64)> {
        let k = self.next;
        if k >= self.lattice.len() {
            return None;
        }
        self.next += 1;
        Some(match self.lattice.0 {
            LatticeRef::Listed(l) => l[k],
            LatticeRef::Runs { runs, .. } => {
                while self.run + 1 < runs.len() && runs[self.run + 1].start <= k {
                    self.run += 1;
                }
                runs[self.run].at(k)
            }
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.lattice.len() - self.next;
        (left, Some(left))
    }

    /// The same indices in the same order as [`next`](Self::next), a grid's
    /// run by run: no search for the run at every point, and an inner loop
    /// the caller's `f` can be compiled into (`sum`, `for_each`, and
    /// `enumerate` and `map` before them, come here; a `collect` into a
    /// vector takes `next`: the iterator is not `TrustedLen`).
    fn fold<B, F>(self, init: B, mut f: F) -> B
    where
        F: FnMut(B, (i64, i64)) -> B,
    {
        let len = self.lattice.len();
        match self.lattice.0 {
            LatticeRef::Listed(l) => l[self.next.min(len)..].iter().copied().fold(init, f),
            LatticeRef::Runs { runs, .. } => {
                let mut acc = init;
                let mut k = self.next;
                for (r, run) in runs.iter().enumerate().skip(self.run) {
                    let end = runs.get(r + 1).map_or(len, |next| next.start);
                    while k < end {
                        acc = f(acc, run.at(k));
                        k += 1;
                    }
                }
                acc
            }
        }
    }
}

impl ExactSizeIterator for LatticeIter<'_> {}

/// A table may hold at most this many entries per point before the direct
/// path is cheaper (a sparse set on a fine lattice).
const TABLE_ENTRIES_PER_POINT: usize = 4;

/// The bounding box of a set's lattice indices: `ni x nj` lattice cells
/// from `(i_min, j_min)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LatticeBox {
    pub(crate) i_min: i64,
    pub(crate) j_min: i64,
    pub(crate) ni: usize,
    pub(crate) nj: usize,
}

impl LatticeBox {
    /// The box of lattice indices (`None` for none, or a side that does
    /// not fit a usize).
    pub(crate) fn of_lattice(lattice: Lattice<'_>) -> Option<Self> {
        let (mut i_min, mut i_max, mut j_min, mut j_max) = (i64::MAX, i64::MIN, i64::MAX, i64::MIN);
        for (i, j) in lattice.iter() {
            i_min = i_min.min(i);
            i_max = i_max.max(i);
            j_min = j_min.min(j);
            j_max = j_max.max(j);
        }
        let side = |lo: i64, hi: i64| usize::try_from(i128::from(hi) - i128::from(lo) + 1).ok();
        Some(Self {
            i_min,
            j_min,
            ni: side(i_min, i_max)?,
            nj: side(j_min, j_max)?,
        })
    }

    /// The number of lattice cells in the box, `ni nj` (saturating).
    pub(crate) fn cells(&self) -> usize {
        self.ni.saturating_mul(self.nj)
    }

    /// The most cells a box may hold for `n` points before a table (or a
    /// padded grid) over it costs more than the points themselves:
    /// [`TABLE_ENTRIES_PER_POINT`] per point, plus 64 for tiny sets.
    pub(crate) const fn cell_limit(n: usize) -> usize {
        TABLE_ENTRIES_PER_POINT * n + 64
    }

    /// Whether the box is small enough for `n` points ([`Self::cell_limit`]).
    pub(crate) fn is_dense(&self, n: usize) -> bool {
        self.cells() <= Self::cell_limit(n)
    }

    /// The lattice indices of a point shifted into the box, `0 <= i < ni`,
    /// `0 <= j < nj`.
    pub(crate) fn local(&self, (i, j): (i64, i64)) -> (usize, usize) {
        ((i - self.i_min) as usize, (j - self.j_min) as usize)
    }
}

/// The point at each lattice coordinate of a set
/// ([`PointSet::lattice_index`](super::PointSet::lattice_index)):
/// for a grid its runs (O(rows) memory; the run of lattice row i is
/// `i - i_0` when the runs are the consecutive rows, as the grid
/// constructors' are, else found by a binary search over the rows); else a table over the lattice's bounding box (4 bytes a
/// cell) when the box is at most `TABLE_ENTRIES_PER_POINT` cells a point,
/// else a hash map.
#[derive(Debug, Clone)]
pub struct LatticeIndex(Index);

#[derive(Debug, Clone)]
enum Index {
    /// `cells[i * nj + j]` at the box's local `(i, j)`; `u32::MAX` where no
    /// point is.
    Table {
        bounds: LatticeBox,
        cells: Vec<u32>,
    },
    Map(HashMap<(i64, i64), usize>),
    /// A grid's runs (see the point set's `Layout::Grid`), its
    /// number of points, and `i_0` when run r is lattice row `i_0 + r`
    /// (along j).
    Runs {
        runs: Vec<Run>,
        len: usize,
        first_row: Option<i64>,
    },
}

/// `i_0` when run r of `runs` is the lattice row `i_0 + r`, along j.
fn consecutive_rows(runs: &[Run]) -> Option<i64> {
    let i0 = runs.first()?.first.0;
    runs.iter()
        .zip(0..)
        .all(|(run, r)| run.step == (0, 1) && i0.checked_add(r) == Some(run.first.0))
        .then_some(i0)
}

impl LatticeIndex {
    /// The index of lattice coordinates (point k at `lattice[k]`).
    pub(super) fn of(lattice: Lattice<'_>) -> Self {
        if let LatticeRef::Runs { runs, len, .. } = lattice.0 {
            return Self(Index::Runs {
                runs: runs.to_vec(),
                len,
                first_row: consecutive_rows(runs),
            });
        }
        let table = LatticeBox::of_lattice(lattice)
            .filter(|b| b.is_dense(lattice.len()) && lattice.len() < u32::MAX as usize);
        Self(match table {
            Some(bounds) => {
                let mut cells = vec![u32::MAX; bounds.cells()];
                for (k, l) in lattice.iter().enumerate() {
                    let (i, j) = bounds.local(l);
                    cells[i * bounds.nj + j] = k as u32;
                }
                Index::Table { bounds, cells }
            }
            None => Index::Map(lattice.iter().enumerate().map(|(k, ij)| (ij, k)).collect()),
        })
    }

    /// The point at lattice coordinates `(i, j)`, if any.
    pub fn get(&self, (i, j): (i64, i64)) -> Option<usize> {
        match &self.0 {
            Index::Table { bounds, cells } => {
                let r = usize::try_from(i.checked_sub(bounds.i_min)?).ok()?;
                let c = usize::try_from(j.checked_sub(bounds.j_min)?).ok()?;
                if r >= bounds.ni || c >= bounds.nj {
                    return None;
                }
                let k = cells[r * bounds.nj + c];
                (k != u32::MAX).then_some(k as usize)
            }
            Index::Map(map) => map.get(&(i, j)).copied(),
            Index::Runs {
                runs,
                len,
                first_row,
            } => {
                let r = match first_row {
                    Some(i0) => usize::try_from(i.checked_sub(*i0)?).ok()?,
                    None if runs.len() == 1 => 0,
                    None => runs.partition_point(|run| run.first.0 < i),
                };
                let run = runs.get(r)?;
                let end = runs.get(r + 1).map_or(*len, |next| next.start);
                run.find((i, j), end - run.start)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::scattered;
    use crate::points::{Dimension, PointSet};

    #[test]
    fn the_lattice_index_is_runs_on_grids_a_table_on_lattices_and_a_map_on_sparse_sets() {
        let disk = PointSet::grid_disk(1.0, 6.0).unwrap();
        let index = disk.lattice_index().unwrap();
        assert!(matches!(index.0, Index::Runs { .. }));
        let listed = PointSet::from_points(
            Dimension::Surface,
            disk.xs().to_vec(),
            disk.ys().to_vec(),
            disk.cell(),
        )
        .unwrap();
        let table = listed.lattice_index().unwrap();
        assert!(matches!(table.0, Index::Table { .. }));
        let line = PointSet::line(-1.0, 1.0, 5).unwrap();
        let along = line.lattice_index().unwrap();
        assert_eq!(
            (0..7).map(|i| along.get((i - 1, 0))).collect::<Vec<_>>(),
            [None, Some(0), Some(1), Some(2), Some(3), Some(4), None]
        );
        assert_eq!(along.get((2, 1)), None);
        let sparse = [(0, 0), (1000, -1000), (3, 2)];
        let map = LatticeIndex::of(Lattice(LatticeRef::Listed(&sparse)));
        assert!(matches!(map.0, Index::Map(_)));
        // Listed indices count from point 0, the disk's (-6, 0).
        let shifted = |l: (i64, i64)| (l.0 - 6, l.1);
        for (k, ij) in listed.lattice().unwrap().iter().enumerate() {
            assert_eq!(index.get(shifted(ij)), Some(k));
        }
        for (index, lattice) in [
            (&index, disk.lattice().unwrap()),
            (&map, Lattice(LatticeRef::Listed(&sparse))),
        ] {
            for (k, ij) in lattice.iter().enumerate() {
                assert_eq!(index.get(ij), Some(k));
            }
            for absent in [
                (7, 0),
                (-7, 0),
                (6, 6),
                (i64::MIN, 0),
                (0, i64::MAX),
                (1, 1000),
            ] {
                assert_eq!(index.get(absent), None, "{absent:?}");
            }
        }
        // A set without a lattice has no index.
        let scattered = scattered();
        assert!(scattered.lattice_index().is_none());
    }

    /// Runs of the given lengths along j, at rows `rows[r]`, each from j =
    /// -r (a ragged grid).
    fn ragged(rows: &[i64], lengths: &[usize]) -> GridRuns {
        let mut start = 0;
        let runs = rows
            .iter()
            .zip(lengths)
            .enumerate()
            .map(|(r, (&i, &n))| {
                let run = Run {
                    start,
                    first: (i, -(r as i64)),
                    step: (0, 1),
                };
                start += n;
                run
            })
            .collect();
        GridRuns::new(runs, start)
    }

    #[test]
    fn grid_points_and_lattice_rows_are_found_by_arithmetic_as_by_a_search() {
        let disk = PointSet::grid_disk(0.01, 0.73).unwrap();
        let column = PointSet::grid_rectangle(2.0, 0.5, 200, 1).unwrap();
        let line = PointSet::line(-1.0, 1.0, 300).unwrap();
        // Runs of 1 to 150 points, many in one bucket, some spanning several.
        let lengths: Vec<usize> = (0..120).map(|r| 1 + (r * r * 7) % 150).collect();
        let rows: Vec<i64> = (0..120).map(|r| r - 60).collect();
        let consecutive = ragged(&rows, &lengths);
        // The same rows with gaps between them: the index searches.
        let gapped_rows: Vec<i64> = (0..120).map(|r| 3 * r + r % 2).collect();
        let gapped = ragged(&gapped_rows, &lengths);
        let lattices = [
            disk.lattice().unwrap(),
            column.lattice().unwrap(),
            line.lattice().unwrap(),
            consecutive.lattice(),
            gapped.lattice(),
        ];
        for (lattice, first_row) in lattices.into_iter().zip([true, true, false, true, false]) {
            let LatticeRef::Runs { runs, len, .. } = lattice.0 else {
                panic!("a grid's lattice is its runs");
            };
            // Point k by a linear scan of the runs: the run starting last at or before k.
            for k in 0..len {
                let r = runs.iter().rposition(|run| run.start <= k).unwrap();
                assert_eq!(lattice.get(k), runs[r].at(k), "point {k}");
            }
            assert_eq!(lattice.iter().collect::<Vec<_>>(), lattice.to_vec());
            let index = LatticeIndex::of(lattice);
            let Index::Runs { first_row: i0, .. } = &index.0 else {
                panic!("a grid's index is its runs");
            };
            assert_eq!(i0.is_some(), first_row);
            for (k, (i, j)) in lattice.iter().enumerate() {
                assert_eq!(index.get((i, j)), Some(k));
                for absent in [(i, j + 1000), (i + 1000, j), (i64::MIN, j), (i64::MAX, j)] {
                    assert_eq!(index.get(absent), None, "{absent:?}");
                }
            }
        }
        // Between the gapped rows, nothing.
        let index = LatticeIndex::of(gapped.lattice());
        assert_eq!(index.get((gapped_rows[3] + 1, 0)), None);
    }
}
