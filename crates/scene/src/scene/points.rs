//! `[points]`: the candidate points' layout (a disk, a rectangle or a
//! line, absolute or relative to the Hertz contact), each key checked
//! against the grid, and the point set a layout gives at a Hertz scale.

use elcon_analysis::GridFamily;
use elcon_analysis::grid::EllipseExtent;
use elcon_influence::{Dimension, MAX_POINTS, PointSet};
use toml::Spanned;

use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::schema::{Grid, PointsToml};

/// How the candidate points are laid out: in lengths, as the grid family
/// elcon-analysis lays out (the same at any load), or relative to the
/// Hertz contact of the case's load.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum PointsSpec {
    /// A square grid of `spacing` clipped to a disk of `radius`, `nx x ny`
    /// cells on a rectangle, or `n` cells of a line: lengths given.
    Fixed(GridFamily),
    /// Relative to the Hertz contact of the case's load.
    Hertz(HertzLayout),
}

/// A layout relative to the Hertz contact of the case's load: its size
/// follows the contact's radius, half-width or ellipse.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum HertzLayout {
    /// Square grid with `across` points across the Hertz contact diameter,
    /// clipped to `zone` Hertz radii.
    Disk {
        /// Points across the Hertz diameter (odd: the centre is a point).
        across: usize,
        /// Candidate zone over the Hertz radius (> 1).
        zone: f64,
    },
    /// `nx x ny` cells on `[-half_x, half_x] x [-half_y, half_y]`,
    /// `half_x` being `zone` Hertz half-widths of the case's load (a
    /// roller along y).
    Rectangle {
        /// Half-size along x over the Hertz half-width (> 1).
        zone: f64,
        /// Half-size along y (length).
        half_y: f64,
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
    },
    /// Cells with `across` points across the Hertz contact width, out to
    /// `zone` Hertz half-widths.
    Line {
        /// Points across the Hertz width.
        across: usize,
        /// Candidate zone over the Hertz half-width (> 1).
        zone: f64,
    },
    /// A rectangle of cells around an elliptical Hertz contact
    /// (`elcon_analysis::grid::hertz_ellipse_family`), out to `zone` times
    /// its half-extents along x and y: `across` points over each axis of
    /// an ellipse aligned with x and y; square cells with `across` points
    /// over the minor axis of a turned one.
    Ellipse {
        /// Points across each extent (odd: the centre is a point).
        across: usize,
        /// Candidate zone over the ellipse (> 1).
        zone: f64,
        /// The ellipse's shape: fixed by the surfaces, whatever the load.
        shape: EllipseShape,
    },
}

/// An elliptical Hertz contact's shape, its lengths over its equivalent
/// radius `sqrt(a b)` (the Hertz scale of an ellipse grid): the same at
/// any load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseShape {
    /// The half-extent along x over `sqrt(a b)`
    /// (`HertzEllipse::half_extents`).
    pub half_x: f64,
    /// The half-extent along y over `sqrt(a b)`.
    pub half_y: f64,
    /// The semi-minor axis b over `sqrt(a b)`, `sqrt(b / a)`.
    pub semi_minor: f64,
    /// The major axis's direction from x (radians, `HertzEllipse::angle`).
    pub angle: f64,
}

impl EllipseShape {
    /// The shape of a circle: its half-extents and semi-axes are its radius.
    pub const CIRCLE: EllipseShape = EllipseShape {
        half_x: 1.0,
        half_y: 1.0,
        semi_minor: 1.0,
        angle: 0.0,
    };

    /// The lengths at the Hertz scale `r` (the equivalent radius).
    fn extent(&self, r: f64) -> EllipseExtent {
        EllipseExtent {
            half_x: self.half_x * r,
            half_y: self.half_y * r,
            semi_minor: self.semi_minor * r,
        }
    }
}

