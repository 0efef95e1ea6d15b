//! The closed forms a scene is compared with: the Hertz contact at a load
//! (point or line contact, from the layout, the bodies and the surfaces),
//! a flat punch, a beam on a Winkler foundation.

use elcon_analysis::references::{
    BeamOnFoundation, FlatPunch, HertzCylinders, HertzEllipse, HertzSpheres, HetenyiBeam,
};
use elcon_analysis::{Geometry, GridFamily, Loading, Normal, Surface};
use elcon_influence::{PointSet, combined_modulus_of};

use super::body::{BodySpec, ModelKind};
use super::geometry::combined;
use super::points::{EllipseShape, HertzLayout, PointsSpec};
use crate::sanity::StrainExtent;
use crate::schema::Grid;

/// The parts of a scene its Hertz contact and its closed forms come from:
/// the bodies, the surfaces (or separations) and the layout of the points.
/// A design over problems given piece by piece may know them: what its
/// logarithmic crown's roller is derived from.
#[derive(Debug, Clone, Copy)]
pub struct DesignLayoutParts<'a> {
    /// The two bodies.
    pub bodies: &'a [BodySpec; 2],
    /// The surfaces.
    pub geometry: &'a Geometry,
    /// The layout of the points.
    pub points_spec: &'a PointsSpec,
}

/// A scene's layout, as the closed forms read it ([`DesignLayoutParts`]).
pub(crate) type Layout<'a> = DesignLayoutParts<'a>;

/// The closed form a scene is compared with, when one applies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference {
    /// Hertz, two spheres or a sphere on a plane.
    HertzSpheres(HertzSpheres),
    /// Hertz line contact (plane strain); the approach is compared when the
    /// datum distance d0 is the same for the elastic bodies.
    HertzCylinders {
        /// The closed form.
        hertz: HertzCylinders,
        /// The common datum distance d0.
        datum: Option<f64>,
    },
    /// A rigid flat circular punch whose face is the candidate disk.
    FlatPunch(FlatPunch),
    /// A free-free beam on a Winkler foundation under a central load.
    Hetenyi(HetenyiBeam),
    /// Hertz, an elliptical contact of quadrics (or a sphere's against a
    /// quadric): the gap curves both ways, not equally.
    HertzEllipse(HertzEllipse),
}

impl Reference {
    /// A short name: "hertz-spheres", "hertz-cylinders", "flat-punch",
    /// "hetenyi-beam", "hertz-ellipse".
    pub fn kind(&self) -> &'static str {
        match self {
            Reference::HertzEllipse(_) => "hertz-ellipse",
            Reference::HertzSpheres(_) => "hertz-spheres",
            Reference::HertzCylinders { .. } => "hertz-cylinders",
            Reference::FlatPunch(_) => "flat-punch",
            Reference::Hetenyi(_) => "hetenyi-beam",
        }
    }
}

/// E* of the bodies if they are half-space models of a `line` (plane
/// strain) or of a surface (point forces, uniform patches), or rigid.
fn half_space_modulus(bodies: &[BodySpec; 2], line: bool) -> Option<f64> {
    let half_space = |m: ModelKind| match line {
        true => m == ModelKind::PlaneStrain,
        false => m.is_surface(),
    };
    if !bodies
        .iter()
        .all(|b| b.model() == ModelKind::Rigid || half_space(b.model()))
    {
        return None;
    }
    let e = combined_modulus_of(bodies[0].material(), bodies[1].material());
    e.is_finite().then_some(e)
}

/// The Hertz contact of a scene at one load: the closed form its layout,
/// bodies and surfaces call for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Hertz {
    /// Point contact: spheres (or a sphere on a plane) on a disk grid.
    Spheres(HertzSpheres),
    /// Line contact: cylinders (or a cylinder on a plane) on a line, or a
    /// roller along y on a rectangle grid (per unit length `2 half_y`).
    Cylinders(HertzCylinders),
    /// An elliptical contact of quadrics, on a disk or an ellipse grid.
    Ellipse(HertzEllipse),
}

