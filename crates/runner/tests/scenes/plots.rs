//! The pressure plot: a map with the contact's boundary and a colour bar for
//! a surface whose pressure is not a function of the radius, pressure
//! against the radius with the closed form for one that is. Maps (and the
//! subsurface section) at equal scales or a stated stretch, their colour
//! bars labelled, their numbers written as people write them.

use std::path::Path;

use crate::common;
use crate::common::with_table;
use elcon_runner::run;
use elcon_scene::{Plot, Scene};

/// A roller (cylinder on a plane) on a 9 x 12 rectangle: not axisymmetric.
fn roller() -> String {
    let roller = common::roller("zone = 1.6\nhalf_y = 5.0\nnx = 9\nny = 12", "5000.0");
    with_table(&roller, "outputs", "plots = [\"pressure\"]")
}

/// Example 1's spheres, 11 across: axisymmetric.
fn spheres() -> String {
    let spheres = common::spheres("across = 11\nzone = 1.2");
    with_table(&spheres, "outputs", "plots = [\"pressure\"]")
}

fn pressure_svg(text: &str) -> (String, usize, usize) {
    let (r, svg) = plotted(text, Plot::Pressure);
    (svg, r.problem.points().len(), r.solution.contact.len())
}

/// The run of the scene `text` and its plot `plot`'s SVG.
fn plotted(text: &str, plot: Plot) -> (elcon_report::Run, String) {
    let scene = Scene::from_str(Path::new("plot.toml"), text).unwrap();
    assert!(scene.outputs().plots().contains(&plot));
    let r = run(&scene).unwrap();
    // Each call its own directory: the tests run in parallel, and their
    // scenes share a name.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "elcon-plots-{}-{call}-{}",
        std::process::id(),
        scene.name()
    ));
    let written = elcon_report::write_run(&r, &dir).unwrap();
    let file = match plot {
        Plot::Pressure => "pressure.svg",
        Plot::Design => "design.svg",
        Plot::Subsurface => "subsurface.svg",
    };
    let svg = std::fs::read_to_string(written.join(file)).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (r, svg)
}

/// The size in pixels of each map's plotting area in `svg`: the frames
/// drawn round them (unfilled, stroked #404040).
fn frames(svg: &str) -> Vec<(f64, f64)> {
    let attribute = |tag: &str, name: &str| -> f64 {
        let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[at..].split('"').next().unwrap().parse().unwrap()
    };
    svg.split("<rect")
        .skip(1)
        .map(|r| &r[..r.find("/>").unwrap()])
        .filter(|r| r.contains(r##"fill="none" stroke="#404040""##))
        .map(|r| (attribute(r, "width"), attribute(r, "height")))
        .collect()
}

/// The stretch an axis named `name` states in `svg` (`x (mm, ×3)`), 1
/// without one.
fn stretch(svg: &str, name: &str, unit: &str) -> f64 {
    let stated = format!("{name} ({unit}, ×");
    let all = texts(svg);
    match all.iter().find_map(|t| t.strip_prefix(&stated)) {
        Some(k) => k.trim_end_matches(')').parse().unwrap(),
        None => {
            let plain = format!("{name} ({unit})");
            assert!(all.contains(&plain.as_str()), "{name}'s axis");
            1.0
        }
    }
}

/// Asserts that a map's plotting area of `size` pixels draws data of
/// `spans` at the scales its axes state (within a pixel), and no more
/// slender than 4:1.
fn assert_scaled(size: (f64, f64), spans: (f64, f64), stretch: (f64, f64)) {
    let drawn = size.0 / size.1;
    let data = spans.0 * stretch.0 / (spans.1 * stretch.1);
    assert!(
        (drawn - data).abs() <= data * (1.0 / size.0 + 1.0 / size.1) * 1.01,
        "{size:?} pixels for {spans:?}, stretched {stretch:?}"
    );
    assert!(drawn.max(1.0 / drawn) <= 4.0 + 1e-9, "{size:?}");
}

/// The texts of `svg` (its `<text>` elements' contents).
fn texts(svg: &str) -> Vec<&str> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            t.split_once('>')
                .map(|(_, rest)| rest.split('<').next().unwrap().trim())
        })
        .collect()
}

