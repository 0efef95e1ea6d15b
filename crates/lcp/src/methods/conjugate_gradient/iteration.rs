//! The passes of one iteration over the method's vectors (`z`, `u = M z`,
//! the direction `t`, the product `r = M t`) and the data (`q`, `B`), each
//! a single pass, chunk by chunk ([`passes`](super::passes): the same
//! bits on any number of threads). Inside a chunk (32 kB a vector, in
//! cache) the border's shift `B λ` is formed column by column, and each
//! sum ([`Terms`]) and each loop that writes a vector or takes the
//! measures ([`chunk`](super::chunk)) runs in vector registers; every lane
//! still adds the same terms in the same order as one loop over the
//! entries would:
//!
//! ```text
//!     fit:        Σ_J B u,  Σ_J B q,  B_J^T B_J                     (after a true product)
//!     measure:    w = c u + q - B λ;  min w, max |z w|, the scales, ‖w_J‖², B^T z, |B|^T z
//!     direction:  t_J = w_J + β t_J, t = 0 off J;  w_J · t_J
//!     curvature:  r_J · t_J
//!     update:     z_J -= τ t_J (clipped at 0), entries off J;  B^T z;  while J keeps: u -= τ r, Σ_J B u, |B|^T z
//!   preconditioned, in place of direction:
//!     (measure)   also r = w on J, 0 off it                          (then p = P r)
//!     projection: Σ_J B p,  Σ_J B r,  r_J · p_J
//!     direction:  t_J = (p - B μ)_J + β t_J, t = 0 off J;  r_J · t_J
//! ```
//!
//! with `J = {i : z_i > 0}`. `z` and `u` may carry a pending scale `c`
//! (the one-row restoration's, `M (c z) = c u`): the measure and
//! direction passes read `c z` and `c u` in registers, and the update
//! stores its result at scale 1. Once a chunk of the update has changed
//! `J`, the later chunks leave `u` as it was: a changed `J` recomputes `u`
//! from a true product before it is read.

use std::borrow::Cow;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use faer::{ColRef, Mat, MatRef};

#[cfg(test)]
use super::chunk::residual_at;
use super::chunk::{Rule, Step, direction_chunk, measure_chunk, update_chunk};
use super::passes::{CHUNK, Compensated, LANES, Lanes, Terms, map_parts, masked_pair_and, total};

/// `q` and the border's columns as slices (copied where a column is not
/// contiguous).
pub(super) struct Data<'a> {
    pub q: Cow<'a, [f64]>,
    border: Vec<Column<'a>>,
}

/// A border column as the passes read it: its entries, or, where they are
/// all the same number (the approach's column of ones), a chunk's length
/// of that number, which stays in cache (the passes then read one vector
/// fewer from memory; the terms are the same to the bit).
enum Column<'a> {
    Entries(Cow<'a, [f64]>),
    Constant(Vec<f64>),
}

impl Column<'_> {
    /// The entries `base..base + len` of a chunk.
    #[inline(always)]
    fn part(&self, base: usize, len: usize) -> &[f64] {
        match self {
            Column::Entries(c) => &c[base..base + len],
            Column::Constant(c) => &c[..len],
        }
    }
}

fn slice_of<'a>(c: ColRef<'a, f64>) -> Cow<'a, [f64]> {
    match c.try_as_col_major() {
        Some(c) => Cow::Borrowed(c.as_slice()),
        None => Cow::Owned(c.iter().copied().collect()),
    }
}

impl<'a> Data<'a> {
    pub fn new(q: ColRef<'a, f64>, border: MatRef<'a, f64>) -> Self {
        Self {
            q: slice_of(q),
            border: (0..border.ncols())
                .map(|j| column_of(border.col(j)))
                .collect(),
        }
    }

    fn columns(&self) -> &[Column<'a>] {
        &self.border
    }
}

