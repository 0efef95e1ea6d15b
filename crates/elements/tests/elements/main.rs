//! The rolling bearing as a system of contacts against the discrete
//! Hertz-spring model (Harris & Kotzalas, ch. 7) and Stribeck's ratio.

use elcon_analysis::Material;
use elcon_analysis::system::SystemSettings;
use elcon_elements::ElementsError;
use elcon_elements::bearing::{BallBearing, BearingGrid};
use elcon_elements::life::RatingLife;
use elcon_elements::springs::HertzSprings;

/// The bearing of examples/scenes/ball-bearing-radial.toml.
fn bearing(clearance: Option<f64>) -> BallBearing {
    BallBearing {
        ball_diameter: 7.938,
        inner_raceway_diameter: 31.0,
        outer_raceway_diameter: 46.9,
        inner_groove_radius: 0.52 * 7.938,
        outer_groove_radius: 0.53 * 7.938,
        balls: 9,
        diametral_clearance: clearance,
        material: Material::new(210e3, 0.3).unwrap(),
        radial_load: 2000.0,
    }
}

/// The tolerance against the Hertz springs: the 21-across grid's own
/// discretization error of a Hertz approach (docs/validation.md §2b: about
/// 2e-3 at 21 across), which the loads inherit through the ring's
/// equilibrium.
const GRID: f64 = 3e-3;

#[test]
fn the_ball_loads_and_the_ring_displacement_are_the_hertz_springs() {
    for clearance in [None, Some(0.0), Some(0.05)] {
        let b = bearing(clearance);
        let springs = HertzSprings::of(&b).unwrap().solve().unwrap();
        let s = b
            .system(&BearingGrid::default())
            .unwrap()
            .solve(&SystemSettings::default())
            .unwrap();
        assert!(s.system.certificate.holds(), "{:?}", s.system.certificate);
        assert_eq!(s.loaded, springs.loaded(), "{clearance:?}");
        for (e, q) in s.elements.iter().zip(&springs.loads) {
            assert!(
                (e.load - q).abs() <= GRID * springs.loads[0],
                "{clearance:?}: {} vs {q}",
                e.load
            );
        }
        let delta = springs.ring_displacement;
        assert!(
            (s.ring_displacement[0] / delta - 1.0).abs() <= GRID,
            "{clearance:?}"
        );
        // The ring does not move sideways under a load along x.
        assert!(s.ring_displacement[1].abs() <= 1e-9 * delta);
        // The most loaded ball's inner peak pressure is Hertz's at its load.
        let [inner, _] = b.hertz(s.elements[0].load).unwrap();
        let p0 = inner.peak_pressure();
        assert!(
            (s.elements[0].max_pressure_inner / p0 - 1.0).abs() < 1e-2,
            "{clearance:?}"
        );
        // The ring's equilibrium from the balls' loads.
        let total: f64 = s
            .elements
            .iter()
            .map(|e| e.load * e.angle.to_radians().cos())
            .sum();
        assert!((total / 2000.0 - 1.0).abs() < 1e-9);
    }
}

#[test]
fn zero_clearance_gives_stribecks_ratio() {
    let s = bearing(Some(0.0))
        .system(&BearingGrid::default())
        .unwrap()
        .solve(&SystemSettings::default())
        .unwrap();
    let ratio = 9.0 * s.elements[0].load / 2000.0;
    // Stribeck's 4.37 is the many-ball limit; 9 Hertz springs give 4.385.
    assert!((ratio / 4.37 - 1.0).abs() < 5e-3, "{ratio}");
}

#[test]
fn a_cold_start_reaches_the_same_answer() {
    let system = bearing(None)
        .system(&BearingGrid {
            across: 11,
            zone: 1.5,
        })
        .unwrap();
    let warm = system.solve(&SystemSettings::default()).unwrap();
    let cold = SystemSettings {
        initial: Some(vec![0.0; system.system.free_motions().len()]),
        ..SystemSettings::default()
    };
    let cold = system.solve(&cold).unwrap();
    assert!(cold.system.certificate.holds());
    for (a, b) in warm.elements.iter().zip(&cold.elements) {
        assert!(
            (a.load - b.load).abs() <= 1e-7 * warm.elements[0].load,
            "{} vs {}",
            a.load,
            b.load
        );
    }
    assert!(cold.system.iterations >= warm.system.iterations);
}

#[test]
fn the_life_from_the_system_and_the_refusals() {
    let b = bearing(None);
    let s = b
        .system(&BearingGrid {
            across: 11,
            zone: 1.5,
        })
        .unwrap()
        .solve(&SystemSettings::default())
        .unwrap();
    let loads: Vec<f64> = s.elements.iter().map(|e| e.load).collect();
    let life = RatingLife::of(&b, &loads).unwrap();
    // Twice the load: an eighth of the life (the loads scale nearly
    // linearly with the radial load; the exponent 3 of the life).
    let heavy = BallBearing {
        radial_load: 4000.0,
        ..b.clone()
    };
    let s2 = heavy
        .system(&BearingGrid {
            across: 11,
            zone: 1.5,
        })
        .unwrap()
        .solve(&SystemSettings::default())
        .unwrap();
    let loads2: Vec<f64> = s2.elements.iter().map(|e| e.load).collect();
    let life2 = RatingLife::of(&heavy, &loads2).unwrap();
    let ratio = life.l10 / life2.l10;
    assert!(ratio > 6.0 && ratio < 10.0, "{ratio}");
    // No balls, and a preload deeper than the contact could take.
    for (edit, field) in [
        (
            BallBearing {
                balls: 0,
                ..b.clone()
            },
            "balls",
        ),
        (
            BallBearing {
                diametral_clearance: Some(-2.0),
                ..b.clone()
            },
            "diametral_clearance",
        ),
    ] {
        let e = edit.system(&BearingGrid::default()).unwrap_err();
        assert!(
            matches!(e, ElementsError::InvalidInput { .. }) && e.to_string().contains(field),
            "{e}"
        );
    }
}
