//! The symmetric (swept) tableau of principal pivots on a symmetric `M`,
//! with delayed updates, and the state of the parametric path on it.
//!
//! For a P-matrix, Lemke's method with a covering vector follows the
//! solution path of a parametric LCP (Cottle, Pang & Stone 1992, ch. 4):
//! every basis on the path is complementary for the parametric problem, and
//! every pivot a principal pivot. For a symmetric `M` this form keeps the
//! tableau symmetric, so a pivot reads one column (its row is the same
//! numbers) and needs no lexicographic bookkeeping of `B^{-1}`. The
//! parametric problems, in the mixed form's sign (`b = -B`):
//!
//! ```text
//!     w = M z + q + b λ,   z >= 0, w >= 0, z^T w = 0
//!     border:    C z = P (k rows, C = B^T),  λ free, from the first contact to the resultants
//!     standard:  λ a scalar rising to 0 from the first contact, b = -1 (λ = -z0)
//! ```
//!
//! With `J` the basic `z` and `K` the rest, the tableau is the swept matrix
//! (Goodnight 1979)
//!
//! ```text
//!     A = [ -M_JJ^{-1}          M_JJ^{-1} M_JK             ]
//!         [  M_KJ M_JJ^{-1}     M_KK - M_KJ M_JJ^{-1} M_JK ]
//! ```
//!
//! and the basic values are `x_i = σ_i (q̄_i + b̄_i λ)` (`σ = -1` on `J`,
//! `z_J = x_J`, `w_K = x_K`), with `q̄`, `b̄` the swept `q` and `b` (k
//! columns). A principal pivot on `p` (into `J`, or out of it), `a = A_pp`,
//! `c = A[:, p]`:
//!
//! ```text
//!     A'_ij = A_ij - c_i c_j / a   (i, j != p),   A'_ip = A'_pi = ±c_i / a,   A'_pp = -1 / a
//! ```
//!
//! (`+` into `J`, `-` out): a symmetric rank-1 update. As in the general
//! tableau, the updates are delayed, `A = A0 - U Λ U^T` with up to
//! `SWEEP_BLOCK` pivots, and applied every block as faer products;
//! here only to the lower triangle of `A0`, `n^2 k` flops per block instead
//! of the general tableau's `2 n (n + 1) k`. Fewer still: with `f` the
//! frontier (every position before it on `J`), the block `A_JJ` of the
//! leading `f` positions (`-M_JJ^{-1}` there) is read only when one of them
//! leaves `J`, so a block's update skips the leading `f x f` triangle,
//! `k (n^2 - f^2)` flops, and keeps its vectors' leading `f` rows; the first
//! read of a column before the frontier replays them on the triangles they
//! skipped (the same flops, later) and the frontier starts again from 0.
//! Likewise at the back: the trailing triangle of the positions from `g`
//! on, none of which has pivoted yet, is read only when one of them
//! pivots, so its updates are kept (the vectors' rows from `g`) and applied
//! when a column from `g` on is first read, to the columns up to `p + W`
//! (`W` two blocks), `g` moving there. A path that activates its first
//! `|J|` positions in order and never releases one skips `|J|^3 / 3` of the
//! `n^2 |J|` flops at the front, and `|J| (n - |J|)^2` at the back (the
//! positions that never touch). A pivot writes row and column
//! `p` of that triangle exactly (the part left of the diagonal along row
//! `p`) and reads column `p` (its part above the diagonal along row `p`).
//! The indices are held in the order in which they would touch, so that the
//! pivots mostly come in increasing position: the row part of the pivot at
//! position `p` has `p` entries, about `|J|^2 / 2` over a path that
//! activates the first `|J|` positions, against `|J| (2 n - |J|) / 2` in
//! the reverse order.
//!
//! Ties are broken under a fixed perturbation `q + ε g` ([`perturbation`]),
//! in place of the general tableau's lexicographic rule on `B^{-1}`, which
//! this form does not keep. The pivot rules that walk this tableau are
//! Lemke's (its symmetric form) and the restricted-entry
//! simplex's (its symmetric form).

