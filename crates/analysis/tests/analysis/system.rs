//! Systems of contacts (`elcon_analysis::system`) against what a single
//! contact gives, and their refusals.

use elcon_analysis::references::HertzSpheres;
use elcon_analysis::system::{Frame, Motion, RigidBody, System, SystemSettings, SystemZone};
use elcon_analysis::{
    AnalysisError, Body, ContactProblem, Geometry, Loading, Material, Method, Options, PointSet,
    Storage, Surface, combined_modulus, grid,
};

/// Conry & Seireg's Example 1 (two steel spheres, R = 1 and 10 in, 100 lb)
/// on 15 points across, unfolded and dense.
fn spheres(loading: Loading) -> ContactProblem {
    let steel = Material::new(30e6, 0.3).unwrap();
    let hertz = HertzSpheres::new(combined_modulus(&steel, &steel), 1.0 / 1.1, 100.0).unwrap();
    let points = grid::hertz_disk(hertz.contact_radius(), 15, 1.3).unwrap();
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    ContactProblem::builder(points, &body, &body, &geometry, loading)
        .storage(Storage::Dense)
        .fold(false)
        .build()
        .unwrap()
}

/// The frame of a zone at height `z` facing up (+z).
fn up(z: f64) -> Frame {
    Frame {
        origin: [0.0, 0.0, z],
        e1: [1.0, 0.0, 0.0],
        e2: [0.0, 1.0, 0.0],
    }
}

fn zone(name: &str, body_a: usize, body_b: usize, frame: Frame, clearance: f64) -> SystemZone {
    SystemZone {
        name: name.into(),
        body_a,
        body_b,
        frame,
        problem: spheres(Loading::approach(0.0)),
        clearance,
    }
}

#[test]
fn one_zone_under_a_load_and_moments_is_the_single_contact() {
    let (p, mx, my) = (100.0, 0.3, -0.2);
    let body = RigidBody::free("punch", [0.0; 3], &[Motion::Z, Motion::RotX, Motion::RotY])
        .with_load(Motion::Z, p)
        .with_load(Motion::RotX, mx)
        .with_load(Motion::RotY, my);
    let system = System::new(
        vec![body, RigidBody::fixed("base")],
        vec![zone("contact", 0, 1, up(0.0), 0.0)],
    )
    .unwrap();
    let s = system.solve(&SystemSettings::default()).unwrap();
    assert!(s.certificate.holds(), "{:?}", s.certificate);
    let single = spheres(Loading::load(p).with_moment_x(mx).with_moment_y(my))
        .solve(Method::Lemke, &Options::default())
        .unwrap();
    let z = &s.zones[0];
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-8 * scale;
    let alpha = single.approach;
    assert!(close(z.approach, alpha, alpha), "{} vs {alpha}", z.approach);
    let tilt = single.tilt_x.abs().max(single.tilt_y.abs());
    assert!(close(z.tilt_x, single.tilt_x, tilt) && close(z.tilt_y, single.tilt_y, tilt));
    let fmax = single.forces.iter().fold(0.0f64, |a, f| a.max(*f));
    for (a, b) in z.forces.iter().zip(&single.forces) {
        assert!(close(*a, *b, fmax), "{a} vs {b}");
    }
    assert_eq!(s.displacements[0][2], z.approach);
}

#[test]
fn a_free_element_between_two_zones_carries_the_load_through_and_a_far_zone_none() {
    // A plate pressed down... up: body 0 pushes a free ball (body 1) into
    // the fixed top (body 2); a side zone with a wide clearance stays open.
    let bodies = vec![
        RigidBody::free("press", [0.0; 3], &[Motion::Z]).with_load(Motion::Z, 100.0),
        RigidBody::free("ball", [0.0, 0.0, 1.0], &[Motion::Z]),
        RigidBody::fixed("top"),
    ];
    let zones = vec![
        zone("below", 0, 1, up(0.0), 0.0),
        zone("above", 1, 2, up(2.0), 1e-4),
        zone("aside", 0, 2, up(0.0), 1.0),
    ];
    let system = System::new(bodies, zones).unwrap();
    // From a cold start (every body at rest, nothing in contact).
    let s = system.solve(&SystemSettings::default()).unwrap();
    assert!(s.certificate.holds(), "{:?}", s.certificate);
    let (below, above, aside) = (&s.zones[0], &s.zones[1], &s.zones[2]);
    assert!((below.load / 100.0 - 1.0).abs() < 1e-8 && (above.load / 100.0 - 1.0).abs() < 1e-8);
    assert_eq!(aside.load, 0.0);
    // The two contacts are the same: each takes the single contact's
    // approach, and the press moves by both plus the clearance.
    let single = spheres(Loading::load(100.0))
        .solve(Method::Lemke, &Options::default())
        .unwrap();
    let press = s.displacements[0][2];
    assert!(
        (press / (2.0 * single.approach + 1e-4) - 1.0).abs() < 1e-8,
        "{press}"
    );
}

