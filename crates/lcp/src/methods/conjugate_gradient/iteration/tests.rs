//! Tests of `iteration` (the parent module).

use super::*;
use crate::operator::Operator;

#[test]
fn a_step_cut_at_the_boundary_lets_the_first_point_leave() {
    let z = [0.3, 0.2, 0.0, 0.4];
    let t = [0.1, 0.4, 0.0, -0.2];
    // z_1 / t_1 = 0.5 is the first ratio; z_3 grows, z_2 is off J.
    let boundary = boundary_pass(&z, &t);
    assert_eq!(boundary, 0.2 / 0.4);
    let mut cut = [9.0; 4];
    boundary_step(&mut cut, &z, &t, boundary);
    assert_eq!(cut, [0.3 - 0.5 * 0.1, 0.0, 0.0, 0.4 + 0.5 * 0.2]);
    // Nothing decreases: no boundary.
    assert_eq!(boundary_pass(&z, &[0.0, -1.0, 1.0, 0.0]), f64::INFINITY);
}

/// The vectors of an iteration, from a fixed sequence.
struct Sample {
    q: faer::Col<f64>,
    z: Vec<f64>,
    u: Vec<f64>,
    t: Vec<f64>,
    r: Vec<f64>,
}

/// `n` entries (three chunks and a tail for the tests): `z` about half
/// in contact.
fn sample(n: usize) -> Sample {
    let h = |i: usize| (i as f64 * 0.618_033_988_749_895).fract() - 0.4;
    Sample {
        q: faer::Col::from_fn(n, |i| h(i + 7)),
        z: (0..n).map(|i| h(i).max(0.0)).collect(),
        u: (0..n).map(|i| h(i + 3)).collect(),
        t: (0..n).map(|i| h(i + 5) * 1e-3).collect(),
        r: (0..n).map(|i| h(i + 11) * 1e-3).collect(),
    }
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn measures_bits(m: &Measures) -> Vec<u64> {
    let mut v = vec![m.min_w, m.complementarity, m.w_scale, m.z_scale, m.g];
    v.extend(&m.rows);
    v.extend(&m.rows_terms);
    bits(&v)
}

#[test]
fn the_measure_pass_writes_the_residual_pass_bits() {
    let n = 3 * CHUNK + 13;
    let Sample { q, z, u, .. } = sample(n);
    let b = faer::Mat::from_fn(n, 2, |i, j| 1.0 + (i * (j + 1)) as f64 * 1e-4);
    let data = Data::new(q.as_ref(), b.as_ref());
    let lambda = [0.01, -0.02];
    let separate = measure_pass(&data, (&z, &u), None, 1.5, &lambda);
    let mut r1 = vec![0.0; n];
    residual_pass(&data, (&z, &u, 1.5), &mut r1, &lambda);
    let mut r2 = vec![9.0; n];
    let fused = measure_pass(&data, (&z, &u), Some(&mut r2), 1.5, &lambda);
    assert_eq!(measures_bits(&separate), measures_bits(&fused));
    assert_eq!(bits(&r1), bits(&r2));
    assert!(r2.iter().zip(&z).all(|(r, z)| *z > 0.0 || *r == 0.0));
    // A pending scale, applied in registers, measures what the scaled
    // vectors measure.
    let scaled = |v: &[f64]| v.iter().map(|x| 1.5 * x).collect::<Vec<f64>>();
    let stored = measure_pass(&data, (&scaled(&z), &scaled(&u)), None, 1.0, &lambda);
    assert_eq!(measures_bits(&separate), measures_bits(&stored));
}

#[test]
fn a_constant_column_is_read_from_a_chunk_with_the_same_bits() {
    let n = 3 * CHUNK + 13;
    let Sample { q, z, u, t, r } = sample(n);
    let ones = faer::Mat::from_fn(n, 1, |_, _| 1.0);
    let constant = Data::new(q.as_ref(), ones.as_ref());
    assert!(matches!(constant.border[0], Column::Constant(ref c) if c.len() == CHUNK));
    let entries = Data {
        q: constant.q.clone(),
        border: vec![Column::Entries(Cow::Owned(vec![1.0; n]))],
    };
    let lambda = [0.03];
    let fits = [&constant, &entries].map(|d| fit_pass(d, &z, &u));
    assert_eq!(bits(&fits[0].bu), bits(&fits[1].bu));
    assert_eq!(bits(&fits[0].bq), bits(&fits[1].bq));
    assert_eq!(
        fits[0].gram[(0, 0)].to_bits(),
        fits[1].gram[(0, 0)].to_bits()
    );
    let measures = [&constant, &entries].map(|d| {
        let mut r = vec![0.0; n];
        let m = measure_pass(d, (&z, &u), Some(&mut r), 0.75, &lambda);
        (measures_bits(&m), bits(&r))
    });
    assert_eq!(measures[0], measures[1]);
    let projections = [&constant, &entries].map(|d| {
        let p = projection_pass(d, &z, &r, &t);
        bits(&[p.bp, p.br, vec![p.rp]].concat())
    });
    assert_eq!(projections[0], projections[1]);
    let directions = [&constant, &entries].map(|d| {
        let mut tt = t.clone();
        let num = preconditioned_direction_pass(d, &z, &r, &u, &mut tt, &lambda, 0.5);
        (num.to_bits(), bits(&tt))
    });
    assert_eq!(directions[0], directions[1]);
}

#[test]
fn a_step_that_keeps_the_contact_set_updates_the_fit_as_a_fresh_fit_pass() {
    let n = 3 * CHUNK + 13;
    // One column (its sums in the step's and the measures' own loops)
    // and two (a loop each).
    for k in [1, 2] {
        let Sample { q, z, u, r, .. } = sample(n);
        let b = faer::Mat::from_fn(n, k, |i, j| 1.0 + (i * (j + 1)) as f64 * 1e-4);
        let data = Data::new(q.as_ref(), b.as_ref());
        let before = fit_pass(&data, &z, &u);
        // A direction that moves every point in contact by 1 % and
        // enters none: the points off J have w >= 0 with λ_0 = -1e3.
        let t: Vec<f64> = z.iter().map(|&v| 0.01 * v).collect();
        let lambda = &[-1e3, 0.0][..k];
        let (mut z1, mut u1) = (z.clone(), u.clone());
        let update = update_pass(
            &data,
            (&mut z1, &mut u1, 1.0),
            &t,
            &r,
            lambda,
            0.5,
            (true, None),
        );
        let rows = update.rows;
        let sums = update.sums.expect("no point left or entered");
        let after = fit_pass(&data, &z1, &u1);
        assert_eq!(bits(&sums.bu), bits(&after.bu));
        assert_eq!(bits(&before.bq), bits(&after.bq));
        let measured = measure_pass(&data, (&z1, &u1), None, 1.0, lambda);
        assert_eq!(bits(&rows), bits(&measured.rows));
        assert_eq!(bits(&sums.rows_terms), bits(&measured.rows_terms));
        // A full step clips the points in contact: no sums.
        let t: Vec<f64> = z.iter().map(|&v| 2.0 * v).collect();
        let (mut z2, mut u2) = (z, u);
        let update = update_pass(
            &data,
            (&mut z2, &mut u2, 1.0),
            &t,
            &r,
            lambda,
            1.0,
            (true, None),
        );
        assert!(update.sums.is_none());
    }
}

/// A step that clips and lets in points, with its changes collected: `u`
/// (the recurrence everywhere) plus `M d` by the columns is `M z` of the
/// new iterate, to rounding relative to the terms of `M z` (`|M| |z|`);
/// a pending scale and a limit below the changes' count included.
#[test]
fn collected_changes_by_columns_equal_the_full_product() {
    let n = 2 * CHUNK + 29;
    let Sample { q, z, t, .. } = sample(n);
    let m = faer::Mat::from_fn(n, n, |i, j| {
        let d = i.abs_diff(j) as f64;
        1.0 / (1.0 + d) + if i == j { 1.0 } else { 0.0 }
    });
    let product = |x: &[f64]| {
        let mut y = vec![0.0; n];
        faer::MatRef::apply(
            &m.as_ref(),
            x,
            &mut y,
            faer::dyn_stack::PodStack::new(&mut []),
        );
        y
    };
    let ones = faer::Mat::from_fn(n, 1, |_, _| 1.0);
    let data = Data::new(q.as_ref(), ones.as_ref());
    let c = 1.25;
    // u = M z (at scale 1: the pending scale applies to both), r = M t.
    let (u, r) = (product(&z), product(&t));
    let lambda = [0.05];
    // A step of 200 clips about a third of the points in contact.
    let (mut z1, mut u1) = (z.clone(), u.clone());
    let update = update_pass(
        &data,
        (&mut z1, &mut u1, c),
        &t,
        &r,
        &lambda,
        200.0,
        (true, Some(n)),
    );
    let changes = update
        .changes
        .expect("the contact set changed, within the limit");
    assert!(update.sums.is_none());
    let moved = changes.columns.len();
    assert!(moved > 100, "{moved} points clipped or let in");
    assert!(changes.columns.windows(2).all(|w| w[0].0 < w[1].0));
    assert!(faer::MatRef::add_columns(
        &m.as_ref(),
        &changes.columns,
        &mut u1
    ));
    let exact = product(&z1);
    let terms = product(&z1.iter().map(|v| v.abs()).collect::<Vec<_>>());
    let scale = terms.iter().fold(0.0f64, |a, v| a.max(*v))
        + u.iter().fold(0.0f64, |a, v| a.max(c * v.abs()));
    for i in 0..n {
        assert!(
            (u1[i] - exact[i]).abs() <= 1e-13 * scale,
            "{i}: {} vs {}",
            u1[i],
            exact[i]
        );
    }
    let measured = measure_pass(&data, (&z1, &u1), None, 1.0, &lambda);
    assert_eq!(bits(&changes.rows_terms), bits(&measured.rows_terms));
    // Over the limit: no changes, and the fit is left to a true product.
    let (mut z2, mut u2) = (z, u);
    let update = update_pass(
        &data,
        (&mut z2, &mut u2, c),
        &t,
        &r,
        &lambda,
        200.0,
        (true, Some(moved - 1)),
    );
    assert!(update.changes.is_none() && update.sums.is_none());
    assert_eq!(bits(&z2), bits(&z1));
}
