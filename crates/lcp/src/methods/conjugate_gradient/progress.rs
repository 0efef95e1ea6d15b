//! When a conjugate gradient stops ([`Progress`]: at a target fraction of
//! the certificate's tolerance, or stalled on the rounding floor of sums of
//! n terms, `ROUNDING_FLOOR eps sqrt(n)`), and its step length
//! `τ = num / den` with `den = p · M p > 0`.

use crate::statistics::Breakdown;
use crate::tolerance::{ITERATIVE_STOP, ROUNDING_FLOOR, STALL_WINDOW, STALLED_STOP};

/// When a conjugate gradient stops: its residual `c` (relative to the
/// data's scale) at most [`ITERATIVE_STOP`] times the certificate's
/// tolerance, or stalled: at most [`STALLED_STOP`] times the tolerance,
/// below the rounding floor of sums of n terms, and not halved over the
/// last [`STALL_WINDOW`] iterations (at the rounding floor of very large
/// sums the residuals creep down for hundreds of iterations: the iterate
/// is then as good as the arithmetic allows).
pub(super) struct Progress {
    target: f64,
    stalled_target: f64,
    /// `ROUNDING_FLOOR eps sqrt(n)`: only there is a stall the
    /// arithmetic's, not a slow convergence.
    floor: f64,
    /// The residual at the start of the current window.
    checkpoint: f64,
    stalled: bool,
}

impl Progress {
    pub(super) fn new(tolerance: f64, n: usize) -> Self {
        Self {
            target: ITERATIVE_STOP * tolerance,
            stalled_target: STALLED_STOP * tolerance,
            floor: ROUNDING_FLOOR * f64::EPSILON * (n as f64).sqrt(),
            checkpoint: f64::INFINITY,
            stalled: false,
        }
    }

    /// Whether the iterate of `iteration` (counted from 0), of residual
    /// `c`, is done: converged, or stalled (judged every window).
    pub(super) fn done(&mut self, iteration: usize, c: f64) -> bool {
        if iteration.is_multiple_of(STALL_WINDOW) {
            self.stalled = c <= self.stalled_target && c <= self.floor && c > 0.5 * self.checkpoint;
            self.checkpoint = c;
        }
        c <= self.target || self.stalled
    }

    /// Whether a done iterate's residual `c`, recomputed from a true
    /// product, is accepted: at the target, or after a stall at the
    /// stalled target.
    pub(super) fn accepts(&self, c: f64) -> bool {
        c <= self.target || (self.stalled && c <= self.stalled_target)
    }

    /// Whether a true product confirms what the recurrence found done:
    /// its residual `c` at most the stalled target (what is left above the
    /// recurrence's residual is its rounding drift, or the rounding floor
    /// of sums of n terms).
    pub(super) fn confirms(&self, c: f64) -> bool {
        c <= self.stalled_target
    }

    /// Judges afresh: the iteration restarted from a true residual.
    pub(super) fn restart(&mut self) {
        self.checkpoint = f64::INFINITY;
        self.stalled = false;
    }
}

/// `Σ_{i in J} a_i b_i` over the indices `J` that `on` selects (the
/// contact set, or every index), summed in order.
pub(super) fn dot_on(on: impl Fn(usize) -> bool, a: &[f64], b: &[f64]) -> f64 {
    (0..a.len()).filter(|&i| on(i)).map(|i| a[i] * b[i]).sum()
}

/// The step `num / den` along a direction `p` with `den = p · M p` (on the
/// contact set): a breakdown where `den` is not positive (`M` is not
/// positive definite along `p`) or not finite, unless there is nothing to
/// step (`num = 0`).
pub(super) fn step_length(num: f64, den: f64) -> Result<f64, Breakdown> {
    if !(den > 0.0) && num != 0.0 {
        return Err(if den.is_finite() {
            Breakdown::NotPositiveDefinite
        } else {
            Breakdown::NonFinite
        });
    }
    Ok(if num == 0.0 { 0.0 } else { num / den })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::STALL_WINDOW;

    #[test]
    fn a_step_needs_a_positive_curvature() {
        assert_eq!(step_length(2.0, 4.0), Ok(0.5));
        assert_eq!(step_length(0.0, -1.0), Ok(0.0));
        assert_eq!(step_length(1.0, 0.0), Err(Breakdown::NotPositiveDefinite));
        assert_eq!(step_length(1.0, -3.0), Err(Breakdown::NotPositiveDefinite));
        assert_eq!(step_length(1.0, f64::NAN), Err(Breakdown::NonFinite));
    }

    #[test]
    fn progress_stops_at_the_target_or_at_a_stall_on_the_rounding_floor() {
        let mut p = Progress::new(1e-12, 100);
        assert!(!p.done(0, 1e-3));
        assert!(!p.done(1, 0.6e-12));
        assert!(p.done(2, 0.5e-12));
        // A million terms: a rounding floor (8 eps sqrt(n) = 1.8e-12) above
        // the stalled target (7.5e-13). Below that and not halved over a
        // window: a stall, whose residual is accepted up to the stalled
        // target.
        let mut p = Progress::new(1e-12, 1_000_000);
        assert!(!p.done(0, 7e-13));
        assert!(!p.accepts(6e-13));
        assert!(p.done(STALL_WINDOW, 6e-13));
        assert!(p.accepts(7e-13) && !p.accepts(8e-13));
        p.restart();
        assert!(!p.accepts(7e-13));
    }
}