/// A border column, [`Column::Constant`] where every entry has the bits of
/// the first.
fn column_of(c: ColRef<'_, f64>) -> Column<'_> {
    match c.iter().next() {
        Some(&first) if c.iter().all(|v| v.to_bits() == first.to_bits()) => {
            Column::Constant(vec![first; c.nrows().min(CHUNK)])
        }
        _ => Column::Entries(slice_of(c)),
    }
}

/// The chunk ranges of `0..n`.
fn ranges(n: usize) -> Vec<std::ops::Range<usize>> {
    (0..n.div_ceil(CHUNK))
        .map(|c| c * CHUNK..((c + 1) * CHUNK).min(n))
        .collect()
}

/// The border's shift `B λ` as a pass reads it, chunk by chunk: where
/// every column is constant (the approach's column of ones, or no column
/// at all) one chunk's worth is formed once and every chunk reads it (the
/// same values to the bit: the same operations on the same numbers), else
/// each chunk forms its own ([`shift_of`]).
struct Shift<'c, 'a> {
    columns: &'c [Column<'a>],
    lambda: &'c [f64],
    terms: bool,
    shared: Option<(Vec<f64>, Vec<f64>)>,
}

impl<'c, 'a> Shift<'c, 'a> {
    /// The shift by `lambda` over `n` entries, with its terms' magnitude
    /// where `terms` is set.
    fn new(columns: &'c [Column<'a>], lambda: &'c [f64], n: usize, terms: bool) -> Self {
        let constant = columns.iter().all(|c| matches!(c, Column::Constant(_)));
        Self {
            columns,
            lambda,
            terms,
            shared: constant.then(|| shift_of(columns, lambda, 0, n.min(CHUNK), terms)),
        }
    }

    /// The shift over the chunk `base..base + len`, and its terms'
    /// magnitude (empty where not asked for).
    fn chunk(&self, base: usize, len: usize) -> (Cow<'_, [f64]>, Cow<'_, [f64]>) {
        match &self.shared {
            Some((s, t)) => (
                Cow::Borrowed(&s[..len]),
                Cow::Borrowed(&t[..if self.terms { len } else { 0 }]),
            ),
            None => {
                let (s, t) = shift_of(self.columns, self.lambda, base, len, self.terms);
                (Cow::Owned(s), Cow::Owned(t))
            }
        }
    }
}

