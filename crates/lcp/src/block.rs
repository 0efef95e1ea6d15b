//! Block principal pivoting for LCPs with a symmetric positive definite `M`
//! (Júdice & Pires 1994; Kostreva 1978), extended to the mixed form with
//! free unknowns and as many equality rows.
//!
//! Guess the set `J` of basic `z` (the contact set); solve the equilibrium on
//! it with a faer Cholesky of `M_JJ`:
//!
//! ```text
//!     M_JJ z_J + B_J u = -q_J              (w_J = 0)
//!     C_J z_J + D u    = -r                (the equality rows)
//!     =>  (D - C_J M_JJ^{-1} B_J) u = C_J M_JJ^{-1} q_J - r,   z_J = -M_JJ^{-1} (q_J + B_J u)
//! ```
//!
//! then `w = M z + B u + q`. Every infeasible index (`z_i < 0` in `J`,
//! `w_i < 0` outside) moves to the other side at once. Safeguard (finite
//! termination): the number of infeasibilities must fall at least once every
//! `1 + BLOCK_RETRIES` iterations; otherwise single principal pivots on the
//! infeasible index of least number (Murty 1974), which terminate for a
//! P-matrix; past an iteration cap, or when a block system is singular, the
//! solve falls back to Lemke's method, which terminates on every problem of
//! this class.
//!
//! The first guess, without a warm start, comes from a prefix search: the
//! indices in the order in which they would activate, grown by a fixed
//! ratio until the block solution turns negative somewhere, so that the
//! factorization work is about that of the final contact set rather than of
//! the whole of `M` (see `prefix_search`).

use faer::linalg::matmul::matmul;
use faer::{Accum, Col, Mat};

use faer::dyn_stack::{MemBuffer, MemStack};

use crate::dense::{Lu, norm_inf, unit_of};
use crate::lemke;
use crate::problem::{Bound, MixedLcpRef, Options, RawSolution, Statistics};
use crate::tolerance::Tolerances;
use crate::{LcpError, Method};

/// Full block exchanges allowed without a fall in the infeasibility count.
const BLOCK_RETRIES: usize = 3;

/// Why a block iteration could not be solved.
enum BlockFailure {
    /// `M_JJ` is not positive definite.
    NotPositiveDefinite,
    /// The equality rows' Schur complement is singular for this `J`.
    Singular,
}

pub(crate) fn solve_mixed(p: &MixedLcpRef<'_>, opts: &Options) -> Result<RawSolution, LcpError> {
    let n = p.size();
    let k = p.extras();
    if k != p.equalities() || p.bounds.iter().any(|b| *b != Bound::Free) {
        return Err(LcpError::Unsupported {
            method: "block principal pivoting",
            reason: "it needs free extra unknowns and as many equality rows; use the restricted-entry simplex".into(),
        });
    }
    if let Some((i, j)) = asymmetry(p.m) {
        return Err(LcpError::Unsupported {
            method: "block principal pivoting",
            reason: format!("M is not symmetric (entry ({i}, {j})); use Lemke's method"),
        });
    }
    let mut stats = Statistics::new(Method::BlockPivoting);
    let par = opts.par(n, n);
    let tol = opts.tolerances;
    let cap = opts.max_pivots.unwrap_or(3 * n + 50);
    let mut best = usize::MAX;
    let mut retries = BLOCK_RETRIES;
    let key = keys(p);
    let mut factor = Factor::new(n);
    let mut active = match warm_start(p, opts) {
        Some(a) => a,
        None => prefix_search(p, &key, &mut factor, &tol, par, &mut stats),
    };
    loop {
        stats.iterations += 1;
        // Iterations only need the signs of z and w; the solution is refined
        // once the active set is found (below).
        let solved = factor
            .update(p, &active, &key, par, &mut stats)
            .and_then(|()| BlockSystem::new(p, &factor, par));
        let system = match solved {
            Ok(v) => v,
            // A principal block that is not positive definite (a beam's
            // clamped point has a zero row) or a singular Schur complement:
            // Lemke's method solves what block pivoting cannot.
            Err(BlockFailure::NotPositiveDefinite | BlockFailure::Singular) => {
                return fallback(p, opts, stats);
            }
        };
        let (mut z, mut u) = system.solution(p);
        let mut infeasible = violations(p, &active, &z, &u, &tol, par);
        if infeasible.is_empty() {
            // The active set is found: refine its solution from the original
            // data; if that moves a sign, the safeguarded exchange goes on.
            system.refine(p, &mut z, &mut u, opts.refinement_steps, &mut stats);
            infeasible = violations(p, &active, &z, &u, &tol, par);
            if infeasible.is_empty() {
                return Ok(RawSolution {
                    z,
                    u,
                    basic: active,
                    statistics: stats,
                });
            }
        }
        if stats.iterations >= cap {
            return fallback(p, opts, stats);
        }
        if infeasible.len() < best {
            best = infeasible.len();
            retries = BLOCK_RETRIES;
        } else if retries > 0 {
            retries -= 1;
        } else {
            // Murty's least-index single principal pivot.
            let i = infeasible[0];
            active[i] = !active[i];
            stats.pivots += 1;
            continue;
        }
        for &i in &infeasible {
            active[i] = !active[i];
        }
        stats.pivots += infeasible.len();
    }
}

