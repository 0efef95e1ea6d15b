//! The per-chunk loops of the passes that write vectors or take many
//! measures at once, in vector registers (`pulp`'s dispatch picks the
//! widest the processor has: AVX-512, else AVX2, else its scalar path): the measures
//! of `w = u + q - B λ`, the direction `t` and the step `z_J -= τ t_J`.
//! Entry `i` belongs to lane `i mod LANES`, and a group of [`LANES`]
//! entries fills `LANES / width` registers, so every lane takes the same
//! operations in the same order on any processor as the entry-by-entry
//! form (each kernel's `add` or `at`, which also takes a chunk's tail):
//! the iterates are the same to the bit with or without vector
//! instructions. Comparisons are written as selections (`a < b ? a : b`),
//! not as `min`/`max`, whose NaN rules differ between instruction sets.

use pulp::{Simd, WithSimd};

use super::passes::{Compensated, LANES, Lanes, add_compensated, registers, to_lanes};

/// A border column's sums over a chunk, lane by lane: `Σ b_i z_i`
/// (compensated) and `Σ |b_i z_i|`, the row's sum and its terms'
/// magnitude.
#[derive(Default)]
pub(super) struct RowSums {
    pub sum: Compensated,
    pub terms: Lanes,
}

impl RowSums {
    /// Adds entry `(b, z)` to lane `l`.
    #[inline(always)]
    fn add(&mut self, l: usize, b: f64, z: f64) {
        self.sum.add(l, b * z);
        self.terms.add(l, (b * z).abs());
    }
}

/// [`RowSums`] in registers: register `r` holds lanes `r S::F64_LANES ..`.
struct RowRegisters<S: Simd> {
    sum: [S::f64s; LANES],
    carry: [S::f64s; LANES],
    terms: [S::f64s; LANES],
}

impl<S: Simd> RowRegisters<S> {
    #[inline(always)]
    fn new(simd: S) -> Self {
        let zero = simd.splat_f64s(0.0);
        Self {
            sum: [zero; LANES],
            carry: [zero; LANES],
            terms: [zero; LANES],
        }
    }

    /// Adds register `r`'s entries `(b, z)`: the operations of
    /// [`RowSums::add`] lane by lane.
    #[inline(always)]
    fn add(&mut self, simd: S, r: usize, b: S::f64s, z: S::f64s) {
        let bz = simd.mul_f64s(b, z);
        add_compensated(simd, (&mut self.sum[r], &mut self.carry[r]), bz);
        self.terms[r] = simd.add_f64s(self.terms[r], simd.abs_f64s(bz));
    }

    /// The sums in lane order.
    #[inline(always)]
    fn lanes(&self) -> RowSums {
        RowSums {
            sum: Compensated::from_lanes(to_lanes::<S>(&self.sum), to_lanes::<S>(&self.carry)),
            terms: Lanes(to_lanes::<S>(&self.terms)),
        }
    }
}

/// A chunk's measures of `w`, lane by lane (lane `l` of the entries `i ≡
/// l (mod LANES)`): the extrema and the sums of
/// [`Measures`](super::iteration::Measures), and
/// `Σ 0 w_i`, 0 where every `w_i` is finite and NaN otherwise.
#[derive(Default)]
pub(super) struct WLanes {
    pub min_w: [f64; LANES],
    pub comp: [f64; LANES],
    pub w_scale: [f64; LANES],
    pub z_scale: [f64; LANES],
    pub g: [f64; LANES],
    pub chopped: [f64; LANES],
    pub nonfinite: [f64; LANES],
    /// With one border column: its [`RowSums`].
    pub row: RowSums,
}