/// The border's shift `(B λ)_i` over a chunk's entries `base..base +
/// len`, and the magnitude of its terms when asked (`terms`): column after
/// column, each entry's terms added in the columns' order from 0 (as one
/// entry's sum would add them), so that every loop is a plain sweep the
/// compiler vectorizes. Written without clearing first (no memset of
/// buffers the first column overwrites).
fn shift_of(
    columns: &[Column<'_>],
    lambda: &[f64],
    base: usize,
    len: usize,
    terms: bool,
) -> (Vec<f64>, Vec<f64>) {
    let mut pairs = columns.iter().zip(lambda);
    let Some((b, &l)) = pairs.next() else {
        return (
            vec![0.0; len],
            if terms { vec![0.0; len] } else { Vec::new() },
        );
    };
    let b = b.part(base, len);
    let mut shift: Vec<f64> = b.iter().map(|&b| 0.0 + b * l).collect();
    let mut magnitude: Vec<f64> = if terms {
        b.iter().map(|&b| 0.0 + (b * l).abs()).collect()
    } else {
        Vec::new()
    };
    for (b, &l) in pairs {
        let b = b.part(base, len);
        for i in 0..len {
            shift[i] += b[i] * l;
        }
        if terms {
            for i in 0..len {
                magnitude[i] += (b[i] * l).abs();
            }
        }
    }
    (shift, magnitude)
}

/// The fit's sums over the contact set `J`: `Σ_J B_j u`, `Σ_J B_j q`
/// (compensated) and the Gram matrix `B_J^T B_J`.
#[derive(Debug, Clone)]
pub(super) struct FitSums {
    pub bu: Vec<f64>,
    pub bq: Vec<f64>,
    pub gram: Mat<f64>,
}

/// Per chunk: the fit's sums, compensated, and the Gram matrix's lower
/// triangle.
#[derive(Clone)]
struct FitParts {
    bu: Vec<Compensated>,
    bq: Vec<Compensated>,
    gram: Vec<Lanes>,
}

impl FitParts {
    fn new(k: usize) -> Self {
        Self {
            bu: vec![Compensated::default(); k],
            bq: vec![Compensated::default(); k],
            gram: vec![Lanes::default(); k * (k + 1) / 2],
        }
    }

    fn merge(parts: &[FitParts], k: usize) -> FitSums {
        let mut bu = vec![Compensated::default(); k];
        let mut bq = vec![Compensated::default(); k];
        for p in parts {
            for j in 0..k {
                bu[j].merge(&p.bu[j]);
                bq[j].merge(&p.bq[j]);
            }
        }
        let mut gram = Mat::zeros(k, k);
        let mut e = 0;
        for a in 0..k {
            for b in 0..=a {
                let v = total(parts.iter().map(|p| p.gram[e].value()));
                gram[(a, b)] = v;
                gram[(b, a)] = v;
                e += 1;
            }
        }
        FitSums {
            bu: bu.iter().map(Compensated::value).collect(),
            bq: bq.iter().map(Compensated::value).collect(),
            gram,
        }
    }
}

/// The fit's sums of `z` and `u = M z` (a true product).
pub(super) fn fit_pass(data: &Data<'_>, z: &[f64], u: &[f64]) -> FitSums {
    let (columns, q) = (data.columns(), &*data.q);
    let k = columns.len();
    let parts = map_parts(ranges(z.len()), |range| {
        let mut p = FitParts::new(k);
        let (z, u, q) = (&z[range.clone()], &u[range.clone()], &q[range.clone()]);
        let len = range.len();
        let mut e = 0;
        for a in 0..k {
            let ba = columns[a].part(range.start, len);
            for b in 0..a {
                let bb = columns[b].part(range.start, len);
                p.gram[e] = Terms::Masked(z, ba, bb).plain();
                e += 1;
            }
            // The column's two sums and its square, in one sweep.
            (p.bu[a], p.bq[a], p.gram[e]) =
                masked_pair_and((z, ba), (u, q), Terms::Masked(z, ba, ba));
            e += 1;
        }
        p
    });
    FitParts::merge(&parts, k)
}

/// What the measure pass finds: the residuals the certificate measures
/// (from `u` in place of `M z`), `‖w_J‖²` and the rows' sums.
#[derive(Debug, Clone)]
pub(super) struct Measures {
    /// The smallest `w_i` (at most 0).
    pub min_w: f64,
    /// The largest `|z_i w_i|`.
    pub complementarity: f64,
    /// `max_i (|u_i| + |q_i| + Σ_j |B_ij λ_j|)`: `w`'s terms.
    pub w_scale: f64,
    /// `max_i z_i`.
    pub z_scale: f64,
    /// `‖w_J‖²`.
    pub g: f64,
    /// `‖β‖²`, `β_i = w_i` where `z_i = 0` and `w_i < 0` (the points that
    /// interfere off `J`: Dostál's chopped gradient), 0 elsewhere.
    pub chopped: f64,
    /// `B^T z` and `|B|^T z`, by row.
    pub rows: Vec<f64>,
    pub rows_terms: Vec<f64>,
    /// Whether every `w_i` is finite.
    pub finite: bool,
}

#[derive(Clone)]
struct MeasureParts {
    min_w: [f64; LANES],
    comp: [f64; LANES],
    w_scale: [f64; LANES],
    z_scale: [f64; LANES],
    g: Lanes,
    chopped: Lanes,
    rows: Vec<Compensated>,
    rows_terms: Vec<Lanes>,
    finite: bool,
}

impl MeasureParts {
    fn new(k: usize) -> Self {
        Self {
            min_w: [0.0; LANES],
            comp: [0.0; LANES],
            w_scale: [0.0; LANES],
            z_scale: [0.0; LANES],
            g: Lanes::default(),
            chopped: Lanes::default(),
            rows: vec![Compensated::default(); k],
            rows_terms: vec![Lanes::default(); k],
            finite: true,
        }
    }
}

fn lanes_max(a: &[f64; LANES]) -> f64 {
    a.iter().fold(0.0f64, |m, &v| if v > m { v } else { m })
}

fn lanes_min(a: &[f64; LANES]) -> f64 {
    a.iter().fold(0.0f64, |m, &v| if v < m { v } else { m })
}

/// Measures `w = c u + q - B λ` (see [`Measures`]) of `c z` and `c u`,
/// `c` the pending `scale` (applied in registers; `z` and `u` are only
/// read); with a `residual` to write (a preconditioned step's), also `r =
/// w` on `J`, 0 off it, the same bits as `residual_pass` (its tests' reference), from the chunk
/// while it is in cache.
pub(super) fn measure_pass(
    data: &Data<'_>,
    (z, u): (&[f64], &[f64]),
    residual: Option<&mut [f64]>,
    scale: f64,
    lambda: &[f64],
) -> Measures {
    let (columns, q) = (data.columns(), &*data.q);
    let k = columns.len();
    let parts: Vec<Option<&mut [f64]>> = match residual {
        Some(r) => r.chunks_mut(CHUNK).map(Some).collect(),
        None => (0..z.len().div_ceil(CHUNK)).map(|_| None).collect(),
    };
    let parts: Vec<_> = parts.into_iter().enumerate().collect();
    let shift = Shift::new(columns, lambda, q.len(), true);
    let parts = map_parts(parts, |(c, r)| {
        let base = c * CHUNK;
        let len = CHUNK.min(z.len() - base);
        let (z, u, q) = (
            &z[base..base + len],
            &u[base..base + len],
            &q[base..base + len],
        );
        let mut p = MeasureParts::new(k);
        let (s, s_terms) = shift.chunk(base, len);
        // One column's sums in the measures' own loop; several, a loop
        // each.
        let row = (k == 1).then(|| columns[0].part(base, len));
        let w = measure_chunk([z, u, q, &s, &s_terms], scale, row, r);
        (p.min_w, p.comp, p.w_scale, p.z_scale) = (w.min_w, w.comp, w.w_scale, w.z_scale);
        (p.g, p.chopped) = (Lanes(w.g), Lanes(w.chopped));
        p.finite = w.nonfinite.iter().all(|&v| v == 0.0);
        if k == 1 {
            (p.rows[0], p.rows_terms[0]) = (w.row.sum, w.row.terms);
        } else {
            // Several rows keep the scale at 1 (only one row is restored by
            // a scale); should one be pending, the sums read `c z`.
            let z: Cow<'_, [f64]> = if scale == 1.0 {
                Cow::Borrowed(z)
            } else {
                Cow::Owned(z.iter().map(|v| scale * v).collect())
            };
            for j in 0..k {
                let b = columns[j].part(base, len);
                p.rows[j] = Terms::Product(b, &z).compensated();
                p.rows_terms[j] = Terms::AbsProduct(b, &z).plain();
            }
        }
        p
    });
    let mut rows = vec![Compensated::default(); k];
    for p in &parts {
        for j in 0..k {
            rows[j].merge(&p.rows[j]);
        }
    }
    Measures {
        min_w: parts.iter().fold(0.0, |m, p| m.min(lanes_min(&p.min_w))),
        complementarity: parts.iter().fold(0.0, |m, p| m.max(lanes_max(&p.comp))),
        w_scale: parts.iter().fold(0.0, |m, p| m.max(lanes_max(&p.w_scale))),
        z_scale: parts.iter().fold(0.0, |m, p| m.max(lanes_max(&p.z_scale))),
        g: total(parts.iter().map(|p| p.g.value())),
        chopped: total(parts.iter().map(|p| p.chopped.value())),
        rows: rows.iter().map(Compensated::value).collect(),
        rows_terms: (0..k)
            .map(|j| total(parts.iter().map(|p| p.rows_terms[j].value())))
            .collect(),
        finite: parts.iter().all(|p| p.finite),
    }
}

