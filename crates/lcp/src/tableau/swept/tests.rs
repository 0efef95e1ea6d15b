//! Tests of `swept` (the parent module).

use super::*;

/// The swept matrix by definition, for the set `into`.
fn swept_explicitly(m: &Mat<f64>, into: &[bool]) -> Mat<f64> {
    let mut a = m.clone();
    let n = m.nrows();
    for p in (0..n).filter(|&p| into[p]) {
        let c = a.col(p).to_owned();
        let piv = c[p];
        for j in 0..n {
            for i in 0..n {
                if i != p && j != p {
                    a[(i, j)] -= c[i] * c[j] / piv;
                }
            }
        }
        for i in 0..n {
            if i != p {
                a[(i, p)] = c[i] / piv;
                a[(p, i)] = c[i] / piv;
            }
        }
        a[(p, p)] = -1.0 / piv;
    }
    a
}

/// A symmetric positive definite matrix of order `n`: every principal
/// pivot exists.
fn definite(n: usize) -> Mat<f64> {
    let g = Mat::from_fn(n, n, |i, j| ((i * 7 + j * 3) % 5) as f64 - 2.0);
    let mut m = Mat::<f64>::identity(n, n) * 4.0;
    matmul(
        m.as_mut(),
        Accum::Add,
        g.as_ref(),
        g.transpose(),
        0.3,
        Par::Seq,
    );
    m
}

/// Asserts that column `j` read from the tableau is that of `expect`
/// (`when`: after which pivot, for the message).
fn assert_column(col: &Col<f64>, expect: &Mat<f64>, j: usize, when: &str) {
    for i in 0..expect.nrows() {
        assert!(
            (col[i] - expect[(i, j)]).abs() <= 1e-12 * expect.norm_max(),
            "entry ({i}, {j}){when}: {} against {}",
            col[i],
            expect[(i, j)]
        );
    }
}

/// A [`definite`] matrix of order `n`, its swept tableau gathered in its
/// own order, blocks of 2 (flushes between pivots, and indices pivoted in
/// one block and read in the next), and the empty set swept in.
fn gathered(n: usize) -> (Mat<f64>, Swept, Vec<bool>) {
    let m = definite(n);
    let order: Vec<usize> = (0..n).collect();
    let tab = Swept::gather(m.as_ref(), &order, &vec![1.0; n], 2, Par::Seq).unwrap();
    (m, tab, vec![false; n])
}

/// Pivots `tab` on `p` with its column `c`: `p` joins the set `into` when
/// out of it, and leaves it when in.
fn toggle(tab: &mut Swept, into: &mut [bool], p: usize, c: &Col<f64>) {
    let joins = !into[p];
    tab.pivot(p, c, joins);
    into[p] = joins;
}

#[test]
fn a_path_in_order_skips_both_triangles_and_replays_them_when_read() {
    let n = 14;
    let (m, mut tab, mut into) = gathered(n);
    // In order (the frontier advances and the leading triangle goes
    // stale), then releases before the frontier (a replay) and after
    // it, rejoins, and more in order; only the pivots' columns are read
    // until the end, as a pivot rule reads them.
    let (mut skipped, mut trailing) = (false, false);
    for &p in &[0, 1, 2, 3, 4, 5, 6, 7, 2, 8, 9, 2, 4, 10, 4, 11] {
        let c = tab.column(p);
        assert_column(&c, &swept_explicitly(&m, &into), p, "");
        toggle(&mut tab, &mut into, p, &c);
        skipped |= !tab.stale.is_empty();
        trailing |= !tab.trail_lambda.is_empty() && tab.back < n;
    }
    assert!(skipped, "some block skipped its leading triangle");
    assert!(trailing, "some block skipped the trailing triangle");
    let expect = swept_explicitly(&m, &into);
    for j in 0..n {
        assert_column(&tab.column(j), &expect, j, "");
    }
    // The bound on the skipped blocks' memory holds throughout.
    assert!(tab.stale_len <= n * n / STALE_SHARE);
}

#[test]
fn delayed_sweeps_in_and_out_read_the_explicit_swept_matrix() {
    let n = 9;
    let (m, mut tab, mut into) = gathered(n);
    for &p in &[3, 0, 7, 3, 5, 1, 0, 8, 2, 5, 3, 4] {
        let c = tab.column(p);
        toggle(&mut tab, &mut into, p, &c);
        let expect = swept_explicitly(&m, &into);
        for j in 0..n {
            assert_column(&tab.column(j), &expect, j, &format!(" after pivot on {p}"));
            assert!((tab.diagonal(j) - expect[(j, j)]).abs() <= 1e-12 * expect.norm_max());
        }
    }
}