/// The order in which indices join the factor: by the threshold `q_i /
/// |B_i|` (for one extra unknown: the approach at which point i touches),
/// else by `q_i`.
fn keys(p: &MixedLcpRef<'_>) -> Vec<f64> {
    (0..p.size())
        .map(|i| {
            let b = (0..p.extras()).fold(0.0f64, |a, j| a.max(p.b[(i, j)].abs()));
            if b > 0.0 { p.q[i] / b } else { p.q[i] }
        })
        .collect()
}

/// The solution on a given active set, from the original data: one
/// Cholesky of `M_JJ`, the block system, iterative refinement. `None` when
/// `M_JJ` is not positive definite, the equality rows' Schur complement is
/// singular, or a sign is wrong (the set does not solve the problem). The
/// final basic solution of a method that found the set by other means.
pub(crate) fn solve_active_set(
    p: &MixedLcpRef<'_>,
    active: &[bool],
    opts: &Options,
    stats: &mut Statistics,
) -> Option<(Col<f64>, Col<f64>)> {
    // The extra unknowns' columns and the equality rows in units where each
    // is of order 1 (powers of two, exact; `B u` and `C z` unchanged with
    // u in units of 1 / b_unit): with b and c near 1e154 the Schur
    // complement C M^{-1} B would overflow in the data's own units.
    let (b_unit, c_unit) = if opts.equilibrate {
        (unit_of(p.b.norm_max()), unit_of(p.c.norm_max()))
    } else {
        (1.0, 1.0)
    };
    let (b, c, d, r) = (
        p.b * b_unit,
        p.c * c_unit,
        p.d * (b_unit * c_unit),
        p.r * c_unit,
    );
    let scaled = MixedLcpRef {
        b: b.as_ref(),
        c: c.as_ref(),
        d: d.as_ref(),
        r: r.as_ref(),
        ..*p
    };
    let p = &scaled;
    let par = opts.par(p.size(), p.size());
    let factor = Factor::of(p, active, par, stats).ok()?;
    let system = BlockSystem::new(p, &factor, par).ok()?;
    let (mut z, mut u) = system.solution(p);
    system.refine(p, &mut z, &mut u, opts.refinement_steps, stats);
    violations(p, active, &z, &u, &opts.tolerances, par)
        .is_empty()
        .then(|| (z, u * b_unit))
}

