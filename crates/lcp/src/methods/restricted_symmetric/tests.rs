//! Tests of `restricted_symmetric` (the parent module).

use super::*;

/// A reproducible stream in [-1, 1) (a linear congruential generator).
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// One ratio test's data: values of both signs, some exactly zero, on
/// and off `J`, and a column whose rates include falls far slower than
/// the pivot tolerance allows (when `slow`), for the one-pass rule and
/// the two-pass definition to be compared on.
struct Case {
    qbar: Vec<f64>,
    bbar: Vec<f64>,
    into: Vec<bool>,
    column: Vec<f64>,
}

fn case(seed: u64, n: usize, slow: bool) -> Case {
    let mut g = Stream(seed);
    let qbar = (0..n)
        .map(|i| if i % 7 == 3 { 0.0 } else { g.next() })
        .collect();
    let bbar = (0..n).map(|_| g.next()).collect();
    let into = (0..n).map(|_| g.next() < 0.0).collect();
    let column = (0..n)
        .map(|i| {
            let a = g.next();
            if slow && i % 5 == 1 { a * 1e-18 } else { a }
        })
        .collect();
    Case {
        qbar,
        bbar,
        into,
        column,
    }
}

/// What one ratio test leaves: the least step, the rates, the steps and
/// the positions near the least.
type Steps = (f64, Vec<f64>, Vec<f64>, Vec<usize>);

/// `rule`'s one-pass steps over `values`.
fn one_pass(rule: &Rates<'_>, values: &Values<'_>) -> Steps {
    let n = values.qbar.len();
    let (mut rates, mut reach, mut near) = (vec![0.0; n], vec![0.0; n], Vec::new());
    let least = rule.steps(values, &mut rates, &mut reach, &mut near);
    (least, rates, reach, near)
}

/// The rates and steps in two passes (the rates and their largest, then
/// the steps): what [`Rates::steps`] returns, by definition.
fn two_passes(rule: &Rates<'_>, values: &Values<'_>) -> Steps {
    let n = values.qbar.len();
    let mut largest = [0.0f64; 2];
    let mut rates = vec![0.0; n];
    for (i, rate) in rates.iter_mut().enumerate() {
        let kind = usize::from(!values.into[i]);
        let r = rule.unsigned(values, i);
        *rate = if kind == 0 { -r } else { r };
        largest[kind] = largest[kind].max(r.abs());
    }
    let small = largest.map(|v| rule.tol.pivot * v);
    let (mut reach, mut near) = (vec![0.0; n], Vec::new());
    let least = falling_steps(values, small, rule.tol.tie, &rates, &mut reach, &mut near);
    (least, rates, reach, near)
}

/// The one-pass steps against their two-pass definition, bit for bit.
fn assert_same_steps(c: &Case, column: Option<&[f64]>, f: f64, s: usize) {
    let values = Values {
        qbar: &c.qbar,
        bbar: &c.bbar,
        into: &c.into,
        alpha: 0.37,
        zero: [1e-3, 2e-3],
    };
    let rule = Rates {
        column,
        f,
        s,
        tol: Tolerances::default(),
    };
    let (least, rates, reach, near) = one_pass(&rule, &values);
    let (least2, rates2, reach2, near2) = two_passes(&rule, &values);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(least.to_bits(), least2.to_bits());
    assert_eq!(bits(&rates), bits(&rates2));
    assert_eq!(bits(&reach), bits(&reach2));
    assert_eq!(near, near2);
}

#[test]
fn one_pass_steps_are_those_of_the_two_pass_definition() {
    for seed in 0..40 {
        for slow in [false, true] {
            let c = case(seed, 37 + seed as usize, slow);
            // An entering index's column (not the pin's), the pin's,
            // and the release's (no column).
            assert_same_steps(&c, Some(c.column.as_slice()), 0.8, 5);
            assert_same_steps(&c, Some(c.column.as_slice()), c.column[5] * 1.3, 5);
            assert_same_steps(&c, None, -1.3, 5);
        }
    }
}

#[test]
fn a_fall_slower_than_the_pivot_tolerance_is_no_step() {
    // Gaps off J falling at rates -1 and -1e-18 (below the pivot
    // tolerance of the largest): only the first has a step, although the
    // second would reach zero first.
    let (qbar, bbar, into) = (vec![1.0, 1e-20, 1.0], vec![0.0; 3], vec![false; 3]);
    let column = [-1.0, -1e-18, 0.5];
    let values = Values {
        qbar: &qbar,
        bbar: &bbar,
        into: &into,
        alpha: 0.0,
        zero: [0.0, 0.0],
    };
    let rule = Rates {
        column: Some(&column[..]),
        f: 0.0,
        s: 2,
        tol: Tolerances::default(),
    };
    let (least, _, reach, near) = one_pass(&rule, &values);
    assert_eq!(least, 1.0);
    assert_eq!(reach, vec![1.0, f64::INFINITY, f64::INFINITY]);
    assert_eq!(near, vec![0]);
}
