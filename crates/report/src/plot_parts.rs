//! The parts every plot shares: axes whose ticks are written as people
//! write numbers ([`elcon_num::plain_to`]) at a readable size, legends
//! beside the data rather than on it, and maps drawn at equal scales
//! ([`fit`]: one unit of x as long as one of y, or a stated stretch of the
//! shorter axis for a slender contact) with a labelled colour bar.

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;

use crate::error::ReportError;

/// A drawing failure of plotters, as a report's error.
pub(crate) fn err(e: impl std::fmt::Display) -> ReportError {
    ReportError::Draw {
        reason: e.to_string(),
    }
}

/// The font of axis tick labels and colour-bar ticks, in plotters' sizes
/// (its SVG writes size s as `font-size` s / 1.24: 16 is about 13 px).
pub(crate) const TICK_FONT: u32 = 16;
/// The font of an axis's (or the colour bar's) description.
pub(crate) const DESC_FONT: u32 = 17;
/// The font of a legend's entries.
pub(crate) const LEGEND_FONT: u32 = 16;
/// The font of a map's title.
pub(crate) const TITLE_FONT: u32 = 20;

/// The longest a map's plotting area may be against its shorter side: a
/// contact more slender than this is drawn with its shorter axis
/// stretched by a whole factor, stated on that axis. At 4:1 the shorter
/// side of a map (about 430 pixels long) still holds 100 pixels, room
/// for three tick labels and for the pressure's shape across it, and a
/// 9.3:1 ellipse drawn 3.1:1 still reads as slender; drawn at equal scales
/// it would be a sliver 46 pixels wide with no readable axis.
pub(crate) const SLENDER: f64 = 4.0;

/// A chart over f64 axes, as plots draw them.
pub(crate) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// How a map is scaled: the whole factors its axes are stretched by (at
/// least one of them 1, both 1 at equal scales), and its plotting area's
/// size in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Fit {
    pub(crate) stretch: (u32, u32),
    pub(crate) size: (u32, u32),
}

/// The largest plotting area within `room` (pixels) that draws data
/// spanning `spans` (x, y) at equal scales, the shorter axis stretched by
/// the least whole factor that keeps the area within [`SLENDER`]:1.
pub(crate) fn fit(spans: (f64, f64), room: (u32, u32)) -> Fit {
    let (dx, dy) = (spans.0.abs(), spans.1.abs());
    let ratio = if dx > 0.0 && dy > 0.0 { dx / dy } else { 1.0 };
    let factor = |r: f64| (r / SLENDER).ceil().max(1.0);
    let (kx, ky) = if ratio > SLENDER {
        (1.0, factor(ratio))
    } else if ratio < 1.0 / SLENDER {
        (factor(1.0 / ratio), 1.0)
    } else {
        (1.0, 1.0)
    };
    let aspect = ratio * kx / ky;
    let (w, h) = (f64::from(room.0.max(1)), f64::from(room.1.max(1)));
    let (pw, ph) = if w / h > aspect {
        (h * aspect, h)
    } else {
        (w, w / aspect)
    };
    Fit {
        stretch: (kx as u32, ky as u32),
        size: (pw.round().max(1.0) as u32, ph.round().max(1.0) as u32),
    }
}

/// An axis's description, naming its stretch when it has one:
/// `x (mm)` or `x (mm, ×3)`.
pub(crate) fn axis_name(name: &str, unit: &str, stretch: u32) -> String {
    if stretch > 1 {
        format!("{name} ({unit}, ×{stretch})")
    } else {
        format!("{name} ({unit})")
    }
}

/// An axis's ticks: how many key points plotters is asked for, and the
/// labels it writes (as people write numbers, to the ticks' spacing).
/// Plotters puts key points at multiples of 1, 2 or 5 times a power of
/// ten, as many as fit the count; a narrow axis over an odd range would
/// get one label (`0`) or five crowded ones, so it is asked for many and
/// only every first, second, fifth or tenth is labelled, the labels
/// apart by more than their width (`along_x`) or height.
pub(crate) fn ticks(
    range: std::ops::Range<f64>,
    pixels: u32,
    along_x: bool,
) -> (usize, impl Fn(&f64) -> String) {
    let (start, end) = (range.start.min(range.end), range.start.max(range.end));
    let asked = (pixels / 20).clamp(3, 40) as usize;
    let span = (range.end - range.start).abs();
    let points = RangedCoordf64::from(range).key_points(asked);
    let step = match points.as_slice() {
        [a, b, ..] => (b - a).abs(),
        _ => span,
    };
    let apart = if span > 0.0 {
        step / span * f64::from(pixels)
    } else {
        f64::INFINITY
    };
    let every = [1.0, 2.0, 5.0, 10.0, 20.0, 50.0]
        .into_iter()
        .find(|k| k * apart >= label_gap((start, end), k * step, step, along_x))
        .unwrap_or(100.0);
    let shown = every * step;
    // One form for every label of the axis: scientific throughout when
    // its largest end or its step needs it.
    let widest = range_end_magnitude(&points);
    let scientific = !elcon_num::plain_to(widest, step).is_fixed()
        || !elcon_num::plain_to(step, step).is_fixed();
    let format = move |v: &f64| {
        let multiple = shown > 0.0 && ((v / shown).round() * shown - v).abs() <= 1e-6 * shown;
        let label = elcon_num::plain_to(*v, step);
        match (multiple, scientific) {
            (false, _) => String::new(),
            (true, false) => label.to_string(),
            (true, true) => label.scientific().to_string(),
        }
    };
    (asked, format)
}

