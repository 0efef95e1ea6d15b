//! A run's discretization error estimate and its reference where the load
//! acts off the origin: result.json's `discretization` block (on by
//! default, off with `[solver] error_estimate = false`, saying so when the
//! grid is too coarse for a coarser one; finer grids where the coarser
//! ones leave a quantity not resolved; a singular rim named), and the
//! eccentric spheres'
//! errors against the Hertz solution translated to the load centre, at the
//! discretization's level (the origin-centred one gave an approach error
//! of -50 %).

use crate::common::{EXAMPLE1_GRID, SPHERES, scene, with_table};
use elcon_runner::run;

#[test]
fn every_run_estimates_its_discretization_error_unless_told_not_to() {
    let r = run(&scene(SPHERES).unwrap()).unwrap();
    let d = r.result.discretization.as_ref().expect("on by default");
    // h, 2h, 4h and, the approach not resolved by them (its grid at 4h lies
    // closer to Hertz than 2h's: alternating changes), the two grids
    // between for the least-squares fit; still not resolved, the finer grid
    // h/2 and the grid between it and h: seven grids, the run's own third.
    assert_eq!((d.grids.len(), d.own_grid), (7, 2));
    assert_eq!(d.grids[2].points, r.result.header.points);
    let ratios: Vec<f64> = d.grids.iter().map(|g| g.ratio.unwrap()).collect();
    assert!(
        (ratios[0] - 0.5).abs() < 1e-12 && ratios[2] == 1.0,
        "{ratios:?}"
    );
    assert!((ratios[6] - 4.0).abs() < 1e-12, "{ratios:?}");
    let peak = &d.quantities.max_pressure;
    assert_eq!(peak.verdict.name(), "converging");
    assert_eq!(peak.value, r.result.max_pressure);
    // Within a factor 2 of the error against Hertz (1.4e-4 at 41 across).
    let truth = r
        .result
        .reference
        .as_ref()
        .unwrap()
        .errors
        .max_pressure
        .unwrap();
    let ratio = peak.relative_error.unwrap() / truth.abs();
    assert!((0.5..=2.0).contains(&ratio), "{ratio}");
    assert_eq!(d.quantities.tilt_x.verdict.name(), "exact");
    assert!(r.result.seconds.error_estimate > 0.0);
    // The approach, from h/2, h and 2h: within a factor 2 of its error
    // against Hertz (-7.1e-5).
    let approach = &d.quantities.approach;
    assert_eq!(approach.verdict.name(), "converging", "{approach:?}");
    let truth = r
        .result
        .reference
        .as_ref()
        .unwrap()
        .errors
        .approach
        .unwrap();
    let ratio = approach.relative_error.unwrap() / truth.abs();
    assert!((0.5..=2.0).contains(&ratio), "{ratio}");
    // The estimate's cost, in the block and among the run's seconds.
    assert_eq!(r.result.seconds.error_estimate, d.extra_seconds());
    assert_eq!(d.seconds, d.extra_seconds());
    let others: usize = (d.grids.iter().enumerate())
        .filter(|&(i, _)| i != d.own_grid)
        .map(|(_, g)| g.points)
        .sum();
    assert_eq!(d.points, others);
    let json = serde_json::to_value(&r.result).unwrap();
    assert_eq!(json["discretization"]["grids"][0]["ratio"], 0.5);
    assert_eq!(json["discretization"]["seconds"], d.seconds);

    let off = with_table(SPHERES, "solver", "error_estimate = false");
    let r = run(&scene(&off).unwrap()).unwrap();
    assert!(r.result.discretization.is_none());
    assert_eq!(r.result.seconds.error_estimate, 0.0);
}

/// An example scene, read from examples/scenes, run.
fn example(name: &str) -> elcon_report::Run {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenes")
        .join(name);
    let text = std::fs::read_to_string(&file).unwrap();
    run(&elcon_scene::Scene::from_str(&file, &text).unwrap()).unwrap()
}

