//! The matrix-free conjugate gradient stops on the residuals its
//! certificate checks: on a stiff problem of tens of thousands of points
//! its answer certifies at every tolerance asked for, and a looser
//! tolerance stops it sooner (it is not held to a tighter residual of its
//! own).

use crate::common;

use common::Tridiagonal;
use elcon_lcp::{LcpSolution, Method, Operator, OperatorLcp, Options, Tolerances};
use faer::{Col, Mat};

/// A punch on a curved, slightly asymmetric gap under a load (one row of
/// ones), `n = 20,000`, condition number about 2000, certified to
/// `tolerance`.
fn solve(tolerance: f64) -> LcpSolution {
    let n = 20_000;
    // `d` barely above `2 c`: a condition number near `4 c / (d - 2 c)`,
    // the stiffness of a long elastic strip.
    let m = Tridiagonal::new(n, 1.001, 0.5);
    let x = |i: usize| 2.0 * i as f64 / (n - 1) as f64 - 1.0;
    let q = Col::from_fn(n, |i| x(i) * x(i) + 0.1 * x(i).powi(3));
    let border = Mat::from_fn(n, 1, |_, _| 1.0);
    let load = Col::from_fn(1, |_| 50.0);
    let operator: &dyn Operator = &m;
    let lcp = OperatorLcp::new(operator, q.as_ref())
        .unwrap()
        .with_border(border.as_ref(), load.as_ref())
        .unwrap();
    let options = Options {
        tolerances: Tolerances {
            certificate: tolerance,
            ..Tolerances::default()
        },
        ..Options::default()
    };
    lcp.solve(Method::ConjugateGradient, &options).unwrap()
}

#[test]
fn the_answer_certifies_at_every_tolerance_and_a_looser_one_stops_sooner() {
    let mut last = usize::MAX;
    for tolerance in [1e-12, 1e-10, 1e-8] {
        let sol = solve(tolerance);
        let c = &sol.certificate;
        assert!(c.holds(), "{tolerance:e}: {c:?}");
        assert!(c.worst() <= tolerance, "{tolerance:e}: {}", c.worst());
        let contact = sol.z.iter().filter(|&&v| v > 0.0).count();
        assert!(contact > 1000 && contact < 20_000, "{contact}");
        let iterations = sol.statistics.iterations();
        assert!(
            iterations < last,
            "{tolerance:e}: {iterations} iterations, {last} at the tighter tolerance"
        );
        last = iterations;
    }
}
