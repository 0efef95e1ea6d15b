//! Bordered LCPs with k = 1, 2, 3 free unknowns and rows (the contact
//! problem's approach and two tilts): `w = M z - B λ + q`, `B^T z = b`. On
//! random symmetric positive definite problems built around a known
//! solution, every method on every tableau returns that solution, certified
//! from the original data: against brute-force enumeration of the active
//! sets for small n, against Lemke's general tableau for larger n.

use elcon_lcp::{BorderedLcp, LcpError, LcpSolution, Method, OperatorLcp, Options, Tableau};
use faer::{Col, Mat};
use proptest::prelude::*;

use crate::common;
use common::rel_diff;

/// M = A A^T / n + shift I from the entries of A (n x n, row-major).
fn spd(n: usize, a: &[f64], shift: f64) -> Mat<f64> {
    let a = Mat::from_fn(n, n, |i, j| a[i * n + j]);
    let mut m = &a * a.transpose() * (1.0 / n as f64);
    for i in 0..n {
        m[(i, i)] += shift;
    }
    m
}

/// A bordered problem and its solution.
struct Known {
    problem: BorderedLcp,
    z: Col<f64>,
    lambda: Col<f64>,
    m: Mat<f64>,
    border: Mat<f64>,
    q: Col<f64>,
    resultant: Col<f64>,
}

/// A problem around a known solution: one border column is ones (an
/// approach: the first, or with `ones_last` the last, so that a border of
/// several rows starts from its first contact rather than along the
/// approach), the others `coords` (tilts' lever arms); the active set
/// holds at least k indices, `z* > 0` on it, `w* > 0` off it, `λ*` given;
/// then `q = w* - M z* + B λ*` and `b = B^T z*`.
fn known(m: Mat<f64>, k: usize, draw: &Draw, ones_last: bool) -> Known {
    let n = m.nrows();
    let ones = if ones_last { k - 1 } else { 0 };
    let border = Mat::from_fn(n, k, |i, l| {
        if l == ones {
            1.0
        } else {
            draw.coords[l * 60 + i]
        }
    });
    let active: Vec<bool> = (0..n).map(|i| i < k || draw.active[i]).collect();
    let z = Col::from_fn(n, |i| if active[i] { 0.1 + draw.values[i] } else { 0.0 });
    let w = Col::from_fn(n, |i| if active[i] { 0.0 } else { 0.1 + draw.values[i] });
    let lambda = Col::from_fn(k, |l| draw.lambda[l]);
    let q = &w - &m * &z + &border * &lambda;
    let resultant = border.transpose() * &z;
    let problem = BorderedLcp::new(m.clone(), q.clone())
        .unwrap()
        .with_border(border.clone(), resultant.clone())
        .unwrap();
    Known {
        problem,
        z,
        lambda,
        m,
        border,
        q,
        resultant,
    }
}

/// The same problem with no border: `q - B λ*` in place of `q`, so that
/// `z*` (with the same `w*`) solves the LCP `w = M z + q`.
fn without_border(k: Known) -> Known {
    let n = k.q.nrows();
    let q = &k.q - &k.border * &k.lambda;
    Known {
        problem: BorderedLcp::new(k.m.clone(), q.clone()).unwrap(),
        z: k.z,
        lambda: Col::zeros(0),
        m: k.m,
        border: Mat::zeros(n, 0),
        q,
        resultant: Col::zeros(0),
    }
}

/// The random draws a problem is made of (up to 60 points, 3 columns).
#[derive(Debug, Clone)]
struct Draw {
    /// Up to three columns of 60 levers.
    coords: Vec<f64>,
    active: Vec<bool>,
    values: Vec<f64>,
    lambda: Vec<f64>,
}

fn draw() -> impl Strategy<Value = Draw> {
    (
        proptest::collection::vec(-1.0f64..1.0, 180),
        proptest::collection::vec(any::<bool>(), 60),
        proptest::collection::vec(0.0f64..1.0, 60),
        proptest::collection::vec(-1.0f64..1.0, 3),
    )
        .prop_map(|(coords, active, values, lambda)| Draw {
            coords,
            active,
            values,
            lambda,
        })
}

/// A xorshift generator of uniform draws in [0, 1) from `seed`: a fixed
/// set of random problems, the same on every run.
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut rng = seed;
    move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random problem (see [`known`]) of `points.start + next() * points.len()`
