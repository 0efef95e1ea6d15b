//! A design's profile as the user is given it: profile.csv, read the
//! natural way (straight between its rows), holds the design on a grid
//! finer than the design's own, where its values at the design grid's
//! stations, read so, do not; `design.profile_spacing` sets its rows and
//! is refused, by name, where it is no spacing.

use std::path::{Path, PathBuf};

use crate::common::{roller, scene, with_table};
use elcon_analysis::{ContactProblem, Loading, Storage};
use elcon_design::{Analysis, Axis, Profile, axial_stations, evaluate};
use elcon_report::write_run;
use elcon_runner::run;
use elcon_scene::Scene;

/// A directory of its own for `label` (the tests run in parallel).
fn scratch(label: &str) -> PathBuf {
    std::env::temp_dir().join(format!("elcon-profile-{}-{label}", std::process::id()))
}

/// The misaligned roller of docs/design.md §6, smaller: the steel roller
/// (D = 10 mm, l = 10 mm) on 9 x 16 cells, its free crown designed for 5
/// and 10 kN each at 0 and 0.5 mrad, relative to each load's Hertz peak,
/// with the design keys `extra`.
fn misaligned_roller(extra: &str) -> String {
    with_table(
        &roller("zone = 1.6\nhalf_y = 5.0\nnx = 9\nny = 16", "10000.0"),
        "design",
        &format!(
            "family = \"free\"\nloads = [5000.0, 10000.0]\nmisalignments = [0.0, 5e-4]\n\
             relative_to = \"hertz\"\naxis = \"y\"\n{extra}"
        ),
    )
}

/// profile.csv's header and rows (position, drop).
fn read_csv(path: &Path) -> (String, Vec<(f64, f64)>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let rows = lines
        .map(|l| {
            let (s, y) = l.split_once(',').unwrap();
            (s.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    (header, rows)
}

/// The scene's design cases on its grid refined `fineness` times, S held
/// as elcon-analysis decides for the size (as the design stage builds its
/// finer grids).
fn cases_on(scene: &Scene, fineness: f64) -> Vec<ContactProblem> {
    let spec = scene.design().unwrap();
    spec.case_loadings()
        .into_iter()
        .map(|(load, misalignment)| {
            let points = scene.grid_for(load, fineness).unwrap().points().unwrap();
            let loading = Loading::load(load).with_tilt_x(misalignment.unwrap_or(0.0));
            let builder = scene.builder(points, loading).fold(false);
            builder.storage(Storage::Auto).build().unwrap()
        })
        .collect()
}

#[test]
fn the_misaligned_rollers_profile_csv_read_linearly_holds_on_a_grid_six_times_finer() {
    let scene = scene(&misaligned_roller("")).unwrap();
    let r = run(&scene).unwrap();
    let design = r.result.design.as_ref().unwrap();
    let written = write_run(&r, &scratch("roller")).unwrap();
    let (header, rows) = read_csv(&written.join("profile.csv"));
    assert_eq!(header, "# y_mm,drop_mm");
    // The file reads back, as written, as a scene's measured profile.
    let back = roller("zone = 1.6\nhalf_y = 5.0\nnx = 9\nny = 16", "10000.0").replace(
        "surface1 = { shape = \"cylinder\", radius = 5.0 }",
        &format!(
            "surface1 = {{ shape = \"cylinder\", radius = 5.0 }}\nprofile = {{ file = {:?}, axis = \"y\" }}",
            written.join("profile.csv").display().to_string()
        ),
    );
    assert!(back.contains("profile = "));
    let read = crate::common::scene(&back);
    assert!(read.is_ok(), "{:?}", read.err());
    // Ten rows to a station of the design's grid, over the roller's length.
    let own = design.grids.last().unwrap();
    let stations = (16.0 * own.fineness).round() as usize;
    assert_eq!(rows.len(), 10 * stations + 1);
    assert_eq!((rows[0].0, rows[rows.len() - 1].0), (-5.0, 5.0));
    let spacing = design.profile_spacing.unwrap();
    assert!((spacing - 10.0 / (10 * stations) as f64).abs() < 1e-15);
    // Read straight between its rows, on cells six times finer than the
    // design's: its worst p_max / p0 is the design's to the tolerance the
    // design held on its verification grid.
    let (positions, drops) = rows.into_iter().unzip();
    let linear = Profile::Free { positions, drops };
    let cases = cases_on(&scene, 6.0 * own.fineness);
    let analysis = Analysis::new(cases[0].default_method(), scene.options());
    let e = evaluate(&cases, Axis::Y, &linear, &analysis).unwrap();
    let references: Vec<f64> = design.cases.iter().map(|c| c.reference_intensity).collect();
    let worst = e.relative_worst(&references);
    let tolerance = design.grid_tolerance.unwrap();
    let agreement = worst / design.objective - 1.0;
    assert!(
        agreement.abs() <= tolerance,
        "profile.csv on {} points a case: {worst} against the design's {} ({agreement:+.2e}, \
         tolerance {tolerance})",
        cases[0].points().len(),
        design.objective
    );
    // The design's drops at its own grid's stations, read the same way,
    // do not hold it there (+3.5 %): a kink at every station.
    let design_run = r.design.as_ref().unwrap();
    let points = design_run.cases.iter().map(ContactProblem::points);
    let (stations, _) = axial_stations(points, Axis::Y);
    let (positions, drops) = design_run
        .profile
        .table(&stations)
        .unwrap()
        .into_iter()
        .unzip();
    let at_stations = Profile::Free { positions, drops };
    let e = evaluate(&cases, Axis::Y, &at_stations, &analysis).unwrap();
    let kinked = e.relative_worst(&references) / design.objective - 1.0;
    assert!(kinked > tolerance, "{kinked:+.2e}");
    std::fs::remove_dir_all(&written).ok();
}

#[test]
fn a_given_spacing_sets_the_rows_and_no_spacing_is_refused_by_name() {
    let text = misaligned_roller("profile_spacing = 0.5\nrefine = false");
    let r = run(&scene(&text).unwrap()).unwrap();
    let written = write_run(&r, &scratch("spacing")).unwrap();
    let (_, rows) = read_csv(&written.join("profile.csv"));
    let positions: Vec<f64> = rows.iter().map(|r| r.0).collect();
    let expected: Vec<f64> = (0..=20).map(|i| -5.0 + 0.5 * i as f64).collect();
    assert_eq!(positions, expected);
    // The rows are the profile's own values there.
    let profile = r.result.design.as_ref().unwrap().profile.profile().unwrap();
    for (s, y) in &rows {
        assert_eq!(profile.separation(*s).unwrap(), *y);
    }
    std::fs::remove_dir_all(&written).ok();
    for (value, reason) in [
        ("0.0", "must be > 0"),
        ("-1.0", "must be > 0"),
        ("nan", "must be a finite number"),
        ("inf", "must be a finite number"),
        ("1e-6", "too fine: more than 1,000,000 samples"),
    ] {
        let e = scene(&misaligned_roller(&format!("profile_spacing = {value}")))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`design.profile_spacing`") && e.contains(reason),
            "{value}: {e}"
        );
    }
}