#[test]
fn the_ball_bearing_s_peak_unresolved_by_coarser_grids_is_estimated_on_a_finer_one() {
    // ball-bearing.toml at 31 points across: its grids at 2h and 4h (16 and
    // 8.5 across) leave the peak's changes alternating, and so do the grids
    // between; the finer grid h/2 (61 across) and the one between it and h
    // resolve it, within a factor 2 of its error against Hertz's ellipse.
    let r = example("ball-bearing.toml");
    let d = r.result.discretization.as_ref().unwrap();
    assert_eq!(d.grids[d.own_grid].points, r.result.header.points);
    assert!((d.grids[0].ratio.unwrap() - 0.5).abs() < 1e-12, "{d:?}");
    let errors = &r.result.reference.as_ref().unwrap().errors;
    let peak = &d.quantities.max_pressure;
    assert_eq!(peak.verdict.name(), "converging", "{peak:?}");
    let ratio = peak.relative_error.unwrap() / errors.max_pressure.unwrap().abs();
    assert!((0.5..=2.0).contains(&ratio), "{ratio}");
    // Honest where it is not: the approach's staircase noise (its error
    // against Hertz changes sign from grid to grid) is not resolved, and
    // says why; so is the contact's extent.
    for q in [&d.quantities.approach, &d.quantities.contact_extent] {
        match q.verdict.name() {
            "not resolved" => assert!(q.reason.as_deref().unwrap().contains("changes")),
            verdict => panic!("{verdict}: {q:?}"),
        }
    }
    assert!(r.result.seconds.error_estimate > d.grids[d.own_grid].seconds);
}

#[test]
fn the_flat_punch_s_peak_and_extent_name_its_singular_rim() {
    // flat-punch.toml: the punch's face is the zone, pressed to its rim.
    let r = example("flat-punch.toml");
    let d = r.result.discretization.as_ref().unwrap();
    assert_eq!(d.limits.len(), 1, "{:?}", d.limits);
    assert!(d.limits[0].contains("bodies' own edge"), "{}", d.limits[0]);
    assert!(r.result.solution.warnings.contains(&d.limits[0]));
    for q in [&d.quantities.max_pressure, &d.quantities.contact_extent] {
        assert_eq!(q.verdict.name(), "not resolved", "{q:?}");
        let why = q.reason.as_deref().unwrap();
        assert!(why.starts_with(&d.limits[0]), "{why}");
        assert!(why.contains("the grids show changes"), "{why}");
    }
    assert_eq!(d.quantities.approach.verdict.name(), "exact");
}

#[test]
fn a_grid_too_coarse_for_coarser_ones_is_estimated_on_finer_ones() {
    // At 11 points across even the grid at 2h would not resolve the
    // contact: the grids are h/4, h/2 and the run's own h, last.
    let coarse = SPHERES.replace(EXAMPLE1_GRID, "across = 11\nzone = 1.15");
    let r = run(&scene(&coarse).unwrap()).unwrap();
    let d = r.result.discretization.as_ref().unwrap();
    assert_eq!(d.note, None);
    // With the grids between them where the fit is needed: the run's own
    // is the last either way.
    let own = d.grids.len() - 1;
    assert!(d.grids.len() == 3 || d.grids.len() == 5, "{d:?}");
    assert_eq!(d.own_grid, own);
    assert_eq!(d.grids[own].points, r.result.header.points);
    assert!(d.grids[0].points > 12 * d.grids[own].points);
    let peak = &d.quantities.max_pressure;
    assert_eq!(peak.value, r.result.max_pressure);
    assert_eq!(peak.values[own], peak.value);
    assert!(r.result.seconds.error_estimate > d.grids[own].seconds);
}

#[test]
fn a_finer_grid_over_its_allowance_is_not_solved_and_the_note_says_why() {
    // Example 1 on a disk of 2,463 points, 12.8 cells per contact radius:
    // the grid at 4h would not resolve the contact. Held dense and
    // unfolded for block pivoting, the grid at h/2 (four times the points)
    // would hold 16 times the run's solve, over 2 GiB: above the allowance
    // (the run's own, at least 256 MiB), so it is not solved.
    let coarse = SPHERES.replace(EXAMPLE1_GRID, "spacing = 0.00125\nradius = 0.035")
        + "[solver]\nmethod = \"block-pivoting\"\nsymmetry = \"none\"\n";
    let r = run(&scene(&coarse).unwrap()).unwrap();
    let d = r.result.discretization.as_ref().unwrap();
    let note = d.note.as_deref().unwrap();
    assert!(note.contains("MiB a finer grid may"), "{note}");
    assert_eq!(d.quantities.max_pressure.verdict.name(), "not estimated");
}

