//! Property tests of the engine: on random symmetric positive definite
//! problems both methods return certified complementary solutions that agree
//! with each other and, for small sizes, with brute-force enumeration of the
//! complementary bases (the solution is unique for a positive definite M).

use elcon_lcp::{
    BorderedLcp, Bound, Lcp, LcpSolution, Method, MixedLcp, MixedLcpParts, Options, Tableau,
};
use faer::linalg::solvers::Solve;
use faer::{Col, Mat, Side};
use proptest::prelude::*;

use crate::common;
use common::rel_diff;

/// M = A A^T + shift I from the entries of A (n x n, row-major).
fn spd(n: usize, a: &[f64], shift: f64) -> Mat<f64> {
    let a = Mat::from_fn(n, n, |i, j| a[i * n + j]);
    let mut m = &a * a.transpose();
    for i in 0..n {
        m[(i, i)] += shift;
    }
    m
}

/// Both answers to one contact form certified, and agreeing: the forces z
/// to 1e-9 of the largest, the free unknown (the approach) to 1e-9 of its
/// size.
fn agree(a: &LcpSolution, b: &LcpSolution) -> Result<(), TestCaseError> {
    prop_assert!(
        a.certificate.holds() && b.certificate.holds(),
        "{} / {}",
        a.certificate,
        b.certificate
    );
    prop_assert!(rel_diff(&a.z, &b.z) < 1e-9);
    prop_assert!((a.u[0] - b.u[0]).abs() <= 1e-9 * a.u[0].abs().max(1e-300));
    Ok(())
}

/// The solution of the LCP by trying every complementary basis (n <= 10).
fn brute_force(m: &Mat<f64>, q: &Col<f64>) -> Option<Col<f64>> {
    let n = q.nrows();
    let scale = q.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
    for mask in 0u32..(1 << n) {
        let act: Vec<usize> = (0..n).filter(|i| mask & (1 << i) != 0).collect();
        let k = act.len();
        let mut z = Col::<f64>::zeros(n);
        if k > 0 {
            let mss = Mat::from_fn(k, k, |i, j| m[(act[i], act[j])]);
            let Ok(llt) = mss.llt(Side::Lower) else {
                continue;
            };
            let rhs = Col::from_fn(k, |i| -q[act[i]]);
            let zs = llt.solve(&rhs);
            for (i, &a) in act.iter().enumerate() {
                z[a] = zs[i];
            }
        }
        let w = m * &z + q;
        let zmax = z.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
        if z.iter().all(|&v| v >= -1e-10 * zmax) && w.iter().all(|&v| v >= -1e-10 * scale) {
            return Some(z);
        }
    }
    None
}

/// The contact form `w = M z + b alpha + q`, `c^T z = load` with `c = -b`,
/// as a bordered LCP (`B = -b`).
fn loaded(m: Mat<f64>, b: &[f64], q: &[f64], load: f64) -> BorderedLcp {
    let n = q.len();
    BorderedLcp::new(m, Col::from_fn(n, |i| q[i]))
        .unwrap()
        .with_border(Mat::from_fn(n, 1, |i, _| -b[i]), faer::col![load])
        .unwrap()
}

/// The contact-shaped mixed form of `(m, q)`: w = M z - alpha e + |q|,
/// e^T z = `load`, alpha free.
fn contact_form(m: Mat<f64>, q: &Col<f64>, load: f64) -> BorderedLcp {
    let n = q.nrows();
    let gaps: Vec<f64> = q.iter().map(|v| v.abs()).collect();
    loaded(m, &vec![-1.0; n], &gaps, load)
}

