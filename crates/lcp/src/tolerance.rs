//! Every tolerance of the engine, in one place.
//!
//! The engine works on a problem that has been equilibrated (rows and columns
//! scaled by powers of two so that the largest entry of every row and column
//! of the constraint matrix is about 1; see docs/stability.md). The
//! tolerances below are then *relative* factors: each is multiplied by a scale
//! taken from the data before it is used.
//!
//! | tolerance | multiplies | meaning |
//! |---|---|---|
//! | [`pivot`](Tolerances::pivot) | the largest magnitude in the entering column | smaller entries are not pivots |
//! | [`zero`](Tolerances::zero) | the right-hand side's scale, `max(‖b‖∞, ‖b̄‖∞)` | basic values below it are degenerate (0) |
//! | [`cost`](Tolerances::cost) | the objective row's scale | reduced costs above `-cost` do not improve |
//! | [`tie`](Tolerances::tie) | the smallest ratio of a ratio test | ratios within it are ties (lexicographic rule) |
//! | [`certificate`](Tolerances::certificate) | (already relative) | largest accepted relative residual |
//!
//! Defaults are derived from the double-precision unit roundoff
//! `u = f64::EPSILON / 2 ≈ 1.1e-16`: a tableau entry after `k` pivots carries
//! a relative error of order `k u` times the growth of the basis inverse, so a
//! pivot must stand well above `m u` of its column (`pivot = 2^-36 ≈ 1.5e-11`
//! is about 13 times `m u ≈ 1.1e-12` at `m = 10^4`: about one order of
//! headroom there, more for smaller `m`); basic values are compared to zero
//! at `2^-42 ≈ 2.3e-13` of the right-hand side's scale, `2^11 u`;
//! and the certificate accepts `1e-12` relative residuals: the rounding error
//! of a length-`n` dot product is about `sqrt(n) u` in practice (at most
//! `n u`), i.e. below `1e-13` up to `n = 10^4` after refinement.

use crate::LcpError;
use elcon_num::Num;

/// The relative tolerances of the engine (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Smallest accepted pivot, relative to the largest magnitude in the entering column.
    pub pivot: f64,
    /// Basic values at or below `zero * rhs_scale` count as zero (degenerate).
    pub zero: f64,
    /// An entering variable must have reduced cost below `-cost * cost_scale`.
    pub cost: f64,
    /// Ratios within `tie * ratio` of the smallest ratio are ties.
    pub tie: f64,
    /// Largest accepted relative residual of the final certificate.
    pub certificate: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            pivot: 2f64.powi(-36),
            zero: 2f64.powi(-42),
            cost: 2f64.powi(-40),
            tie: 2f64.powi(-40),
            certificate: 1e-12,
        }
    }
}

impl Tolerances {
    /// Checks that every tolerance is finite and in `[0, 1)`.
    pub fn validate(&self) -> Result<(), LcpError> {
        let fields = [
            ("tolerances.pivot", self.pivot),
            ("tolerances.zero", self.zero),
            ("tolerances.cost", self.cost),
            ("tolerances.tie", self.tie),
            ("tolerances.certificate", self.certificate),
        ];
        for (field, value) in fields {
            if !(value.is_finite() && (0.0..1.0).contains(&value)) {
                return Err(LcpError::InvalidOption {
                    field,
                    value: Num(value).to_string(),
                    reason: "a relative tolerance must be finite and in [0, 1)",
                });
            }
        }
        Ok(())
    }
}

/// `M` counts as symmetric when `|m_ij - m_ji|` is at most this times its
/// largest diagonal entry (`1e3 u`: the rounding of assembling the two
/// entries by different sums, with room).
pub(crate) const SYMMETRY: f64 = 1e3 * f64::EPSILON;

/// An LU factor (a basis, a border's Schur complement) is numerically
/// singular when its smallest over largest pivot is at most this times its
/// order (`u` per row: below it the factor's own rounding swamps the
/// smallest pivot).
pub(crate) const SINGULAR_PER_ROW: f64 = f64::EPSILON;

/// A basis is near singular when the reciprocal condition estimate
/// `1 / (|B|_1 |B^{-1}|_1)` is at most this times its rows: refinement with
/// the tableau's `B^{-1}` could then reach a small backward error and a
/// meaningless answer, so a fresh LU decides instead.
pub(crate) const NEAR_SINGULAR_PER_ROW: f64 = f64::EPSILON;

