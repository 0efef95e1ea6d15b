//! SVG plots (plotters): pressure against position with the closed form
//! overlaid (lines, and surfaces whose pressure depends on the radius
//! alone), a pressure map at equal scales with the contact's boundary and
//! a labelled colour bar and the pressure along the principal axes (other
//! surfaces); a design's separations and pressures before and after; a
//! batch's error against run time (log-log, one series per method). Their
//! shared parts (axes, legends below the data, maps) are in `plot_parts`.

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use elcon_analysis::{Geometry, Surface};
use elcon_influence::Dimension;

use crate::error::ReportError;
use crate::plot_parts::{Colours, Entries, Key, Map, axes, err, legend_below, map};
use crate::result::Run;

pub(crate) const SIZE: (u32, u32) = (900, 560);
pub(crate) const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// An SVG of `size` on white, drawn by `draw` on its root area.
pub(crate) fn svg(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), ReportError>,
) -> Result<String, ReportError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw(&root)?;
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// A chart on `area` under `caption` (of font size `size`), with label
/// areas of `x_label` and `y_label` pixels below and left.
pub(crate) fn titled<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: impl AsRef<str>,
    size: u32,
    (x_label, y_label): (u32, u32),
) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(caption, ("sans-serif", size))
        .margin(12)
        .x_label_area_size(x_label)
        .y_label_area_size(y_label);
    builder
}

/// `[lo, hi]` widened by 5 % (and made non-empty).
pub(crate) fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let span = (hi - lo)
        .abs()
        .max(hi.abs().max(lo.abs()) * 1e-6)
        .max(f64::MIN_POSITIVE);
    (lo - 0.05 * span, hi + 0.05 * span)
}

/// Whether a surface run's pressure depends on the radius alone: surfaces
/// of revolution (spheres, planes) about the origin, no rigid rotation
/// prescribed or loaded by a moment, and the contact centred there.
fn axisymmetric(run: &Run) -> bool {
    let revolution = |s: &Surface| matches!(s, Surface::Sphere { .. } | Surface::Plane);
    let surfaces =
        matches!(run.scene.geometry(), Geometry::Surfaces(a, b) if revolution(a) && revolution(b));
    let rigid = run.problem.rigid();
    let level = rigid
        .prescribed
        .iter()
        .all(|&(m, v)| m == elcon_analysis::RigidMode::Approach || v == 0.0)
        && rigid.free.iter().skip(1).all(|&(_, moment)| moment == 0.0);
    let (x, y) = run.solution.load_centre;
    let (ex, ey) = run.problem.points().extent();
    let centred = x.abs() <= 1e-9 * ex.max(ey) && y.abs() <= 1e-9 * ex.max(ey);
    surfaces && level && centred
}

/// The most bins of position a pressure-against-position plot draws: a
/// run of more than twice as many points is drawn by the largest and the
/// smallest pressure of each bin (pressure.csv keeps every point).
pub(crate) const MAX_MARKS: usize = 2048;

/// `(position, value)` pairs reduced to [`MAX_MARKS`] equal bins of
/// position: each bin's largest pair and, with `smallest`, its smallest.
fn extremes(pairs: &[(f64, f64)], smallest: bool) -> Vec<(f64, f64)> {
    let (lo, hi) = pairs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let width = (hi - lo) / MAX_MARKS as f64;
    // Each bin's (largest, smallest) pair.
    type Bin = Option<((f64, f64), (f64, f64))>;
    let mut bins: Vec<Bin> = vec![None; MAX_MARKS];
    for &p in pairs {
        let i = if width > 0.0 {
            (((p.0 - lo) / width) as usize).min(MAX_MARKS - 1)
        } else {
            0
        };
        let (most, least) = bins[i].get_or_insert((p, p));
        if p.1 > most.1 {
            *most = p;
        }
        if p.1 < least.1 {
            *least = p;
        }
    }
    bins.into_iter()
        .flatten()
        .flat_map(|(most, least)| {
            let second = (smallest && least != most).then_some(least);
            std::iter::once(most).chain(second)
        })
        .collect()
}

