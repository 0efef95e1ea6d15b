//! Matrix-free problems (`ContactProblem::lattice`): S held as an FFT
//! convolution on the lattice and solved by the conjugate gradient give the
//! dense problem's exact solution to the iteration's tolerance, under a
//! load, an approach, an eccentric load (free tilts) and a prescribed
//! misalignment; Hertz's closed form is met to the discretization's error;
//! the pivoting methods and beams are refused with messages that say why.

use elcon_analysis::references::{HertzSpheres, combined_radius};
use elcon_analysis::{
    AnalysisError, ContactProblem, Geometry, Loading, Method, Options, Storage, Surface,
};
use elcon_fixtures::scenes;
use elcon_influence::{Body, Material, PointSet, combined_modulus};

fn steel() -> Material {
    Material::new(30e6, 0.3).expect("steel") // psi
}

/// Example 1's candidate disk of `a / cells` spacing and radius `zone a`,
/// its geometry and its Hertz solution.
fn example1(cells: f64, zone: f64) -> (PointSet, Geometry, HertzSpheres) {
    let hertz = HertzSpheres::new(
        combined_modulus(&steel(), &steel()),
        combined_radius(1.0, 10.0),
        100.0,
    )
    .expect("Hertz");
    let a = hertz.contact_radius();
    let points = PointSet::grid_disk(a / cells, zone * a).expect("grid");
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    (points, geometry, hertz)
}

