//! Candidate points laid out relative to a Hertz contact, as a scene's
//! `across` and `zone` do.
//!
//! With the Hertz contact radius a (or half-width b on a line), `across`
//! points span the contact's diameter, so the spacing is
//!
//! ```text
//!     h = 2 a / (across - 1)
//! ```
//!
//! and the outermost points of a diameter sit on the Hertz circle; the
//! candidate zone reaches `zone` times a (or b) from the centre. A zone
//! above 1 leaves room for a contact larger than Hertz's (a coarse grid, a
//! misalignment, a load centre off the middle).
//!
//! Every layout is a member of a [`GridFamily`]: the same zone at any
//! spacing, refined or coarsened (`crate::discretization` solves a problem
//! on the coarser members to estimate its discretization error).

use elcon_influence::PointSet;

use crate::AnalysisError;

/// Checks `across` (at least 2) and `zone` (finite, at least 1) and the
/// size (finite, > 0); the spacing `2 size / (across - 1)`.
fn spacing(size: f64, across: usize, zone: f64) -> Result<f64, AnalysisError> {
    elcon_num::check([
        (
            size.is_finite() && size > 0.0,
            "contact size",
            size,
            "the Hertz radius or half-width must be finite and > 0",
        ),
        (
            across >= 2,
            "across",
            across as f64,
            "at least 2 points across the contact",
        ),
        (
            zone.is_finite() && zone >= 1.0,
            "zone",
            zone,
            "the candidate zone must be finite and at least the contact (zone >= 1)",
        ),
    ])?;
    Ok(2.0 * size / (across - 1) as f64)
}

/// The family of [`hertz_disk`]: a square lattice of spacing
/// `2 contact_radius / (across - 1)` clipped to the disk of
/// `zone * contact_radius`.
///
/// # Errors
/// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the contact
/// size.
pub fn hertz_disk_family(
    contact_radius: f64,
    across: usize,
    zone: f64,
) -> Result<GridFamily, AnalysisError> {
    let h = spacing(contact_radius, across, zone)?;
    Ok(GridFamily::Disk {
        spacing: h,
        radius: zone * contact_radius,
    })
}

/// A square grid on a disk around the origin: `across` points over the
/// diameter of a Hertz contact of radius `contact_radius`, out to
/// `zone * contact_radius` (the scenes' `grid = "disk"` with `across`,
/// `zone`): the points of [`hertz_disk_family`].
///
/// # Errors
/// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the contact
/// size; [`AnalysisError::Influence`] when the grid has too many points.
///
/// ```
/// use elcon_analysis::grid;
/// let points = grid::hertz_disk(0.0134, 21, 1.2).unwrap();
/// // The spacing is 2 a / 20; the outermost points of a diameter lie on the circle.
/// assert!((points.xs().iter().cloned().fold(0.0, f64::max) / 0.0134 - 1.2).abs() < 0.1);
/// ```
pub fn hertz_disk(
    contact_radius: f64,
    across: usize,
    zone: f64,
) -> Result<PointSet, AnalysisError> {
    hertz_disk_family(contact_radius, across, zone)?.points()
}

/// The family of [`hertz_line`]: `2 m + 1` cells of `h = 2 half_width /
/// (across - 1)` centred on the origin, `m = round(zone half_width / h)`
/// (at least 1).
///
/// # Errors
/// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the contact
/// size; `zone` or `across`, whichever is the larger factor of the count,
/// when the line would have more than `MAX_POINTS` points.
pub fn hertz_line_family(
    half_width: f64,
    across: usize,
    zone: f64,
) -> Result<GridFamily, AnalysisError> {
    let family = GridFamily::HertzLine {
        half_width,
        across,
        zone,
    };
    family.line()?;
    Ok(family)
}

/// The half-length `(m + 1/2) h` and the count `2 m + 1` of the cells of
/// [`GridFamily::HertzLine`] over a contact of half-size `size`.
fn centred_cells(size: f64, across: usize, zone: f64) -> Result<(f64, usize), AnalysisError> {
    let h = spacing(size, across, zone)?;
    cells_of(size, h, across, zone)
}

/// `2 m + 1` cells of the spacing `h` centred on the origin over the
/// half-length `(m + 1/2) h`, `m = round(zone extent / h)` (at least 1).
fn cells_of(extent: f64, h: f64, across: usize, zone: f64) -> Result<(f64, usize), AnalysisError> {
    let m = (zone * extent / h).round().max(1.0);
    if !(m <= elcon_influence::MAX_POINTS as f64) {
        // m = zone (across - 1) / 2: blame the factor that makes it big.
        let zone_is_larger = zone >= (across - 1) as f64;
        return Err(AnalysisError::InvalidInput {
            field: if zone_is_larger { "zone" } else { "across" },
            value: if zone_is_larger { zone } else { across as f64 },
            reason: "the line would hold more than 4,194,304 points, the most elcon lays out \
                     (the count is about zone * (across - 1))",
        });
    }
    Ok(((m + 0.5) * h, 2 * m as usize + 1))
}

