//! The passes of one iteration over the method's vectors (`z`, `u = M z`,
//! the direction `t`, the product `r = M t`) and the data (`q`, `B`), each
//! a single sweep, chunk by chunk ([`passes`](super::passes): the same
//! bits on any number of threads):
//!
//! ```text
//!     fit:        Σ_J B u,  Σ_J B q,  B_J^T B_J                     (after a true product)
//!     measure:    w = u + q - B λ;  min w, max |z w|, the scales, ‖w_J‖², B^T z
//!     direction:  t_J = w_J + β t_J, t = 0 off J;  w_J · t_J
//!     curvature:  r_J · t_J
//!     update:     z_J -= τ t_J (clipped at 0), entries off J;  u -= τ r;  Σ_J' B u, Σ_J' B q, B^T z
//! ```
//!
//! with `J = {i : z_i > 0}`. The measure pass also applies a pending scale
//! of `z` and `u` (the one-row restoration's, `M (c z) = c u`).

use std::borrow::Cow;

use faer::{ColRef, Mat, MatRef};

use super::passes::{CHUNK, Compensated, LANES, Lanes, for_lanes, map_parts, total};

/// `q` and the border's columns as slices (copied where a column is not
/// contiguous).
pub(super) struct Data<'a> {
    pub q: Cow<'a, [f64]>,
    pub border: Vec<Cow<'a, [f64]>>,
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
                .map(|j| slice_of(border.col(j)))
                .collect(),
        }
    }

    fn columns(&self) -> Vec<&[f64]> {
        self.border.iter().map(|c| &**c).collect()
    }
}

/// The chunk ranges of `0..n`.
fn ranges(n: usize) -> Vec<std::ops::Range<usize>> {
    (0..n.div_ceil(CHUNK))
        .map(|c| c * CHUNK..((c + 1) * CHUNK).min(n))
        .collect()
}

