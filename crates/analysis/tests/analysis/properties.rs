//! Property tests on random contact scenes: whatever the materials, radii,
//! load, grid and model, every method returns forces with sum F = P, F >= 0,
//! gaps Y = S F + eps - alpha e >= 0 and F_k Y_k = 0, checked from the
//! problem's own S and eps (not from the engine's certificate; the check is
//! tests/analysis/common/checks.rs), and the methods agree.

use crate::common;

use common::checks::{check, force_scale, gap_scale};
use elcon_analysis::references::{HertzSpheres, combined_radius};
use elcon_analysis::{
    ContactProblem, ContactSolution, Geometry, Loading, Method, Options, Surface,
};
use elcon_influence::{Body, Material, PointSet, combined_modulus};
use proptest::prelude::*;

fn agree(
    problem: &ContactProblem,
    a: &ContactSolution,
    b: &ContactSolution,
) -> Result<(), TestCaseError> {
    let fmax = force_scale(problem, a, gap_scale(problem, a));
    for k in 0..a.forces.len() {
        prop_assert!(
            (a.forces[k] - b.forces[k]).abs() <= 1e-9 * fmax,
            "point {k}"
        );
    }
    prop_assert!((a.approach - b.approach).abs() <= 1e-9 * a.approach.abs().max(b.approach.abs()));
    Ok(())
}

/// `problem` solved by `reference` and by each of `others`: every solution
/// checked, and each of the others agreeing with the reference's.
fn all_agree(
    problem: &ContactProblem,
    reference: Method,
    others: [Method; 2],
) -> Result<(), TestCaseError> {
    let reference = problem.solve(reference, &Options::default()).unwrap();
    check(problem, &reference)?;
    for method in others {
        let sol = problem.solve(method, &Options::default()).unwrap();
        check(problem, &sol)?;
        agree(problem, &reference, &sol)?;
    }
    Ok(())
}

/// A material with E from 1e3 to 1e12 (any unit) and nu in (-0.9, 0.49).
fn material() -> impl Strategy<Value = Material> {
    (3.0f64..12.0, -0.9f64..0.49)
        .prop_map(|(log_e, nu)| Material::new(10f64.powf(log_e), nu).unwrap())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Two spheres on Love patches, load controlled, grid scaled to the Hertz radius.
    #[test]
    fn spheres_under_load(
        m1 in material(),
        m2 in material(),
        log_r1 in -3.0f64..1.0,
        log_ratio in -2.0f64..2.0,
        log_load in -3.0f64..5.0,
        cells in 2.0f64..5.0,
        zone in 1.05f64..1.6,
    ) {
        let r1 = 10f64.powf(log_r1);
        let r2 = r1 * 10f64.powf(log_ratio);
        let load = 10f64.powf(log_load);
        let hertz = HertzSpheres::new(combined_modulus(&m1, &m2), combined_radius(r1, r2), load).unwrap();
        let a = hertz.contact_radius();
        let points = PointSet::grid_disk(a / cells, zone * a).unwrap();
        let geometry = Geometry::Surfaces(Surface::Sphere { radius: r1 }, Surface::Sphere { radius: r2 });
        let problem = ContactProblem::new(
            points, &Body::uniform_patch(m1), &Body::uniform_patch(m2), &geometry, Loading::load(load),
        ).unwrap();
        all_agree(&problem, Method::RestrictedSimplex, [Method::Lemke, Method::BlockPivoting])?;
    }

    /// Arbitrary non-negative separations on a line (plane strain, optionally
    /// on a Winkler foundation), under a given approach.
    #[test]
    fn line_contact_under_approach(
        m in material(),
        n in 3usize..60,
        seps in proptest::collection::vec(0.0f64..1.0, 60),
        approach in 0.01f64..1.5,
        winkler in proptest::option::of(0.0f64..3.0),
    ) {
        let half = 1.0;
        let points = PointSet::line(-half, half, n).unwrap();
        // Separations in units of 1e-3 of the half-width, on the same scale as elastic deflections.
        let scale = 1e-3 * half;
        let eps: Vec<f64> = seps[..n].iter().map(|s| s * scale).collect();
        let elastic = Body::plane_strain(m, 10.0 * half);
        let second = match winkler {
            Some(log_k) => Body::winkler(m.youngs_modulus() * 10f64.powf(log_k)),
            None => Body::rigid(),
        };
        let problem = ContactProblem::new(
            points, &elastic, &second, &Geometry::Separation(eps), Loading::approach(approach * scale),
        ).unwrap();
        all_agree(&problem, Method::Lemke, [Method::RestrictedSimplex, Method::BlockPivoting])?;
    }
}