/// Pressure (intensity) against the radius (an axisymmetric surface run)
/// or x (line); the closed form as a line where one applies. Other surface
/// runs get [`pressure_map`].
pub(crate) fn pressure(run: &Run) -> Result<String, ReportError> {
    let points = run.problem.points();
    let surface = points.dimension() == Dimension::Surface;
    if surface && !axisymmetric(run) {
        return pressure_map(run);
    }
    let u = run.scene.units();
    let pos = |k: usize| {
        if surface {
            points.radius(k)
        } else {
            points.x(k)
        }
    };
    let all: Vec<(f64, f64)> = (0..points.len())
        .map(|k| (pos(k), run.solution.pressures[k]))
        .collect();
    let binned = all.len() > 2 * MAX_MARKS;
    let data = if binned { extremes(&all, true) } else { all };
    let mut reference: Vec<(f64, f64)> = match &run.reference_pressures {
        Some(r) => {
            let curve: Vec<(f64, f64)> = (0..points.len()).map(|k| (pos(k), r[k])).collect();
            if binned {
                extremes(&curve, false)
            } else {
                curve
            }
        }
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
    let mut legend: Entries = vec![(
        if binned {
            format!(
                "elcon, {} points, {} (largest and smallest of each of {MAX_MARKS} bins)",
                points.len(),
                run.scene.method()
            )
        } else {
            format!("elcon, {} points, {}", points.len(), run.scene.method())
        },
        Key::Dot(COLORS[0]),
    )];
    if !reference.is_empty() {
        let kind = run
            .result
            .reference
            .as_ref()
            .map_or("closed form".to_string(), |r| r.kind.clone());
        legend.push((kind, Key::Line(COLORS[1])));
    }
    svg(SIZE, |root| {
        let area = legend_below(root, &legend)?;
        let mut chart = titled(
            &area,
            format!("{}: pressure", run.scene.name()),
            22,
            (50, 80),
        )
        .build_cartesian_2d(x0..x1, 0.0..ymax * 1.08 + f64::MIN_POSITIVE)
        .map_err(err)?;
        let x_desc = if surface {
            format!("radius ({})", u.length())
        } else {
            format!("x ({})", u.length())
        };
        let y_desc = format!("pressure ({})", u.intensity());
        axes(&mut chart, (&x_desc, &y_desc), true)?;
        chart
            .draw_series(data.iter().map(|&p| Circle::new(p, 2, COLORS[0].filled())))
            .map_err(err)?;
        if !reference.is_empty() {
            chart
                .draw_series(LineSeries::new(reference, COLORS[1].stroke_width(2)))
                .map_err(err)?;
        }
        Ok(())
    })
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

/// A chart of values from 0 to above `max` (named `y_desc`) against the
/// axial position over `stations` (in `length`), on `area` under `caption`
/// (its text and font size).
fn axial_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    (caption, size): (impl AsRef<str>, u32),
    (s0, s1): (f64, f64),
    max: f64,
    length: &str,
    y_desc: String,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>, ReportError>
where
    DB::ErrorType: 'static,
{
    let mut chart = titled(area, caption, size, (50, 90))
        .build_cartesian_2d(s0..s1, 0.0..max * 1.1 + f64::MIN_POSITIVE)
        .map_err(err)?;
    let x_desc = format!("axial position ({length})");
    axes(&mut chart, (&x_desc, &y_desc), true)?;
    Ok(chart)
}

/// A design: the correction (top) and each load case's pressure along the
/// axis before and after (bottom).
pub(crate) fn design(run: &Run) -> Result<String, ReportError> {
    let d = run.design.as_ref().ok_or_else(|| err("no design stage"))?;
    let spec = run.scene.design().ok_or_else(|| err("no design section"))?;
    let u = run.scene.units();
    svg((SIZE.0, SIZE.1 + 300), |root| {
        let (top, bottom) = root.split_vertically(360);
        // The correction as profile.csv samples it, dense enough to draw
        // its curve between the stations; where it is infinite (Lundberg's
        // crown at the end of its length) it leaves the plot.
        let table: Vec<(f64, f64)> = d
            .samples
            .iter()
            .copied()
            .filter(|r| r.1.is_finite())
            .collect();
        let (Some(first), Some(last)) = (table.first(), table.last()) else {
            return Err(err("no finite sample of the correction"));
        };
        let (s0, s1) = padded(first.0, last.0);
        let ymax = table.iter().fold(0.0f64, |a, r| a.max(r.1));
        let caption = format!(
            "{}: correction ({})",
            run.scene.name(),
            run.result.design.as_ref().map_or("", |d| d.family.as_str())
        );
        let y_desc = format!("separation ({})", u.length());
        let mut chart = axial_chart(&top, (caption, 22), (s0, s1), ymax, u.length(), y_desc)?;
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
            let before = along(spec.axis(), case.points(), &d.before.solutions[l].pressures);
            let after = along(spec.axis(), case.points(), &d.after.solutions[l].pressures);
            let label = match misalignment {
                Some(angle) => format!(
                    "load {} {}, misaligned {} rad",
                    elcon_num::plain(load),
                    u.force(),
                    elcon_num::plain(angle)
                ),
                None => format!("load {} {}", elcon_num::plain(load), u.force()),
            };
            series.push((label, before, after));
        }
        let pmax = series
            .iter()
            .flat_map(|(_, b, a)| b.iter().chain(a))
            .fold(0.0f64, |m, p| m.max(p.1));
        let caption =
            "pressure along the axis (largest across the width), before (dashed) and after";
        let y_desc = format!("pressure ({})", u.intensity());
        let mut legend: Entries = Vec::new();
        for (i, (label, ..)) in series.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            legend.push((format!("{label}, after"), Key::Line(color)));
            legend.push((format!("{label}, before"), Key::Dashed(color)));
        }
        let bottom = legend_below(&bottom, &legend)?;
        let mut chart = axial_chart(&bottom, (caption, 18), (s0, s1), pmax, u.length(), y_desc)?;
        for (i, (_, before, after)) in series.into_iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            chart
                .draw_series(DashedLineSeries::new(before, 6, 4, color.stroke_width(1)))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(after, color.stroke_width(2)))
                .map_err(err)?;
        }
        Ok(())
    })
}