/// `t_J = w_J + β t_J`, `t = 0` off `J`, from `z` and `u` at their
/// pending scale `c`; returns `w_J · t_J`.
pub(super) fn direction_pass(
    data: &Data<'_>,
    (z, u, c): (&[f64], &[f64], f64),
    t: &mut [f64],
    lambda: &[f64],
    beta: f64,
) -> f64 {
    direction_by(data, (z, u, c), t, lambda, Some(beta))
}

/// The proportioning direction: `t_i = w_i` where `z_i = 0` and `w_i < 0`
/// (Dostál's chopped gradient `β`), 0 elsewhere; returns `w · t = t · t`.
pub(super) fn chopped_pass(
    data: &Data<'_>,
    (z, u, c): (&[f64], &[f64], f64),
    t: &mut [f64],
    lambda: &[f64],
) -> f64 {
    direction_by(data, (z, u, c), t, lambda, None)
}

/// A direction from `w = c u + q - B λ`, in one pass: the conjugate one
/// with `beta` ([`Rule::Conjugate`]), else the chopped gradient
/// ([`Rule::Chopped`]); returns `w · t`.
fn direction_by(
    data: &Data<'_>,
    (z, u, scale): (&[f64], &[f64], f64),
    t: &mut [f64],
    lambda: &[f64],
    beta: Option<f64>,
) -> f64 {
    let q = &*data.q;
    direction_chunks(data, q.len(), t, lambda, |range, s, t| {
        let (z, u, q) = (&z[range.clone()], &u[range.clone()], &q[range]);
        let rule = match beta {
            Some(beta) => Rule::Conjugate {
                u,
                c: scale,
                q,
                s,
                beta,
            },
            None => Rule::Chopped { u, c: scale, q, s },
        };
        direction_chunk(rule, z, t).value()
    })
}