/// Asserts that no text of `svg` holds a number in plotters' or Rust's
/// scientific form for everyday magnitudes (`0.0000e0`, `1.4874e3`) or
/// float noise (`0.30000000000000004`).
fn assert_numbers_read_plainly(svg: &str) {
    for t in texts(svg) {
        let numbers = t
            .split(|c: char| c.is_whitespace() || c == ',' || c == '(' || c == ')')
            .filter(|w| w.parse::<f64>().is_ok());
        for n in numbers {
            let exponent = n.split_once('e').map(|(_, e)| e.parse::<i32>().unwrap());
            assert!(
                !exponent.is_some_and(|e| (-4..5).contains(&e)),
                "{n} in {t:?}: everyday magnitudes are written out"
            );
            let decimals = n.split(['.', 'e']).nth(1).map_or(0, str::len);
            assert!(decimals <= 5 && n != "-0", "{n} in {t:?}");
        }
    }
}

/// The extents (x, y) of a run's cells: where its map draws.
fn cell_spans(r: &elcon_report::Run) -> (f64, f64) {
    let points = r.problem.points();
    let cell = points.cell();
    let span = |v: &[f64], width: f64| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(*x), b.max(*x))
            });
        hi - lo + width
    };
    (span(&points.xs(), cell.dx), span(&points.ys(), cell.dy))
}

