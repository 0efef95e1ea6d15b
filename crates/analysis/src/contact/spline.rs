//! The two cubic interpolants of the tabulated departures
//! (`crate::contact::tabulated`), each exact at the nodes with a slope
//! that is continuous across them:
//!
//! - the natural cubic spline through `(t_i, y_i)` at increasing, not
//!   necessarily even, positions (an axial profile): on `[t_i, t_(i+1)]`,
//!   `h_i = t_(i+1) - t_i`, `a = (t_(i+1) - u) / h_i`, `b = 1 - a`,
//!
//!   ```text
//!       s(u) = a y_i + b y_(i+1) + ((a^3 - a) m_i + (b^3 - b) m_(i+1)) h_i^2 / 6
//!   ```
//!
//!   its second derivatives `m_i` solving the tridiagonal system
//!   `h_(i-1) m_(i-1) + 2 (h_(i-1) + h_i) m_i + h_i m_(i+1) = 6 (d_i - d_(i-1))`,
//!   `d_i = (y_(i+1) - y_i) / h_i`, with `m_0 = m_(n-1) = 0` (natural
//!   ends): continuous slope and curvature (C2). The system is strictly
//!   diagonally dominant, so the Thomas algorithm solves it stably in O(n);
//! - Keys's cubic convolution (Catmull-Rom) on even spacing (a height map,
//!   one axis at a time): on the cell `[i, i + 1]` at `s` in [0, 1],
//!
//!   ```text
//!       c(s) = w_(-1)(s) f_(i-1) + w_0(s) f_i + w_1(s) f_(i+1) + w_2(s) f_(i+2)
//!       w_(-1) = (-s^3 + 2 s^2 - s) / 2      w_0 = (3 s^3 - 5 s^2 + 2) / 2
//!       w_1    = (-3 s^3 + 4 s^2 + s) / 2    w_2 = (s^3 - s^2) / 2
//!   ```
//!
//!   whose slope at node i is `(f_(i+1) - f_(i-1)) / 2` from either side
//!   (C1), with the nodes beyond the ends extrapolated as the quadratic
//!   through the three end nodes, `f_(-1) = 3 f_0 - 3 f_1 + f_2` (as a
//!   line, `2 f_0 - f_1`, with two nodes), so that it reproduces any
//!   quadratic exactly up to the ends (Keys 1981, IEEE Trans. ASSP 29,
//!   1153-1160).

/// The natural cubic spline's second derivatives `m_i` at the positions
/// `t` (increasing) of the values `y` (see the module documentation);
/// all zero for two nodes. Holds one `f64` per node besides its result
/// while it solves.
///
/// # Errors
/// Why it could not: the memory for `2 n` doubles is not there, or a
/// second derivative is not finite (values or steps near the range of a
/// double).
pub(crate) fn natural_curvatures(t: &[f64], y: &[f64]) -> Result<Vec<f64>, String> {
    let n = t.len();
    let doubles = |n: usize| -> Result<Vec<f64>, String> {
        let mut v = Vec::new();
        v.try_reserve_exact(n).map_err(|_| {
            format!(
                "the cubic spline's {n} second derivatives ({} MiB, twice while it is solved) do \
                 not fit in memory; use interpolation = \"linear\" or a shorter table",
                (2 * n * std::mem::size_of::<f64>()) >> 20
            )
        })?;
        v.resize(n, 0.0);
        Ok(v)
    };
    let mut m = doubles(n)?;
    if n < 3 {
        return Ok(m);
    }
    // Forward sweep over the interior nodes 1..n-1: `diag` the eliminated
    // diagonal, `m` the eliminated right-hand side; then back substitution
    // in place.
    let mut diag = doubles(n)?;
    let step = |i: usize| t[i + 1] - t[i];
    let slope = |i: usize| (y[i + 1] - y[i]) / step(i);
    for i in 1..n - 1 {
        diag[i] = 2.0 * (step(i - 1) + step(i));
        m[i] = 6.0 * (slope(i) - slope(i - 1));
        if i > 1 {
            let w = step(i - 1) / diag[i - 1];
            diag[i] -= w * step(i - 1);
            m[i] -= w * m[i - 1];
        }
    }
    for i in (1..n - 1).rev() {
        let next = if i + 1 < n - 1 {
            step(i) * m[i + 1]
        } else {
            0.0
        };
        m[i] = (m[i] - next) / diag[i];
    }
    if let Some(i) = m.iter().position(|v| !v.is_finite()) {
        return Err(format!(
            "row {i} (from 0): the cubic spline's second derivative there is not a finite \
             number (values or steps beyond what a double holds); use interpolation = \"linear\""
        ));
    }
    Ok(m)
}

