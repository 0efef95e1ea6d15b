//! The stability suite: stiff and extreme cases (elcon-fixtures'
//! `stability_cases`) solved by every method. For every case the
//! certificate (equilibrium, feasibility, complementarity, from the
//! original data) holds at 1e-12, and the contact conditions hold when
//! recomputed here from S and eps (tests/analysis/common/checks.rs). The engine
//! refuses an answer that does not certify (an error, never a "solved" that
//! does not hold), and a refusal fails these tests: on these ranges every
//! method must certify. docs/stability.md tabulates the same cases at
//! larger sizes.

use crate::common;

use common::checks::{assert_solves, check};
use elcon_analysis::{ContactProblem, Geometry, Loading, Method, Options, Surface, Warning};
use elcon_fixtures::scenes;
use elcon_fixtures::stability_cases::{Case, Expect, Reference, catalogue, error};
use elcon_influence::{Body, Material, PointSet};
use proptest::prelude::*;

#[test]
fn every_case_is_certified_by_every_method() {
    let cases = catalogue(21, &[256, 1024]);
    for case in &cases {
        let mut first: Option<Vec<f64>> = None;
        for method in Method::ALL {
            let label = format!("{} / {} / {method}", case.family, case.name);
            let sol = match case.problem.solve(method, &Options::default()) {
                Ok(s) => s,
                Err(e) => panic!("{label}: {e}"),
            };
            assert!(sol.certificate.holds(), "{label}: {}", sol.certificate);
            assert!(sol.certificate.worst() <= 1e-12, "{label}");
            assert_solves(&case.problem, &sol, &label);
            // Every S here is symmetric positive definite: Lemke's method,
            // and under load control (where no point starts in
            // interference) the restricted-entry simplex, finish on the
            // symmetric tableau (one Cholesky at the end), with no fall back
            // to the general tableau, and in about a pivot a point (a beam
            // whose every point touches at once took Lemke's method to the
            // pivot limit under a least-index rule for ties).
            let load_control = matches!(
                case.problem.loading().normal,
                elcon_analysis::Normal::Load(_)
            );
            // (A border of several rows, a free rotation beside the
            // approach, takes the restricted simplex to the general
            // tableau: its swept form has one pin.)
            // (Nor does a prescribed misalignment, which starts some points
            // in interference.)
            let rigid = case.problem.rigid();
            let one_row = rigid.free.len() == 1 && rigid.prescribed.iter().all(|&(_, v)| v == 0.0);
            if method == Method::Lemke
                || (method == Method::RestrictedSimplex && load_control && one_row)
            {
                let s = &sol.statistics;
                assert!(s.symmetric_tableau(), "{label}: {s:?}");
                assert!(s.pivots() <= 2 * sol.forces.len(), "{label}: {s:?}");
            }
            match case.expect {
                Expect::Solved => {}
                Expect::EdgeWarning => assert!(
                    sol.warnings
                        .iter()
                        .any(|w| matches!(w, Warning::ContactAtEdge { .. })),
                    "{label}: a truncated contact must warn"
                ),
                Expect::OnePoint => {
                    assert_eq!(sol.contact.len(), 1, "{label}");
                    let load = sol.load;
                    assert!(
                        (sol.forces[sol.contact[0]] / load - 1.0).abs() < 1e-12,
                        "{label}"
                    );
                }
            }
            // The discretization errors of these grids (21 points across,
            // measured): Hertz within 1 %, the punch's staircase within 2 %,
            // Hetenyi within 1e-3 at 40 points.
            if let Some(err) = error(case.reference, sol.approach, sol.load) {
                let bound = match case.reference {
                    Reference::Punch(..) => 0.02,
                    Reference::Hetenyi(_) => 1e-3,
                    _ => 0.01,
                };
                assert!(err.abs() < bound, "{label}: error {err:e}");
            }
            // Every method returns the same solution.
            match &first {
                None => first = Some(sol.forces.clone()),
                Some(f) => {
                    let fmax = f.iter().cloned().fold(0.0, f64::max);
                    for k in 0..f.len() {
                        assert!(
                            (f[k] - sol.forces[k]).abs() <= 1e-9 * fmax,
                            "{label}: point {k}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn extreme_materials_and_radii_give_the_same_dimensionless_answer() {
    // Scaled by the Hertz values, the discrete problem is the same whatever
    // the moduli, Poisson's ratios and radii (only E* and R enter): the
    // dimensionless forces agree to rounding times the conditioning.
    let cases = catalogue(21, &[]);
    let hertz: Vec<_> = cases
        .iter()
        .filter(|c| {
            matches!(
                c.family,
                "modulus ratio" | "Poisson's ratio" | "radius ratio" | "conformal"
            )
        })
        .collect();
    let shape = |c: &Case| -> (Vec<f64>, f64) {
        let sol = c
            .problem
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap();
        let Reference::Hertz(h) = c.reference else {
            unreachable!()
        };
        (
            sol.forces.iter().map(|f| f / h.load).collect(),
            sol.approach / h.approach(),
        )
    };
    let (f0, d0) = shape(hertz[0]);
    for c in &hertz[1..] {
        let (f, d) = shape(c);
        assert_eq!(f.len(), f0.len(), "{}", c.name);
        for k in 0..f.len() {
            assert!(
                (f[k] - f0[k]).abs() < 1e-11,
                "{}: point {k}: {} vs {}",
                c.name,
                f[k],
                f0[k]
            );
        }
        assert!((d / d0 - 1.0).abs() < 1e-11, "{}", c.name);
    }
}

#[test]
fn three_unit_systems_give_the_same_answer_to_1e_12() {
    // Example 1 in inch-pound, SI and millimetre-newton.
    let run = |length: f64, force: f64| {
        let stress = force / (length * length);
        let steel = Material::new(30e6 * stress, 0.3).unwrap();
        let a = 0.016 * length;
        let points = PointSet::grid_disk(a / 8.0, 1.3 * a).unwrap();
        let geometry = Geometry::Surfaces(
            Surface::Sphere { radius: length },
            Surface::Sphere {
                radius: 10.0 * length,
            },
        );
        let body = Body::uniform_patch(steel);
        let p = ContactProblem::new(
            points,
            &body,
            &body,
            &geometry,
            Loading::load(100.0 * force),
        )
        .unwrap();
        let sol = p.solve(Method::Lemke, &Options::default()).unwrap();
        (
            sol.forces
                .iter()
                .map(|f| f / (100.0 * force))
                .collect::<Vec<f64>>(),
            sol.approach / length,
        )
    };
    let inch_pound = run(1.0, 1.0);
    for (name, length, force) in [
        ("SI", 0.0254, 4.448_221_615_260_5),
        ("mm-N", 25.4, 4.448_221_615_260_5),
    ] {
        let other = run(length, force);
        for k in 0..inch_pound.0.len() {
            assert!(
                (inch_pound.0[k] - other.0[k]).abs() < 1e-12,
                "{name}: point {k}"
            );
        }
        assert!((inch_pound.1 / other.1 - 1.0).abs() < 1e-12, "{name}");
    }
}

#[test]
fn the_condition_estimate_grows_with_refinement() {
    let cases = catalogue(21, &[64, 256, 1024]);
    let sizes: Vec<(usize, f64)> = cases
        .iter()
        .filter(|c| c.family == "size")
        .map(|c| {
            (
                c.problem.points().len(),
                elcon_lcp::condition_estimate(
                    c.problem.entries("the condition estimate").expect("dense"),
                ),
            )
        })
        .collect();
    for w in sizes.windows(2) {
        assert!(w[1].1 > w[0].1, "{sizes:?}");
    }
    // S of Love patches is well conditioned: below 1e3 at N ~ 1000 here.
    assert!(sizes.iter().all(|s| s.1 < 1e3), "{sizes:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    /// Scenes drawn from the extreme ranges: moduli ratios 1e-6..1e6, Poisson's
    /// ratios (-0.999, 0.4999), radius ratios 1e-3..1e3 (convex or concave
    /// but not inverted), loads 1e-6..1e6 of the grid's nominal load. Every
    /// method must certify them: the engine's refusal of an uncertified
    /// answer (an error) fails the test.
    #[test]
    fn extreme_scenes_are_certified(
        log_ratio in -6.0f64..6.0,
        nu1 in -0.999f64..0.4999,
        nu2 in -0.999f64..0.4999,
        log_radius in -3.0f64..3.0,
        concave in proptest::bool::ANY,
        log_load in -6.0f64..6.0,
        method in prop_oneof![Just(Method::RestrictedSimplex), Just(Method::Lemke), Just(Method::BlockPivoting)],
    ) {
        let m1 = Material::new(200e9, nu1).unwrap();
        let m2 = Material::new(200e9 * 10f64.powf(log_ratio), nu2).unwrap();
        let r1 = 0.01;
        let mut r2 = r1 * 10f64.powf(log_radius);
        if concave && r2 > 1.01 * r1 {
            r2 = -r2; // a groove larger than the ball
        }
        let nominal = 100.0;
        let e = elcon_influence::combined_modulus(&m1, &m2);
        let hertz = elcon_analysis::references::HertzSpheres::new(e, elcon_analysis::references::combined_radius(r1, r2), nominal).unwrap();
        let a = hertz.contact_radius();
        let points = PointSet::grid_disk(a / 6.0, 1.3 * a).unwrap();
        let geometry = Geometry::Surfaces(Surface::Sphere { radius: r1 }, Surface::Sphere { radius: r2 });
        let problem = ContactProblem::new(points, &Body::uniform_patch(m1), &Body::uniform_patch(m2), &geometry,
            Loading::load(nominal * 10f64.powf(log_load))).unwrap();
        match problem.solve(method, &Options::default()) {
            Ok(sol) => {
                prop_assert!(sol.certificate.holds(), "{method}: {}", sol.certificate);
                prop_assert!(sol.certificate.worst() <= 1e-12);
                check(&problem, &sol)?;
            }
            // A refusal fails the test, and says why.
            Err(e) => prop_assert!(false, "{method}: refused: {e}"),
        }
    }
}

#[test]
fn a_point_that_just_touches_is_reported_uncertain() {
    // A Winkler foundation under a rigid flat pressed to exactly the second
    // point's separation: that point has zero force and zero gap, and which
    // side of contact it is on is uncertain. Every method names it.
    let points = PointSet::line(-1.0, 1.0, 3).unwrap();
    let problem = ContactProblem::new(
        points,
        &Body::winkler(1e6),
        &Body::rigid(),
        &Geometry::Separation(vec![0.0, 1e-3, 2e-3]),
        Loading::approach(1e-3).aligned(),
    )
    .unwrap();
    for method in Method::ALL {
        let sol = problem.solve(method, &Options::default()).unwrap();
        assert!(sol.certificate.holds(), "{method}");
        assert_solves(&problem, &sol, &format!("{method}"));
        let uncertain = sol.warnings.iter().find_map(|w| match w {
            Warning::UncertainContact { points } => Some(points.clone()),
            _ => None,
        });
        assert_eq!(uncertain, Some(vec![1]), "{method}: {:?}", sol.warnings);
        assert_eq!(sol.contact, vec![0], "{method}");
    }
}

#[test]
fn a_folded_problem_reports_the_uncertain_points_of_the_full_one() {
    // The same just-touching point on a symmetric line, folded about x = 0:
    // once on an orbit of two points (s = 1), once at the centre, an orbit
    // of its own (s = 2, its folded row halved).
    let points = PointSet::line(-1.0, 1.0, 5).unwrap();
    for (eps, uncertain, contact) in [
        (vec![2e-3, 1e-3, 0.0, 1e-3, 2e-3], vec![1, 3], vec![2]),
        (
            vec![0.0, 0.5e-3, 1e-3, 0.5e-3, 0.0],
            vec![2],
            vec![0, 1, 3, 4],
        ),
    ] {
        let build = |fold: bool| {
            let build = if fold {
                ContactProblem::symmetric
            } else {
                ContactProblem::new
            };
            build(
                points.clone(),
                &Body::winkler(1e6),
                &Body::rigid(),
                &Geometry::Separation(eps.clone()),
                Loading::approach(1e-3),
            )
            .unwrap()
        };
        let (full, folded) = (build(false), build(true));
        assert_eq!(folded.folding().map(|f| f.order()), Some(2));
        for method in Method::ALL {
            for problem in [&full, &folded] {
                let sol = problem.solve(method, &Options::default()).unwrap();
                assert_solves(&full, &sol, &format!("{method}"));
                let found = sol.warnings.iter().find_map(|w| match w {
                    Warning::UncertainContact { points } => Some(points.clone()),
                    _ => None,
                });
                let label = format!("{method}, folded {}", problem.folding().is_some());
                assert_eq!(
                    found.as_ref(),
                    Some(&uncertain),
                    "{label}: {:?}",
                    sol.warnings
                );
                assert_eq!(sol.contact, contact, "{label}");
            }
        }
    }
}

#[test]
fn a_beam_alone_on_a_rigid_flat_is_solved_by_every_method() {
    // The loaded point is a candidate point: its row of S is zero (the beam
    // is clamped there), so S is only semidefinite and block pivoting's
    // Cholesky fails; it falls back to Lemke's method. The clamped point
    // carries the whole load.
    let points = PointSet::line(-1.0, 1.0, 21).unwrap();
    let problem =
        scenes::beam_on(ContactProblem::new, Body::rigid(), (1e6, 0.0), points, 10.0).unwrap();
    // S is only semidefinite (zero at the clamped point): the conjugate
    // gradient refuses it, naming the method to use.
    let e = problem
        .solve(Method::ConjugateGradient, &Options::default())
        .unwrap_err();
    assert!(e.to_string().contains("Lemke"), "{e}");
    for method in Method::PIVOTING {
        let sol = problem.solve(method, &Options::default()).unwrap();
        assert!(sol.certificate.holds(), "{method}: {}", sol.certificate);
        assert_solves(&problem, &sol, &format!("{method}"));
        assert!(
            (sol.forces[10] - 10.0).abs() < 1e-12,
            "{method}: {:?}",
            sol.forces
        );
        if method == Method::BlockPivoting {
            assert!(sol.statistics.fell_back());
        }
    }
}

#[test]
fn lemke_ends_when_the_covering_variable_reaches_zero_outside_the_relative_tie() {
    // Folded Hertz spheres at 131 points across (a split LCP of 2261 rows):
    // at pivot 1726 the second row of the split load equation leaves while
    // z0 is at zero in exact arithmetic, but rounding put z0's ratio just
    // outside the relative tie, so z0 stayed basic at the zero level and the
    // next entering variable (u- with u+ basic) was a ray. The ratio test now
    // also ties every row that the step brings to the zero level, so z0 is
    // preferred and leaves.
    let a = scenes::example1_hertz().contact_radius();
    let points = PointSet::grid_disk(2.0 * a / 130.0, 1.15 * a).unwrap();
    let problem =
        scenes::example1(ContactProblem::symmetric, points, Loading::load(100.0)).unwrap();
    let lemke = problem.solve(Method::Lemke, &Options::default()).unwrap();
    assert!(lemke.certificate.holds(), "{}", lemke.certificate);
    // Not checked from the full S (common::checks): about 17,500 points,
    // a 2.5 GB matrix; the independent check here is block pivoting's answer.
    let bp = problem
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap();
    assert!((lemke.approach / bp.approach - 1.0).abs() < 1e-12);
    assert_eq!(lemke.contact, bp.contact);
}
