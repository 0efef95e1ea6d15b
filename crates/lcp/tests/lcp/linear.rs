//! Linear systems `M X = R`: a dense symmetric positive definite `M` by its
//! Cholesky factorization, against faer's own solve; the same system by its
//! products (the conjugate gradient), agreeing to the tolerance; an
//! indefinite `M`, which the dense route solves by its LU fallback (in the
//! log) and the operator route refuses with a typed breakdown; and the
//! inputs and limits that are errors.

use elcon_lcp::{
    Breakdown, LcpError, LinearMethod, LinearSolution, LinearSystem, Method, Options, Outcome,
    Reason, Tolerances,
};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side, mat};

use crate::common;
use common::rel_diff;

/// M = A A^T / n + I (n x n), entries of A from a fixed sequence.
fn spd(n: usize) -> Mat<f64> {
    let a = Mat::from_fn(n, n, |i, j| ((7 * i + 3 * j) as f64).sin());
    let mut m = &a * a.transpose() * (1.0 / n as f64);
    for i in 0..n {
        m[(i, i)] += 1.0;
    }
    m
}

/// Three right-hand sides, the last zero.
fn rhs(n: usize) -> Mat<f64> {
    Mat::from_fn(n, 3, |i, c| match c {
        0 => 1.0,
        1 => (i as f64).cos() * 1e3,
        _ => 0.0,
    })
}

/// `M X = R` with `M` dense, solved with `options`.
fn dense(m: &Mat<f64>, r: &Mat<f64>, options: &Options) -> Result<LinearSolution, LcpError> {
    LinearSystem::dense(m.as_ref(), r.as_ref())
        .unwrap()
        .solve(options)
}

/// `M X = R` with `M` given by its products, solved with `options`.
fn by_products(m: &Mat<f64>, r: &Mat<f64>, options: &Options) -> Result<LinearSolution, LcpError> {
    let products = m.as_ref();
    LinearSystem::operator(&products, r.as_ref())
        .unwrap()
        .solve(options)
}

/// The largest difference of two matrices, relative to their largest entry.
fn rel_diff_mat(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    (0..a.ncols())
        .map(|c| rel_diff(&a.col(c).to_owned(), &b.col(c).to_owned()))
        .fold(0.0, f64::max)
}

#[test]
fn a_dense_system_is_solved_by_cholesky_as_faer_solves_it() {
    let (m, r) = (spd(40), rhs(40));
    let sol = dense(&m, &r, &Options::default()).unwrap();
    let faer = m.llt(Side::Lower).unwrap().solve(&r);
    assert!(rel_diff_mat(&sol.x, &faer) < 1e-13);
    assert!(sol.residual <= Tolerances::default().certificate);
    assert!(sol.x.col(2).iter().all(|&v| v == 0.0));
    let log = &sol.statistics.attempts;
    assert_eq!(log.len(), 1, "{log:?}");
    assert_eq!(
        (
            log[0].method,
            log[0].tableau,
            log[0].reason,
            &log[0].outcome
        ),
        (
            LinearMethod::Cholesky.into(),
            None,
            Reason::First,
            &Outcome::Returned
        )
    );
    assert_eq!(sol.statistics.factorizations(), 1);
    assert!(!sol.statistics.fell_back());
}

#[test]
fn the_same_system_by_its_products_agrees_to_the_tolerance() {
    let (m, r) = (spd(40), rhs(40));
    let dense = dense(&m, &r, &Options::default()).unwrap();
    let sol = by_products(&m, &r, &Options::default()).unwrap();
    // A residual of the tolerance, times M's condition number (about 10).
    assert!(rel_diff_mat(&sol.x, &dense.x) < 1e-10);
    assert!(sol.residual <= Tolerances::default().certificate);
    let returned = sol.statistics.returned().unwrap();
    assert_eq!(returned.method, LinearMethod::ConjugateGradient);
    // Every column but the zero one took iterations, at most n each in
    // exact arithmetic (a few more in floating point).
    assert!(sol.statistics.iterations() >= 2 && sol.statistics.iterations() <= 3 * 40);
}

#[test]
fn an_indefinite_dense_matrix_falls_back_to_lu_in_the_log() {
    // Eigenvalues 3 and -1: the Cholesky factorization meets a negative
    // pivot, the LU solves it: M^{-1} = [[-1, 2], [2, -1]] / 3.
    let m = mat![[1.0, 2.0], [2.0, 1.0]];
    let r = Mat::<f64>::identity(2, 2);
    let sol = dense(&m, &r, &Options::default()).unwrap();
    let inverse = mat![[-1.0, 2.0], [2.0, -1.0]] * (1.0 / 3.0);
    assert!(rel_diff_mat(&sol.x, &inverse) < 1e-15);
    let log = &sol.statistics.attempts;
    assert_eq!(log.len(), 2, "{log:?}");
    assert_eq!(
        (log[0].method, log[0].reason),
        (LinearMethod::Cholesky.into(), Reason::First)
    );
    assert_eq!(
        log[0].outcome,
        Outcome::Breakdown(Breakdown::NotPositiveDefinite)
    );
    assert_eq!(
        (log[1].method, log[1].reason, &log[1].outcome),
        (
            LinearMethod::Lu.into(),
            Reason::Fallback,
            &Outcome::Returned
        )
    );
    assert!(sol.statistics.fell_back());
    // A matrix that is not symmetric is not symmetric positive definite
    // either: the LU solves it too.
    let m = mat![[2.0, 1.0], [0.0, 2.0]];
    let sol = dense(&m, &r, &Options::default()).unwrap();
    assert_eq!(sol.statistics.returned().unwrap().method, LinearMethod::Lu);
    assert!(rel_diff_mat(&(&m * &sol.x), &r) < 1e-15);
}