/// A direction over `t` chunk by chunk, `n` entries: each chunk's
/// `chunk(range, s, t)`, `s` the shift `B ν` on its range (`ν` = `nu`);
/// returns the sum of the chunks' values, in their order.
fn direction_chunks(
    data: &Data<'_>,
    n: usize,
    t: &mut [f64],
    nu: &[f64],
    chunk: impl Fn(Range<usize>, &[f64], &mut [f64]) -> f64 + Sync + Send,
) -> f64 {
    let parts: Vec<_> = t.chunks_mut(CHUNK).enumerate().collect();
    let shift = Shift::new(data.columns(), nu, n, false);
    let parts = map_parts(parts, |(c, t)| {
        let base = c * CHUNK;
        let (s, _) = shift.chunk(base, t.len());
        chunk(base..base + t.len(), &s, t)
    });
    total(parts.into_iter())
}

/// `r_J · t_J` (`t` is 0 off `J`).
pub(super) fn curvature_pass(t: &[f64], r: &[f64]) -> f64 {
    let parts = map_parts(ranges(t.len()), |range| {
        let (t, r) = (&t[range.clone()], &r[range]);
        Terms::Product(t, r).plain().value()
    });
    total(parts.into_iter())
}

/// What a step changed: the points that entered, and, where no point left
/// or entered, the sums the next iteration reads.
pub(super) struct Update {
    pub entered: usize,
    /// The rows' sums `B^T z` after the step (compensated), whatever it
    /// changed.
    pub rows: Vec<f64>,
    /// `None` where a point left or entered: the contact set changed and
    /// `u` is recomputed from a true product, with the fit's sums (or kept
    /// by [`Changes`]' columns).
    pub sums: Option<UpdateSums>,
    /// Where the step collected them ([`update_pass`]'s `collect`) and the
    /// contact set changed: what `z` differs by from the step along the
    /// direction.
    pub changes: Option<Changes>,
}

/// The rows' magnitudes `|B|^T z` after a step that kept the contact
/// set, and the fit's `Σ_J B u` (its `Σ_J B q` and Gram matrix are the
/// same, to the bit, as before the step: the same terms in the same order).
pub(super) struct UpdateSums {
    pub rows_terms: Vec<f64>,
    pub bu: Vec<f64>,
}

/// A step that changed the contact set at a few points: `z = c z_old - τ
/// t + d`, `d = Σ v_p e_p` over the `columns` `(p, v_p)` (the points
/// clipped or let in, in the order of their index), while `u` took the
/// recurrence everywhere, `u = c u_old - τ r`: `u + M d` is `M z` again.
/// With the rows' magnitudes `|B|^T z` (one row at most).
pub(super) struct Changes {
    pub columns: Vec<(usize, f64)>,
    pub rows_terms: Vec<f64>,
}

struct UpdateParts {
    clipped: usize,
    entered: usize,
    rows: Vec<Compensated>,
    rows_terms: Vec<Lanes>,
    bu: Vec<Compensated>,
    /// The chunk's entries of `d` ([`Changes`]) where collected and at
    /// most the limit.
    columns: Option<Vec<(usize, f64)>>,
}

