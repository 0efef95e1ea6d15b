//! The natural cubic spline of the tabulated departures
//! (`crate::contact::tabulated`), held two ways, each exact at the nodes
//! with a slope and a curvature continuous across them:
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
//! - the same spline on even spacing, held as cubic B-spline coefficients
//!   `c_k` (a height map, one axis at a time, in place of its values): on
//!   the cell `[i, i + 1]` at `s` in [0, 1],
//!
//!   ```text
//!       c(s) = w_(-1)(s) c_(i-1) + w_0(s) c_i + w_1(s) c_(i+1) + w_2(s) c_(i+2)
//!       w_(-1) = (1 - s)^3 / 6               w_0 = (3 s^3 - 6 s^2 + 4) / 6
//!       w_1    = (-3 s^3 + 3 s^2 + 3 s + 1) / 6    w_2 = s^3 / 6
//!   ```
//!
//!   so that the value at node i is `(c_(i-1) + 4 c_i + c_(i+1)) / 6` and
//!   the second derivative `(c_(i-1) - 2 c_i + c_(i+1)) / h^2`. Natural
//!   ends (no second derivative at the end nodes) make `c_(-1) = 2 c_0 -
//!   c_1` and `c_0 = f_0` (alike at the far end), and the interior
//!   coefficients solve `c_(i-1) + 4 c_i + c_(i+1) = 6 f_i`: the same
//!   strictly diagonally dominant tridiagonal system for every row, whose
//!   pivots are computed once and which is solved over the values in
//!   place. Along y it is solved over whole rows at a time, so the pass
//!   reads the map row after row.

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
    let mut m = zeros(n)?;
    if n < 3 {
        return Ok(m);
    }
    // Forward sweep over the interior nodes 1..n-1: `diag` the eliminated
    // diagonal, `m` the eliminated right-hand side; then back substitution
    // in place.
    let mut diag = zeros(n)?;
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

/// The cubic B-spline's weights `[w_(-1), w_0, w_1, w_2]` at `s` in
/// [0, 1] (see the module documentation); they sum to 1.
pub(crate) fn bspline_weights(s: f64) -> [f64; 4] {
    let (s2, r) = (s * s, 1.0 - s);
    let s3 = s2 * s;
    [
        r * r * r / 6.0,
        (3.0 * s3 - 6.0 * s2 + 4.0) / 6.0,
        (-3.0 * s3 + 3.0 * s2 + 3.0 * s + 1.0) / 6.0,
        s3 / 6.0,
    ]
}

/// The four coefficients `c_(i-1) .. c_(i+2)` the B-spline weighs on the
/// cell `[i, i + 1]` of `n >= 2` nodes, `get(k)` node k's; beyond an end
/// the natural spline's `c_(-1) = 2 c_0 - c_1` (alike at the far end).
pub(crate) fn stencil(n: usize, i: usize, get: impl Fn(usize) -> f64) -> [f64; 4] {
    let (c0, c1) = (get(i), get(i + 1));
    let before = if i > 0 { get(i - 1) } else { 2.0 * c0 - c1 };
    let after = if i + 2 < n { get(i + 2) } else { 2.0 * c1 - c0 };
    [before, c0, c1, after]
}

/// `sum_k w_k f_k`.
pub(crate) fn weigh(w: [f64; 4], f: [f64; 4]) -> f64 {
    w[0] * f[0] + w[1] * f[1] + w[2] * f[2] + w[3] * f[3]
}

/// `n` doubles of 0, or why the memory is not there.
fn zeros(n: usize) -> Result<Vec<f64>, String> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| {
        format!(
            "the cubic spline's {n} working values ({} MiB) do not fit in memory; use \
             interpolation = \"linear\"",
            (n * std::mem::size_of::<f64>()) >> 20
        )
    })?;
    v.resize(n, 0.0);
    Ok(v)
}

/// The reciprocal pivots `1 / d_i` of the system `c_(i-1) + 4 c_i +
/// c_(i+1) = r_i` over the interior nodes `1..n-1` of `n` (entry `i`;
/// `d_1 = 4`, `d_i = 4 - 1 / d_(i-1)`, all within [2 + sqrt 3, 4]).
fn pivots(n: usize) -> Result<Vec<f64>, String> {
    let mut p = zeros(n)?;
    let mut d = 4.0;
    for i in 1..n.saturating_sub(1) {
        p[i] = 1.0 / d;
        d = 4.0 - p[i];
    }
    Ok(p)
}

