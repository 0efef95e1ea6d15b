//! The solution of a bordered or mixed problem on a given active set `J`
//! (the basic `z`, the contact set), from the original data:
//!
//! ```text
//!     M_JJ z_J + B_J u = -q_J              (w_J = 0)
//!     C_J z_J + D u    = -r                (the equality rows)
//!     =>  (D - C_J M_JJ^{-1} B_J) u = C_J M_JJ^{-1} q_J - r,   z_J = -M_JJ^{-1} (q_J + B_J u)
//! ```
//!
//! through a Cholesky factor of `M_JJ` kept between active sets
//! ([`Factor`]: a new set keeps the longest prefix of the old order that
//! stays active and factors only the rest) and the border's Schur complement
//! `D - C_J M_JJ^{-1} B_J` (k x k, LU). Block pivoting iterates on it; the
//! symmetric tableau's methods finish with it ([`solve_active_set`]).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::matmul;
use faer::{Accum, Col, Mat, Par};

use crate::linalg::{
    AllocationFailed, Lu, NotPositiveDefinite, cholesky_lower, norm_inf, try_mat, unit_of,
};
use crate::options::Options;
use crate::problem::MixedRef;
use crate::statistics::Work;
use crate::tolerance::{REFINED, Tolerances};

/// Why the block system of an active set could not be solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum BlockFailure {
    /// `M_JJ` is not positive definite.
    NotPositiveDefinite,
    /// The equality rows' Schur complement is singular for this `J`.
    Singular,
    /// The factor's storage could not be allocated.
    Allocation(AllocationFailed),
}

impl From<AllocationFailed> for BlockFailure {
    fn from(e: AllocationFailed) -> Self {
        Self::Allocation(e)
    }
}

impl From<NotPositiveDefinite> for BlockFailure {
    fn from(_: NotPositiveDefinite) -> Self {
        BlockFailure::NotPositiveDefinite
    }
}

/// The solution on a given active set, from the original data: one
/// Cholesky of `M_JJ`, the block system, iterative refinement. `None` when
/// `M_JJ` is not positive definite, the equality rows' Schur complement is
/// singular, or a sign is wrong (the set does not solve the problem). The
/// final basic solution of a method that found the set by other means.
pub(crate) fn solve_active_set(
    p: &MixedRef<'_>,
    active: &[bool],
    opts: &Options,
    work: &mut Work,
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
    let scaled = MixedRef {
        b: b.as_ref(),
        c: c.as_ref(),
        d: d.as_ref(),
        r: r.as_ref(),
        ..*p
    };
    let p = &scaled;
    let par = opts.par(p.size(), p.size());
    let factor = Factor::of(p, active, par, work).ok()?;
    let system = BlockSystem::new(p, &factor, par).ok()?;
    let (mut z, mut u) = system.solution(p);
    system.refine(p, &mut z, &mut u, opts.refinement_steps, work);
    violations(p, active, &z, &u, &opts.tolerances, par)
        .is_empty()
        .then(|| (z, u * b_unit))
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
pub(crate) struct Factor {
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
    pub fn new(n: usize) -> Self {
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
        p: &MixedRef<'_>,
        active: &[bool],
        par: Par,
        work: &mut Work,
    ) -> Result<Self, BlockFailure> {
        let order: Vec<usize> = (0..active.len()).filter(|&i| active[i]).collect();
        let nj = order.len();
        let mut l = try_mat(nj, nj, "the active block's factor", |a, b| {
            if a >= b {
                p.m[(order[a], order[b])]
            } else {
                0.0
            }
        })?;
        cholesky_lower(l.as_mut(), par)?;
        work.factorizations += 1;
        Ok(Self {
            order,
            l,
            capacity: nj,
            n: active.len(),
        })
    }

    /// Refactors for `active`; `key` orders the indices that join.
    pub fn update(
        &mut self,
        p: &MixedRef<'_>,
        active: &[bool],
        key: &[f64],
        par: Par,
        work: &mut Work,
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
                let failed = AllocationFailed {
                    what: "the active block's factor",
                    bytes: self
                        .capacity
                        .saturating_mul(self.capacity)
                        .saturating_mul(8),
                };
                self.l
                    .try_reserve(self.capacity, self.capacity)
                    .map_err(|_| BlockFailure::Allocation(failed))?;
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
        work.factorizations += 1;
        self.order.extend(rest);
        Ok(())
    }

    /// The factor of the current active block.
    fn factor(&self) -> faer::MatRef<'_, f64> {
        let n = self.order.len();
        self.l.as_ref().submatrix(0, 0, n, n)
    }

    /// Overwrites `rhs` (in `order`) with `M_JJ^{-1} rhs`.
    fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>, par: Par) {
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
pub(crate) struct BlockSystem<'f> {
    factor: &'f Factor,
    /// `G = M_JJ^{-1} B_J` (nj x k).
    g: Mat<f64>,
    /// `M_JJ^{-1} (-q_J)`, the data's part of the solution.
    data: Col<f64>,
    /// The Schur complement's LU and `C_J` (None without equality rows).
    schur: Option<(Lu, Mat<f64>)>,
    par: Par,
}

impl<'f> BlockSystem<'f> {
    /// Forms `G` and the Schur complement for the active set of `factor`,
    /// and `M_JJ^{-1} (-q_J)` for [`solution`](Self::solution) in the same
    /// triangular solves (one pass over the factor, not two: the solves are
    /// bound by reading it).
    pub fn new(p: &MixedRef<'_>, factor: &'f Factor, par: Par) -> Result<Self, BlockFailure> {
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
                Par::Seq,
            );
            let lu = Lu::new(s, Par::Seq);
            if lu.is_singular() {
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
            Par::Seq,
        );
        lu.solve_in_place(u.as_mat_mut());
        matmul(
            y.as_mat_mut(),
            Accum::Add,
            self.g.as_ref(),
            u.as_mat(),
            -1.0,
            Par::Seq,
        );
        (y, u)
    }

    /// The active set's solution, `z` scattered to full length (0 off `J`).
    pub fn solution(&self, p: &MixedRef<'_>) -> (Col<f64>, Col<f64>) {
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
    pub fn refine(
        &self,
        p: &MixedRef<'_>,
        z: &mut Col<f64>,
        u: &mut Col<f64>,
        steps: usize,
        work: &mut Work,
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
                matmul(rh.as_mat_mut(), Accum::Add, p.c, z.as_mat(), 1.0, Par::Seq);
                matmul(rh.as_mat_mut(), Accum::Add, p.d, u.as_mat(), 1.0, Par::Seq);
            }
            let rh = -rh;
            let (dz, du) = self.solve(&rf, &rh);
            for (a, &i) in idx.iter().enumerate() {
                z[i] += dz[a];
            }
            *u += &du;
            work.refinement_steps += 1;
            if norm_inf(dz.as_ref()) <= REFINED * norm_inf(z.as_ref()) {
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
pub(crate) fn violations(
    p: &MixedRef<'_>,
    active: &[bool],
    z: &Col<f64>,
    u: &Col<f64>,
    tol: &Tolerances,
    par: Par,
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
    p: &MixedRef<'_>,
    z: &Col<f64>,
    u: &Col<f64>,
    rows: &[usize],
    par: Par,
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