/// The border's shift `(B λ)_i` and the magnitude of its terms.
#[inline(always)]
fn shift(columns: &[&[f64]], lambda: &[f64], i: usize) -> (f64, f64) {
    let (mut s, mut terms) = (0.0, 0.0);
    for (b, l) in columns.iter().zip(lambda) {
        let v = b[i] * l;
        s += v;
        terms += v.abs();
    }
    (s, terms)
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
        let base = range.start;
        for_lanes(range.len(), |i, l| {
            let i = base + i;
            let on = z[i] > 0.0;
            let mut e = 0;
            for a in 0..k {
                let ba = if on { columns[a][i] } else { 0.0 };
                p.bu[a].add(l, ba * u[i]);
                p.bq[a].add(l, ba * q[i]);
                for b in 0..=a {
                    p.gram[e].add(l, ba * columns[b][i]);
                    e += 1;
                }
            }
        });
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

/// Applies the pending `scale` to `z` and `u`, then measures `w = u + q -
/// B λ` (see [`Measures`]).
pub(super) fn measure_pass(
    data: &Data<'_>,
    z: &mut [f64],
    u: &mut [f64],
    scale: f64,
    lambda: &[f64],
) -> Measures {
    let (columns, q) = (data.columns(), &*data.q);
    let k = columns.len();
    let parts: Vec<_> = z
        .chunks_mut(CHUNK)
        .zip(u.chunks_mut(CHUNK))
        .enumerate()
        .collect();
    let parts = map_parts(parts, |(c, (z, u))| {
        let base = c * CHUNK;
        let mut p = MeasureParts::new(k);
        let mut bad = false;
        for_lanes(z.len(), |i, l| {
            if scale != 1.0 {
                z[i] *= scale;
                u[i] *= scale;
            }
            let (s, s_terms) = shift(&columns, lambda, base + i);
            let qi = q[base + i];
            let w = (u[i] + qi) - s;
            let zi = z[i];
            bad |= !w.is_finite();
            let cw = (zi * w).abs();
            let terms = u[i].abs() + qi.abs() + s_terms;
            p.min_w[l] = if w < p.min_w[l] { w } else { p.min_w[l] };
            p.comp[l] = if cw > p.comp[l] { cw } else { p.comp[l] };
            p.w_scale[l] = if terms > p.w_scale[l] {
                terms
            } else {
                p.w_scale[l]
            };
            p.z_scale[l] = if zi > p.z_scale[l] { zi } else { p.z_scale[l] };
            p.g.add(l, if zi > 0.0 { w * w } else { 0.0 });
            for j in 0..k {
                let v = columns[j][base + i] * zi;
                p.rows[j].add(l, v);
                p.rows_terms[j].add(l, v.abs());
            }
        });
        p.finite = !bad;
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
        rows: rows.iter().map(Compensated::value).collect(),
        rows_terms: (0..k)
            .map(|j| total(parts.iter().map(|p| p.rows_terms[j].value())))
            .collect(),
        finite: parts.iter().all(|p| p.finite),
    }
}

/// `t_J = w_J + β t_J`, `t = 0` off `J`; returns `w_J · t_J`.
pub(super) fn direction_pass(
    data: &Data<'_>,
    z: &[f64],
    u: &[f64],
    t: &mut [f64],
    lambda: &[f64],
    beta: f64,
) -> f64 {
    let (columns, q) = (data.columns(), &*data.q);
    let parts: Vec<_> = t.chunks_mut(CHUNK).enumerate().collect();
    let parts = map_parts(parts, |(c, t)| {
        let base = c * CHUNK;
        let mut num = Lanes::default();
        for_lanes(t.len(), |i, l| {
            let g = base + i;
            let w = (u[g] + q[g]) - shift(&columns, lambda, g).0;
            let next = if z[g] > 0.0 { w + beta * t[i] } else { 0.0 };
            t[i] = next;
            num.add(l, w * next);
        });
        num.value()
    });
    total(parts.into_iter())
}

/// `r_J · t_J` (`t` is 0 off `J`).
pub(super) fn curvature_pass(t: &[f64], r: &[f64]) -> f64 {
    let parts = map_parts(ranges(t.len()), |range| {
        let mut den = Lanes::default();
        let (t, r) = (&t[range.clone()], &r[range]);
        den.add_all(t.len(), |i| t[i] * r[i]);
        den.value()
    });
    total(parts.into_iter())
}

/// What a step changed: the points clipped to 0 and the points that
/// entered, the rows' sums `B^T z` and `|B|^T z`, and the fit's sums over
/// the new contact set (valid for the next iteration when no point left or
/// entered: the Gram matrix is then the same).
pub(super) struct Update {
    pub clipped: usize,
    pub entered: usize,
    pub rows: Vec<f64>,
    pub rows_terms: Vec<f64>,
    pub bu: Vec<f64>,
    pub bq: Vec<f64>,
}

struct UpdateParts {
    clipped: usize,
    entered: usize,
    rows: Vec<Compensated>,
    rows_terms: Vec<Lanes>,
    fit: FitParts,
}

/// The step `z_J -= τ t_J`, clipped at 0; a point off `J` with `w_i < 0`
/// (interference) enters with `z_i = -τ w_i` (`-w_i` when `τ = 0`); the
/// product by its recurrence, `u -= τ r`.
#[allow(clippy::too_many_arguments)]
pub(super) fn update_pass(
    data: &Data<'_>,
    z: &mut [f64],
    u: &mut [f64],
    t: &[f64],
    r: &[f64],
    lambda: &[f64],
    tau: f64,
) -> Update {
    let (columns, q) = (data.columns(), &*data.q);
    let k = columns.len();
    let parts: Vec<_> = z
        .chunks_mut(CHUNK)
        .zip(u.chunks_mut(CHUNK))
        .enumerate()
        .collect();
    let parts = map_parts(parts, |(c, (z, u))| {
        let base = c * CHUNK;
        let mut p = UpdateParts {
            clipped: 0,
            entered: 0,
            rows: vec![Compensated::default(); k],
            rows_terms: vec![Lanes::default(); k],
            fit: FitParts::new(k),
        };
        for_lanes(z.len(), |i, l| {
            let g = base + i;
            let old = z[i];
            let next = if old > 0.0 {
                let v = old - tau * t[g];
                p.clipped += usize::from(!(v > 0.0));
                v.max(0.0)
            } else {
                let w = (u[i] + q[g]) - shift(&columns, lambda, g).0;
                if w < 0.0 {
                    p.entered += 1;
                    if tau > 0.0 { -tau * w } else { -w }
                } else {
                    old
                }
            };
            z[i] = next;
            u[i] -= tau * r[g];
            let on = next > 0.0;
            for j in 0..k {
                let b = columns[j][g];
                let v = b * next;
                p.rows[j].add(l, v);
                p.rows_terms[j].add(l, v.abs());
                let b = if on { b } else { 0.0 };
                p.fit.bu[j].add(l, b * u[i]);
                p.fit.bq[j].add(l, b * q[g]);
            }
        });
        p
    });
    let fits: Vec<FitParts> = parts.iter().map(|p| p.fit.clone()).collect();
    let fit = FitParts::merge(&fits, k);
    let mut rows = vec![Compensated::default(); k];
    for p in &parts {
        for j in 0..k {
            rows[j].merge(&p.rows[j]);
        }
    }
    Update {
        clipped: parts.iter().map(|p| p.clipped).sum(),
        entered: parts.iter().map(|p| p.entered).sum(),
        rows: rows.iter().map(Compensated::value).collect(),
        rows_terms: (0..k)
            .map(|j| total(parts.iter().map(|p| p.rows_terms[j].value())))
            .collect(),
        bu: fit.bu,
        bq: fit.bq,
    }
}

/// `z *= scale` (a pending scale applied before a true product).
pub(super) fn scale_pass(z: &mut [f64], scale: f64) {
    let parts: Vec<_> = z.chunks_mut(CHUNK).collect();
    map_parts(parts, |z| z.iter_mut().for_each(|v| *v *= scale));
}