/// A componentwise backward error at rounding level (`2 u`): refinement
/// stops there.
pub(crate) const ROUNDING_LEVEL: f64 = 2.0 * f64::EPSILON;

/// The backward error at which the tableau's own basic solution is kept
/// (`64 u`): refinement plateaus a few units of rounding above
/// [`ROUNDING_LEVEL`] whichever `B^{-1}` corrects it, since the residual is
/// itself computed in floating point; above this the tableau drifted and a
/// fresh LU of the basis decides.
pub(crate) const TABLEAU_ACCEPT: f64 = 64.0 * f64::EPSILON;

/// Iterative refinement on an active set stops when the correction is at
/// most this times the solution (`u`: nothing left to correct).
pub(crate) const REFINED: f64 = f64::EPSILON;

/// A border column depends on the ones before it when its squared distance
/// from their span, in units of its own length, is at most this (`2^-40`:
/// a distance of about 1e-6, past which the border's Schur complement has a
/// condition number near `1 / u`).
pub(crate) const BORDER_RANK: f64 = 1.0 / (1u64 << 40) as f64;

/// The conjugate-gradient method stops when its residuals (the ones the
/// certificate measures, computed from its iterate) are at most this
/// fraction of the certificate's tolerance. Judged from a product kept by
/// its recurrence, they are then confirmed from a true product up to
/// [`STALLED_STOP`] (the recurrence's drift, a small part of the residual
/// at the end); the certificate recomputes them from the same product of
/// the original operator with the original data, which changes only the
/// order of the border's sums, so the quarter left above [`STALLED_STOP`]
/// is the margin. A tighter target would buy iterations the certificate
/// does not need (each one cuts the residual by about a fifth on Hertz's
/// problem). A linear system's conjugate gradient stops at the same
/// fraction: its residual `‖b - M x‖∞` relative to the data's scale
/// `max_i (|(M x)_i| + |b_i|)`, a relative residual of `5e-13` at the
/// default tolerance.
pub const ITERATIVE_STOP: f64 = 0.5;

/// The conjugate gradient also stops when its residuals are at most this
/// fraction of the certificate's tolerance and did not halve over the last
/// [`STALL_WINDOW`] iterations: on very large problems (N of 10^5 and more)
/// the sums' rounding leaves the residuals a floor of a fraction of the
/// tolerance, which the iterate approaches over hundreds of iterations
/// without gaining a digit.
pub const STALLED_STOP: f64 = 0.75;

/// Iterations over which the conjugate gradient's progress is judged
/// ([`STALLED_STOP`]).
pub const STALL_WINDOW: usize = 25;

/// A stall counts only at residuals below `ROUNDING_FLOOR eps sqrt(n)`, the
/// rounding of sums of n terms with room. Below n of about 2e4 this is under
/// [`STALLED_STOP`] times the default tolerance, so a small problem that
/// converges slowly is not stopped early; on large ones the stall test
/// alone decides.
pub const ROUNDING_FLOOR: f64 = 8.0;

/// The conjugate gradient's rows `B^T z = b` count as restored when each
/// row's residual is at most this times the magnitude of its terms
/// (`2^-46 ≈ 1.4e-14`: a few units of rounding of the row's sum).
pub(crate) const ROWS_RESTORED: f64 = 1.0 / (1u64 << 46) as f64;

/// The restoration of several rows fails when Newton's method stops (no
/// decrease left) with a row's residual above this times the largest
/// magnitude of the rows' terms (`2^-36 ≈ 1.5e-11`): the contact set cannot
/// carry the rows. Below it, what is left is rounding, and the iteration's
/// own test of the rows decides.
pub(crate) const ROWS_STALLED: f64 = 1.0 / (1u64 << 36) as f64;

/// Newton steps of the restoration of several rows before it gives up.
pub(crate) const RESTORE_STEPS: usize = 60;

/// Sufficient decrease of the restoration's line search (Armijo's constant).
pub(crate) const ARMIJO: f64 = 1e-4;

/// Rounds of the additive correction that restores several rows when the
/// contact set cannot carry them (each round clips what went negative; the
/// next corrects the clipped remainder).
pub(crate) const EQUALITY_CORRECTIONS: usize = 10;

/// The conjugate gradient fits `λ` on a contact set too small to carry the
/// border's rows (an early iterate) by normal equations with this times
/// their largest diagonal entry added to the diagonal: near the least-norm
/// fit (`2^-30 ≈ 1e-9`, far above rounding, far below the data).
pub(crate) const RIDGE: f64 = 1.0 / (1u64 << 30) as f64;
