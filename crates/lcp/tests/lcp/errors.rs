//! One test per error variant of the engine, checking the message a caller sees.

use elcon_lcp::{
    BorderedLcp, Bound, Breakdown, Lcp, LcpError, LinearSystem, Method, MixedLcp, MixedLcpParts,
    OperatorLcp, Options, Outcome, PodStack, Preconditioner, ProgramBuilder, Reason, StackReq,
    Tableau, Tolerances,
};
use faer::{Col, Mat, col, mat};

fn message(e: LcpError) -> String {
    e.to_string()
}

/// Asserts that `e`'s message starts with `start` and ends with `end` (its
/// advice).
fn assert_message(e: LcpError, start: &str, end: &str) {
    let text = message(e);
    assert!(text.starts_with(start), "{text}");
    assert!(text.ends_with(end), "{text}");
}

/// Adds to a one-row program `p` an unknown of column `[1]` and a slack
/// of column `[coef]`, both non-negative, named `names`; returns their
/// indices.
fn unknown_and_slack(p: &mut ProgramBuilder, names: [&str; 2], coef: f64) -> (usize, usize) {
    let x = p
        .dense_column(names[0], col![1.0].as_ref(), Bound::NonNegative)
        .unwrap();
    let s = p.unit_columns(names[1], 0..1, coef, Bound::NonNegative);
    (x, s.unwrap().start)
}

/// The default options with the pivots (the conjugate gradient's
/// iterations) capped at `limit`.
fn capped(limit: usize) -> Options {
    Options {
        max_pivots: Some(limit),
        ..Options::default()
    }
}

/// The mixed form `w = z - u`, `z = 1`, with `u` bounded by `bound`.
fn one_pair(bound: Bound) -> MixedLcp {
    MixedLcp::new(MixedLcpParts {
        m: Mat::identity(1, 1),
        b: mat![[-1.0]],
        q: col![0.0],
        c: mat![[1.0]],
        d: Mat::zeros(1, 1),
        r: col![-1.0],
        bounds: vec![bound],
    })
    .unwrap()
}

#[test]
fn dimension_mismatch_names_the_field() {
    let e = Lcp::new(Mat::zeros(2, 3), Col::zeros(2)).unwrap_err();
    assert!(matches!(e, LcpError::DimensionMismatch { field: "m", .. }));
    assert_eq!(message(e), "`m` has 3 columns, expected 2");
    let e = MixedLcp::new(MixedLcpParts {
        m: Mat::identity(2, 2),
        b: Mat::zeros(2, 1),
        q: Col::zeros(2),
        c: Mat::zeros(1, 2),
        d: Mat::zeros(1, 1),
        r: Col::zeros(1),
        bounds: vec![Bound::Free, Bound::Free],
    })
    .unwrap_err();
    assert_eq!(message(e), "`b` has 1 columns, expected 2");
    // A preconditioner of another size than the operator's.
    let (m, other) = (Mat::<f64>::identity(2, 2), Mat::<f64>::identity(3, 3));
    let (m, other) = (m.as_ref(), Diagonal(other.as_ref()));
    let q = col![1.0, -1.0];
    let e = OperatorLcp::new(&m, q.as_ref())
        .unwrap()
        .with_preconditioner(&other)
        .unwrap_err();
    assert_eq!(message(e), "`preconditioner` has 3 rows, expected 2");
}

/// The inverse of a diagonal matrix's diagonal, as a preconditioner.
struct Diagonal<'a>(faer::MatRef<'a, f64>);

impl Preconditioner for Diagonal<'_> {
    fn size(&self) -> usize {
        self.0.nrows()
    }

    fn precondition_scratch(&self) -> StackReq {
        StackReq::EMPTY
    }

    fn precondition(&self, r: &[f64], z: &mut [f64], _: &mut PodStack) {
        for (i, (z, r)) in z.iter_mut().zip(r).enumerate() {
            *z = r / self.0[(i, i)];
        }
    }
}