#[test]
fn an_unrestrained_body_and_bad_zones_are_named() {
    let loaded = || RigidBody::free("press", [0.0; 3], &[Motion::Z]).with_load(Motion::Z, 1.0);
    // A free translation along y: every zone's normal is z.
    let slides =
        RigidBody::free("slider", [0.0; 3], &[Motion::Z, Motion::Y]).with_load(Motion::Z, 1.0);
    let e = System::new(
        vec![slides, RigidBody::fixed("base")],
        vec![zone("c", 0, 1, up(0.0), 0.0)],
    )
    .unwrap_err();
    assert!(matches!(e, AnalysisError::Unrestrained { .. }), "{e}");
    assert!(
        e.to_string().contains("slider") && e.to_string().contains("along y"),
        "{e}"
    );
    // A rotation about z: no lever for it either.
    let spins = loaded().with_load(Motion::RotZ, 0.0);
    let e = System::new(
        vec![spins, RigidBody::fixed("base")],
        vec![zone("c", 0, 1, up(0.0), 0.0)],
    )
    .unwrap_err();
    assert!(e.to_string().contains("rotation about z"), "{e}");
    let two = || vec![loaded(), RigidBody::fixed("base")];
    let cases: Vec<(Vec<SystemZone>, &str)> = vec![
        (vec![], "zones"),
        (vec![zone("c", 0, 5, up(0.0), 0.0)], "zones[0] (c).body_b"),
        (vec![zone("c", 1, 1, up(0.0), 0.0)], "zones[0] (c).body_b"),
        (
            vec![SystemZone {
                frame: Frame {
                    e2: [0.0, 0.9, 0.0],
                    ..up(0.0)
                },
                ..zone("c", 0, 1, up(0.0), 0.0)
            }],
            "zones[0] (c).frame",
        ),
        (
            vec![zone("c", 0, 1, up(0.0), f64::NAN)],
            "zones[0] (c).clearance",
        ),
        (
            vec![SystemZone {
                problem: spheres(Loading::approach(0.0))
                    .with_loading(Loading::approach(0.0))
                    .unwrap(),
                ..zone("c", 0, 1, up(0.0), 0.0)
            }],
            "",
        ),
    ];
    for (zones, field) in cases {
        let result = System::new(two(), zones);
        if field.is_empty() {
            assert!(result.is_ok());
            continue;
        }
        let e = result.unwrap_err();
        assert!(e.to_string().contains(field), "{field}: {e}");
    }
    // A folded zone and a line zone are refused, naming the zone's problem.
    let steel = Material::new(30e6, 0.3).unwrap();
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    let folded = ContactProblem::builder(
        PointSet::grid_disk(0.002, 0.02).unwrap(),
        &body,
        &body,
        &geometry,
        Loading::approach(0.0),
    )
    .storage(Storage::Folded)
    .build()
    .unwrap();
    let line_geometry = Geometry::Surfaces(Surface::Cylinder { radius: 1.0 }, Surface::Plane);
    let strip = Body::plane_strain(steel, 1.0);
    let line = ContactProblem::new(
        PointSet::line(-0.01, 0.01, 11).unwrap(),
        &strip,
        &strip,
        &line_geometry,
        Loading::approach(0.0),
    )
    .unwrap();
    for (problem, why) in [(folded, "unfolded"), (line, "line")] {
        let zones = vec![SystemZone {
            problem,
            ..zone("c", 0, 1, up(0.0), 0.0)
        }];
        let e = System::new(two(), zones).unwrap_err();
        assert!(
            e.to_string().contains("zones[0] (c).problem") && e.to_string().contains(why),
            "{e}"
        );
    }
    // A non-finite load names its body and motion.
    let e = System::new(
        vec![
            RigidBody::free("press", [0.0; 3], &[Motion::Z]).with_load(Motion::Z, f64::INFINITY),
            RigidBody::fixed("b"),
        ],
        vec![zone("c", 0, 1, up(0.0), 0.0)],
    )
    .unwrap_err();
    assert!(
        e.to_string().contains("press") && e.to_string().contains("translation along z"),
        "{e}"
    );
}
