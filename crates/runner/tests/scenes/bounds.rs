//! The bounds `check` and `run` share on what a solve can resolve: a load
//! or approach whose deformation is lost in the rounding of the
//! separations, a grid with one point across the contact, strain measured
//! along the zone's smaller extent, quadrics cancelling at an angle; and
//! the keys the parser's and the data files' messages name.

use std::path::{Path, PathBuf};

use crate::common;
use crate::common::scene;
use elcon_runner::run;
use elcon_scene::{MIN_POINTS_RESOLVED, Scene, SceneError};

/// An example scene's path.
fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenes")
        .join(name)
}

/// An example scene's text with `from` replaced by `to` (which must occur),
/// validated as if it were the example (its data files found beside it).
fn example_with(name: &str, from: &str, to: &str) -> Result<Scene, SceneError> {
    let path = example(name);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(from), "{name} has no {from:?}");
    Scene::from_str(&path, &text.replacen(from, to, 1))
}

/// The field an `Invalid` refusal names, and its message.
fn refused(r: Result<Scene, SceneError>) -> (String, String) {
    match r {
        Err(e @ SceneError::Invalid { .. }) => {
            let SceneError::Invalid { field, .. } = &e else {
                unreachable!()
            };
            (field.clone(), e.to_string())
        }
        Err(e) => panic!("not a refusal of a value: {e}"),
        Ok(_) => panic!("accepted"),
    }
}

/// The message of `r`, a refusal of a value naming `field` ([`refused`]),
/// which says each of `parts`.
#[track_caller]
fn refused_saying(r: Result<Scene, SceneError>, field: &str, parts: &[&str]) -> String {
    let (named, e) = refused(r);
    assert_eq!(named, field, "{e}");
    for part in parts {
        assert!(e.contains(part), "{part}: {e}");
    }
    e
}

/// The value a message names after the `nth` occurrence of `marker` (from
/// 1), up to `end`: the bound it hands back ("at most 44640,").
fn named<'a>(e: &'a str, marker: &str, nth: usize, end: char) -> &'a str {
    e.split(marker).nth(nth).unwrap().split(end).next().unwrap()
}

/// Example 1's spheres on a rigid plane on an absolute disk of radius
/// 0.02 in: the largest separation over it is 2e-4 in, and a load P
/// deforms the bodies by at most 1.5e-5 P in (P on one cell of 0.002 in
/// against E* = 3.3e7 psi).
fn spheres_on_disk(loading: &str) -> String {
    common::sphere_on_rigid_plane("spacing = 0.002\nradius = 0.02").replace("load = 100.0", loading)
}

/// Example 1 on its own Hertz grid (41 across, zone 1.15) with its line
/// `load = 100.0` replaced by `loading`.
fn example1_loaded(loading: &str) -> String {
    common::SPHERES.replace("load = 100.0", loading)
}

