//! Lemke's method for a symmetric `M`, in its parametric principal-pivoting
//! form on a symmetric (swept) tableau with delayed updates.
//!
//! For a P-matrix, Lemke's method with a covering vector `d` follows the
//! solution path of the parametric LCP `w = M z + q + d z0` as its
//! artificial `z0` falls (Cottle, Pang & Stone 1992, ch. 4): every basis on
//! the path is complementary for the parametric problem, and every pivot a
//! principal pivot. For a symmetric `M` this form keeps the tableau
//! symmetric, so a pivot reads one column (its row is the same numbers) and
//! needs no lexicographic bookkeeping of `B^{-1}`. The path is
//!
//! ```text
//!     w = M z + q + b α,   z >= 0, w >= 0, z^T w = 0,   α rising from the first contact
//!     stop:  c^T z = P    (the contact form: c = -κ b, α the approach, P the load)
//!       or:  α = 0        (a standard LCP: b = -1, α = -z0)
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
//! and the basic values are `x_i = σ_i (q̄_i + α b̄_i)` (`σ = -1` on `J`,
//! `z_J = x_J`, `w_K = x_K`), with `q̄`, `b̄` the swept `q` and `b`. A
//! principal pivot on `p` (into `J`, or out of it), `a = A_pp`, `c = A[:, p]`:
//!
//! ```text
//!     A'_ij = A_ij - c_i c_j / a   (i, j != p),   A'_ip = A'_pi = ±c_i / a,   A'_pp = -1 / a
//! ```
//!
//! (`+` into `J`, `-` out): a symmetric rank-1 update. As in the general
//! tableau, the updates are delayed, `A = A0 - U Λ U^T` with up to
//! [`SWEEP_BLOCK`] pivots, and applied every block as one faer product;
//! here only to the lower triangle of `A0`, `n^2 k` flops per block instead
//! of the general tableau's `2 n (n + 1) k`. A pivot writes row and column
//! `p` of that triangle exactly (the part left of the diagonal along row
//! `p`) and reads column `p` (its part above the diagonal along row `p`).
//! The indices are held in the order in which they would touch, so that the
//! pivots mostly come in increasing position: the row part of the pivot at
//! position `p` has `p` entries, about `|J|^2 / 2` over a path that
//! activates the first `|J|` positions, against `|J| (2 n - |J|) / 2` in
//! the reverse order (arithmetic, not a timing).
//! The pivot needs no lexicographic rule on `B^{-1}`, and the rows of the
//! general tableau's rule are not kept.
//!
//! The pivot rule: step `α` to the first value reaching zero (a step of
//! length 0 when one at zero is falling), or to the stop, whichever is
//! first; ties go to the first under a perturbation `q + ε g` with a fixed
//! irregular `g > 0` ([`perturbation`]), which keeps the path of the
//! perturbed problem free of degenerate cycles. A run of zero steps longer
//! than `2 n + 10` (a rule of thumb: a tie's own path can be longer, at the
//! cost of a fall back) and a step that is not finite are breakdowns. The
//! pivot is then on that value's index (in or out of `J`). The final basic
//! solution is computed from the original data on the found active set (a
//! Cholesky of `M_JJ` and iterative refinement, [`block::solve_active_set`]).
//!
//! The form applies when `M` is symmetric with a positive diagonal, `b <= 0`
//! (each index reached as `α` rises), and, with a load, `c = -κ b` (the load
//! rises with `α` for a positive definite `M`). Anything else, a breakdown
//! (a principal block that is not positive definite), or explicit options
//! (a covering vector, a refactorization interval: the retry's) go to the
//! general tableau (`lemke::solve_mixed`).
//!
//! The tableau and the start ([`Swept`], [`start`], [`finish`]) are shared
//! with the restricted-entry simplex on the symmetric tableau
//! ([`crate::swept_simplex`]), whose bases are those of this path with the
//! approach pinned by one more index.

use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::{Accum, Col, Mat, MatMut, MatRef, Par};

