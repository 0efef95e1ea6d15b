//! Reference tests: discrete solutions against the closed forms (Hertz
//! spheres, Hertz cylinders, rigid flat punch) on two material pairs and in
//! two unit systems, and agreement of the engine's methods.
//!
//! Tolerances are discretization errors measured on these grids (the
//! discrete model converges to the closed form as the cell size h -> 0), with
//! a margin of about 2x; each is stated where it is used.

use crate::common;

use common::checks::assert_solves;
use elcon_analysis::references::{
    BeamOnFoundation, HertzCylinders, HertzSpheres, HetenyiBeam, combined_radius,
};
use elcon_analysis::{
    ContactProblem, ContactSolution, Geometry, Loading, Method, Options, Surface, Warning,
};
use elcon_fixtures::scenes;
use elcon_influence::{Beam, Body, Material, PointSet, combined_modulus};

/// A material pair and a unit system: (E1, nu1), (E2, nu2), length and force factors from inch-pound.
struct Case {
    m1: Material,
    m2: Material,
    /// metres per inch (1 for inch-pound)
    length: f64,
    /// newtons per pound (1 for inch-pound)
    force: f64,
}

const IN: f64 = 0.0254;
const LBF: f64 = 4.448_221_615_260_5;

fn cases() -> Vec<(&'static str, Case)> {
    let psi = |unit_len: f64, unit_force: f64| unit_force / (unit_len * unit_len);
    let mut out = Vec::new();
    for (name, length, force) in [("inch-pound", 1.0, 1.0), ("SI", IN, LBF)] {
        let p = psi(length, force);
        // steel on steel, and steel on aluminium
        for (e2, nu2) in [(30e6, 0.3), (10e6, 0.33)] {
            out.push((
                name,
                Case {
                    m1: Material::new(30e6 * p, 0.3).unwrap(),
                    m2: Material::new(e2 * p, nu2).unwrap(),
                    length,
                    force,
                },
            ));
        }
    }
    out
}

/// Example 1's spheres (R1 = 1 in, R2 = 10 in, P = 100 lb, in the case's
/// units and materials) on a zone of `zone` Hertz radii.
fn sphere_problem(case: &Case, cells_per_radius: f64, zone: f64) -> (ContactProblem, HertzSpheres) {
    scenes::spheres(
        case.m1,
        case.m2,
        1.0 * case.length,
        10.0 * case.length,
        100.0 * case.force,
        cells_per_radius,
        zone,
    )
}

/// The spheres on a zone of 1.25 Hertz radii, solved by `method` and
/// checked from the problem's data.
fn spheres(case: &Case, cells_per_radius: f64, method: Method) -> (ContactSolution, HertzSpheres) {
    let (problem, hertz) = sphere_problem(case, cells_per_radius, 1.25);
    let sol = problem.solve(method, &Options::default()).unwrap();
    assert_solves(&problem, &sol, &format!("spheres, {method}"));
    (sol, hertz)
}

#[test]
fn hertz_spheres_on_love_patches() {
    for (units, case) in cases() {
        let (sol, hertz) = spheres(&case, 10.0, Method::BlockPivoting);
        assert!(sol.certificate.holds(), "{units}: {}", sol.certificate);
        let err_delta = sol.approach / hertz.approach() - 1.0;
        let err_a = sol.contact_extent / hertz.contact_radius() - 1.0;
        let err_p0 = sol.max_pressure / hertz.peak_pressure() - 1.0;
        // h = a/10: the approach converges like h^2 (peers' table: 4.7e-4 at
        // h = a/9.2 on this point set); the contact radius to within about a
        // cell's share of the area (h/a = 0.1 -> a few %); the peak pressure
        // is the mean over the central cell, within 1% at this h.
        assert!(
            err_delta.abs() < 1e-3,
            "{units}: approach error {err_delta:e}"
        );
        assert!(
            err_a.abs() < 0.03,
            "{units}: contact radius error {err_a:e}"
        );
        assert!(
            err_p0.abs() < 0.01,
            "{units}: peak pressure error {err_p0:e}"
        );
        assert!((sol.load / hertz.load - 1.0).abs() < 1e-12);
        assert!(
            sol.warnings
                .iter()
                .all(|w| !matches!(w, Warning::ContactAtEdge { .. }))
        );
    }
}