impl WLanes {
    /// Adds entry `(z, u, q, s, s_terms)` to lane `l`: a chunk's tail, and
    /// the entry-by-entry reference the register loop keeps to the bit.
    #[inline(always)]
    fn add(&mut self, l: usize, [z, u, q, s, s_terms]: [f64; 5]) {
        let w = (u + q) - s;
        let cw = (z * w).abs();
        let terms = u.abs() + q.abs() + s_terms;
        self.nonfinite[l] += w * 0.0;
        self.min_w[l] = if w < self.min_w[l] { w } else { self.min_w[l] };
        self.comp[l] = if cw > self.comp[l] { cw } else { self.comp[l] };
        self.w_scale[l] = if terms > self.w_scale[l] {
            terms
        } else {
            self.w_scale[l]
        };
        self.z_scale[l] = if z > self.z_scale[l] {
            z
        } else {
            self.z_scale[l]
        };
        self.g[l] += if z > 0.0 { w * w } else { 0.0 };
        self.chopped[l] += if (z > 0.0) | (w >= 0.0) { 0.0 } else { w * w };
    }
}

/// The measures of a chunk's `w = c u + q - s` from its slices `[z, u, q,
/// s, s_terms]` (of one length) and the pending scale `c` of `z` and `u`
/// (applied in registers, `c z` and `c u`, not stored), and with the
/// border's one column `row` its sums: the groups of [`LANES`] entries in
/// vector registers, lane `l` of the result the same operations in the
/// same order as [`WLanes::add`] and [`RowSums::add`] entry by entry
/// (of `c z`, `c u`), then the tail entry by entry. With a `residual` to
/// write (a preconditioned step's), also `r = w` on `J`, 0 off it, from
/// the same `w`.
pub(super) fn measure_chunk(
    v: [&[f64]; 5],
    scale: f64,
    row: Option<&[f64]>,
    residual: Option<&mut [f64]>,
) -> WLanes {
    pulp::Arch::new().dispatch(MeasureChunk {
        v,
        scale,
        row,
        residual,
    })
}