/// Points on a line, centred: `across` over the width `2 half_width` of a
/// Hertz line contact, a whole number of spacings out to about
/// `zone * half_width` on each side (the scenes' `grid = "line"` with
/// `across`, `zone`): the points of [`hertz_line_family`].
///
/// # Errors
/// As [`hertz_line_family`]; [`AnalysisError::Influence`] when the points
/// cannot be laid out.
pub fn hertz_line(half_width: f64, across: usize, zone: f64) -> Result<PointSet, AnalysisError> {
    hertz_line_family(half_width, across, zone)?.points()
}

/// The size of an elliptical Hertz contact a grid is laid around
/// ([`hertz_ellipse_family`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseExtent {
    /// The ellipse's half-extent along x (length):
    /// `sqrt(a^2 c^2 + b^2 s^2)` for semi-axes a, b turned by an angle of
    /// cosine c and sine s.
    pub half_x: f64,
    /// The ellipse's half-extent along y (length):
    /// `sqrt(a^2 s^2 + b^2 c^2)`.
    pub half_y: f64,
    /// The semi-minor axis b (length).
    pub semi_minor: f64,
}

impl EllipseExtent {
    /// Whether the ellipse is turned from x and y: its smaller half-extent
    /// exceeds its semi-minor axis by more than rounding
    /// ([`ALIGNED_TOLERANCE`] relative). An aligned ellipse's half-extents
    /// are its semi-axes.
    pub fn is_turned(&self) -> bool {
        self.half_x.min(self.half_y) > self.semi_minor * (1.0 + ALIGNED_TOLERANCE)
    }
}

/// The candidate zone's extent across an elliptical Hertz contact's minor
/// axis (semi-minor axis `semi_minor`), in the ellipse's own frame: the
/// `(2 m + 1) h` of [`hertz_ellipse_family`]'s cells along the minor axis
/// of an aligned ellipse, `h = 2 b / (across - 1)`, `m = round(zone b /
/// h)`. Turned or not, the ellipse gets the same spacing across its minor
/// axis, so this is the same at any turn (what an approach is measured
/// against for the small strain).
///
/// # Errors
/// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the contact
/// size.
pub fn ellipse_minor_zone(semi_minor: f64, across: usize, zone: f64) -> Result<f64, AnalysisError> {
    centred_cells(semi_minor, across, zone).map(|(half, _)| 2.0 * half)
}

/// How far (relative) an ellipse's smaller half-extent may exceed its
/// semi-minor axis and still count as aligned with x and y: the rounding
/// of the half-extents `sqrt(a^2 c^2 + b^2 s^2)` computed from an angle
/// that is a multiple of 90 degrees to rounding, and of their scaling
/// with the load.
pub const ALIGNED_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// The family of an elliptical Hertz contact's grid: a rectangle of cells
/// aligned with x and y around the ellipse, out to `zone` times its
/// half-extents along x and y, centred on the origin as
/// [`hertz_line_family`] lays a line out (`2 m + 1` cells of `h` along an
/// axis of half-extent e, `m = round(zone e / h)`).
///
/// - Aligned with x and y (a, b along the axes): along each axis
///   `h = 2 e / (across - 1)`, so `across` points span each axis and the
///   cells are as long as the ellipse is (`dx / dy = a / b`); the grid has
///   about `(across zone)^2` points whatever the slenderness.
/// - Turned ([`EllipseExtent::is_turned`]): square cells of
///   `h = 2 b / (across - 1)`, so `across` points span the minor axis in
///   every direction (cells sized by the half-extents would be wider than
///   a slender turned ellipse). The grid has about
///   `(across zone)^2 ex ey / b^2` points: many for a slender ellipse
///   (turning the surfaces to lay it along x is the cheap layout).
///
/// # Errors
/// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the contact
/// size.
pub fn hertz_ellipse_family(
    extent: EllipseExtent,
    across: usize,
    zone: f64,
) -> Result<GridFamily, AnalysisError> {
    let family = GridFamily::HertzEllipse {
        extent,
        across,
        zone,
    };
    family.rectangle()?;
    Ok(family)
}

/// The rectangle of cells an elliptical Hertz contact's grid lays out
/// ([`hertz_ellipse_family`]).
fn ellipse_rectangle(
    extent: EllipseExtent,
    across: usize,
    zone: f64,
) -> Result<GridFamily, AnalysisError> {
    let ((half_x, nx), (half_y, ny)) = if extent.is_turned() {
        let h = spacing(extent.semi_minor, across, zone)?;
        (
            cells_of(extent.half_x, h, across, zone)?,
            cells_of(extent.half_y, h, across, zone)?,
        )
    } else {
        (
            centred_cells(extent.half_x, across, zone)?,
            centred_cells(extent.half_y, across, zone)?,
        )
    };
    Ok(GridFamily::Rectangle {
        half_x,
        half_y,
        nx,
        ny,
    })
}

