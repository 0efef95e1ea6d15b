//! What several examples share: the `--out DIR` option, writing a file
//! whole, the process's CPU time, and the look of their line plots. An example takes it with
//! `mod common;`; the directory has no main.rs, so it is no example itself.

#![allow(dead_code)]

use std::error::Error;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use plotters::coord::CoordTranslate;
use plotters::prelude::*;

/// The directory `--out DIR` names, or `default`; any other option is an
/// error.
pub fn out_dir(default: &str) -> Result<PathBuf, Box<dyn Error>> {
    let mut out = PathBuf::from(default);
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match (flag.as_str(), it.next()) {
            ("--out", Some(dir)) => out = PathBuf::from(dir),
            _ => return Err(format!("unknown option {flag} (--out DIR)").into()),
        }
    }
    Ok(out)
}

/// Writes `contents` to `path` whole or not at all (a temporary file, then
/// a rename).
pub fn write_whole(path: &Path, contents: impl AsRef<[u8]>) -> std::io::Result<()> {
    let tmp = path.with_extension("tmp");
    {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(contents.as_ref())?;
        f.sync_all()?;
    }
    fs::rename(&tmp, path)
}

/// Draws `points` as line `i` of `chart`, 2 px wide in Palette99's colour
/// `i`, named `name` in the legend; returns the colour.
pub fn labelled_line<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    i: usize,
    name: &str,
    points: impl IntoIterator<Item = (f64, f64)>,
) -> Result<RGBAColor, Box<dyn Error>>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    CT: CoordTranslate<From = (f64, f64)>,
{
    let colour = Palette99::pick(i).to_rgba();
    chart
        .draw_series(LineSeries::new(points, colour.stroke_width(2)))?
        .label(name)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
    Ok(colour)
}

/// The legend of `chart`'s named series, framed, at its upper left.
pub fn legend_upper_left<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
) -> Result<(), Box<dyn Error>>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.8))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    Ok(())
}

/// The CPU seconds the process has used, all its threads (utime + stime
/// of /proc/self/stat, in clock ticks of 10 ms).
pub fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|t| {
            // The fields after the command's closing parenthesis: utime and
            // stime are the 12th and 13th of them.
            let rest = &t[t.rfind(')')? + 2..];
            let mut f = rest.split_whitespace().skip(11);
            let user: f64 = f.next()?.parse().ok()?;
            let system: f64 = f.next()?.parse().ok()?;
            Some((user + system) / 100.0)
        })
        .unwrap_or(f64::NAN)
}
