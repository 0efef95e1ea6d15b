//! The conjugate gradient's passes over its vectors, chunk by chunk, on
//! all the threads of the current rayon pool, with results that do not
//! depend on how many there are:
//!
//! ```text
//!     Σ_i a_i = Σ_c ( Σ_l ( Σ_{i in chunk c, i ≡ l (mod LANES)} a_i ) )
//! ```
//!
//! the vectors cut into chunks of [`CHUNK`] entries (a fixed length, not a
//! share of the threads), each chunk's sum kept in [`LANES`] interleaved
//! partial sums, the lanes then the chunks added in their order. A chunk's
//! sums ([`Terms`]) run in vector registers, the widest the processor has
//! (`pulp`'s dispatch: AVX-512, else AVX2, else its scalar path): a group
//! of [`LANES`] terms fills `LANES / width` registers, so that each lane
//! adds the same terms in the same order on any processor, and the sums
//! are the same to the bit with or without vector instructions. Which thread adds a chunk
//! changes nothing: every sum is the same to the bit on one thread or
//! many. Maxima and minima are exact in any order. Sums that must be
//! accurate whatever the number of terms (the border's fit from 10^5 to
//! 10^6 nearly equal gaps) are compensated ([`Compensated`]: Knuth's
//! two-sum in every lane).

use rayon::prelude::*;

/// Entries of a chunk: 32 kB of a vector, a few microseconds of work, so
/// that a pass of 10^5 entries has a few dozen chunks to share.
pub(super) const CHUNK: usize = 4096;

/// Interleaved partial sums in a chunk (eight doubles: one AVX-512
/// register, two AVX2 ones).
pub(super) const LANES: usize = 8;

/// Runs `body` on every part, on the pool's threads when there are several
/// parts and threads (each part is one chunk of the vectors), and returns
/// the results in the parts' order. One part, or one thread, runs on the
/// caller's thread: no hand-over to the pool.
pub(super) fn map_parts<P: Send, T: Send>(
    parts: Vec<P>,
    body: impl Fn(P) -> T + Sync + Send,
) -> Vec<T> {
    if parts.len() > 1 && rayon::current_num_threads() > 1 {
        parts.into_par_iter().map(body).collect()
    } else {
        parts.into_iter().map(body).collect()
    }
}

/// A plain sum in [`LANES`] interleaved partial sums.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Lanes(pub(super) [f64; LANES]);

impl Lanes {
    /// Adds `v` to lane `l`.
    #[inline(always)]
    pub(super) fn add(&mut self, l: usize, v: f64) {
        self.0[l] += v;
    }

    /// The lanes' sum, in lane order.
    pub(super) fn value(&self) -> f64 {
        self.0.iter().fold(0.0, |a, &v| a + v)
    }
}

/// Sums the chunks' values in chunk order.
pub(super) fn total(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |a, v| a + v)
}

/// A compensated sum in [`LANES`] interleaved lanes: each lane a running
/// sum and the rounding errors of its additions (Knuth's two-sum, exact),
/// accurate to a few units of rounding of the result whatever the number of
/// terms.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Compensated {
    sum: [f64; LANES],
    carry: [f64; LANES],
}

/// `a + b` as `(s, e)` with `s + e = a + b` exactly (Knuth's two-sum).
#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

impl Compensated {
    /// The sum whose lanes hold `sum` and `carry`.
    pub(super) fn from_lanes(sum: [f64; LANES], carry: [f64; LANES]) -> Self {
        Self { sum, carry }
    }

    /// Adds `v` to lane `l`.
    #[inline(always)]
    pub(super) fn add(&mut self, l: usize, v: f64) {
        let (s, e) = two_sum(self.sum[l], v);
        self.sum[l] = s;
        self.carry[l] += e;
    }

    /// Adds another compensated sum (lane by lane).
    pub(super) fn merge(&mut self, other: &Compensated) {
        for l in 0..LANES {
            let (s, e) = two_sum(self.sum[l], other.sum[l]);
            self.sum[l] = s;
            self.carry[l] += e + other.carry[l];
        }
    }

    /// The sum: the lanes added by two-sums in lane order, then the carries.
    pub(super) fn value(&self) -> f64 {
        let (mut sum, mut carry) = (0.0, 0.0);
        for l in 0..LANES {
            let (s, e) = two_sum(sum, self.sum[l]);
            sum = s;
            carry += e + self.carry[l];
        }
        sum + carry
    }
}