#[test]
fn non_finite_input_is_located() {
    let e = Lcp::new(Mat::identity(2, 2), col![1.0, f64::NAN]).unwrap_err();
    assert_eq!(message(e), "`q` has a non-finite entry (NaN) at index 1");
    let mut m = Mat::<f64>::identity(3, 3);
    m[(1, 2)] = f64::INFINITY;
    let e = Lcp::new(m, Col::zeros(3)).unwrap_err();
    assert_eq!(message(e), "`m` has a non-finite entry (inf) at index 5");
}

#[test]
fn empty_problem() {
    let e = Lcp::new(Mat::zeros(0, 0), Col::zeros(0)).unwrap_err();
    assert_eq!(message(e), "the problem is empty: `q` has size 0");
}

#[test]
fn invalid_options() {
    let lcp = Lcp::new(Mat::identity(1, 1), col![-1.0]).unwrap();
    // The message of the refusal of `opts`.
    let refused = |opts: Options| message(lcp.solve(Method::Lemke, &opts).unwrap_err());
    assert_eq!(
        refused(Options {
            tolerances: Tolerances {
                pivot: 2.0,
                ..Tolerances::default()
            },
            ..Options::default()
        }),
        "option `tolerances.pivot` = 2: a relative tolerance must be finite and in [0, 1)"
    );
    // A tiny value in its shortest form, not as hundreds of zeros.
    assert_eq!(
        refused(Options {
            tolerances: Tolerances {
                zero: -1e-300,
                ..Tolerances::default()
            },
            ..Options::default()
        }),
        "option `tolerances.zero` = -1e-300: a relative tolerance must be finite and in [0, 1)"
    );
    assert_eq!(
        refused(Options {
            max_pivots: Some(0),
            ..Options::default()
        }),
        "option `max_pivots` = 0: must be at least 1"
    );
    assert!(
        refused(Options {
            tableau: Tableau::General,
            covering_vector: Some(vec![-1.0]),
            ..Options::default()
        })
        .starts_with("option `covering_vector` = entry 0 = -1")
    );
    assert_eq!(
        refused(Options {
            tableau: Tableau::General,
            covering_vector: Some(vec![-1e-300]),
            ..Options::default()
        }),
        "option `covering_vector` = entry 0 = -1e-300: every entry must be finite and > 0"
    );
    // A covering vector is the general tableau's: with another tableau it
    // is refused, not silently ignored or used to pick the tableau.
    assert_eq!(
        refused(Options {
            covering_vector: Some(vec![1.0]),
            ..Options::default()
        }),
        "option `covering_vector` = given with tableau = auto: a covering vector applies to the \
         general tableau only: set `tableau` to General"
    );
}

#[test]
fn a_border_with_dependent_columns_names_the_column() {
    let e = BorderedLcp::new(Mat::identity(2, 2), col![1.0, 1.0])
        .unwrap()
        .with_border(mat![[1.0, 2.0], [1.0, 2.0]], col![1.0, 2.0])
        .unwrap_err();
    assert_eq!(
        message(e),
        "column 1 of `border` depends linearly on the ones before it: each free unknown must move the gaps differently"
    );
    let e = BorderedLcp::new(Mat::identity(2, 2), col![1.0, 1.0])
        .unwrap()
        .with_border(mat![[1.0], [1.0], [1.0]], col![1.0])
        .unwrap_err();
    assert_eq!(message(e), "`border` has 3 rows, expected 2");
}