/// points, `M` from [`spd`] with a shift 0.3, drawn from `next` (the size,
/// then `A`, then the [`Draw`]'s fields in order).
fn random_known(
    next: &mut impl FnMut() -> f64,
    points: std::ops::Range<usize>,
    k: usize,
    ones_last: bool,
) -> Known {
    let n = points.start + (next() * points.len() as f64) as usize;
    let a: Vec<f64> = (0..n * n).map(|_| 2.0 * next() - 1.0).collect();
    let draw = Draw {
        coords: (0..180).map(|_| 2.0 * next() - 1.0).collect(),
        active: (0..60).map(|_| next() < 0.5).collect(),
        values: (0..60).map(|_| next()).collect(),
        lambda: (0..3).map(|_| 2.0 * next() - 1.0).collect(),
    };
    known(spd(n, &a, 0.3), k, &draw, ones_last)
}

/// For each case `(points, k, ones_last)`, 40 random problems
/// ([`random_known`], drawn from [`uniform`] of `seed` across the cases)
/// solved by `method`: each returns the known solution and passes `check`
/// (its own assertions), and `check` answers true for at least nine in ten
/// of them (else the message `message(k, counted, trials)`).
fn nearly_every<const C: usize>(
    seed: u64,
    cases: [(std::ops::Range<usize>, usize, bool); C],
    method: Method,
    check: impl Fn(&Known, &LcpSolution) -> bool,
    message: impl Fn(usize, usize, usize) -> String,
) {
    let mut next = uniform(seed);
    let trials = 40;
    for (points, k, ones_last) in cases {
        let mut counted = 0;
        for _ in 0..trials {
            let known = random_known(&mut next, points.clone(), k, ones_last);
            let sol = known.problem.solve(method, &Options::default()).unwrap();
            let counts = check(&known, &sol);
            assert!(rel_diff(&sol.z, &known.z) < 1e-8);
            counted += usize::from(counts);
        }
        assert!(
            counted * 10 >= trials * 9,
            "{}",
            message(k, counted, trials)
        );
    }
}

/// The solution by trying every active set J with |J| >= k: the KKT
/// system `[M_JJ -B_J; B_J^T 0] [z_J; λ] = [-q_J; b]` by an LU, kept
/// when `z_J >= 0` and `w >= 0` (n <= 10).
fn brute_force(k: &Known) -> Option<(Col<f64>, Col<f64>)> {
    use faer::linalg::solvers::Solve;
    let n = k.q.nrows();
    let kb = k.border.ncols();
    let scale = k.q.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
    for mask in 0u32..(1 << n) {
        let act: Vec<usize> = (0..n).filter(|i| mask & (1 << i) != 0).collect();
        let j = act.len();
        if j < kb {
            continue;
        }
        let kkt = Mat::from_fn(j + kb, j + kb, |r, c| match (r < j, c < j) {
            (true, true) => k.m[(act[r], act[c])],
            (true, false) => -k.border[(act[r], c - j)],
            (false, true) => k.border[(act[c], r - j)],
            (false, false) => 0.0,
        });
        let rhs = Col::from_fn(j + kb, |r| {
            if r < j {
                -k.q[act[r]]
            } else {
                k.resultant[r - j]
            }
        });
        let lu = kkt.partial_piv_lu();
        let x = lu.solve(&rhs);
        if !x.iter().all(|v| v.is_finite()) {
            continue;
        }
        let mut z = Col::<f64>::zeros(n);
        for (r, &i) in act.iter().enumerate() {
            z[i] = x[r];
        }
        let lambda = Col::from_fn(kb, |l| x[j + l]);
        let w = &k.m * &z - &k.border * &lambda + &k.q;
        let residual = &kkt * &x - &rhs;
        let solved = residual.iter().all(|v| v.abs() <= 1e-9 * scale.max(1.0));
        let zmax = z.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
        if solved && z.iter().all(|&v| v >= -1e-10 * zmax) && w.iter().all(|&v| v >= -1e-10 * scale)
        {
            return Some((z, lambda));
        }
    }
    None
}