/// An entry `(i, j)` where `M` is not symmetric (to `1e3 u` of its largest
/// diagonal entry), compared tile by tile so that the transposed reads stay
/// in cache.
pub(crate) fn asymmetry(m: faer::MatRef<'_, f64>) -> Option<(usize, usize)> {
    const TILE: usize = 64;
    let n = m.nrows();
    let scale = (0..n).fold(0.0f64, |a, i| a.max(m[(i, i)].abs()));
    let tolerance = 1e3 * f64::EPSILON * scale;
    for j0 in (0..n).step_by(TILE) {
        for i0 in (0..=j0).step_by(TILE) {
            for j in j0..(j0 + TILE).min(n) {
                for i in i0..(i0 + TILE).min(j) {
                    if (m[(i, j)] - m[(j, i)]).abs() > tolerance {
                        return Some((i, j));
                    }
                }
            }
        }
    }
    None
}

/// The warm start, if one was given and fits (with equality rows it must
/// activate at least one index, or the block system is singular).
fn warm_start(p: &MixedLcpRef<'_>, opts: &Options) -> Option<Vec<bool>> {
    let a = opts.warm_start.as_ref()?;
    (a.len() == p.size() && (p.extras() == 0 || a.iter().any(|&x| x))).then(|| a.clone())
}

/// Growth of the prefix per step of [`prefix_search`] (its size times this,
/// plus [`PREFIX_STEP`]).
const PREFIX_GROWTH: f64 = 1.15;
/// The first prefix's size, and the fixed part of each step.
const PREFIX_STEP: usize = 32;
/// Steps in a row a prefix search grows past a singular Schur complement.
const SINGULAR_STEPS: usize = 3;

/// The initial active set without a warm start: the shortest prefix of the
/// indices in `key` order whose block solution has a negative `z`.
///
/// In a contact problem `key` is the approach at which each point touches,
/// and a prefix is the set of points of least separation. A prefix smaller
/// than the contact set pushes everywhere (`z > 0`) but leaves points outside
/// it interpenetrating, and the whole-set exchange of the first iterations
/// would jump from it to nearly every index: one factorization of the
/// whole of `M`. Growing the prefix by a fixed ratio instead, each step
/// factoring only the indices that join (the factor keeps the prefix), stops
/// at the first prefix whose solution turns negative: on a contact problem
/// at most about [`PREFIX_GROWTH`] times the contact set plus
/// [`PREFIX_STEP`], which the block iterations then shrink (a shrinking
/// prefix keeps its factor), so the factorization work is about that of the
/// contact set, not of `M`. It is a heuristic first guess: the iterations
/// correct any guess.
///
/// Without equality rows the prefix is capped at the indices with `q_i < 0`
/// (where `w` is negative at `z = 0`: the old initial guess); with them, the
/// first prefix holds at least the indices whose key ties the smallest (a
/// flat contact touches everywhere at once) to the zero tolerance of the
/// keys' scale, since equal separations computed from a geometry differ in
/// their last bits.
fn prefix_search(
    p: &MixedLcpRef<'_>,
    key: &[f64],
    factor: &mut Factor,
    tol: &Tolerances,
    par: faer::Par,
    stats: &mut Statistics,
) -> Vec<bool> {
    let n = p.size();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| key[a].total_cmp(&key[b]).then(a.cmp(&b)));
    let (first, cap) = if p.extras() == 0 {
        let negative = (0..n).filter(|&i| p.q[i] < 0.0).count();
        (negative.min(PREFIX_STEP), negative)
    } else {
        let kmin = key.iter().copied().fold(f64::INFINITY, f64::min);
        let kscale = key.iter().fold(0.0f64, |a, k| a.max(k.abs()));
        let ties = key
            .iter()
            .filter(|&&k| k <= kmin + tol.zero * kscale)
            .count();
        (ties.max(PREFIX_STEP.min(n)), n)
    };
    let mut active = vec![false; n];
    let mut size = 0;
    let mut next = first;
    let mut singular = 0;
    while next > size {
        for &i in &order[size..next] {
            active[i] = true;
        }
        size = next;
        if size == cap {
            break;
        }
        let grown = cap.min((size as f64 * PREFIX_GROWTH) as usize + PREFIX_STEP);
        let solved = factor
            .update(p, &active, key, par, stats)
            .and_then(|()| BlockSystem::new(p, factor, par));
        match solved {
            Ok(system) => {
                singular = 0;
                let (z, _) = system.solution(p);
                let zscale = norm_inf(z.as_ref());
                if z.iter().any(|&v| v < -tol.zero * zscale) {
                    break;
                }
            }
            // A singular Schur complement of the equality rows (a prefix
            // that does not yet reach every extra unknown): a larger prefix
            // may cure it, a few steps in a row at most (badly posed extra
            // unknowns would otherwise grow it to all of M for nothing).
            Err(BlockFailure::Singular) => {
                singular += 1;
                if singular > SINGULAR_STEPS {
                    break;
                }
            }
            // Not positive definite: the block iterations fall back.
            Err(BlockFailure::NotPositiveDefinite) => break,
        }
        next = grown;
    }
    active
}