/// Error against run time, log-log, one series per method: `series` holds
/// (method, [(seconds, |error|)]); `error` names the error on the axis. The
/// SVG's text, or why it could not be drawn (no positive pair).
///
/// # Errors
/// A message when no (time, error) pair is positive or plotters fails.
pub fn error_time(
    title: &str,
    error: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> Result<String, ReportError> {
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|(_, p)| p.iter().copied())
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .collect();
    if all.is_empty() {
        return Err(err("no positive (time, error) pair to plot"));
    }
    let (t0, t1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    let (e0, e1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let legend: Entries = series
        .iter()
        .enumerate()
        .map(|(i, (method, _))| (method.clone(), Key::Line(COLORS[i % COLORS.len()])))
        .collect();
    svg(SIZE, |root| {
        let area = legend_below(root, &legend)?;
        let mut chart = titled(&area, title, 22, (50, 80))
            .build_cartesian_2d(
                (t0 / 1.5..t1 * 1.5).log_scale(),
                (e0 / 1.5..e1 * 1.5).log_scale(),
            )
            .map_err(err)?;
        // A log axis labels its 1, 2 and 5 of each decade (and 3 over
        // less than two decades); the other grid lines stay unlabelled,
        // so that labels do not crowd.
        let few = |lo: f64, hi: f64| (hi / lo).log10() < 2.0;
        let (few_t, few_e) = (few(t0 / 1.5, t1 * 1.5), few(e0 / 1.5, e1 * 1.5));
        let label = |v: &f64, three: bool| {
            let mantissa = *v / 10f64.powf(v.log10().floor());
            let round = [1.0, 2.0, 5.0, 10.0]
                .iter()
                .chain(three.then_some(&3.0))
                .any(|m| (mantissa - m).abs() < 1e-6);
            if round {
                elcon_num::plain(*v).to_string()
            } else {
                String::new()
            }
        };
        let (x_fmt, y_fmt) = (|v: &f64| label(v, few_t), |v: &f64| label(v, few_e));
        chart
            .configure_mesh()
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12))
            .x_labels(12)
            .y_labels(12)
            .x_desc("run time (s)")
            .y_desc(format!("|relative error| of {error}"))
            .label_style(("sans-serif", crate::plot_parts::TICK_FONT))
            .axis_desc_style(("sans-serif", crate::plot_parts::DESC_FONT))
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .draw()
            .map_err(err)?;
        for (i, (_, points)) in series.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            let mut pts: Vec<(f64, f64)> = points
                .iter()
                .copied()
                .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(err)?;
            chart
                .draw_series(
                    pts.into_iter()
                        .map(move |p| Circle::new(p, 4, color.filled())),
                )
                .map_err(err)?;
        }
        Ok(())
    })
}

