//! Surfaces and separations from files: a separation file equal to the
//! inline separations solves bit for bit the same problem, a profile file
//! adds its drops, and bad files are refused naming the file and the row.

use std::path::{Path, PathBuf};

use crate::common::roller;
use elcon_analysis::Interpolation;
use elcon_runner::run;
use elcon_scene::{Scene, SceneError};

/// A fresh directory for one test's files.
fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("elcon-surface-files-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A roller on an absolute 11 x 8 grid (0.8 mm by 10 mm, 1000 N: 3 points
/// across the Hertz width, the fewest the scene takes).
fn base() -> String {
    roller("half_x = 0.4\nhalf_y = 5.0\nnx = 11\nny = 8", "1000.0")
}

/// The scene `text` as the file `scene.toml` of `d`.
fn scene_in(d: &Path, text: &str) -> Result<Scene, SceneError> {
    Scene::from_str(&d.join("scene.toml"), text)
}

/// The reason of an invalid scene.
fn reason(r: Result<Scene, SceneError>) -> (String, String) {
    match r {
        Err(SceneError::Invalid { field, reason, .. }) => (field, reason),
        other => panic!("{other:?}"),
    }
}

/// Asserts that `r` is refused as invalid naming `field`, its reason
/// saying each of `parts`.
#[track_caller]
fn refused(r: Result<Scene, SceneError>, field: &str, parts: &[&str]) {
    let (named, why) = reason(r);
    assert_eq!(named, field, "{why}");
    for part in parts {
        assert!(why.contains(part), "{part}: {why}");
    }
}

/// The scene `text` in `d`, the file `name` written beside it first with
/// `contents`.
fn beside(
    d: &Path,
    name: &str,
    contents: impl AsRef<[u8]>,
    text: &str,
) -> Result<Scene, SceneError> {
    std::fs::write(d.join(name), contents).unwrap();
    scene_in(d, text)
}

/// [`base`]'s first surface, the cylinder.
const CYLINDER: &str = "surface1 = { shape = \"cylinder\", radius = 5.0 }";

/// [`base`] with the separations of the file `name` (beside the scene) in
/// place of its cylinder.
fn separated_by(name: &str) -> String {
    base().replace(CYLINDER, &format!("separation_file = \"{name}\""))
}

#[test]
fn a_separation_file_equal_to_the_inline_separations_is_bit_identical() {
    let d = dir("separation");
    let s = Scene::from_str(Path::new("test.toml"), &base()).unwrap();
    let eps = elcon_analysis::separations(s.points(), s.geometry()).unwrap();
    let points = s.points();
    let row = |k: usize, separation: f64| {
        format!("{:?},{:?},{:?}\n", points.x(k), points.y(k), separation)
    };
    // Shuffled rows (reversed) under a `#` header: matched by position.
    let mut csv = String::from("# x,y,separation\n");
    for k in (0..points.len()).rev() {
        csv += &row(k, eps[k]);
    }
    assert!(base().contains(CYLINDER));
    let inline: Vec<String> = eps.iter().map(|e| format!("{e:?}")).collect();
    let inline_text = base().replace(CYLINDER, &format!("separation = [{}]", inline.join(", ")));
    let a = run(&scene_in(&d, &inline_text).unwrap()).unwrap();
    let b = run(&beside(&d, "eps.csv", &csv, &separated_by("eps.csv")).unwrap()).unwrap();
    let (sa, sb) = (&a.result.solution, &b.result.solution);
    assert_eq!(sa.approach.to_bits(), sb.approach.to_bits());
    assert_eq!(a.solution.pressures, b.solution.pressures);
    assert_eq!(a.solution.forces, b.solution.forces);
    // A file that misses a point names it.
    let short: String = csv.lines().take(10).map(|l| format!("{l}\n")).collect();
    refused(
        beside(&d, "short.csv", short, &separated_by("short.csv")),
        "geometry.separation_file",
        &["short.csv", "candidate point 0"],
    );
    // Two rows for one point: the same separation twice is harmless,
    // another one is refused naming both lines and the point.
    let n = points.len();
    let again = format!("{csv}{}", row(0, eps[0]));
    beside(&d, "again.csv", again, &separated_by("again.csv")).unwrap();
    let twice = format!("{csv}{}", row(0, eps[0] + 1e-3));
    refused(
        beside(&d, "twice.csv", twice, &separated_by("twice.csv")),
        "geometry.separation_file",
        &[
            "twice.csv",
            &format!("lines {} and {} both give candidate point 0", n + 1, n + 2),
        ],
    );
}

#[test]
fn a_profile_file_adds_its_drops_to_the_cylinder() {
    let d = dir("profile");
    // A uniform drop of 1 um changes no pressure; it adds to the approach.
    let with = base().replace(
        CYLINDER,
        &format!("{CYLINDER}\nprofile = {{ file = \"crown.csv\", axis = \"y\" }}"),
    );
    let plain = run(&scene_in(&d, &base()).unwrap()).unwrap();
    let crown = "# y, drop\n-5.0, 0.001\n5.0, 0.001\n";
    let dropped = run(&beside(&d, "crown.csv", crown, &with).unwrap()).unwrap();
    let (p, q) = (&plain.result.solution, &dropped.result.solution);
    assert!((q.approach - p.approach - 0.001).abs() < 1e-12 * p.approach.abs().max(1.0));
    // A profile that stops short of the roller's ends is refused at check.
    let short = with.replace("crown.csv", "short.csv");
    refused(
        beside(&d, "short.csv", "-4.0, 0.0\n4.0, 0.0\n", &short),
        "geometry.profile.file",
        &["short.csv", "does not cover"],
    );
}

#[test]
fn a_batch_sweeps_over_files_read_beside_its_base_scene() {
    let d = dir("batch");
    std::fs::create_dir_all(d.join("data")).unwrap();
    std::fs::write(d.join("data/a.csv"), "-5.0, 0.0\n5.0, 0.0\n").unwrap();
    std::fs::write(d.join("data/b.csv"), "-5.0, 0.002\n5.0, 0.002\n").unwrap();
    let text = base().replace(
        CYLINDER,
        &format!("{CYLINDER}\nprofile = {{ file = \"data/a.csv\" }}"),
    );
    std::fs::write(d.join("roller.toml"), text).unwrap();
    std::fs::write(
        d.join("b.toml"),
        "[batch]\nscene = \"roller.toml\"\n[[batch.group]]\n\
         \"geometry.profile.file\" = [\"data/a.csv\", \"data/b.csv\"]\n",
    )
    .unwrap();
    let batch = elcon_scene::Batch::from_file(&d.join("b.toml")).unwrap();
    let approaches: Vec<f64> = batch
        .runs()
        .map(|r| {
            run(&batch.scene(&r).unwrap())
                .unwrap()
                .result
                .solution
                .approach
        })
        .collect();
    // The uniform drop of b.csv adds 0.002 to the approach.
    assert!(
        (approaches[1] - approaches[0] - 0.002).abs() < 1e-12,
        "{approaches:?}"
    );
}

#[test]
fn bad_files_are_refused_naming_the_file_and_the_row() {
    let d = dir("bad");
    let map = |file: &str| {
        base().replace(
            CYLINDER,
            &format!("{CYLINDER}\nheight_map = {{ file = \"{file}\", spacing = [0.5, 5.0] }}"),
        )
    };
    // The height map of the file `name`, written with `contents`.
    let mapped = |name: &str, contents: &str| beside(&d, name, contents, &map(name));
    let file = "geometry.height_map.file";
    // Missing.
    refused(
        scene_in(&d, &map("missing.csv")),
        file,
        &["missing.csv", "cannot be read"],
    );
    // A device that never ends: refused before it is opened.
    refused(
        scene_in(&d, &map("/dev/zero")),
        file,
        &["not a regular file"],
    );
    // A hole (NaN) at row 1, column 2.
    refused(
        mapped("hole.csv", "0,0,0\n0,0,nan\n0,0,0\n"),
        file,
        &["hole.csv", "row 1, column 2"],
    );
    // One row: the content is the file's fault.
    refused(mapped("row.csv", "0,0,0\n"), file, &[]);
    // A zero spacing is the spacing's fault, quoted as written.
    std::fs::write(d.join("ok.csv"), "0,0,0\n0,0,0\n0,0,0\n").unwrap();
    let zero = map("ok.csv").replace("spacing = [0.5, 5.0]", "spacing = [0.0, 5.0]");
    let e = scene_in(&d, &zero).unwrap_err().to_string();
    assert!(
        e.contains("`geometry.height_map.spacing` = [0.0, 5.0]: both spacings"),
        "{e}"
    );
    // A profile whose positions do not increase names its file.
    let profile = base().replace(
        CYLINDER,
        &format!("{CYLINDER}\nprofile = {{ file = \"down.csv\" }}"),
    );
    refused(
        beside(&d, "down.csv", "1,0\n0,0\n", &profile),
        "geometry.profile.file",
        &["positions must increase"],
    );
    // Ragged rows.
    refused(
        mapped("ragged.csv", "0,0,0\n0,0\n0,0,0\n"),
        file,
        &["ragged.csv", "line 2"],
    );
    // Text where numbers belong, after a `#` header line.
    refused(
        mapped("text.csv", "# a,b,c\n0,0,0\n0,x,0\n"),
        file,
        &["text.csv", "line 3", "\"0,x,0\""],
    );
    // A header not declared by `#` is a bad row, not a header.
    refused(
        mapped("undeclared.csv", "a,b,c\n0,0,0\n0,0,0\n"),
        file,
        &["line 1 is not numbers", "a header line starts with #"],
    );
    // A map that does not cover the grid: x in [-0.25, 0.25] against
    // cell centres out to 0.32.
    let small = map("small.csv").replace("spacing = [0.5, 5.0]", "spacing = [0.25, 5.0]");
    refused(
        beside(&d, "small.csv", "0,0,0\n0,0,0\n0,0,0\n", &small),
        file,
        &["small.csv", "does not cover"],
    );
    // Not a .npy file, and a 1-D .npy array.
    refused(
        mapped("fake.npy", "0,0\n"),
        file,
        &["fake.npy", "not a .npy"],
    );
    let line = npy(&[3], &[0.0, 0.0, 0.0]);
    refused(
        beside(&d, "line.npy", line, &map("line.npy")),
        file,
        &["1-D array"],
    );
}

#[test]
fn a_csv_is_read_exactly_its_first_row_never_taken_for_a_header() {
    let d = dir("exact-csv");
    let profile = |name: &str| {
        base().replace(
            CYLINDER,
            &format!("{CYLINDER}\nprofile = {{ file = \"{name}\" }}"),
        )
    };
    let crown = "-5.0, 0.002\n0.0, 0.0\n5.0, 0.002\n";
    let plain = beside(&d, "plain.csv", crown, &profile("plain.csv")).unwrap();
    let eps = |s: &Scene| elcon_analysis::separations(s.points(), s.geometry()).unwrap();
    // A byte-order mark, and a `#` header line, leave the rows as they are.
    let bom = [b"\xEF\xBB\xBF".as_slice(), crown.as_bytes()].concat();
    let marked = beside(&d, "bom.csv", bom, &profile("bom.csv")).unwrap();
    assert_eq!(eps(&marked), eps(&plain));
    let with_header = format!("# y, drop\n{crown}");
    let headed = beside(&d, "head.csv", with_header, &profile("head.csv")).unwrap();
    assert_eq!(eps(&headed), eps(&plain));
    // A typo in the first row is refused at its line, not taken as a header.
    refused(
        beside(
            &d,
            "typo.csv",
            "-5.0, O.12\n0.0, 0.0\n5.0, 0.002\n",
            &profile("typo.csv"),
        ),
        "geometry.profile.file",
        &["typo.csv", "line 1 is not numbers", "\"-5.0, O.12\""],
    );
    // A long bad line is quoted by its first 40 characters, no more.
    let secret = format!("{}SECRET", "x".repeat(40));
    let (_, why) = reason(beside(
        &d,
        "long.csv",
        format!("0.0, 0.0\n{secret}\n"),
        &profile("long.csv"),
    ));
    assert!(why.contains(&format!("line 2 is not numbers: \"{}\"...", "x".repeat(40))));
    assert!(!why.contains("SECRET"), "{why}");
    // UTF-16 is named as such.
    refused(
        beside(&d, "wide.csv", b"\xFF\xFE0\x00", &profile("wide.csv")),
        "geometry.profile.file",
        &["UTF-16"],
    );
}

#[test]
fn a_npy_height_map_is_read_as_numpy_writes_it() {
    let d = dir("npy");
    // A plane tilted along x, h = 0.001 x, on 3 x 3 nodes at spacing
    // 0.5 x 5 (centred by default): bilinear interpolation is exact on it,
    // so the separations are the cylinder's plus 0.001 x to rounding.
    let values: Vec<f64> = (0..3)
        .flat_map(|_| (0..3).map(|i| 0.001 * (i as f64 - 1.0) * 0.5))
        .collect();
    std::fs::write(d.join("tilt.npy"), npy(&[3, 3], &values)).unwrap();
    let text = base().replace(
        CYLINDER,
        &format!("{CYLINDER}\nheight_map = {{ file = \"tilt.npy\", spacing = [0.5, 5.0] }}"),
    );
    let s = scene_in(&d, &text).unwrap();
    let eps = elcon_analysis::separations(s.points(), s.geometry()).unwrap();
    for (k, e) in eps.iter().enumerate() {
        let x = s.points().x(k);
        assert!((e - (x * x / 10.0 + 0.001 * x)).abs() < 1e-15, "{k}: {e}");
    }
}

#[test]
fn a_npy_header_is_read_as_a_python_literal() {
    let d = dir("npy-header");
    // A plane tilted along x and y on 3 x 3 nodes, so that a transposed
    // map would give other separations.
    let z = |j: usize, i: usize| 0.001 * (i as f64 - 1.0) + 0.0001 * (j as f64 - 1.0);
    let c_order: Vec<f64> = (0..3).flat_map(|j| (0..3).map(move |i| z(j, i))).collect();
    let f_order: Vec<f64> = (0..3).flat_map(|i| (0..3).map(move |j| z(j, i))).collect();
    let map = |name: &str| {
        base().replace(
            CYLINDER,
            &format!("{CYLINDER}\nheight_map = {{ file = \"{name}\", spacing = [0.5, 5.0] }}"),
        )
    };
    let eps = |s: &Scene| elcon_analysis::separations(s.points(), s.geometry()).unwrap();
    let c = npy(&[3, 3], &c_order);
    let reference = eps(&beside(&d, "c.npy", c, &map("c.npy")).unwrap());
    for (n, header) in [
        "{'descr':'<f8','fortran_order':True,'shape':(3,3)}",
        "{'fortran_order': True, 'shape': (3, 3,), 'descr': '<f8',}",
        "{\"descr\": \"<f8\", \"fortran_order\": True, \"shape\": (3, 3)}",
    ]
    .iter()
    .enumerate()
    {
        let name = format!("f{n}.npy");
        let file = npy_raw(header, &f_order);
        let s = beside(&d, &name, file, &map(&name)).unwrap();
        assert_eq!(eps(&s), reference, "{header}");
    }
    // Big-endian values, as `>f8`.
    let big = npy_raw_with(
        "{'descr': '>f8', 'fortran_order': False, 'shape': (3, 3), }",
        &c_order,
        f64::to_be_bytes,
    );
    let s = beside(&d, "big.npy", big, &map("big.npy")).unwrap();
    assert_eq!(eps(&s), reference);
    let file = "geometry.height_map.file";
    // A shape whose product is not the data's length.
    let short = npy_raw(
        "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }",
        &c_order,
    );
    refused(
        beside(&d, "short.npy", short, &map("short.npy")),
        file,
        &["short.npy", "72 bytes", "(3, 4)", "needs 96"],
    );
    // A header numpy would not write, and a type elcon does not read.
    let broken = npy_raw("{'descr': '<f8', 'shape': (3, 3)}", &c_order);
    refused(
        beside(&d, "broken.npy", broken, &map("broken.npy")),
        file,
        &["no 'fortran_order'"],
    );
    let ints = npy_raw(
        "{'descr': '<i8', 'fortran_order': False, 'shape': (3, 3)}",
        &c_order,
    );
    refused(
        beside(&d, "ints.npy", ints, &map("ints.npy")),
        file,
        &["\"<i8\"", "not float64"],
    );
}

/// A version-1 `.npy` file of little-endian float64 values of `shape`.
fn npy(shape: &[usize], values: &[f64]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    npy_raw(
        &format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}"),
        values,
    )
}