/// The terms of a sum over a chunk's entries `i` (slices of one length).
#[derive(Clone, Copy)]
pub(super) enum Terms<'a> {
    /// `a_i b_i`.
    Product(&'a [f64], &'a [f64]),
    /// `|a_i b_i|`.
    AbsProduct(&'a [f64], &'a [f64]),
    /// `(a_i if z_i > 0 else 0) b_i`, as `Masked(z, a, b)`.
    Masked(&'a [f64], &'a [f64], &'a [f64]),
    /// `a_i b_i if z_i > 0 else 0`, as `MaskedProduct(z, a, b)`.
    MaskedProduct(&'a [f64], &'a [f64], &'a [f64]),
}

impl Terms<'_> {
    fn len(&self) -> usize {
        match *self {
            Terms::Product(a, _) | Terms::AbsProduct(a, _) => a.len(),
            Terms::Masked(z, ..) | Terms::MaskedProduct(z, ..) => z.len(),
        }
    }

    /// Term `i`, one entry at a time (the tail of a chunk).
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        match *self {
            Terms::Product(a, b) => a[i] * b[i],
            Terms::AbsProduct(a, b) => (a[i] * b[i]).abs(),
            Terms::Masked(z, a, b) => (if z[i] > 0.0 { a[i] } else { 0.0 }) * b[i],
            Terms::MaskedProduct(z, a, b) => {
                if z[i] > 0.0 {
                    a[i] * b[i]
                } else {
                    0.0
                }
            }
        }
    }

    /// The sum in [`LANES`] interleaved partial sums, the groups of
    /// [`LANES`] terms in vector registers (the widest the processor has:
    /// `pulp`'s dispatch), each lane the same additions in the same order
    /// as [`Lanes::add`] term by term.
    pub(super) fn plain(self) -> Lanes {
        pulp::Arch::new()
            .dispatch(Sum {
                terms: self,
                compensated: false,
            })
            .0
    }

    /// The sum compensated in [`LANES`] interleaved lanes, in vector
    /// registers, each lane the same operations in the same order as
    /// [`Compensated::add`] term by term.
    pub(super) fn compensated(self) -> Compensated {
        pulp::Arch::new()
            .dispatch(Sum {
                terms: self,
                compensated: true,
            })
            .1
    }
}

/// A sum of [`Terms`] in vector registers: plain, or compensated.
struct Sum<'a> {
    terms: Terms<'a>,
    compensated: bool,
}

/// The full groups of `v` as vector registers (the tail left out).
#[inline(always)]
pub(super) fn registers<S: pulp::Simd>(v: &[f64]) -> &[S::f64s] {
    S::as_simd_f64s(&v[..v.len() - v.len() % LANES]).0
}

/// Registers `r` of `[S::f64s; LANES]` (the first `LANES / S::F64_LANES`
/// hold the lanes) as [`LANES`] doubles, lane order.
#[inline(always)]
pub(super) fn to_lanes<S: pulp::Simd>(v: &[S::f64s; LANES]) -> [f64; LANES] {
    let mut out = [0.0; LANES];
    let w = S::F64_LANES;
    for r in 0..LANES / w {
        let part: &[f64] = pulp::bytemuck::cast_slice(std::slice::from_ref(&v[r]));
        out[r * w..(r + 1) * w].copy_from_slice(part);
    }
    out
}

impl pulp::WithSimd for Sum<'_> {
    type Output = (Lanes, Compensated);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) -> (Lanes, Compensated) {
        let zero = simd.splat_f64s(0.0);
        let positive = |z: S::f64s| simd.greater_than_f64s(z, zero);
        let (sum, carry) = match self.terms {
            Terms::Product(a, b) => {
                let (a, b) = (registers::<S>(a), registers::<S>(b));
                self.registers(simd, a.len(), |k| simd.mul_f64s(a[k], b[k]))
            }
            Terms::AbsProduct(a, b) => {
                let (a, b) = (registers::<S>(a), registers::<S>(b));
                self.registers(simd, a.len(), |k| simd.abs_f64s(simd.mul_f64s(a[k], b[k])))
            }
            Terms::Masked(z, a, b) => {
                let (z, a, b) = (registers::<S>(z), registers::<S>(a), registers::<S>(b));
                self.registers(simd, z.len(), |k| {
                    simd.mul_f64s(simd.select_f64s(positive(z[k]), a[k], zero), b[k])
                })
            }
            Terms::MaskedProduct(z, a, b) => {
                let (z, a, b) = (registers::<S>(z), registers::<S>(a), registers::<S>(b));
                self.registers(simd, z.len(), |k| {
                    simd.select_f64s(positive(z[k]), simd.mul_f64s(a[k], b[k]), zero)
                })
            }
        };
        let len = self.terms.len();
        let full = len - len % LANES;
        let mut plain = Lanes(to_lanes::<S>(&sum));
        let mut comp = Compensated {
            sum: plain.0,
            carry: to_lanes::<S>(&carry),
        };
        for i in full..len {
            let v = self.terms.at(i);
            if self.compensated {
                comp.add(i - full, v);
            } else {
                plain.add(i - full, v);
            }
        }
        (plain, comp)
    }
}