use crate::Method;
use crate::block;
use crate::dense::unit_of;
use crate::problem::{Bound, MixedLcpRef, Options, RawSolution, Statistics};
use crate::tolerance::Tolerances;

/// Where the parametric path stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Stop {
    /// `c^T z = load`, `c = -kappa b` (the mixed contact form).
    Load {
        /// `P = -r`.
        load: f64,
    },
    /// `α = 0` (a standard LCP, `b = -1` in the scaled problem).
    Parameter,
}

/// The stop of the parametric form when it applies to `p` with `opts`.
pub(crate) fn applies(p: &MixedLcpRef<'_>, opts: &Options) -> Option<Stop> {
    if opts.covering_vector.is_some() || opts.refactor_interval.is_some() {
        return None;
    }
    let n = p.size();
    let stop = match (p.extras(), p.equalities()) {
        (0, 0) => Stop::Parameter,
        (1, 1) => {
            if p.bounds[0] != Bound::Free || p.d[(0, 0)] != 0.0 || !(p.r[0] < 0.0) {
                return None;
            }
            let b = p.b.col(0);
            let c = p.c.row(0);
            // c = -kappa b, kappa > 0, each index reached as α rises.
            let imax = (0..n).max_by(|&i, &j| b[i].abs().total_cmp(&b[j].abs()))?;
            if !(b[imax] < 0.0) {
                return None;
            }
            let kappa = -c[imax] / b[imax];
            let proportional = (0..n).all(|i| {
                b[i] <= 0.0
                    && (c[i] + kappa * b[i]).abs()
                        <= 1e3 * f64::EPSILON * (c[i].abs() + kappa * b[i].abs())
                    && (b[i] < 0.0 || p.q[i] >= 0.0)
            });
            if !(kappa > 0.0) || !proportional {
                return None;
            }
            Stop::Load { load: -p.r[0] }
        }
        _ => return None,
    };
    let positive_diagonal = (0..n).all(|i| p.m[(i, i)] > 0.0);
    (positive_diagonal && block::asymmetry(p.m).is_none()).then_some(stop)
}

/// Pivots delayed before they are applied to the tableau. A pivot reads one
/// column through the correction (`n k` flops); 64 against 128 roughly halved
/// those reads and left the products' time unchanged at N = 1961
/// (`scaling_probe --method lemke` with temporary timers, 2026-11-23, not stored).
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
    par: Par,
}

impl Swept {
    /// The tableau of `J = {}`: `A0 = D M D` with rows and columns in the
    /// positions `order` (`order[t]` is the index at position t), its lower
    /// triangle gathered column by column on up to `par`'s threads.
    fn gather(m: MatRef<'_, f64>, order: &[usize], d: &[f64], block: usize, par: Par) -> Self {
        let n = order.len();
        // Zeroed by the allocator (fresh pages), so the upper triangle costs nothing.
        let mut a0 = vec![0.0; n * n];
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
        Self {
            a0,
            n,
            u: Mat::zeros(n, block),
            lambda: vec![0.0; block],
            k: 0,
            par,
        }
    }