/// The largest magnitude among an axis's key points (0 for none).
fn range_end_magnitude(points: &[f64]) -> f64 {
    points.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// The pixels tick labels `shown` apart over `(start, end)` (written to
/// `step`) need between their centres: along x, the widest's width
/// (about 6 pixels a character, with a gap); along y, a label's height
/// with a gap.
fn label_gap((start, end): (f64, f64), shown: f64, step: f64, along_x: bool) -> f64 {
    if !along_x || shown <= 0.0 {
        return 40.0;
    }
    let first = (start / shown).ceil() * shown;
    let last = (end / shown).floor() * shown;
    // The ends and their neighbours: a label's length grows with its
    // magnitude and with the digits of its place among the multiples.
    let widest = [first, first + shown, last - shown, last]
        .iter()
        .map(|v| elcon_num::plain_to(*v, step).to_string().len())
        .max()
        .unwrap_or(1);
    6.0 * widest as f64 + 8.0
}

/// Draws `chart`'s axes (and, with `grid`, a light grid): ticks written
/// as people write numbers to the axis's resolution, at [`TICK_FONT`],
/// the descriptions at [`DESC_FONT`].
pub(crate) fn axes<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    (x_desc, y_desc): (&str, &str),
    grid: bool,
) -> Result<(), ReportError>
where
    DB::ErrorType: 'static,
{
    let (w, h) = chart.plotting_area().dim_in_pixel();
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let (nx, x_fmt) = ticks(xr, w, true);
    let (ny, y_fmt) = ticks(yr, h, false);
    let mut mesh = chart.configure_mesh();
    if grid {
        mesh.light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12));
    } else {
        mesh.disable_mesh();
    }
    mesh.x_labels(nx)
        .y_labels(ny)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", TICK_FONT))
        .axis_desc_style(("sans-serif", DESC_FONT))
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .draw()
        .map_err(err)
}

/// A legend's key: how its series is drawn.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Key {
    /// A line two pixels wide.
    Line(RGBColor),
    /// A dashed line one pixel wide.
    Dashed(RGBColor),
    /// A filled circle.
    Dot(RGBColor),
    /// A cross.
    Cross(RGBColor),
}

/// A legend's entries: each series' name and key.
pub(crate) type Entries = Vec<(String, Key)>;

/// The width of a legend entry's key and the gaps around it (pixels).
const KEY_WIDTH: i32 = 30;
/// The height of a row of a legend (pixels).
const LEGEND_ROW: i32 = 24;

/// Each entry's (row, left edge) when `entries` are laid out in rows
/// across `width` pixels, each row centred, with the number of rows.
fn legend_rows<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, Key)],
    width: i32,
) -> (Vec<(i32, i32)>, i32) {
    let style = ("sans-serif", LEGEND_FONT).into_text_style(area);
    let (mut row, mut x) = (0, 0);
    let mut places = Vec::new();
    // Each row's width, to centre it.
    let mut widths = vec![0];
    for (text, _) in entries {
        let text_width = area
            .estimate_text_size(text, &style)
            .map_or(8 * text.len() as i32, |s| s.0 as i32);
        let wide = KEY_WIDTH + text_width + 24;
        if x > 0 && x + wide > width {
            row += 1;
            x = 0;
            widths.push(0);
        }
        places.push((row, x));
        x += wide;
        widths[row as usize] = x - 24;
    }
    for place in &mut places {
        place.1 += (width - widths[place.0 as usize]).max(0) / 2;
    }
    (places, if entries.is_empty() { 0 } else { row + 1 })
}