/// The smallest number of points (cells) along an axis that
/// [`GridFamily::coarser`] leaves a grid: a coarser grid of fewer is not
/// made (`None`).
pub const MIN_COARSE_COUNT: usize = 3;

/// A grid and the family it belongs to: the same candidate zone at any
/// spacing. [`GridFamily::points`] lays the points out;
/// [`GridFamily::refined`] and [`GridFamily::coarser`] give the same zone
/// at another spacing (a refinement study, a discretization error
/// estimate: `crate::discretization`).
///
/// Coarser grids (about twice the spacing, a point or the middle cell kept
/// at the centre):
///
/// ```text
///     Disk        h' = 2 h, the same radius (the origin stays a point)
///     Rectangle   n' = the integer nearest n / 2 with the parity of n (each of nx, ny)
///     Line        n' = the integer nearest n / 2 with the parity of n
///     HertzLine   across' - 1 = (across - 1) / 2 (rounded up): spacing 2h exactly
/// ```
///
/// (an even n whose half is odd has two such integers; the larger is
/// taken, a ratio of `n / n' < 2`). Keeping the parity keeps the centre a
/// point (n odd) or a cell face (n even), so a symmetric problem stays
/// symmetric on every grid. No coarser grid is made with fewer than
/// [`MIN_COARSE_COUNT`] points along an axis (a disk's diameter, a count).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum GridFamily {
    /// a square lattice of `spacing`, the origin on a point, clipped to a disk of `radius`
    Disk {
        /// The spacing h (length).
        spacing: f64,
        /// The radius of the candidate disk (length).
        radius: f64,
    },
    /// nx x ny cells on [-half_x, half_x] x [-half_y, half_y]
    Rectangle {
        /// Half-size along x (length).
        half_x: f64,
        /// Half-size along y (length).
        half_y: f64,
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
    },
    /// n cells on [start, end] of the x axis
    Line {
        /// Start (length).
        start: f64,
        /// End (length).
        end: f64,
        /// Number of cells.
        n: usize,
    },
    /// `across` points over each axis of an elliptical Hertz contact, out
    /// to `zone` times it ([`hertz_ellipse_family`]). Coarsened by
    /// `across - 1` halved, as [`GridFamily::HertzLine`]: the spacing
    /// doubles exactly and the ellipse's ends keep their place among the
    /// cells.
    HertzEllipse {
        /// The ellipse's size.
        extent: EllipseExtent,
        /// Points across each axis.
        across: usize,
        /// The zone over the ellipse.
        zone: f64,
    },
    /// `across` points over a Hertz line contact's width `2 half_width`, a
    /// whole number of spacings out to about `zone * half_width` on each
    /// side ([`hertz_line`]). Coarsened by `across - 1` halved, so the
    /// spacing doubles exactly and the contact's edge keeps its place
    /// among the cells (on a point for an odd `across`).
    HertzLine {
        /// The Hertz half-width b (length).
        half_width: f64,
        /// Points across the contact's width.
        across: usize,
        /// The zone's half-length over b.
        zone: f64,
    },
}

impl std::fmt::Display for GridFamily {
    /// "9 x 40 cells", "80 cells", "spacing 0.001 on a disk of radius 0.02".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            GridFamily::Disk { spacing, radius } => {
                write!(f, "spacing {spacing:e} on a disk of radius {radius:e}")
            }
            GridFamily::Rectangle { nx, ny, .. } => write!(f, "{nx} x {ny} cells"),
            GridFamily::Line { n, .. } => write!(f, "{n} cells"),
            GridFamily::HertzEllipse { across, .. } => match self.rectangle() {
                Ok(GridFamily::Rectangle { nx, ny, .. }) => write!(f, "{nx} x {ny} cells"),
                _ => write!(f, "{across} points across an ellipse"),
            },
            GridFamily::HertzLine { across, .. } => write!(f, "{across} points across"),
        }
    }
}

impl GridFamily {
    /// The grid's points: bit for bit those of [`PointSet::grid_disk`],
    /// [`PointSet::grid_rectangle`] and [`PointSet::line`].
    ///
    /// # Errors
    /// [`AnalysisError::Influence`] as those constructors refuse (a size
    /// not finite and positive, a count of 0, more than `MAX_POINTS`).
    pub fn points(&self) -> Result<PointSet, AnalysisError> {
        Ok(match *self {
            GridFamily::Disk { spacing, radius } => PointSet::grid_disk(spacing, radius)?,
            GridFamily::Rectangle {
                half_x,
                half_y,
                nx,
                ny,
            } => PointSet::grid_rectangle(half_x, half_y, nx, ny)?,
            GridFamily::Line { start, end, n } => PointSet::line(start, end, n)?,
            GridFamily::HertzLine { .. } | GridFamily::HertzEllipse { .. } => {
                return self.laid_out()?.points();
            }
        })
    }