use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::{Accum, Col, Mat, MatMut, MatRef, Par};

use crate::LcpError;
use crate::linalg::{try_zeros, unit_of};
use crate::options::Options;
use crate::problem::MixedRef;
use crate::statistics::Work;
use crate::tolerance::Tolerances;

/// Where the parametric path stops.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Stop {
    /// `C z = P` (a bordered problem: `C = B^T`, P the resultants in the
    /// original units).
    Border,
    /// `λ = 0` (a standard LCP, `b = -1` in the scaled problem).
    Parameter,
}

/// Pivots delayed before they are applied to the tableau. A pivot reads one
/// column through the correction (`n k` flops): 64 reads half as much as
/// 128 for the same time in the products at N = 1961 (`scaling_probe
/// --method lemke`).
const SWEEP_BLOCK: usize = 64;

/// The swept matrix `A = A0 - U Λ U^T` (see the module documentation),
/// its lower triangle stored: entry `(i, j)`, `i >= j`, at `(i, j)` of `A0`.
pub(crate) struct Swept {
    /// `A0`, column-major `n x n`, lower triangle (the upper one is zeroed
    /// by the allocator and never written: for a large matrix, fresh pages
    /// that are never touched).
    a0: Vec<f64>,
    n: usize,
    /// The delayed updates' vectors, `n x block`.
    u: Mat<f64>,
    /// Their weights `1 / a`.
    lambda: Vec<f64>,
    /// Number of delayed updates held.
    k: usize,
    /// Whether each position is on `J` (as the pivots left it).
    into: Vec<bool>,
    /// The frontier `f`: every position before it is on `J`, and the
    /// leading `f x f` triangle of `A0` may lack the updates in `stale`.
    front: usize,
    /// The applied blocks whose leading triangles were skipped, in order.
    stale: Vec<Skipped>,
    /// Entries held in `stale` (bounded: see [`STALE_SHARE`]).
    stale_len: usize,
    /// The back frontier `g`: no position from it on has pivoted since the
    /// trailing triangle from `g` was last brought up to date.
    back: usize,
    /// The applied updates that trailing triangle misses: their vectors'
    /// rows from the back frontier where the first of them was kept
    /// (column-major, `trail_rows` a column; the rows above `g` are no
    /// longer read) and their weights.
    trail: Vec<f64>,
    trail_rows: usize,
    trail_lambda: Vec<f64>,
    par: Par,
}

/// The part of one applied block of updates that its leading triangle
/// missed: the vectors' leading `rows` rows (`rows x k`, `rows` the
/// frontier at the time) and their weights.
struct Skipped {
    u: Mat<f64>,
    lambda: Vec<f64>,
}

/// The stale blocks' entries are bounded by `n^2 / STALE_SHARE`: past it
/// they are applied (so their memory stays a fraction of the tableau's);
/// the same bound holds for the trailing triangle's.
const STALE_SHARE: usize = 4;

/// The trailing triangle is brought up to date this many blocks of
/// positions past the column read (`W` in the module documentation).
const BACK_WINDOW: usize = 2;