    fn a(&self) -> MatRef<'_, f64> {
        MatRef::from_column_major_slice(&self.a0, self.n, self.n)
    }

    /// Column `p` of the current `A`: rows from `p` down from column `p`,
    /// the rows above from row `p`.
    pub(crate) fn column(&self, p: usize) -> Col<f64> {
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
    fn diagonal(&self, i: usize) -> f64 {
        (0..self.k).fold(self.a0[i * self.n + i], |v, l| {
            v - self.lambda[l] * self.u[(i, l)] * self.u[(i, l)]
        })
    }

    /// Applies the delayed updates to the lower triangle of `A0` (one
    /// triangular matrix product: half the flops of a full one).
    fn flush(&mut self) {
        if self.k == 0 {
            return;
        }
        let k = self.k;
        let n = self.n;
        let weighted = Mat::from_fn(n, k, |i, l| self.lambda[l] * self.u[(i, l)]);
        let (u, w) = (self.u.as_ref().subcols(0, k), weighted.as_ref());
        triangular::matmul(
            MatMut::from_column_major_slice_mut(&mut self.a0, n, n),
            BlockStructure::TriangularLower,
            Accum::Add,
            u,
            BlockStructure::Rectangular,
            w.transpose(),
            BlockStructure::Rectangular,
            -1.0,
            self.par,
        );
        self.k = 0;
    }

    /// The principal pivot on `p`, given its current column `c`; `into`
    /// says whether `p` joins `J`.
    pub(crate) fn pivot(&mut self, p: usize, c: &Col<f64>, into: bool) {
        let n = self.n;
        let a = c[p];
        if self.k == self.u.ncols() {
            self.flush();
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
    }
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
/// coefficient, which for a P-matrix leaves no degenerate cycle (Murty's
/// least-index rule, finite but exponential in the worst case, reached the
/// pivot limit of 1700 on a 40-point beam whose every point touched at
/// once: `stability_report` on 2026-11-23 before this rule, not stored).
fn perturbation(t: usize) -> f64 {
    1.0 + (t as f64 * 0.618_033_988_749_894_9).fract()
}

/// The path's state: the swept `q` and `b`, the active set, and the basic
/// values and their rates at the current `α`.
pub(crate) struct Path {
    /// The swept `q`.
    pub qbar: Vec<f64>,
    /// The swept `b`.
    pub bbar: Vec<f64>,
    /// The swept perturbation `g` (see [`perturbation`]).
    pub gbar: Vec<f64>,
    /// Whether each position is on the active set `J`.
    pub into: Vec<bool>,
    /// Each value's step to zero (scratch of the pivot rule).
    reach: Vec<f64>,
    /// The largest term `|q̄_i| + |α b̄_i|` on and off the active set, and the
    /// largest rate on and off it (forces and gaps have their own units):
    /// the scales of the zero tests.
    scales: [f64; 4],
}

impl Path {
    /// Value `i` at `α`, `x_i = σ_i (q̄_i + α b̄_i)` (`z_i` on the active
    /// set, `w_i` off it), and its rate `dx_i / dα = σ_i b̄_i`.
    fn value(&self, i: usize, alpha: f64) -> (f64, f64) {
        let sigma = if self.into[i] { -1.0 } else { 1.0 };
        let b = self.bbar[i];
        (sigma * (self.qbar[i] + alpha * b), sigma * b)
    }

    /// The order of ties: `dx_i / dε` over the value's fall with `α`
    /// (`σ_i` cancels), the ε-step at which value `i` reaches zero.
    fn tie_key(&self, i: usize) -> f64 {
        let sigma = if self.into[i] { -1.0 } else { 1.0 };
        (sigma * self.gbar[i]).max(0.0) / (-sigma * self.bbar[i])
    }

    /// Applies the principal pivot on `p` (column `p` of `A` before it is
    /// `c`; `p` joins the active set or leaves it) to `q̄`, `b̄` and `ḡ`.
    pub(crate) fn sweep(&mut self, p: usize, c: &Col<f64>, joins: bool) {
        let a = c[p];
        let (qp, bp, gp) = (self.qbar[p], self.bbar[p], self.gbar[p]);
        // Multipliers, not divisions, in the loop (which vectorizes).
        let (fq, fb, fg) = (qp / a, bp / a, gp / a);
        for (i, &ci) in c.iter().enumerate() {
            self.qbar[i] -= ci * fq;
            self.bbar[i] -= ci * fb;
            self.gbar[i] -= ci * fg;
        }
        let s = if joins { 1.0 } else { -1.0 };
        (self.qbar[p], self.bbar[p], self.gbar[p]) = (s * fq, s * fb, s * fg);
        self.into[p] = joins;
    }

    /// Recomputes the zero tests' scales at `α`. (Plain comparisons, as
    /// throughout the pivot rules' passes: they leave a NaN out as `f64::max`
    /// and `f64::min` do, without their extra instructions on the loop's
    /// critical path, which made those passes several times slower.)
    fn rescale(&mut self, alpha: f64) {
        let larger = |a: f64, v: f64| if v > a { v } else { a };
        let (mut zscale, mut wscale) = (0.0f64, 0.0f64);
        let (mut zrates, mut wrates) = (0.0f64, 0.0f64);
        for ((&q, &b), &joined) in self.qbar.iter().zip(&self.bbar).zip(&self.into) {
            let size = q.abs() + (alpha * b).abs();
            let (on, off) = if joined { (size, 0.0) } else { (0.0, size) };
            zscale = larger(zscale, on);
            wscale = larger(wscale, off);
            let (on, off) = if joined {
                (b.abs(), 0.0)
            } else {
                (0.0, b.abs())
            };
            zrates = larger(zrates, on);
            wrates = larger(wrates, off);
        }
        self.scales = [zscale, wscale, zrates, wrates];
    }
}

/// The symmetric tableau of the empty active set (`A = D M D`, in the order
/// in which the indices would touch) and the path's state there: what both
/// pivot rules on it (this module's and [`crate::swept_simplex`]) start from.
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
    /// The load's weights on the scaled `z`, `D c` in the load row's unit
    /// (empty for [`Stop::Parameter`]).
    pub weight: Vec<f64>,
    /// The load of [`Stop::Load`] in that unit (0 for [`Stop::Parameter`]).
    pub load: f64,
    /// The statistics of a solve by `method` on this tableau, before its
    /// first pivot.
    pub stats: Statistics,
}

/// The start of the path for `p`, solved by `method` (see [`Start`]).
pub(crate) fn start(p: &MixedLcpRef<'_>, opts: &Options, stop: Stop, method: Method) -> Start {
    let n = p.size();
    let mut stats = Statistics::new(method);
    stats.tableau_rows = n;
    stats.tableau_columns = n + 2;
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
    // The approach's column and the load row in units where each is of
    // order 1 (powers of two again: the approach and the load are only
    // read in these units, so data near the overflow threshold still has
    // products, slopes and loads in range).
    let unit = |v: f64| if opts.equilibrate { unit_of(v) } else { 1.0 };
    let (b_unit, c_unit) = match stop {
        Stop::Load { .. } => (unit(p.b.norm_max()), unit(p.c.norm_max())),
        Stop::Parameter => (1.0, 1.0),
    };
    let b_of = |i: usize| match stop {
        Stop::Load { .. } => scale[i] * (b_unit * p.b[(i, 0)]),
        Stop::Parameter => -1.0,
    };
    // The indices in the order in which they would touch (the pivots then
    // mostly come in increasing position, which keeps the strided parts of
    // the column reads, along rows left of the diagonal, the least in total:
    // see the module documentation).
    let touch = |i: usize| {
        let b = b_of(i);
        if b < 0.0 {
            scale[i] * p.q[i] / -b
        } else {
            f64::INFINITY
        }
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| touch(i).total_cmp(&touch(j)).then(i.cmp(&j)));
    let d: Vec<f64> = order.iter().map(|&i| scale[i]).collect();
    let tab = Swept::gather(p.m, &order, &d, SWEEP_BLOCK, opts.par(n, n));
    let diagonal: Vec<f64> = (0..n).map(|t| tab.a()[(t, t)]).collect();
    let path = Path {
        qbar: (0..n).map(|t| d[t] * p.q[order[t]]).collect(),
        bbar: order.iter().map(|&i| b_of(i)).collect(),
        gbar: (0..n).map(perturbation).collect(),
        into: vec![false; n],
        reach: vec![0.0; n],
        scales: [0.0; 4],
    };
    // Load weights on the scaled z: c^T z = (c D)^T z'.
    let (weight, load) = match stop {
        Stop::Load { load } => (
            (0..n)
                .map(|t| d[t] * (c_unit * p.c[(0, order[t])]))
                .collect(),
            c_unit * load,
        ),
        Stop::Parameter => (Vec::new(), 0.0),
    };
    Start {
        order,
        tab,
        diagonal,
        path,
        weight,
        load,
        stats,
    }
}

/// The final basic solution on the active set `into` (in positions) from
/// the original data; `Err` (the statistics) when it does not solve the
/// problem.
pub(crate) fn finish(
    p: &MixedLcpRef<'_>,
    opts: &Options,
    order: &[usize],
    into: &[bool],
    mut stats: Statistics,
) -> Result<RawSolution, Statistics> {
    let mut basic = vec![false; p.size()];
    for (t, &i) in order.iter().enumerate() {
        basic[i] = into[t];
    }
    match block::solve_active_set(p, &basic, opts, &mut stats) {
        Some((z, u)) => Ok(RawSolution {
            z,
            u,
            basic,
            statistics: Statistics {
                symmetric_tableau: true,
                ..stats
            },
        }),
        // The path's active set does not solve the problem from the data.
        None => Err(stats),
    }
}

/// Follows the parametric path; on success, the final basic solution on its
/// active set from the original data. `Err` is the attempt's statistics
/// when the path cannot finish (a ray, the pivot limit, a principal pivot
/// or a load slope that is not positive: `M` not positive definite where
/// the path went) or its active set does not solve the problem from the
/// data: the caller goes on with the general tableau, whose own errors
/// then say what is wrong.
pub(crate) fn solve(
    p: &MixedLcpRef<'_>,
    opts: &Options,
    stop: Stop,
) -> Result<RawSolution, Statistics> {
    let n = p.size();
    let tol = opts.tolerances;
    let Start {
        order,
        mut tab,
        diagonal,
        mut path,
        weight,
        load,
        mut stats,
    } = start(p, opts, stop, Method::Lemke);
    // The first contact: the least α at which some w_i = q_i + b_i α is 0.
    let mut alpha = (0..n)
        .filter(|&i| path.bbar[i] < 0.0)
        .map(|i| path.qbar[i] / -path.bbar[i])
        .fold(f64::INFINITY, f64::min);
    if stop == Stop::Parameter && alpha >= 0.0 {
        // q >= 0: z = 0 solves it.
        return Ok(RawSolution {
            z: Col::zeros(n),
            u: Col::zeros(0),
            basic: vec![false; n],
            statistics: Statistics {
                symmetric_tableau: true,
                ..stats
            },
        });
    }
    let limit = opts.pivot_limit(n, n);
    path.rescale(alpha);
    let mut zero_run = ZeroRun::new(n);
    loop {
        // Each falling value's step to zero (0 at the zero level), the
        // least of them, and the load on the contact set.
        let [zscale, wscale, zrates, wrates] = path.scales.map(|v| tol.zero * v);
        let (mut step, mut value, mut slope) = (f64::INFINITY, 0.0, 0.0);
        for i in 0..n {
            let ((xi, ri), joined) = (path.value(i, alpha), path.into[i]);
            if joined && !weight.is_empty() {
                value += weight[i] * xi;
                slope += weight[i] * ri;
            }
            let (zero, falls) = if joined {
                (zscale, -zrates)
            } else {
                (wscale, -wrates)
            };
            path.reach[i] = if ri < falls {
                let s = if xi <= zero { 0.0 } else { xi / -ri };
                step = if s < step { s } else { step };
                s
            } else {
                f64::INFINITY
            };
        }
        let to_stop = match stop {
            Stop::Load { .. } => {
                if slope > 0.0 {
                    (load - value) / slope
                } else if path.into.iter().any(|&j| j) {
                    // The load does not rise with the approach: M is not
                    // positive definite on the contact set.
                    return Err(stats);
                } else {
                    f64::INFINITY
                }
            }
            Stop::Parameter => -alpha,
        };
        if to_stop.is_nan() || (!step.is_finite() && !(to_stop < f64::INFINITY)) {
            // Nothing limits the path and it never reaches the stop (a ray),
            // or the data's scale overflowed (a NaN load).
            return Err(stats);
        }
        if to_stop <= step {
            break;
        }
        // Among the values whose steps tie the least (those at zero, when
        // it is 0), the first to reach zero under the perturbation q + ε g.
        let tied = step + tol.tie * step;
        let first = (0..n)
            .filter(|&i| path.reach[i] <= tied)
            .map(|i| (i, path.tie_key(i)))
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        // A step that is not finite (overflow, a NaN bound) is a breakdown.
        let (Some((pivot_on, _)), true) = (first, step.is_finite()) else {
            return Err(stats);
        };
        if step == 0.0 {
            // (The path starts at the first contact: its first pivot is
            // Lemke's first, not a step of length 0.)
            if stats.pivots > 0 {
                stats.degenerate_pivots += 1;
            }
        } else {
            alpha += step;
        }
        if !zero_run.record(step == 0.0) {
            return Err(stats);
        }
        if stats.pivots >= limit {
            return Err(stats);
        }
        let joins = !path.into[pivot_on];
        let c = tab.column(pivot_on);
        // (Scaled M: its diagonal, kept from the start.)
        if !definite_pivot(c[pivot_on], diagonal[pivot_on], joins, &tol) {
            return Err(stats);
        }
        tab.pivot(pivot_on, &c, joins);
        path.sweep(pivot_on, &c, joins);
        path.rescale(alpha);
        stats.pivots += 1;
    }
    finish(p, opts, &order, &path.into, stats)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The swept matrix by definition, for the set `into`.
    fn swept_explicitly(m: &Mat<f64>, into: &[bool]) -> Mat<f64> {
        let mut a = m.clone();
        let n = m.nrows();
        for p in (0..n).filter(|&p| into[p]) {
            let c = a.col(p).to_owned();
            let piv = c[p];
            for j in 0..n {
                for i in 0..n {
                    if i != p && j != p {
                        a[(i, j)] -= c[i] * c[j] / piv;
                    }
                }
            }
            for i in 0..n {
                if i != p {
                    a[(i, p)] = c[i] / piv;
                    a[(p, i)] = c[i] / piv;
                }
            }
            a[(p, p)] = -1.0 / piv;
        }
        a
    }

    #[test]
    fn delayed_sweeps_in_and_out_read_the_explicit_swept_matrix() {
        let n = 9;
        // Symmetric positive definite: every principal pivot exists.
        let g = Mat::from_fn(n, n, |i, j| ((i * 7 + j * 3) % 5) as f64 - 2.0);
        let mut m = Mat::<f64>::identity(n, n) * 4.0;
        matmul(
            m.as_mut(),
            Accum::Add,
            g.as_ref(),
            g.transpose(),
            0.3,
            Par::Seq,
        );
        // Block 2: flushes between pivots, and indices pivoted in one block
        // and read in the next.
        let order: Vec<usize> = (0..n).collect();
        let mut tab = Swept::gather(m.as_ref(), &order, &vec![1.0; n], 2, Par::Seq);
        let mut into = vec![false; n];
        for &p in &[3, 0, 7, 3, 5, 1, 0, 8, 2, 5, 3, 4] {
            let c = tab.column(p);
            let joins = !into[p];
            tab.pivot(p, &c, joins);
            into[p] = joins;
            let expect = swept_explicitly(&m, &into);
            for j in 0..n {
                let col = tab.column(j);
                for i in 0..n {
                    assert!(
                        (col[i] - expect[(i, j)]).abs() <= 1e-12 * expect.norm_max(),
                        "entry ({i}, {j}) after pivot on {p}: {} against {}",
                        col[i],
                        expect[(i, j)]
                    );
                }
                assert!((tab.diagonal(j) - expect[(j, j)]).abs() <= 1e-12 * expect.norm_max());
            }
        }
    }
}
