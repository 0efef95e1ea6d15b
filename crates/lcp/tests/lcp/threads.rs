//! The matrix-free conjugate gradient gives the same answer to the bit on
//! any number of threads: its passes over the vectors cut them into chunks
//! of a fixed length and add the chunks' sums in a fixed order, whichever
//! thread computed them. A problem of tens of thousands of points (many
//! chunks) is solved in rayon pools of 1, 2 and 3 threads. It also counts
//! the operator's products against the iterations.

use crate::common;

use common::Tridiagonal;
use elcon_lcp::{LcpSolution, Method, Operator, OperatorLcp, Options};
use faer::{Col, Mat};

/// A punch on a curved gap: `q_i = gap_i - δ` (the approach `δ` inside `q`
/// for `k = 0`), or `q_i = gap_i` with rows: ones (the load) and, for
/// `k = 2`, the lever arm `x_i` (a moment of zero).
fn solve(threads: usize, k: usize, preconditioned: bool) -> LcpSolution {
    let n = 30_000;
    // Diagonally dominant, with its Neumann preconditioner where asked.
    let m = Tridiagonal {
        preconditioned,
        ..Tridiagonal::new(n, 1.01, 0.5)
    };
    let x = |i: usize| 2.0 * i as f64 / (n - 1) as f64 - 1.0;
    let gap = |i: usize| x(i) * x(i) + 0.1 * x(i).powi(3);
    let approach = if k == 0 { 0.3 } else { 0.0 };
    let q = Col::from_fn(n, |i| gap(i) - approach);
    let border = Mat::from_fn(n, k, |i, j| if j == 0 { 1.0 } else { x(i) });
    let resultant = Col::from_fn(k, |j| if j == 0 { 500.0 } else { 0.0 });
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let operator: &dyn Operator = &m;
        let lcp = OperatorLcp::new(operator, q.as_ref()).unwrap();
        let lcp = match preconditioned {
            true => lcp.with_preconditioner(&m).unwrap(),
            false => lcp,
        };
        let lcp = if k == 0 {
            lcp
        } else {
            lcp.with_border(border.as_ref(), resultant.as_ref())
                .unwrap()
        };
        lcp.solve(Method::ConjugateGradient, &Options::default())
            .unwrap()
    })
}

#[test]
fn the_answer_is_the_same_to_the_bit_on_one_thread_or_several() {
    for k in [0, 1, 2] {
        let one = solve(1, k, false);
        assert!(one.certificate.holds(), "k = {k}: {:?}", one.certificate);
        let contact = one.z.iter().filter(|&&v| v > 0.0).count();
        assert!(contact > 1000 && contact < 30_000, "k = {k}: {contact}");
        // About one product per iteration: the product `M z` is kept by
        // the recurrence (true products at the start, where points left or
        // entered, and for the certificate). Several rows restored by
        // tilting need a true product after each such step.
        let (iterations, products) = (one.statistics.iterations(), one.statistics.products());
        assert!(iterations > 50, "k = {k}: {iterations}");
        if k < 2 {
            assert!(
                4 * products <= 5 * iterations + 16,
                "k = {k}: {products} products in {iterations} iterations"
            );
        }
        for threads in [2, 3] {
            let many = solve(threads, k, false);
            let bits = |s: &LcpSolution| s.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&one), bits(&many), "k = {k}, {threads} threads");
            let lambda = |s: &LcpSolution| s.u.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(lambda(&one), lambda(&many), "k = {k}, {threads} threads");
            assert_eq!(
                one.statistics.iterations(),
                many.statistics.iterations(),
                "k = {k}"
            );
        }
    }
}

/// Preconditioned, the same answer as without to the certificate's
/// tolerance, in fewer iterations, one application of the preconditioner
/// an iteration, and the same bits on one thread or two.
#[test]
fn the_preconditioned_answer_is_the_plain_one_and_the_same_on_any_threads() {
    for k in [0, 1, 2] {
        let (plain, pre) = (solve(1, k, false), solve(1, k, true));
        assert!(pre.certificate.holds(), "k = {k}: {:?}", pre.certificate);
        let scale = plain.z.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let gap = (0..plain.z.nrows()).fold(0.0f64, |m, i| m.max((plain.z[i] - pre.z[i]).abs()));
        assert!(
            gap <= 1e-9 * scale,
            "k = {k}: z apart by {gap:e} of {scale:e}"
        );
        let (i_plain, i_pre) = (plain.statistics.iterations(), pre.statistics.iterations());
        assert!(
            i_pre < i_plain,
            "k = {k}: {i_pre} iterations against {i_plain}"
        );
        assert_eq!(plain.statistics.preconditionings(), 0, "k = {k}");
        assert_eq!(pre.statistics.preconditionings(), i_pre, "k = {k}");
        let two = solve(2, k, true);
        let bits = |s: &LcpSolution| s.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&pre), bits(&two), "k = {k}");
    }
}