/// A version-1 `.npy` file of the header dict `header` and little-endian
/// float64 `values`.
fn npy_raw(header: &str, values: &[f64]) -> Vec<u8> {
    npy_raw_with(header, values, f64::to_le_bytes)
}

/// A version-1 `.npy` file of the header dict `header` and `values`, each
/// written by `bytes`.
fn npy_raw_with(header: &str, values: &[f64], bytes: fn(f64) -> [u8; 8]) -> Vec<u8> {
    let mut header = header.to_string();
    while !(10 + header.len() + 1).is_multiple_of(64) {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header.as_bytes());
    for &v in values {
        out.extend(bytes(v));
    }
    out
}

#[test]
fn a_flat_punch_s_reference_takes_a_uniform_separation_as_an_offset() {
    let d = dir("punch");
    let punch = "[units]\nlength = \"m\"\nforce = \"N\"\npressure = \"Pa\"\n\n[body1]\nmodel = \
                 \"rigid\"\n\n[body2]\nmodel = \"uniform-patch\"\nyoungs_modulus = 70e9\n\
                 poissons_ratio = 0.33\n\n[geometry]\nGEOMETRY\n\n[points]\ngrid = \"disk\"\n\
                 spacing = 0.001\nradius = 0.01\n\n[loading]\napproach = 1e-5\n";
    let flat = punch.replace(
        "GEOMETRY",
        "surface1 = { shape = \"plane\" }\nsurface2 = { shape = \"plane\" }",
    );
    let plain = run(&scene_in(&d, &flat).unwrap()).unwrap();
    // The same punch 1e-5 into the other surface before any approach: it
    // carries the load of an approach of 2e-5, and the reference says so.
    let s = scene_in(&d, &flat).unwrap();
    let mut csv = String::new();
    for k in 0..s.points().len() {
        csv += &format!("{:?},{:?},-1e-5\n", s.points().x(k), s.points().y(k));
    }
    std::fs::write(d.join("offset.csv"), csv).unwrap();
    let offset = punch.replace("GEOMETRY", "separation_file = \"offset.csv\"");
    let r = run(&scene_in(&d, &offset).unwrap()).unwrap();
    let (a, b) = (
        plain.result.reference.as_ref().unwrap(),
        r.result.reference.as_ref().unwrap(),
    );
    assert_eq!(b.kind, "flat-punch");
    let ratio = b.load.unwrap() / a.load.unwrap();
    assert!((ratio - 2.0).abs() < 1e-12, "{ratio}");
    // The same relative error: the punch's answer is linear in the
    // indentation.
    let (ea, eb) = (a.errors.load.unwrap(), b.errors.load.unwrap());
    assert!((ea - eb).abs() < 1e-9 * (1.0 + ea.abs()), "{ea} {eb}");
    assert!(
        b.note.as_deref().unwrap().contains("uniform separation"),
        "{:?}",
        b.note
    );
    // At no approach the punch still presses 1e-5 in: its reference stays,
    // half the load of the approach of 1e-5 (the indentation 2e-5 before).
    let at_zero = offset.replace("approach = 1e-5", "approach = 0.0");
    let z = run(&scene_in(&d, &at_zero).unwrap()).unwrap();
    let c = z
        .result
        .reference
        .as_ref()
        .expect("a reference at no approach");
    let ratio = c.load.unwrap() / a.load.unwrap();
    assert!((ratio - 1.0).abs() < 1e-12, "{ratio}");
}