impl UpdateParts {
    /// The chunks' parts merged into the step's [`Update`] (the sums in
    /// the chunks' order), over `k` rows, the changes where `collect`
    /// (their limit) was given and they are no more.
    fn merge(parts: &[UpdateParts], k: usize, collect: Option<usize>) -> Update {
        let clipped: usize = parts.iter().map(|p| p.clipped).sum();
        let entered: usize = parts.iter().map(|p| p.entered).sum();
        let mut rows = vec![Compensated::default(); k];
        for p in parts {
            for j in 0..k {
                rows[j].merge(&p.rows[j]);
            }
        }
        let rows_terms = || -> Vec<f64> {
            (0..k)
                .map(|j| total(parts.iter().map(|p| p.rows_terms[j].value())))
                .collect()
        };
        let moved = parts
            .iter()
            .any(|p| p.columns.as_ref().is_none_or(|c| !c.is_empty()));
        let changed = clipped + entered > 0 || (collect.is_some() && moved);
        let changes = collect.filter(|_| changed).and_then(|limit| {
            let columns: Option<Vec<_>> = parts.iter().map(|p| p.columns.as_deref()).collect();
            let columns = columns?.concat();
            (columns.len() <= limit).then(|| Changes {
                columns,
                rows_terms: rows_terms(),
            })
        });
        let sums = (!changed).then(|| {
            let mut bu = vec![Compensated::default(); k];
            for p in parts {
                for j in 0..k {
                    bu[j].merge(&p.bu[j]);
                }
            }
            UpdateSums {
                rows_terms: rows_terms(),
                bu: bu.iter().map(Compensated::value).collect(),
            }
        });
        Update {
            entered,
            rows: rows.iter().map(Compensated::value).collect(),
            sums,
            changes,
        }
    }
}

/// What every chunk of a step reads: the data, the border's shift `B λ`,
/// the direction `t` and its product `r`, the pending scale, the step
/// length and whether points may enter; whether a chunk taken before
/// has changed the contact set; and whether the step collects its
/// [`Changes`] (their limit).
struct Stepping<'a, 'c> {
    data: &'a Data<'a>,
    shift: &'a Shift<'c, 'a>,
    t: &'a [f64],
    r: &'a [f64],
    scale: f64,
    tau: f64,
    enter: bool,
    changed: &'a AtomicBool,
    collect: Option<usize>,
}

impl Stepping<'_, '_> {
    /// The step on the chunk `z`, `u` that starts at entry `base`, and its
    /// sums (see [`update_pass`]).
    fn chunk(&self, base: usize, z: &mut [f64], u: &mut [f64]) -> UpdateParts {
        let columns = self.data.columns();
        let k = columns.len();
        let len = z.len();
        let mut p = UpdateParts {
            clipped: 0,
            entered: 0,
            rows: vec![Compensated::default(); k],
            rows_terms: vec![Lanes::default(); k],
            bu: vec![Compensated::default(); k],
            columns: None,
        };
        let (s, _) = self.shift.chunk(base, len);
        let t = &self.t[base..base + len];
        let step = Step {
            c: self.scale,
            t,
            r: &self.r[base..base + len],
            q: &self.data.q[base..base + len],
            s: &s,
            tau: self.tau,
            enter: self.enter,
        };
        // One column's sums in the step's own loop; several, a loop each.
        let row = (k == 1).then(|| columns[0].part(base, len));
        // Collecting, every chunk takes the recurrence: the columns then
        // complete it.
        let recur = self.collect.is_some() || !self.changed.load(Ordering::Relaxed);
        let before = self.collect.map(|_| z.to_vec());
        let stepped = update_chunk(step, (z, u), row, recur);
        if stepped.clipped + stepped.entered > 0 {
            self.changed.store(true, Ordering::Relaxed);
        }
        if let (Some(limit), Some(before)) = (self.collect, before) {
            p.columns = departures(z, &before, t, (self.scale, self.tau), base, limit);
        }
        (p.clipped, p.entered) = (stepped.clipped, stepped.entered);
        if k == 1 {
            (p.rows[0], p.rows_terms[0], p.bu[0]) =
                (stepped.row.sum, stepped.row.terms, stepped.bu);
            return p;
        }
        let (z, u) = (&*z, &*u);
        for j in 0..k {
            p.rows[j] = Terms::Product(columns[j].part(base, len), z).compensated();
        }
        if !recur || p.clipped + p.entered > 0 {
            return p;
        }
        for j in 0..k {
            let b = columns[j].part(base, len);
            p.rows_terms[j] = Terms::AbsProduct(b, z).plain();
            p.bu[j] = Terms::Masked(z, b, u).compensated();
        }
        p
    }
}