impl Swept {
    /// The tableau of `J = {}`: `A0 = D M D` with rows and columns in the
    /// positions `order` (`order[t]` is the index at position t), its lower
    /// triangle gathered column by column on up to `par`'s threads.
    fn gather(
        m: MatRef<'_, f64>,
        order: &[usize],
        d: &[f64],
        block: usize,
        par: Par,
    ) -> Result<Self, LcpError> {
        let n = order.len();
        // Zeroed by the allocator (fresh pages), so the upper triangle costs nothing.
        let mut a0 = try_zeros(n.saturating_mul(n), "the symmetric tableau")?;
        let fill = |first: usize, columns: &mut [f64]| {
            for (t, col) in columns.chunks_mut(n.max(1)).enumerate() {
                let j = first + t;
                let src = m.col(order[j]);
                let dj = d[j];
                for (i, v) in col.iter_mut().enumerate().skip(j) {
                    *v = d[i] * src[order[i]] * dj;
                }
            }
        };
        // (`Options::par` is already sequential for small matrices.)
        let threads = par.degree().clamp(1, n.max(1));
        if threads == 1 {
            fill(0, &mut a0);
        } else {
            // Equal shares of the triangle: column boundaries n (1 - sqrt(1 - t / threads)).
            let bounds: Vec<usize> = (0..=threads)
                .map(|t| {
                    let f = 1.0 - (1.0 - t as f64 / threads as f64).sqrt();
                    ((n as f64 * f).round() as usize).min(n)
                })
                .collect();
            std::thread::scope(|scope| {
                let mut rest: &mut [f64] = &mut a0;
                for t in 0..threads {
                    let (part, tail) = rest.split_at_mut((bounds[t + 1] - bounds[t]) * n);
                    rest = tail;
                    let first = bounds[t];
                    let fill = &fill;
                    scope.spawn(move || fill(first, part));
                }
            });
        }
        Ok(Self {
            a0,
            n,
            u: Mat::zeros(n, block),
            lambda: vec![0.0; block],
            k: 0,
            into: vec![false; n],
            front: 0,
            stale: Vec::new(),
            stale_len: 0,
            back: n.min(BACK_WINDOW * block),
            trail: Vec::new(),
            trail_rows: 0,
            trail_lambda: Vec::new(),
            par,
        })
    }

