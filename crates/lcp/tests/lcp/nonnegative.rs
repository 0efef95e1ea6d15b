//! An operator whose entries are all non-negative (`Operator::
//! entries_nonnegative`) is certified from one product: `|M| z = M z` for
//! `z >= 0`, so the certificate reads the terms' magnitude from `M z`. The
//! same problem, its operator not saying so, takes two products and gives
//! the same certificate and answer to the bit.

use crate::common;

use common::Tridiagonal;
use elcon_lcp::{LcpSolution, Method, Operator, OperatorLcp, Options};
use faer::{Col, Mat};

/// A load of 20 on a curved gap over 400 points.
fn solve(says: bool) -> LcpSolution {
    let n = 400;
    let m = Tridiagonal {
        says_nonnegative: says,
        ..Tridiagonal::new(n, 2.0, 0.5)
    };
    let x = |i: usize| 2.0 * i as f64 / (n - 1) as f64 - 1.0;
    let q = Col::from_fn(n, |i| x(i) * x(i));
    let border = Mat::from_fn(n, 1, |_, _| 1.0);
    let resultant = Col::from_fn(1, |_| 20.0);
    let operator: &dyn Operator = &m;
    OperatorLcp::new(operator, q.as_ref())
        .unwrap()
        .with_border(border.as_ref(), resultant.as_ref())
        .unwrap()
        .solve(Method::ConjugateGradient, &Options::default())
        .unwrap()
}

#[test]
fn non_negative_entries_are_certified_from_one_product() {
    let (one, two) = (solve(true), solve(false));
    assert!(one.certificate.holds(), "{:?}", one.certificate);
    let bits = |s: &LcpSolution| s.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(
        one.certificate.worst().to_bits(),
        two.certificate.worst().to_bits()
    );
    assert_eq!(one.statistics.products() + 1, two.statistics.products());
}