#[test]
fn spheres_converge_with_refinement() {
    let (_, case) = cases().swap_remove(0);
    let (coarse, hertz) = spheres(&case, 5.0, Method::BlockPivoting);
    let (fine, _) = spheres(&case, 20.0, Method::BlockPivoting);
    let err = |s: &ContactSolution| {
        (
            (s.max_pressure / hertz.peak_pressure() - 1.0).abs(),
            (s.approach / hertz.approach() - 1.0).abs(),
        )
    };
    let (p_coarse, _) = err(&coarse);
    let (p_fine, delta_fine) = err(&fine);
    // The centre cell's mean pressure converges like h^2 and monotonically
    // (measured 3.5e-3 at a/5, 1.4e-4 at a/20): 4x finer must gain well over 4x.
    // The approach error is not monotone in h on a disk grid (the staircase
    // boundary of the contact set shifts with h: -3.2e-5 at a/5, -6.6e-4 at
    // a/6, -7.1e-5 at a/20), so it is only bounded at the fine grid.
    assert!(
        p_fine < p_coarse / 8.0,
        "peak pressure: coarse {p_coarse:e}, fine {p_fine:e}"
    );
    assert!(delta_fine < 2e-4, "approach at a/20: {delta_fine:e}");
}

#[test]
fn units_give_the_same_dimensionless_answer() {
    let all = cases();
    for pair in [(0, 2), (1, 3)] {
        let (sol_ip, h_ip) = spheres(&all[pair.0].1, 8.0, Method::Lemke);
        let (sol_si, h_si) = spheres(&all[pair.1].1, 8.0, Method::Lemke);
        let a = sol_ip.approach / h_ip.approach();
        let b = sol_si.approach / h_si.approach();
        // The SI data are the inch-pound data times rounded conversion
        // factors: the inputs differ by ~1e-16 relative, the answers by that
        // times the condition of the discrete problem (~1e3 here).
        assert!((a / b - 1.0).abs() < 1e-12, "{a} vs {b}");
        for k in 0..sol_ip.forces.len() {
            let fa = sol_ip.forces[k] / h_ip.load;
            let fb = sol_si.forces[k] / h_si.load;
            assert!((fa - fb).abs() < 1e-12, "point {k}: {fa} vs {fb}");
        }
    }
}

#[test]
fn methods_agree_on_a_contact_problem() {
    let (_, case) = cases().swap_remove(1);
    let (reference, _) = spheres(&case, 6.0, Method::RestrictedSimplex);
    for method in [Method::Lemke, Method::BlockPivoting] {
        let (sol, _) = spheres(&case, 6.0, method);
        assert_eq!(sol.contact, reference.contact, "{method}");
        let fmax = reference.forces.iter().cloned().fold(0.0, f64::max);
        for k in 0..sol.forces.len() {
            assert!(
                (sol.forces[k] - reference.forces[k]).abs() < 1e-11 * fmax,
                "{method}, point {k}"
            );
        }
        assert!(
            (sol.approach / reference.approach - 1.0).abs() < 1e-12,
            "{method}"
        );
    }
}

/// The first case (inch-pound steel on steel, P = 100 lb) at 6 cells per
/// Hertz radius on a zone of `zone` Hertz radii, solved by Lemke's method.
fn inch_pound_by_lemke(zone: f64) -> (ContactProblem, ContactSolution) {
    let (_, case) = cases().swap_remove(0);
    let (problem, _) = sphere_problem(&case, 6.0, zone);
    let sol = problem.solve(Method::Lemke, &Options::default()).unwrap();
    (problem, sol)
}