/// Three sums over a chunk in one sweep: `Σ (b_i if z_i > 0 else 0) x_i`
/// and the same of `y` (compensated: [`Terms::Masked`]), and `third`
/// (plain), each lane the same operations in the same order as the sums
/// one at a time.
pub(super) fn masked_pair_and(
    (z, b): (&[f64], &[f64]),
    (x, y): (&[f64], &[f64]),
    third: Terms<'_>,
) -> (Compensated, Compensated, Lanes) {
    pulp::Arch::new().dispatch(MaskedPair { z, b, x, y, third })
}

struct MaskedPair<'a> {
    z: &'a [f64],
    b: &'a [f64],
    x: &'a [f64],
    y: &'a [f64],
    third: Terms<'a>,
}

impl pulp::WithSimd for MaskedPair<'_> {
    type Output = (Compensated, Compensated, Lanes);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) -> Self::Output {
        let zero = simd.splat_f64s(0.0);
        let positive = |z: S::f64s| simd.greater_than_f64s(z, zero);
        let ([xs, xc, ys, yc], sums) = match self.third {
            Terms::Product(a, b) => {
                let (a, b) = (registers::<S>(a), registers::<S>(b));
                self.sweep(simd, |k| simd.mul_f64s(a[k], b[k]))
            }
            Terms::AbsProduct(a, b) => {
                let (a, b) = (registers::<S>(a), registers::<S>(b));
                self.sweep(simd, |k| simd.abs_f64s(simd.mul_f64s(a[k], b[k])))
            }
            Terms::Masked(z, a, b) => {
                let (z, a, b) = (registers::<S>(z), registers::<S>(a), registers::<S>(b));
                self.sweep(simd, |k| {
                    simd.mul_f64s(simd.select_f64s(positive(z[k]), a[k], zero), b[k])
                })
            }
            Terms::MaskedProduct(z, a, b) => {
                let (z, a, b) = (registers::<S>(z), registers::<S>(a), registers::<S>(b));
                self.sweep(simd, |k| {
                    simd.select_f64s(positive(z[k]), simd.mul_f64s(a[k], b[k]), zero)
                })
            }
        };
        let lanes = to_lanes::<S>;
        let mut first = Compensated::from_lanes(lanes(&xs), lanes(&xc));
        let mut second = Compensated::from_lanes(lanes(&ys), lanes(&yc));
        let mut third = Lanes(lanes(&sums));
        let len = self.z.len();
        let full = len - len % LANES;
        let (z, b) = (self.z, self.b);
        for i in full..len {
            let l = i - full;
            first.add(l, Terms::Masked(z, b, self.x).at(i));
            second.add(l, Terms::Masked(z, b, self.y).at(i));
            third.add(l, self.third.at(i));
        }
        (first, second, third)
    }
}