#[test]
fn an_explicit_tableau_that_cannot_finish_is_an_error() {
    // M = [[1, -2], [-2, 1]] (symmetric, indefinite): the symmetric tableau
    // meets a pivot no positive definite M gives. Asked for explicitly, it
    // does not hand over to the general tableau.
    let p = BorderedLcp::new(mat![[1.0, -2.0], [-2.0, 1.0]], col![0.0, 0.5])
        .unwrap()
        .with_border(mat![[1.0], [1.0]], col![10.0])
        .unwrap();
    let opts = Options {
        tableau: Tableau::Symmetric,
        ..Options::default()
    };
    let e = p.solve(Method::Lemke, &opts).unwrap_err();
    assert!(matches!(e, LcpError::BrokeDown { size: 2, .. }), "{e}");
    assert!(
        message(e).starts_with(
            "lemke on the symmetric tableau broke down after 1 pivot (size 2): a pivot a positive definite matrix would not give"
        ),
    );
    // On the default tableau the general one answers, and the log shows
    // each attempt and why it ran.
    let sol = p.solve(Method::Lemke, &Options::default()).unwrap();
    let log = &sol.statistics.attempts;
    assert_eq!(log.len(), 2, "{log:?}");
    assert_eq!(
        (log[0].reason, log[1].reason),
        (Reason::First, Reason::Fallback)
    );
    assert_eq!(
        log[0].outcome,
        Outcome::Breakdown(Breakdown::NotPositiveDefinite)
    );
    assert_eq!(log[1].outcome, Outcome::Returned);
    assert_eq!(log[1].tableau, Some(Tableau::General));
    // A mixed form has no symmetric tableau at all.
    let mixed = one_pair(Bound::Free);
    let e = mixed.solve(Method::Lemke, &opts).unwrap_err();
    assert!(matches!(e, LcpError::Unsupported { .. }));
    assert!(message(e).contains("the symmetric tableau takes a standard or bordered LCP"));
    // Nor has a program with complementarity constraints.
    let mut program = ProgramBuilder::new(1);
    program
        .dense_column("x", col![1.0].as_ref(), Bound::NonNegative)
        .unwrap();
    program.rhs(col![1.0].as_ref()).unwrap();
    let e = program.build().unwrap().solve(&opts).unwrap_err();
    assert!(matches!(e, LcpError::Unsupported { .. }), "{e}");
    assert!(message(e).contains("has no symmetric tableau"));
}

#[test]
fn unsupported_forms() {
    // Non-negative extra unknown: not an LCP for Lemke or block pivoting.
    let p = one_pair(Bound::NonNegative);
    for method in [Method::Lemke, Method::BlockPivoting] {
        let e = p.solve(method, &Options::default()).unwrap_err();
        assert!(matches!(e, LcpError::Unsupported { .. }), "{method}");
        assert!(message(e).contains("use the restricted-entry simplex"));
    }
    // ... while the restricted-entry simplex solves it: z = 1, u = 1.
    let s = p
        .solve(Method::RestrictedSimplex, &Options::default())
        .unwrap();
    assert!((s.z[0] - 1.0).abs() < 1e-15 && (s.u[0] - 1.0).abs() < 1e-15);
    // Block pivoting needs a symmetric matrix.
    let lcp = Lcp::new(mat![[2.0, 1.0], [0.0, 2.0]], col![-1.0, -1.0]).unwrap();
    let e = lcp
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap_err();
    assert!(message(e).contains("M is not symmetric"));
}

#[test]
fn ray_termination_on_an_unsolvable_lcp() {
    // w = -z - 1 >= 0 has no solution with z >= 0.
    let lcp = Lcp::new(mat![[-1.0]], col![-1.0]).unwrap();
    let e = lcp.solve(Method::Lemke, &Options::default()).unwrap_err();
    assert_eq!(
        message(e),
        "ray termination at pivot 1 (size 1): the entering variable `z[0]` is unbounded; \
         the problem has no solution if its matrix is copositive-plus (e.g. positive semidefinite)"
    );
}

#[test]
fn restricted_simplex_reports_infeasibility() {
    let lcp = Lcp::new(mat![[-1.0]], col![-1.0]).unwrap();
    let e = lcp
        .solve(Method::RestrictedSimplex, &Options::default())
        .unwrap_err();
    assert!(matches!(e, LcpError::Infeasible { size: 1, .. }));
    assert!(
        message(e).starts_with("no feasible complementary solution found (size 1, after 0 pivots)")
    );
}