    /// A [`GridFamily::HertzEllipse`] as the [`GridFamily::Rectangle`] it
    /// lays out (any other family as it is).
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the
    /// contact size.
    pub fn rectangle(&self) -> Result<GridFamily, AnalysisError> {
        match *self {
            GridFamily::HertzEllipse {
                extent,
                across,
                zone,
            } => ellipse_rectangle(extent, across, zone),
            other => Ok(other),
        }
    }

    /// A [`GridFamily::HertzLine`] as the [`GridFamily::Line`] it lays out
    /// (any other family as it is).
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming `across`, `zone` or the
    /// contact size.
    pub fn line(&self) -> Result<GridFamily, AnalysisError> {
        match *self {
            GridFamily::HertzLine {
                half_width,
                across,
                zone,
            } => {
                let (half, n) = centred_cells(half_width, across, zone)?;
                Ok(GridFamily::Line {
                    start: -half,
                    end: half,
                    n,
                })
            }
            other => Ok(other),
        }
    }

    /// The representative spacing h: the disk's spacing, `sqrt(dx dy)` of
    /// a rectangle's cells, a line's `dx = (end - start) / n`.
    pub fn spacing(&self) -> f64 {
        match *self {
            GridFamily::Disk { spacing, .. } => spacing,
            GridFamily::Rectangle {
                half_x,
                half_y,
                nx,
                ny,
            } => (2.0 * half_x / nx as f64 * 2.0 * half_y / ny as f64).sqrt(),
            GridFamily::Line { start, end, n } => (end - start) / n as f64,
            GridFamily::HertzLine {
                half_width, across, ..
            } => 2.0 * half_width / (across.max(2) - 1) as f64,
            GridFamily::HertzEllipse { .. } => self.rectangle().map_or(f64::NAN, |r| r.spacing()),
        }
    }