impl MaskedPair<'_> {
    /// The registers of the two compensated sums (sum and carry of each)
    /// and of the plain one, whose term of register `k` is `third(k)`.
    #[inline(always)]
    fn sweep<S: pulp::Simd>(
        &self,
        simd: S,
        third: impl Fn(usize) -> S::f64s,
    ) -> ([[S::f64s; LANES]; 4], [S::f64s; LANES]) {
        let regs = LANES / S::F64_LANES;
        let zero = simd.splat_f64s(0.0);
        let (zs, bs) = (registers::<S>(self.z), registers::<S>(self.b));
        let (xs, ys) = (registers::<S>(self.x), registers::<S>(self.y));
        let mut acc = [[zero; LANES]; 4];
        let mut plain = [zero; LANES];
        let mut k = 0;
        while k < zs.len() {
            for r in 0..regs {
                let on = simd.greater_than_f64s(zs[k + r], zero);
                let masked = simd.select_f64s(on, bs[k + r], zero);
                let [xs_, xc, ys_, yc] = &mut acc;
                add_compensated(
                    simd,
                    (&mut xs_[r], &mut xc[r]),
                    simd.mul_f64s(masked, xs[k + r]),
                );
                add_compensated(
                    simd,
                    (&mut ys_[r], &mut yc[r]),
                    simd.mul_f64s(masked, ys[k + r]),
                );
                plain[r] = simd.add_f64s(plain[r], third(k + r));
            }
            k += regs;
        }
        (acc, plain)
    }
}

/// Adds `v` to a compensated sum's register `(sum, carry)`: Knuth's
/// two-sum lane by lane, the operations of [`Compensated::add`].
#[inline(always)]
pub(super) fn add_compensated<S: pulp::Simd>(
    simd: S,
    (sum, carry): (&mut S::f64s, &mut S::f64s),
    v: S::f64s,
) {
    let a = *sum;
    let s = simd.add_f64s(a, v);
    let bb = simd.sub_f64s(s, a);
    let e = simd.add_f64s(simd.sub_f64s(a, simd.sub_f64s(s, bb)), simd.sub_f64s(v, bb));
    *sum = s;
    *carry = simd.add_f64s(*carry, e);
}

impl Sum<'_> {
    /// The lanes' sums (and, compensated, carries) of the terms `term(k)`
    /// of registers `k` in `0..count`, register `k` into lanes `(k mod
    /// LANES / S::F64_LANES) S::F64_LANES ..`.
    #[inline(always)]
    fn registers<S: pulp::Simd>(
        &self,
        simd: S,
        count: usize,
        term: impl Fn(usize) -> S::f64s,
    ) -> ([S::f64s; LANES], [S::f64s; LANES]) {
        let regs = LANES / S::F64_LANES;
        let zero = simd.splat_f64s(0.0);
        let (mut sum, mut carry) = ([zero; LANES], [zero; LANES]);
        let mut k = 0;
        if self.compensated {
            while k < count {
                for r in 0..regs {
                    add_compensated(simd, (&mut sum[r], &mut carry[r]), term(k + r));
                }
                k += regs;
            }
        } else {
            while k < count {
                for r in 0..regs {
                    sum[r] = simd.add_f64s(sum[r], term(k + r));
                }
                k += regs;
            }
        }
        (sum, carry)
    }
}