#[test]
fn load_and_displacement_control_agree() {
    // Inch-pound steel on steel: P = 100 lb.
    let (load, by_load) = inch_pound_by_lemke(1.3);
    assert_solves(&load, &by_load, "by load");
    let approach = load
        .with_loading(Loading::approach(by_load.approach))
        .unwrap();
    let by_approach = approach.solve(Method::Lemke, &Options::default()).unwrap();
    assert!(by_approach.certificate.holds());
    assert_solves(&approach, &by_approach, "by approach");
    assert!(
        (by_approach.load / 100.0 - 1.0).abs() < 1e-10,
        "{}",
        by_approach.load
    );
    assert_eq!(by_load.contact, by_approach.contact);
}

#[test]
fn hertz_cylinders_in_plane_strain() {
    for (units, case) in cases() {
        let (r1, r2) = (1.0 * case.length, 3.0 * case.length);
        let load = 1000.0 * case.force / case.length; // per unit length
        let hertz = HertzCylinders::new(
            combined_modulus(&case.m1, &case.m2),
            combined_radius(r1, r2),
            load,
        )
        .unwrap();
        let b = hertz.half_width();
        let d0 = 10.0 * b;
        // 201 strips over [-1.3 b, 1.3 b]: h = 0.013 b.
        let points = PointSet::line(-1.3 * b, 1.3 * b, 201).unwrap();
        let geometry = Geometry::Surfaces(
            Surface::Cylinder { radius: r1 },
            Surface::Cylinder { radius: r2 },
        );
        let problem = ContactProblem::new(
            points,
            &Body::plane_strain(case.m1, d0),
            &Body::plane_strain(case.m2, d0),
            &geometry,
            Loading::load(load),
        )
        .unwrap();
        for method in Method::ALL {
            let sol = problem
                .solve(method, &Options::default())
                .unwrap_or_else(|e| panic!("{units} {method}: {e}"));
            assert!(
                sol.certificate.holds(),
                "{units} {method}: {}",
                sol.certificate
            );
            assert_solves(&problem, &sol, &format!("{units} {method}"));
            let err_b = sol.contact_extent / b - 1.0;
            let err_p0 = sol.max_pressure / hertz.peak_pressure() - 1.0;
            let err_delta = sol.approach / hertz.approach(d0).unwrap() - 1.0;
            // Half-width within one strip (h/b = 0.013); the centre strip's
            // mean pressure within 0.2%; the approach (relative to the datum
            // at d0) within 0.1%: all measured errors are about half of these.
            assert!(
                err_b.abs() < 0.013,
                "{units} {method}: half-width error {err_b:e}"
            );
            assert!(
                err_p0.abs() < 2e-3,
                "{units} {method}: peak error {err_p0:e}"
            );
            assert!(
                err_delta.abs() < 1e-3,
                "{units} {method}: approach error {err_delta:e}"
            );
        }
    }
}

#[test]
fn rigid_flat_punch() {
    for (units, case) in cases() {
        let (problem, punch) =
            scenes::flat_punch(case.m2, 0.1 * case.length, 20.0, 1e-4 * case.length);
        let n = problem.points().len();
        let sol = problem
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap();
        assert!(sol.certificate.holds(), "{units}: {}", sol.certificate);
        assert_solves(&problem, &sol, units);
        // Every point touches, and the zone is the punch: the edge warning
        // fires, unless the zone's edge is declared the punch's own rim.
        assert_eq!(sol.contact.len(), n);
        let rim = problem.clone().with_body_edges(true, true);
        let quiet = rim
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap();
        assert_solves(&rim, &quiet, units);
        assert!(
            quiet
                .warnings
                .iter()
                .all(|w| !matches!(w, Warning::ContactAtEdge { .. }))
        );
        assert_eq!(quiet.forces, sol.forces);
        assert!(
            sol.warnings
                .iter()
                .any(|w| matches!(w, Warning::ContactAtEdge { .. }))
        );
        // P = 2 a E* delta; the staircase disk of 20 cells per radius has an
        // area within ~1% of pi a^2, and the load error follows it.
        let err = sol.load / punch.load(1e-4 * case.length) - 1.0;
        assert!(err.abs() < 0.02, "{units}: load error {err:e}");
        // Centre pressure: p(0) = P / (2 pi a^2) within 2% (singular edge, coarse cells).
        let centre = (0..n).find(|&k| problem.points().radius(k) == 0.0).unwrap();
        let err_p = sol.pressures[centre] / punch.pressure(sol.load, 0.0) - 1.0;
        assert!(
            err_p.abs() < 0.02,
            "{units}: centre pressure error {err_p:e}"
        );
    }
}