/// Draws `entries` in rows along the bottom of `area`, outside the data,
/// and returns the area above them (the whole area when there are none).
pub(crate) fn legend_below<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, Key)],
) -> Result<DrawingArea<DB, Shift>, ReportError>
where
    DB::ErrorType: 'static,
{
    let (w, h) = area.dim_in_pixel();
    let (places, rows) = legend_rows(area, entries, w as i32 - 40);
    if rows == 0 {
        return Ok(area.margin(0, 0, 0, 0));
    }
    let height = rows * LEGEND_ROW + 8;
    let (above, strip) = area.split_vertically(h as i32 - height);
    let style = ("sans-serif", LEGEND_FONT).into_text_style(&strip);
    for ((text, key), (row, x)) in entries.iter().zip(places) {
        let (x, y) = (20 + x, 4 + row * LEGEND_ROW + LEGEND_ROW / 2);
        draw_key(&strip, *key, (x, y))?;
        let at = (x + KEY_WIDTH, y - LEGEND_FONT as i32 / 2 - 1);
        strip
            .draw(&Text::new(text.as_str(), at, style.clone()))
            .map_err(err)?;
    }
    Ok(above)
}

/// Draws `key` at `(x, y)` (its left edge, mid-height) on `area`.
fn draw_key<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    key: Key,
    (x, y): (i32, i32),
) -> Result<(), ReportError>
where
    DB::ErrorType: 'static,
{
    let line = |c: RGBColor, w: u32| PathElement::new(vec![(x, y), (x + 22, y)], c.stroke_width(w));
    match key {
        Key::Line(c) => area.draw(&line(c, 2)),
        Key::Dashed(c) => [(x, x + 6), (x + 9, x + 15), (x + 18, x + 22)]
            .into_iter()
            .try_for_each(|(a, b)| {
                area.draw(&PathElement::new(vec![(a, y), (b, y)], c.stroke_width(1)))
            }),
        Key::Dot(c) => area.draw(&Circle::new((x + 11, y), 4, c.filled())),
        Key::Cross(c) => area.draw(&Cross::new((x + 11, y), 6, c.stroke_width(3))),
    }
    .map_err(err)
}

/// A colour map's description: the quantity and unit its colour bar is
/// labelled with, and the value at its top (the bar runs from 0).
pub(crate) struct Colours {
    pub(crate) label: String,
    pub(crate) top: f64,
}

impl Colours {
    /// The colour of `v` on the bar; at or below 0 (out of contact), a
    /// light grey.
    pub(crate) fn of(&self, v: f64) -> RGBColor {
        if v <= 0.0 {
            RGBColor(235, 235, 235)
        } else {
            ViridisRGB::get_color_normalized(v, 0.0, self.top)
        }
    }
}

/// The width of a colour bar with its ticks and label (pixels).
pub(crate) const BAR_WIDTH: u32 = 100;

/// A vertical colour bar of `colours` on `area`: 100 steps from 0 to its
/// top, ticks and the bar's label on its right.
pub(crate) fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    colours: &Colours,
) -> Result<(), ReportError>
where
    DB::ErrorType: 'static,
{
    let top = colours.top.max(f64::MIN_POSITIVE);
    let mut bar = ChartBuilder::on(area)
        .set_label_area_size(LabelAreaPosition::Right, BAR_WIDTH - 20)
        .build_cartesian_2d(0.0..1.0, 0.0..top)
        .map_err(err)?;
    let (_, h) = bar.plotting_area().dim_in_pixel();
    let (n, fmt) = ticks(0.0..top, h, false);
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(n)
        .y_desc(colours.label.as_str())
        .label_style(("sans-serif", TICK_FONT))
        .axis_desc_style(("sans-serif", DESC_FONT))
        .y_label_formatter(&fmt)
        .draw()
        .map_err(err)?;
    let steps = 100;
    bar.draw_series((0..steps).map(|i| {
        let (lo, hi) = (
            top * i as f64 / steps as f64,
            top * (i + 1) as f64 / steps as f64,
        );
        let colour = ViridisRGB::get_color_normalized(0.5 * (lo + hi), 0.0, top);
        Rectangle::new([(0.0, lo), (1.0, hi)], colour.filled())
    }))
    .map_err(err)?;
    Ok(())
}

/// A map: its title, its ranges along x and y (a range may run downward,
/// as depth does), its axes' names and length unit, its colours and its
/// legend.
pub(crate) struct Map {
    pub(crate) title: String,
    pub(crate) x: (f64, f64),
    pub(crate) y: (f64, f64),
    pub(crate) names: (&'static str, &'static str),
    pub(crate) unit: String,
    pub(crate) colours: Colours,
    pub(crate) legend: Entries,
}

/// The pixels left of a map's plotting area (ticks and the y axis's
/// description) and below it (ticks and the x axis's description).
const MAP_LABELS: (u32, u32) = (80, 52);

