//! Helpers shared by the integration tests.

use faer::Col;

/// The largest difference of `a` and `b`, relative to their largest entry.
pub fn rel_diff(a: &Col<f64>, b: &Col<f64>) -> f64 {
    let scale = a
        .iter()
        .chain(b.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(1e-300);
    (a - b).iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale
}