impl Hertz {
    /// The length scale: the contact radius or the half-width.
    pub(crate) fn scale(&self) -> f64 {
        match self {
            Hertz::Spheres(h) => h.contact_radius(),
            Hertz::Cylinders(h) => h.half_width(),
            Hertz::Ellipse(h) => h.equivalent_radius(),
        }
    }

    /// The approach of a point contact (spheres, an ellipse); `None` for a
    /// line contact, whose approach depends on where it is measured.
    pub(crate) fn approach(&self) -> Option<f64> {
        match self {
            Hertz::Spheres(h) => Some(h.approach()),
            Hertz::Ellipse(h) => Some(h.approach()),
            Hertz::Cylinders(_) => None,
        }
    }

    /// The peak pressure (intensity unit).
    pub(crate) fn peak_pressure(&self) -> f64 {
        match self {
            Hertz::Spheres(h) => h.peak_pressure(),
            Hertz::Cylinders(h) => h.peak_pressure(),
            Hertz::Ellipse(h) => h.peak_pressure(),
        }
    }
}

impl Layout<'_> {
    /// The Hertz contact at `load`, if one applies: spheres/planes and
    /// half-space surface bodies on a disk; cylinders/planes and
    /// plane-strain bodies on a line; cylinders/planes and half-space
    /// surface bodies on a rectangle (a roller along y, per unit length
    /// `2 half_y`); quadrics on a disk or an ellipse grid. Rigid bodies
    /// count as half-spaces; the surfaces must not both be planes.
    pub(crate) fn hertz(&self, load: f64) -> Option<Hertz> {
        let (bodies, geometry) = (self.bodies, self.geometry);
        // Quadrics on a disk of lengths are an ellipse's; a disk relative
        // to the Hertz contact is laid out around a circle.
        let fixed = matches!(self.points_spec, PointsSpec::Fixed(_));
        match self.points_spec.grid() {
            Grid::Disk if fixed && combined(geometry, true).is_none() => {
                ellipse(bodies, geometry, load).map(Hertz::Ellipse)
            }
            Grid::Ellipse => ellipse(bodies, geometry, load).map(Hertz::Ellipse),
            Grid::Disk => {
                let e = half_space_modulus(bodies, false)?;
                let r = combined(geometry, true)?;
                HertzSpheres::new(e, r, load).ok().map(Hertz::Spheres)
            }
            Grid::Line => {
                let e = half_space_modulus(bodies, true)?;
                let r = combined(geometry, false)?;
                HertzCylinders::new(e, r, load).ok().map(Hertz::Cylinders)
            }
            Grid::Rectangle => {
                let e = half_space_modulus(bodies, false)?;
                let r = combined(geometry, false)?;
                let half_y = self.points_spec.half_y()?;
                HertzCylinders::new(e, r, load / (2.0 * half_y))
                    .ok()
                    .map(Hertz::Cylinders)
            }
        }
    }

    /// The Hertz length scale at `load`: the contact radius (disk) or the
    /// half-width (line; rectangle of a roller, per unit length `2 half_y`).
    pub(crate) fn scale(&self, load: f64) -> Option<f64> {
        self.hertz(load).map(|h| h.scale())
    }

    /// The combined radius `R` of spheres (or a sphere on a plane) and the
    /// Hertz radius `a` at `load`, on a disk grid: what a prescribed tilt's
    /// shift of the gap's minimum, `R tilt`, is measured against.
    pub(crate) fn spheres_at(&self, load: f64) -> Option<(f64, f64)> {
        match self.hertz(load)? {
            Hertz::Spheres(h) => Some((combined(self.geometry, true)?, h.contact_radius())),
            _ => None,
        }
    }

    /// The length the small strain measures an approach against on
    /// `points` laid out around the Hertz contact `hertz`: on an ellipse
    /// grid the zone across the Hertz ellipse's minor axis in the
    /// ellipse's own frame (`elcon_analysis::grid::ellipse_minor_zone`: the
    /// same at any turn, where the grid's extents along x and y grow with
    /// the turn), else the zone's smaller extent.
    pub(crate) fn approach_extent(&self, hertz: Option<&Hertz>, points: &PointSet) -> StrainExtent {
        if let (
            PointsSpec::Hertz(HertzLayout::Ellipse { across, zone, .. }),
            Some(Hertz::Ellipse(h)),
        ) = (self.points_spec, hertz)
            && let Ok(length) =
                elcon_analysis::grid::ellipse_minor_zone(h.semi_minor(), *across, *zone)
        {
            return StrainExtent {
                length,
                what: "the candidate zone's extent across the Hertz ellipse's minor axis",
            };
        }
        StrainExtent::of(points)
    }

    /// The closed form that applies to the scene on `points` under
    /// `loading`, if one does.
    pub(crate) fn reference(&self, points: &PointSet, loading: Loading) -> Option<Reference> {
        let (bodies, geometry) = (self.bodies, self.geometry);
        let flat = match geometry {
            // Departures from the quadrics have no closed form.
            Geometry::Tabulated { .. } => return None,
            Geometry::Surfaces(Surface::Plane, Surface::Plane) => true,
            Geometry::Separation(eps) => eps.iter().all(|&e| e == eps[0]),
            _ => false,
        };
        let fixed_disk = match self.points_spec {
            PointsSpec::Fixed(GridFamily::Disk { radius, .. }) => Some(*radius),
            _ => None,
        };
        match self.points_spec.grid() {
            Grid::Ellipse => ellipse_reference(bodies, geometry, loading),
            Grid::Disk if fixed_disk.is_some() && !flat && combined(geometry, true).is_none() => {
                ellipse_reference(bodies, geometry, loading)
            }
            Grid::Disk if flat && fixed_disk.is_some() => {
                let radius = fixed_disk?;
                // A rigid flat punch: one rigid body, the candidate disk its face.
                let rigid = bodies.iter().filter(|b| b.body().is_rigid()).count() == 1;
                let e = half_space_modulus(bodies, false)?;
                rigid.then(|| FlatPunch::new(e, radius).ok().map(Reference::FlatPunch))?
            }
            Grid::Disk => {
                let e = half_space_modulus(bodies, false)?;
                let r = combined(geometry, true)?;
                let load = match loading.normal {
                    Normal::Load(p) => p,
                    // The Hertz load of the approach: P = 4 E* a^3 / (3 R), a = sqrt(R delta).
                    Normal::Approach(d) if d > 0.0 => 4.0 * e * (r * d).powf(1.5) / (3.0 * r),
                    Normal::Approach(_) => return None,
                };
                HertzSpheres::new(e, r, load)
                    .ok()
                    .map(Reference::HertzSpheres)
            }
            Grid::Line => {
                let Normal::Load(p) = loading.normal else {
                    return None;
                };
                match combined(geometry, false) {
                    Some(r) => cylinders_reference(bodies, r, p),
                    // A beam on a Winkler foundation, central load, no separation.
                    None if flat => hetenyi_reference(bodies, points, p),
                    None => None,
                }
            }
            Grid::Rectangle => None,
        }
    }
}

