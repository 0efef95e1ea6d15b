//! SVG plots (plotters): pressure against position with the closed form
//! overlaid; a design's separations and pressures before and after; a
//! batch's error against run time (log-log, one series per method).

use plotters::prelude::*;

use elcon_influence::Dimension;

use crate::run::Run;

const SIZE: (u32, u32) = (900, 560);
const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

fn err(e: impl std::fmt::Display) -> String {
    format!("plot: {e}")
}

/// `[lo, hi]` widened by 5 % (and made non-empty).
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let span = (hi - lo)
        .abs()
        .max(hi.abs().max(lo.abs()) * 1e-6)
        .max(f64::MIN_POSITIVE);
    (lo - 0.05 * span, hi + 0.05 * span)
}

/// Pressure (intensity) against the radius (surface) or x (line); the
/// closed form as a line where one applies.
pub(crate) fn pressure(run: &Run) -> Result<String, String> {
    let points = run.problem.points();
    let surface = points.dimension() == Dimension::Surface;
    let u = &run.scene.units;
    let pos = |k: usize| {
        if surface {
            points.radius(k)
        } else {
            points.x(k)
        }
    };
    let data: Vec<(f64, f64)> = (0..points.len())
        .map(|k| (pos(k), run.solution.pressures[k]))
        .collect();
    let mut reference: Vec<(f64, f64)> = match &run.reference_pressures {
        Some(r) => (0..points.len()).map(|k| (pos(k), r[k])).collect(),
        None => Vec::new(),
    };
    reference.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (x0, x1) = data
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let ymax = data
        .iter()
        .chain(&reference)
        .fold(0.0f64, |a, p| a.max(p.1));
    let (x0, x1) = padded(x0, x1);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(format!("{}: pressure", run.scene.name), ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, 0.0..ymax * 1.08 + f64::MIN_POSITIVE)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(if surface {
                format!("radius ({})", u.length)
            } else {
                format!("x ({})", u.length)
            })
            .y_desc(format!("pressure ({})", u.intensity))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(data.iter().map(|&p| Circle::new(p, 2, COLORS[0].filled())))
            .map_err(err)?
            .label(format!(
                "elcon, {} points, {}",
                points.len(),
                run.scene.method
            ))
            .legend(|(x, y)| Circle::new((x + 10, y), 3, COLORS[0].filled()));
        if !reference.is_empty() {
            let kind = run
                .result
                .reference
                .as_ref()
                .map_or("closed form".to_string(), |r| r.kind.clone());
            chart
                .draw_series(LineSeries::new(reference, COLORS[1].stroke_width(2)))
                .map_err(err)?
                .label(kind)
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], COLORS[1].stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// The largest value across the width at each axial station, sorted.
fn along(
    axis: elcon_design::Axis,
    points: &elcon_influence::PointSet,
    values: &[f64],
) -> Vec<(f64, f64)> {
    let (stations, index) = elcon_design::axial_stations([points], axis);
    let mut rows: Vec<(f64, f64)> = stations
        .into_iter()
        .map(|s| (s, f64::NEG_INFINITY))
        .collect();
    for (&st, &v) in index[0].iter().zip(values) {
        rows[st].1 = rows[st].1.max(v);
    }
    rows
}

/// A design: the correction (top) and each load case's pressure along the
/// axis before and after (bottom).
pub(crate) fn design(run: &Run) -> Result<String, String> {
    let d = run.design.as_ref().ok_or("no design stage")?;
    let spec = run.scene.design.as_ref().ok_or("no design section")?;
    let u = &run.scene.units;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (SIZE.0, SIZE.1 + 300)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (top, bottom) = root.split_vertically(360);
        let table = &run.result.design.as_ref().ok_or("no design result")?.table;
        let (s0, s1) = padded(table[0].0, table[table.len() - 1].0);
        let ymax = table.iter().fold(0.0f64, |a, r| a.max(r.1));
        let mut chart = ChartBuilder::on(&top)
            .caption(
                format!(
                    "{}: correction ({})",
                    run.scene.name,
                    run.result.design.as_ref().map_or("", |d| d.family.as_str())
                ),
                ("sans-serif", 22),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(90)
            .build_cartesian_2d(s0..s1, 0.0..ymax * 1.1 + f64::MIN_POSITIVE)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(format!("axial position ({})", u.length))
            .y_desc(format!("separation ({})", u.length))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(
                table.iter().copied(),
                COLORS[2].stroke_width(2),
            ))
            .map_err(err)?;
        let mut series = Vec::new();
        for ((l, case), (load, misalignment)) in
            d.cases.iter().enumerate().zip(spec.case_loadings())
        {
            let before = along(spec.axis, case.points(), &d.before.solutions[l].pressures);
            let after = along(spec.axis, case.points(), &d.after.solutions[l].pressures);
            let label = match misalignment {
                Some(angle) => format!("load {load} {}, {angle:e} rad", u.force),
                None => format!("load {load} {}", u.force),
            };
            series.push((label, before, after));
        }
        let pmax = series
            .iter()
            .flat_map(|(_, b, a)| b.iter().chain(a))
            .fold(0.0f64, |m, p| m.max(p.1));
        let mut chart = ChartBuilder::on(&bottom)
            .caption(
                "pressure along the axis (largest across the width), before (dashed) and after",
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(90)
            .build_cartesian_2d(s0..s1, 0.0..pmax * 1.1 + f64::MIN_POSITIVE)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(format!("axial position ({})", u.length))
            .y_desc(format!("pressure ({})", u.intensity))
            .draw()
            .map_err(err)?;
        for (i, (label, before, after)) in series.into_iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            chart
                .draw_series(DashedLineSeries::new(before, 6, 4, color.stroke_width(1)))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(after, color.stroke_width(2)))
                .map_err(err)?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// Error against run time, log-log, one series per method: `series` holds
/// (method, [(seconds, |error|)]).
pub(crate) fn error_time(
    title: &str,
    error: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<String, String> {
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|(_, p)| p.iter().copied())
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .collect();
    if all.is_empty() {
        return Err("no positive (time, error) pair to plot".into());
    }
    let (t0, t1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    let (e0, e1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(
                (t0 / 1.5..t1 * 1.5).log_scale(),
                (e0 / 1.5..e1 * 1.5).log_scale(),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("run time (s)")
            .y_desc(format!("|relative error| of {error}"))
            .draw()
            .map_err(err)?;
        for (i, (method, points)) in series.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            let mut pts: Vec<(f64, f64)> = points
                .iter()
                .copied()
                .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(err)?
                .label(method.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            chart
                .draw_series(
                    pts.into_iter()
                        .map(move |p| Circle::new(p, 4, color.filled())),
                )
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}