#[test]
fn every_example_scene_passes_the_bounds() {
    for entry in std::fs::read_dir(example("")).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        // Batches and bearing scenes have their own readers and bounds.
        let other = elcon_scene::is_batch_text(&text) || elcon_scene::is_bearing_text(&text);
        if path.extension().is_some_and(|e| e == "toml") && !other {
            Scene::from_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
}

#[test]
fn a_load_lost_in_the_rounding_of_the_separations_is_refused() {
    // 1e-8 lbf on one cell of 0.002 in deforms the bodies by at most
    // 1.5e-13 in, 7e-10 of the separations: refused, with the smallest
    // load resolved.
    refused_saying(
        scene(&spheres_on_disk("load = 1e-8")),
        "loading.load",
        &[
            "of the largest initial separation",
            "give a load of at least",
        ],
    );
    // Example 1's load is resolved.
    scene(&spheres_on_disk("load = 100.0")).unwrap();
    // An approach likewise.
    refused_saying(
        scene(&spheres_on_disk("approach = 1e-14")),
        "loading.approach",
        &[],
    );
    scene(&spheres_on_disk("approach = 1e-4")).unwrap();
}

#[test]
fn a_load_near_the_subnormal_numbers_never_reaches_a_solver() {
    // On a grid sized by its own Hertz contact the separations shrink with
    // the load: the force per point is what is bounded.
    let tiny = common::sphere_on_rigid_plane("across = 11\nzone = 1.3")
        .replace("load = 100.0", "load = 1e-297");
    refused_saying(scene(&tiny), "loading.load", &["per candidate point"]);
    // A beam on its foundation: no separations, the deformation is bounded.
    // (1e-286 lbf is 6e-288 a point, and compresses the foundation by
    // 1.25e-294 in.)
    let beam = include_str!("common/beam.toml").replace("load = 1000.0", "load = 1e-286");
    refused_saying(scene(&beam), "loading.load", &["subnormal"]);
}

#[test]
fn a_resolvability_refusal_names_the_input_out_of_scale_with_its_range() {
    // Example 2's foundation at 1e307 lbf/in per in: 50,000 lbf compresses
    // it by 4.5e-302 in, below the doubles' floor; the load is sensible
    // against the beam, the modulus is 1e300 times the beam's E.
    let foundation = |k: &str| example_with("example2-beam-design.toml", "modulus = 1e7", k);
    let e = refused_saying(
        foundation("modulus = 1e307"),
        "body2.modulus",
        &[
            "below 6.72e-139 in",
            "body2.modulus is the farthest out of scale",
        ],
    );
    // The range: the foundation's small strain (mean compression 0.1 of
    // the beam's 8.9 in) below, the solve's product above.
    assert!(e.contains("give a modulus from 6319 to 1.589e96"), "{e}");
    // The range is the analysis's: the scene without its design takes
    // both ends. A design also keeps the beam within 40 of its
    // characteristic lengths (4 E I / k)^(1/4), which the stiff end is
    // far past, and names the foundation's modulus for it.
    let analysis = |k: &str| {
        let path = example("example2-beam-design.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let text = text.replacen("modulus = 1e7", k, 1);
        let text = &text[..text.find("[design]").unwrap()];
        Scene::from_str(&path, text)
    };
    for k in ["modulus = 6320", "modulus = 1.589e96"] {
        analysis(k).unwrap_or_else(|e| panic!("{k}: {e}"));
    }
    foundation("modulus = 6320").unwrap_or_else(|e| panic!("{e}"));
    refused_saying(
        foundation("modulus = 1.589e96"),
        "body2.modulus",
        &["characteristic length"],
    );
    // A sphere of radius 1e301 on a rigid plane, on its Hertz grid: a cell
    // of 1e97 in, whose compliance times the squared residuals is 1e-312;
    // the radius, not the moduli, is out of scale.
    let huge = |r: &str| {
        common::sphere_on_rigid_plane("across = 11\nzone = 1.4")
            .replace("radius = 1.0 }", &format!("radius = {r} }}"))
    };
    let e = refused_saying(
        scene(&huge("1e301")),
        "geometry.surface1.radius",
        &["is about 1e-312"],
    );
    let most = e.split(" to ").last().unwrap().split(',').next().unwrap();
    scene(&huge(most)).unwrap();
    // An approach of 1e-305 m names the approach, not the modulus.
    let e = refused_saying(
        example_with("flat-punch.toml", "approach = ", "approach = 1e-305 # "),
        "loading.approach",
        &["give an approach of at least"],
    );
    // The least approach it names passes the solve's product bound too
    // (6.7e-139 m, the deformations' floor alone, did not).
    let least = named(&e, "at least ", 1, ',');
    example_with(
        "flat-punch.toml",
        "approach = ",
        &format!("approach = {least} # "),
    )
    .unwrap_or_else(|e| panic!("{least}: {e}"));
}

#[test]
fn a_modulus_range_of_two_elastic_bodies_holds_at_its_ends() {
    // Example 1's two steel spheres with moduli of 1e200 psi: the solve's
    // product underflows. Body 2's modulus enters through E*, `1 / E* =
    // (1 - nu^2) (1 / E1 + 1 / E2)`, not alone: the range it names (the
    // upper end half what scaling E* by E2 alone gave) passes at both
    // ends.
    let stiff = |e2: &str| {
        common::spheres("across = 41\nzone = 1.15")
            .replacen("youngs_modulus = 30e6", "youngs_modulus = 1e200", 1)
            .replacen(
                "youngs_modulus = 30e6",
                &format!("youngs_modulus = {e2}"),
                1,
            )
    };
    let (field, e) = refused(scene(&stiff("1e200")));
    assert!(field.ends_with(".youngs_modulus"), "{e}");
    let range = e.split("give a youngs_modulus from ").nth(1).unwrap();
    let (low, rest) = range.split_once(" to ").unwrap();
    let high = rest.split(',').next().unwrap();
    let other = if field == "body1.youngs_modulus" {
        "body2"
    } else {
        "body1"
    };
    assert!(other != field.split('.').next().unwrap());
    for end in [low, high] {
        let text = if field == "body2.youngs_modulus" {
            stiff(end)
        } else {
            stiff("1e200").replacen(
                "youngs_modulus = 1e200",
                &format!("youngs_modulus = {end}"),
                1,
            )
        };
        scene(&text).unwrap_or_else(|e| panic!("{end}: {e}"));
    }
    // Both at 1e300: no modulus of one body alone brings E* back.
    let (_, e) = refused(scene(&stiff("1e300").replacen(
        "youngs_modulus = 1e200",
        "youngs_modulus = 1e300",
        1,
    )));
    assert!(
        e.contains("no value of it alone brings the scene within range"),
        "{e}"
    );
}

#[test]
fn a_load_whose_residuals_square_below_the_normal_numbers_is_refused() {
    // Example 1 at 1e-250 lbf on its own Hertz grid: an approach of about
    // 1e-168 in, whose residuals' squares (1e-32 of its square) are
    // subnormal; the conjugate gradient ran out of iterations there.
    let tiny = common::sphere_on_rigid_plane("across = 41\nzone = 1.15")
        .replace("load = 100.0", "load = 1e-250");
    let e = refused_saying(
        scene(&tiny),
        "loading.load",
        &["below 6.72e-139", "subnormal"],
    );
    assert!(!e.contains("EPSILON") && !e.contains("MIN_"), "{e}");
    // The load the message names is accepted.
    let least = named(&e, "at least ", 1, ',');
    scene(&tiny.replace("load = 1e-250", &format!("load = {least}"))).unwrap();
}

#[test]
fn forces_and_deformations_whose_squares_overflow_are_refused() {
    // Moduli of 1e200 psi: 1e145 lbf is a small strain, but 6e141 lbf a
    // point, whose square overflows.
    let stiff = common::sphere_on_rigid_plane("across = 41\nzone = 1.15")
        .replace("youngs_modulus = 30e6", "youngs_modulus = 1e200")
        .replace("load = 100.0", "load = 1e145");
    refused_saying(
        scene(&stiff),
        "loading.load",
        &["above 1.49e138", "give a load of at most"],
    );
    // An approach of 1e140 in on a zone of 1e150 in.
    let wide = spheres_on_disk("approach = 1e140")
        .replace("spacing = 0.002", "spacing = 1e148")
        .replace("radius = 0.02", "radius = 1e150");
    refused_saying(scene(&wide), "loading.approach", &["above 1.49e138"]);
}

#[test]
fn a_load_whose_hertz_approach_strains_the_zone_is_refused_by_check() {
    // Example 1 on its own Hertz grid: the zone grows as P^(1/3), Hertz's
    // approach as P^(2/3); at 3e5 lbf it is 0.108 of the zone, and the run
    // would refuse the solved approach.
    let heavy = |load: &str| example1_loaded(&format!("load = {load}"));
    let e = refused_saying(
        scene(&heavy("3e5")),
        "loading.load",
        &[
            "Hertz's approach at this load",
            "beyond the small strain (at most 0.1)",
        ],
    );
    // The load the message names passes check and runs.
    let most = named(&e, "at most ", 2, ',');
    let s = scene(&heavy(most)).unwrap();
    run(&s).unwrap();
}

#[test]
fn a_tilt_that_moves_the_contact_off_the_zone_is_refused_by_check() {
    // R tilt = 0.09 in against a zone of 0.019 in.
    let tilted = |tilt: &str| example1_loaded(&format!("load = 100.0\ntilt_x = {tilt}"));
    refused_saying(
        scene(&tilted("0.1")),
        "loading.tilt_x",
        &["R tilt = 0.09091 in", "beyond the candidate zone's"],
    );
    // Near the zone's edge check tests the Hertz circle moved by R tilt
    // against the zone's boundary points as the run tests the solved
    // contact (its edge half a cell past a boundary point): 0.0024 and
    // 0.0025 were refused by the run after check passed them.
    let e = refused_saying(
        scene(&tilted("0.0024")),
        "loading.tilt_x",
        &["by half a cell or more"],
    );
    let most: f64 = named(&e, "at most ", 1, ' ').parse().unwrap();
    assert!(most > 0.0022 && most < 0.0024, "{most}");
    // The tilt it names runs, clear of the edge.
    run(&scene(&tilted(&format!("{most}"))).unwrap()).unwrap();
}

#[test]
fn a_moment_against_the_zone_s_edge_names_the_moment() {
    let s = scene(&example1_loaded("load = 100.0\nmoment_y = 0.8")).unwrap();
    let e = run(&s).unwrap_err().to_string();
    assert!(e.contains("`loading.moment_y` = 0.8: "), "{e}");
}

#[test]
fn a_logarithmic_crown_for_a_load_it_cannot_resolve_is_refused_by_check() {
    refused_saying(
        example_with(
            "crowned-roller.toml",
            "[design]\n",
            "[design]\ndesign_load = 1e-300\n",
        ),
        "design.design_load",
        &[],
    );
}

#[test]
fn a_grid_with_one_point_across_the_contact_is_refused() {
    refused_saying(
        example_with("flat-punch.toml", "spacing = 0.0005", "spacing = 1.0"),
        "points.spacing",
        &["at most 0.01", &format!("fewer than {MIN_POINTS_RESOLVED}")],
    );
    // Three points across (spacing = radius) pass, with a warning.
    let s = example_with("flat-punch.toml", "spacing = 0.0005", "spacing = 0.01").unwrap();
    assert!(!s.warnings().is_empty());
    // One cell across the roller's Hertz width (0.149 mm): nx names it.
    let roller = common::roller("half_x = 0.2\nhalf_y = 5.0\nnx = 1\nny = 8", "1000.0");
    refused_saying(scene(&roller), "points.nx", &["at least 6 cells"]);
}

#[test]
fn an_approach_is_bounded_by_the_zone_s_smaller_extent() {
    // 0.05 mm is 0.5 % of the roller's length but 12.5 % of the zone's
    // width (0.4 mm).
    let roller = common::roller("half_x = 0.2\nhalf_y = 5.0\nnx = 11\nny = 8", "1000.0")
        .replace("load = 1000.0", "approach = 0.05");
    refused_saying(scene(&roller), "loading.approach", &["smaller extent"]);
}

#[test]
fn a_solved_approach_beyond_the_small_strain_fails_the_run() {
    // The measured crown on a body of E = 0.21 MPa and a roller radius of
    // 5e6 mm: the mean pressure over the (wide) zone is small against E*,
    // but the roller sinks about half its length.
    let path = example("measured-crown.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replacen("youngs_modulus = 210e3", "youngs_modulus = 0.21", 1)
        .replace("radius = 5.0 }", "radius = 5e6 }");
    let s = Scene::from_str(&path, &text).unwrap();
    let e = run(&s).unwrap_err().to_string();
    assert!(e.contains("`loading.load` = 10000"), "{e}");
    assert!(e.contains("the solved approach"), "{e}");
    assert!(e.contains("smaller extent, 10 mm"), "{e}");
}

#[test]
fn quadrics_that_cancel_along_a_turned_direction_are_refused() {
    // Along 30 degrees the curvatures are 1 and -1; along x and y they do
    // not cancel (0.875 - 0.6875, 0.625 - 0.0625).
    let quadrics = |r: &str| {
        common::spheres("spacing = 0.002\nradius = 0.02").replace(
            "surface1 = { shape = \"sphere\", radius = 1.0 }\nsurface2 = { shape = \"sphere\", \
             radius = 10.0 }",
            &format!(
                "surface1 = {{ shape = \"quadric\", radius_x = 1.0, radius_y = 2.0, angle = 30.0 \
                 }}\nsurface2 = {{ shape = \"quadric\", radius_x = {r}, radius_y = 4.0, angle = \
                 30.0 }}"
            ),
        )
    };
    let text = quadrics("-1.0");
    assert!(text.contains("quadric"));
    refused_saying(
        scene(&text),
        "geometry.surface2.angle",
        &["principal direction at 30.00 degrees"],
    );
    // A convex second surface is a contact like any other.
    scene(&quadrics("1.0")).unwrap();
}

#[test]
fn parse_errors_name_the_key() {
    let base = common::sphere_on_rigid_plane("across = 11\nzone = 1.3");
    let e = scene(&base.replace("load = 100.0", "load = 100.0\nload = 200.0"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`loading.load`: duplicate key"), "{e}");
    let e = scene(&base.replace("across = 11", "across = 99999999999999999999999"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`points.across`"), "{e}");
    assert!(
        e.contains("the integer 99999999999999999999999 is out of range"),
        "{e}"
    );
    assert!(!e.contains("i128"), "{e}");
    let deep = format!("{}{}", "[".repeat(200), "]".repeat(200));
    let e = scene(&base.replace("zone = 1.3", &format!("zone = {deep}")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`points.zone`"), "{e}");
    assert!(e.contains("nested too deep"), "{e}");
}

#[test]
fn table_header_errors_name_the_table_and_say_how_to_write_it() {
    let base = common::sphere_on_rigid_plane("across = 11\nzone = 1.3");
    let refusal = |text: String| scene(&text).unwrap_err().to_string();
    let e = refusal(format!("{base}\n[loading]\nload = 200.0\n"));
    assert!(
        e.contains("`loading`: the table `[loading]` is given twice"),
        "{e}"
    );
    let e = refusal(base.replace("[body2]", "[[body2]]"));
    assert!(
        e.contains("`body2` must be a table `[body2]`, not an array of tables `[[body2]]`"),
        "{e}"
    );
    let e = refusal(base.replace("[points]", "[[points]]"));
    assert!(
        e.contains("`points` must be a table `[points]`, not an array of tables"),
        "{e}"
    );
    let e = refusal(format!("[scene]\n[scene.name]\nname = \"spheres\"\n{base}"));
    assert!(
        e.contains("`scene.name` must be a string (`name = ...` under its table), not a table `[scene.name]`"),
        "{e}"
    );
}

#[test]
fn a_data_file_s_errors_name_its_key() {
    // A profile's table read as a height map covers a sliver of the
    // candidate zone.
    refused_saying(
        example_with(
            "rough-sphere.toml",
            "file = \"data/rough-surface.npy\"",
            "file = \"data/measured-crown.csv\"",
        ),
        "geometry.height_map.file",
        &[],
    );
    // A file over the bound (sparse: it costs no disk), refused by its
    // size before it is read: the bound said as a user reads it.
    let big = std::env::temp_dir().join(format!("elcon-big-{}.csv", std::process::id()));
    std::fs::File::create(&big)
        .and_then(|f| f.set_len(257 << 20))
        .unwrap();
    let e = refused_saying(
        example_with(
            "measured-crown.toml",
            "file = \"data/measured-crown.csv\"",
            &format!("file = {:?}", big.display().to_string()),
        ),
        "geometry.profile.file",
        &["the largest data file elcon reads"],
    );
    let _ = std::fs::remove_file(&big);
    assert!(!e.contains("MAX_"), "{e}");
    // A device or a pipe is refused before it is opened: a pipe without a
    // writer would block the read, deaf to an interrupt.
    let fifo = std::env::temp_dir().join(format!("elcon-fifo-{}", std::process::id()));
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    let mut specials = vec!["/dev/zero".to_string()];
    if made.is_ok_and(|s| s.success()) {
        specials.push(fifo.display().to_string());
    }
    for special in specials {
        refused_saying(
            example_with(
                "measured-crown.toml",
                "file = \"data/measured-crown.csv\"",
                &format!("file = {special:?}"),
            ),
            "geometry.profile.file",
            &["is not a regular file"],
        );
    }
    let _ = std::fs::remove_file(&fifo);
}

#[test]
fn moduli_whose_influence_products_underflow_are_refused() {
    // Moduli of 1e200 psi at 100 lbf on the Hertz grid: one cell's
    // compliance 3e-133 in/lbf against residuals of 3e-131 in makes the
    // conjugate gradient's t.S t about 1e-393, and it broke down after one
    // iteration; 1e130 psi keeps it near 1e-253 and solves.
    let stiff = |e: &str| {
        common::sphere_on_rigid_plane("across = 11\nzone = 1.3")
            .replace("youngs_modulus = 30e6", &format!("youngs_modulus = {e}"))
    };
    refused_saying(
        scene(&stiff("1e200")),
        "body1.youngs_modulus",
        &["is about 1e-39", "check the units of the moduli"],
    );
    scene(&stiff("1e130")).unwrap();
}

/// An aluminium ball of radius 10 mm in a groove (a quadric of radii 20
/// and -10.4 mm) at `angle` degrees, on an ellipse grid, under `load` N.
fn ball_in_groove(angle: &str, load: &str) -> String {
    format!(
        "[units]\nlength = \"m\"\nforce = \"N\"\npressure = \"Pa\"\n\
         [body1]\nmodel = \"uniform-patch\"\nyoungs_modulus = 7e10\npoissons_ratio = 0.33\n\
         [body2]\nmodel = \"uniform-patch\"\nyoungs_modulus = 7e10\npoissons_ratio = 0.33\n\
         [geometry]\nsurface1 = {{ shape = \"sphere\", radius = 0.01 }}\n\
         surface2 = {{ shape = \"quadric\", radius_x = 0.02, radius_y = -0.0104, angle = {angle} }}\n\
         [points]\ngrid = \"ellipse\"\nacross = 21\nzone = 1.2\n\
         [loading]\nload = {load}\n"
    )
}

#[test]
fn hertz_s_approach_on_an_ellipse_grid_is_measured_across_the_ellipse_whatever_its_turn() {
    // At 1 MN Hertz's approach is 1.754 mm against the zone's 6.223 mm
    // across the ellipse's minor axis: refused turned or not (turned by 20
    // degrees, the grid's extents along x and y are larger, and were the
    // measure).
    let mut messages = Vec::new();
    for angle in ["0.0", "20.0", "-35.0"] {
        let (field, e) = refused(scene(&ball_in_groove(angle, "1e6")));
        assert_eq!(field, "loading.load", "{angle}: {e}");
        assert!(
            e.contains("is 0.2818 times the candidate zone's extent across the Hertz ellipse's minor axis, 0.006223 m"),
            "{angle}: {e}"
        );
        messages.push(e.split("`loading.load`").nth(1).unwrap().to_string());
    }
    assert!(messages.iter().all(|m| *m == messages[0]), "{messages:?}");
    // The load the message names passes check at either turn.
    let most = named(&messages[0], "at most ", 2, ',');
    assert_eq!(most, "44640");
    for angle in ["0.0", "20.0"] {
        scene(&ball_in_groove(angle, most)).unwrap();
    }
}

#[test]
fn a_tilt_that_moves_an_elliptical_contact_off_the_zone_is_refused_by_check() {
    // The ball-bearing example (its contact ellipse 1.311 x 0.1403 mm,
    // along y) tilted about x: the gap's minimum moves by tilt / k_yy =
    // 103.2 tilt mm along y, 1.032 mm at 0.01 rad against a zone reaching
    // 1.574 mm: the run found the contact against the zone's edge.
    let tilted = |tilt: &str| {
        example_with(
            "ball-bearing.toml",
            "load = 1000.0 ",
            &format!("load = 1000.0\ntilt_x = {tilt} "),
        )
    };
    refused_saying(
        tilted("0.01"),
        "loading.tilt_x",
        &[
            "K^-1 tilt = 1.032 mm to (x, y) = (0, -1.032)",
            "against the zone's edge",
            "at most 0.002964 rad",
        ],
    );
    // Within the bound the run keeps the contact clear of the edge, and
    // the bound itself (rounded down) runs.
    run(&tilted("0.0025").unwrap()).unwrap();
    run(&tilted("0.002964").unwrap()).unwrap();
}

#[test]
fn a_plane_strain_datum_that_strains_the_zone_is_refused_naming_it() {
    // Hertz's cylinders (0.5025 mm of zone) with body 2's datum at 1e301
    // mm: its compression, 1.379e-3 (ln(2 d0 / b) + 1/2) mm, is 0.96 mm,
    // and the run refused the solved approach naming the load.
    let datum = |d0: &str| {
        example_with(
            "hertz-cylinders.toml",
            "poissons_ratio = 0.3\nreference_distance = 10.0\n\n[geometry]",
            &format!("poissons_ratio = 0.3\nreference_distance = {d0}\n\n[geometry]"),
        )
    };
    let e = refused_saying(
        datum("1e301"),
        "body2.reference_distance",
        &[
            "is 0.967 mm",
            "this datum adds 0.9599 mm of it",
            "from 0.5025 (the grid's extent) to ",
        ],
    );
    // The largest datum the message names passes check and runs.
    let most = e.split(" to ").last().unwrap().split(' ').next().unwrap();
    run(&datum(most).unwrap()).unwrap();
    run(&datum("1e8").unwrap()).unwrap();
}