/// The instruction sets a test runs a kernel on (`arch.dispatch(op)`):
/// `pulp`'s scalar path, and AVX2 and AVX-512 where the processor has
/// them. `pulp::Arch::new` picks the widest; every one must give the same
/// bits.
#[cfg(test)]
pub(super) fn arches() -> Vec<pulp::Arch> {
    #[allow(unused_mut)]
    let mut all = vec![pulp::Arch::Scalar];
    #[cfg(target_arch = "x86_64")]
    {
        all.extend(pulp::x86::V3::try_new().map(pulp::Arch::V3));
        all.extend(pulp::x86::V4::try_new().map(pulp::Arch::V4));
    }
    all
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entry-by-entry sums of `terms`: the reference the vector sums keep.
    fn by_entry(terms: Terms<'_>) -> (Lanes, Compensated) {
        let (mut plain, mut comp) = (Lanes::default(), Compensated::default());
        for i in 0..terms.len() {
            plain.add(i % LANES, terms.at(i));
            comp.add(i % LANES, terms.at(i));
        }
        (plain, comp)
    }

    /// The sums of `terms` on `arch`.
    fn sums_on(arch: pulp::Arch, terms: Terms<'_>) -> (Lanes, Compensated) {
        let plain = Sum {
            terms,
            compensated: false,
        };
        let comp = Sum {
            terms,
            compensated: true,
        };
        (arch.dispatch(plain).0, arch.dispatch(comp).1)
    }

    fn bits(l: &Lanes, c: &Compensated) -> Vec<u64> {
        l.0.iter()
            .chain(&c.sum)
            .chain(&c.carry)
            .map(|v| v.to_bits())
            .collect()
    }

    #[test]
    fn a_compensated_sum_keeps_what_a_plain_one_loses() {
        // In lane 0: 1, then 10^5 terms of 1e-17 (each below half an ulp
        // of 1), then -1: a plain sum gives 0, the compensated one 1e-12.
        let m = 100_002;
        let a: Vec<f64> = (0..LANES * m)
            .map(|i| match (i % LANES, i / LANES) {
                (0, 0) => 1.0,
                (0, j) if j == m - 1 => -1.0,
                (0, _) => 1e-17,
                _ => 0.0,
            })
            .collect();
        let ones = vec![1.0; a.len()];
        let c = Terms::Product(&a, &ones).compensated();
        assert!((c.value() / 1e-12 - 1.0).abs() < 1e-10, "{}", c.value());
        assert_eq!(Terms::Product(&a, &ones).plain().value(), 0.0);
        // Across lanes (the tail): 1e16 + 1 - 1e16.
        let three = [1e16, 1.0, -1e16];
        let c = Terms::Product(&three, &[1.0; 3]).compensated();
        assert_eq!(
            (c.value(), Terms::Product(&three, &[1.0; 3]).plain().value()),
            (1.0, 0.0)
        );
        // Merged chunks add up as one.
        let mut b = Compensated::default();
        b.merge(&c);
        b.merge(&c);
        assert_eq!(b.value(), 2.0);
    }

    #[test]
    fn vector_sums_keep_the_bits_of_sums_entry_by_entry() {
        let h = |i: usize, k: usize| {
            ((i as f64 * 0.618_033_988_749_895 + k as f64 * 0.3).fract() - 0.4)
                * 1e3f64.powi((i % 7) as i32)
        };
        for len in [0, 5, LANES, 8 * LANES + 3, CHUNK + 7] {
            let z: Vec<f64> = (0..len).map(|i| h(i, 0)).collect();
            let a: Vec<f64> = (0..len).map(|i| h(i, 1)).collect();
            let b: Vec<f64> = (0..len).map(|i| h(i, 2)).collect();
            for terms in [
                Terms::Product(&a, &b),
                Terms::AbsProduct(&a, &b),
                Terms::Masked(&z, &a, &b),
                Terms::MaskedProduct(&z, &a, &b),
            ] {
                let reference = by_entry(terms);
                let reference = bits(&reference.0, &reference.1);
                let vector = bits(&terms.plain(), &terms.compensated());
                assert_eq!(vector, reference, "{len} entries");
                for arch in arches() {
                    let (plain, comp) = sums_on(arch, terms);
                    assert_eq!(bits(&plain, &comp), reference, "{len} entries, {arch:?}");
                }
            }
        }
    }

    #[test]
    fn three_sums_in_one_sweep_keep_the_bits_of_each_alone() {
        let h =
            |i: usize, k: usize| (i as f64 * 0.618_033_988_749_895 + k as f64 * 0.3).fract() - 0.4;
        for len in [0, 5, LANES, 8 * LANES + 3, CHUNK + 7] {
            let v: Vec<Vec<f64>> = (0..5)
                .map(|k| (0..len).map(|i| h(i, k)).collect())
                .collect();
            let (z, b, x, y) = (&v[0][..], &v[1][..], &v[2][..], &v[3][..]);
            for third in [
                Terms::Masked(z, b, b),
                Terms::MaskedProduct(z, x, y),
                Terms::Product(x, y),
                Terms::AbsProduct(x, y),
            ] {
                let alone = (
                    Terms::Masked(z, b, x).compensated().value().to_bits(),
                    Terms::Masked(z, b, y).compensated().value().to_bits(),
                    third.plain().value().to_bits(),
                );
                let bits = |(p, q, r): (Compensated, Compensated, Lanes)| {
                    (
                        p.value().to_bits(),
                        q.value().to_bits(),
                        r.value().to_bits(),
                    )
                };
                assert_eq!(bits(masked_pair_and((z, b), (x, y), third)), alone, "{len}");
                for arch in arches() {
                    let pair = MaskedPair { z, b, x, y, third };
                    assert_eq!(bits(arch.dispatch(pair)), alone, "{len}, {arch:?}");
                }
            }
        }
    }

    #[test]
    fn parts_keep_their_order_on_any_pool() {
        let parts: Vec<usize> = (0..100).collect();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let out = pool.install(|| map_parts(parts.clone(), |p| p * 2));
            assert_eq!(out, (0..100).map(|p| p * 2).collect::<Vec<_>>());
        }
    }
}