/// The Cholesky factor of the lower triangle of `a`, in place (the upper
/// triangle is left as it was).
fn cholesky_lower(a: faer::MatMut<'_, f64>, par: faer::Par) -> Result<(), BlockFailure> {
    use faer::linalg::cholesky::llt::factor::{
        LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
    };
    let mut mem = MemBuffer::new(cholesky_in_place_scratch::<f64>(
        a.nrows(),
        par,
        Default::default(),
    ));
    cholesky_in_place(
        a,
        LltRegularization {
            dynamic_regularization_delta: 0.0,
            dynamic_regularization_epsilon: 0.0,
        },
        par,
        MemStack::new(&mut mem),
        Default::default(),
    )
    .map(|_| ())
    .map_err(|_| BlockFailure::NotPositiveDefinite)
}

/// The Cholesky factor `L L^T = M_JJ` of the active block, its rows in the
/// order `order`, kept between iterations.
///
/// Active indices are ordered by a key (the threshold `q_i / |B_i|` at which
/// index i would activate, ascending), and a new active set keeps the
/// longest prefix of the old order that stays active; only the rest R is
/// factored, against the kept prefix P:
///
/// ```text
///     L_RP = M_RP L_PP^{-T}                   a triangular solve
///     L_RR L_RR^T = M_RR - L_RP L_RP^T        a Cholesky of order |R|
/// ```
///
/// In a contact problem the points that leave the contact set are those
/// with the largest separations, last in that order, so a shrinking contact
/// set keeps almost all of its factor.
struct Factor {
    order: Vec<usize>,
    /// The factor in its leading `order.len()` rows and columns; the matrix
    /// may be larger, and its capacity larger still, so a shrinking or
    /// growing active set reuses it in place.
    l: Mat<f64>,
    /// The rows and columns reserved for `l`.
    capacity: usize,
    /// The largest order the factor can reach.
    n: usize,
}

impl Factor {
    /// An empty factor for at most `n` indices.
    fn new(n: usize) -> Self {
        Self {
            order: Vec::new(),
            l: Mat::zeros(0, 0),
            capacity: 0,
            n,
        }
    }

    /// The factor of the block `active`, in one factorization (indices in
    /// ascending order, gathered straight into the factor's storage).
    fn of(
        p: &MixedLcpRef<'_>,
        active: &[bool],
        par: faer::Par,
        stats: &mut Statistics,
    ) -> Result<Self, BlockFailure> {
        let order: Vec<usize> = (0..active.len()).filter(|&i| active[i]).collect();
        let nj = order.len();
        let mut l = Mat::from_fn(nj, nj, |a, b| {
            if a >= b {
                p.m[(order[a], order[b])]
            } else {
                0.0
            }
        });
        cholesky_lower(l.as_mut(), par)?;
        stats.factorizations += 1;
        Ok(Self {
            order,
            l,
            capacity: nj,
            n: active.len(),
        })
    }