/// The worst residual of `(z, λ)` computed here from the problem's data,
/// not by the engine: `-min z`, `-min w`, `max |z_i w_i|` and `|B^T z - b|`,
/// each relative to the size of the terms it is made of.
fn residuals(k: &Known, z: &Col<f64>, lambda: &Col<f64>) -> f64 {
    let n = k.q.nrows();
    let w = &k.m * z - &k.border * lambda + &k.q;
    let terms = Col::from_fn(n, |i| {
        (0..n).map(|j| (k.m[(i, j)] * z[j]).abs()).sum::<f64>()
            + (0..lambda.nrows())
                .map(|l| (k.border[(i, l)] * lambda[l]).abs())
                .sum::<f64>()
            + k.q[i].abs()
    });
    let w_scale = terms
        .iter()
        .fold(0.0f64, |a, v| a.max(*v))
        .max(f64::MIN_POSITIVE);
    let z_scale = z
        .iter()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let equality = k.border.transpose() * z - &k.resultant;
    let eq_scale = k
        .resultant
        .iter()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(z_scale);
    let mut worst = 0.0f64;
    for i in 0..n {
        worst = worst
            .max(-z[i] / z_scale)
            .max(-w[i] / w_scale)
            .max((z[i] * w[i]).abs() / (z_scale * w_scale));
    }
    equality
        .iter()
        .fold(worst, |a, v| a.max(v.abs() / eq_scale))
}

/// Every method with every tableau that applies: `(method, tableau)`.
const ROUTES: [(Method, Tableau); 8] = [
    (Method::Lemke, Tableau::Auto),
    (Method::Lemke, Tableau::Symmetric),
    (Method::Lemke, Tableau::General),
    (Method::RestrictedSimplex, Tableau::Auto),
    (Method::RestrictedSimplex, Tableau::General),
    (Method::BlockPivoting, Tableau::Auto),
    (Method::BlockPivoting, Tableau::General),
    (Method::ConjugateGradient, Tableau::Auto),
];

/// Solves `k` by every route; each answer certified and equal to `(z, λ)`
/// to `tolerance`. The symmetric tableau alone may break down (a border
/// singular on the active set met along the path), never answer wrongly.
/// The condition number of the border's rows on the known contact set.
fn border_conditioning(k: &Known) -> f64 {
    let rows: Vec<usize> = (0..k.z.nrows()).filter(|&i| k.z[i] > 0.0).collect();
    let b = Mat::from_fn(rows.len(), k.border.ncols(), |a, j| k.border[(rows[a], j)]);
    match b.singular_values() {
        Ok(s) if !s.is_empty() => {
            let (hi, lo) = s
                .iter()
                .fold((0.0f64, f64::INFINITY), |(h, l), &v| (h.max(v), l.min(v)));
            if lo > 0.0 { hi / lo } else { f64::INFINITY }
        }
        _ => f64::INFINITY,
    }
}

fn check_routes(k: &Known, z: &Col<f64>, lambda: &Col<f64>, tolerance: f64) -> Result<(), String> {
    for (method, tableau) in ROUTES {
        let options = Options {
            tableau,
            ..Options::default()
        };
        let sol = match k.problem.solve(method, &options) {
            Ok(sol) => sol,
            Err(LcpError::BrokeDown { .. }) if tableau == Tableau::Symmetric => continue,
            Err(e) => return Err(format!("{method} / {}: {e}", tableau.name())),
        };
        let label = format!("{method} / {}", tableau.name());
        if !sol.certificate.holds() {
            return Err(format!("{label}: {}", sol.certificate));
        }
        let residual = residuals(k, &sol.z, &sol.u);
        if residual > 1e-10 {
            return Err(format!(
                "{label}: residual {residual:.2e} from the test's own data"
            ));
        }
        // The conjugate gradient's λ is the least-squares fit of its
        // gradient on the contact set: as exact as its certified residuals
        // (1e-12 of their scale) through B_J's conditioning, so where B_J is
        // square and ill-conditioned λ itself may differ at 1e-8 while the
        // border's force B λ, what the residuals see, agrees. Its B λ is
        // compared; the exact methods' λ itself.
        let lambda_differs = if method == Method::ConjugateGradient {
            rel_diff(&(&k.border * &sol.u), &(&k.border * lambda)) > tolerance
        } else {
            rel_diff(&sol.u, lambda) > tolerance
        };
        if rel_diff(&sol.z, z) > tolerance || lambda_differs {
            return Err(format!(
                "{label}: z {:?} against {:?}, λ {:?} against {:?}",
                sol.z, z, sol.u, lambda
            ));
        }
    }
    Ok(())
}