/// The most cells a pressure map draws along x or along y: a larger grid
/// is drawn in square blocks of cells, each in the colour of its largest
/// pressure, so the SVG stays a few MB however many points the run has
/// (pressure.csv keeps every point).
pub(crate) const MAX_DRAWN: usize = 256;

/// A block of the cells of a map as drawn: the extent of its cells and
/// the largest pressure among them.
#[derive(Debug, Clone, Copy)]
struct Block {
    x: (f64, f64),
    y: (f64, f64),
    top: f64,
}

/// The cells of `points` merged into square blocks of `side` cells, at
/// most [`MAX_DRAWN`] along x and along y (`side` is 1 for a grid that
/// small): the blocks by column and row (`None` where no point lies).
struct Blocks {
    side: usize,
    columns: usize,
    rows: usize,
    cells: Vec<Option<Block>>,
}

impl Blocks {
    fn of(points: &elcon_influence::PointSet, pressures: &[f64]) -> Self {
        let cell = points.cell();
        let (hx, hy) = (0.5 * cell.dx, 0.5 * cell.dy);
        let (px, py) = (points.xs(), points.ys());
        let low = |v: &[f64]| v.iter().fold(f64::INFINITY, |a, b| a.min(*b));
        let high = |v: &[f64]| v.iter().fold(f64::NEG_INFINITY, |a, b| a.max(*b));
        let (x0, y0) = (low(&px), low(&py));
        // A cell's index along an axis: its centre's offset in cells.
        let index = |v: f64, origin: f64, width: f64| -> usize {
            let i = ((v - origin) / width).round();
            if i.is_finite() && i > 0.0 {
                i as usize
            } else {
                0
            }
        };
        let cells_x = index(high(&px), x0, cell.dx) + 1;
        let cells_y = index(high(&py), y0, cell.dy) + 1;
        let side = cells_x.max(cells_y).div_ceil(MAX_DRAWN).max(1);
        let (columns, rows) = (cells_x.div_ceil(side), cells_y.div_ceil(side));
        let mut cells: Vec<Option<Block>> = vec![None; columns * rows];
        for k in 0..points.len() {
            let (x, y) = (px[k], py[k]);
            let (i, j) = (
                (index(x, x0, cell.dx) / side).min(columns - 1),
                (index(y, y0, cell.dy) / side).min(rows - 1),
            );
            let b = cells[j * columns + i].get_or_insert(Block {
                x: (x - hx, x + hx),
                y: (y - hy, y + hy),
                top: pressures[k],
            });
            b.x = (b.x.0.min(x - hx), b.x.1.max(x + hx));
            b.y = (b.y.0.min(y - hy), b.y.1.max(y + hy));
            b.top = b.top.max(pressures[k]);
        }
        Self {
            side,
            columns,
            rows,
            cells,
        }
    }

    fn get(&self, i: isize, j: isize) -> Option<Block> {
        let inside =
            (0..self.columns as isize).contains(&i) && (0..self.rows as isize).contains(&j);
        if inside {
            self.cells[j as usize * self.columns + i as usize]
        } else {
            None
        }
    }