#[test]
fn a_roller_gets_a_pressure_map_with_its_boundary_and_a_colour_bar() {
    let (svg, points, contact) = pressure_svg(&roller());
    assert!(svg.contains("pressure map"), "the map's caption");
    assert!(svg.contains("contact boundary"), "the boundary's legend");
    assert!(svg.contains("pressure (MPa)"), "the colour bar's label");
    assert!(svg.contains("along x, at y =") && svg.contains("along y, at x ="));
    // One rectangle per cell (a grid this small is drawn cell by cell) and
    // a hundred for the colour bar, besides the frames.
    let rects = svg.matches("<rect").count();
    assert!(
        rects >= points + 100,
        "{rects} rectangles for {points} cells"
    );
    // The boundary: black faces of width 2, at least four (a closed outline)
    // and at most four per cell in contact.
    let faces = svg
        .matches(r##"stroke="#000000" stroke-width="2""##)
        .count();
    assert!(
        faces >= 4 && faces <= 4 * contact + 1,
        "{faces} faces, {contact} cells in contact"
    );
}

#[test]
fn axisymmetric_spheres_keep_pressure_against_the_radius() {
    let (svg, ..) = pressure_svg(&spheres());
    assert!(!svg.contains("pressure map"));
    assert!(svg.contains("radius (in)"));
    assert!(svg.contains("hertz-spheres"), "the closed form's legend");
}

/// A misaligned roller of 10,400 points, more than 512 cells along x
/// (MAX_DRAWN = 256): its map is drawn in 174 x 7 blocks of 3 x 3 cells,
/// each its largest pressure. Any grid is drawn in at most 256 x 256 blocks, about
/// 90 bytes each: under 6 MB.
#[test]
fn a_large_grid_s_map_is_drawn_in_blocks_of_bounded_size() {
    let roller = common::roller("zone = 1.6\nhalf_y = 5.0\nnx = 520\nny = 20", "10000.0")
        .replace("load = 10000.0", "load = 10000.0\ntilt_x = 2e-4");
    let text = with_table(
        &with_table(&roller, "outputs", "plots = [\"pressure\"]"),
        "solver",
        "method = \"conjugate-gradient\"\nerror_estimate = false",
    );
    let (svg, points, _) = pressure_svg(&text);
    assert_eq!(points, 10_400);
    assert!(
        svg.contains("pressure map (174 x 7 blocks of 3 x 3 cells, each its largest)"),
        "the caption says how the map is drawn: {}",
        &svg[svg.find("pressure map").unwrap_or(0)..][..80]
    );
    let rects = svg.matches("<rect").count();
    assert!(rects <= 174 * 7 + 100 + 10, "{rects} rectangles");
    assert!(svg.len() < 400_000, "{} bytes", svg.len());
}

/// The ball bearing's contact (examples/scenes/ball-bearing.toml, on a
/// coarser grid): an ellipse 9.3 times longer along y than across x.
fn ball_bearing() -> String {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/ball-bearing.toml");
    let text = std::fs::read_to_string(path).unwrap();
    text.replace("across = 31", "across = 15")
        .replace(
            "plots = [\"pressure\"]",
            "plots = [\"pressure\"]\nsubsurface = true",
        )
        .replace(
            "method = \"auto\"",
            "method = \"auto\"\nerror_estimate = false",
        )
}

#[test]
fn a_slender_ellipse_s_map_states_its_stretch_and_keeps_its_proportions() {
    let (r, svg) = plotted(&ball_bearing(), Plot::Pressure);
    let k = (stretch(&svg, "x", "mm"), stretch(&svg, "y", "mm"));
    assert_eq!(
        k,
        (3.0, 1.0),
        "9.3:1 drawn at most 4:1: x stretched 3 times"
    );
    let framed = frames(&svg);
    assert_eq!(framed.len(), 1, "one map");
    assert_scaled(framed[0], cell_spans(&r), k);
    assert!(
        texts(&svg).contains(&"pressure (MPa)"),
        "the colour bar's label"
    );
    assert!(svg.contains("along x, at y = 0 mm"), "{:?}", texts(&svg));
    assert_numbers_read_plainly(&svg);
}

#[test]
fn a_round_contact_s_map_is_drawn_at_equal_scales() {
    // Example 1's spheres under a moment: off centre, so a map.
    let text = spheres().replace("load = 100.0", "load = 100.0\nmoment_x = 0.05");
    let (r, svg) = plotted(&text, Plot::Pressure);
    assert!(svg.contains("pressure map"));
    let k = (stretch(&svg, "x", "in"), stretch(&svg, "y", "in"));
    assert_eq!(k, (1.0, 1.0));
    let framed = frames(&svg);
    assert_eq!(framed.len(), 1);
    assert_scaled(framed[0], cell_spans(&r), k);
    assert!(
        texts(&svg).contains(&"pressure (lbf/in^2)"),
        "the colour bar's label"
    );
    assert_numbers_read_plainly(&svg);
}

#[test]
fn the_subsurface_section_has_its_colour_bar_and_equal_scales() {
    let text = ball_bearing().replace("plots = [\"pressure\"]", "plots = [\"subsurface\"]");
    let (r, svg) = plotted(&text, Plot::Subsurface);
    let fields: Vec<_> = r
        .subsurface
        .iter()
        .flatten()
        .filter_map(|s| match s {
            elcon_analysis::subsurface::Subsurface::Stresses(b) => Some(b.section.clone()),
            elcon_analysis::subsurface::Subsurface::NotApplicable(_) => None,
        })
        .collect();
    let framed = frames(&svg);
    assert_eq!(framed.len(), fields.len(), "a section map per body");
    let k = (stretch(&svg, "x", "mm"), stretch(&svg, "depth", "mm"));
    for (size, s) in framed.into_iter().zip(&fields) {
        let spans = (s.xs[s.xs.len() - 1] - s.xs[0], s.depths[s.depths.len() - 1]);
        assert_scaled(size, spans, k);
    }
    assert_eq!(
        texts(&svg)
            .iter()
            .filter(|t| **t == "von Mises stress (MPa)")
            .count(),
        fields.len(),
        "each section's colour bar is labelled"
    );
    assert!(
        svg.contains("max 1") && svg.contains(" MPa at depth 0."),
        "{:?}",
        texts(&svg)
    );
    assert_numbers_read_plainly(&svg);
}