#[test]
fn truncated_zone_warns() {
    // Candidate zone smaller than the contact: the answer is truncated.
    let (problem, sol) = inch_pound_by_lemke(0.7);
    assert!(sol.certificate.holds());
    assert_solves(&problem, &sol, "truncated");
    let warning = sol
        .warnings
        .iter()
        .find(|w| matches!(w, Warning::ContactAtEdge { .. }))
        .expect("a truncated contact must warn");
    assert!(warning.to_string().contains("truncated"));
}

#[test]
fn flat_punch_is_maximally_degenerate_and_every_method_agrees() {
    // All separations equal: every ratio test of the tableau methods ties at
    // the first pivot. 8 cells per radius keeps the tableau small.
    for (units, case) in cases() {
        let (problem, _) = scenes::flat_punch(case.m2, 0.1 * case.length, 8.0, 1e-4 * case.length);
        let n = problem.points().len();
        let reference = problem
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap();
        for method in Method::TABLEAU {
            let sol = problem.solve(method, &Options::default()).unwrap();
            assert!(sol.certificate.holds(), "{units} {method}");
            assert_solves(&problem, &sol, &format!("{units} {method}"));
            assert_eq!(sol.contact.len(), n, "{units} {method}");
            assert!(
                (sol.load / reference.load - 1.0).abs() < 1e-11,
                "{units} {method}"
            );
        }
    }
}

/// A beam on a Winkler foundation under a central load, every point in
/// contact, against Hetenyi's closed form.
fn hetenyi_case(per_half: usize, length: f64) -> (ContactSolution, HetenyiBeam, PointSet) {
    // Example 2's section and foundation: steel E = 30e6 psi, 1 in x 4 in, k = 1e7 lb/in/in.
    let (e, i, k, load) = (30e6, 1.0 * 4.0f64.powi(3) / 12.0, 1e7, 5e4);
    let points = PointSet::line(-0.5 * length, 0.5 * length, 2 * per_half).unwrap();
    let n = points.len();
    let problem = ContactProblem::new(
        points.clone(),
        &Body::beam(Beam {
            youngs_modulus: e,
            second_moment: i,
            loaded_point: 0.0,
        })
        .unwrap(),
        &Body::winkler(k),
        &Geometry::Separation(vec![0.0; n]),
        Loading::load(load),
    )
    .unwrap();
    let sol = problem
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap();
    assert_solves(&problem, &sol, &format!("Hetenyi, {per_half} per half"));
    (
        sol,
        HetenyiBeam::new(BeamOnFoundation {
            flexural_rigidity: e * i,
            foundation_modulus: k,
            length,
            load,
        })
        .unwrap(),
        points,
    )
}

#[test]
fn beam_on_winkler_foundation_matches_hetenyi() {
    // L = 6 in: lambda L = 2.12 < pi, every point stays in contact.
    let mut previous = f64::INFINITY;
    for per_half in [10, 20, 40, 80] {
        let (sol, hetenyi, points) = hetenyi_case(per_half, 6.0);
        assert!(sol.certificate.holds(), "{}", sol.certificate);
        assert_eq!(sol.contact.len(), points.len(), "every point in contact");
        let peak = hetenyi.load_intensity(0.0);
        let err_intensity = (0..points.len())
            .map(|k| (sol.pressures[k] - hetenyi.load_intensity(points.x(k))).abs() / peak)
            .fold(0.0, f64::max);
        let err_alpha = (sol.approach / hetenyi.centre_deflection() - 1.0).abs();
        // Point forces at cell centres on a cantilever: second order in h.
        // Measured 3.3e-4 (10 per half), 8.3e-5, 2.1e-5, 5.2e-6 (80) for both
        // errors: 3.3e-4 (10 / n)^2; the bound adds 20 %.
        let bound = 4e-4 * (10.0 / per_half as f64).powi(2);
        assert!(
            err_intensity < bound,
            "{per_half}: intensity {err_intensity:e}"
        );
        assert!(err_alpha < bound, "{per_half}: approach {err_alpha:e}");
        assert!(
            err_alpha < previous / 3.5,
            "{per_half}: {err_alpha:e} after {previous:e}"
        );
        previous = err_alpha;
    }
}

