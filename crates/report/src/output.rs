//! Writing a run's outputs under `<out>/<scene>/`, the directory written
//! whole (elcon-process's `Staging`): result.json (docs/results.md),
//! pressure.csv (position, measure, force, pressure, gap, separation, and
//! the closed form's pressure where one applies), a design's profile.csv
//! (its correction sampled along the axis), the subsurface sections when
//! asked for (`subsurface_body1.csv`, `subsurface_profile_body1.csv`,
//! and body 2's), and the plots asked for.

use std::io;
use std::path::{Path, PathBuf};

use elcon_analysis::subsurface::Subsurface;
use elcon_influence::Dimension;
use elcon_process::{Staging, faults, write_atomic, write_atomic_with};
use elcon_scene::Plot;

use crate::error::ReportError;
use crate::plot;
use crate::plot_subsurface;
use crate::profile::profile_csv;
use crate::result::Run;
use crate::subsurface::section_csv;

/// Writes a run's outputs under `<out>/<scene name>/`, the directory
/// replaced as a unit ([`Staging`]); returns that directory.
///
/// # Errors
/// [`ReportError`] for a file that could not be written.
pub fn write_run(run: &Run, out: &Path) -> Result<PathBuf, ReportError> {
    let staging = Staging::begin(&out.join(run.scene.name()), &|_| {})?;
    write_run_files(run, staging.path())?;
    Ok(staging.commit()?)
}

/// Writes a run's files into `dir`: result.json, pressure.csv (unless
/// switched off), a design's profile.csv and the plots asked for.
///
/// # Errors
/// [`ReportError`] for a file that could not be written.
pub fn write_run_files(run: &Run, dir: &Path) -> Result<(), ReportError> {
    let json = serde_json::to_string_pretty(&run.result).map_err(|e| ReportError::Json {
        path: dir.join("result.json"),
        reason: e.to_string(),
    })?;
    write_atomic(&dir.join("result.json"), json.as_bytes())?;
    faults::write_delay();
    if run.scene.outputs().pressure_csv() {
        write_atomic_with(&dir.join("pressure.csv"), |w| pressure_csv(run, w))?;
        faults::write_delay();
    }
    if let (Some(design), Some(spec)) = (&run.design, run.scene.design()) {
        let length = run.scene.units().length();
        write_atomic_with(&dir.join("profile.csv"), |w| {
            profile_csv(spec.axis().name(), length, &design.samples, w)
        })?;
        faults::write_delay();
    }
    write_subsurface(run, dir)?;
    for plot in run.scene.outputs().plots() {
        let (name, svg) = match plot {
            Plot::Pressure => ("pressure.svg", plot::pressure(run)),
            Plot::Design => ("design.svg", plot::design(run)),
            Plot::Subsurface => ("subsurface.svg", plot_subsurface::subsurface(run)),
        };
        let svg = svg.map_err(|e| ReportError::Plot {
            path: dir.join(name),
            reason: e.to_string(),
        })?;
        write_atomic(&dir.join(name), svg.as_bytes())?;
        faults::write_delay();
    }
    Ok(())
}

/// Each body's section through its largest von Mises stress and its depth
/// profile below the peak pressure, `subsurface_body{1,2}.csv` and
/// `subsurface_profile_body{1,2}.csv`, when the scene asks for the
/// stresses (bodies without a field write none).
fn write_subsurface(run: &Run, dir: &Path) -> Result<(), ReportError> {
    let u = run.scene.units();
    for (i, field) in run.subsurface.iter().flatten().enumerate() {
        let Subsurface::Stresses(body) = field else {
            continue;
        };
        for (name, section) in [
            (format!("subsurface_body{}.csv", i + 1), &body.section),
            (
                format!("subsurface_profile_body{}.csv", i + 1),
                &body.profile,
            ),
        ] {
            write_atomic_with(&dir.join(name), |w| {
                section_csv(section, u.length(), u.pressure(), w)
            })?;
            faults::write_delay();
        }
    }
    Ok(())
}

/// pressure.csv: one row per candidate point, written row by row.
fn pressure_csv(run: &Run, w: &mut dyn io::Write) -> io::Result<()> {
    let u = run.scene.units();
    let points = run.problem.points();
    let sol = &run.solution;
    let eps = run.problem.separation();
    let surface = points.dimension() == Dimension::Surface;
    let (l, f, p) = (u.length(), u.force(), u.intensity());
    if surface {
        write!(
            w,
            "x_{l},y_{l},r_{l},area_{l}^2,force_{f},pressure_{p},gap_{l},separation_{l}"
        )?;
    } else {
        write!(
            w,
            "x_{l},length_{l},force_{f},intensity_{p},gap_{l},separation_{l}"
        )?;
    }
    if run.reference_pressures.is_some() {
        write!(w, ",reference_{p}")?;
    }
    writeln!(w)?;
    for k in 0..points.len() {
        if surface {
            write!(w, "{},{},{},", points.x(k), points.y(k), points.radius(k))?;
        } else {
            write!(w, "{},", points.x(k))?;
        }
        write!(
            w,
            "{},{},{},{},{}",
            points.measure(k),
            sol.forces[k],
            sol.pressures[k],
            sol.gaps[k],
            eps[k]
        )?;
        if let Some(r) = &run.reference_pressures {
            write!(w, ",{}", r[k])?;
        }
        writeln!(w)?;
    }
    Ok(())
}