    /// The faces between a block in contact and one that is not (or the
    /// grid's edge), as segments: the contact's boundary on the blocks.
    fn boundary(&self) -> Vec<[(f64, f64); 2]> {
        let mut faces = Vec::new();
        for j in 0..self.rows as isize {
            for i in 0..self.columns as isize {
                let Some(b) = self.get(i, j).filter(|b| b.top > 0.0) else {
                    continue;
                };
                for (di, dj) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    if self.get(i + di, j + dj).is_some_and(|n| n.top > 0.0) {
                        continue;
                    }
                    faces.push(match (di, dj) {
                        (1, _) => [(b.x.1, b.y.0), (b.x.1, b.y.1)],
                        (-1, _) => [(b.x.0, b.y.0), (b.x.0, b.y.1)],
                        (_, 1) => [(b.x.0, b.y.1), (b.x.1, b.y.1)],
                        _ => [(b.x.0, b.y.0), (b.x.1, b.y.0)],
                    });
                }
            }
        }
        faces
    }
}

/// The pressure along one grid line: where it lies (the other coordinate)
/// and its (position, pressure) pairs, sorted.
struct Section {
    at: f64,
    values: Vec<(f64, f64)>,
}

/// The pressure along the grid row and column nearest the contact's centre
/// of pressure: `[along x, along y]`.
fn principal_axes(
    points: &elcon_influence::PointSet,
    pressures: &[f64],
    centre: (f64, f64),
) -> [Section; 2] {
    let nearest = |coord: &dyn Fn(usize) -> f64, target: f64| -> f64 {
        (0..points.len())
            .map(coord)
            .min_by(|a, b| (a - target).abs().total_cmp(&(b - target).abs()))
            .unwrap_or(target)
    };
    let row = nearest(&|k| points.y(k), centre.1);
    let column = nearest(&|k| points.x(k), centre.0);
    let tolerance = 1e-9 * points.extent().0.max(points.extent().1);
    let line = |on: &dyn Fn(usize) -> bool, at: &dyn Fn(usize) -> f64| {
        let mut v: Vec<(f64, f64)> = (0..points.len())
            .filter(|&k| on(k))
            .map(|k| (at(k), pressures[k]))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let x = |k: usize| points.x(k);
    let y = |k: usize| points.y(k);
    [
        Section {
            at: row,
            values: line(&|k| (y(k) - row).abs() <= tolerance, &x),
        },
        Section {
            at: column,
            values: line(&|k| (x(k) - column).abs() <= tolerance, &y),
        },
    ]
}

/// A surface run's pressure as a colour map over x, y at equal scales (or
/// a stated stretch of the shorter axis; each cell in its colour, the
/// contact's boundary drawn on the cells' faces, a labelled colour bar),
/// and the pressure along the row and the column through the centre of
/// pressure.
pub(crate) fn pressure_map(run: &Run) -> Result<String, ReportError> {
    let u = run.scene.units();
    pressure_map_of(&MapOf {
        name: run.scene.name(),
        points: run.problem.points(),
        pressures: &run.solution.pressures,
        centre: run.solution.load_centre,
        length: u.length(),
        intensity: u.intensity(),
    })
}

/// What a pressure map draws: a contact's points and pressures, its centre
/// of pressure, and the names and units it is labelled with.
pub(crate) struct MapOf<'a> {
    /// The name in the title (the scene's, or a zone's).
    pub(crate) name: &'a str,
    /// The candidate points.
    pub(crate) points: &'a elcon_influence::PointSet,
    /// The pressure at each point.
    pub(crate) pressures: &'a [f64],
    /// The centre of pressure, where the sections cross.
    pub(crate) centre: (f64, f64),
    /// The length unit.
    pub(crate) length: &'a str,
    /// The pressure unit.
    pub(crate) intensity: &'a str,
}

