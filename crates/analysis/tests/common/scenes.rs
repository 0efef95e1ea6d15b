//! Contact problems that several tests build: two spheres on Love patches
//! and a rigid flat punch; and the data of Conry & Seireg's Example 1, which
//! tests/cli.rs and the benches and examples of the root package include
//! too (by `#[path]`). Declared by stability_cases.rs (which
//! examples/stability_report.rs includes on its own), re-exported as
//! `common::scenes`.

#![allow(dead_code)]

use elcon_analysis::references::{FlatPunch, HertzSpheres, combined_radius};
use elcon_analysis::{ContactProblem, Geometry, Loading, Surface};
use elcon_influence::{Body, Material, PointSet, combined_modulus};

/// Two spheres of radii `r1`, `r2` (negative = concave) and materials `m1`,
/// `m2` on Love patches under the load `load`, on a disk grid of spacing
/// `a / cells_per_radius` and radius `zone * a`, `a` the Hertz contact
/// radius; with the Hertz solution.
pub fn spheres(
    m1: Material,
    m2: Material,
    r1: f64,
    r2: f64,
    load: f64,
    cells_per_radius: f64,
    zone: f64,
) -> (ContactProblem, HertzSpheres) {
    let hertz = HertzSpheres::new(combined_modulus(&m1, &m2), combined_radius(r1, r2), load)
        .expect("Hertz");
    let a = hertz.contact_radius();
    let points = PointSet::grid_disk(a / cells_per_radius, zone * a).expect("grid");
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: r1 },
        Surface::Sphere { radius: r2 },
    );
    let problem = ContactProblem::new(
        points,
        &Body::uniform_patch(m1),
        &Body::uniform_patch(m2),
        &geometry,
        Loading::load(load),
    )
    .expect("spheres problem");
    (problem, hertz)
}

/// A rigid flat punch of radius `radius` pressed by `approach` into a
/// half-space of `material` (Love patches): every separation 0, the
/// candidate zone the punch's face on a disk grid of `cells_per_radius`
/// cells per radius; with the closed form.
pub fn flat_punch(
    material: Material,
    radius: f64,
    cells_per_radius: f64,
    approach: f64,
) -> (ContactProblem, FlatPunch) {
    let points = PointSet::grid_disk(radius / cells_per_radius, radius).expect("grid");
    let n = points.len();
    let problem = ContactProblem::new(
        points,
        &Body::uniform_patch(material),
        &Body::rigid(),
        &Geometry::Separation(vec![0.0; n]),
        Loading::approach(approach),
    )
    .expect("punch problem");
    let punch = FlatPunch::new(material.plane_strain_modulus(), radius).expect("punch");
    (problem, punch)
}

/// Conry & Seireg's Example 1: steel (E = 30e6 psi, nu = 0.3) on both sides.
pub fn example1_steel() -> Material {
    Material::new(30e6, 0.3).expect("steel")
}

/// Example 1's Hertz contact: steel spheres of radii 1 in and 10 in under
/// 100 lb.
pub fn example1_hertz() -> HertzSpheres {
    let steel = example1_steel();
    HertzSpheres::new(
        combined_modulus(&steel, &steel),
        combined_radius(1.0, 10.0),
        100.0,
    )
    .expect("Hertz")
}

/// Example 1's bodies on Love patches, and its surfaces: spheres of radii
/// 1 in and 10 in.
pub fn example1_bodies() -> (Body, Geometry) {
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    (Body::uniform_patch(example1_steel()), geometry)
}