    fn a(&self) -> MatRef<'_, f64> {
        MatRef::from_column_major_slice(&self.a0, self.n, self.n)
    }

    /// Column `p` of the current `A`: rows from `p` down from column `p`,
    /// the rows above from row `p`. Before the frontier, the skipped
    /// updates are applied first (every entry read from row `p` down is
    /// current otherwise).
    pub(crate) fn column(&mut self, p: usize) -> Col<f64> {
        if p < self.front {
            self.catch_up();
        }
        if p >= self.back {
            self.catch_up_back(p);
        }
        let n = self.n;
        let a = self.a();
        let below = &self.a0[p * n + p..(p + 1) * n];
        let mut c = Col::from_fn(n, |i| if i < p { a[(p, i)] } else { below[i - p] });
        if self.k > 0 {
            let weights = Col::from_fn(self.k, |l| self.lambda[l] * self.u[(p, l)]);
            matmul(
                c.as_mat_mut(),
                Accum::Add,
                self.u.as_ref().subcols(0, self.k),
                weights.as_mat(),
                -1.0,
                Par::Seq,
            );
        }
        c
    }

    /// Entry `(i, i)` of the current `A`.
    #[cfg(test)]
    fn diagonal(&mut self, i: usize) -> f64 {
        if i < self.front {
            self.catch_up();
        }
        if i >= self.back {
            self.catch_up_back(i);
        }
        (0..self.k).fold(self.a0[i * self.n + i], |v, l| {
            v - self.lambda[l] * self.u[(i, l)] * self.u[(i, l)]
        })
    }

    /// Applies the delayed updates to the lower triangle of `A0` from row
    /// `f` (the frontier, advanced over the positions now on `J`) down and
    /// left of column `g` (the back frontier): the rows below the leading
    /// triangle (one product), the triangle between the frontiers (one
    /// triangular product: half the flops of a full one) and the rows
    /// below it (one product). The leading triangle's part is kept in
    /// `stale`, the trailing triangle's in `trail`.
    fn flush(&mut self) {
        if self.k == 0 {
            return;
        }
        let (k, n) = (self.k, self.n);
        while self.front < n && self.into[self.front] {
            self.front += 1;
        }
        let f = self.front;
        if f > 0 && self.stale_len + f * k > n * n / STALE_SHARE {
            // Past the bound: the leading triangle is brought up to date,
            // this block included.
            self.catch_up();
        }
        let bound = n * n / STALE_SHARE;
        let starts = self.trail_lambda.is_empty();
        // (Reserved at once, so the kept rows never move; memory that
        // cannot be had leaves the triangle to the flushes.)
        if self.back < n
            && ((if starts {
                n - self.back
            } else {
                self.trail_rows
            }) * (self.trail_lambda.len() + k)
                > bound
                || (starts && self.trail.try_reserve(bound).is_err()))
        {
            self.catch_up_back(n - 1);
        }
        let (f, g) = (self.front, self.back);
        let weighted = Mat::from_fn(n, k, |i, l| self.lambda[l] * self.u[(i, l)]);
        let (u, w) = (self.u.as_ref().subcols(0, k), weighted.as_ref());
        let a = MatMut::from_column_major_slice_mut(&mut self.a0, n, n);
        let (_, _, left, trailing) = a.split_at_mut(f, f);
        if f > 0 {
            matmul(
                left,
                Accum::Add,
                u.subrows(f, n - f),
                w.subrows(0, f).transpose(),
                -1.0,
                self.par,
            );
            self.stale_len += f * k;
            self.stale.push(Skipped {
                u: u.subrows(0, f).to_owned(),
                lambda: self.lambda[..k].to_vec(),
            });
        }
        // (f <= g: a position before the frontier has pivoted, so it was
        // before the back frontier then, and that one only moves on.)
        let (middle, _, below, _) = trailing.split_at_mut(g - f, g - f);
        lower_update(middle, u.subrows(f, g - f), w.subrows(f, g - f), self.par);
        if g < n {
            matmul(
                below,
                Accum::Add,
                u.subrows(g, n - g),
                w.subrows(f, g - f).transpose(),
                -1.0,
                self.par,
            );
            if self.trail_lambda.is_empty() {
                self.trail_rows = n - g;
                self.trail.clear();
            }
            let first = n - self.trail_rows;
            for l in 0..k {
                // (The rows above g, no longer read, are left at zero.)
                let start = self.trail.len() + g - first;
                self.trail.resize(self.trail.len() + self.trail_rows, 0.0);
                self.trail[start..].copy_from_slice(&self.u.col_as_slice(l)[g..]);
            }
            self.trail_lambda.extend_from_slice(&self.lambda[..k]);
        }
        self.k = 0;
    }

    /// Applies the updates the trailing triangle from `g` missed to its
    /// columns up to `p + W` (or all), the back frontier moving there; the
    /// rest stays in `trail`.
    fn catch_up_back(&mut self, p: usize) {
        let (n, g) = (self.n, self.back);
        let to = n.min(p + 1 + BACK_WINDOW * self.u.ncols()).max(g);
        let (rows, cols) = (n - g, self.trail_lambda.len());
        if cols > 0 && to > g {
            let skip = g - (n - self.trail_rows);
            let v = MatRef::from_column_major_slice_with_stride(
                &self.trail[skip..],
                rows,
                cols,
                self.trail_rows,
            );
            let lambda = &self.trail_lambda;
            let w = Mat::from_fn(to - g, cols, |i, l| lambda[l] * v[(i, l)]);
            let a = MatMut::from_column_major_slice_mut(&mut self.a0, n, n);
            let (_, _, _, trailing) = a.split_at_mut(g, g);
            let (reached, _, below, _) = trailing.split_at_mut(to - g, to - g);
            lower_update(reached, v.subrows(0, to - g), w.as_ref(), self.par);
            matmul(
                below,
                Accum::Add,
                v.subrows(to - g, n - to),
                w.transpose(),
                -1.0,
                self.par,
            );
            if to == n {
                self.trail_lambda.clear();
            }
        }
        self.back = to;
    }

    /// Applies the skipped updates to the leading triangles they skipped
    /// (in any order: each is a sum of terms), and moves the frontier back
    /// to 0.
    fn catch_up(&mut self) {
        let n = self.n;
        for block in std::mem::take(&mut self.stale) {
            let f = block.u.nrows();
            let weighted =
                Mat::from_fn(f, block.u.ncols(), |i, l| block.lambda[l] * block.u[(i, l)]);
            let a = MatMut::from_column_major_slice_mut(&mut self.a0, n, n);
            lower_update(
                a.submatrix_mut(0, 0, f, f),
                block.u.as_ref(),
                weighted.as_ref(),
                self.par,
            );
        }
        self.stale_len = 0;
        self.front = 0;
    }

    /// The principal pivot on `p`, given its current column `c`; `into`
    /// says whether `p` joins `J`.
    pub(crate) fn pivot(&mut self, p: usize, c: &Col<f64>, into: bool) {
        let n = self.n;
        let a = c[p];
        if self.k == self.u.ncols() {
            self.flush();
        }
        if p < self.front {
            // Row and column p are about to be written exactly: no skipped
            // update may reach them afterwards.
            self.catch_up();
        }
        if p >= self.back {
            self.catch_up_back(p);
        }
        let k = self.k;
        // Row and column p are written exactly; their delayed entries are
        // cleared so the correction leaves them alone.
        for l in 0..k {
            self.u[(p, l)] = 0.0;
        }
        for (i, v) in self.u.col_as_slice_mut(k).iter_mut().enumerate() {
            *v = if i == p { 0.0 } else { c[i] };
        }
        self.lambda[k] = 1.0 / a;
        self.k += 1;
        let s = if into { 1.0 / a } else { -1.0 / a };
        for (i, v) in self.a0[p * n + p..(p + 1) * n].iter_mut().enumerate() {
            *v = s * c[p + i];
        }
        for j in 0..p {
            self.a0[j * n + p] = s * c[j];
        }
        self.a0[p * n + p] = -1.0 / a;
        self.into[p] = into;
    }
}