/// The pressure map of [`pressure_map`] for any contact.
pub(crate) fn pressure_map_of(of: &MapOf<'_>) -> Result<String, ReportError> {
    let (points, p) = (of.points, of.pressures);
    let top = p
        .iter()
        .fold(0.0f64, |a, v| a.max(*v))
        .max(f64::MIN_POSITIVE);
    let cell = points.cell();
    let (hx, hy) = (0.5 * cell.dx, 0.5 * cell.dy);
    let (px, py) = (points.xs(), points.ys());
    let xs = padded(
        px.iter().fold(f64::INFINITY, |a, v| a.min(*v)) - hx,
        px.iter().fold(f64::NEG_INFINITY, |a, v| a.max(*v)) + hx,
    );
    let ys = padded(
        py.iter().fold(f64::INFINITY, |a, v| a.min(*v)) - hy,
        py.iter().fold(f64::NEG_INFINITY, |a, v| a.max(*v)) + hy,
    );
    let blocks = Blocks::of(points, p);
    let title = if blocks.side == 1 {
        format!("{}: pressure map", of.name)
    } else {
        format!(
            "{}: pressure map ({} x {} blocks of {s} x {s} cells, each its largest)",
            of.name,
            blocks.columns,
            blocks.rows,
            s = blocks.side
        )
    };
    // The boundary on a lattice's cells (or blocks); scattered points
    // have no neighbours to tell it by.
    let faces = if points.lattice().is_some() {
        blocks.boundary()
    } else {
        Vec::new()
    };
    let legend = if faces.is_empty() {
        Vec::new()
    } else {
        vec![("contact boundary".to_string(), Key::Line(BLACK))]
    };
    let spec = Map {
        title,
        x: xs,
        y: ys,
        names: ("x", "y"),
        unit: of.length.to_string(),
        colours: Colours {
            label: format!("pressure ({})", of.intensity),
            top,
        },
        legend,
    };
    svg((SIZE.0, SIZE.1 + 340), |root| {
        let (upper, lower) = root.split_vertically(SIZE.1);
        map(&upper, &spec, |chart| {
            chart
                .draw_series(blocks.cells.iter().flatten().map(|b| {
                    let colour = spec.colours.of(b.top);
                    Rectangle::new([(b.x.0, b.y.0), (b.x.1, b.y.1)], colour.filled())
                }))
                .map_err(err)?;
            chart
                .draw_series(
                    faces
                        .iter()
                        .map(|face| PathElement::new(face.to_vec(), BLACK.stroke_width(2))),
                )
                .map_err(err)?;
            Ok(())
        })?;
        let axes = principal_axes(points, p, of.centre);
        sections(&lower, axes, (xs, ys), top, (of.length, of.intensity))
    })
}

/// The pressure along the row and the column through the centre of
/// pressure (`axes`, [`principal_axes`]), side by side on `area` over the
/// map's ranges along x and y, up to `top`; `units` of length and
/// intensity.
fn sections<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    [along_x, along_y]: [Section; 2],
    (xs, ys): ((f64, f64), (f64, f64)),
    top: f64,
    (length, intensity): (&str, &str),
) -> Result<(), ReportError>
where
    DB::ErrorType: 'static,
{
    let (left, right) = area.split_horizontally(SIZE.0 / 2);
    let at = |v: f64| elcon_num::plain_to(v, (xs.1 - xs.0).max(ys.1 - ys.0) * 1e-3);
    for (i, (area, label, range, series)) in [
        (
            &left,
            format!("along x, at y = {} {length}", at(along_x.at)),
            xs,
            along_x.values,
        ),
        (
            &right,
            format!("along y, at x = {} {length}", at(along_y.at)),
            ys,
            along_y.values,
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let colour = COLORS[i];
        let mut chart = titled(area, &label, 17, (50, 80))
            .build_cartesian_2d(range.0..range.1, 0.0..top * 1.08)
            .map_err(err)?;
        let x_desc = format!("{} ({length})", if i == 0 { "x" } else { "y" });
        let y_desc = format!("pressure ({intensity})");
        axes(&mut chart, (&x_desc, &y_desc), true)?;
        chart
            .draw_series(LineSeries::new(series, colour.stroke_width(2)))
            .map_err(err)?;
    }
    Ok(())
}