#[test]
fn an_indefinite_operator_is_a_typed_breakdown() {
    // p = r = (1, -1): p · M p = -2 at the first step.
    let m = mat![[1.0, 2.0], [2.0, 1.0]];
    let r = mat![[1.0], [-1.0]];
    let e = by_products(&m, &r, &Options::default()).unwrap_err();
    let LcpError::BrokeDown {
        ref method,
        ref reason,
        size: 2,
        ..
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!(method, "conjugate-gradient");
    assert_eq!(*reason, Breakdown::NotPositiveDefinite.to_string());
    assert!(e.to_string().contains("give M densely"), "{e}");
}

#[test]
fn empty_and_mismatched_inputs_are_typed() {
    let m = spd(3);
    let e = LinearSystem::dense(m.as_ref(), Mat::<f64>::zeros(2, 1).as_ref()).unwrap_err();
    assert_eq!(
        e,
        LcpError::DimensionMismatch {
            field: "rhs",
            expected: 3,
            found: 2,
            unit: "rows"
        }
    );
    let e = LinearSystem::dense(Mat::<f64>::zeros(3, 2).as_ref(), rhs(3).as_ref()).unwrap_err();
    assert!(
        matches!(e, LcpError::DimensionMismatch { field: "m", .. }),
        "{e}"
    );
    let products = m.as_ref();
    let e = LinearSystem::operator(&products, rhs(4).as_ref()).unwrap_err();
    assert!(
        matches!(
            e,
            LcpError::DimensionMismatch {
                field: "rhs",
                expected: 3,
                found: 4,
                ..
            }
        ),
        "{e}"
    );
    for r in [Mat::<f64>::zeros(3, 0), Mat::<f64>::zeros(0, 0)] {
        let e = LinearSystem::dense(Mat::<f64>::zeros(r.nrows(), r.nrows()).as_ref(), r.as_ref())
            .unwrap_err();
        assert_eq!(e, LcpError::Empty { field: "rhs" });
    }
    let e = LinearSystem::operator(&products, Mat::<f64>::zeros(3, 0).as_ref()).unwrap_err();
    assert_eq!(e, LcpError::Empty { field: "rhs" });
    let mut r = rhs(3);
    r[(1, 1)] = f64::NAN;
    let e = LinearSystem::dense(m.as_ref(), r.as_ref()).unwrap_err();
    assert!(
        matches!(
            e,
            LcpError::NonFinite {
                field: "rhs",
                index: 4,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn the_iteration_cap_is_an_error_not_an_answer() {
    let (m, r) = (spd(40), rhs(40));
    let options = Options {
        max_pivots: Some(2),
        ..Options::default()
    };
    let e = by_products(&m, &r, &options).unwrap_err();
    let LcpError::IterationLimit {
        size,
        column,
        limit,
        residual,
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!((size, column, limit), (40, 0, 2));
    assert!(residual > 0.25 * Tolerances::default().certificate);
}

#[test]
fn a_residual_above_the_tolerance_is_refused() {
    let (m, r) = (spd(40), rhs(40));
    let strict = Options {
        tolerances: Tolerances {
            certificate: 0.0,
            ..Tolerances::default()
        },
        ..Options::default()
    };
    let e = dense(&m, &r, &strict).unwrap_err();
    let LcpError::Inaccurate {
        size, certificate, ..
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!(size, 40);
    assert!(certificate.equality > 0.0 && certificate.equality < 1e-14);
}

#[test]
fn a_factorization_is_no_method_of_an_lcp() {
    // The factorizations are a linear system's methods: an LCP cannot be
    // asked to use one (the strategy's guard says why, should one be
    // routed), and their names are no LCP method's.
    for method in LinearMethod::ALL {
        assert_eq!(method.name().parse::<LinearMethod>(), Ok(method));
    }
    for name in ["cholesky", "lu"] {
        let e = name.parse::<Method>().unwrap_err();
        assert_eq!(e.allowed, Method::NAMES);
        assert!(
            e.to_string()
                .contains("expected one of `restricted-simplex`"),
            "{e}"
        );
    }
    let e = "lemke".parse::<LinearMethod>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "unknown linear method `lemke`, expected one of `cholesky`, `lu`, `conjugate-gradient`"
    );
}
