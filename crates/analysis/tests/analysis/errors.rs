//! One test per `AnalysisError` variant: the error a user gets, and that its
//! message names the field and the reason.

use elcon_analysis::{AnalysisError, ContactProblem, Geometry, Loading, Method, Surface};
use elcon_fixtures::errors::{assert_pivot_limit_passes_through, one_pivot};
use elcon_influence::{Body, Material, PointSet};
use elcon_lcp::LcpError;
use faer::Mat;

fn steel() -> Material {
    Material::new(30e6, 0.3).unwrap()
}

fn disk() -> PointSet {
    PointSet::grid_disk(0.01, 0.05).unwrap()
}

fn spheres() -> Geometry {
    Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    )
}

#[test]
fn invalid_input_names_the_field() {
    let body = Body::uniform_patch(steel());
    for (loading, field) in [
        (Loading::load(0.0), "load"),
        (Loading::load(-5.0), "load"),
        (Loading::load(f64::NAN), "load"),
        (Loading::approach(f64::INFINITY), "approach"),
    ] {
        let e = ContactProblem::new(disk(), &body, &body, &spheres(), loading).unwrap_err();
        assert!(
            matches!(e, AnalysisError::InvalidInput { field: f, .. } if f == field),
            "{e:?}"
        );
        assert!(e.to_string().starts_with(&format!("`{field}` = ")), "{e}");
    }
    let flat = Geometry::Surfaces(Surface::Sphere { radius: 0.0 }, Surface::Plane);
    let e = ContactProblem::new(disk(), &body, &body, &flat, Loading::load(1.0)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "`surface1.radius` = 0: a radius must be finite and non-zero (negative for a concave surface)"
    );
}

#[test]
fn size_mismatch_names_the_field_and_sizes() {
    let body = Body::uniform_patch(steel());
    let n = disk().len();
    let e = ContactProblem::new(
        disk(),
        &body,
        &body,
        &Geometry::Separation(vec![0.0; 3]),
        Loading::load(1.0),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("`separation` has 3 entries, expected {n} (one per candidate point)")
    );
    let e = ContactProblem::from_parts(
        disk(),
        Mat::zeros(n, n + 1),
        vec![0.0; n],
        Loading::load(1.0),
    )
    .unwrap_err();
    assert!(
        matches!(e, AnalysisError::SizeMismatch { field: "influence", found, .. } if found == n + 1)
    );
}

#[test]
fn non_finite_separation_is_located() {
    let body = Body::uniform_patch(steel());
    let n = disk().len();
    let mut eps = vec![0.0; n];
    eps[4] = f64::NAN;
    let e = ContactProblem::new(
        disk(),
        &body,
        &body,
        &Geometry::Separation(eps),
        Loading::load(1.0),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "`separation` has a non-finite value (NaN) at point 4"
    );
}

#[test]
fn a_non_finite_entry_of_a_given_influence_matrix_is_located() {
    let n = disk().len();
    let mut s = Mat::<f64>::identity(n, n);
    s[(2, 3)] = f64::NAN;
    s[(4, 1)] = f64::INFINITY;
    let e = ContactProblem::from_parts(disk(), s, vec![0.0; n], Loading::load(1.0)).unwrap_err();
    assert!(matches!(
        e,
        AnalysisError::NonFiniteEntry {
            field: "influence",
            row: 2,
            column: 3,
            ..
        }
    ));
    assert_eq!(
        e.to_string(),
        "`influence`[2, 3] = NaN: must be a finite number"
    );
}

#[test]
fn incompatible_geometry_says_what_to_use() {
    let line = PointSet::line(-1.0, 1.0, 11).unwrap();
    let body = Body::plane_strain(steel(), 10.0);
    let e = ContactProblem::new(line, &body, &body, &spheres(), Loading::load(1.0)).unwrap_err();
    assert!(matches!(
        e,
        AnalysisError::Incompatible {
            field: "surface1.radius",
            ..
        }
    ));
    assert!(e.to_string().contains("use a cylinder"), "{e}");
}

#[test]
fn influence_errors_pass_through() {
    let line = PointSet::line(-1.0, 1.0, 11).unwrap();
    let body = Body::uniform_patch(steel());
    let cylinders = Geometry::Surfaces(Surface::Cylinder { radius: 1.0 }, Surface::Plane);
    let e = ContactProblem::new(line, &body, &body, &cylinders, Loading::load(1.0)).unwrap_err();
    assert!(matches!(e, AnalysisError::Influence(_)), "{e:?}");
    assert!(
        e.to_string()
            .contains("does not apply to a line (2D) point set"),
        "{e}"
    );
}

#[test]
fn engine_errors_pass_through() {
    // A pivot limit of 1 cannot solve a contact that needs dozens of pivots.
    let body = Body::uniform_patch(steel());
    let problem =
        ContactProblem::new(disk(), &body, &body, &spheres(), Loading::load(100.0)).unwrap();
    let e = problem.solve(Method::Lemke, &one_pivot()).unwrap_err();
    assert!(
        matches!(
            e,
            AnalysisError::Engine(LcpError::PivotLimit { limit: 1, .. })
        ),
        "{e:?}"
    );
    // The engine's error is also the source of the chain.
    assert_pivot_limit_passes_through(&e, "the contact solve failed: pivot limit 1 reached");
}

#[test]
fn the_loading_is_checked_before_the_assembly() {
    // A bad load is reported even when the bodies would be refused by the
    // assembly too: the cheap checks come before the O(N^2) work.
    let line = PointSet::line(-1.0, 1.0, 11).unwrap();
    let body = Body::uniform_patch(steel()); // a surface model on a line
    let cylinders = Geometry::Surfaces(Surface::Cylinder { radius: 1.0 }, Surface::Plane);
    for build in [ContactProblem::new, ContactProblem::symmetric] {
        let e = build(line.clone(), &body, &body, &cylinders, Loading::load(-1.0)).unwrap_err();
        assert!(
            matches!(e, AnalysisError::InvalidInput { field: "load", .. }),
            "{e:?}"
        );
    }
}