/// `A -= U W^T` on the lower triangle of the square `A` (one triangular
/// faer product).
fn lower_update(a: MatMut<'_, f64>, u: MatRef<'_, f64>, w: MatRef<'_, f64>, par: Par) {
    if a.nrows() == 0 {
        return;
    }
    triangular::matmul(
        a,
        BlockStructure::TriangularLower,
        Accum::Add,
        u,
        BlockStructure::Rectangular,
        w.transpose(),
        BlockStructure::Rectangular,
        -1.0,
        par,
    );
}

/// Steps of length 0 in a row. The perturbation orders ties, so a run
/// longer than every index joining and leaving once, `2 n + 10` (a rule of
/// thumb: a tie's own path can be longer, at the cost of a fall back), is
/// a breakdown.
pub(crate) struct ZeroRun {
    run: usize,
    cap: usize,
}

impl ZeroRun {
    /// No step yet, for `n` indices.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            run: 0,
            cap: 2 * n + 10,
        }
    }

    /// Records a step (`zero`: of length 0); `false` on a breakdown.
    pub(crate) fn record(&mut self, zero: bool) -> bool {
        self.run = if zero { self.run + 1 } else { 0 };
        self.run <= self.cap
    }
}

/// Whether `a`, the pivot of a principal pivot on an index whose scaled
/// diagonal entry is `m_pp`, is that of a positive definite `M`: into the
/// active set it is a Schur complement of a positive definite block, in
/// `(0, M_pp]`; out of it, minus a diagonal entry of its inverse, at most
/// `-1 / M_pp`. Each is judged against that bound.
pub(crate) fn definite_pivot(a: f64, m_pp: f64, joins: bool, tol: &Tolerances) -> bool {
    let bound = if joins { a / m_pp } else { -a * m_pp };
    bound > tol.pivot
}