/// The elliptical Hertz contact of half-space (or rigid) surface bodies
/// whose gap's curvature is the surfaces' (`Geometry::curvature`).
fn ellipse(bodies: &[BodySpec; 2], geometry: &Geometry, load: f64) -> Option<HertzEllipse> {
    let e = half_space_modulus(bodies, false)?;
    HertzEllipse::new(e, geometry.curvature()?, load).ok()
}

/// An ellipse grid's shape, the ellipse's half-extents over its equivalent
/// radius, set from the surfaces (the same at any load); other layouts,
/// and an ellipse grid with no elliptical Hertz contact, as they are.
pub(super) fn shaped(spec: PointsSpec, bodies: &[BodySpec; 2], geometry: &Geometry) -> PointsSpec {
    match (spec, ellipse(bodies, geometry, 1.0)) {
        (PointsSpec::Hertz(HertzLayout::Ellipse { across, zone, .. }), Some(h)) => {
            let (ex, ey) = h.half_extents();
            let r = h.equivalent_radius();
            PointsSpec::Hertz(HertzLayout::Ellipse {
                across,
                zone,
                shape: EllipseShape {
                    half_x: ex / r,
                    half_y: ey / r,
                    semi_minor: h.semi_minor() / r,
                    angle: h.angle(),
                },
            })
        }
        (spec, _) => spec,
    }
}