#[test]
fn folded_problems_agree_with_full_ones() {
    let steel = Material::new(30e6, 0.3).unwrap();
    let sphere = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    let cylinder = Geometry::Surfaces(Surface::Cylinder { radius: 2.0 }, Surface::Plane);
    let a = 0.016;
    let cases: Vec<(PointSet, Body, Body, Geometry, Loading, usize)> = vec![
        (
            PointSet::grid_disk(a / 6.0, 1.3 * a).unwrap(),
            Body::uniform_patch(steel),
            Body::uniform_patch(steel),
            sphere.clone(),
            Loading::load(100.0),
            8,
        ),
        (
            PointSet::grid_disk(a / 5.0, 1.4 * a).unwrap(),
            Body::point_force(steel),
            Body::point_force(steel),
            sphere,
            Loading::approach(2e-4),
            8,
        ),
        (
            PointSet::grid_rectangle(0.01, 0.1, 7, 12).unwrap(),
            Body::uniform_patch(steel),
            Body::rigid(),
            cylinder.clone(),
            Loading::load(300.0),
            4,
        ),
        (
            PointSet::line(-0.02, 0.02, 41).unwrap(),
            Body::plane_strain(steel, 1.0),
            Body::plane_strain(steel, 1.0),
            cylinder,
            Loading::load(1e3),
            2,
        ),
        (
            PointSet::line(-4.45, 4.45, 30).unwrap(),
            Body::beam(Beam {
                youngs_modulus: 30e6,
                second_moment: 16.0 / 3.0,
                loaded_point: 0.0,
            })
            .unwrap(),
            Body::winkler(1e7),
            Geometry::Separation(vec![0.0; 30]),
            Loading::load(5e4),
            2,
        ),
    ];
    for (points, b1, b2, geometry, loading, order) in cases {
        let full = ContactProblem::new(points.clone(), &b1, &b2, &geometry, loading).unwrap();
        let folded = ContactProblem::symmetric(points, &b1, &b2, &geometry, loading).unwrap();
        let f = folded.folding().expect("a symmetric scene folds");
        assert_eq!(f.order(), order);
        assert_eq!(folded.entries("a test").expect("dense").nrows(), f.len());
        for method in Method::ALL {
            let x = full.solve(method, &Options::default()).unwrap();
            let y = folded.solve(method, &Options::default()).unwrap();
            assert!(y.certificate.holds(), "{method}: {}", y.certificate);
            // Both from the full S and eps: the folded answer too.
            assert_solves(&full, &x, &format!("{method}, full"));
            assert_solves(&full, &y, &format!("{method}, folded"));
            let fmax = x.forces.iter().cloned().fold(0.0, f64::max);
            for k in 0..x.forces.len() {
                assert!(
                    (x.forces[k] - y.forces[k]).abs() <= 1e-10 * fmax,
                    "{method} point {k}"
                );
                assert!(
                    (x.gaps[k] - y.gaps[k]).abs() <= 1e-10 * x.approach.abs(),
                    "{method} gap {k}"
                );
            }
            assert!(
                (x.approach - y.approach).abs() <= 1e-11 * x.approach.abs(),
                "{method}"
            );
            assert_eq!(x.contact, y.contact, "{method}");
            assert!((x.load - y.load).abs() <= 1e-11 * x.load, "{method}");
        }
    }
}