/// The entries where the step's `z` departs from the step along the
/// direction, `d_i = z_i - (c before_i - τ t_i)` (the same operations as
/// the step's, so 0 to the bit where it moved a point along `t`): the
/// points clipped at 0 or let in, at index `base + i`; `None` where there
/// are more than `limit`.
fn departures(
    z: &[f64],
    before: &[f64],
    t: &[f64],
    (c, tau): (f64, f64),
    base: usize,
    limit: usize,
) -> Option<Vec<(usize, f64)>> {
    let mut out = Vec::new();
    for i in 0..z.len() {
        let along = c * before[i] - tau * t[i];
        if z[i] != along {
            if out.len() == limit {
                return None;
            }
            out.push((base + i, z[i] - along));
        }
    }
    Some(out)
}

/// The step `z_J = c z_J - τ t_J` from `z` and `u` at their pending scale
/// `c` (stored at scale 1 after it), clipped at 0; a point off `J` with
/// `w_i < 0` (interference) enters with `z_i = -τ w_i` (`-w_i` when `τ =
/// 0`) where `enter` is set, else stays at 0; the product by its
/// recurrence, `u = c u - τ r`. A chunk where a point left or entered
/// skips the sums (the step's are then not read), and the chunks after it
/// skip `u`'s recurrence too: where the contact set changed, `u` is
/// recomputed from a true product before it is read again. Where
/// `collect` gives a limit (one row at most), every chunk takes the
/// recurrence and the step's [`Changes`] are returned where they are at
/// most the limit: `u` is then `M z` once their columns are added.
#[allow(clippy::too_many_arguments)]
pub(super) fn update_pass(
    data: &Data<'_>,
    (z, u, scale): (&mut [f64], &mut [f64], f64),
    t: &[f64],
    r: &[f64],
    lambda: &[f64],
    tau: f64,
    (enter, collect): (bool, Option<usize>),
) -> Update {
    let k = data.columns().len();
    debug_assert!(
        collect.is_none() || k <= 1,
        "changes are collected for one row at most"
    );
    let parts: Vec<_> = z
        .chunks_mut(CHUNK)
        .zip(u.chunks_mut(CHUNK))
        .enumerate()
        .collect();
    let shift = Shift::new(data.columns(), lambda, data.q.len(), false);
    // Once a chunk has clipped or let in points the contact set has
    // changed, and `u` will be recomputed from a true product: the chunks
    // taken after it leave `u` and its sums alone. Which chunks those are
    // depends on the threads' timing; the iterate does not.
    let changed = AtomicBool::new(false);
    let stepping = Stepping {
        data,
        shift: &shift,
        t,
        r,
        scale,
        tau,
        enter,
        changed: &changed,
        collect,
    };
    let parts = map_parts(parts, |(c, (z, u))| stepping.chunk(c * CHUNK, z, u));
    UpdateParts::merge(&parts, k, collect)
}

/// `r = w` on `J`, 0 off it: the residual the preconditioner is applied to
/// (as a pass of its own: the reference of [`measure_pass`]'s).
#[cfg(test)]
pub(super) fn residual_pass(
    data: &Data<'_>,
    (z, u, scale): (&[f64], &[f64], f64),
    r: &mut [f64],
    lambda: &[f64],
) {
    let (columns, q) = (data.columns(), &*data.q);
    let parts: Vec<_> = r.chunks_mut(CHUNK).enumerate().collect();
    let shift = Shift::new(columns, lambda, z.len(), false);
    map_parts(parts, |(c, r)| {
        let base = c * CHUNK;
        let len = r.len();
        let (z, u, q) = (
            &z[base..base + len],
            &u[base..base + len],
            &q[base..base + len],
        );
        let (s, _) = shift.chunk(base, len);
        for i in 0..len {
            r[i] = residual_at([scale * z[i], scale * u[i], q[i], s[i], 0.0]);
        }
    });
}

