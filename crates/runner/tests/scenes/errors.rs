//! One test per `SceneError` variant, through the library: the message a
//! user gets names the file, the line and column, and the field.

use std::path::Path;

use crate::common;
use crate::common::{scene, with_table};
use elcon_runner::run;
use elcon_scene::{Location, Scene, SceneError};

/// Example 1's first sphere on a rigid plane, 11 points across the Hertz
/// diameter on a disk of 1.3 Hertz radii.
fn base() -> String {
    common::sphere_on_rigid_plane("across = 11\nzone = 1.3")
}

/// A roller on an absolute 11 x 8 rectangle grid, 0.4 mm by 10 mm, under
/// 1000 N.
fn roller() -> String {
    // 5 points across the Hertz width (0.149 mm): a design needs them.
    common::roller("half_x = 0.2\nhalf_y = 5.0\nnx = 11\nny = 8", "1000.0")
}

#[test]
fn location_counts_lines_and_characters() {
    let text = "a = 1\nbé = 2\n";
    assert_eq!(Location::of(text, 0), Location { line: 1, column: 1 });
    assert_eq!(Location::of(text, 6), Location { line: 2, column: 1 });
    // 'é' is two bytes, one column.
    assert_eq!(Location::of(text, 9), Location { line: 2, column: 3 });
}