struct MeasureChunk<'a, 'b> {
    v: [&'a [f64]; 5],
    scale: f64,
    row: Option<&'a [f64]>,
    residual: Option<&'b mut [f64]>,
}

impl WithSimd for MeasureChunk<'_, '_> {
    type Output = WLanes;

    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> WLanes {
        let (v, scale) = (self.v, self.scale);
        match (self.row, self.residual) {
            (Some(b), Some(r)) => sweep_measures::<S, true, true>(simd, (v, scale), b, r),
            (Some(b), None) => sweep_measures::<S, true, false>(simd, (v, scale), b, &mut []),
            (None, Some(r)) => sweep_measures::<S, false, true>(simd, (v, scale), &[], r),
            (None, None) => sweep_measures::<S, false, false>(simd, (v, scale), &[], &mut []),
        }
    }
}

/// The measures of `v = [z, u, q, s, s_terms]` at the pending `scale`,
/// with the row's sums of `b` where `ROW` and the residual written to
/// `residual` where `RESIDUAL`.
#[inline(always)]
fn sweep_measures<S: Simd, const ROW: bool, const RESIDUAL: bool>(
    simd: S,
    (v, scale): ([&[f64]; 5], f64),
    b: &[f64],
    residual: &mut [f64],
) -> WLanes {
    let [z, u, q, s, s_terms] = v;
    let len = z.len();
    let full = len - len % LANES;
    let regs = LANES / S::F64_LANES;
    let zero = simd.splat_f64s(0.0);
    let mut min_w = [zero; LANES];
    let mut comp = [zero; LANES];
    let mut w_scale = [zero; LANES];
    let mut z_scale = [zero; LANES];
    let mut g = [zero; LANES];
    let mut chopped = [zero; LANES];
    let mut nonfinite = [zero; LANES];
    let mut row = RowRegisters::new(simd);
    let zs = registers::<S>(z);
    let us = registers::<S>(u);
    let qs = registers::<S>(q);
    let ss = registers::<S>(s);
    let ts = registers::<S>(s_terms);
    let bs = registers::<S>(b);
    let rs = if RESIDUAL {
        S::as_mut_simd_f64s(&mut residual[..full]).0
    } else {
        &mut []
    };
    let c = simd.splat_f64s(scale);
    let mut k = 0;
    while k < zs.len() {
        for r in 0..regs {
            let (z, u, q) = (
                simd.mul_f64s(c, zs[k + r]),
                simd.mul_f64s(c, us[k + r]),
                qs[k + r],
            );
            let w = simd.sub_f64s(simd.add_f64s(u, q), ss[k + r]);
            let cw = simd.abs_f64s(simd.mul_f64s(z, w));
            let terms = simd.add_f64s(simd.add_f64s(simd.abs_f64s(u), simd.abs_f64s(q)), ts[k + r]);
            nonfinite[r] = simd.add_f64s(nonfinite[r], simd.mul_f64s(w, zero));
            min_w[r] = simd.select_f64s(simd.less_than_f64s(w, min_w[r]), w, min_w[r]);
            comp[r] = simd.select_f64s(simd.greater_than_f64s(cw, comp[r]), cw, comp[r]);
            w_scale[r] =
                simd.select_f64s(simd.greater_than_f64s(terms, w_scale[r]), terms, w_scale[r]);
            z_scale[r] = simd.select_f64s(simd.greater_than_f64s(z, z_scale[r]), z, z_scale[r]);
            let on = simd.greater_than_f64s(z, zero);
            if RESIDUAL {
                rs[k + r] = simd.select_f64s(on, w, zero);
            }
            let ww = simd.mul_f64s(w, w);
            g[r] = simd.add_f64s(g[r], simd.select_f64s(on, ww, zero));
            let quiet = simd.or_m64s(on, simd.greater_than_or_equal_f64s(w, zero));
            chopped[r] = simd.add_f64s(chopped[r], simd.select_f64s(quiet, zero, ww));
            if ROW {
                row.add(simd, r, bs[k + r], z);
            }
        }
        k += regs;
    }
    let lanes = to_lanes::<S>;
    let mut acc = WLanes {
        min_w: lanes(&min_w),
        comp: lanes(&comp),
        w_scale: lanes(&w_scale),
        z_scale: lanes(&z_scale),
        g: lanes(&g),
        chopped: lanes(&chopped),
        nonfinite: lanes(&nonfinite),
        row: row.lanes(),
    };
    let c = scale;
    for i in full..len {
        let entry = [c * z[i], c * u[i], q[i], s[i], s_terms[i]];
        acc.add(i - full, entry);
        if ROW {
            acc.row.add(i - full, b[i], entry[0]);
        }
        if RESIDUAL {
            residual[i] = residual_at(entry);
        }
    }
    acc
}

/// `r_i = w_i` on `J`, 0 off it, from entry `[c z, c u, q, s, _]` (the
/// operations of [`WLanes::add`]'s `w`).
#[inline(always)]
pub(super) fn residual_at([z, u, q, s, _]: [f64; 5]) -> f64 {
    if z > 0.0 { (u + q) - s } else { 0.0 }
}

/// How a direction pass forms `t` from a chunk (slices of the chunk's
/// length; `s` the border's shift `B λ`, or `B μ` preconditioned).
#[derive(Clone, Copy)]
pub(super) enum Rule<'a> {
    /// `t_i = w_i + β t_i` on `J`, 0 off it, `w = (c u + q) - s` (`c`
    /// the pending scale of `u`); sums `w_i t_i`.
    Conjugate {
        u: &'a [f64],
        c: f64,
        q: &'a [f64],
        s: &'a [f64],
        beta: f64,
    },
    /// `t_i = w_i` where `z_i = 0` and `w_i < 0`, else 0 (the chopped
    /// gradient); sums `w_i t_i`.
    Chopped {
        u: &'a [f64],
        c: f64,
        q: &'a [f64],
        s: &'a [f64],
    },
    /// `t_i = (p_i - s_i) + β t_i` on `J`, 0 off it; sums `r_i t_i`.
    Preconditioned {
        p: &'a [f64],
        s: &'a [f64],
        r: &'a [f64],
        beta: f64,
    },
}