    /// Refactors for `active`; `key` orders the indices that join.
    fn update(
        &mut self,
        p: &MixedLcpRef<'_>,
        active: &[bool],
        key: &[f64],
        par: faer::Par,
        stats: &mut Statistics,
    ) -> Result<(), BlockFailure> {
        use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
        let keep = self.order.iter().take_while(|&&i| active[i]).count();
        let mut kept = vec![false; active.len()];
        for &i in &self.order[..keep] {
            kept[i] = true;
        }
        let mut rest: Vec<usize> = (0..active.len())
            .filter(|&i| active[i] && !kept[i])
            .collect();
        self.order.truncate(keep);
        if rest.is_empty() {
            // The active set shrank to a prefix of the order: its factor is
            // the leading block, already in place.
            return Ok(());
        }
        rest.sort_by(|&a, &b| key[a].total_cmp(&key[b]).then(a.cmp(&b)));
        let (np, nr) = (keep, rest.len());
        if self.l.nrows() < np + nr {
            // Grow in place, the capacity at least doubling (capped at n) so
            // that the kept prefix moves O(log n) times over a prefix search.
            if self.capacity < np + nr {
                self.capacity = (2 * self.capacity).max(np + nr).min(self.n);
                self.l.reserve(self.capacity, self.capacity);
            }
            self.l.resize_with(np + nr, np + nr, |_, _| 0.0);
        }
        let prefix = &self.order[..keep];
        // L_RP^T = L_PP^{-1} M_PR.
        let mut lrp_t = Mat::from_fn(np, nr, |a, b| p.m[(prefix[a], rest[b])]);
        if np > 0 {
            solve_lower_triangular_in_place(
                self.l.as_ref().submatrix(0, 0, np, np),
                lrp_t.as_mut(),
                par,
            );
        }
        let mut srr = Mat::from_fn(nr, nr, |a, b| p.m[(rest[a], rest[b])]);
        if np > 0 {
            matmul(
                srr.as_mut(),
                Accum::Add,
                lrp_t.transpose(),
                lrp_t.as_ref(),
                -1.0,
                par,
            );
        }
        cholesky_lower(srr.as_mut(), par)?;
        self.l
            .as_mut()
            .submatrix_mut(np, 0, nr, np)
            .copy_from(lrp_t.transpose());
        // The new diagonal block's lower triangle (cholesky_in_place leaves
        // the upper triangle as it was); above it stays zero.
        for j in 0..nr {
            let tail = &srr.col_as_slice(j)[j..];
            self.l.col_as_slice_mut(np + j)[np + j..np + nr].copy_from_slice(tail);
            self.l.col_as_slice_mut(np + j)[np..np + j].fill(0.0);
        }
        stats.factorizations += 1;
        self.order.extend(rest);
        Ok(())
    }

    /// The factor of the current active block.
    fn factor(&self) -> faer::MatRef<'_, f64> {
        let n = self.order.len();
        self.l.as_ref().submatrix(0, 0, n, n)
    }

    /// Overwrites `rhs` (in `order`) with `M_JJ^{-1} rhs`.
    fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>, par: faer::Par) {
        let mut mem = MemBuffer::new(faer::dyn_stack::StackReq::EMPTY);
        faer::linalg::cholesky::llt::solve::solve_in_place(
            self.factor(),
            rhs,
            par,
            MemStack::new(&mut mem),
        );
    }
}

/// The block system of an active set `J`, factored:
///
/// ```text
///     K [z_J; u] = [-q_J; -r],   K = [M_JJ  B_J]
///                                    [C_J   D  ]
/// ```
///
/// through the Cholesky factor of `M_JJ` and the Schur complement
/// `D - C_J M_JJ^{-1} B_J` (k x k, LU), both formed once per active set.
struct BlockSystem<'f> {
    factor: &'f Factor,
    /// `G = M_JJ^{-1} B_J` (nj x k).
    g: Mat<f64>,
    /// `M_JJ^{-1} (-q_J)`, the data's part of the solution.
    data: Col<f64>,
    /// The Schur complement's LU and `C_J` (None without equality rows).
    schur: Option<(Lu, Mat<f64>)>,
    par: faer::Par,
}

