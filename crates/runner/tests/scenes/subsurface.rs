//! `[outputs] subsurface = true`: result.json's `subsurface` block (each
//! body's maxima against Hertz's, or why it has none), the section CSVs
//! and the plot; the keys' refusals.

use std::path::Path;

use crate::common::{BEAM, scene, spheres, with_table};
use elcon_report::write_run;
use elcon_runner::run;
use elcon_scene::{Scene, SceneError};

/// A directory of its own for `label` (the tests run in parallel).
fn scratch(label: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("elcon-subsurface-{}-{label}", std::process::id()))
}

#[test]
fn spheres_report_hertz_largest_shear_and_write_their_sections() {
    let text = with_table(
        &spheres("across = 41\nzone = 1.15"),
        "outputs",
        "subsurface = true\nplots = [\"subsurface\"]",
    );
    let scene = Scene::from_str(Path::new("spheres.toml"), &text).unwrap();
    let r = run(&scene).unwrap();
    let block = r.result.subsurface.as_ref().expect("the subsurface block");
    assert_eq!(block.stress_unit, "lbf/in^2");
    // Example 1's Hertz contact: steel on steel, R = 1 in against 10 in.
    let steel = elcon_influence::Material::new(30e6, 0.3).unwrap();
    let hertz = elcon_analysis::references::HertzSpheres::new(
        elcon_influence::combined_modulus(&steel, &steel),
        elcon_analysis::references::combined_radius(1.0, 10.0),
        100.0,
    )
    .unwrap();
    let (p0, a) = (hertz.peak_pressure(), hertz.contact_radius());
    for body in [&block.body1, &block.body2] {
        assert!(body.applicable && body.reason.is_none());
        let tresca = body.tresca.unwrap();
        // Johnson's 0.31 p0 at 0.48 a on the axis, within 1 % and 0.02 a.
        assert!(
            (tresca.value / p0 / 0.3100 - 1.0).abs() < 0.01,
            "{tresca:?}"
        );
        assert!(
            (tresca.depth / a - 0.48).abs() < 0.02 + 0.01 * 0.48,
            "{tresca:?}"
        );
    }
    let dir = scratch("spheres");
    let written = write_run(&r, &dir).unwrap();
    let csv = std::fs::read_to_string(written.join("subsurface_body1.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("x_in,y_in,depth_in,sigma_x_lbf/in^2"),
        "{header}"
    );
    assert!(
        header.ends_with("von_mises_lbf/in^2,tresca_lbf/in^2"),
        "{header}"
    );
    // The section's largest von Mises stress is the block's, to the
    // refinement between grid depths (the block's is refined).
    let largest = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(9).unwrap().parse::<f64>().unwrap())
        .fold(0.0f64, f64::max);
    let vm = block.body1.von_mises.unwrap().value;
    assert!(
        largest <= vm * (1.0 + 1e-12) && largest > 0.97 * vm,
        "{largest} {vm}"
    );
    let profile = std::fs::read_to_string(written.join("subsurface_profile_body2.csv")).unwrap();
    assert_eq!(profile.lines().count(), 1 + 24, "a row per default depth");
    let svg = std::fs::read_to_string(written.join("subsurface.svg")).unwrap();
    assert!(svg.contains("largest von Mises stress") && svg.contains("below the peak pressure"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_beam_on_a_foundation_says_why_it_has_no_stresses() {
    let text = with_table(BEAM, "outputs", "subsurface = true");
    let r = run(&scene(&text).unwrap()).unwrap();
    let block = r.result.subsurface.unwrap();
    for (body, what) in [(&block.body1, "beam"), (&block.body2, "Winkler")] {
        assert!(!body.applicable && body.von_mises.is_none());
        assert!(body.reason.as_ref().unwrap().contains(what), "{body:?}");
    }
}

#[test]
fn off_by_default_and_given_depths_are_used() {
    let plain = run(&scene(&spheres("across = 11\nzone = 1.2")).unwrap()).unwrap();
    assert!(plain.result.subsurface.is_none() && plain.subsurface.is_none());
    let text = with_table(
        &spheres("across = 11\nzone = 1.2"),
        "outputs",
        "subsurface = true\nsubsurface_depths = [0.002, 0.004, 0.008]",
    );
    let r = run(&scene(&text).unwrap()).unwrap();
    let fields = r.subsurface.unwrap();
    let elcon_analysis::subsurface::Subsurface::Stresses(b) = &fields[0] else {
        panic!("no field");
    };
    assert_eq!(b.profile.depths, vec![0.002, 0.004, 0.008]);
}

#[test]
fn bad_subsurface_keys_name_the_field_and_the_reason() {
    let base = spheres("across = 11\nzone = 1.2");
    for (lines, field, reason) in [
        (
            "subsurface_depths = [0.1]",
            "outputs.subsurface_depths",
            "needs outputs.subsurface = true",
        ),
        (
            "subsurface = true\nsubsurface_depths = [0.1, 0.1]",
            "outputs.subsurface_depths",
            "increasing",
        ),
        (
            "subsurface = true\nsubsurface_depths = [-0.1]",
            "outputs.subsurface_depths",
            "> 0",
        ),
        (
            "subsurface = true\nsubsurface_depths = [0.001, 1e4]",
            "outputs.subsurface_depths",
            "deeper than 10 times the candidate zone's size",
        ),
        (
            "subsurface = true\nsubsurface_depths = [1e300]",
            "outputs.subsurface_depths",
            "a point force's",
        ),
        (
            "subsurface = true\nsubsurface_depths = []",
            "outputs.subsurface_depths",
            "1 to 400",
        ),
        (
            "plots = [\"subsurface\"]",
            "outputs.plots",
            "needs outputs.subsurface = true",
        ),
    ] {
        let e = scene(&with_table(&base, "outputs", lines)).unwrap_err();
        let SceneError::Invalid {
            field: f,
            reason: r,
            ..
        } = &e
        else {
            panic!("{e}");
        };
        assert_eq!(f, field, "{e}");
        assert!(r.contains(reason), "{e}");
    }
}
