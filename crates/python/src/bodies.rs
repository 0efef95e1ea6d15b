//! Hertz's elliptical contact as a function (`hertz_ellipse`), and a
//! height map given as a 2-D array added to a problem's surfaces: the
//! checks are elcon-analysis's own (`HertzEllipse::new`, `HeightMap::new`).

use elcon_analysis::references::HertzEllipse;
use elcon_analysis::{Curvature, Departure, Geometry, HeightMap, Interpolation, Surface};
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{InputError, analysis_error};

/// Hertz's elliptical contact of two quadrics pressed by `load`, each
/// surface `(radius_x, radius_y, angle_degrees)` (an infinite radius
/// straight, a negative one concave; a sphere `(R, R, 0)`): a dict of the
/// semi-axes `semi_major`, `semi_minor`, the major axis's `angle`
/// (degrees from x), `approach`, `peak_pressure`, `eccentricity`,
/// `equivalent_radius` (`sqrt(a b)`), and `pressure` at the points `x`,
/// `y` when given.
#[pyfunction]
#[pyo3(signature = (combined_modulus, load, surface1, surface2=None, x=None, y=None))]
pub(crate) fn hertz_ellipse<'py>(
    py: Python<'py>,
    combined_modulus: f64,
    load: f64,
    surface1: (f64, f64, f64),
    surface2: Option<(f64, f64, f64)>,
    x: Option<Vec<f64>>,
    y: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let quadric = |(radius_x, radius_y, angle): (f64, f64, f64)| Surface::Quadric {
        radius_x,
        radius_y,
        angle: angle.to_radians(),
    };
    let mut curvature = Curvature::of(&quadric(surface1));
    if let Some(s) = surface2 {
        curvature = curvature + Curvature::of(&quadric(s));
    }
    let h = HertzEllipse::new(combined_modulus, curvature, load).map_err(analysis_error)?;
    let d = PyDict::new(py);
    d.set_item("semi_major", h.semi_major())?;
    d.set_item("semi_minor", h.semi_minor())?;
    d.set_item("angle", h.angle().to_degrees())?;
    d.set_item("approach", h.approach())?;
    d.set_item("peak_pressure", h.peak_pressure())?;
    d.set_item("eccentricity", h.eccentricity())?;
    d.set_item("equivalent_radius", h.equivalent_radius())?;
    match (x, y) {
        (Some(x), Some(y)) if x.len() == y.len() => {
            let p: Vec<f64> = x.iter().zip(&y).map(|(&a, &b)| h.pressure(a, b)).collect();
            d.set_item("pressure", p)?;
        }
        (None, None) => {}
        _ => {
            return Err(InputError::new_err(
                "`x` and `y`: give both, of one length, for the pressure at the points",
            ));
        }
    }
    Ok(d)
}

/// `geometry` with the height map `z` (`z[j, i]` at `(x0 + i dx, y0 + j
/// dy)`) added, when given: its spacing `(dx, dy)` required, its origin
/// `(x0, y0)` by default the map centred on the origin, its
/// interpolation by name (`"linear"` by default, or `"cubic"`:
/// `elcon_analysis::Interpolation`).
pub(crate) fn with_height_map(
    geometry: Geometry,
    z: Option<PyReadonlyArray2<'_, f64>>,
    spacing: Option<(f64, f64)>,
    origin: Option<(f64, f64)>,
    interpolation: Option<&str>,
) -> PyResult<Geometry> {
    let Some(z) = z else {
        if spacing.is_some() || origin.is_some() || interpolation.is_some() {
            return Err(InputError::new_err(
                "`height_map_spacing`, `height_map_origin`, `height_map_interpolation`: they go \
                 with `height_map`",
            ));
        }
        return Ok(geometry);
    };
    let interpolation = match interpolation {
        None => Interpolation::Linear,
        Some(name) => name.parse::<Interpolation>().map_err(|_| {
            InputError::new_err(format!(
                "`height_map_interpolation` = \"{name}\": one of {}",
                Interpolation::NAMES.join(", ")
            ))
        })?,
    };
    let z = z.as_array();
    let (ny, nx) = z.dim();
    let spacing =
        spacing.ok_or_else(|| InputError::new_err("`height_map_spacing`: required, (dx, dy)"))?;
    let origin = origin.unwrap_or((
        -0.5 * nx.saturating_sub(1) as f64 * spacing.0,
        -0.5 * ny.saturating_sub(1) as f64 * spacing.1,
    ));
    let values: Vec<f64> = z.iter().copied().collect();
    let map = HeightMap::new("height_map", values, nx, ny, spacing, origin)
        .and_then(|m| m.with_interpolation(interpolation))
        .map_err(analysis_error)?;
    let departure = Departure::HeightMap(std::sync::Arc::new(map));
    match geometry {
        Geometry::Surfaces(a, b) => Ok(Geometry::Tabulated {
            surfaces: (a, b),
            departures: vec![departure],
        }),
        Geometry::Tabulated {
            surfaces,
            mut departures,
        } => {
            departures.push(departure);
            Ok(Geometry::Tabulated {
                surfaces,
                departures,
            })
        }
        _ => Err(InputError::new_err(
            "`height_map` adds to surfaces: give `geometry` surfaces (or none: two planes), \
             not `separation`",
        )),
    }
}