    /// The same zone at the spacing over `factor`: a disk's spacing
    /// `h / factor`; each count `round(n factor)`, at least 1.
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming `factor` when it is not
    /// finite and > 0, or a count would overflow.
    pub fn refined(&self, factor: f64) -> Result<GridFamily, AnalysisError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(AnalysisError::InvalidInput {
                field: "factor",
                value: factor,
                reason: "a refinement factor must be finite and > 0",
            });
        }
        let count = |n: usize| -> Result<usize, AnalysisError> {
            let m = (n as f64 * factor).round().max(1.0);
            if m <= elcon_influence::MAX_POINTS as f64 {
                Ok(m as usize)
            } else {
                Err(AnalysisError::InvalidInput {
                    field: "factor",
                    value: factor,
                    reason: "the refined grid would have more than 4,194,304 cells along an axis, \
                             the most elcon lays out",
                })
            }
        };
        Ok(match *self {
            GridFamily::Disk { spacing, radius } => GridFamily::Disk {
                spacing: spacing / factor,
                radius,
            },
            GridFamily::Rectangle {
                half_x,
                half_y,
                nx,
                ny,
            } => GridFamily::Rectangle {
                half_x,
                half_y,
                nx: count(nx)?,
                ny: count(ny)?,
            },
            GridFamily::Line { start, end, n } => GridFamily::Line {
                start,
                end,
                n: count(n)?,
            },
            GridFamily::HertzLine { across, .. } | GridFamily::HertzEllipse { across, .. } => {
                self.with_across(count(across.max(2) - 1)? + 1)
            }
        })
    }

    /// The same zone at about twice the spacing, a point (or the middle
    /// cell) kept at the centre (see the type's documentation): `None`
    /// when it would have fewer than [`MIN_COARSE_COUNT`] points along an
    /// axis.
    pub fn coarser(&self) -> Option<GridFamily> {
        // A Hertz layout's spacings across halved (rounded up when odd: an
        // even `across` straddles the edge on every grid).
        self.scaled(2.0, half_count, |spans| spans.div_ceil(2))
    }

    /// The same zone at about `sqrt 2` times the spacing, between this
    /// grid and its [`GridFamily::coarser`] (the least-squares estimate's
    /// grids, `crate::discretization::fitted`): a disk's spacing times
    /// `sqrt 2`; each count the integer nearest `n / sqrt 2` with the
    /// parity of n (the centre kept a point or a cell face); a Hertz
    /// layout's `across - 1` likewise. `None` when it would have fewer
    /// than [`MIN_COARSE_COUNT`] points along an axis.
    pub fn intermediate(&self) -> Option<GridFamily> {
        let r = std::f64::consts::SQRT_2;
        let count = |n: usize| {
            let m = parity_nearest(n as f64 / r, n);
            (m >= MIN_COARSE_COUNT).then_some(m)
        };
        self.scaled(r, count, |spans| {
            parity_nearest(spans as f64 / r, spans).max(2)
        })
    }

    /// The same zone at `ratio` times the spacing: a disk's spacing times
    /// `ratio`, each count of a rectangle or a line by `count`, a Hertz
    /// layout's spacings across (`across - 1`) by `spans`; `None` when it
    /// would have fewer than [`MIN_COARSE_COUNT`] points along an axis (or
    /// a Hertz layout fewer than 3 across, or no fewer than its own).
    fn scaled(
        &self,
        ratio: f64,
        count: impl Fn(usize) -> Option<usize>,
        spans: impl Fn(usize) -> usize,
    ) -> Option<GridFamily> {
        match *self {
            GridFamily::Disk { spacing, radius } => {
                let h = ratio * spacing;
                // The points of a diameter, as PointSet::grid_disk counts them.
                let m = (radius / h * (1.0 + 1e-9)).floor();
                (2.0 * m + 1.0 >= MIN_COARSE_COUNT as f64)
                    .then_some(GridFamily::Disk { spacing: h, radius })
            }
            GridFamily::Rectangle {
                half_x,
                half_y,
                nx,
                ny,
            } => Some(GridFamily::Rectangle {
                half_x,
                half_y,
                nx: count(nx)?,
                ny: count(ny)?,
            }),
            GridFamily::Line { start, end, n } => Some(GridFamily::Line {
                start,
                end,
                n: count(n)?,
            }),
            GridFamily::HertzLine { across, .. } | GridFamily::HertzEllipse { across, .. } => {
                let own = across.max(2) - 1;
                let fewer = spans(own);
                let grid = self.with_across(fewer + 1);
                let smallest = match grid.laid_out().ok()? {
                    GridFamily::Line { n, .. } => n,
                    GridFamily::Rectangle { nx, ny, .. } => nx.min(ny),
                    _ => return None,
                };
                (smallest >= MIN_COARSE_COUNT && fewer >= 2 && fewer < own).then_some(grid)
            }
        }
    }

    /// A Hertz layout with `across` points across its contact (any other
    /// family as it is).
    fn with_across(self, across: usize) -> GridFamily {
        match self {
            GridFamily::HertzLine {
                half_width, zone, ..
            } => GridFamily::HertzLine {
                half_width,
                across,
                zone,
            },
            GridFamily::HertzEllipse { extent, zone, .. } => GridFamily::HertzEllipse {
                extent,
                across,
                zone,
            },
            other => other,
        }
    }

    /// The line or rectangle a Hertz layout lays out (any other family as
    /// it is).
    fn laid_out(&self) -> Result<GridFamily, AnalysisError> {
        match self {
            GridFamily::HertzLine { .. } => self.line(),
            GridFamily::HertzEllipse { .. } => self.rectangle(),
            other => Ok(*other),
        }
    }

    /// The same zone at half the spacing, the inverse of
    /// [`GridFamily::coarser`]: its coarser grid is this one. Four times
    /// the points on a surface, twice on a line.
    pub fn finer(&self) -> GridFamily {
        match *self {
            GridFamily::Disk { spacing, radius } => GridFamily::Disk {
                spacing: 0.5 * spacing,
                radius,
            },
            GridFamily::Rectangle {
                half_x,
                half_y,
                nx,
                ny,
            } => GridFamily::Rectangle {
                half_x,
                half_y,
                nx: double_count(nx),
                ny: double_count(ny),
            },
            GridFamily::Line { start, end, n } => GridFamily::Line {
                start,
                end,
                n: double_count(n),
            },
            GridFamily::HertzLine { across, .. } | GridFamily::HertzEllipse { across, .. } => {
                self.with_across(2 * across.max(2) - 1)
            }
        }
    }
}

/// The integer nearest `t` with the parity of `n`.
fn parity_nearest(t: f64, n: usize) -> usize {
    let parity = (n % 2) as f64;
    (2.0 * ((t - parity) / 2.0).round() + parity).max(parity) as usize
}

/// The count whose [`half_count`] is `n`: `2n - 1` for an odd `n` (a point
/// stays at the centre), `2n` for an even one.
fn double_count(n: usize) -> usize {
    if n % 2 == 1 { 2 * n - 1 } else { 2 * n }
}