/// The sums that project the preconditioned residual `p` onto the rows'
/// null space on `J`: `Σ_J B_j p`, `Σ_J B_j r` (compensated) and `r_J · p_J`.
pub(super) struct Projection {
    pub bp: Vec<f64>,
    pub br: Vec<f64>,
    pub rp: f64,
}

/// The [`Projection`]'s sums of `r` (0 off `J`) and `p`.
pub(super) fn projection_pass(data: &Data<'_>, z: &[f64], r: &[f64], p: &[f64]) -> Projection {
    let columns = data.columns();
    let k = columns.len();
    let parts = map_parts(ranges(z.len()), |range| {
        let (z, r, p) = (&z[range.clone()], &r[range.clone()], &p[range.clone()]);
        let len = range.len();
        let mut bp = vec![Compensated::default(); k];
        let mut br = vec![Compensated::default(); k];
        let rp = Terms::MaskedProduct(z, r, p);
        if k == 1 {
            // One column: the three sums in one sweep.
            let b = columns[0].part(range.start, len);
            let (sum_p, sum_r, dot) = masked_pair_and((z, b), (p, r), rp);
            (bp[0], br[0]) = (sum_p, sum_r);
            return (bp, br, dot.value());
        }
        for j in 0..k {
            let b = columns[j].part(range.start, len);
            bp[j] = Terms::Masked(z, b, p).compensated();
            br[j] = Terms::Masked(z, b, r).compensated();
        }
        (bp, br, rp.plain().value())
    });
    let (mut bp, mut br) = (
        vec![Compensated::default(); k],
        vec![Compensated::default(); k],
    );
    for (pb, pr, _) in &parts {
        for j in 0..k {
            bp[j].merge(&pb[j]);
            br[j].merge(&pr[j]);
        }
    }
    Projection {
        bp: bp.iter().map(Compensated::value).collect(),
        br: br.iter().map(Compensated::value).collect(),
        rp: total(parts.iter().map(|p| p.2)),
    }
}

/// The preconditioned direction: `t_J = (p - B μ)_J + β t_J`, `t = 0` off
/// `J`; returns `r_J · t_J` (`r = w` on `J`).
pub(super) fn preconditioned_direction_pass(
    data: &Data<'_>,
    z: &[f64],
    r: &[f64],
    p: &[f64],
    t: &mut [f64],
    mu: &[f64],
    beta: f64,
) -> f64 {
    direction_chunks(data, z.len(), t, mu, |range, s, t| {
        let (z, r, p) = (&z[range.clone()], &r[range.clone()], &p[range]);
        let rule = Rule::Preconditioned { p, s, r, beta };
        direction_chunk(rule, z, t).value()
    })
}

/// The longest step `z_J - τ t_J` that keeps `z >= 0`: `min z_i / t_i`
/// over `z_i > 0`, `t_i > 0` (infinite where no entry decreases).
pub(super) fn boundary_pass(z: &[f64], t: &[f64]) -> f64 {
    let parts = map_parts(ranges(z.len()), |range| {
        let (z, t) = (&z[range.clone()], &t[range]);
        (0..z.len())
            .filter(|&i| z[i] > 0.0 && t[i] > 0.0)
            .fold(f64::INFINITY, |m, i| m.min(z[i] / t[i]))
    });
    parts.into_iter().fold(f64::INFINITY, f64::min)
}

/// The step cut at the boundary: `z = before - τ_b t` on the contact set
/// of `before`, `τ_b` from [`boundary_pass`]; the points that reach the
/// boundary (ratio `before_i / t_i` at most `τ_b`) leave with `z_i = 0`
/// exactly, the others stay positive.
pub(super) fn boundary_step(z: &mut [f64], before: &[f64], t: &[f64], boundary: f64) {
    for i in 0..z.len() {
        let (b, ti) = (before[i], t[i]);
        z[i] = if !(b > 0.0) || (ti > 0.0 && b / ti <= boundary) {
            0.0
        } else {
            (b - boundary * ti).max(0.0)
        };
    }
}

#[cfg(test)]
mod tests;