/// Turns the values of an `nx x ny` map (row by row, `nx` a row) into its
/// natural tensor-product spline's B-spline coefficients, in place (see
/// the module documentation); beside the map it holds `nx + ny` doubles.
///
/// # Errors
/// Why not: the memory for those doubles is not there.
pub(crate) fn natural_coefficients(values: &mut [f64], nx: usize, ny: usize) -> Result<(), String> {
    let px = pivots(nx)?;
    for row in values.chunks_exact_mut(nx) {
        solve_row(&px, row);
    }
    let py = pivots(ny)?;
    // Along y: node i of every column at once is row i.
    if ny >= 3 {
        let last = ny - 1;
        for i in 1..last {
            let (before, rest) = values.split_at_mut(i * nx);
            let (row, after) = rest.split_at_mut(nx);
            let prev = &before[(i - 1) * nx..];
            let end = (i == last - 1).then(|| &after[..nx]);
            for k in 0..nx {
                let r = 6.0 * row[k] - end.map_or(0.0, |e| e[k]);
                row[k] = if i == 1 {
                    r - prev[k]
                } else {
                    r - py[i - 1] * prev[k]
                };
            }
        }
        for i in (1..last).rev() {
            let (head, tail) = values.split_at_mut((i + 1) * nx);
            let row = &mut head[i * nx..];
            let next = (i + 1 < last).then(|| &tail[..nx]);
            for k in 0..nx {
                row[k] = (row[k] - next.map_or(0.0, |n| n[k])) * py[i];
            }
        }
    }
    Ok(())
}

/// Solves the natural spline's coefficients of one row of values in
/// place (the Thomas algorithm, `p` the reciprocal pivots: see
/// [`pivots`]); the end nodes keep their values.
fn solve_row(p: &[f64], row: &mut [f64]) {
    let n = row.len();
    if n < 3 {
        return;
    }
    let last = n - 1;
    for i in 1..last {
        let end = if i == last - 1 { row[last] } else { 0.0 };
        let r = 6.0 * row[i] - end;
        row[i] = if i == 1 {
            r - row[0]
        } else {
            r - p[i - 1] * row[i - 1]
        };
    }
    for i in (1..last).rev() {
        let next = if i + 1 < last { row[i + 1] } else { 0.0 };
        row[i] = (row[i] - next) * p[i];
    }
}

/// The inverse of [`natural_coefficients`]: the values of the map at its
/// nodes from its coefficients, `(c_(i-1) + 4 c_i + c_(i+1)) / 6` along
/// each axis (the end nodes' own coefficients), in place, to rounding.
///
/// # Errors
/// Why not: the memory for one row of doubles is not there.
pub(crate) fn natural_values(values: &mut [f64], nx: usize, ny: usize) -> Result<(), String> {
    let mid = |a: f64, b: f64, c: f64| (a + 4.0 * b + c) / 6.0;
    for row in values.chunks_exact_mut(nx) {
        let mut prev = row[0];
        for i in 1..nx.saturating_sub(1) {
            let here = row[i];
            row[i] = mid(prev, here, row[i + 1]);
            prev = here;
        }
    }
    let mut prev = zeros(nx)?;
    prev.copy_from_slice(&values[..nx]);
    for i in 1..ny.saturating_sub(1) {
        let (head, tail) = values.split_at_mut((i + 1) * nx);
        let row = &mut head[i * nx..];
        for k in 0..nx {
            let here = row[k];
            row[k] = mid(prev[k], here, tail[k]);
            prev[k] = here;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn b_spline_weights_sum_to_one_and_give_a_node_its_neighbours_sixths() {
        for s in [0.0, 0.1, 0.5, 0.93, 1.0] {
            let w = bspline_weights(s);
            assert!(
                (w.iter().sum::<f64>() - 1.0).abs() < 4.0 * f64::EPSILON,
                "{s}"
            );
        }
        assert_eq!(bspline_weights(0.0), [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0]);
        // Two nodes: a line, carried on beyond both ends.
        assert_eq!(stencil(2, 0, |k| [1.0, 3.0][k]), [-1.0, 1.0, 3.0, 5.0]);
    }

    #[test]
    fn a_map_s_coefficients_give_its_values_back_along_both_axes() {
        let (nx, ny) = (6, 5);
        let values: Vec<f64> = (0..nx * ny)
            .map(|k| ((k * 7919) % 13) as f64 - 6.0)
            .collect();
        let mut c = values.clone();
        natural_coefficients(&mut c, nx, ny).unwrap();
        // At node (i, j) the B-spline's value is the 3 x 3 sum of sixths.
        let at = |i: usize, j: usize| {
            let (i0, s) = if i == nx - 1 { (nx - 2, 1.0) } else { (i, 0.0) };
            let (j0, t) = if j == ny - 1 { (ny - 2, 1.0) } else { (j, 0.0) };
            let (wx, wy) = (bspline_weights(s), bspline_weights(t));
            let row = |j: usize| weigh(wx, stencil(nx, i0, |i| c[j * nx + i]));
            weigh(wy, stencil(ny, j0, row))
        };
        for j in 0..ny {
            for i in 0..nx {
                let v = at(i, j);
                assert!(
                    (v - values[j * nx + i]).abs() < 1e-14 * 6.0,
                    "({i}, {j}): {v}"
                );
            }
        }
        natural_values(&mut c, nx, ny).unwrap();
        for (a, b) in c.iter().zip(&values) {
            assert!((a - b).abs() < 1e-14 * 6.0, "{a} {b}");
        }
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