/// The perturbation `g` of `q'` (scaled units) at position `t`, in [1, 2):
/// positive, so the first basis stays feasible under `q' + ε g`, and
/// irregular (the golden ratio's multiples), so that points a symmetry makes
/// tie (a grid, a flat punch) do not tie under it. The path is that of the
/// perturbed problem as `ε -> 0+`: ties in the step are broken by `ε`'s
/// coefficient, which for a P-matrix leaves no degenerate cycle. (Murty's
/// least-index rule is finite too, but exponential in the worst case: on a
/// 40-point beam whose every point touches at once it reaches the pivot
/// limit.)
fn perturbation(t: usize) -> f64 {
    1.0 + (t as f64 * 0.618_033_988_749_894_9).fract()
}

/// The path's state: the swept `q`, `b` (k columns) and perturbation, and
/// the active set.
pub(crate) struct Path {
    /// The swept `q`.
    pub qbar: Vec<f64>,
    /// The swept `b`, column-major `n x k` (column `l` at `l n ..`).
    pub bbar: Vec<f64>,
    /// The swept perturbation `g` (see [`perturbation`]).
    pub gbar: Vec<f64>,
    /// Whether each position is on the active set `J`.
    pub into: Vec<bool>,
    /// Number of positions `n`.
    n: usize,
}

impl Path {
    /// Number of border columns `k`.
    pub fn columns(&self) -> usize {
        self.bbar.len().checked_div(self.n).unwrap_or(0)
    }

    /// Applies the principal pivot on `p` (column `p` of `A` before it is
    /// `c`; `p` joins the active set or leaves it) to `q̄`, `b̄` and `ḡ`.
    pub(crate) fn sweep(&mut self, p: usize, c: &Col<f64>, joins: bool) {
        let a = c[p];
        let s = if joins { 1.0 } else { -1.0 };
        // Multipliers, not divisions, in the loops (which vectorize).
        for v in [&mut self.qbar, &mut self.gbar] {
            let f = v[p] / a;
            for (x, &ci) in v.iter_mut().zip(c.iter()) {
                *x -= ci * f;
            }
            v[p] = s * f;
        }
        let n = self.n;
        for column in self.bbar.chunks_exact_mut(n.max(1)) {
            let f = column[p] / a;
            for (x, &ci) in column.iter_mut().zip(c.iter()) {
                *x -= ci * f;
            }
            column[p] = s * f;
        }
        self.into[p] = joins;
    }
}

/// The symmetric tableau of the empty active set (`A = D M D`, in the order
/// in which the indices would touch) and the path's state there: what both
/// pivot rules on it start from.
pub(crate) struct Start {
    /// `order[t]` is the index at position `t`; everything else is in positions.
    pub order: Vec<usize>,
    /// The tableau.
    pub tab: Swept,
    /// The scaled `M`'s diagonal, `D_t^2 M_tt` in `[1/2, 2)` (the scale of a
    /// pivot's test).
    pub diagonal: Vec<f64>,
    /// `q̄ = D q`, `b̄ = D b` (or `-1`), the perturbation, no index active.
    pub path: Path,
    /// The border rows' weights on the scaled `z`, `D C` in each row's
    /// unit, row-major `k x n` (empty for [`Stop::Parameter`]).
    pub weight: Vec<f64>,
    /// The resultants in those units (empty for [`Stop::Parameter`]).
    pub load: Vec<f64>,
    /// Each border column's unit (`λ_l = unit_l λ'_l`, λ' the scaled unknowns).
    pub units: Vec<f64>,
    /// The work of an attempt on this tableau before its first pivot.
    pub work: Work,
}