#[test]
fn eccentric_spheres_are_compared_with_hertz_translated_to_the_load_centre() {
    // The load 0.1 a off the apex: M_y = -P e, e = 0.0016 in (a = 0.016 in).
    let eccentric = SPHERES
        .replace(EXAMPLE1_GRID, "across = 41\nzone = 1.4")
        .replace("load = 100.0", "load = 100.0\nmoment_y = -0.16");
    let r = run(&scene(&eccentric).unwrap()).unwrap();
    let reference = r.result.reference.as_ref().unwrap();
    let centre = reference.load_centre.unwrap();
    assert!((centre.x - 0.0016).abs() < 1e-15 && centre.y == 0.0);
    let e = &reference.errors;
    // The aligned grid's errors at 41 across: approach -7.1e-5, peak
    // +1.4e-4, L2 1.0e-2 (docs/validation.md §1); the translated contact
    // sits on the same lattice, so about the same.
    assert!(e.approach.unwrap().abs() < 2e-4, "{e:?}");
    assert!(e.max_pressure.unwrap().abs() < 5e-4, "{e:?}");
    assert!(e.contact_extent.unwrap().abs() < 2e-3, "{e:?}");
    assert!(e.pressure_l2.unwrap() < 0.02, "{e:?}");
    // The tilt e / R = 0.0016 * 1.1, to the discretization.
    assert!(e.tilt_y.unwrap().abs() < 1e-4, "{e:?}");
    assert_eq!(e.tilt_x, None);
    // A moment under displacement control: the centre is not known before
    // the solve, so no errors, and a note.
    let by_approach = eccentric
        .replace(
            "across = 41\nzone = 1.4",
            "spacing = 0.0008\nradius = 0.0225",
        )
        .replace("load = 100.0", "approach = 2.8e-4");
    let r = run(&scene(&by_approach).unwrap()).unwrap();
    let reference = r.result.reference.as_ref().unwrap();
    assert!(reference.errors.approach.is_none() && reference.errors.load.is_none());
    assert!(
        reference
            .note
            .as_deref()
            .unwrap()
            .contains("displacement control")
    );
}

#[test]
fn a_kinked_profile_leaves_the_peak_not_resolved_and_a_cubic_one_does_not() {
    // The measured crown's profile, read linearly, kinks at every row: the
    // peak pressure is not a converged property of the scene, whatever its
    // three grids show, and the warning names the file; read as a cubic
    // spline it is estimated as any other quantity.
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenes/measured-crown.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    let linear = run(&elcon_scene::Scene::from_str(&file, &text).unwrap()).unwrap();
    let d = linear.result.discretization.as_ref().unwrap();
    let peak = &d.quantities.max_pressure;
    assert_eq!(peak.verdict.name(), "not resolved");
    let reason = peak.reason.as_deref().unwrap();
    assert!(
        reason.contains("measured-crown.csv") && reason.contains("linearly"),
        "{reason}"
    );
    // Its contact reaches the roller's ends, but its peak is not there:
    // the profile is the one limit.
    assert_eq!(d.limits.len(), 1, "{:?}", d.limits);
    assert!(linear.result.solution.warnings.contains(&d.limits[0]));
    let cubic_text = text.replace(
        "axis = \"y\" }",
        "axis = \"y\", interpolation = \"cubic\" }",
    );
    assert_ne!(cubic_text, text);
    let cubic = run(&elcon_scene::Scene::from_str(&file, &cubic_text).unwrap()).unwrap();
    let d = cubic.result.discretization.as_ref().unwrap();
    assert!(d.limits.is_empty());
    assert_ne!(d.quantities.max_pressure.reason.as_deref(), Some(reason));
}