/// `[points]`: the grid and its parameters, each key checked against the grid.
pub(super) fn points_spec(
    ctx: &Ctx<'_>,
    p: &Spanned<PointsToml>,
) -> Result<(PointsSpec, Dimension), SceneError> {
    let t = p.get_ref();
    let grid = *t.grid.get_ref();
    let allowed: &[&str] = match grid {
        Grid::Disk => &["spacing", "radius", "across", "zone"],
        Grid::Rectangle => &["half_x", "half_y", "nx", "ny", "zone"],
        Grid::Line => &["start", "end", "n", "across", "zone"],
        Grid::Ellipse => &["across", "zone"],
    };
    grid_keys(ctx, t, grid.name(), allowed)?;
    let spec = match grid {
        Grid::Disk => disk_spec(ctx, p)?,
        Grid::Rectangle => rectangle_spec(ctx, p)?,
        Grid::Line => line_spec(ctx, p)?,
        Grid::Ellipse => {
            let a = ctx.required(&t.across, p.span(), "points.across", "for an ellipse")?;
            PointsSpec::Hertz(HertzLayout::Ellipse {
                across: hertz_across(ctx, a)?,
                zone: hertz_zone(ctx, p)?,
                // Set from the surfaces once they are read (super::hertz::shaped).
                shape: EllipseShape::CIRCLE,
            })
        }
    };
    let dimension = if grid == Grid::Line {
        Dimension::Line
    } else {
        Dimension::Surface
    };
    Ok((spec, dimension))
}

/// Every key given under `[points]` must be one of `grid`'s.
fn grid_keys(
    ctx: &Ctx<'_>,
    t: &PointsToml,
    grid: &str,
    allowed: &[&str],
) -> Result<(), SceneError> {
    let span = |v: Option<&Spanned<f64>>| v.map(Spanned::span);
    let count = |v: Option<&Spanned<i64>>| v.map(Spanned::span);
    let given = [
        ("spacing", span(t.spacing.as_ref())),
        ("radius", span(t.radius.as_ref())),
        ("zone", span(t.zone.as_ref())),
        ("half_x", span(t.half_x.as_ref())),
        ("half_y", span(t.half_y.as_ref())),
        ("start", span(t.start.as_ref())),
        ("end", span(t.end.as_ref())),
        ("across", count(t.across.as_ref())),
        ("nx", count(t.nx.as_ref())),
        ("ny", count(t.ny.as_ref())),
        ("n", count(t.n.as_ref())),
    ];
    let given = given
        .into_iter()
        .filter_map(|(key, span)| Some((key, span?, String::new())));
    ctx.allowed_keys("points", &format!("grid = \"{grid}\""), allowed, given)
}