#[test]
fn unbounded_objective() {
    // minimize -x subject to x - s = 1, x, s >= 0.
    let mut p = ProgramBuilder::new(1);
    let (x, _) = unknown_and_slack(&mut p, ["x", "s"], -1.0);
    p.cost(x, -1.0).unwrap();
    p.rhs(col![1.0].as_ref()).unwrap();
    let e = p.build().unwrap().solve(&Options::default()).unwrap_err();
    assert!(matches!(e, LcpError::Unbounded { .. }));
    assert!(message(e).starts_with("the objective is unbounded below along `s[0]`"));
}

#[test]
fn pivot_limit() {
    let n = 6;
    let m = Mat::from_fn(n, n, |i, j| if i == j { 4.0 } else { 1.0 });
    let lcp = Lcp::new(m, Col::from_fn(n, |_| -1.0)).unwrap();
    for method in Method::TABLEAU {
        let e = lcp.solve(method, &capped(2)).unwrap_err();
        assert_eq!(
            message(e),
            "pivot limit 2 reached (size 6); raise `max_pivots` or check the problem",
            "{method}"
        );
    }
}

#[test]
fn singular_basis_is_detected() {
    // M = [[t, t], [t, t + 1]] with t = 2^52: its LU has pivots t and 1, a
    // ratio of 2^-52 (condition ~ 2^54), below m u; the solution z = (1/2, 1/2)
    // needs both columns. With no equilibration and no pivot tolerance the
    // engine reaches that basis and must report it, not return it. (The
    // general tableau explicitly: for a symmetric M, Lemke's method
    // otherwise runs on the symmetric tableau and ends with a Cholesky of
    // the contact block.)
    let t = 2f64.powi(52);
    let m = mat![[t, t], [t, t + 1.0]];
    let lcp = Lcp::new(m, col![-t, -t - 0.5]).unwrap();
    let opts = Options {
        tableau: Tableau::General,
        equilibrate: false,
        covering_vector: Some(vec![1.0, 1.0]),
        tolerances: Tolerances {
            pivot: 0.0,
            ..Tolerances::default()
        },
        ..Options::default()
    };
    let e = lcp.solve(Method::Lemke, &opts);
    match e {
        Err(e @ LcpError::SingularBasis { .. }) => {
            assert!(message(e).contains("is numerically singular (size 2"));
        }
        Ok(sol) => panic!("a singular basis was accepted: z = {:?}", sol.z),
        Err(other) => panic!("wrong error: {other}"),
    }
}

#[test]
fn inaccurate_solutions_are_not_returned() {
    // A zero tolerance cannot be met by any rounded solution.
    let n = 12;
    let m = Mat::from_fn(n, n, |i, j| {
        1.0 / (1.0 + i as f64 + j as f64) + if i == j { 1.0 } else { 0.0 }
    });
    let lcp = Lcp::new(m, Col::from_fn(n, |i| -(1.0 + (i as f64).sin()))).unwrap();
    let opts = Options {
        tolerances: Tolerances {
            certificate: 0.0,
            ..Tolerances::default()
        },
        ..Options::default()
    };
    let e = lcp.solve(Method::Lemke, &opts).unwrap_err();
    // Before giving up, the engine solved once more, refactoring from the
    // data every 10 pivots (the general tableau; the first attempt ran on the
    // symmetric one): the error counts the pivots of both attempts.
    let once = lcp.solve(Method::Lemke, &Options::default()).unwrap();
    assert!(!once.statistics.retried());
    assert!(once.statistics.symmetric_tableau(), "the symmetric tableau");
    let retry = Options {
        tableau: Tableau::General,
        refactor_interval: Some(10),
        refinement_steps: 10,
        ..Options::default()
    };
    let again = lcp.solve(Method::Lemke, &retry).unwrap();
    assert!(!again.statistics.symmetric_tableau(), "the general tableau");
    match &e {
        LcpError::Inaccurate { pivots, .. } => {
            assert_eq!(
                *pivots,
                once.statistics.pivots() + again.statistics.pivots()
            )
        }
        other => panic!("{other:?}"),
    }
    let text = message(e);
    assert!(
        text.starts_with("the solution's certificate does not hold after"),
        "{text}"
    );
    assert!(text.contains("> tolerance 0.0e0"), "{text}");
}