/// The scaling of the start: each index's power of two `scale` (`D`), and
/// each border column's unit (`k` of them; one of 1 along a parameter).
fn scales(p: &MixedRef<'_>, opts: &Options, stop: &Stop, k: usize) -> (Vec<f64>, Vec<f64>) {
    let n = p.size();
    // Symmetric scaling by powers of two, D M D with a diagonal in [1/2, 2)
    // (unless `equilibrate` is off): exact, so the scaled data is the
    // original in other units.
    let scale: Vec<f64> = (0..n)
        .map(|i| {
            if opts.equilibrate {
                2f64.powi(-(p.m[(i, i)].log2() / 2.0).round() as i32)
            } else {
                1.0
            }
        })
        .collect();
    // Each border column and its row in units where each is of order 1
    // (powers of two again: λ and the resultants are only read in these
    // units, so data near the overflow threshold still has products,
    // slopes and loads in range). C = B^T: a column and its row share it.
    let units: Vec<f64> = match stop {
        Stop::Border => (0..k)
            .map(|l| {
                if opts.equilibrate {
                    unit_of(p.b.col(l).norm_max())
                } else {
                    1.0
                }
            })
            .collect(),
        Stop::Parameter => vec![1.0],
    };
    (scale, units)
}

/// The start of the path for the mixed form `p` of a bordered (or standard)
/// problem. `touch[i]` orders the indices by when they would touch (the gap
/// at the first contact of several rows); without it, by the approach at
/// which each touches, `q_i / -b_i` in the scaled units of one row (or
/// the scaled `q_i` of a standard LCP).
///
/// # Errors
/// [`LcpError::AllocationFailed`] (with the work of the start) when the
/// tableau cannot be allocated.
pub(crate) fn start(
    p: &MixedRef<'_>,
    opts: &Options,
    stop: &Stop,
    touch: Option<&[f64]>,
) -> Result<Start, Box<(LcpError, Work)>> {
    let n = p.size();
    let k = match stop {
        Stop::Border => p.extras(),
        Stop::Parameter => 1,
    };
    let work = Work {
        tableau_rows: n,
        tableau_columns: n + 1 + k,
        ..Work::default()
    };
    let (scale, units) = scales(p, opts, stop, k);
    // The indices in the order in which they would touch (the pivots then
    // mostly come in increasing position, which keeps the strided parts of
    // the column reads, along rows left of the diagonal, the least in total:
    // see the module documentation).
    let b_of = |i: usize| match stop {
        Stop::Border => scale[i] * (units[0] * p.b[(i, 0)]),
        Stop::Parameter => -1.0,
    };
    let by_approach = |i: usize| {
        let b = b_of(i);
        if b < 0.0 {
            scale[i] * p.q[i] / -b
        } else {
            f64::INFINITY
        }
    };
    let key: Vec<f64> = match touch {
        Some(t) => t.to_vec(),
        None => (0..n).map(by_approach).collect(),
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| key[i].total_cmp(&key[j]).then(i.cmp(&j)));
    let d: Vec<f64> = order.iter().map(|&i| scale[i]).collect();
    let tab = match Swept::gather(p.m, &order, &d, SWEEP_BLOCK, opts.par(n, n)) {
        Ok(tab) => tab,
        Err(e) => return Err(Box::new((e, work))),
    };
    let diagonal: Vec<f64> = (0..n).map(|t| tab.a()[(t, t)]).collect();
    let bbar = match stop {
        Stop::Border => (0..k)
            .flat_map(|l| (0..n).map(move |t| (l, t)))
            .map(|(l, t)| d[t] * (units[l] * p.b[(order[t], l)]))
            .collect(),
        Stop::Parameter => vec![-1.0; n],
    };
    let path = Path {
        qbar: (0..n).map(|t| d[t] * p.q[order[t]]).collect(),
        bbar,
        gbar: (0..n).map(perturbation).collect(),
        into: vec![false; n],
        n,
    };
    // Border weights on the scaled z: C z = (C D) z'.
    let (weight, load) = match stop {
        Stop::Border => (
            (0..k)
                .flat_map(|l| (0..n).map(move |t| (l, t)))
                .map(|(l, t)| d[t] * (units[l] * p.c[(l, order[t])]))
                .collect(),
            (0..k).map(|l| units[l] * -p.r[l]).collect(),
        ),
        Stop::Parameter => (Vec::new(), Vec::new()),
    };
    Ok(Start {
        order,
        tab,
        diagonal,
        path,
        weight,
        load,
        units,
        work,
    })
}

#[cfg(test)]
mod tests;