/// The natural cubic spline through `(t, y)` with second derivatives `m`
/// at `u` in the interval `[t_i, t_(i+1)]`.
pub(crate) fn natural_at(t: &[f64], y: &[f64], m: &[f64], i: usize, u: f64) -> f64 {
    let h = t[i + 1] - t[i];
    let a = (t[i + 1] - u) / h;
    let b = 1.0 - a;
    a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0
}

/// Keys's weights `[w_(-1), w_0, w_1, w_2]` at `s` in [0, 1] (see the
/// module documentation); they sum to 1.
pub(crate) fn keys_weights(s: f64) -> [f64; 4] {
    let s2 = s * s;
    let s3 = s2 * s;
    [
        0.5 * (-s3 + 2.0 * s2 - s),
        0.5 * (3.0 * s3 - 5.0 * s2 + 2.0),
        0.5 * (-3.0 * s3 + 4.0 * s2 + s),
        0.5 * (s3 - s2),
    ]
}

/// The four values `f_(i-1) .. f_(i+2)` Keys's convolution weighs on the
/// cell `[i, i + 1]` of `n >= 2` nodes, `get(k)` the value of node k; a
/// node beyond an end extrapolated (see the module documentation).
pub(crate) fn keys_stencil(n: usize, i: usize, get: impl Fn(usize) -> f64) -> [f64; 4] {
    let (f0, f1) = (get(i), get(i + 1));
    // The node beyond `a0` from `a1`, `a2` inward.
    let beyond = |a0: f64, a1: f64, a2: Option<f64>| match a2 {
        Some(a2) => 3.0 * a0 - 3.0 * a1 + a2,
        None => 2.0 * a0 - a1,
    };
    let before = if i > 0 {
        get(i - 1)
    } else {
        beyond(f0, f1, (n > 2).then(|| get(2)))
    };
    let after = if i + 2 < n {
        get(i + 2)
    } else {
        beyond(f1, f0, (n > 2).then(|| get(n - 3)))
    };
    [before, f0, f1, after]
}

/// `sum_k w_k f_k`.
pub(crate) fn weigh(w: [f64; 4], f: [f64; 4]) -> f64 {
    w[0] * f[0] + w[1] * f[1] + w[2] * f[2] + w[3] * f[3]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_weights_sum_to_one_and_pick_the_node_at_its_ends() {
        for s in [0.0, 0.1, 0.5, 0.93, 1.0] {
            let w = keys_weights(s);
            assert!(
                (w.iter().sum::<f64>() - 1.0).abs() < 4.0 * f64::EPSILON,
                "{s}"
            );
        }
        assert_eq!(keys_weights(0.0), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(keys_weights(1.0), [0.0, 0.0, 1.0, 0.0]);
    }

    #[test]
    fn the_stencil_extrapolates_a_quadratic_beyond_the_ends() {
        let f = |k: usize| {
            let x = k as f64;
            x * x - 3.0 * x + 2.0
        };
        // f(-1) = 6, f(5) = 12 on nodes 0..=4.
        assert_eq!(keys_stencil(5, 0, f), [6.0, 2.0, 0.0, 0.0]);
        assert_eq!(keys_stencil(5, 3, f), [0.0, 2.0, 6.0, 12.0]);
        // Two nodes: a line.
        assert_eq!(keys_stencil(2, 0, |k| [1.0, 3.0][k]), [-1.0, 1.0, 3.0, 5.0]);
    }

    #[test]
    fn a_natural_spline_of_two_or_a_line_has_no_curvature() {
        assert_eq!(
            natural_curvatures(&[0.0, 1.0], &[1.0, 5.0]).unwrap(),
            [0.0, 0.0]
        );
        let t = [0.0, 0.3, 1.0, 1.2, 2.5];
        let y: Vec<f64> = t.iter().map(|x| 2.0 * x - 1.0).collect();
        let m = natural_curvatures(&t, &y).unwrap();
        assert!(m.iter().all(|v| v.abs() < 1e-14), "{m:?}");
        let m = natural_curvatures(&[0.0, 1e-300, 1.0], &[1e300, -1e300, 1e300]).unwrap_err();
        assert!(m.contains("row"), "{m}");
    }
}
