//! Tests of `strategy` (the parent module).

use super::*;
use crate::problem::MixedLcpParts;
use faer::{Mat, col, mat};

fn contact(k: usize) -> BorderedLcp {
    let m = mat![[2.0, 0.5, 0.1], [0.5, 2.0, 0.5], [0.1, 0.5, 2.0]];
    let border = Mat::from_fn(3, k, |i, l| if l == 0 { 1.0 } else { i as f64 - 1.0 });
    let resultant = Col::from_fn(k, |l| if l == 0 { 3.0 } else { 0.2 });
    BorderedLcp::new(m, col![0.1, 0.0, 0.1])
        .unwrap()
        .with_border(border, resultant)
        .unwrap()
}

fn route_of(p: &BorderedLcp, method: Method, tableau: Tableau) -> Result<Vec<Kind>, LcpError> {
    let view = p.as_ref();
    let parts = MixedBorder::of(&view);
    let problem = Problem::bordered(&view, &parts);
    route(
        &problem,
        method,
        &Options {
            tableau,
            ..Options::default()
        },
    )
}

#[test]
fn the_routes_of_the_table() {
    use Kind::*;
    use {Method as M, Tableau as T};
    let one = contact(1);
    let two = contact(2);
    // Two rows: Lemke keeps the symmetric tableau, the restricted
    // simplex's needs one pin. Block pivoting has no tableau: the option
    // only chooses its fallback's, and a fallback that tableau cannot take
    // is left out.
    for (p, method, tableau, expected) in [
        (&one, M::Lemke, T::Auto, &[LemkeSymmetric, LemkeGeneral][..]),
        (
            &one,
            M::RestrictedSimplex,
            T::Auto,
            &[RestrictedSymmetric, RestrictedGeneral],
        ),
        (
            &one,
            M::BlockPivoting,
            T::Auto,
            &[BlockPivoting, LemkeSymmetric, LemkeGeneral],
        ),
        (&two, M::Lemke, T::Auto, &[LemkeSymmetric, LemkeGeneral]),
        (
            &two,
            M::RestrictedSimplex,
            T::Auto,
            &[RestrictedGeneral, LemkeSymmetric, LemkeGeneral],
        ),
        (
            &two,
            M::BlockPivoting,
            T::General,
            &[BlockPivoting, LemkeGeneral],
        ),
        (&one, M::Lemke, T::Symmetric, &[LemkeSymmetric]),
        (
            &one,
            M::BlockPivoting,
            T::Symmetric,
            &[BlockPivoting, LemkeSymmetric],
        ),
    ] {
        let k = p.as_ref().border_size();
        assert_eq!(
            route_of(p, method, tableau).unwrap(),
            expected,
            "{method:?}, {tableau:?}, k = {k}"
        );
    }
    assert!(matches!(
        route_of(&two, Method::RestrictedSimplex, Tableau::Symmetric),
        Err(LcpError::Unsupported { .. })
    ));
    let zero_diagonal = BorderedLcp::new(mat![[0.0, 1.0], [1.0, 0.0]], col![0.0, 0.5])
        .unwrap()
        .with_border(mat![[1.0], [1.0]], col![1.0])
        .unwrap();
    assert!(route_of(&zero_diagonal, Method::Lemke, Tableau::Symmetric).is_err());
    assert_eq!(
        route_of(&zero_diagonal, Method::BlockPivoting, Tableau::Symmetric).unwrap(),
        [BlockPivoting]
    );
}

#[test]
fn a_linear_method_routed_to_an_lcp_is_unsupported() {
    let p = contact(1);
    let view = p.as_ref();
    let parts = MixedBorder::of(&view);
    let problem = Problem::bordered(&view, &parts);
    for kind in [Kind::Cholesky, Kind::Lu, Kind::LinearConjugateGradient] {
        let Err(Failure {
            breakdown: Breakdown::Error(e),
            ..
        }) = problem.attempt(kind, &Options::default(), false)
        else {
            panic!("{kind:?} answered an LCP");
        };
        assert!(matches!(*e, LcpError::Unsupported { .. }), "{e}");
        assert!(
            e.to_string().contains("not a complementarity problem"),
            "{e}"
        );
    }
}

#[test]
fn a_mixed_form_goes_to_the_general_tableau() {
    let mixed = MixedLcp::new(MixedLcpParts {
        m: Mat::identity(2, 2),
        b: mat![[-1.0], [-1.0]],
        q: col![0.0, 1.0],
        c: mat![[1.0, 1.0]],
        d: Mat::zeros(1, 1),
        r: col![-1.0],
        bounds: vec![Bound::Free],
    })
    .unwrap();
    let problem = Problem::mixed(mixed.view());
    assert_eq!(
        route(&problem, Method::Lemke, &Options::default()).unwrap(),
        [Kind::LemkeGeneral]
    );
}

#[test]
fn a_retry_runs_on_the_general_tableau_unless_the_symmetric_was_asked_for() {
    // (The log of a fallback: tests/errors.rs, beside the error of the
    // same problem on an explicit symmetric tableau.)
    // A certificate no rounded answer meets: the retry runs on the
    // general tableau, refactored, and both answers are rejected.
    let strict = Options {
        tolerances: crate::Tolerances {
            certificate: 0.0,
            ..crate::Tolerances::default()
        },
        ..Options::default()
    };
    let e = contact(1).solve(Method::Lemke, &strict).unwrap_err();
    assert!(matches!(e, LcpError::Inaccurate { .. }), "{e}");
    // On an explicit symmetric tableau there is no retry elsewhere.
    let symmetric = Options {
        tableau: Tableau::Symmetric,
        ..strict
    };
    let e = contact(1).solve(Method::Lemke, &symmetric).unwrap_err();
    let LcpError::Inaccurate { pivots, .. } = e else {
        panic!("{e}")
    };
    let once = contact(1)
        .solve(Method::Lemke, &Options::default())
        .unwrap();
    assert_eq!(pivots, once.statistics.pivots());
}