/// Draws `map` on `area`: its title on top, its legend below, the map at
/// equal scales (or its stated stretch, [`fit`]) with the colour bar
/// beside it; `draw` draws the data on the map's chart. Returns the fit.
pub(crate) fn map<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    map: &Map,
    draw: impl FnOnce(&mut Chart<'_, DB>) -> Result<(), ReportError>,
) -> Result<Fit, ReportError>
where
    DB::ErrorType: 'static,
{
    area.draw(&Text::new(
        map.title.as_str(),
        (16, 10),
        ("sans-serif", TITLE_FONT),
    ))
    .map_err(err)?;
    let body = legend_below(&area.margin(40, 0, 0, 0), &map.legend)?;
    let (bw, bh) = body.dim_in_pixel();
    let room = (
        bw.saturating_sub(MAP_LABELS.0 + BAR_WIDTH + 40),
        bh.saturating_sub(MAP_LABELS.1 + 10),
    );
    let fit = fit((map.x.1 - map.x.0, map.y.1 - map.y.0), room);
    let used = fit.size.0 + MAP_LABELS.0 + 20 + BAR_WIDTH;
    let left = bw.saturating_sub(used) / 2;
    let chart_area = body.margin(
        10,
        bh.saturating_sub(10 + fit.size.1 + MAP_LABELS.1),
        left,
        bw.saturating_sub(left + MAP_LABELS.0 + fit.size.0),
    );
    let mut chart = ChartBuilder::on(&chart_area)
        .x_label_area_size(MAP_LABELS.1)
        .y_label_area_size(MAP_LABELS.0)
        .build_cartesian_2d(map.x.0..map.x.1, map.y.0..map.y.1)
        .map_err(err)?;
    let x_desc = axis_name(map.names.0, &map.unit, fit.stretch.0);
    let y_desc = axis_name(map.names.1, &map.unit, fit.stretch.1);
    axes(&mut chart, (&x_desc, &y_desc), false)?;
    draw(&mut chart)?;
    // The frame of the plotting area, over the data's edge.
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(map.x.0, map.y.0), (map.x.1, map.y.1)],
            RGBColor(64, 64, 64).stroke_width(1),
        )))
        .map_err(err)?;
    let bar_left = left + MAP_LABELS.0 + fit.size.0 + 20;
    let bar_area = body.margin(
        10,
        bh.saturating_sub(10 + fit.size.1),
        bar_left,
        bw.saturating_sub(bar_left + BAR_WIDTH),
    );
    colour_bar(&bar_area, &map.colours)?;
    Ok(fit)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The labels `ticks` writes over `range` on an axis of `pixels`.
    fn labels(range: std::ops::Range<f64>, pixels: u32, along_x: bool) -> Vec<String> {
        let (n, format) = ticks(range.clone(), pixels, along_x);
        RangedCoordf64::from(range)
            .key_points(n)
            .iter()
            .map(format)
            .filter(|s| !s.is_empty())
            .collect()
    }

    #[test]
    fn a_narrow_axis_gets_a_few_round_labels() {
        // The ball bearing's map across x, 134 pixels wide, and the
        // crowned roller's, 125 (as drawn).
        assert_eq!(labels(-0.19..0.19, 134, true), ["-0.1", "0", "0.1"]);
        assert_eq!(labels(-0.41..0.41, 125, true), ["-0.4", "0", "0.4"]);
        assert_eq!(
            labels(-0.41..0.41, 600, true),
            [
                "-0.4", "-0.3", "-0.2", "-0.1", "0", "0.1", "0.2", "0.3", "0.4"
            ]
        );
        assert_eq!(
            labels(0.0..2603.0, 420, false),
            ["0", "400", "800", "1200", "1600", "2000", "2400"]
        );
    }

    #[test]
    fn a_round_contact_is_drawn_at_equal_scales() {
        let f = fit((2.0, 1.0), (600, 400));
        assert_eq!(f.stretch, (1, 1));
        assert_eq!(f.size, (600, 300));
        let f = fit((1.0, 3.0), (600, 400));
        assert_eq!(f.stretch, (1, 1));
        assert_eq!(f.size, (133, 400));
    }

    #[test]
    fn a_slender_contact_has_its_short_axis_stretched_by_a_whole_factor() {
        // The ball bearing: 0.35 mm across x, 3.2 mm along y (9.1:1).
        let f = fit((0.35, 3.2), (700, 430));
        assert_eq!(f.stretch, (3, 1));
        let drawn = f64::from(f.size.1) / f64::from(f.size.0);
        assert!((drawn - 3.2 / (3.0 * 0.35)).abs() < 0.02, "{drawn}");
        assert!(drawn <= SLENDER);
        // A roller's section: long in x, shallow in depth.
        let f = fit((10.0, 0.5), (700, 430));
        assert_eq!(f.stretch, (1, 5));
        assert_eq!(f.size, (700, 175));
        assert_eq!(axis_name("y", "mm", 3), "y (mm, ×3)");
        assert_eq!(axis_name("y", "mm", 1), "y (mm)");
    }
}
