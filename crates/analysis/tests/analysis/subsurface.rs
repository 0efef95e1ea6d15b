//! Stresses below the surface against Hertz's (Johnson 1985, §3.4, §4.2):
//! the point contact's largest shear 0.31 p0 at z = 0.48 a, the line
//! contact's 0.30 p0 at z = 0.78 b and its orthogonal shear 0.25 p0 at
//! z = 0.50 b, x = +-0.87 b, each within 1 % on the grids the example
//! scenes use; each body its own field; the bodies that have none said so;
//! the field independent of how the grid lies under the contact.

use elcon_analysis::references::HertzCylinders;
use elcon_analysis::subsurface::reference::{hertz_line, hertz_point_axis};
use elcon_analysis::subsurface::{
    DEPTH_SPAN, Subsurface, SubsurfaceOptions, contact_half_width, depth_grid,
};
use elcon_analysis::{ContactProblem, Geometry, Loading, Method, Options, PointSet, Surface};
use elcon_fixtures::scenes::spheres;
use elcon_influence::{Body, Material, combined_modulus};

fn stresses(s: Subsurface) -> elcon_analysis::subsurface::BodyStresses {
    match s {
        Subsurface::Stresses(b) => *b,
        Subsurface::NotApplicable(why) => panic!("{why}"),
    }
}

#[test]
fn below_hertz_spheres_the_largest_shear_is_031_p0_at_048_a() {
    // Example 1's spheres on its 41-across grid (20 cells a radius).
    let steel = Material::new(30e6, 0.3).unwrap();
    let (problem, hertz) = spheres(steel, steel, 1.0, 10.0, 100.0, 20.0, 1.3);
    let sol = problem
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap();
    let body = Body::uniform_patch(steel);
    let s = stresses(Subsurface::of(
        problem.points(),
        &sol,
        &body,
        &SubsurfaceOptions::default(),
    ));
    let (p0, a) = (hertz.peak_pressure(), hertz.contact_radius());
    // The largest shear on the axis: 0.31 p0 at 0.48 a (the closed form's
    // own maximum, to its rounding).
    let reference = (1..=4000)
        .map(|i| {
            (
                hertz_point_axis(i as f64 * 5e-4 * a, a, 0.3).tresca(),
                i as f64 * 5e-4,
            )
        })
        .fold((0.0, 0.0), |b, c| if c.0 > b.0 { c } else { b });
    let tau = s.tresca.value / p0;
    assert!(
        (tau / reference.0 - 1.0).abs() < 0.01,
        "{tau} against {reference:?}"
    );
    assert!(
        (s.tresca.z / a - reference.1).abs() < 0.01 * reference.1 + 0.02,
        "{}",
        s.tresca.z / a
    );
    assert!(s.tresca.x.abs() < 0.05 * a && s.tresca.y.abs() < 0.05 * a);
    // The von Mises stress below the centre against the closed form, at
    // every depth of the profile.
    for (z, stress) in s.profile.depths.iter().zip(&s.profile.stresses) {
        let exact = hertz_point_axis(*z, a, 0.3).von_mises();
        assert!(
            (stress.von_mises() / p0 - exact).abs() < 0.01,
            "z = {z}: {} {exact}",
            stress.von_mises() / p0
        );
    }
}

