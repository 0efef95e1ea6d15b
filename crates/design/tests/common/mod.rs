//! The cases the design tests start from, each written once: Conry &
//! Seireg's Example 2 beam and a misaligned roller; and the design options
//! of a method. benches/design.rs reads this file too (by `#[path]`).

#![allow(dead_code)]

use elcon_analysis::references::HertzCylinders;
use elcon_analysis::{ContactProblem, Geometry, Loading, Storage, Surface};
use elcon_design::{Axis, Design, DesignError, DesignMethod, DesignOptions, Family, design};
use elcon_influence::{Beam, Body, Material, PointSet, combined_modulus};

/// Example 2's beam: steel (E = 30e6 psi), 1 in x 4 in (I = 64/12 in^4),
/// 8.9 in long, on a Winkler foundation of 1e7 lb/in/in, at `n` points
/// along it, loaded at `x0` (in) under `loading`; in the units where an
/// inch is `length` and a pound `force` (`(1.0, 1.0)`: inch and pound),
/// `loading` given in them.
pub fn example2_in(
    (length, force): (f64, f64),
    n: usize,
    x0: f64,
    loading: Loading,
) -> ContactProblem {
    let l = 8.9 * length;
    let points = PointSet::line(-0.5 * l, 0.5 * l, n).unwrap();
    let beam = Body::beam(Beam {
        youngs_modulus: 30e6 * force / (length * length),
        second_moment: 64.0 / 12.0 * length.powi(4),
        loaded_point: x0 * length,
    })
    .unwrap();
    let foundation = Body::winkler(1e7 * force / (length * length));
    let separation = Geometry::Separation(vec![0.0; n]);
    ContactProblem::new(points, &beam, &foundation, &separation, loading).unwrap()
}

/// [`example2_in`] in inch and pound.
pub fn example2(n: usize, x0: f64, loading: Loading) -> ContactProblem {
    example2_in((1.0, 1.0), n, x0, loading)
}

/// A steel roller (D = 10 mm, l = 10 mm) on Love patches, each load's
/// `nx` x `ny` grid 1.6 of its Hertz half-width across, its ends (along
/// y) the body's own, under every load (N) at every misalignment (a
/// prescribed rotation about x, rad), S dense: the cases load by load (one
/// S per load), and each case's aligned Hertz peak.
pub fn misaligned_roller(
    loads: &[f64],
    misalignments: &[f64],
    cells: (usize, usize),
) -> (Vec<ContactProblem>, Vec<f64>) {
    roller_on(loads, misalignments, cells, Storage::Dense)
}

/// The roller of [`misaligned_roller`], S held as `storage` says
/// (elcon-analysis's choice with `Storage::Auto`).
pub fn roller_on(
    loads: &[f64],
    misalignments: &[f64],
    (nx, ny): (usize, usize),
    storage: Storage,
) -> (Vec<ContactProblem>, Vec<f64>) {
    let steel = Material::new(210e3, 0.3).unwrap();
    let e_star = combined_modulus(&steel, &steel);
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
    let (mut cases, mut references) = (Vec::new(), Vec::new());
    for &load in loads {
        let hertz = HertzCylinders::new(e_star, 5.0, load / 10.0).unwrap();
        let points = PointSet::grid_rectangle(1.6 * hertz.half_width(), 5.0, nx, ny).unwrap();
        let aligned = ContactProblem::builder(points, &body, &body, &geometry, Loading::load(load))
            .storage(storage)
            .fold(false)
            .body_edges(false, true)
            .build()
            .unwrap();
        for &angle in misalignments {
            let loading = Loading::load(load).with_tilt_x(angle);
            cases.push(aligned.with_loading(loading).unwrap());
            references.push(hertz.peak_pressure());
        }
    }
    (cases, references)
}

/// The design options of `method` with the cases' reference intensities
/// `references` (`None`: 1 each), the rest the defaults.
pub fn options(method: DesignMethod, references: Option<Vec<f64>>) -> DesignOptions {
    DesignOptions {
        method,
        reference_intensities: references,
        ..DesignOptions::default()
    }
}

/// The design of the one case `case` along `axis` in `family`, with the
/// default options.
pub fn design_one(
    case: &ContactProblem,
    axis: Axis,
    family: Family,
) -> Result<Design, DesignError> {
    design(
        std::slice::from_ref(case),
        axis,
        family,
        &DesignOptions::default(),
    )
}
