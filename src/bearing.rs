//! The command line's bearing scenes (a `[bearing]` table): `run` solves
//! each into `<out>/<scene>/` (written whole) and prints a line per
//! bearing; `check` validates one and prints its memory estimate.

use std::path::Path;

use elcon_lcp::Cancel;
use elcon_num::plain;
use elcon_process::{Ceiling, Staging, interruptible, isolated};
use elcon_report::{BearingResult, write_bearing_files};
use elcon_runner::{BearingEstimate, RunError, run_bearing};
use elcon_scene::BearingScene;

/// Runs the bearing scene `text` (read from `path`) into `out`; prints its
/// summary. Returns `Err` with whether it was interrupted.
pub(crate) fn run_file(
    path: &Path,
    text: &str,
    out: &Path,
    ceiling: &Ceiling,
    cancel: &Cancel,
) -> Result<(), bool> {
    let label = path.display().to_string();
    let outcome = interruptible::<_, RunError>(cancel, &label, || {
        isolated(&label, || {
            let scene = BearingScene::from_str(path, text)?;
            let run = run_bearing(&scene, ceiling)?;
            let staging = Staging::begin(&out.join(scene.name()), &|m| eprintln!("{m}"))?;
            write_bearing_files(&run, staging.path())?;
            Ok((run.result, staging.commit()?))
        })
    });
    match outcome {
        Ok((r, dir)) => {
            print_result(&r);
            println!("{:<28} wrote {}", "", dir.display());
            Ok(())
        }
        Err(e) if e.is_interrupted() => {
            eprintln!("{e}; the scenes after it did not run");
            Err(true)
        }
        Err(e) => {
            eprintln!("error: {e}");
            Err(false)
        }
    }
}

/// A bearing's lines: its load distribution, peak pressure, ring
/// displacement, life and certificate.
fn print_result(r: &BearingResult) {
    let u = &r.units;
    let most = r
        .elements
        .iter()
        .fold(None::<&elcon_report::ElementJson>, |a, e| match a {
            Some(m) if m.load >= e.load => Some(m),
            _ => Some(e),
        });
    let (q, p) = most.map_or((0.0, 0.0), |e| {
        (e.load, e.max_pressure_inner.max(e.max_pressure_outer))
    });
    println!(
        "{:<28} {} bearing, {} elements ({} loaded, load zone +-{} deg), {} zones of {} points",
        r.scene,
        r.bearing,
        r.elements.len(),
        r.loaded,
        plain(r.load_zone),
        r.grid.zones,
        r.grid.points
    );
    println!(
        "{:<28} largest element load {} {}, peak pressure {} {}; ring displacement {} {}",
        "",
        plain(q),
        u.force(),
        plain(p),
        u.pressure(),
        plain(r.ring_displacement.x),
        u.length()
    );
    let reference = &r.reference;
    println!(
        "{:<28} {}: largest load {} {} (elcon {:+.2} %), ring {} {}{}",
        "",
        reference.model,
        plain(reference.max_load),
        u.force(),
        100.0 * reference.max_load_difference,
        plain(reference.ring_displacement),
        u.length(),
        reference.max_pressure.map_or(String::new(), |p| format!(
            ", largest slice pressure {} {}",
            plain(p),
            u.pressure()
        ))
    );
    if let Some(e) = most.filter(|e| e.end_pressure_inner.is_some_and(|p| p > 0.0)) {
        println!(
            "{:<28} most loaded roller's end pressure {} {} ({} % of its peak)",
            "",
            plain(e.end_pressure_inner.unwrap_or(0.0)),
            u.pressure(),
            plain(100.0 * e.end_pressure_inner.unwrap_or(0.0) / e.max_pressure_inner)
        );
    }
    if let Some(d) = &r.crown_design {
        println!(
            "{:<28} crown designed ({}) over {} rollers in {} rounds: peak {} -> {} {} (objective {}); profile.csv",
            "",
            d.family,
            d.cases.len(),
            d.rounds,
            plain(d.max_pressure_before),
            plain(d.max_pressure_after),
            u.pressure(),
            plain(d.objective)
        );
    }
    if let Some(l) = &r.life {
        println!(
            "{:<28} basic rating life L10 {} million revolutions",
            "",
            plain(l.l10)
        );
    }
    println!(
        "{:<28} certificate: equilibrium {:.1e}, zones {:.1e} ({}); {} Newton steps, {} zone solves, {:.2} s",
        "",
        r.certificate.equilibrium,
        r.certificate.zones,
        if r.certificate.holds {
            "holds"
        } else {
            "DOES NOT HOLD"
        },
        r.iterations,
        r.zone_solves,
        r.seconds.total
    );
}

/// `check` of a bearing scene's text: valid, and its memory within the
/// ceiling.
pub(crate) fn check_text(path: &Path, text: &str, ceiling: &Ceiling) -> bool {
    let checked = BearingScene::from_str(path, text)
        .map_err(RunError::from)
        .and_then(|scene| {
            let estimate = BearingEstimate::of(&scene);
            estimate.admit(&scene, ceiling)?;
            Ok((scene, estimate))
        });
    match checked {
        Ok((scene, estimate)) => {
            println!(
                "{}: bearing `{}`: valid; {}",
                path.display(),
                scene.name(),
                estimate.summary()
            );
            true
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}