#[test]
fn a_table_s_interpolation_is_read_by_name_and_an_unknown_one_lists_the_names() {
    let d = dir("interpolation");
    std::fs::write(d.join("crown.csv"), "-5.0, 0.0\n0.0, 0.001\n5.0, 0.0\n").unwrap();
    std::fs::write(d.join("map.csv"), "0,0,0\n0,0,0\n0,0,0\n").unwrap();
    let with = |tables: &str| base().replace(CYLINDER, &format!("{CYLINDER}\n{tables}"));
    let profile = |extra: &str| format!("profile = {{ file = \"crown.csv\"{extra} }}");
    let map =
        |extra: &str| format!("height_map = {{ file = \"map.csv\", spacing = [0.5, 5.0]{extra} }}");
    let interpolations = |text: &str| -> Vec<Interpolation> {
        let s = scene_in(&d, text).unwrap();
        s.geometry()
            .departures()
            .iter()
            .map(|t| t.interpolation())
            .collect()
    };
    // Linear unless asked; each table its own.
    let both = format!("{}\n{}", map(""), profile(""));
    assert_eq!(interpolations(&with(&both)), [Interpolation::Linear; 2]);
    let both = format!(
        "{}\n{}",
        map(", interpolation = \"cubic\""),
        profile(", interpolation = \"linear\"")
    );
    assert_eq!(
        interpolations(&with(&both)),
        [Interpolation::Cubic, Interpolation::Linear]
    );
    let cubic = with(&profile(", axis = \"y\", interpolation = \"cubic\""));
    assert_eq!(interpolations(&cubic), [Interpolation::Cubic]);
    for (table, key) in [
        (profile(", interpolation = \"spline\""), "profile"),
        (map(", interpolation = \"spline\""), "height_map"),
    ] {
        let e = scene_in(&d, &with(&table)).unwrap_err().to_string();
        assert!(
            e.contains(&format!(
                "`geometry.{key}.interpolation`: unknown variant `spline`, expected `linear` or \
                 `cubic`"
            )),
            "{e}"
        );
    }
}