#[test]
fn a_folded_problem_refuses_an_asymmetric_separation() {
    let steel = Material::new(30e6, 0.3).unwrap();
    let points = PointSet::line(-1.0, 1.0, 6).unwrap();
    let body = Body::plane_strain(steel, 10.0);
    let p = ContactProblem::symmetric(
        points,
        &body,
        &body,
        &Geometry::Separation(vec![0.0; 6]),
        Loading::load(1.0),
    )
    .unwrap();
    assert!(p.folding().is_some());
    let e = p
        .with_separation(vec![0.0, 0.0, 0.0, 0.0, 0.0, 1e-6])
        .unwrap_err();
    assert!(
        e.to_string().contains("break the symmetry (mirror x)"),
        "{e}"
    );
    // An asymmetric geometry is simply not folded.
    let q = ContactProblem::symmetric(
        PointSet::line(-1.0, 1.0, 6).unwrap(),
        &body,
        &body,
        &Geometry::Separation(vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]),
        Loading::load(1.0),
    )
    .unwrap();
    assert!(q.folding().is_none());
}

#[test]
fn a_warm_start_from_the_previous_load_step_saves_iterations() {
    let a = 0.016;
    let points = PointSet::grid_disk(a / 8.0, 1.4 * a).unwrap();
    // The data the warm solutions are checked against (folded or not).
    let full = scenes::example1(ContactProblem::new, points.clone(), Loading::load(100.0)).unwrap();
    for fold in [false, true] {
        let build = if fold {
            ContactProblem::symmetric
        } else {
            ContactProblem::new
        };
        let light = scenes::example1(build, points.clone(), Loading::load(90.0)).unwrap();
        let heavy = light.with_loading(Loading::load(100.0)).unwrap();
        let first = light
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap();
        let cold = heavy
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap();
        let warm = heavy
            .solve_from(&first, Method::BlockPivoting, &Options::default())
            .unwrap();
        assert!(warm.certificate.holds());
        assert_solves(&full, &warm, &format!("warm, fold {fold}"));
        assert_eq!(warm.contact, cold.contact);
        let fmax = cold.forces.iter().cloned().fold(0.0, f64::max);
        for k in 0..cold.forces.len() {
            assert!((warm.forces[k] - cold.forces[k]).abs() <= 1e-12 * fmax);
        }
        // The step from 90 to 100 lb adds a ring of points: at most three iterations, fewer than cold.
        assert!(
            warm.statistics.iterations() < cold.statistics.iterations(),
            "fold {fold}: warm {} cold {}",
            warm.statistics.iterations(),
            cold.statistics.iterations()
        );
        assert!(
            warm.statistics.iterations() <= 3,
            "{}",
            warm.statistics.iterations()
        );
    }
}

#[test]
fn a_cylinder_on_a_square_grid_folds_by_its_two_mirrors() {
    // x^2 / 2R is not invariant under the swap of x and y, but is under both
    // mirrors: the problem folds by 4, not 8, and not by 1.
    let steel = Material::new(30e6, 0.3).unwrap();
    let points = PointSet::grid_disk(0.002, 0.02).unwrap();
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 1.0 }, Surface::Plane);
    let body = Body::uniform_patch(steel);
    let held = |build: scenes::Build| {
        build(
            points.clone(),
            &body,
            &body,
            &geometry,
            Loading::load(100.0),
        )
        .unwrap()
    };
    let folded = held(ContactProblem::symmetric);
    assert_eq!(folded.folding().map(|f| f.order()), Some(4));
    let full = held(ContactProblem::new);
    let (a, b) = (
        folded
            .solve(Method::BlockPivoting, &Options::default())
            .unwrap(),
        full.solve(Method::BlockPivoting, &Options::default())
            .unwrap(),
    );
    let fmax = b.forces.iter().cloned().fold(0.0, f64::max);
    for k in 0..a.forces.len() {
        assert!((a.forces[k] - b.forces[k]).abs() <= 1e-10 * fmax);
    }
}