/// The integer nearest `n / 2` with the parity of `n` (the larger of two),
/// or `None` below [`MIN_COARSE_COUNT`].
fn half_count(n: usize) -> Option<usize> {
    let half = n / 2;
    let m = if half % 2 == n % 2 { half } else { half + 1 };
    (m >= MIN_COARSE_COUNT).then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spacing_puts_the_outermost_points_of_a_diameter_on_the_circle() {
        let a = 2.0;
        let points = hertz_disk(a, 11, 1.0).unwrap();
        // h = 2 a / 10: points at multiples of 0.4 out to the radius.
        let on_axis: Vec<f64> = (0..points.len())
            .filter(|&k| points.y(k).abs() < 1e-12)
            .map(|k| points.x(k))
            .collect();
        let largest = on_axis.iter().cloned().fold(0.0, f64::max);
        assert!((largest - a).abs() < 1e-12, "{largest}");
        assert_eq!(on_axis.len(), 11);
        let line = hertz_line(1.0, 21, 1.5).unwrap();
        assert_eq!(line.len(), 31);
    }

    /// The extents of semi-axes `(a, b)` turned by `angle` from x.
    fn extent_of(a: f64, b: f64, angle: f64) -> EllipseExtent {
        let (s, c) = angle.sin_cos();
        EllipseExtent {
            half_x: (a * c).hypot(b * s),
            half_y: (a * s).hypot(b * c),
            semi_minor: b,
        }
    }

    #[test]
    fn a_turned_ellipse_gets_square_cells_spanning_its_minor_axis() {
        let (a, b, across, zone) = (4.0, 0.5, 11, 1.2);
        let turned = extent_of(a, b, 30f64.to_radians());
        assert!(turned.is_turned());
        let GridFamily::Rectangle {
            half_x,
            half_y,
            nx,
            ny,
        } = hertz_ellipse_family(turned, across, zone)
            .and_then(|f| f.rectangle())
            .unwrap()
        else {
            panic!("a rectangle");
        };
        let (dx, dy) = (2.0 * half_x / nx as f64, 2.0 * half_y / ny as f64);
        assert!((dx - dy).abs() <= 4.0 * f64::EPSILON * dx, "{dx} {dy}");
        // The minor axis 2 b, in any direction, spans at least across - 1 cells.
        let cells = 2.0 * b / dx.max(dy);
        assert!(
            cells >= (across - 1) as f64 * (1.0 - 1e3 * f64::EPSILON),
            "{cells}"
        );
        // Cells sized by the half-extent along x would be 6.9 times wider.
        assert!(2.0 * turned.half_x / (across - 1) as f64 > 6.0 * dx);
        // The zone still covers zone times the half-extents (to half a cell).
        assert!(half_x >= zone * turned.half_x - 0.5 * dx);
        assert!(half_y >= zone * turned.half_y - 0.5 * dy);
    }

    #[test]
    fn the_zone_across_the_minor_axis_is_the_aligned_grid_s_whatever_the_turn() {
        let (a, b, across, zone) = (4.0, 0.5, 11, 1.2);
        let minor = ellipse_minor_zone(b, across, zone).unwrap();
        // Aligned along x: the grid's extent along y is the zone across b.
        let GridFamily::Rectangle { half_y, .. } =
            hertz_ellipse_family(extent_of(a, b, 0.0), across, zone)
                .and_then(|f| f.rectangle())
                .unwrap()
        else {
            panic!("a rectangle");
        };
        assert_eq!(minor, 2.0 * half_y);
        // Turned by 30 degrees the grid's extents are larger, the minor
        // axis the same; 2 m + 1 = 13 cells of 0.1 here.
        let GridFamily::Rectangle { half_x, half_y, .. } =
            hertz_ellipse_family(extent_of(a, b, 30f64.to_radians()), across, zone)
                .and_then(|f| f.rectangle())
                .unwrap()
        else {
            panic!("a rectangle");
        };
        assert!(2.0 * half_x.min(half_y) > 2.0 * minor);
        assert!((minor - 1.3).abs() < 1e-12, "{minor}");
        assert!(ellipse_minor_zone(b, 1, zone).is_err());
    }

    #[test]
    fn an_ellipse_family_coarsens_across_so_the_spacing_doubles_exactly() {
        let (a, b, zone) = (4.0, 0.5, 1.2);
        let family = hertz_ellipse_family(extent_of(a, b, 0.0), 41, zone).unwrap();
        let coarse = family.coarser().unwrap();
        assert!(
            matches!(coarse, GridFamily::HertzEllipse { across: 21, .. }),
            "{coarse:?}"
        );
        let ratio = coarse.spacing() / family.spacing();
        assert!((ratio - 2.0).abs() < 1e-12, "{ratio}");
        assert_eq!(coarse.finer(), family);
        assert_eq!(family.points().unwrap().len(), {
            let GridFamily::Rectangle { nx, ny, .. } = family.rectangle().unwrap() else {
                panic!("a rectangle");
            };
            nx * ny
        });
    }

    #[test]
    fn an_aligned_ellipse_keeps_across_points_over_each_axis() {
        let (a, b, across, zone) = (4.0, 0.5, 11, 1.2);
        for angle in [0.0, std::f64::consts::FRAC_PI_2] {
            let aligned = extent_of(a, b, angle);
            assert!(!aligned.is_turned(), "{angle}");
            let family = hertz_ellipse_family(aligned, across, zone)
                .and_then(|f| f.rectangle())
                .unwrap();
            let (hx, nx) = centred_cells(aligned.half_x, across, zone).unwrap();
            let (hy, ny) = centred_cells(aligned.half_y, across, zone).unwrap();
            assert_eq!(
                family,
                GridFamily::Rectangle {
                    half_x: hx,
                    half_y: hy,
                    nx,
                    ny
                }
            );
            // dx / dy = a / b (or b / a): not square.
            let GridFamily::Rectangle { half_x, nx, .. } = family else {
                unreachable!()
            };
            let dx = 2.0 * half_x / nx as f64;
            let along_x = aligned.half_x;
            assert!((dx - 2.0 * along_x / (across - 1) as f64).abs() <= 1e-12 * dx);
        }
    }

    #[test]
    fn bad_layouts_name_the_field() {
        for (e, field) in [
            (hertz_disk(1.0, 1, 1.2), "across"),
            (hertz_disk(1.0, 11, 0.5), "zone"),
            (hertz_disk(f64::NAN, 11, 1.2), "contact size"),
            (hertz_line(-1.0, 11, 1.2), "contact size"),
            (hertz_line(1.0, 101, 1.3e300), "zone"),
            (hertz_line(1.0, 20_000_001, 1.5), "across"),
        ] {
            match e {
                Err(AnalysisError::InvalidInput { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        let e = hertz_line(1.0, 101, 1.3e300).unwrap_err().to_string();
        assert!(e.contains("4,194,304 points") && !e.contains("MAX_"), "{e}");
    }

    #[test]
    fn a_hertz_line_coarsens_by_doubling_its_spacing_with_the_edge_on_a_point() {
        let b = 0.3;
        let family = hertz_line_family(b, 41, 1.3).unwrap();
        assert_eq!(family.to_string(), "41 points across");
        let coarse = family.coarser().unwrap();
        let coarsest = coarse.coarser().unwrap();
        assert_eq!(
            coarse,
            GridFamily::HertzLine {
                half_width: b,
                across: 21,
                zone: 1.3
            }
        );
        assert!(matches!(coarsest, GridFamily::HertzLine { across: 11, .. }));
        for (fine, coarse) in [(&family, &coarse), (&coarse, &coarsest)] {
            assert!((coarse.spacing() / fine.spacing() - 2.0).abs() < 1e-15);
            // The edge x = b is a point of each grid.
            let points = coarse.points().unwrap();
            assert!((0..points.len()).any(|k| (points.x(k) - b).abs() < 1e-12 * b));
        }
        // Refined by 2 it is 81 across; too coarse to halve below 3 cells.
        assert!(matches!(
            family.refined(2.0).unwrap(),
            GridFamily::HertzLine { across: 81, .. }
        ));
        assert!(hertz_line_family(b, 3, 1.0).unwrap().coarser().is_none());
    }

    fn same_points(a: &PointSet, b: &PointSet) -> bool {
        a.len() == b.len()
            && (0..a.len()).all(|k| {
                a.x(k).to_bits() == b.x(k).to_bits()
                    && a.y(k).to_bits() == b.y(k).to_bits()
                    && a.measure(k).to_bits() == b.measure(k).to_bits()
            })
    }

    #[test]
    fn a_family_lays_out_the_points_of_its_constructor() {
        let disk = GridFamily::Disk {
            spacing: 0.1,
            radius: 1.15,
        };
        assert!(same_points(
            &disk.points().unwrap(),
            &PointSet::grid_disk(0.1, 1.15).unwrap()
        ));
        let rect = GridFamily::Rectangle {
            half_x: 0.3,
            half_y: 5.0,
            nx: 9,
            ny: 40,
        };
        assert!(same_points(
            &rect.points().unwrap(),
            &PointSet::grid_rectangle(0.3, 5.0, 9, 40).unwrap()
        ));
        // sqrt(dx dy) of the rectangle's cells.
        assert!((rect.spacing() - (0.6f64 / 9.0 * 10.0 / 40.0).sqrt()).abs() < 1e-15);
        let line = hertz_line_family(1.0, 21, 1.5).unwrap();
        assert!((line.spacing() - 0.1).abs() < 1e-15);
        assert!(same_points(
            &line.points().unwrap(),
            &hertz_line(1.0, 21, 1.5).unwrap()
        ));
    }

    #[test]
    fn coarser_grids_halve_the_counts_keeping_their_parity_and_the_centre() {
        assert_eq!(half_count(21), Some(11));
        assert_eq!(half_count(27), Some(13));
        assert_eq!(half_count(13), Some(7));
        assert_eq!(half_count(9), Some(5));
        assert_eq!(half_count(5), Some(3));
        assert_eq!(half_count(80), Some(40));
        assert_eq!(half_count(40), Some(20));
        // 6 / 2 = 3 is odd: the even neighbours 2 and 4, the larger taken.
        assert_eq!(half_count(6), Some(4));
        assert_eq!(half_count(4), None);
        assert_eq!(half_count(3), None);
        // A disk: twice the spacing, the same radius; 21 across becomes 11.
        let a = 1.0;
        let fine = hertz_disk_family(a, 21, 1.15).unwrap();
        let coarse = fine.coarser().unwrap();
        assert!(same_points(
            &coarse.points().unwrap(),
            &hertz_disk(a, 11, 1.15).unwrap()
        ));
        // Each coarser line keeps the origin a point, the zone the same.
        let mut family = hertz_line_family(1.0, 21, 1.3).unwrap().line().unwrap();
        while let Some(c) = family.coarser() {
            let points = c.points().unwrap();
            assert!((0..points.len()).any(|k| points.x(k) == 0.0), "{c:?}");
            assert!(c.spacing() > 1.8 * family.spacing(), "{c:?}");
            family = c;
        }
        // 27 cells, then 13, 7, 3.
        assert!(
            matches!(family, GridFamily::Line { n: 3, .. }),
            "{family:?}"
        );
        // A disk with fewer than 3 points across at twice the spacing.
        let small = GridFamily::Disk {
            spacing: 0.3,
            radius: 0.5,
        };
        assert_eq!(small.coarser(), None);
    }

    #[test]
    fn a_finer_grid_is_the_one_whose_coarser_grid_is_this() {
        for n in [3, 5, 8, 21, 40, 121] {
            assert_eq!(half_count(double_count(n)), Some(n), "{n}");
        }
        let families = [
            GridFamily::Disk {
                spacing: 0.1,
                radius: 1.0,
            },
            GridFamily::Rectangle {
                half_x: 1.0,
                half_y: 2.0,
                nx: 21,
                ny: 40,
            },
            GridFamily::Line {
                start: -1.0,
                end: 1.0,
                n: 27,
            },
            hertz_line_family(1.0, 21, 1.3).unwrap(),
        ];
        for family in families {
            let finer = family.finer();
            assert_eq!(finer.coarser(), Some(family), "{family:?}");
            let ratio = family.spacing() / finer.spacing();
            assert!((1.9..=2.1).contains(&ratio), "{family:?}: {ratio}");
        }
    }

    #[test]
    fn refined_grids_divide_the_spacing() {
        let line = GridFamily::Line {
            start: -1.0,
            end: 1.0,
            n: 10,
        };
        assert_eq!(
            line.refined(2.5).unwrap(),
            GridFamily::Line {
                start: -1.0,
                end: 1.0,
                n: 25
            }
        );
        assert_eq!(
            line.refined(0.01).unwrap(),
            GridFamily::Line {
                start: -1.0,
                end: 1.0,
                n: 1
            }
        );
        let disk = GridFamily::Disk {
            spacing: 0.2,
            radius: 1.0,
        };
        assert_eq!(disk.refined(2.0).unwrap().spacing(), 0.1);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                disk.refined(bad),
                Err(AnalysisError::InvalidInput {
                    field: "factor",
                    ..
                })
            ));
        }
    }

    #[test]
    fn an_intermediate_grid_lies_about_sqrt_2_coarser() {
        let families = [
            GridFamily::Rectangle {
                half_x: 1.0,
                half_y: 2.0,
                nx: 41,
                ny: 80,
            },
            GridFamily::Line {
                start: -1.0,
                end: 1.0,
                n: 131,
            },
            GridFamily::Disk {
                spacing: 0.1,
                radius: 2.0,
            },
            hertz_line_family(1.0, 101, 1.3).unwrap(),
            hertz_ellipse_family(
                EllipseExtent {
                    semi_minor: 1.0,
                    half_x: 3.0,
                    half_y: 1.0,
                },
                31,
                1.2,
            )
            .unwrap(),
        ];
        for family in families {
            let between = family.intermediate().unwrap();
            let ratio = between.spacing() / family.spacing();
            assert!(
                (ratio / std::f64::consts::SQRT_2 - 1.0).abs() < 0.05,
                "{family}: {ratio}"
            );
            assert!(
                between.spacing() < family.coarser().unwrap().spacing(),
                "{family}"
            );
        }
        if let Some(GridFamily::Rectangle { nx, ny, .. }) = families[0].intermediate() {
            assert_eq!((nx, ny), (29, 56));
        }
        assert_eq!(parity_nearest(2.2, 7), 3);
        assert_eq!(parity_nearest(92.0, 130), 92);
    }
}