impl Rule<'_> {
    /// Entry `i`'s new `t_i` from `z_i` and `t_i`, and its term of the sum.
    #[inline(always)]
    fn at(&self, i: usize, z: f64, t: f64) -> (f64, f64) {
        match *self {
            Rule::Conjugate { u, c, q, s, beta } => {
                let w = (c * u[i] + q[i]) - s[i];
                let next = if z > 0.0 { w + beta * t } else { 0.0 };
                (next, w * next)
            }
            Rule::Chopped { u, c, q, s } => {
                let w = (c * u[i] + q[i]) - s[i];
                let next = if z > 0.0 || w >= 0.0 { 0.0 } else { w };
                (next, w * next)
            }
            Rule::Preconditioned { p, s, r, beta } => {
                let next = if z > 0.0 {
                    (p[i] - s[i]) + beta * t
                } else {
                    0.0
                };
                (next, r[i] * next)
            }
        }
    }
}

/// Writes a chunk's direction `t` by `rule` from `z`; returns the sum of
/// the rule's terms in lanes.
pub(super) fn direction_chunk(rule: Rule<'_>, z: &[f64], t: &mut [f64]) -> Lanes {
    pulp::Arch::new().dispatch(DirectionChunk { rule, z, t })
}

struct DirectionChunk<'a, 'b> {
    rule: Rule<'a>,
    z: &'a [f64],
    t: &'b mut [f64],
}

impl WithSimd for DirectionChunk<'_, '_> {
    type Output = Lanes;

    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> Lanes {
        let Self { rule, z, t } = self;
        let len = z.len();
        let full = len - len % LANES;
        let zero = simd.splat_f64s(0.0);
        let mut num = [zero; LANES];
        let zs = registers::<S>(z);
        let ts = S::as_mut_simd_f64s(&mut t[..full]).0;
        let on = |z: S::f64s| simd.greater_than_f64s(z, zero);
        match rule {
            Rule::Conjugate { u, c, q, s, beta } => {
                let (us, qs, ss) = (registers::<S>(u), registers::<S>(q), registers::<S>(s));
                let (beta, c) = (simd.splat_f64s(beta), simd.splat_f64s(c));
                sweep(simd, zs, &mut *ts, &mut num, |k, z, t| {
                    let w = simd.sub_f64s(simd.add_f64s(simd.mul_f64s(c, us[k]), qs[k]), ss[k]);
                    let next = simd.add_f64s(w, simd.mul_f64s(beta, t));
                    let next = simd.select_f64s(on(z), next, zero);
                    (next, simd.mul_f64s(w, next))
                });
            }
            Rule::Chopped { u, c, q, s } => {
                let (us, qs, ss) = (registers::<S>(u), registers::<S>(q), registers::<S>(s));
                let c = simd.splat_f64s(c);
                sweep(simd, zs, &mut *ts, &mut num, |k, z, _| {
                    let w = simd.sub_f64s(simd.add_f64s(simd.mul_f64s(c, us[k]), qs[k]), ss[k]);
                    let quiet = simd.or_m64s(on(z), simd.greater_than_or_equal_f64s(w, zero));
                    let next = simd.select_f64s(quiet, zero, w);
                    (next, simd.mul_f64s(w, next))
                });
            }
            Rule::Preconditioned { p, s, r, beta } => {
                let (ps, ss, rs) = (registers::<S>(p), registers::<S>(s), registers::<S>(r));
                let beta = simd.splat_f64s(beta);
                sweep(simd, zs, &mut *ts, &mut num, |k, z, t| {
                    let next = simd.add_f64s(simd.sub_f64s(ps[k], ss[k]), simd.mul_f64s(beta, t));
                    let next = simd.select_f64s(on(z), next, zero);
                    (next, simd.mul_f64s(rs[k], next))
                });
            }
        }
        let mut sum = Lanes(to_lanes::<S>(&num));
        for i in full..len {
            let (next, term) = rule.at(i, z[i], t[i]);
            t[i] = next;
            sum.add(i - full, term);
        }
        sum
    }
}