impl<'f> BlockSystem<'f> {
    /// Forms `G` and the Schur complement for the active set of `factor`,
    /// and `M_JJ^{-1} (-q_J)` for [`solution`](Self::solution) in the same
    /// triangular solves (one pass over the factor, not two: the solves are
    /// bound by reading it).
    fn new(p: &MixedLcpRef<'_>, factor: &'f Factor, par: faer::Par) -> Result<Self, BlockFailure> {
        let idx: &[usize] = &factor.order;
        let nj = idx.len();
        let k = p.extras();
        let mut both = Mat::from_fn(nj, k + 1, |a, j| {
            if j < k {
                p.b[(idx[a], j)]
            } else {
                -p.q[idx[a]]
            }
        });
        factor.solve_in_place(both.as_mut(), par);
        let data = both.col(k).to_owned();
        let g = both.subcols(0, k).to_owned();
        let schur = if k > 0 {
            let cj = Mat::from_fn(k, nj, |e, a| p.c[(e, idx[a])]);
            let mut s = p.d.to_owned();
            matmul(
                s.as_mut(),
                Accum::Add,
                cj.as_ref(),
                g.as_ref(),
                -1.0,
                faer::Par::Seq,
            );
            let lu = Lu::new(s, faer::Par::Seq);
            if lu.pivot_ratio <= f64::EPSILON * k as f64 {
                return Err(BlockFailure::Singular);
            }
            Some((lu, cj))
        } else {
            None
        };
        Ok(Self {
            factor,
            g,
            data,
            schur,
            par,
        })
    }

    /// Solves `K [z_J; u] = [f; h]`: `u = S^{-1} (h - C_J M^{-1} f)`,
    /// `z_J = M^{-1} f - G u`.
    fn solve(&self, f: &Col<f64>, h: &Col<f64>) -> (Col<f64>, Col<f64>) {
        let mut y = f.clone();
        self.factor.solve_in_place(y.as_mat_mut(), self.par);
        self.finish(y, h)
    }

    /// [`solve`](Self::solve) from `y = M_JJ^{-1} f`.
    fn finish(&self, mut y: Col<f64>, h: &Col<f64>) -> (Col<f64>, Col<f64>) {
        let Some((lu, cj)) = &self.schur else {
            return (y, Col::zeros(0));
        };
        let mut u = h.clone();
        matmul(
            u.as_mat_mut(),
            Accum::Add,
            cj.as_ref(),
            y.as_mat(),
            -1.0,
            faer::Par::Seq,
        );
        lu.solve_in_place(u.as_mat_mut());
        matmul(
            y.as_mat_mut(),
            Accum::Add,
            self.g.as_ref(),
            u.as_mat(),
            -1.0,
            faer::Par::Seq,
        );
        (y, u)
    }

    /// The active set's solution, `z` scattered to full length (0 off `J`).
    fn solution(&self, p: &MixedLcpRef<'_>) -> (Col<f64>, Col<f64>) {
        let h = Col::from_fn(p.extras(), |e| -p.r[e]);
        let (zj, u) = self.finish(self.data.clone(), &h);
        (self.scatter(p.size(), &zj), u)
    }

    fn scatter(&self, n: usize, zj: &Col<f64>) -> Col<f64> {
        let mut z = Col::<f64>::zeros(n);
        for (a, &i) in self.factor.order.iter().enumerate() {
            z[i] = zj[a];
        }
        z
    }

