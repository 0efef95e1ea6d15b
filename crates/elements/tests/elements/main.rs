//! The rolling bearing as a system of contacts against the discrete
//! Hertz-spring model (Harris & Kotzalas, ch. 7) and Stribeck's ratio.

use elcon_analysis::system::SystemSettings;
use elcon_elements::ElementsError;
use elcon_elements::bearing::{BallBearing, BearingGrid};
use elcon_elements::life::RatingLife;

/// The bearing of examples/scenes/ball-bearing-radial.toml.
fn bearing(clearance: Option<f64>) -> BallBearing {
    elcon_fixtures::bearings::ball(clearance)
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
        let springs = b.springs().unwrap().solve().unwrap();
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

mod rollers {
    use super::*;
    use elcon_elements::roller::{Crown, RollerBearing, RollerGrid, Slicing};

    /// The bearing of examples/scenes/roller-bearing-misaligned.toml.
    fn bearing(crown: Crown, misalignment: f64) -> RollerBearing {
        elcon_fixtures::bearings::roller(crown, misalignment)
    }

    const CROWN: Crown = elcon_fixtures::bearings::CROWN;

    #[test]
    fn the_rollers_share_the_load_and_tilt_half_the_misalignment() {
        let b = bearing(CROWN, 1e-3);
        let s = b
            .system(&RollerGrid::default())
            .unwrap()
            .solve(&SystemSettings::default())
            .unwrap();
        assert!(s.system.certificate.holds(), "{:?}", s.system.certificate);
        let total: f64 = s
            .elements
            .iter()
            .map(|e| e.load * e.angle.to_radians().cos())
            .sum();
        assert!((total / 8000.0 - 1.0).abs() < 1e-9);
        // Each loaded roller turns by about half the ring's misalignment
        // where it stands (its two contacts nearly alike); the ring moves
        // along the load only.
        for e in s.elements.iter().filter(|e| e.load > 0.0) {
            let ring = 1e-3 * e.angle.to_radians().cos();
            assert!(
                (e.tilt / ring - 0.5).abs() < 0.1,
                "{}: {} vs {ring}",
                e.angle,
                e.tilt
            );
        }
        assert!(s.ring_displacement[1].abs() < 1e-9 * s.ring_displacement[0]);
        // The slicing model shares the load among as many rollers, its
        // largest within 15 % (its Palmgren slices are stiffer than the
        // half-space's contacts: docs/validation.md §6b).
        let slicing = Slicing {
            bearing: b.clone(),
            slices: 60,
        }
        .solve()
        .unwrap();
        let loaded = slicing.loads.iter().filter(|q| **q > 0.0).count();
        assert_eq!(loaded, s.loaded);
        assert!((s.elements[0].load / slicing.loads[0] - 1.0).abs() < 0.15);
        let life =
            RatingLife::of_rollers(&b, &s.elements.iter().map(|e| e.load).collect::<Vec<_>>())
                .unwrap();
        assert!(life.l10 > 0.0 && life.l10 < life.inner_life);
    }

    #[test]
    fn a_straight_misaligned_roller_peaks_at_its_end_and_a_crown_takes_the_peak_away() {
        let grid = RollerGrid::default();
        let solve = |crown| {
            bearing(crown, 1e-3)
                .system(&grid)
                .unwrap()
                .solve(&SystemSettings::default())
                .unwrap()
        };
        let (straight, crowned) = (solve(Crown::Straight), solve(CROWN));
        let end_ratio = |s: &elcon_elements::bearing::BearingSolution| {
            let zone = &s.system.zones[0];
            let n = grid.along;
            let p = &zone.pressures;
            let end = (0..p.len() / n)
                .flat_map(|i| [p[i * n], p[i * n + n - 1]])
                .fold(0.0f64, f64::max);
            end / zone.max_pressure
        };
        // The straight roller's largest pressure is at its end cell, far
        // above what its slices carry; the crown brings it inside.
        assert_eq!(end_ratio(&straight), 1.0);
        assert!(end_ratio(&crowned) < 0.5);
        let slicing = Slicing {
            bearing: bearing(Crown::Straight, 1e-3),
            slices: grid.along,
        }
        .solve()
        .unwrap();
        assert!(straight.elements[0].max_pressure_inner > 1.3 * slicing.max_pressures[0]);
        assert!(crowned.elements[0].max_pressure_inner < straight.elements[0].max_pressure_inner);
    }

    #[test]
    fn bad_roller_data_is_named() {
        for (b, field) in [
            (
                RollerBearing {
                    rollers: 0,
                    ..bearing(CROWN, 0.0)
                },
                "rollers",
            ),
            (bearing(CROWN, 0.05), "misalignment"),
            (
                bearing(
                    Crown::Circular {
                        drop: -1.0,
                        flat: 0.0,
                    },
                    0.0,
                ),
                "crown.drop",
            ),
            (
                bearing(
                    Crown::Circular {
                        drop: 0.01,
                        flat: 9.0,
                    },
                    0.0,
                ),
                "crown.flat",
            ),
            (
                RollerBearing {
                    roller_length: 0.0,
                    ..bearing(CROWN, 0.0)
                },
                "roller_length",
            ),
        ] {
            let e = b.system(&RollerGrid::default()).unwrap_err();
            assert!(e.to_string().contains(field), "{field}: {e}");
        }
        let e = bearing(CROWN, 0.0)
            .system(&RollerGrid {
                across: 10,
                ..RollerGrid::default()
            })
            .unwrap_err();
        assert!(e.to_string().contains("across"), "{e}");
    }
}