/// A direction's sweep over the chunk's full groups: `t_k, term =
/// form(k, z_k, t_k)` register by register, the terms added to `num`
/// (one loop a rule, each a plain sweep of selections).
#[inline(always)]
fn sweep<S: Simd>(
    simd: S,
    zs: &[S::f64s],
    ts: &mut [S::f64s],
    num: &mut [S::f64s; LANES],
    form: impl Fn(usize, S::f64s, S::f64s) -> (S::f64s, S::f64s),
) {
    let regs = LANES / S::F64_LANES;
    let mut k = 0;
    while k < zs.len() {
        for r in 0..regs {
            let (next, term) = form(k + r, zs[k + r], ts[k + r]);
            ts[k + r] = next;
            num[r] = simd.add_f64s(num[r], term);
        }
        k += regs;
    }
}

/// A step's data over a chunk, from `z` and `u` at their pending scale
/// `c` (`c z`, `c u`, stored so after the step): `z_J = c z_J - τ t_J`
/// (clipped at 0), the points off `J` with `w_i = (c u_i + q_i) - s_i <
/// 0` entering with `z_i = -τ w_i` (`-w_i` when `τ = 0`) where `enter` is
/// set, and `u = c u - τ r`.
#[derive(Clone, Copy)]
pub(super) struct Step<'a> {
    pub c: f64,
    pub t: &'a [f64],
    pub r: &'a [f64],
    pub q: &'a [f64],
    pub s: &'a [f64],
    pub tau: f64,
    pub enter: bool,
}

impl Step<'_> {
    /// Entry `i`'s new `(z_i, u_i)` and whether it was clipped or entered.
    #[inline(always)]
    fn at(&self, i: usize, z: f64, u: f64) -> (f64, f64, bool, bool) {
        let (z, u) = (self.c * z, self.c * u);
        let (mut clipped, mut entered) = (false, false);
        let next = if z > 0.0 {
            let v = z - self.tau * self.t[i];
            clipped = !(v > 0.0);
            if v > 0.0 { v } else { 0.0 }
        } else if self.enter {
            let w = (u + self.q[i]) - self.s[i];
            if w < 0.0 {
                entered = true;
                self.entry() * w
            } else {
                z
            }
        } else {
            z
        };
        (next, u - self.tau * self.r[i], clipped, entered)
    }

    /// The factor of `w_i` an entering point takes: `-τ`, or -1 when `τ = 0`
    /// (`(-τ) w` and `-w` to the bit).
    fn entry(&self) -> f64 {
        if self.tau > 0.0 { -self.tau } else { -1.0 }
    }
}

/// What a chunk's step did: how many points were clipped and how many
/// entered, and with the border's one column `b`, the sums after the step:
/// its [`RowSums`] and, where `u`'s recurrence was taken, `Σ_J b_i u_i`
/// (compensated; 0 otherwise).
pub(super) struct Stepped {
    pub clipped: usize,
    pub entered: usize,
    pub row: RowSums,
    pub bu: Compensated,
}

/// Takes a chunk's step (see [`Step`]) on `z` and `u`, with the sums of
/// the border's one column `row` after it ([`Stepped`]). Without
/// `recur` (the step has already changed the contact set elsewhere, so
/// `u` will be recomputed from a true product) `u` is read for the
/// entries but keeps its values, and `Σ_J b u` is not taken.
pub(super) fn update_chunk(
    step: Step<'_>,
    (z, u): (&mut [f64], &mut [f64]),
    row: Option<&[f64]>,
    recur: bool,
) -> Stepped {
    pulp::Arch::new().dispatch(UpdateChunk {
        step,
        z,
        u,
        row,
        recur,
    })
}

struct UpdateChunk<'a, 'b> {
    step: Step<'a>,
    z: &'b mut [f64],
    u: &'b mut [f64],
    row: Option<&'a [f64]>,
    recur: bool,
}

impl WithSimd for UpdateChunk<'_, '_> {
    type Output = Stepped;

    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) -> Stepped {
        match (self.row, self.recur) {
            (Some(b), true) => self.sweep::<S, true, true>(simd, b),
            (Some(b), false) => self.sweep::<S, true, false>(simd, b),
            (None, true) => self.sweep::<S, false, true>(simd, &[]),
            (None, false) => self.sweep::<S, false, false>(simd, &[]),
        }
    }
}

