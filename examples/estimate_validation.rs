//! The discretization error estimate against the true error on the example
//! scenes (docs/validation.md §4b): each scene run as `elcon run` runs it
//! (its estimate from its other grids, result.json's `discretization`),
//! then solved again on grids 2, 4 and 8 times finer (`GridFamily::finer`,
//! as many as `refine` says). The true error of the run's value is
//! against the finest grid's (or against the closed form, where the scene
//! has one: Hertz's ellipse for the ball bearing from 21 to 101 points
//! across). Printed per quantity: the true relative error, the estimate,
//! their ratio (the target: within 1/2 and 2), the verdict; then the tally.
//!
//! - the ball bearing (ball-bearing.toml, Hertz's ellipse) at 21, 31, 41,
//!   61, 81 and 101 points across;
//! - Example 1's spheres (example1-spheres.toml) at 21 and 41 across;
//! - the crowned roller without its design (crowned-roller.toml), aligned
//!   and tilted by 0.5 mrad;
//! - the measured crown (measured-crown.toml), its profile read linearly
//!   and as a cubic spline;
//! - the rough sphere (rough-sphere.toml), its map read bilinearly and as a
//!   bicubic spline;
//! - Example 2's beam without its design (example2-beam-design.toml);
//! - the flat punch (flat-punch.toml), its rim singular;
//! - Example 1 on the paper's point-force model (example1-paper-model.toml,
//!   11 across, its estimate on finer grids);
//! - the Hertz cylinders (hertz-cylinders.toml, against Hertz).
//!
//! Run: `cargo run --release --example estimate_validation` (a few minutes
//! on two cores: the finest grids are up to 64 times the scene's points).

use std::error::Error;
use std::path::Path;

use elcon::analysis::discretization::Quantity;
use elcon_report::{DiscretizationJson, QuantityJson, RunResult};
use elcon_runner::run;
use elcon_scene::Scene;

/// One scene of the study: its file under examples/scenes, an edit of its
/// text, how many times its grid is halved for the truth (0: the scene's
/// closed form is the truth).
struct Case {
    label: String,
    file: &'static str,
    edit: Box<dyn Fn(&str) -> String>,
    refine: usize,
}

/// The quantities compared.
const QUANTITIES: [Quantity; 3] = [
    Quantity::Approach,
    Quantity::MaxPressure,
    Quantity::ContactExtent,
];

/// What one estimate came to.
#[derive(Default)]
struct Tally {
    estimates: usize,
    within: usize,
    not_resolved: usize,
    not_estimated: usize,
}

/// The estimate of `q` in `d` (the contact extent's for any other).
fn quantity(d: &DiscretizationJson, q: Quantity) -> &QuantityJson {
    let qs = &d.quantities;
    match q {
        Quantity::Approach => &qs.approach,
        Quantity::MaxPressure => &qs.max_pressure,
        _ => &qs.contact_extent,
    }
}

/// The closed form's relative error of `q` in `result`, if it has one.
fn closed_form(result: &RunResult, q: Quantity) -> Option<f64> {
    let e = &result.reference.as_ref()?.errors;
    match q {
        Quantity::Approach => e.approach,
        Quantity::MaxPressure => e.max_pressure,
        _ => None,
    }
}

/// The scene's value of each quantity on the grid `times` halvings finer.
fn finer_values(scene: &Scene, times: usize) -> Result<Vec<f64>, Box<dyn Error>> {
    let mut family = scene.grid_family()?;
    for _ in 0..times {
        family = family.finer();
    }
    let problem = scene.builder(family.points()?, scene.loading()).build()?;
    let solution = problem.solve(scene.method(), scene.options())?;
    Ok(QUANTITIES.iter().map(|&q| solution.quantity(q)).collect())
}

