//! Contact problems that several tests build: two spheres on Love patches
//! and a rigid flat punch; and the data of Conry & Seireg's Example 1, which
//! tests/cli.rs and the benches and examples of the root package include
//! too (by `#[path]`). Declared by stability_cases.rs (which
//! examples/stability_report.rs includes on its own), re-exported as
//! `common::scenes`.

#![allow(dead_code)]

use elcon_analysis::references::{FlatPunch, HertzSpheres, combined_radius};
use elcon_analysis::{AnalysisError, ContactProblem, Geometry, Loading, Surface};
use elcon_influence::{Beam, Body, Material, PointSet, combined_modulus};

/// A constructor of a contact problem, by how it holds S:
/// `ContactProblem::new` (dense), `ContactProblem::symmetric` (folded) or
/// `ContactProblem::lattice` (matrix-free).
pub type Build =
    fn(PointSet, &Body, &Body, &Geometry, Loading) -> Result<ContactProblem, AnalysisError>;

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

/// A beam of flexural rigidity `ei` (a unit second moment) loaded at
/// `loaded_point` by `load`, on `foundation`, at the points of a line
/// `points` with no initial separation; S held as `build` holds it.
pub fn beam_on(
    build: Build,
    foundation: Body,
    (ei, loaded_point): (f64, f64),
    points: PointSet,
    load: f64,
) -> Result<ContactProblem, AnalysisError> {
    let beam = Body::beam(Beam {
        youngs_modulus: ei,
        second_moment: 1.0,
        loaded_point,
    })
    .expect("a valid beam");
    let n = points.len();
    let separation = Geometry::Separation(vec![0.0; n]);
    build(points, &beam, &foundation, &separation, Loading::load(load))
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

/// Example 1 (its bodies and surfaces, [`example1_bodies`]) at `points`
/// under `loading`, S held as `build` holds it.
pub fn example1(
    build: Build,
    points: PointSet,
    loading: Loading,
) -> Result<ContactProblem, AnalysisError> {
    let (body, geometry) = example1_bodies();
    build(points, &body, &body, &geometry, loading)
}