fn problem(n: usize) -> impl Strategy<Value = (Mat<f64>, Col<f64>)> {
    (
        proptest::collection::vec(-1.0f64..1.0, n * n),
        proptest::collection::vec(-1.0f64..1.0, n),
        0.01f64..1.0,
    )
        .prop_map(move |(a, q, shift)| (spd(n, &a, shift), Col::from_fn(n, |i| q[i])))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// n <= 8: both methods equal the enumerated solution.
    #[test]
    fn small_problems_match_enumeration((m, q) in (1usize..=8).prop_flat_map(problem)) {
        let expect = brute_force(&m, &q).expect("an SPD LCP has a solution");
        let lcp = Lcp::new(m, q).unwrap();
        for method in Method::ALL {
            let sol = lcp.solve(method, &Options::default()).unwrap();
            prop_assert!(sol.certificate.holds(), "{method}: {}", sol.certificate);
            // The enumerated solution comes from a Cholesky solve of the
            // active block: both are backward stable, so they agree to a
            // small multiple of the condition number times u; the random
            // matrices have condition numbers below ~1e4 (shift >= 0.01).
            prop_assert!(rel_diff(&sol.z, &expect) < 1e-9, "{method}: {:?} vs {:?}", sol.z, expect);
        }
    }

    /// Problems that need more pivots than the tableau's delayed-update
    /// block (64) and its periodic refactorization (every 100 pivots): the
    /// tableau methods agree with block pivoting.
    #[test]
    fn past_the_update_block(
        (n, a, q) in (70usize..=140).prop_flat_map(|n| (
            Just(n),
            proptest::collection::vec(-1.0f64..1.0, n * n),
            proptest::collection::vec(-2.0f64..-0.2, n),
        )),
    ) {
        // M = A A^T / n + I and q < 0: a well-conditioned M whose solution has
        // most indices basic, about one pivot each.
        let mut m = spd(n, &a, 1.0);
        for j in 0..n {
            for i in 0..n {
                if i != j {
                    m[(i, j)] /= n as f64;
                } else {
                    m[(i, i)] = 1.0 + (m[(i, i)] - 1.0) / n as f64;
                }
            }
        }
        let lcp = Lcp::new(m, Col::from_fn(n, |i| q[i])).unwrap();
        let reference = lcp.solve(Method::BlockPivoting, &Options::default()).unwrap();
        // Each index of the solution's active set enters at least once: with
        // more than 64 of them every tableau method passes its update block.
        // (Most draws have; a soak at 1500 cases met one with fewer, where
        // Lemke's method took 63 pivots.)
        prop_assume!(reference.z.iter().filter(|&&v| v > 0.0).count() > 64);
        for method in Method::TABLEAU {
            let sol = lcp.solve(method, &Options::default()).unwrap();
            prop_assert!(sol.statistics.pivots() > 64, "{method}: {} pivots", sol.statistics.pivots());
            prop_assert!(sol.certificate.holds(), "{method}: {}", sol.certificate);
            prop_assert!(rel_diff(&sol.z, &reference.z) < 1e-9, "{method}");
        }
    }

    /// Larger problems: the methods agree with each other, both certified.
    #[test]
    fn methods_agree((m, q) in (9usize..=40).prop_flat_map(problem)) {
        let lcp = Lcp::new(m, q).unwrap();
        let a = lcp.solve(Method::RestrictedSimplex, &Options::default()).unwrap();
        for method in [Method::Lemke, Method::BlockPivoting] {
            let b = lcp.solve(method, &Options::default()).unwrap();
            prop_assert!(a.certificate.holds() && b.certificate.holds());
            prop_assert!(rel_diff(&a.z, &b.z) < 1e-9, "{method}");
            prop_assert_eq!(&a.basic, &b.basic);
        }
    }

    /// The contact-shaped mixed form (w = M z - alpha e + q, e^T z = P, alpha free):
    /// both methods agree and the certificate holds.
    #[test]
    fn mixed_contact_form((m, q) in (1usize..=30).prop_flat_map(problem), load in 0.01f64..100.0) {
        let mixed = contact_form(m, &q, load);
        let a = mixed.solve(Method::RestrictedSimplex, &Options::default()).unwrap();
        prop_assert!(a.certificate.holds(), "{}", a.certificate);
        let total: f64 = a.z.iter().sum();
        prop_assert!((total - load).abs() <= 1e-12 * load);
        for method in [Method::Lemke, Method::BlockPivoting] {
            let b = mixed.solve(method, &Options::default()).unwrap();
            prop_assert!(b.certificate.holds(), "{method}: {}", b.certificate);
            prop_assert!(rel_diff(&a.z, &b.z) < 1e-9, "{method}");
            prop_assert!((a.u[0] - b.u[0]).abs() <= 1e-9 * a.u[0].abs().max(1e-300), "{method}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// The mixed contact form past block pivoting's first prefix (32
    /// indices), so that its prefix search grows the factor in steps on
    /// random orders of the keys: it agrees with Lemke's method.
    #[test]
    fn mixed_contact_form_past_the_first_prefix(
        (m, q) in (40usize..=120).prop_flat_map(problem),
        load in 0.01f64..100.0,
    ) {
        let mixed = contact_form(m, &q, load);
        let a = mixed.solve(Method::Lemke, &Options::default()).unwrap();
        let b = mixed.solve(Method::BlockPivoting, &Options::default()).unwrap();
        agree(&a, &b)?;
        prop_assert!(!b.statistics.fell_back());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// The paper's own form: the approach alpha >= 0 is a NON-NEGATIVE extra
    /// unknown (not free). Problems are generated around a known solution
    /// (z*, w* complementary, u* >= 0), so one exists; the restricted-entry
    /// simplex must find a certified one, and since M is positive definite on
    /// the equality's null space the forces are unique and must match.
    #[test]
    fn restricted_simplex_with_non_negative_approach(
        (m, q) in (1usize..=25).prop_flat_map(problem),
        active in proptest::collection::vec(any::<bool>(), 25),
        u_star in 0.0f64..2.0,
    ) {
        let n = q.nrows();
        let z_star = Col::from_fn(n, |i| if active[i] || i == 0 { q[i].abs() + 0.1 } else { 0.0 });
        let w_star = Col::from_fn(n, |i| if active[i] || i == 0 { 0.0 } else { q[i].abs() });
        // w = M z - e u + q'  =>  q' = w* - M z* + e u*;   e^T z = P
        let qq = &w_star - &m * &z_star + Col::from_fn(n, |_| u_star);
        let load: f64 = z_star.iter().sum();
        let mixed = MixedLcp::new(MixedLcpParts {
m,
b: Mat::from_fn(n, 1, |_, _| -1.0),
q: qq,
c: Mat::from_fn(1, n, |_, _| 1.0),
d: Mat::zeros(1, 1),
r: Col::from_fn(1, |_| -load),
bounds: vec![Bound::NonNegative],
}).unwrap();
        let sol = mixed.solve(Method::RestrictedSimplex, &Options::default()).unwrap();
        prop_assert!(sol.certificate.holds(), "{}", sol.certificate);
        prop_assert!(rel_diff(&sol.z, &z_star) < 1e-9, "{:?} vs {:?}", sol.z, z_star);
    }
}

#[test]
fn trivial_solution_when_q_is_non_negative() {
    let lcp = Lcp::new(Mat::identity(3, 3), Col::from_fn(3, |i| i as f64)).unwrap();
    for method in Method::ALL {
        let sol = lcp.solve(method, &Options::default()).unwrap();
        assert!(sol.z.iter().all(|&v| v == 0.0));
        assert_eq!(sol.statistics.pivots(), 0, "{method}");
    }
}

#[test]
fn known_two_by_two() {
    // z = (4/3, 7/3): both active.
    let m = faer::mat![[2.0, 1.0], [1.0, 2.0]];
    let q = faer::col![-5.0, -6.0];
    let lcp = Lcp::new(m, q).unwrap();
    for method in Method::ALL {
        let sol = lcp.solve(method, &Options::default()).unwrap();
        assert!((sol.z[0] - 4.0 / 3.0).abs() < 1e-14);
        assert!((sol.z[1] - 7.0 / 3.0).abs() < 1e-14);
        assert!(sol.w.iter().all(|w| w.abs() < 1e-14));
    }
    // Only the second active: z = (0, 1/2), w0 = 1/2 - ... = q0 + 0.5 = 1.5.
    let lcp = Lcp::new(faer::mat![[2.0, 1.0], [1.0, 2.0]], faer::col![1.0, -1.0]).unwrap();
    for method in Method::ALL {
        let sol = lcp.solve(method, &Options::default()).unwrap();
        assert_eq!(sol.z[0], 0.0);
        assert!((sol.z[1] - 0.5).abs() < 1e-15);
        assert!((sol.w[0] - 1.5).abs() < 1e-15);
        assert_eq!(sol.basic, vec![false, true]);
    }
}

/// Deferred unknowns stay at 0 through phase 1 and enter only in phase 2.
#[test]
fn deferred_unknowns_enter_only_in_phase_two() {
    use elcon_lcp::ProgramBuilder;
    use faer::col;
    let build = |with_cost: bool| {
        // x + d = 1, x >= 0, d free and deferred; optionally minimize x.
        let mut p = ProgramBuilder::new(1);
        let x = p
            .dense_column("x", col![1.0].as_ref(), Bound::NonNegative)
            .unwrap();
        let d = p
            .dense_column("d", col![1.0].as_ref(), Bound::Free)
            .unwrap();
        p.defer(d..d + 1).unwrap();
        if with_cost {
            p.cost(x, 1.0).unwrap();
        }
        p.rhs(col![1.0].as_ref()).unwrap();
        (p.build().unwrap(), x, d)
    };
    let (feasible, x, d) = build(false);
    let sol = feasible.solve(&Options::default()).unwrap();
    assert_eq!(
        (sol.x[x], sol.x[d]),
        (1.0, 0.0),
        "phase 1 alone leaves d at 0"
    );
    let (optimal, x, d) = build(true);
    let sol = optimal.solve(&Options::default()).unwrap();
    assert!(sol.certificate.holds());
    assert_eq!((sol.x[x], sol.x[d]), (0.0, 1.0), "phase 2 moves d");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Lemke's method on the symmetric tableau (a symmetric M, the default
    /// options; it ends with one Cholesky) against the general tableau
    /// (`Tableau::General`), in the standard and the
    /// contact forms, up to past the symmetric tableau's update block (64
    /// pivots). Random A A^T + shift I have off-diagonal entries of both
    /// signs, so indices also leave the active set along the path.
    #[test]
    fn symmetric_tableau_matches_the_general_one(
        (m, q) in (2usize..=110).prop_flat_map(problem),
        load in 0.01f64..100.0,
    ) {
        let general = Options {
            tableau: Tableau::General,
            ..Options::default()
        };
        let lcp = Lcp::new(m.clone(), q.clone()).unwrap();
        let a = lcp.solve(Method::Lemke, &Options::default()).unwrap();
        let b = lcp.solve(Method::Lemke, &general).unwrap();
        if q.iter().any(|&v| v < 0.0) {
            prop_assert!(a.statistics.symmetric_tableau(), "the symmetric tableau ran");
        }
        prop_assert!(!b.statistics.symmetric_tableau());
        prop_assert!(a.certificate.holds() && b.certificate.holds(), "{} / {}", a.certificate, b.certificate);
        prop_assert!(rel_diff(&a.z, &b.z) < 1e-9);
        let mixed = contact_form(m, &q, load);
        let a = mixed.solve(Method::Lemke, &Options::default()).unwrap();
        let b = mixed.solve(Method::Lemke, &general).unwrap();
        prop_assert!(a.statistics.symmetric_tableau(), "the symmetric tableau ran");
        agree(&a, &b)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// The restricted-entry simplex on the symmetric tableau (the contact
    /// form with a symmetric M and q >= 0, the default options; it ends
    /// with one Cholesky) against the same rule on the general tableau
    /// (`Tableau::General`), up to past the symmetric
    /// tableau's update block. Off-diagonal entries of both signs make
    /// indices leave the active set, and some separated indices admissible
    /// to a restricted entry.
    #[test]
    fn symmetric_tableau_runs_the_restricted_simplex_as_the_general_one(
        (m, q) in (2usize..=110).prop_flat_map(problem),
        load in 0.01f64..100.0,
    ) {
        let n = q.nrows();
        let general = Options {
            tableau: Tableau::General,
            refactor_interval: Some(4 * n),
            ..Options::default()
        };
        let mixed = contact_form(m, &q, load);
        let a = mixed.solve(Method::RestrictedSimplex, &Options::default()).unwrap();
        let b = mixed.solve(Method::RestrictedSimplex, &general).unwrap();
        prop_assert!(a.statistics.symmetric_tableau(), "the symmetric tableau ran: {:?}", a.statistics);
        prop_assert!(!b.statistics.symmetric_tableau());
        agree(&a, &b)?;
        prop_assert!(a.statistics.pivots() <= 4 * n + 1, "{:?}", a.statistics);
    }
}

/// Three points in a row, M = tridiag(0.6, 1, 0.6) (positive definite),
/// gaps (1, 0, 1), load 20: a point leaves the contact set on the way.
fn three_in_a_row() -> BorderedLcp {
    let m = faer::mat![[1.0, 0.6, 0.0], [0.6, 1.0, 0.6], [0.0, 0.6, 1.0]];
    loaded(m, &[-1.0; 3], &[1.0, 0.0, 1.0], 20.0)
}

#[test]
fn the_symmetric_tableau_follows_a_point_out_of_contact() {
    // Three points in a row, M = tridiag(0.6, 1, 0.6) (positive definite),
    // gaps (1, 0, 1), load 20. The middle point touches at alpha = 0 and
    // carries z_1 = alpha; the outer two touch together at alpha = 2.5 (a tie:
    // one pivot of length 0). Then dz/dalpha = M^{-1} e = (10, -5, 10) / 7, so the
    // middle point unloads and leaves at alpha = 6 (load 10); on {0, 2}, M = I:
    // z_0 = z_2 = alpha - 1 = 10 at alpha = 11, and w_1 = 0.6 * 20 - 11 = 1.
    let mixed = three_in_a_row();
    let sol = mixed.solve(Method::Lemke, &Options::default()).unwrap();
    let s = &sol.statistics;
    assert!(s.symmetric_tableau(), "the symmetric tableau ran");
    // In: 1, 0, 2 (after a step of length 0); out: 1.
    assert_eq!((s.pivots(), s.degenerate_pivots()), (4, 1), "{s:?}");
    assert_eq!(sol.basic, vec![true, false, true]);
    let expect = [10.0, 0.0, 10.0];
    for i in 0..3 {
        assert!((sol.z[i] - expect[i]).abs() <= 1e-13 * 10.0, "{:?}", sol.z);
    }
    assert!((sol.u[0] - 11.0).abs() <= 1e-13 * 11.0);
    assert!((sol.w[1] - 1.0).abs() <= 1e-13);
}

#[test]
fn the_restricted_simplex_on_the_symmetric_tableau_takes_the_general_one_s_pivots() {
    // The three points of the test above, under the paper's rule. The
    // approach enters at the first contact (alpha = 0, a step of length 0);
    // z_1 enters and w_0 leaves at alpha = 2.5 (tied with w_2, which leaves
    // at the next pivot, of length 0); z_0 enters; z_2 enters and z_1
    // leaves at alpha = 6; w_1 enters and the load row's artificial leaves.
    let mixed = three_in_a_row();
    let swept = mixed
        .solve(Method::RestrictedSimplex, &Options::default())
        .unwrap();
    let general = Options {
        tableau: Tableau::General,
        refactor_interval: Some(100),
        ..Options::default()
    };
    let general = mixed.solve(Method::RestrictedSimplex, &general).unwrap();
    let (s, g) = (&swept.statistics, &general.statistics);
    assert!(s.symmetric_tableau() && !g.symmetric_tableau(), "{s:?}");
    assert_eq!((s.pivots(), s.degenerate_pivots()), (5, 2), "{s:?}");
    assert_eq!(
        (s.pivots(), s.degenerate_pivots()),
        (g.pivots(), g.degenerate_pivots()),
        "{g:?}"
    );
    assert_eq!(swept.basic, vec![true, false, true]);
    let expect = [10.0, 0.0, 10.0];
    for i in 0..3 {
        assert!(
            (swept.z[i] - expect[i]).abs() <= 1e-13 * 10.0,
            "{:?}",
            swept.z
        );
    }
    assert!((swept.u[0] - 11.0).abs() <= 1e-13 * 11.0);
}

#[test]
fn the_restricted_simplex_on_the_symmetric_tableau_stops_where_the_load_is_met() {
    // Loads met exactly when point 1 touches (found by review): the load
    // row's artificial reaches zero in a tie with w_1, which leaves instead.
    // Phase 1 ends there, as on the general tableau; it used to go on with
    // a step of length 0 (one pivot more), and on the singular M below to
    // try the singular block {0, 1} and fall back.
    let general = Options {
        tableau: Tableau::General,
        refactor_interval: Some(100),
        ..Options::default()
    };
    let m = faer::mat![[1.0, 0.75], [0.75, 1.0]];
    // z_0 = alpha until w_1 = 1 + 0.75 alpha - 2 alpha = 0: alpha = 0.8, load 0.8.
    let mixed = loaded(m, &[-1.0, -2.0], &[0.0, 1.0], 0.8);
    let a = mixed
        .solve(Method::RestrictedSimplex, &Options::default())
        .unwrap();
    let b = mixed.solve(Method::RestrictedSimplex, &general).unwrap();
    let (s, g) = (&a.statistics, &b.statistics);
    assert!(s.symmetric_tableau(), "{s:?}");
    assert_eq!(
        (s.pivots(), s.degenerate_pivots()),
        (g.pivots(), g.degenerate_pivots()),
        "{s:?} / {g:?}"
    );
    assert_eq!(a.basic, vec![true, false]);
    assert!((a.z[0] - 0.8).abs() <= 1e-15 && a.z[1] == 0.0 && (a.u[0] - 0.8).abs() <= 1e-15);
    // M singular: z_0 = alpha / 1, w_1 = 1 + alpha - 2 alpha = 0 at alpha = 1 = load.
    let singular = loaded(
        faer::mat![[1.0, 1.0], [1.0, 1.0]],
        &[-1.0, -2.0],
        &[0.0, 1.0],
        1.0,
    );
    let a = singular
        .solve(Method::RestrictedSimplex, &Options::default())
        .unwrap();
    assert!(a.statistics.symmetric_tableau(), "{:?}", a.statistics);
    assert_eq!(a.statistics.pivots(), 2, "{:?}", a.statistics);
    assert!((a.z[0] - 1.0).abs() <= 1e-15 && a.z[1] == 0.0);
}

#[test]
fn the_restricted_simplex_on_the_symmetric_tableau_reads_kappa_without_squares() {
    // b and c of order 1e154 and up (found by review): kappa as
    // sum(c b) / sum(b b) overflowed to inf / inf, every reduced cost was
    // NaN, and the final solve's Schur complement c M^{-1} b overflowed too;
    // the solve fell back to the general tableau. Kappa is now read as
    // c_i / -b_i at the largest b, and b and c are taken in units of their
    // largest entries (powers of two) by the tableau and the final solve.
    for scale in [1.0, 1e153, 1e154, 1e200, 1e300] {
        let m = faer::mat![[2.0, 0.5], [0.5, 1.0]];
        let mixed = loaded(m, &[-scale, -2.0 * scale], &[0.1, 0.03], scale);
        let a = mixed
            .solve(Method::RestrictedSimplex, &Options::default())
            .unwrap();
        assert!(
            a.statistics.symmetric_tableau(),
            "{scale:e}: {:?}",
            a.statistics
        );
        assert!(a.certificate.holds(), "{scale:e}: {}", a.certificate);
    }
}

#[test]
fn the_restricted_simplex_leaves_the_symmetric_tableau_where_m_is_not_positive_definite() {
    // M = [[1, -2], [-2, 1]] (symmetric, indefinite), gaps (0, 0.5), load 10:
    // point 0 carries the load until point 1 touches at alpha = 1/6, whose
    // Schur complement 1 - 4 < 0 is no pivot of a positive definite block.
    // The general tableau finishes (the pivots of both attempts counted).
    let mixed = loaded(
        faer::mat![[1.0, -2.0], [-2.0, 1.0]],
        &[-1.0, -1.0],
        &[0.0, 0.5],
        10.0,
    );
    let general = Options {
        tableau: Tableau::General,
        refactor_interval: Some(100),
        ..Options::default()
    };
    let a = mixed.solve(Method::RestrictedSimplex, &Options::default());
    let b = mixed.solve(Method::RestrictedSimplex, &general);
    match (a, b) {
        (Ok(a), Ok(b)) => {
            assert!(!a.statistics.symmetric_tableau(), "{:?}", a.statistics);
            assert!(a.certificate.holds(), "{}", a.certificate);
            // The symmetric tableau's two pivots: the approach, then z_0.
            assert_eq!(a.statistics.pivots(), b.statistics.pivots() + 2);
            assert!(rel_diff(&a.z, &b.z) < 1e-12);
        }
        (a, b) => panic!("{a:?} / {b:?}"),
    }
}

#[test]
fn the_symmetric_tableau_judges_pivots_in_the_data_s_own_units() {
    // Without equilibration the data keep their units. A pivot test against
    // an absolute 1 (found by review) refused the first pivot of a matrix of
    // order 1e-12, and an index leaving the set at order 1e12; each is a
    // positive definite problem the symmetric tableau must finish.
    let raw = Options {
        equilibrate: false,
        ..Options::default()
    };
    let small = faer::mat![[2.0, 1.0, 1.0], [1.0, 2.0, 1.0], [1.0, 1.0, 2.0]] * 1e-12;
    let large = faer::mat![
        [1.875, 1.0625, 0.75],
        [1.0625, 1.0625, 0.5625],
        [0.75, 0.5625, 1.4375]
    ] * 1e12;
    for (m, q) in [
        (small, faer::col![-1.0, -0.9, -0.05] * 1e-12),
        (large, faer::col![-1.25, -1.25, -1.25] * 1e12),
    ] {
        let expect = brute_force(&m, &q).expect("an SPD LCP has a solution");
        let sol = Lcp::new(m, q).unwrap().solve(Method::Lemke, &raw).unwrap();
        assert!(sol.statistics.symmetric_tableau(), "{:?}", sol.statistics);
        assert!(sol.certificate.holds(), "{}", sol.certificate);
        assert!(
            rel_diff(&sol.z, &expect) < 1e-12,
            "{:?} vs {:?}",
            sol.z,
            expect
        );
    }
}