impl UpdateChunk<'_, '_> {
    /// The step, with the row's sums of `b` where `ROW`, and `u`'s
    /// recurrence (with `Σ_J b u`) where `RECUR`.
    #[inline(always)]
    fn sweep<S: Simd, const ROW: bool, const RECUR: bool>(self, simd: S, b: &[f64]) -> Stepped {
        let Self { step, z, u, .. } = self;
        let len = z.len();
        let full = len - len % LANES;
        let regs = LANES / S::F64_LANES;
        let (zero, one) = (simd.splat_f64s(0.0), simd.splat_f64s(1.0));
        let (tau, entry) = (simd.splat_f64s(step.tau), simd.splat_f64s(step.entry()));
        let c = simd.splat_f64s(step.c);
        let (ts, rs) = (registers::<S>(step.t), registers::<S>(step.r));
        let (qs, ss) = (registers::<S>(step.q), registers::<S>(step.s));
        let bs = registers::<S>(b);
        let zs = S::as_mut_simd_f64s(&mut z[..full]).0;
        let us = S::as_mut_simd_f64s(&mut u[..full]).0;
        let (mut clipped, mut entered) = ([zero; LANES], [zero; LANES]);
        let mut row = RowRegisters::new(simd);
        let (mut bu, mut bu_carry) = ([zero; LANES], [zero; LANES]);
        let mut k = 0;
        while k < zs.len() {
            for r in 0..regs {
                let (old, ui) = (simd.mul_f64s(c, zs[k + r]), simd.mul_f64s(c, us[k + r]));
                let on = simd.greater_than_f64s(old, zero);
                let v = simd.sub_f64s(old, simd.mul_f64s(tau, ts[k + r]));
                let keep = simd.greater_than_f64s(v, zero);
                let kept = simd.select_f64s(keep, v, zero);
                let clip = simd.select_f64s(on, simd.select_f64s(keep, zero, one), zero);
                clipped[r] = simd.add_f64s(clipped[r], clip);
                let off = if step.enter {
                    let w = simd.sub_f64s(simd.add_f64s(ui, qs[k + r]), ss[k + r]);
                    let interferes = simd.less_than_f64s(w, zero);
                    let enters = simd.select_f64s(interferes, one, zero);
                    entered[r] = simd.add_f64s(entered[r], simd.select_f64s(on, zero, enters));
                    simd.select_f64s(interferes, simd.mul_f64s(entry, w), old)
                } else {
                    old
                };
                let zn = simd.select_f64s(on, kept, off);
                zs[k + r] = zn;
                if ROW {
                    row.add(simd, r, bs[k + r], zn);
                }
                if RECUR {
                    let un = simd.sub_f64s(ui, simd.mul_f64s(tau, rs[k + r]));
                    us[k + r] = un;
                    if ROW {
                        let on = simd.greater_than_f64s(zn, zero);
                        let masked = simd.mul_f64s(simd.select_f64s(on, bs[k + r], zero), un);
                        add_compensated(simd, (&mut bu[r], &mut bu_carry[r]), masked);
                    }
                }
            }
            k += regs;
        }
        let lanes = to_lanes::<S>;
        let count = |v: &[S::f64s; LANES]| lanes(v).iter().map(|&c| c as usize).sum::<usize>();
        let mut out = Stepped {
            clipped: count(&clipped),
            entered: count(&entered),
            row: row.lanes(),
            bu: Compensated::from_lanes(lanes(&bu), lanes(&bu_carry)),
        };
        for i in full..len {
            let (next, ui, clip, enter) = step.at(i, z[i], u[i]);
            z[i] = next;
            out.clipped += usize::from(clip);
            out.entered += usize::from(enter);
            let l = i - full;
            if ROW {
                out.row.add(l, b[i], next);
            }
            if RECUR {
                u[i] = ui;
                if ROW {
                    out.bu.add(l, (if next > 0.0 { b[i] } else { 0.0 }) * ui);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests;
