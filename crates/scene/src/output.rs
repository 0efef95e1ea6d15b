//! Writing a run's outputs, each file whole or not at all: the contents go
//! to a temporary file in the same directory, which is then renamed over the
//! target (a rename within a directory is atomic), so an interrupted run
//! leaves either the old file or the new one, never half of one.
//!
//! Per scene, in `<out>/<scene>/`: result.json (docs/results.md),
//! pressure.csv (position, measure, force, pressure, gap, separation, and
//! the closed form's pressure where one applies), and the plots asked for.

use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use elcon_influence::Dimension;

use crate::error::SceneError;
use crate::plot;
use crate::run::Run;
use crate::scene::Plot;

/// Writes `contents` to `path` whole or not at all (temporary file in the
/// same directory, flushed to disk, then renamed).
///
/// # Errors
/// [`SceneError::Io`] naming the file.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), SceneError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    fs::create_dir_all(dir).map_err(|e| SceneError::io(dir, e))?;
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = fs::remove_file(&tmp);
        SceneError::io(path, e)
    })
}

/// Writes a run's outputs under `<out>/<scene name>/`; returns that directory.
///
/// # Errors
/// [`SceneError::Io`] for a file that could not be written.
pub fn write_run(run: &Run, out: &Path) -> Result<PathBuf, SceneError> {
    let dir = out.join(&run.scene.name);
    let json = serde_json::to_string_pretty(&run.result).map_err(|e| SceneError::io(&dir, e))?;
    write_atomic(&dir.join("result.json"), json.as_bytes())?;
    if run.scene.outputs.pressure_csv {
        write_atomic(&dir.join("pressure.csv"), pressure_csv(run).as_bytes())?;
    }
    for plot in &run.scene.outputs.plots {
        let (name, svg) = match plot {
            Plot::Pressure => ("pressure.svg", plot::pressure(run)),
            Plot::Design => ("design.svg", plot::design(run)),
        };
        let svg = svg.map_err(|reason| SceneError::Io {
            path: dir.join(name),
            reason,
        })?;
        write_atomic(&dir.join(name), svg.as_bytes())?;
    }
    Ok(dir)
}

/// pressure.csv: one row per candidate point.
fn pressure_csv(run: &Run) -> String {
    let u = &run.scene.units;
    let points = run.problem.points();
    let sol = &run.solution;
    let eps = run.problem.separation();
    let surface = points.dimension() == Dimension::Surface;
    let mut s = String::new();
    let (l, f, p) = (&u.length, &u.force, &u.intensity);
    if surface {
        let _ = write!(
            s,
            "x_{l},y_{l},r_{l},area_{l}^2,force_{f},pressure_{p},gap_{l},separation_{l}"
        );
    } else {
        let _ = write!(
            s,
            "x_{l},length_{l},force_{f},intensity_{p},gap_{l},separation_{l}"
        );
    }
    if run.reference_pressures.is_some() {
        let _ = write!(s, ",reference_{p}");
    }
    s.push('\n');
    for k in 0..points.len() {
        if surface {
            let _ = write!(s, "{},{},{},", points.x(k), points.y(k), points.radius(k));
        } else {
            let _ = write!(s, "{},", points.x(k));
        }
        let _ = write!(
            s,
            "{},{},{},{},{}",
            points.measure(k),
            sol.forces[k],
            sol.pressures[k],
            sol.gaps[k],
            eps[k]
        );
        if let Some(r) = &run.reference_pressures {
            let _ = write!(s, ",{}", r[k]);
        }
        s.push('\n');
    }
    s
}