#[test]
fn deferred_unknowns_cannot_be_complementary() {
    let mut p = ProgramBuilder::new(1);
    let (x, y) = unknown_and_slack(&mut p, ["x", "y"], 1.0);
    p.complementary(x, y).unwrap();
    let e = p.defer(x..x + 1).unwrap_err();
    assert!(matches!(e, LcpError::InvalidOption { field: "defer", .. }));
    assert_eq!(
        message(e),
        "option `defer` = 0: a complementary unknown cannot be deferred"
    );
    let (z, w) = unknown_and_slack(&mut p, ["z", "w"], 1.0);
    p.defer(z..z + 1).unwrap();
    let e = p.complementary(z, w).unwrap_err();
    assert!(message(e).ends_with("a deferred unknown cannot be complementary"));
}

#[test]
fn a_non_finite_solution_never_certifies() {
    let lcp = MixedLcp::new(MixedLcpParts {
        m: mat![[1.0]],
        b: Mat::zeros(1, 0),
        q: col![-1.0],
        c: Mat::zeros(0, 1),
        d: Mat::zeros(0, 0),
        r: Col::zeros(0),
        bounds: vec![],
    })
    .unwrap();
    for z in [f64::NAN, f64::INFINITY] {
        let (c, _) = lcp.certify(col![z].as_ref(), Col::<f64>::zeros(0).as_ref(), 1e-12);
        assert!(!c.finite);
        assert!(!c.holds(), "z = {z}");
        assert_eq!(c.worst(), f64::INFINITY);
    }
    // Data spanning more than double precision: an error, never a panic.
    let lcp = Lcp::new(mat![[1e-300]], col![-1e300]).unwrap();
    for method in Method::ALL {
        assert!(lcp.solve(method, &Options::default()).is_err(), "{method}");
    }
}

#[test]
fn a_negative_multiplier_for_a_non_negative_extra_unknown_is_infeasible() {
    // w = z - u - 2 >= 0, z w = 0, z = 1, u >= 0: z = 1 > 0 forces w = 0,
    // so u = -1 < 0. The free-multiplier solve the engine falls back to
    // finds that u and must not return it.
    let mixed = MixedLcp::new(MixedLcpParts {
        m: mat![[1.0]],
        b: mat![[-1.0]],
        q: col![-2.0],
        c: mat![[1.0]],
        d: mat![[0.0]],
        r: col![-1.0],
        bounds: vec![Bound::NonNegative],
    })
    .unwrap();
    let e = mixed
        .solve(Method::RestrictedSimplex, &Options::default())
        .unwrap_err();
    assert!(matches!(e, LcpError::Infeasible { .. }), "{e}");
}