/// `(n, k, A's entries, shift)` of [`spd`] with a border of k = 1, 2, 3
/// rows and n in `sizes(k)`.
fn sized(
    sizes: fn(usize) -> std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = (usize, usize, Vec<f64>, f64)> {
    sized_with(1..=3, sizes)
}

/// [`sized`] with a border of `rows` rows.
fn sized_with(
    rows: std::ops::RangeInclusive<usize>,
    sizes: fn(usize) -> std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = (usize, usize, Vec<f64>, f64)> {
    rows.prop_flat_map(move |k| {
        sizes(k).prop_flat_map(move |n| {
            (
                Just(n),
                Just(k),
                proptest::collection::vec(-1.0f64..1.0, n * n),
                0.05f64..1.0,
            )
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// n <= 8, k = 1, 2, 3: every route equals the enumerated solution,
    /// which equals the known one.
    #[test]
    fn small_bordered_problems_match_enumeration(
        (n, k, a, shift) in sized(|k| k..=8),
        draw in draw(),
        ones_last in any::<bool>(),
    ) {
        let known = known(spd(n, &a, shift), k, &draw, ones_last);
        // λ is as well determined as the border's rows on the contact set:
        // a nearly dependent B_J (the coordinates drawn close together)
        // leaves it ill-conditioned for every method, the exact ones too.
        prop_assume!(border_conditioning(&known) < 1e4);
        let (z, lambda) = brute_force(&known).expect("the known solution is one");
        prop_assert!(rel_diff(&z, &known.z) < 1e-9 && rel_diff(&lambda, &known.lambda) < 1e-8);
        if let Err(e) = check_routes(&known, &z, &lambda, 1e-8) {
            prop_assert!(false, "{}", e);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// 9 <= n <= 60, k = 1, 2, 3: every route equals Lemke's general
    /// tableau's answer and the known solution.
    #[test]
    fn larger_bordered_problems_agree_with_the_general_tableau(
        (n, k, a, shift) in sized(|_| 9..=60),
        draw in draw(),
        ones_last in any::<bool>(),
    ) {
        let known = known(spd(n, &a, shift), k, &draw, ones_last);
        let general = Options { tableau: Tableau::General, ..Options::default() };
        let reference = known.problem.solve(Method::Lemke, &general).unwrap();
        prop_assert!(rel_diff(&reference.z, &known.z) < 1e-8);
        if let Err(e) = check_routes(&known, &reference.z, &reference.u, 1e-8) {
            prop_assert!(false, "{}", e);
        }
    }
}

/// The symmetric tableau finishes borders of two and three rows, not only
/// one, from either start (along the approach, or from the first contact
/// of all the rows): over a fixed set of random problems, nearly every
/// Lemke solve returns from it.
#[test]
fn the_symmetric_tableau_solves_borders_of_several_rows() {
    let cases = [(2, false), (3, false), (2, true), (3, true)].map(|(k, ones)| (20..50, k, ones));
    nearly_every(
        0x2545_f491_4f6c_dd1du64,
        cases,
        Method::Lemke,
        |_, sol| {
            assert!(sol.certificate.holds());
            sol.statistics.symmetric_tableau()
        },
        |k, symmetric, trials| format!("k = {k}: {symmetric} of {trials} on the symmetric tableau"),
    );
}

/// Block pivoting answers borders of two and three rows itself (its k x k
/// Schur complement of the border), not through its fallback to Lemke's
/// method: over a fixed set of random problems, nearly every solve returns
/// from block pivoting's own attempt.
#[test]
fn block_pivoting_solves_borders_of_several_rows_itself() {
    nearly_every(
        0x9e37_79b9_7f4a_7c15u64,
        [1, 2, 3].map(|k| (10..60, k, false)),
        Method::BlockPivoting,
        |known, sol| {
            assert!(residuals(known, &sol.z, &sol.u) < 1e-10);
            let returned = sol.statistics.returned().expect("an answer was returned");
            returned.method == Method::BlockPivoting
        },
        |k, own, trials| format!("k = {k}: block pivoting answered {own} of {trials} itself"),
    );
}

/// The same problems with `M` given only by its products (an
/// [`OperatorLcp`]): the conjugate gradient returns the known solution,
/// certified from products of the operator, and the pivoting methods refuse
/// the problem naming the method to use.
#[test]
fn operator_problems_solve_by_the_conjugate_gradient() {
    let mut next = uniform(0x1234_5678_9abc_def1u64);
    for k in [0, 1, 2, 3] {
        for _ in 0..20 {
            let known = random_known(&mut next, 10..60, k.max(1), false);
            // k = 0: the standard LCP of the same M and q (its own solution).
            let m = known.m.as_ref();
            let border = known.border.as_ref().subcols(0, k);
            let resultant = known.resultant.as_ref().subrows(0, k);
            let lcp = OperatorLcp::new(&m, known.q.as_ref())
                .unwrap()
                .with_border(border, resultant)
                .unwrap();
            let sol = lcp
                .solve(Method::ConjugateGradient, &Options::default())
                .unwrap();
            assert!(sol.certificate.holds(), "k = {k}: {}", sol.certificate);
            let exact = BorderedLcp::new(known.m.clone(), known.q.clone())
                .unwrap()
                .with_border(border.to_owned(), resultant.to_owned())
                .unwrap()
                .solve(Method::BlockPivoting, &Options::default())
                .unwrap();
            assert!(rel_diff(&sol.z, &exact.z) < 1e-8, "k = {k}");
            assert!(rel_diff(&sol.w, &exact.w) < 1e-8, "k = {k}");
            if k > 0 {
                assert!(rel_diff(&sol.z, &known.z) < 1e-8, "k = {k}");
            }
            let e = lcp.solve(Method::Lemke, &Options::default()).unwrap_err();
            assert!(
                matches!(e, LcpError::Unsupported { .. })
                    && e.to_string().contains("conjugate gradient"),
                "{e}"
            );
        }
    }
}

/// The conjugate gradient's iterations on a small problem of `n` points
/// are at most `8 n + 8`: a few runs of at most n conjugate steps each
/// while the contact set settles (its cap, 10,000, stands far above).
fn small_iteration_bound(n: usize) -> usize {
    8 * n + 8
}

/// The problem on which the conjugate gradient cycled to its cap: three
/// points, two rows (an approach and a tilt whose third lever is 0),
/// `M = 0.05 I`, the solution on the first two points. Its first step
/// (length `1 / 0.05`) clipped two points, and restoring the rows from the
/// one point left returned the iterate to where the step started; the step
/// is now cut where the third point leaves, which is the solution.
#[test]
fn the_conjugate_gradient_does_not_cycle_on_a_contact_set_of_the_rows_size() {
    let draw = Draw {
        coords: (0..180)
            .map(|i| match i {
                60 => 0.5575992114997591,
                61 => 0.24455614828999522,
                _ => 0.0,
            })
            .collect(),
        active: (0..60).map(|i| i < 2).collect(),
        values: (0..60)
            .map(|i| [0.11099065627941541, 0.20865462846550736, 0.7743935434498561][i.min(2)])
            .collect(),
        lambda: vec![0.4366746602559435, 0.7757937533716053, 0.0],
    };
    let known = known(spd(3, &[0.0; 9], 0.05), 2, &draw, false);
    let sol = known
        .problem
        .solve(Method::ConjugateGradient, &Options::default())
        .unwrap();
    assert!(sol.certificate.holds(), "{}", sol.certificate);
    assert!(rel_diff(&sol.z, &known.z) < 1e-12, "{:?}", sol.z);
    let iterations = sol.statistics.iterations();
    assert!(
        (1..=small_iteration_bound(3)).contains(&iterations),
        "{iterations} iterations"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// n <= 12, k = 0 to 3: the conjugate gradient returns the known
    /// solution, certified (by the engine and from the test's own data), in
    /// at most [`small_iteration_bound`] iterations.
    #[test]
    fn the_conjugate_gradient_finishes_small_problems_in_a_few_times_their_size(
        (n, k, a, shift) in sized_with(0..=3, |k| k.max(1)..=12),
        draw in draw(),
        ones_last in any::<bool>(),
    ) {
        let bordered = known(spd(n, &a, shift), k.max(1), &draw, ones_last);
        prop_assume!(border_conditioning(&bordered) < 1e4);
        let known = if k == 0 { without_border(bordered) } else { bordered };
        let sol = known
            .problem
            .solve(Method::ConjugateGradient, &Options::default())
            .unwrap();
        prop_assert!(sol.certificate.holds(), "{}", sol.certificate);
        prop_assert!(residuals(&known, &sol.z, &sol.u) < 1e-10);
        prop_assert!(rel_diff(&sol.z, &known.z) < 1e-8, "{:?} against {:?}", sol.z, known.z);
        let iterations = sol.statistics.iterations();
        prop_assert!(
            iterations <= small_iteration_bound(n),
            "{} iterations at n = {}, k = {}", iterations, n, k
        );
    }
}