/// The peak pressure of `scene` on its layout's grid of `fineness` (h /
/// fineness), S held as elcon-analysis decides for its size.
fn peak_at(scene: &Scene, fineness: f64) -> f64 {
    let load = scene.loading().load_value().unwrap();
    let points = scene.grid_for(load, fineness).unwrap().points().unwrap();
    let problem = scene
        .builder(points, scene.loading())
        .storage(elcon_analysis::Storage::Auto)
        .build()
        .unwrap();
    let solution = problem
        .solve(problem.default_method(), scene.options())
        .unwrap();
    assert!(solution.certificate.holds());
    solution.max_pressure
}

#[test]
fn a_measured_crown_interpolated_cubically_has_a_peak_pressure_that_settles() {
    // examples/scenes/measured-crown.toml, its profile's rows 0.25 mm
    // apart, on its layout at 2, 4 and 8 times its points along each axis
    // (18 x 80 to 72 x 320 cells). Linearly the kinks at the rows put
    // logarithmic peaks under them, each finer grid higher; cubically the
    // peak's changes shrink.
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/measured-crown.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let linear_key = "axis = \"y\" }";
    assert!(text.contains(linear_key));
    let peaks = |interpolation: &str| -> Vec<f64> {
        let text = text.replace(
            linear_key,
            &format!("axis = \"y\", interpolation = \"{interpolation}\" }}"),
        );
        let scene = Scene::from_str(&path, &text).unwrap();
        [2.0, 4.0, 8.0].map(|f| peak_at(&scene, f)).to_vec()
    };
    let (linear, cubic) = (peaks("linear"), peaks("cubic"));
    let changes = |p: &[f64]| [(p[1] - p[0]).abs() / p[2], (p[2] - p[1]).abs() / p[2]];
    let (l, c) = (changes(&linear), changes(&cubic));
    assert!(c[1] < 0.7 * c[0] && c[1] < 0.005, "cubic {cubic:?}: {c:?}");
    assert!(l[1] > l[0] && l[1] > 0.03, "linear {linear:?}: {l:?}");
}