#[test]
fn below_a_hertz_line_contact_the_shears_are_johnsons() {
    // The hertz-cylinders scene: steel cylinder R = 5 mm on a plane, 1 kN/mm,
    // plane strain, 41 points across the contact.
    let steel = Material::new(210e3, 0.3).unwrap();
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 5.0, 1000.0).unwrap();
    let b = hertz.half_width();
    let points = elcon_analysis::grid::hertz_line(b, 41, 1.5).unwrap();
    let body = Body::plane_strain(steel, 100.0);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
    let problem =
        ContactProblem::new(points, &body, &body, &geometry, Loading::load(1000.0)).unwrap();
    let sol = problem
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap();
    let s = stresses(Subsurface::of(
        problem.points(),
        &sol,
        &body,
        &SubsurfaceOptions::default(),
    ));
    let p0 = hertz.peak_pressure();
    assert!(
        (s.tresca.value / p0 - 0.3005).abs() < 0.01 * 0.30,
        "{}",
        s.tresca.value / p0
    );
    assert!((s.tresca.z / b - 0.786).abs() < 0.02, "{}", s.tresca.z / b);
    assert!(
        (s.orthogonal_xz.value.abs() / p0 - 0.2500).abs() < 0.01 * 0.25,
        "{}",
        s.orthogonal_xz.value / p0
    );
    assert!(
        (s.orthogonal_xz.z / b - 0.50).abs() < 0.02,
        "{}",
        s.orthogonal_xz.z / b
    );
    assert!(
        (s.orthogonal_xz.x.abs() / b - 0.866).abs() < 0.02,
        "{}",
        s.orthogonal_xz.x / b
    );
    // The whole section against McEwen's field, sign included.
    for (i, x) in s.section.xs.iter().enumerate() {
        for (j, z) in s.section.depths.iter().enumerate() {
            let got = s.section.stresses[i * s.section.depths.len() + j];
            let exact = hertz_line(*x, *z, b, 0.3);
            for (g, e) in [(got.xx, exact.xx), (got.zz, exact.zz), (got.xz, exact.xz)] {
                assert!((g / p0 - e).abs() < 0.01, "({x}, {z}): {g} against {e}");
            }
        }
    }
    assert_eq!(s.orthogonal_yz.value, 0.0);
}

#[test]
fn each_body_has_its_own_field_and_those_without_one_say_so() {
    let steel = Material::new(210e3, 0.3).unwrap();
    let glass = Material::new(70e3, 0.22).unwrap();
    let (problem, _) = spheres(steel, glass, 10.0, 20.0, 100.0, 12.0, 1.3);
    let sol = problem
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap();
    let options = SubsurfaceOptions::default();
    let on_steel = stresses(Subsurface::of(
        problem.points(),
        &sol,
        &Body::uniform_patch(steel),
        &options,
    ));
    let on_glass = stresses(Subsurface::of(
        problem.points(),
        &sol,
        &Body::uniform_patch(glass),
        &options,
    ));
    assert_eq!(on_steel.poissons_ratio, 0.3);
    assert_eq!(on_glass.poissons_ratio, 0.22);
    // The same pressure, another Poisson's ratio: another von Mises peak
    // (the axial stresses depend on nu, sigma_z does not).
    assert!((on_steel.von_mises.value / on_glass.von_mises.value - 1.0).abs() > 0.01);
    for body in [Body::rigid(), Body::winkler(1e6)] {
        assert!(matches!(
            Subsurface::of(problem.points(), &sol, &body, &options),
            Subsurface::NotApplicable(_)
        ));
    }
}

#[test]
fn a_contact_has_a_half_width_and_no_contact_has_none() {
    // Cells of 1 x 0.5 on [-4, 4] x [-2, 2], points ordered by x then y.
    let grid = PointSet::grid_rectangle(4.0, 2.0, 8, 8).unwrap();
    assert_eq!(contact_half_width(&grid, std::iter::empty()), None);
    // One point: half its cell's narrower side.
    assert_eq!(contact_half_width(&grid, [9].into_iter()), Some(0.25));
    // Columns x = -3.5 .. -1.5 (3 cells), rows y = -1.75 .. 1.75 (8):
    // 1.5 across x, 2 across y.
    let block: Vec<usize> = (8..32).collect();
    assert_eq!(contact_half_width(&grid, block.iter().copied()), Some(1.5));
    // On a line, across x whatever y.
    let line = PointSet::line(-1.0, 1.0, 10).unwrap();
    let across = contact_half_width(&line, [2, 3, 4].into_iter()).unwrap();
    assert!((across - 0.3).abs() < 1e-15, "{across}");
    assert_eq!(contact_half_width(&line, std::iter::empty()), None);
    // No contact, so no width: the depth grid reaches down a cell's worth
    // of span; the point force's grid starts a cell deep.
    let depths = depth_grid(&grid, 0.0, false, 4);
    assert_eq!(depths, [0.25, 0.5, 0.75, 1.0].map(|f| f * DEPTH_SPAN));
    let depths = depth_grid(&grid, 1.5, true, 2);
    assert_eq!(
        depths,
        [1.0 + (1.5 * DEPTH_SPAN - 1.0) / 2.0, 1.5 * DEPTH_SPAN]
    );
}