#[test]
fn data_at_the_edge_of_double_precision_is_an_error_or_an_answer_never_a_panic() {
    // Found by review: scales of 1e-309 .. 1e93 in one problem drove the
    // general tableau's ratio test to a negative least step, whose relative
    // tie bound excluded every row (an index panic); the symmetric tableau
    // could take an infinite step at an overflowing load slope.
    let m = mat![
        [1.461798185296942e-120, -3.605672395070396e-251],
        [-3.605672395070396e-251, 3.640705763412097e-309]
    ];
    let lcp = Lcp::new(m, col![2.7907475697212115e93, -0.808799592029067]).unwrap();
    for method in Method::ALL {
        if let Ok(sol) = lcp.solve(method, &Options::default()) {
            assert!(sol.certificate.holds(), "{method}");
        }
    }
    let mixed = MixedLcp::new(MixedLcpParts {
        m: mat![[2.0210095273828205e-268]],
        b: mat![[-5.905823572589658e129]],
        q: col![45.78984165975658],
        c: mat![[1.1603547368363403e119]],
        d: mat![[0.0]],
        r: col![-2.4758498208489555e117],
        bounds: vec![Bound::Free],
    })
    .unwrap();
    let exact = Options {
        tolerances: Tolerances {
            zero: 0.0,
            tie: 0.0,
            ..Tolerances::default()
        },
        ..Options::default()
    };
    for options in [Options::default(), exact] {
        for method in Method::ALL {
            if let Ok(sol) = mixed.solve(method, &options) {
                assert!(sol.certificate.holds(), "{method}");
            }
        }
    }
}

/// A symmetric positive definite `n` x `n` matrix that the conjugate
/// gradient needs several iterations for: `1 / (1 + |i - j|)`, plus 2 on
/// the diagonal.
fn decaying_spd(n: usize) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| {
        1.0 / (1.0 + i.abs_diff(j) as f64) + if i == j { 2.0 } else { 0.0 }
    })
}

#[test]
fn iteration_limit_of_a_linear_system() {
    // A linear system's conjugate gradient returns no unconverged answer.
    let n = 20;
    let m = decaying_spd(n);
    let r = Mat::from_fn(n, 1, |i, _| i as f64);
    let products = m.as_ref();
    let e = LinearSystem::operator(&products, r.as_ref())
        .unwrap()
        .solve(&capped(1))
        .unwrap_err();
    assert!(
        matches!(
            e,
            LcpError::IterationLimit {
                size: 20,
                column: 0,
                limit: 1,
                ..
            }
        ),
        "{e}"
    );
    assert_message(
        e,
        "the conjugate gradient reached its iteration limit 1 on right-hand side 0 (size 20) at a relative residual",
        "raise `max_pivots` (its iteration cap) or give M densely (a factorization needs no iterations)",
    );
}

#[test]
fn iteration_limit_of_the_conjugate_gradient() {
    // The conjugate gradient of an LCP returns no unconverged answer: at
    // its cap (`max_pivots`, counting iterations) it stops with its own
    // error, whatever the problem's form.
    let n = 20;
    let m = decaying_spd(n);
    let q = Col::from_fn(n, |i| if i % 3 == 0 { 1.0 } else { -1.0 - i as f64 });
    let lcp = Lcp::new(m.clone(), q.clone()).unwrap();
    let method = Method::ConjugateGradient;
    let needed = lcp
        .solve(method, &Options::default())
        .unwrap()
        .statistics
        .iterations();
    assert!(needed >= 2, "{needed}");
    // Its own count is enough; one fewer is the error.
    let sol = lcp.solve(method, &capped(needed)).unwrap();
    assert!(sol.certificate.holds());
    let e = lcp.solve(method, &capped(needed - 1)).unwrap_err();
    let LcpError::ConjugateGradientLimit {
        size,
        limit,
        residual,
        tolerance,
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!((size, limit), (n, needed - 1));
    assert!(residual > tolerance && tolerance == Tolerances::default().certificate);
    // Given by its products, the same.
    let products = m.as_ref();
    let e = OperatorLcp::new(&products, q.as_ref())
        .unwrap()
        .solve(method, &capped(1))
        .unwrap_err();
    assert!(
        matches!(
            e,
            LcpError::ConjugateGradientLimit {
                size: 20,
                limit: 1,
                ..
            }
        ),
        "{e}"
    );
    assert_message(
        e,
        "iteration limit 1 of the conjugate gradient reached (size 20) at a worst relative residual",
        "raise `max_pivots` (its iteration cap) or check the problem",
    );
}
