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
//! partial sums (which the compiler turns into vector instructions), the
//! lanes then the chunks added in their order. Which thread adds a chunk
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

/// Calls `f(i, l)` for `i` in `0..len`, `l = i mod LANES` its lane, a
/// group of [`LANES`] at a time (the form the compiler vectorizes).
#[inline(always)]
pub(super) fn for_lanes(len: usize, mut f: impl FnMut(usize, usize)) {
    let full = len - len % LANES;
    let mut i = 0;
    while i < full {
        for l in 0..LANES {
            f(i + l, l);
        }
        i += LANES;
    }
    for l in 0..len - full {
        f(full + l, l);
    }
}

/// A plain sum in [`LANES`] interleaved partial sums.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Lanes([f64; LANES]);

impl Lanes {
    /// Adds `v` to lane `l`.
    #[inline(always)]
    pub(super) fn add(&mut self, l: usize, v: f64) {
        self.0[l] += v;
    }

    /// Adds `f(i)` for `i` in `0..len`, `i` to lane `i mod LANES`: a
    /// group's terms formed first, then added in one straight run (the
    /// form the compiler turns into vector additions).
    #[inline(always)]
    pub(super) fn add_all(&mut self, len: usize, f: impl Fn(usize) -> f64) {
        in_groups(len, f, |l, v| self.add(l, v));
    }

    /// The lanes' sum, in lane order.
    pub(super) fn value(&self) -> f64 {
        self.0.iter().fold(0.0, |a, &v| a + v)
    }
}

/// Calls `add(i mod LANES, f(i))` for `i` in `0..len`, in order, a
/// group of [`LANES`] terms formed first and then added in one straight
/// run: the form the compiler turns into vector instructions, with the
/// same operations in the same order as term by term.
#[inline(always)]
fn in_groups(len: usize, f: impl Fn(usize) -> f64, mut add: impl FnMut(usize, f64)) {
    let full = len - len % LANES;
    let mut i = 0;
    while i < full {
        let v: [f64; LANES] = std::array::from_fn(|l| f(i + l));
        for (l, &v) in v.iter().enumerate() {
            add(l, v);
        }
        i += LANES;
    }
    for l in 0..len - full {
        add(l, f(full + l));
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
    /// Adds `v` to lane `l`.
    #[inline(always)]
    pub(super) fn add(&mut self, l: usize, v: f64) {
        let (s, e) = two_sum(self.sum[l], v);
        self.sum[l] = s;
        self.carry[l] += e;
    }

    /// Adds `f(i)` for `i` in `0..len`, `i` to lane `i mod LANES`: a
    /// group's terms formed first, then added by two-sums in one straight
    /// run (the form the compiler turns into vector instructions; the same
    /// operations in the same order as [`add`](Self::add) term by term).
    #[inline(always)]
    pub(super) fn add_all(&mut self, len: usize, f: impl Fn(usize) -> f64) {
        in_groups(len, f, |l, v| self.add(l, v));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_compensated_sum_keeps_what_a_plain_one_loses() {
        // In one lane: 1, then 10^5 terms of 1e-17 (each below half an ulp
        // of 1), then -1: a plain sum gives 0, the compensated one 1e-12.
        let m = 100_002;
        let term = |i: usize| match (i % LANES, i / LANES) {
            (0, 0) => 1.0,
            (0, j) if j == m - 1 => -1.0,
            (0, _) => 1e-17,
            _ => 0.0,
        };
        let (mut c, mut plain) = (Compensated::default(), Lanes::default());
        for_lanes(LANES * m, |i, l| c.add(l, term(i)));
        plain.add_all(LANES * m, term);
        assert!((c.value() / 1e-12 - 1.0).abs() < 1e-10, "{}", c.value());
        assert_eq!(plain.value(), 0.0);
        // Across lanes: 1e16 + 1 - 1e16.
        let (mut c, mut plain) = (Compensated::default(), Lanes::default());
        let three = [1e16, 1.0, -1e16];
        for_lanes(3, |i, l| c.add(l, three[i]));
        plain.add_all(3, |i| three[i]);
        assert_eq!((c.value(), plain.value()), (1.0, 0.0));
        // Merged chunks add up as one.
        let mut a = Compensated::default();
        for_lanes(3, |i, l| a.add(l, three[i]));
        let mut b = Compensated::default();
        b.merge(&a);
        b.merge(&a);
        assert_eq!(b.value(), 2.0);
    }

    #[test]
    fn sums_by_groups_keep_the_bits_of_sums_term_by_term() {
        let term = |i: usize| {
            ((i as f64 * 0.618_033_988_749_895).fract() - 0.5) * 1e3f64.powi((i % 7) as i32)
        };
        for len in [0, 5, LANES, 8 * LANES + 3] {
            let (mut grouped, mut single) = (Compensated::default(), Compensated::default());
            grouped.add_all(len, term);
            for_lanes(len, |i, l| single.add(l, term(i)));
            assert_eq!(grouped.value().to_bits(), single.value().to_bits());
            let mut plain = Lanes::default();
            plain.add_all(len, term);
            let mut by_lane = [0.0f64; LANES];
            (0..len).for_each(|i| by_lane[i % LANES] += term(i));
            let expected = by_lane.iter().fold(0.0, |a, &v| a + v);
            assert_eq!(plain.value().to_bits(), expected.to_bits());
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