/// The maxima of an elliptical contact (gap x^2/2Rx + y^2/2Ry) on a disk
/// grid of square cells, solved as it is and turned by 90 degrees.
fn elliptical(rx: f64, ry: f64, centre: (f64, f64)) -> elcon_analysis::subsurface::BodyStresses {
    let steel = Material::new(210e3, 0.3).unwrap();
    let points = PointSet::grid_disk(0.02, 0.6).unwrap();
    let gap = (0..points.len())
        .map(|k| {
            let (x, y) = (points.x(k) - centre.0, points.y(k) - centre.1);
            x * x / (2.0 * rx) + y * y / (2.0 * ry)
        })
        .collect();
    let body = Body::uniform_patch(steel);
    let problem = ContactProblem::new(
        points,
        &body,
        &body,
        &Geometry::Separation(gap),
        Loading::load(200.0),
    )
    .unwrap();
    let sol = problem
        .solve(Method::BlockPivoting, &Options::default())
        .unwrap();
    stresses(Subsurface::of(
        problem.points(),
        &sol,
        &body,
        &SubsurfaceOptions::default(),
    ))
}

#[test]
fn the_field_does_not_depend_on_how_the_grid_lies() {
    // Turned by 90 degrees on a grid symmetric under the turn: the same
    // discrete problem, so the same maxima to rounding, x and y swapped and
    // tau_xz become tau_yz (a check of the kernels' and the layers'
    // orientation).
    let along = elliptical(10.0, 40.0, (0.0, 0.0));
    let across = elliptical(40.0, 10.0, (0.0, 0.0));
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
    for (a, b) in [
        (along.von_mises, across.von_mises),
        (along.tresca, across.tresca),
    ] {
        assert!(close(a.value, b.value), "{a:?} {b:?}");
        assert!((a.z - b.z).abs() < 1e-6, "{a:?} {b:?}");
    }
    assert!(close(
        along.orthogonal_xz.value.abs(),
        across.orthogonal_yz.value.abs()
    ));
    assert!(close(
        along.orthogonal_yz.value.abs(),
        across.orthogonal_xz.value.abs()
    ));
    assert!((along.orthogonal_xz.z - across.orthogonal_yz.z).abs() < 1e-6);
    // Centred between grid points (half a cell off in x, a third in y):
    // another discrete problem with the same continuum answer, the maxima
    // within 1 % and their positions moved with the contact.
    let moved = elliptical(10.0, 40.0, (0.01, 0.02 / 3.0));
    for (a, b) in [
        (along.von_mises, moved.von_mises),
        (along.tresca, moved.tresca),
    ] {
        assert!((a.value / b.value - 1.0).abs() < 0.01, "{a:?} {b:?}");
        assert!((a.z - b.z).abs() < 0.02 * a.z, "{a:?} {b:?}");
        assert!((b.x - a.x - 0.01).abs() < 0.02 && (b.y - a.y - 0.02 / 3.0).abs() < 0.02);
    }
    assert!((along.orthogonal_xz.value.abs() / moved.orthogonal_xz.value.abs() - 1.0).abs() < 0.01);
}