/// One case's rows, added to `tally`.
fn study(case: &Case, tally: &mut Tally) -> Result<(), Box<dyn Error>> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes")
        .join(case.file);
    let text = (case.edit)(&std::fs::read_to_string(&file)?);
    let scene = Scene::from_str(&file, &text)?;
    let r = run(&scene)?;
    let d = r.result.discretization.as_ref().ok_or("no estimate")?;
    let truth = match case.refine {
        0 => None,
        n => Some(finer_values(&scene, n)?),
    };
    for (i, &q) in QUANTITIES.iter().enumerate() {
        let e = quantity(d, q);
        let true_error = match &truth {
            Some(t) => (t[i] != 0.0).then(|| e.value / t[i] - 1.0),
            None => closed_form(&r.result, q),
        };
        let Some(true_error) = true_error else {
            continue;
        };
        let verdict = match (e.verdict.name(), e.scatter) {
            ("converging", Some(_)) => "converging (fit)",
            (name, _) => name,
        };
        let (est, ratio) = match e
            .relative_error
            .filter(|_| verdict.starts_with("converging"))
        {
            Some(est) => {
                tally.estimates += 1;
                let ratio = est / true_error.abs();
                if (0.5..=2.0).contains(&ratio) {
                    tally.within += 1;
                }
                (format!("{est:.2e}"), format!("{ratio:.2}"))
            }
            None => {
                match verdict {
                    "not resolved" => tally.not_resolved += 1,
                    "not estimated" => tally.not_estimated += 1,
                    _ => {}
                }
                ("-".into(), "-".into())
            }
        };
        let order = e.order.map_or("-".into(), |p| format!("{p:.2}"));
        println!(
            "| {} | {} | {} | {true_error:+.2e} | {est} | {ratio} | {order} | {verdict} |",
            case.label,
            r.result.header.points,
            q.name(),
        );
    }
    Ok(())
}

/// The cases (see the module documentation).
fn cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for across in [21, 31, 41, 61, 81, 101] {
        cases.push(Case {
            label: format!("ball bearing, {across} across"),
            file: "ball-bearing.toml",
            edit: Box::new(move |t| t.replace("across = 31", &format!("across = {across}"))),
            refine: 0,
        });
    }
    for across in [21, 41] {
        cases.push(Case {
            label: format!("Example 1 spheres, {across} across"),
            file: "example1-spheres.toml",
            edit: Box::new(move |t| t.replace("across = 41", &format!("across = {across}"))),
            refine: 2,
        });
    }
    let no_design = |t: &str| match t.find("[design]") {
        Some(at) => {
            let rest = &t[at + 1..];
            let end = rest.find("\n[").map_or(t.len(), |e| at + 1 + e + 1);
            format!("{}{}", &t[..at], &t[end..]).replace("\"pressure\", \"design\"", "\"pressure\"")
        }
        None => t.to_string(),
    };
    cases.push(Case {
        label: "crowned roller, aligned".into(),
        file: "crowned-roller.toml",
        edit: Box::new(no_design),
        refine: 3,
    });
    cases.push(Case {
        label: "crowned roller, tilted 0.5 mrad".into(),
        file: "crowned-roller.toml",
        edit: Box::new(move |t| {
            no_design(t).replace("load = 10000.0", "load = 10000.0\ntilt_x = 0.0005")
        }),
        refine: 3,
    });
    for (label, interpolation) in [("linear", ""), ("cubic", ", interpolation = \"cubic\"")] {
        cases.push(Case {
            label: format!("measured crown, {label}"),
            file: "measured-crown.toml",
            edit: Box::new(move |t| {
                t.replace("axis = \"y\" }", &format!("axis = \"y\"{interpolation} }}"))
            }),
            refine: 3,
        });
        cases.push(Case {
            label: format!("rough sphere, {label}"),
            file: "rough-sphere.toml",
            edit: Box::new(move |t| {
                t.replace(
                    "spacing = [0.005, 0.005] }",
                    &format!("spacing = [0.005, 0.005]{interpolation} }}"),
                )
            }),
            refine: 2,
        });
    }
    cases.push(Case {
        label: "Example 2 beam".into(),
        file: "example2-beam-design.toml",
        edit: Box::new(no_design),
        refine: 3,
    });
    cases.push(Case {
        label: "flat punch".into(),
        file: "flat-punch.toml",
        edit: Box::new(|t| t.to_string()),
        refine: 2,
    });
    cases.push(Case {
        label: "Example 1, paper's model".into(),
        file: "example1-paper-model.toml",
        edit: Box::new(|t| t.to_string()),
        refine: 3,
    });
    cases.push(Case {
        label: "Hertz cylinders".into(),
        file: "hertz-cylinders.toml",
        edit: Box::new(|t| t.to_string()),
        refine: 0,
    });
    cases
}

fn main() -> Result<(), Box<dyn Error>> {
    println!("| scene | N | quantity | true error | estimated | est/true | order | verdict |");
    println!("|---|---|---|---|---|---|---|---|");
    let mut tally = Tally::default();
    for case in cases() {
        if let Err(e) = study(&case, &mut tally) {
            println!("| {} | - | - | - | - | - | - | failed: {e} |", case.label);
        }
    }
    println!(
        "\n{} estimates, {} within a factor 2 ({:.0} %); {} not resolved, {} not estimated",
        tally.estimates,
        tally.within,
        100.0 * tally.within as f64 / tally.estimates.max(1) as f64,
        tally.not_resolved,
        tally.not_estimated
    );
    Ok(())
}