/// Example 1's spheres (R1 = 1 in, R2 = 10 in, P = 100 lb) on a disk grid
/// of `a / cells` spacing and radius `zone a`, dense and matrix-free.
fn spheres(
    cells: f64,
    zone: f64,
    loading: Loading,
) -> (ContactProblem, ContactProblem, HertzSpheres) {
    let (points, geometry, hertz) = example1(cells, zone);
    let body = Body::uniform_patch(steel());
    let dense =
        ContactProblem::new(points.clone(), &body, &body, &geometry, loading).expect("dense");
    let free = ContactProblem::lattice(points, &body, &body, &geometry, loading).expect("lattice");
    (dense, free, hertz)
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The conjugate gradient on the lattice operator against block pivoting
/// on the dense S: forces to 1e-8 of the largest, rigid motions to 1e-8,
/// both certified (the matrix-free certificate from operator products).
fn agree(loading: Loading, label: &str) {
    let (dense, free, _) = spheres(8.0, 1.6, loading);
    assert!(free.storage() == Storage::Lattice && free.entries("a test").is_err());
    let exact = dense
        .solve(Method::BlockPivoting, &Options::default())
        .expect(label);
    let iterative = free
        .solve(Method::ConjugateGradient, &Options::default())
        .expect(label);
    assert!(
        iterative.certificate.holds(),
        "{label}: {}",
        iterative.certificate
    );
    assert!(iterative.certificate.worst() <= 1e-12, "{label}");
    assert!(
        rel(&iterative.forces, &exact.forces) < 1e-8,
        "{label}: forces"
    );
    assert!(rel(&iterative.gaps, &exact.gaps) < 1e-8, "{label}: gaps");
    for (x, y, what) in [
        (iterative.approach, exact.approach, "approach"),
        (iterative.tilt_x, exact.tilt_x, "tilt_x"),
        (iterative.tilt_y, exact.tilt_y, "tilt_y"),
    ] {
        assert!(
            (x - y).abs() <= 1e-8 * exact.approach.abs(),
            "{label}: {what} {x} against {y}"
        );
    }
    assert_eq!(iterative.contact, exact.contact, "{label}: contact set");
    assert!(iterative.statistics.iterations() > 0, "{label}");
}

#[test]
fn a_load_on_the_lattice_gives_the_dense_solution() {
    agree(Loading::load(100.0), "load");
}

#[test]
fn an_approach_on_the_lattice_gives_the_dense_solution() {
    let (dense, _, _) = spheres(8.0, 1.6, Loading::load(100.0));
    let approach = dense
        .solve(Method::BlockPivoting, &Options::default())
        .expect("load")
        .approach;
    agree(Loading::approach(approach), "approach");
}

#[test]
fn an_eccentric_load_on_the_lattice_gives_the_dense_solution() {
    // The load 0.3 a off centre along x and 0.2 a along y: both tilts free
    // (three border rows), balanced by the contact's moments.
    let (_, _, hertz) = spheres(8.0, 1.6, Loading::load(100.0));
    let a = hertz.contact_radius();
    agree(
        Loading::load(100.0)
            .with_moment_y(-100.0 * 0.3 * a)
            .with_moment_x(100.0 * 0.2 * a),
        "eccentric",
    );
}

#[test]
fn a_prescribed_misalignment_on_the_lattice_gives_the_dense_solution() {
    let (_, _, hertz) = spheres(8.0, 1.6, Loading::load(100.0));
    let tilt = 0.2 * hertz.approach() / hertz.contact_radius();
    agree(Loading::load(100.0).with_tilt_y(tilt), "misaligned");
}

#[test]
fn a_fine_lattice_meets_hertz() {
    // 32 cells per radius, N = 5,025: the approach and the peak within the
    // discretization's error of Hertz (the dense solve at this N would hold
    // a 200 MB S; the operator holds under 1 MB).
    let (_, free, hertz) = spheres(32.0, 1.25, Loading::load(100.0));
    let sol = free
        .solve(Method::ConjugateGradient, &Options::default())
        .expect("fine");
    assert!(sol.certificate.holds());
    let approach = sol.approach / hertz.approach() - 1.0;
    let peak = sol.max_pressure / hertz.pressure(0.0) - 1.0;
    assert!(approach.abs() < 2e-3, "approach {approach:e}");
    assert!(peak.abs() < 2e-2, "peak {peak:e}");
    assert!((sol.load - 100.0).abs() < 1e-10 * 100.0);
}

#[test]
fn pivoting_methods_and_beams_are_refused_on_the_lattice() {
    let (_, free, _) = spheres(4.0, 1.3, Loading::load(100.0));
    for method in Method::PIVOTING {
        let e = free.solve(method, &Options::default()).unwrap_err();
        assert!(
            matches!(e, AnalysisError::Engine(_)) && e.to_string().contains("conjugate gradient"),
            "{method}: {e}"
        );
    }
    let points = PointSet::line(-1.0, 1.0, 21).expect("line");
    let winkler = Body::winkler(1e3);
    let e =
        scenes::beam_on(ContactProblem::lattice, winkler, (1e6, 0.0), points, 10.0).unwrap_err();
    assert!(matches!(e, AnalysisError::Influence(_)), "{e}");
}

#[test]
fn the_deflection_is_the_same_from_either_storage() {
    let (dense, free, _) = spheres(6.0, 1.3, Loading::load(100.0));
    let n = dense.points().len();
    let forces: Vec<f64> = (0..n).map(|k| 1.0 + (k % 7) as f64).collect();
    let a = dense.deflection(&forces).expect("dense");
    let b = free.deflection(&forces).expect("free");
    assert!(rel(&a, &b) < 1e-12);
    assert!(matches!(
        dense.deflection(&forces[1..]),
        Err(AnalysisError::SizeMismatch {
            field: "forces",
            ..
        })
    ));
}

#[test]
fn the_lattice_drops_rotations_its_symmetry_makes_zero_and_keeps_the_others() {
    use elcon_analysis::RigidMode;
    // Free rotations without moments on a symmetric scene: both dropped by
    // the mirror groups, as on the dense problem.
    let (dense, free, _) = spheres(4.0, 1.3, Loading::load(100.0));
    assert_eq!(free.rigid().free, dense.rigid().free);
    assert_eq!(free.rigid().free.len(), 1);
    assert_eq!(
        free.rigid().dropped,
        [RigidMode::TiltX, RigidMode::TiltY],
        "{:?}",
        free.rigid()
    );
    // A moment about y keeps θ_y free; θ_x, without a moment, is dropped.
    let (dense, free, _) = spheres(4.0, 1.3, Loading::load(100.0).with_moment_y(0.01));
    assert_eq!(free.rigid().free, dense.rigid().free);
    assert_eq!(free.rigid().dropped, [RigidMode::TiltX]);
    // Both rotations prescribed: nothing to drop, and no group is looked
    // for (the same unknowns either way).
    let (dense, free, _) = spheres(4.0, 1.3, Loading::load(100.0).aligned());
    assert_eq!(free.rigid().free, dense.rigid().free);
    assert!(free.rigid().dropped.is_empty());
}

/// Asked for the conjugate gradient, a folding problem keeps its folded S
/// while that is small and goes matrix-free above `AUTO_DENSE_LIMIT`
/// unknowns, where the folded S's N^2 products would cost more than the
/// lattice's FFT products (and its memory could run to gigabytes).
#[test]
fn the_conjugate_gradient_folds_only_a_small_problem() {
    let storage = |cells: f64| {
        let (points, geometry, _) = example1(cells, 1.3);
        let body = Body::uniform_patch(steel());
        let plan = ContactProblem::builder(points, &body, &body, &geometry, Loading::load(100.0))
            .method(Method::ConjugateGradient)
            .plan()
            .expect("plan");
        (plan.storage, plan.method)
    };
    // 8 cells a radius: 349 points, folded to about an eighth.
    assert_eq!(storage(8.0), (Storage::Folded, Method::ConjugateGradient));
    // 64 cells a radius: 21,749 points, folded to about 2,700 > 2000.
    assert_eq!(storage(64.0), (Storage::Lattice, Method::ConjugateGradient));
}

#[test]
fn the_preconditioned_conjugate_gradient_gives_the_plain_answer_on_any_threads() {
    // Hertz at 32 cells per radius (N = 5,025): the lattice operator's
    // preconditioner (the default) against none, the same forces to the
    // certificate's tolerance in fewer iterations; and the same bits on one
    // thread and two.
    let (_, free, hertz) = spheres(32.0, 1.25, Loading::load(100.0));
    let solve = |preconditioner: bool, threads: usize| {
        let options = Options {
            preconditioner,
            ..Options::default()
        };
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| free.solve(Method::ConjugateGradient, &options))
            .expect("solve")
    };
    let (pre, plain) = (solve(true, 1), solve(false, 1));
    assert!(pre.certificate.holds() && pre.certificate.worst() <= 1e-12);
    assert!(rel(&pre.forces, &plain.forces) < 1e-9, "forces");
    assert!((pre.approach / plain.approach - 1.0).abs() < 1e-9);
    assert!((pre.approach / hertz.approach() - 1.0).abs() < 2e-3);
    let (i_pre, i_plain) = (pre.statistics.iterations(), plain.statistics.iterations());
    assert!(2 * i_pre < i_plain, "{i_pre} iterations against {i_plain}");
    assert_eq!(pre.statistics.preconditionings(), i_pre);
    assert_eq!(plain.statistics.preconditionings(), 0);
    let two = solve(true, 2);
    let bits = |f: &[f64]| f.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&pre.forces), bits(&two.forces));
}