/// `points.zone` (required with `across`): the candidate zone over the
/// Hertz contact, above 1.
fn hertz_zone(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<f64, SceneError> {
    let t = p.get_ref();
    let s = p.span();
    let z = ctx.required(&t.zone, s.clone(), "points.zone", "with across")?;
    let v = ctx.positive(z, "points.zone")?;
    // v is finite: not above 1 is at most 1.
    ctx.ensure(
        v,
        v > 1.0,
        z.span(),
        "points.zone",
        "the candidate zone must extend beyond the Hertz contact (zone > 1), or the contact is cut off",
    )
}

/// `points.across`: odd, at least 3.
fn hertz_across(ctx: &Ctx<'_>, a: &Spanned<i64>) -> Result<usize, SceneError> {
    let n = ctx.count(a, "points.across", 3)?;
    let odd = n % 2 == 1;
    ctx.ensure(
        n,
        odd,
        a.span(),
        "points.across",
        "must be odd (the centre is a point)",
    )
}

/// `across` and `zone`, points across the Hertz contact, when `across` is
/// given; else `None`, `zone` refused (it goes with `across`: points across
/// the Hertz `extent`).
fn hertz_layout(
    ctx: &Ctx<'_>,
    p: &Spanned<PointsToml>,
    extent: &str,
) -> Result<Option<(usize, f64)>, SceneError> {
    let t = p.get_ref();
    match &t.across {
        Some(a) => Ok(Some((hertz_across(ctx, a)?, hertz_zone(ctx, p)?))),
        None => {
            let why = format!("zone goes with across (points across the Hertz {extent})");
            ctx.forbid(&t.zone, "points.zone", &why)?;
            Ok(None)
        }
    }
}

/// A disk: `across` and `zone`, or `spacing` and `radius`.
fn disk_spec(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<PointsSpec, SceneError> {
    let (t, s) = (p.get_ref(), p.span());
    if t.across.is_some() {
        let why = "give either across and zone, or spacing and radius";
        ctx.forbid(&t.spacing, "points.spacing", why)?;
        ctx.forbid(&t.radius, "points.radius", why)?;
    }
    Ok(match hertz_layout(ctx, p, "diameter")? {
        Some((across, zone)) => PointsSpec::Hertz(HertzLayout::Disk { across, zone }),
        None => {
            let why = "for a disk (or across and zone)";
            let h = ctx.required(&t.spacing, s.clone(), "points.spacing", why)?;
            let r = ctx.required(&t.radius, s.clone(), "points.radius", why)?;
            PointsSpec::Fixed(GridFamily::Disk {
                spacing: ctx.positive(h, "points.spacing")?,
                radius: ctx.positive(r, "points.radius")?,
            })
        }
    })
}

/// A rectangle: `half_x` or `zone`, and `half_y`, `nx`, `ny`.
fn rectangle_spec(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<PointsSpec, SceneError> {
    let (t, s) = (p.get_ref(), p.span());
    let half_x = match (&t.half_x, &t.zone) {
        (Some(h), None) => Ok(ctx.positive(h, "points.half_x")?),
        (None, Some(_)) => Err(hertz_zone(ctx, p)?),
        _ => {
            return Err(ctx.invalid(
                s,
                "points.half_x",
                "",
                "give either half_x (length) or zone (Hertz half-widths of the load)",
            ));
        }
    };
    let hy = ctx.required(&t.half_y, s.clone(), "points.half_y", "for a rectangle")?;
    let nx = ctx.required(&t.nx, s.clone(), "points.nx", "for a rectangle")?;
    let ny = ctx.required(&t.ny, s.clone(), "points.ny", "for a rectangle")?;
    let (half_y, nx, ny) = (
        ctx.positive(hy, "points.half_y")?,
        ctx.count(nx, "points.nx", 1)?,
        ctx.count(ny, "points.ny", 1)?,
    );
    // A length, or (the error side) a zone of Hertz half-widths.
    Ok(match half_x {
        Ok(half_x) => PointsSpec::Fixed(GridFamily::Rectangle {
            half_x,
            half_y,
            nx,
            ny,
        }),
        Err(zone) => PointsSpec::Hertz(HertzLayout::Rectangle {
            zone,
            half_y,
            nx,
            ny,
        }),
    })
}

/// A line: `across` and `zone`, or `start`, `end` and `n`.
fn line_spec(ctx: &Ctx<'_>, p: &Spanned<PointsToml>) -> Result<PointsSpec, SceneError> {
    let (t, s) = (p.get_ref(), p.span());
    Ok(match hertz_layout(ctx, p, "width")? {
        Some((across, zone)) => PointsSpec::Hertz(HertzLayout::Line { across, zone }),
        None => {
            let why = "for a line (or across and zone)";
            let a = ctx.required(&t.start, s.clone(), "points.start", why)?;
            let b = ctx.required(&t.end, s.clone(), "points.end", why)?;
            let n = ctx.required(&t.n, s.clone(), "points.n", why)?;
            let (start, end) = (ctx.finite(a, "points.start")?, ctx.finite(b, "points.end")?);
            // Both finite: not above start is at most start.
            let above = end > start;
            let why = format!("must exceed points.start = {}", Num(start));
            let end = ctx.ensure(end, above, b.span(), "points.end", why)?;
            PointsSpec::Fixed(GridFamily::Line {
                start,
                end,
                n: ctx.count(n, "points.n", 1)?,
            })
        }
    })
}

impl PointsSpec {
    /// The grid family of the layout (`elcon_analysis::GridFamily`: the
    /// same zone at any spacing); `scale` is the Hertz radius or half-width
    /// for the relative layouts.
    ///
    /// # Errors
    /// [`SceneError::Points`]: why the layout cannot be made (relative to a
    /// Hertz contact that does not apply, or bad sizes).
    pub fn family(&self, scale: Option<f64>) -> Result<GridFamily, SceneError> {
        let layout = match self {
            PointsSpec::Fixed(family) => return Ok(*family),
            PointsSpec::Hertz(layout) => layout,
        };
        let scale = scale.ok_or_else(|| {
            SceneError::points("the layout is relative to a Hertz contact that does not apply")
        })?;
        let family = match *layout {
            HertzLayout::Disk { across, zone } => {
                elcon_analysis::grid::hertz_disk_family(scale, across, zone)
                    .map_err(SceneError::points)?
            }
            HertzLayout::Rectangle {
                zone,
                half_y,
                nx,
                ny,
            } => GridFamily::Rectangle {
                half_x: zone * scale,
                half_y,
                nx,
                ny,
            },
            HertzLayout::Line { across, zone } => {
                elcon_analysis::grid::hertz_line_family(scale, across, zone)
                    .map_err(SceneError::points)?
            }
            HertzLayout::Ellipse {
                across,
                zone,
                shape,
            } => {
                let family =
                    elcon_analysis::grid::hertz_ellipse_family(shape.extent(scale), across, zone)
                        .map_err(SceneError::points)?;
                return turned_too_many(&shape, across, zone, family);
            }
        };
        Ok(family)
    }

    /// The grid it lays out: a disk, a rectangle, a line or an ellipse's.
    pub(crate) fn grid(&self) -> Grid {
        match self {
            PointsSpec::Fixed(GridFamily::Disk { .. })
            | PointsSpec::Hertz(HertzLayout::Disk { .. }) => Grid::Disk,
            PointsSpec::Fixed(GridFamily::Rectangle { .. })
            | PointsSpec::Hertz(HertzLayout::Rectangle { .. }) => Grid::Rectangle,
            PointsSpec::Hertz(HertzLayout::Ellipse { .. }) => Grid::Ellipse,
            // A layout in lengths is a disk, a rectangle or a line.
            PointsSpec::Hertz(HertzLayout::Line { .. }) | PointsSpec::Fixed(_) => Grid::Line,
        }
    }

    /// The rectangle's half-size along y (length), on a rectangle.
    pub(crate) fn half_y(&self) -> Option<f64> {
        match *self {
            PointsSpec::Fixed(GridFamily::Rectangle { half_y, .. })
            | PointsSpec::Hertz(HertzLayout::Rectangle { half_y, .. }) => Some(half_y),
            _ => None,
        }
    }
}

/// The family of an ellipse grid, or why a turned ellipse's grid is not
/// laid out: square cells spanning its minor axis take more than
/// `MAX_POINTS` points when the ellipse is slender. The message says
/// what turning the surfaces to lay the ellipse along x or y would need.
fn turned_too_many(
    shape: &EllipseShape,
    across: usize,
    zone: f64,
    family: GridFamily,
) -> Result<GridFamily, SceneError> {
    let Ok(GridFamily::Rectangle { nx, ny, .. }) = family.rectangle() else {
        return Ok(family);
    };
    let count = nx as f64 * ny as f64;
    if !shape.extent(1.0).is_turned() || count <= MAX_POINTS as f64 {
        return Ok(family);
    }
    Err(SceneError::points(format!(
        "{} = {} points, more than {MAX_POINTS}, the most elcon lays out. {}",
        turned_cells(shape, across, (nx, ny)),
        Num(count),
        align_hint(shape, across, zone)
    )))
}

/// "the Hertz ellipse is turned by 30.00 degrees from x ...: a grid with
/// 31 points across its minor axis in every direction needs 11 x 13".
fn turned_cells(shape: &EllipseShape, across: usize, (nx, ny): (usize, usize)) -> String {
    format!(
        "the Hertz ellipse is turned by {} degrees from x (its semi-axes {:.1} : 1): a grid \
         with {across} points across its minor axis in every direction needs {nx} x {ny}",
        degrees(shape.angle.to_degrees()),
        1.0 / shape.semi_minor.powi(2),
    )
}

/// The smallest turn (degrees, in [-45, 45]) that lays an ellipse whose
/// major axis is at `angle` (radians, in (-90, 90] degrees) from x along a
/// grid axis, and that axis: the grid lays an aligned ellipse out with
/// `across` points over each axis whether its major axis is along x or
/// along y, so the turn is `-angle` (along x) or `90 - angle` taken
/// modulo 180 (along y), whichever is smaller.
pub(crate) fn aligning_turn(angle: f64) -> (f64, &'static str) {
    let degrees = angle.to_degrees();
    let along_x = -degrees;
    // 90 - angle, brought into (-90, 90].
    let along_y = if degrees > 0.0 {
        90.0 - degrees
    } else {
        -90.0 - degrees
    };
    if along_x.abs() <= along_y.abs() {
        (along_x, "x")
    } else {
        (along_y, "y")
    }
}

/// An angle in degrees as a message gives it: two decimals (`30.00`),
/// and two significant digits for a turn below a hundredth of a degree
/// (`0.00010`), which two decimals would show as no turn at all.
fn degrees(d: f64) -> String {
    // Rounded to two significant digits first, so that 9.99999e-5 is
    // counted as the 1.0e-4 it shows as.
    let rounded: f64 = format!("{d:.1e}").parse().unwrap_or(d);
    let decimals = if !(d.abs() < 0.01) || rounded == 0.0 {
        2
    } else {
        (1.0 - rounded.abs().log10().floor()).clamp(2.0, 20.0) as usize
    };
    format!("{d:.decimals$}")
}

/// What turning the surfaces to lay the ellipse along a grid axis does
/// ([`aligning_turn`]).
fn align_hint(shape: &EllipseShape, across: usize, zone: f64) -> String {
    let (turn, axis) = aligning_turn(shape.angle);
    format!(
        "Turning both surfaces by {} degrees (add it to each quadric's `angle`; a sphere \
         needs none) lays the ellipse along {axis}, where the grid needs about (across zone)^2 = \
         {} points",
        degrees(turn),
        Num((across as f64 * zone).powi(2).round())
    )
}

/// A note for an ellipse grid around a turned ellipse that has more than
/// [`TURNED_NOTE_RATIO`] times the points the aligned ellipse's grid
/// would: the smallest turn that lays it along x or y.
pub(crate) fn turned_note(spec: &PointsSpec, points: &PointSet) -> Option<String> {
    let PointsSpec::Hertz(HertzLayout::Ellipse {
        across,
        zone,
        shape,
    }) = *spec
    else {
        return None;
    };
    let aligned = (across as f64 * zone).powi(2);
    if !shape.extent(1.0).is_turned() || (points.len() as f64) < TURNED_NOTE_RATIO * aligned {
        return None;
    }
    let ((ex, ey), cell) = (points.extent(), points.cell());
    let (nx, ny) = (
        (ex / cell.dx).round() as usize,
        (ey / cell.dy).round() as usize,
    );
    Some(format!(
        "{} = {} points. {}",
        turned_cells(&shape, across, (nx, ny)),
        points.len(),
        align_hint(&shape, across, zone)
    ))
}

/// How many times the aligned ellipse's grid's points a turned ellipse's
/// grid has before `check` notes the turn that would save them.
pub const TURNED_NOTE_RATIO: f64 = 4.0;

/// Builds the point set of the layout's family ([`PointsSpec::family`]);
/// `scale` is the Hertz radius or half-width for the relative layouts.
pub(crate) fn build_points(spec: &PointsSpec, scale: Option<f64>) -> Result<PointSet, SceneError> {
    spec.family(scale)?
        .points()
        .map_err(|e| SceneError::points(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_below_a_hundredth_of_a_degree_is_shown_as_a_turn() {
        assert_eq!(degrees(30.0), "30.00");
        assert_eq!(degrees(-0.0001), "-0.00010");
        assert_eq!(degrees(0.0123), "0.01");
        assert_eq!(degrees(0.00999), "0.010");
        assert_eq!(degrees(0.0), "0.00");
    }

    #[test]
    fn the_aligning_turn_is_the_smaller_of_the_turns_to_x_and_to_y() {
        let turn = |degrees: f64| aligning_turn(degrees.to_radians());
        let close = |(a, axis): (f64, &str), (b, expected): (f64, &str)| {
            (a - b).abs() < 1e-9 && axis == expected
        };
        // An ellipse at -70 degrees: -20 lays it along y, not 70 along x.
        assert!(close(turn(-70.0), (-20.0, "y")), "{:?}", turn(-70.0));
        assert!(close(turn(70.0), (20.0, "y")), "{:?}", turn(70.0));
        assert!(close(turn(30.0), (-30.0, "x")), "{:?}", turn(30.0));
        assert!(close(turn(-30.0), (30.0, "x")), "{:?}", turn(-30.0));
        assert!(close(turn(90.0), (0.0, "y")), "{:?}", turn(90.0));
        // Never more than 45 degrees.
        for k in -89..=90 {
            assert!(turn(f64::from(k)).0.abs() <= 45.0 + 1e-9, "{k}");
        }
    }
}
