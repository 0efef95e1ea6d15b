//! The subsurface plot (`outputs.plots = ["subsurface"]`): for each body
//! with a field, a colour map of the von Mises stress on the section
//! (x against depth, depth downward, at equal scales or a stated stretch,
//! with a labelled colour bar) through its largest value, the maximum
//! marked; and beside it the stresses along depth below the peak pressure
//! (von Mises, Tresca, |tau_xz|).

use plotters::prelude::*;

use elcon_analysis::subsurface::{BodyStresses, Subsurface};

use crate::error::ReportError;
use crate::plot::{COLORS, MAX_DRAWN, SIZE, padded, svg, titled};
use crate::plot_parts::{Colours, Entries, Key, Map, axes, err, legend_below, map};
use crate::result::Run;

/// One stress measure of a tensor.
type Measure = fn(&elcon_influence::Stress) -> f64;

/// The subsurface plot of a run whose scene asked for the stresses.
pub(crate) fn subsurface(run: &Run) -> Result<String, ReportError> {
    let bodies: Vec<(usize, &BodyStresses)> = run
        .subsurface
        .iter()
        .flatten()
        .enumerate()
        .filter_map(|(i, s)| match s {
            Subsurface::Stresses(b) => Some((i + 1, b.as_ref())),
            Subsurface::NotApplicable(_) => None,
        })
        .collect();
    if bodies.is_empty() {
        return svg((SIZE.0, 120), |root| {
            root.draw(&Text::new(
                format!(
                    "{}: no body has stresses below its surface",
                    run.scene.name()
                ),
                (20, 50),
                ("sans-serif", 20),
            ))
            .map_err(err)
        });
    }
    let rows = bodies.len() as u32;
    svg((SIZE.0 + 200, SIZE.1 * rows), |root| {
        for (area, (number, body)) in root.split_evenly((bodies.len(), 1)).iter().zip(&bodies) {
            let (left, right) = area.split_horizontally(SIZE.0 - 120);
            section_map(run, &left, *number, body)?;
            depth_profile(run, &right, body)?;
        }
        Ok(())
    })
}

/// The section's von Mises colour map with its maximum marked.
fn section_map<DB: DrawingBackend>(
    run: &Run,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    number: usize,
    body: &BodyStresses,
) -> Result<(), ReportError>
where
    DB::ErrorType: 'static,
{
    let u = run.scene.units();
    let s = &body.section;
    let top = s
        .stresses
        .iter()
        .fold(f64::MIN_POSITIVE, |a, v| a.max(v.von_mises()));
    let (x0, x1) = (s.xs[0], s.xs[s.xs.len() - 1]);
    let deepest = s.depths[s.depths.len() - 1];
    let merged = if s.xs.len() > MAX_DRAWN || s.depths.len() > MAX_DRAWN {
        "; blocks of cells, each its largest"
    } else {
        ""
    };
    let length = u.length();
    let title = format!(
        "{}, body {number}: von Mises stress at y = {} {length}, max {} {} at depth {} {length}{merged}",
        run.scene.name(),
        elcon_num::plain_to(s.y, (x1 - x0) * 1e-3),
        elcon_num::plain(body.von_mises.value),
        u.pressure(),
        elcon_num::plain(body.von_mises.z),
    );
    let spec = Map {
        title,
        x: (x0, x1),
        y: (deepest, 0.0),
        names: ("x", "depth"),
        unit: length.to_string(),
        colours: Colours {
            label: format!("von Mises stress ({})", u.pressure()),
            top,
        },
        legend: vec![("largest von Mises stress".to_string(), Key::Cross(RED))],
    };
    map(area, &spec, |chart| {
        chart
            .draw_series(section_cells(body, &spec.colours))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Cross::new(
                (body.von_mises.x, body.von_mises.z),
                8,
                RED.stroke_width(3),
            )))
            .map_err(err)?;
        Ok(())
    })?;
    Ok(())
}

/// The section's cells as drawn: a long section (or many depths) in
/// blocks of columns and depths, at most [`MAX_DRAWN`] each way, each in
/// the colour of its largest von Mises stress.
fn section_cells(body: &BodyStresses, colours: &Colours) -> Vec<Rectangle<(f64, f64)>> {
    let s = &body.section;
    let rows = s.depths.len();
    let half = |v: &[f64], i: usize| {
        let lo = if i == 0 {
            v[0]
        } else {
            0.5 * (v[i - 1] + v[i])
        };
        let hi = if i + 1 == v.len() {
            v[i]
        } else {
            0.5 * (v[i] + v[i + 1])
        };
        (lo, hi)
    };
    let mut depths = vec![0.0];
    depths.extend_from_slice(&s.depths);
    let (gx, gz) = (
        s.xs.len().div_ceil(MAX_DRAWN).max(1),
        rows.div_ceil(MAX_DRAWN).max(1),
    );
    let block = |bi: usize, bj: usize| {
        let (i0, i1) = (bi * gx, ((bi + 1) * gx).min(s.xs.len()) - 1);
        let (j0, j1) = (bj * gz, ((bj + 1) * gz).min(rows) - 1);
        let value = (i0..=i1)
            .flat_map(|i| (j0..=j1).map(move |j| i * rows + j))
            .fold(0.0f64, |a, k| a.max(s.stresses[k].von_mises()));
        Rectangle::new(
            [
                (half(&s.xs, i0).0, depths[j0]),
                (half(&s.xs, i1).1, depths[j1 + 1]),
            ],
            colours.of(value).filled(),
        )
    };
    (0..s.xs.len().div_ceil(gx))
        .flat_map(|bi| (0..rows.div_ceil(gz)).map(move |bj| (bi, bj)))
        .map(|(bi, bj)| block(bi, bj))
        .collect()
}

/// The stresses along depth below the peak pressure, their legend below.
fn depth_profile<DB: DrawingBackend>(
    run: &Run,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    body: &BodyStresses,
) -> Result<(), ReportError>
where
    DB::ErrorType: 'static,
{
    let u = run.scene.units();
    let p = &body.profile;
    let measures: [(&str, Measure); 3] = [
        ("von Mises", |s| s.von_mises()),
        ("Tresca", |s| s.tresca()),
        ("|tau_xz|", |s| s.xz.abs()),
    ];
    let top = p
        .stresses
        .iter()
        .fold(0.0f64, |a, s| a.max(s.von_mises()).max(s.tresca()));
    let (lo, hi) = padded(0.0, top);
    let deepest = p.depths[p.depths.len() - 1];
    let legend: Entries = measures
        .iter()
        .enumerate()
        .map(|(i, (name, _))| (name.to_string(), Key::Line(COLORS[i])))
        .collect();
    let area = legend_below(area, &legend)?;
    let length = u.length();
    let caption = format!(
        "below the peak pressure, x = {} {length}",
        elcon_num::plain_to(p.xs[0], deepest.abs() * 1e-3)
    );
    // A right margin for the last stress tick's label.
    let mut chart = titled(&area, caption, 15, (50, 70))
        .margin_right(28)
        .build_cartesian_2d(lo..hi, deepest..0.0)
        .map_err(err)?;
    let x_desc = format!("stress ({})", u.pressure());
    let y_desc = format!("depth ({length})");
    axes(&mut chart, (&x_desc, &y_desc), true)?;
    for (i, (_, of)) in measures.iter().enumerate() {
        chart
            .draw_series(LineSeries::new(
                p.depths.iter().zip(&p.stresses).map(|(z, s)| (of(s), *z)),
                COLORS[i].stroke_width(2),
            ))
            .map_err(err)?;
    }
    Ok(())
}