/// Hertz's line contact of plane-strain (or rigid) bodies of combined
/// radius `r` under the load per length `p`; its approach is compared when
/// the elastic bodies share their datum distance d0.
fn cylinders_reference(bodies: &[BodySpec; 2], r: f64, p: f64) -> Option<Reference> {
    let e = half_space_modulus(bodies, true)?;
    let datums: Vec<f64> = bodies
        .iter()
        .filter_map(|b| match b.body().model() {
            elcon_influence::Model::PlaneStrainStrip {
                reference_distance, ..
            } => Some(*reference_distance),
            _ => None,
        })
        .collect();
    let datum = datums.iter().all(|&d| d == datums[0]).then(|| datums[0]);
    HertzCylinders::new(e, r, p)
        .ok()
        .map(|hertz| Reference::HertzCylinders { hertz, datum })
}

/// Hetenyi's free beam on a Winkler foundation under the central load `p`:
/// a beam and a foundation whose zone, the beam's cells end to end, is
/// centred on the loaded point.
fn hetenyi_reference(bodies: &[BodySpec; 2], points: &PointSet, p: f64) -> Option<Reference> {
    let (mut ei, mut k, mut x0) = (None, None, None);
    for b in bodies {
        match *b.body().model() {
            elcon_influence::Model::Beam {
                flexural_rigidity,
                loaded_point,
            } => {
                ei = Some(flexural_rigidity);
                x0 = Some(loaded_point);
            }
            elcon_influence::Model::Winkler { modulus } => k = Some(modulus),
            _ => return None,
        }
    }
    let (lo, hi) = (points.x(0), points.x(points.len() - 1));
    let length = points.extent().0;
    if (x0? - 0.5 * (lo + hi)).abs() > 1e-9 * length {
        return None;
    }
    let beam = BeamOnFoundation {
        flexural_rigidity: ei?,
        foundation_modulus: k?,
        length,
        load: p,
    };
    HetenyiBeam::new(beam).ok().map(Reference::Hetenyi)
}

/// The elliptical Hertz contact at the scene's load, or at the load of its
/// approach (`HertzEllipse::at_approach`).
fn ellipse_reference(
    bodies: &[BodySpec; 2],
    geometry: &Geometry,
    loading: Loading,
) -> Option<Reference> {
    let h = match loading.normal {
        Normal::Load(p) => ellipse(bodies, geometry, p)?,
        Normal::Approach(d) => ellipse(bodies, geometry, 1.0)?.at_approach(d).ok()?,
    };
    Some(Reference::HertzEllipse(h))
}

/// The reference of a scene under `loading`, and why it was dropped: a
/// flat punch under an approach that does not press it in (`delta - e0 <= 0`,
/// e0 a uniform separation)
/// carries no load, and Boussinesq's `P = 2 a E* delta` would be zero or
/// tensile, no reference to measure an error against.
pub(super) fn pressing(
    reference: Option<Reference>,
    loading: Loading,
    geometry: &Geometry,
) -> (Option<Reference>, Option<String>) {
    // A uniform separation e0 holds the punch's face e0 off the other
    // surface: the indentation is the approach minus it.
    let e0 = match geometry {
        Geometry::Separation(eps) => eps.first().copied().unwrap_or(0.0),
        _ => 0.0,
    };
    match (reference, loading.normal) {
        (Some(Reference::FlatPunch(_)), Normal::Approach(d)) if d - e0 <= 0.0 => (
            None,
            Some(format!(
                "no flat-punch reference: the approach {}{} does not press the punch in, so \
                 the contact carries no load (Boussinesq's P = 2 a E* delta would be {})",
                crate::ctx::Num(d),
                if e0 == 0.0 {
                    String::new()
                } else {
                    format!(" less the uniform separation {}", crate::ctx::Num(e0))
                },
                if d - e0 == 0.0 { "zero" } else { "tensile" }
            )),
        ),
        (reference, _) => (reference, None),
    }
}