#[test]
fn io_names_the_file() {
    let e = Scene::from_file(Path::new("no/such/file.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }));
    assert!(e.to_string().starts_with("no/such/file.toml: "), "{e}");
    assert!(!e.is_input_error());
}

/// The message refusing the scene `text`.
#[track_caller]
fn refusal(text: &str) -> String {
    scene(text).unwrap_err().to_string()
}

/// The message refusing the scene `text` as a syntax error.
#[track_caller]
fn syntax_error(text: &str) -> String {
    let e = scene(text).unwrap_err();
    assert!(matches!(e, SceneError::Syntax { .. }), "{e}");
    assert!(e.is_input_error());
    e.to_string()
}

#[test]
fn syntax_names_line_column_and_key() {
    let base = base();
    let e = syntax_error(&base.replace("[body2]", "[body2]\ncolour = 1"));
    assert!(
        e.starts_with("test.toml:12:1: `body2.colour`: unknown field `colour`"),
        "{e}"
    );
    let e = scene(&base.replace("[loading]\nload = 100.0", "[loading]")).unwrap_err();
    assert!(e.to_string().contains("test.toml:"), "{e}");
    let e = scene(&base.replace("[units]\nlength = \"in\"\nforce = \"lbf\"\n", "")).unwrap_err();
    assert!(e.to_string().contains("missing field `units`"), "{e}");
    assert!(e.is_input_error());
    // A number written as a string names its field, in a section and in an
    // inline table.
    let e = syntax_error(&base.replace("load = 100.0", "load = \"100\""));
    assert!(
        e.ends_with("`loading.load`: invalid type: string \"100\", expected a number"),
        "{e}"
    );
    let e = refusal(&base.replace("across = 11", "across = \"11\""));
    assert!(e.contains("`points.across`"), "{e}");
    assert!(e.contains("expected a whole number"), "{e}");
    let e = refusal(&base.replace("radius = 1.0 }", "radius = \"1.0\" }"));
    assert!(e.contains("`geometry.surface1.radius`"), "{e}");
}

#[test]
fn invalid_names_the_field_and_the_reason() {
    let base = base();
    let e = scene(&base.replace("poissons_ratio = 0.3", "poissons_ratio = -1.0")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "test.toml:9:18: `body1.poissons_ratio` = -1: must be in (-1, 0.5): outside it the elastic energy is not positive definite"
    );
    for (from, to, says) in [
        (
            "model = \"rigid\"",
            "model = \"rigid\"\nmodulus = 3.0",
            "`body2.modulus` = 3: is not a parameter of the rigid model",
        ),
        (
            "across = 11",
            "across = 11\nnx = 4",
            "`points.nx`: is not a parameter of grid = \"disk\"",
        ),
        (
            "shape = \"sphere\", radius = 1.0",
            "shape = \"plane\"",
            "need curved surfaces (a sphere or a cylinder)",
        ),
    ] {
        let e = scene(&base.replace(from, to)).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
        assert!(e.is_input_error());
    }
}

#[test]
fn run_failures_name_the_scene() {
    let s = scene(&with_table(
        &base(),
        "solver",
        "method = \"lemke\"\nmax_pivots = 1",
    ))
    .unwrap();
    let e = run(&s).unwrap_err();
    assert!(matches!(e, elcon_runner::RunError::Run { .. }));
    assert!(
        e.to_string()
            .starts_with("scene `test`: the contact solve failed: pivot limit 1"),
        "{e}"
    );
    assert!(!e.is_input_error());
}

#[test]
fn moduli_near_the_top_of_the_doubles_are_refused_before_a_solve() {
    // At 1e200 psi the conjugate gradient broke down after one iteration
    // (its curvature t.S t underflows); check refuses the modulus (the
    // message's translation of a breakdown is tested in run.rs).
    let huge = base().replace("youngs_modulus = 30e6", "youngs_modulus = 1e200");
    let e = scene(&with_table(
        &huge,
        "solver",
        "method = \"conjugate-gradient\"",
    ))
    .unwrap_err();
    assert!(e.is_input_error(), "{e}");
    assert!(
        e.to_string().contains("`body1.youngs_modulus` = 1e200"),
        "{e}"
    );
}

#[test]
fn a_batch_name_cannot_leave_the_output_directory() {
    let dir = std::env::temp_dir().join(format!("elcon-batch-name-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("base.toml"), base()).unwrap();
    for bad in ["../escape", "", "/tmp/x", ".hidden.1.tmp"] {
        std::fs::write(
            dir.join("b.toml"),
            format!("[batch]\nname = \"{bad}\"\nscene = \"base.toml\"\n[[batch.group]]\n\"loading.load\" = [1.0]\n"),
        )
        .unwrap();
        let e = elcon_scene::Batch::from_file(&dir.join("b.toml")).unwrap_err();
        assert!(e.to_string().contains("`batch.name`"), "{bad}: {e}");
        assert!(e.to_string().contains("no path separators"), "{bad}: {e}");
    }
    // A scene's name likewise: a leading '.' is what elcon's own temporary
    // siblings look like.
    let e = refusal(&format!("[scene]\nname = \".a.1234.tmp\"\n{}", base()));
    assert!(e.contains("`scene.name`"), "{e}");
    assert!(e.contains("no leading '.'"), "{e}");
    // Too long for a directory with its lock, or with a control character.
    for bad in ["x".repeat(300), "a\\u0001b".to_string()] {
        let e = refusal(&format!("[scene]\nname = \"{bad}\"\n{}", base()));
        assert!(e.contains("`scene.name`"), "{e}");
        assert!(e.contains("at most 120 bytes"), "{e}");
    }
}

#[test]
fn a_batch_error_metric_is_one_of_the_results_columns() {
    let dir = std::env::temp_dir().join(format!("elcon-batch-error-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("base.toml"), base()).unwrap();
    let batch = |error: &str| {
        std::fs::write(
            dir.join("b.toml"),
            format!("[batch]\nscene = \"base.toml\"\nerror = \"{error}\"\n[[batch.group]]\n\"loading.load\" = [1.0]\n"),
        )
        .unwrap();
        elcon_scene::Batch::from_file(&dir.join("b.toml"))
    };
    let e = batch("peak").unwrap_err().to_string();
    assert!(e.contains("`batch.error`"), "{e}");
    assert!(e.contains("b.toml:3:9"), "{e}");
    assert!(e.contains("unknown variant `peak`"), "{e}");
    assert!(
        e.contains("`max_pressure`") && e.contains("`pressure_l2`"),
        "{e}"
    );
    let b = batch("contact_extent").unwrap();
    assert_eq!(b.error, elcon_scene::ErrorMetric::ContactExtent);
    assert_eq!(b.error.name(), "contact_extent");
}

#[test]
fn a_batch_whose_base_scene_is_missing_names_its_key_and_path() {
    let dir = std::env::temp_dir().join(format!("elcon-batch-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("b.toml"),
        "[batch]\nscene = \"absent.toml\"\n[[batch.group]]\n\"loading.load\" = [1.0]\n",
    )
    .unwrap();
    let e = elcon_scene::Batch::from_file(&dir.join("b.toml")).unwrap_err();
    assert!(e.is_input_error(), "{e}");
    let text = e.to_string();
    assert!(text.contains("b.toml:2:9"), "{text}");
    assert!(text.contains("`batch.scene` = \"absent.toml\""), "{text}");
    assert!(
        text.contains(&format!(
            "the base scene {} cannot be read",
            dir.join("absent.toml").display()
        )),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn relative_to_hertz_without_a_hertz_contact_is_refused_by_validation() {
    // Valid: spheres on a disk, a cylinder on a rectangle.
    scene(&with_table(
        &base(),
        "design",
        "family = \"quadratic\"\nrelative_to = \"hertz\"",
    ))
    .unwrap();
    scene(&with_table(
        &roller(),
        "design",
        "family = \"free\"\nrelative_to = \"hertz\"",
    ))
    .unwrap();
    // A sphere on a rectangle grid has no line contact to compare with:
    // `elcon check` says so, not only `elcon run`.
    let text = with_table(
        &roller().replace("shape = \"cylinder\"", "shape = \"sphere\""),
        "design",
        "family = \"free\"\nrelative_to = \"hertz\"",
    );
    let e = scene(&text).unwrap_err();
    assert!(matches!(e, SceneError::Invalid { .. }), "{e}");
    assert!(e.is_input_error());
    assert!(
        e.to_string()
            .contains("`design.relative_to` = \"hertz\": needs a Hertz contact at every design load (1000 has none)"),
        "{e}"
    );
    // The location is the value's.
    let line = text
        .lines()
        .position(|l| l.starts_with("relative_to"))
        .unwrap()
        + 1;
    assert!(
        e.to_string().starts_with(&format!("test.toml:{line}:15: ")),
        "{e}"
    );
    // A beam on a foundation has no Hertz contact at all.
    let beam = with_table(
        common::BEAM,
        "design",
        "family = \"quadratic\"\nrelative_to = \"hertz\"",
    );
    let e = refusal(&beam);
    assert!(e.contains("`design.relative_to`"), "{e}");
}

#[test]
fn a_logarithmic_crown_off_a_roller_is_refused_by_validation() {
    let roller = roller();
    let crown = "\n[design]\nfamily = \"logarithmic-crown\"\n";
    let s = scene(&format!("{roller}{crown}")).unwrap();
    assert!(matches!(
        s.design().unwrap().family(),
        elcon_scene::DesignFamily::LogarithmicCrown {
            end: elcon_design::LogEnd::JohnsGohar,
            ..
        }
    ));
    // Lundberg's end by name; another name, or an end for another family,
    // is refused naming the field.
    let s = scene(&format!("{roller}{crown}end = \"lundberg\"\n")).unwrap();
    assert!(matches!(
        s.design().unwrap().family(),
        elcon_scene::DesignFamily::LogarithmicCrown {
            end: elcon_design::LogEnd::Lundberg,
            ..
        }
    ));
    let e = refusal(&format!("{roller}{crown}end = \"hyperbolic\"\n"));
    assert!(
        e.contains(
            "`design.end`: unknown variant `hyperbolic`, expected `johns-gohar` or `lundberg`"
        ),
        "{e}"
    );
    let e = refusal(&format!(
        "{roller}\n[design]\nfamily = \"free\"\nend = \"lundberg\"\n"
    ));
    assert!(e.contains("`design.end`"), "{e}");
    let refused = |text: String| {
        let e = scene(&text).unwrap_err();
        assert!(matches!(e, SceneError::Invalid { .. }), "{e}");
        assert!(
            e.to_string().contains(
                "`design.family` = \"logarithmic-crown\": a logarithmic crown is for a roller"
            ),
            "{e}"
        );
    };
    // A sphere on the rectangle: no roller radius (it used to pass `check`
    // and fail in `run`).
    refused(format!(
        "{}{crown}",
        roller.replace("shape = \"cylinder\"", "shape = \"sphere\"")
    ));
    // Two planes.
    refused(format!(
        "{}{crown}",
        roller.replace("surface1 = { shape = \"cylinder\", radius = 5.0 }", "")
    ));
    // A cylinder on a disk grid: no roller length.
    refused(format!(
        "{}{crown}",
        roller.replace(
            "grid = \"rectangle\"\nhalf_x = 0.2\nhalf_y = 5.0\nnx = 11\nny = 8",
            "grid = \"disk\"\nspacing = 0.1\nradius = 0.5"
        )
    ));
}

#[test]
fn a_name_a_key_does_not_take_is_refused_with_the_names_it_takes() {
    let base = base();
    let cases = [
        (
            base.replace("model = \"rigid\"", "model = \"elastic\""),
            "12:9: `body2.model`: unknown variant `elastic`, expected one of `rigid`, `point-force`",
        ),
        (
            base.replace("shape = \"sphere\"", "shape = \"cube\""),
            "15:22: `geometry.surface1.shape`: unknown variant `cube`, expected one of `plane`",
        ),
        (
            base.replace("grid = \"disk\"", "grid = \"hexagon\""),
            "18:8: `points.grid`: unknown variant `hexagon`, expected one of `disk`, `rectangle`, `line`",
        ),
        (
            with_table(&base, "solver", "symmetry = \"mirror\""),
            "26:12: `solver.symmetry`: unknown variant `mirror`, expected `auto` or `none`",
        ),
        (
            with_table(&base, "design", "family = \"cubic\""),
            "26:10: `design.family`: unknown variant `cubic`, expected one of `quadratic`",
        ),
        (
            with_table(&base, "design", "family = \"quadratic\"\naxis = \"z\""),
            "27:8: `design.axis`: unknown variant `z`, expected `x` or `y`",
        ),
        (
            with_table(
                &base,
                "design",
                "family = \"quadratic\"\nrelative_to = \"peak\"",
            ),
            "27:15: `design.relative_to`: unknown variant `peak`, expected one of `absolute`",
        ),
        (
            with_table(&base, "outputs", "plots = [\"pressure\", \"contour\"]"),
            "26:22: `outputs.plots`: unknown variant `contour`, expected one of `pressure`, `design`, `subsurface`",
        ),
    ];
    for (text, message) in cases {
        let e = syntax_error(&text);
        assert!(
            e.starts_with(&format!("test.toml:{message}")),
            "{message}: {e}"
        );
    }
}

#[test]
fn rotations_outside_the_small_rotation_theory_are_refused() {
    // The sphere's Hertz radius is about 0.0131 in; the zone reaches 1.3 of
    // it, about 0.0171 in.
    let base = base();
    let loaded = |extra: &str| base.replace("load = 100.0", &format!("load = 100.0\n{extra}"));
    // A prescribed tilt is bounded as a design's misalignments are.
    let e = scene(&loaded("tilt_x = 1e300")).unwrap_err();
    assert!(matches!(e, SceneError::Invalid { .. }));
    assert!(
        e.to_string()
            .contains("`loading.tilt_x` = 1e300: at most 0.1 rad in size"),
        "{e}"
    );
    // Within it, a tilt that moves the contact (by R tilt, 0.09 in) off the
    // zone is refused by check (tests/bounds.rs); a small one passes.
    assert!(scene(&loaded("tilt_y = -0.1")).is_err());
    assert!(scene(&loaded("tilt_y = -0.001")).is_ok());
    // A load centre (M / P) outside the zone: no contact inside balances it.
    let e = refusal(&loaded("moment_x = 2.0"));
    assert!(
        e.contains(
            "`loading.moment_x` = 2: puts the load centre (the moment over the load) at (x, y) = \
             (0, 0.02), "
        ) && e.contains("outside the candidate zone (x from"),
        "{e}"
    );
    let e = refusal(&loaded("moment_y = 2.0"));
    assert!(e.contains("at (x, y) = (-0.02, 0)"), "{e}");
    // Inside the zone's extent along x and along y, outside the disk: the
    // zone is its points' convex hull (the engine had answered "ray
    // termination ... unbounded" or a failed certificate).
    let e = scene(&loaded("moment_x = 1.3\nmoment_y = -1.3")).unwrap_err();
    assert!(matches!(e, SceneError::Invalid { .. }));
    assert!(
        e.to_string().contains(
            "`loading.moment_x` = 1.3: with `loading.moment_y` = -1.3, puts the load centre \
             (the moment over the load) at (x, y) = (0.013, 0.013), "
        ),
        "{e}"
    );
    // Inside the zone but near its edge: the solved contact leans on the
    // zone's edge (or turns past 0.1 rad), and the answer is refused.
    for moment in ["1.0", "1.5"] {
        let s = scene(&loaded(&format!("moment_x = {moment}"))).unwrap();
        let e = run(&s).unwrap_err();
        assert!(matches!(e, elcon_runner::RunError::Run { .. }));
        let text = e.to_string();
        assert!(
            (text.contains("against the candidate zone's edge")
                || text.contains("beyond the small-rotation theory's 0.1 rad"))
                && text.contains("give a smaller moment, or a larger zone"),
            "{moment}: {e}"
        );
    }
    // A small moment, its contact well inside the zone, runs.
    let s = scene(&loaded("moment_x = 0.1")).unwrap();
    let r = run(&s).unwrap();
    assert!(r.solution.tilt_x.abs() < 0.1);
}

/// The longest run of digits in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn a_huge_value_is_shown_in_its_shortest_form() {
    let roller = roller();
    let line = "grid = \"line\"\nstart = 1e300\nend = 0.0\nn = 11";
    let cases = [
        (
            roller.replace(
                "grid = \"rectangle\"\nhalf_x = 0.2\nhalf_y = 5.0\nnx = 11\nny = 8",
                line,
            ),
            "`points.end` = 0: must exceed points.start = 1e300",
        ),
        (
            format!(
                "{roller}\n[design]\nfamily = \"circular-crown\"\nradius_range = [1.0, 2.0]\n\
                 flat_length = -1e300\n"
            ),
            "`design.flat_length` = -1e300: must be >= 0",
        ),
        (
            format!(
                "{roller}\n[design]\nfamily = \"circular-crown\"\nradius_range = [1e300, 1e299]\n"
            ),
            "`design.radius_range[1]` = 1e299: must exceed",
        ),
        (
            format!("{roller}\n[design]\nfamily = \"quadratic\"\ngrid_tolerance = 1e300\n"),
            "`design.grid_tolerance` = 1e300: at most 0.5",
        ),
        (
            format!("{roller}\n[design]\nfamily = \"quadratic\"\nmisalignments = [-1e300]\n"),
            "`design.misalignments[0]` = -1e300: at most",
        ),
    ];
    for (text, expected) in cases {
        let e = scene(&text).unwrap_err();
        let message = e.to_string();
        assert!(message.contains(expected), "{message}");
        assert!(longest_digit_run(&message) <= 20, "{message}");
    }
}

#[test]
fn a_design_failure_names_the_scenes_key() {
    let roller = roller();
    let design = |lines: &str| format!("{roller}\n[design]\n{lines}\n");
    // A design load whose Hertz half-width exceeds the crowned half-length
    // over 0.3033: the logarithmic profile is undefined, which check says
    // at the key, as the design stage would.
    let checked = refusal(&design("family = \"logarithmic-crown\"\ndesign_load = 1e9"));
    // A crown radius below the crowned half-length (5 mm): the design
    // stage's failure.
    let s = scene(&design(
        "family = \"circular-crown\"\nradius_range = [1.0, 2.0]",
    ))
    .unwrap();
    let ran = run(&s).unwrap_err().to_string();
    // Each starts with the scene's key, and never says elcon-design's own
    // name for the parameter.
    for (e, start, own_name) in [
        (
            checked,
            "test.toml:32:15: `design.design_load` = 1000000000: the Hertz half-width",
            "log_crown",
        ),
        (
            ran,
            "scene `test`: `design.radius_range` (a crown radius searched in it) = ",
            "circular_crown",
        ),
    ] {
        assert!(e.starts_with(start), "{e}");
        assert!(!e.contains(own_name), "{e}");
    }
}

#[test]
fn a_certificate_tolerance_below_rounding_is_refused() {
    let e = scene(&with_table(
        &base(),
        "solver",
        "certificate_tolerance = 1e-300",
    ))
    .unwrap_err();
    assert!(e.is_input_error());
    let text = e.to_string();
    assert!(
        text.contains("`solver.certificate_tolerance` = 1e-300"),
        "{text}"
    );
    assert!(text.contains("at least 2.2e-16"), "{text}");
    // The bound itself is accepted.
    scene(&with_table(
        &base(),
        "solver",
        "certificate_tolerance = 2.3e-16",
    ))
    .unwrap();
}

#[test]
fn a_radius_too_small_for_its_curvature_is_refused_as_such() {
    let base = base();
    assert!(base.contains("radius = 1.0 }"));
    for (written, key) in [
        ("radius = 5e-324 }", "`geometry.surface1.radius`"),
        ("radius = -5e-324 }", "`geometry.surface1.radius`"),
    ] {
        let e = refusal(&base.replacen("radius = 1.0 }", written, 1));
        assert!(e.contains(key), "{e}");
        assert!(e.contains("is too small: its curvature 1 / radius"), "{e}");
        assert!(!e.contains("NaN") && !e.contains("negative"), "{e}");
    }
    // A quadric's radius alike.
    let quadric = base.replacen(
        "shape = \"sphere\", radius = 1.0 }",
        "shape = \"quadric\", radius_x = 1.0, radius_y = 5e-324 }",
        1,
    );
    assert!(quadric.contains("5e-324"));
    let e = refusal(&quadric);
    assert!(e.contains("`geometry.surface1.radius_y`"), "{e}");
    assert!(e.contains("is too small"), "{e}");
}

#[test]
fn a_grid_beyond_the_largest_names_the_count_not_a_constant() {
    let e = refusal(&common::roller(
        "half_x = 0.2\nhalf_y = 5.0\nnx = 3000\nny = 3000",
        "1000.0",
    ));
    assert!(e.contains("9000000"), "{e}");
    assert!(e.contains("more than 4194304 points"), "{e}");
    assert!(!e.contains("MAX_POINTS"), "{e}");
    let e = refusal(&base().replace("across = 11\nzone = 1.3", "across = 20001\nzone = 1.3"));
    assert!(!e.contains("MAX_POINTS"), "{e}");
}

#[test]
fn a_batch_key_with_an_empty_name_says_so() {
    let dir = std::env::temp_dir().join(format!("elcon-batch-dots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("base.toml"), base()).unwrap();
    for key in ["points..across", ".points.across", "points.across."] {
        std::fs::write(
            dir.join("b.toml"),
            format!("[batch]\nscene = \"base.toml\"\n[[batch.group]]\n\"{key}\" = [11]\n"),
        )
        .unwrap();
        let e = elcon_scene::Batch::from_file(&dir.join("b.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(&format!("\"{key}\"")), "{e}");
        assert!(e.contains("has an empty name"), "{e}");
        assert!(!e.contains("unknown field ``"), "{e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Notices a batch gives, collected.
#[derive(Default)]
struct Notices(std::sync::Mutex<Vec<String>>);

impl elcon_runner::Progress for Notices {
    fn notice(&self, message: &str) {
        self.0.lock().unwrap().push(message.to_string());
    }
}

#[test]
fn a_batch_directory_with_an_empty_or_foreign_journal_says_which() {
    let dir = std::env::temp_dir().join(format!("elcon-batch-journal-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("base.toml"), base()).unwrap();
    std::fs::write(
        dir.join("b.toml"),
        "[batch]\nname = \"j\"\nscene = \"base.toml\"\n[[batch.group]]\n\"loading.load\" = [100.0]\n",
    )
    .unwrap();
    let batch = elcon_scene::Batch::from_file(&dir.join("b.toml")).unwrap();
    let out = dir.join("out");
    // Cancelled from the start: the journal is opened, no run is made.
    let cancel = elcon_lcp::Cancel::new();
    cancel.cancel();
    let options = elcon_runner::BatchOptions {
        jobs: Some(1),
        shard: None,
        ceiling: elcon_process::Ceiling::unlimited(),
        cancel,
    };
    let notice = |journal: &str| {
        std::fs::create_dir_all(out.join("j")).unwrap();
        std::fs::write(out.join("j/journal.jsonl"), journal).unwrap();
        let notices = Notices::default();
        elcon_runner::run_batch(&batch, &out, &options, &notices).unwrap();
        notices.0.into_inner().unwrap().join("\n")
    };
    for (journal, says) in [
        ("", "an empty journal"),
        ("\n", "an empty journal"),
        ("{\"journal\": 1, \"bat", "not a batch's header"),
        (
            "{\"journal\":1,\"batch\":\"other\",\"batch_hash\":\"0\",\"shard\":null,\"runs\":1}\n",
            "the journal of another batch (\"other\")",
        ),
        (
            "{\"journal\":1,\"batch\":\"j\",\"batch_hash\":\"0\",\"shard\":null,\"runs\":1}\n",
            "another version of the batch",
        ),
    ] {
        let said = notice(journal);
        assert!(said.contains(says), "{journal:?}: {said}");
        assert!(said.contains(": replaced"), "{said}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_punch_lifted_off_by_a_moment_is_not_compared_with_the_central_punch() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/flat-punch.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("approach = 1e-5") && text.contains("spacing = 0.0005"));
    // 10 cells per punch radius; about 15 kN presses the punch 1e-5 m.
    let with = |moment: &str| {
        let t = text
            .replacen("spacing = 0.0005", "spacing = 0.001", 1)
            .replacen("approach = 1e-5", &format!("load = 15000.0\n{moment}"), 1);
        run(&Scene::from_str(&path, &t).unwrap()).unwrap()
    };
    // A small moment tilts the punch with its whole face in contact: the
    // approach at the centre is the central punch's.
    let r = with("moment_x = 20.0");
    let reference = r.result.reference.unwrap();
    assert!(
        reference.errors.approach.unwrap().abs() < 0.05,
        "{reference:?}"
    );
    assert!(
        reference
            .note
            .unwrap()
            .contains("whole face stays in contact")
    );
    // A large one lifts an edge off: no error against the central punch.
    let r = with("moment_x = 140.0");
    let reference = r.result.reference.unwrap();
    assert_eq!(reference.errors.approach, None, "{reference:?}");
    let note = reference.note.unwrap();
    assert!(note.contains("lifts the punch off at"), "{note}");
    assert!(note.contains("not compared"), "{note}");
}