    /// Iterative refinement of a solution in place: residuals of the block
    /// equations from the original data, corrections from the factors.
    fn refine(
        &self,
        p: &MixedLcpRef<'_>,
        z: &mut Col<f64>,
        u: &mut Col<f64>,
        steps: usize,
        stats: &mut Statistics,
    ) {
        let idx: &[usize] = &self.factor.order;
        let k = p.extras();
        let mut sorted = idx.to_vec();
        sorted.sort_unstable();
        let mut w = Col::<f64>::zeros(p.size());
        for _ in 0..steps {
            // The block equations' rows only (w off J is not needed here).
            let wj = residual_w_at(p, z, u, &sorted, self.par);
            for (t, &i) in sorted.iter().enumerate() {
                w[i] = wj[t];
            }
            let rf = Col::from_fn(idx.len(), |a| -w[idx[a]]);
            let mut rh = p.r.to_owned();
            if k > 0 {
                matmul(
                    rh.as_mat_mut(),
                    Accum::Add,
                    p.c,
                    z.as_mat(),
                    1.0,
                    faer::Par::Seq,
                );
                matmul(
                    rh.as_mat_mut(),
                    Accum::Add,
                    p.d,
                    u.as_mat(),
                    1.0,
                    faer::Par::Seq,
                );
            }
            let rh = -rh;
            let (dz, du) = self.solve(&rf, &rh);
            for (a, &i) in idx.iter().enumerate() {
                z[i] += dz[a];
            }
            *u += &du;
            stats.refinement_steps += 1;
            if norm_inf(dz.as_ref()) <= f64::EPSILON * norm_inf(z.as_ref()) {
                break;
            }
        }
    }
}

/// The indices whose sign is wrong for the active set: active with
/// `z_i < 0`, inactive with `w_i < 0`, each below the zero tolerance of its
/// own scale: `|z|`, and for w the scale of its terms,
/// `max_i (|M z|_i + |B u|_i + |q_i|)` (with `M z` recovered as
/// `w - B u - q`, and `w_i = 0` on the active rows, where the block solve
/// makes it zero), in w's own units (a gap, for contact), never mixed with
/// the equality rows' (a load). Only the inactive rows of `w` are computed.
fn violations(
    p: &MixedLcpRef<'_>,
    active: &[bool],
    z: &Col<f64>,
    u: &Col<f64>,
    tol: &Tolerances,
    par: faer::Par,
) -> Vec<usize> {
    let n = p.size();
    let inactive: Vec<usize> = (0..n).filter(|&i| !active[i]).collect();
    let w_inactive = residual_w_at(p, z, u, &inactive, par);
    let mut w = Col::<f64>::zeros(n);
    for (t, &i) in inactive.iter().enumerate() {
        w[i] = w_inactive[t];
    }
    let zscale = norm_inf(z.as_ref());
    let wscale = (0..n)
        .map(|i| {
            let bu: f64 = (0..u.nrows()).map(|j| p.b[(i, j)] * u[j]).sum();
            (w[i] - bu - p.q[i]).abs() + bu.abs() + p.q[i].abs()
        })
        .fold(0.0f64, f64::max);
    (0..n)
        .filter(|&i| {
            if active[i] {
                z[i] < -tol.zero * zscale
            } else {
                w[i] < -tol.zero * wscale
            }
        })
        .collect()
}

/// `w_i = (M z)_i + (B u)_i + q_i` for the indices `rows` (ascending), in
/// that order. `M` is symmetric (checked before block pivoting starts), so
/// `(M z)_i` is column i of M against z: a run of consecutive indices is one
/// product with contiguous columns, and the rows not asked for cost nothing.
fn residual_w_at(
    p: &MixedLcpRef<'_>,
    z: &Col<f64>,
    u: &Col<f64>,
    rows: &[usize],
    par: faer::Par,
) -> Col<f64> {
    let mut w = Col::<f64>::zeros(rows.len());
    let mut start = 0;
    while start < rows.len() {
        let mut end = start + 1;
        while end < rows.len() && rows[end] == rows[end - 1] + 1 {
            end += 1;
        }
        let (first, len) = (rows[start], end - start);
        matmul(
            w.as_mut().subrows_mut(start, len).as_mat_mut(),
            Accum::Replace,
            p.m.subcols(first, len).transpose(),
            z.as_mat(),
            1.0,
            par,
        );
        start = end;
    }
    for (t, &i) in rows.iter().enumerate() {
        let bu: f64 = (0..u.nrows()).map(|j| p.b[(i, j)] * u[j]).sum();
        w[t] += bu + p.q[i];
    }
    w
}

/// Lemke's method, keeping the statistics of the block iterations so far.
pub(crate) fn fallback(
    p: &MixedLcpRef<'_>,
    opts: &Options,
    stats: Statistics,
) -> Result<RawSolution, LcpError> {
    let mut raw = lemke::solve_mixed(p, opts)?;
    let s = &mut raw.statistics;
    s.absorb(&stats);
    s.fell_back = true;
    s.method = Method::BlockPivoting;
    Ok(raw)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::ColRef;

    /// A contact-shaped problem on a 2-D grid of `side^2` points, spacing h:
    /// M the Boussinesq kernel h / (pi r) off the diagonal and a uniformly
    /// loaded square's 4 ln(1 + sqrt 2) / pi at its centre on it (the
    /// paper's own discretization, in units of the compliance), q the parabolic
    /// separation |x|^2 / 2, one free approach and the load row sum z = P.
    fn contact(side: usize) -> (Mat<f64>, Mat<f64>, Col<f64>, Mat<f64>) {
        let n = side * side;
        let x = |i: usize| {
            let h = 2.0 / (side - 1) as f64;
            (-1.0 + h * (i % side) as f64, -1.0 + h * (i / side) as f64)
        };
        let m = Mat::from_fn(n, n, |i, j| {
            let ((a, b), (c, d)) = (x(i), x(j));
            let h = 2.0 / (side - 1) as f64;
            if i == j {
                4.0 * (1.0 + 2f64.sqrt()).ln() / std::f64::consts::PI
            } else {
                h / (std::f64::consts::PI * (a - c).hypot(b - d))
            }
        });
        let q = Col::from_fn(n, |i| {
            let (a, b) = x(i);
            (a * a + b * b) / 2.0
        });
        (
            m,
            Mat::from_fn(n, 1, |_, _| -1.0),
            q,
            Mat::from_fn(1, n, |_, _| 1.0),
        )
    }

    #[test]
    fn prefix_search_stops_just_past_the_contact_set() {
        let side = 31;
        let load = 4.0;
        let (m, b, q, c) = contact(side);
        let d = Mat::<f64>::zeros(1, 1);
        let r = [-load];
        let bounds = [Bound::Free];
        let p = MixedLcpRef::new(
            m.as_ref(),
            b.as_ref(),
            q.as_ref(),
            c.as_ref(),
            d.as_ref(),
            ColRef::from_slice(&r),
            &bounds,
        )
        .unwrap();
        let opts = Options::default();
        let n = p.size();
        let key: Vec<f64> = (0..n).map(|i| p.q[i]).collect();
        let mut factor = Factor::new(n);
        let mut stats = Statistics::new(Method::BlockPivoting);
        let prefix = prefix_search(
            &p,
            &key,
            &mut factor,
            &opts.tolerances,
            faer::Par::Seq,
            &mut stats,
        );
        let solution = solve_mixed(&p, &opts).unwrap();
        let contact: Vec<usize> = (0..n).filter(|&i| solution.basic[i]).collect();
        let size = prefix.iter().filter(|&&a| a).count();
        // Several growth steps were taken, and the prefix holds the
        // contact set and ends within one growth step past it.
        assert!(stats.factorizations > 3, "{} steps", stats.factorizations);
        assert!(contact.len() > 2 * PREFIX_STEP && contact.len() < n / 2);
        assert!(contact.iter().all(|&i| prefix[i]));
        let bound = (contact.len() as f64 * PREFIX_GROWTH) as usize + PREFIX_STEP;
        assert!(size <= bound, "prefix {size}, contact {}", contact.len());
        // The prefix is one: every index in it has a key no larger than
        // every index outside.
        let inside = (0..n).filter(|&i| prefix[i]).map(|i| key[i]);
        let outside = (0..n).filter(|&i| !prefix[i]).map(|i| key[i]);
        assert!(inside.fold(f64::MIN, f64::max) <= outside.fold(f64::MAX, f64::min));
    }
}
