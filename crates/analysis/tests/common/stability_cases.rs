//! The stiff and extreme cases of the stability suite, in one place: read by
//! crates/analysis/tests/stability.rs (small sizes) and by
//! examples/stability_report.rs (the docs/stability.md table, sizes to 4096).
//!
//! Every case is a contact problem and, where one applies, the closed form
//! to compare with. SI units unless a case says otherwise.

#![allow(dead_code)]

// The problem builders shared with the other tests (common::scenes), declared
// here so that examples/stability_report.rs, which includes this file alone,
// has them too; the path is relative to this file's directory.
#[path = "scenes.rs"]
pub mod scenes;

use elcon_analysis::references::{
    BeamOnFoundation, FlatPunch, HertzSpheres, HetenyiBeam, combined_radius,
};
use elcon_analysis::{ContactProblem, Geometry, Loading, Surface};
use elcon_influence::{Body, Material, PointSet, combined_modulus};

/// What a case's answer is compared with.
#[derive(Debug, Clone, Copy)]
pub enum Reference {
    /// Hertz: the approach, under load control.
    Hertz(HertzSpheres),
    /// A rigid flat punch of the zone's radius: the load, under a given approach.
    Punch(FlatPunch, f64),
    /// Hetenyi's beam: the approach (valid while every point touches).
    Hetenyi(HetenyiBeam),
    /// No closed form.
    None,
}

/// What the case must show beyond a holding certificate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Expect {
    /// Nothing more.
    Solved,
    /// A warning that the contact reaches the edge of the zone.
    EdgeWarning,
    /// Exactly one point carries the load.
    OnePoint,
}

/// One case of the suite.
pub struct Case {
    /// The family ("modulus ratio", "load", ...).
    pub family: &'static str,
    /// The case within it.
    pub name: String,
    /// The problem.
    pub problem: ContactProblem,
    /// The closed form.
    pub reference: Reference,
    /// What else must hold.
    pub expect: Expect,
}

const STEEL_E: f64 = 200e9;

fn steel() -> Material {
    Material::new(STEEL_E, 0.3).expect("steel")
}

/// Two spheres (R1, R2; negative = concave) of materials m1, m2 under load
/// P, Love patches, `across` points across the Hertz diameter, zone radii.
fn spheres(
    m1: Material,
    m2: Material,
    r1: f64,
    r2: f64,
    load: f64,
    across: usize,
    zone: f64,
) -> (ContactProblem, HertzSpheres) {
    // A spacing of 2a / (across - 1): (across - 1) / 2 is exact, so
    // a / ((across - 1) / 2) rounds the same quotient, to the same grid.
    scenes::spheres(m1, m2, r1, r2, load, (across - 1) as f64 / 2.0, zone)
}

fn hertz_case(
    family: &'static str,
    name: String,
    m1: Material,
    m2: Material,
    r1: f64,
    r2: f64,
    across: usize,
) -> Case {
    let (problem, hertz) = spheres(m1, m2, r1, r2, 100.0, across, 1.3);
    Case {
        family,
        name,
        problem,
        reference: Reference::Hertz(hertz),
        expect: Expect::Solved,
    }
}

/// The suite; `across` sets the grid of the Hertz cases (21 in the tests),
/// `sizes` the candidate-point counts of the size family.
pub fn catalogue(across: usize, sizes: &[usize]) -> Vec<Case> {
    let mut cases = Vec::new();
    // Material extremes: the ratio of the moduli and Poisson's ratio.
    for ratio in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        let soft = Material::new(STEEL_E * ratio, 0.3).expect("material");
        cases.push(hertz_case(
            "modulus ratio",
            format!("E2/E1 = {ratio:e}"),
            steel(),
            soft,
            0.01,
            0.1,
            across,
        ));
    }
    for nu in [0.4999, -0.999] {
        let m = Material::new(STEEL_E, nu).expect("material");
        cases.push(hertz_case(
            "Poisson's ratio",
            format!("nu = {nu}"),
            m,
            m,
            0.01,
            0.1,
            across,
        ));
    }
    // Geometric extremes: radius ratios, conformal contact, a flat punch, a truncated zone.
    for ratio in [1e-3, 1e3] {
        cases.push(hertz_case(
            "radius ratio",
            format!("R2/R1 = {ratio:e}"),
            steel(),
            steel(),
            0.01,
            0.01 * ratio,
            across,
        ));
    }
    cases.push(hertz_case(
        "conformal",
        "ball in a groove, R2 = -1.0005 R1".into(),
        steel(),
        steel(),
        0.01,
        -0.010005,
        across,
    ));
    {
        let (problem, punch) = scenes::flat_punch(steel(), 0.001, 10.0, 1e-6);
        cases.push(Case {
            family: "flat punch",
            name: "all separations equal (every ratio test ties)".into(),
            problem,
            reference: Reference::Punch(punch, 1e-6),
            expect: Expect::EdgeWarning,
        });
    }
    {
        let (problem, _) = spheres(steel(), steel(), 0.01, 0.1, 100.0, across, 0.7);
        cases.push(Case {
            family: "truncated zone",
            name: "zone 0.7 Hertz radii".into(),
            problem,
            reference: Reference::None,
            expect: Expect::EdgeWarning,
        });
    }
    // Load extremes on one grid, sized for the nominal 100 N.
    let (nominal, _) = spheres(steel(), steel(), 0.01, 0.1, 100.0, across, 1.3);
    for factor in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        let load = 100.0 * factor;
        let problem = nominal.with_loading(Loading::load(load)).expect("load");
        let hertz = HertzSpheres::new(
            combined_modulus(&steel(), &steel()),
            combined_radius(0.01, 0.1),
            load,
        )
        .expect("Hertz");
        let (reference, expect) = if factor < 1e-3 {
            (Reference::None, Expect::OnePoint)
        } else if factor > 1.0 {
            (Reference::None, Expect::EdgeWarning)
        } else {
            (Reference::Hertz(hertz), Expect::Solved)
        };
        cases.push(Case {
            family: "load",
            name: format!("P = {factor:e} x nominal"),
            problem,
            reference,
            expect,
        });
    }
    // Size (the condition of S grows with refinement).
    for &n in sizes {
        let hertz = nominal_hertz();
        let a = hertz.contact_radius();
        let zone = 1.3 * a;
        let m0 = (n as f64 / std::f64::consts::PI).sqrt().round().max(1.0) as usize;
        let points = (m0.saturating_sub(2).max(1)..=m0 + 2)
            .map(|m| PointSet::grid_disk(zone / m as f64, zone).expect("grid"))
            .min_by_key(|p| p.len().abs_diff(n))
            .expect("grids");
        let geometry = Geometry::Surfaces(
            Surface::Sphere { radius: 0.01 },
            Surface::Sphere { radius: 0.1 },
        );
        let body = Body::uniform_patch(steel());
        let problem = ContactProblem::new(points, &body, &body, &geometry, Loading::load(100.0))
            .expect("problem");
        cases.push(Case {
            family: "size",
            name: format!("N = {}", problem.points().len()),
            problem,
            reference: Reference::Hertz(hertz),
            expect: Expect::Solved,
        });
    }
    // A beam much stiffer than its foundation, and the reverse: lambda L from 0.01 to 100.
    for lambda_l in [0.01, 1.0, 100.0] {
        let (problem, BeamCase { length, k, ei }) = beam_case(lambda_l, 0.0);
        let reference = if lambda_l < std::f64::consts::PI {
            Reference::Hetenyi(
                HetenyiBeam::new(BeamOnFoundation {
                    flexural_rigidity: ei,
                    foundation_modulus: k,
                    length,
                    load: 1e4,
                })
                .expect("Hetenyi"),
            )
        } else {
            Reference::None
        };
        cases.push(Case {
            family: "beam on foundation",
            name: format!("lambda L = {lambda_l}"),
            problem,
            reference,
            expect: Expect::Solved,
        });
    }
    eccentric_and_tilted(&mut cases, across);
    cases
}

/// A beam case's length, foundation modulus and flexural rigidity.
struct BeamCase {
    length: f64,
    k: f64,
    ei: f64,
}

/// A beam of length 1 on a Winkler foundation of 1e8, its stiffness
/// against the foundation's `lambda_l` (lambda L), under 1e4 at
/// `loaded_at` lengths from its middle, on 40 points.
fn beam_case(lambda_l: f64, loaded_at: f64) -> (ContactProblem, BeamCase) {
    let (length, k) = (1.0f64, 1e8f64);
    let ei = k / (4.0 * (lambda_l / length).powi(4));
    let points = PointSet::line(-0.5 * length, 0.5 * length, 40).expect("line");
    let foundation = Body::winkler(k);
    let problem = scenes::beam_on(
        ContactProblem::new,
        foundation,
        (ei, loaded_at * length),
        points,
        1e4,
    )
    .expect("beam problem");
    (problem, BeamCase { length, k, ei })
}

/// Loads off centre and misalignment: spheres under a load far off their
/// apex (a free rotation balancing a moment), a flat punch at and past its
/// lift-off moment (every point tied, then the heel lifting), an
/// off-centre load on a free beam on a soft foundation, and a roller
/// misaligned by 0.1 to 10 mrad (down to contact over a short length at
/// one end).
fn eccentric_and_tilted(cases: &mut Vec<Case>, across: usize) {
    let hertz = nominal_hertz();
    let a = hertz.contact_radius();
    // The far load's zone is 3.3 radii: half the spacing keeps its N near
    // the nominal grid's.
    for (e, across) in [(0.5, across), (2.0, across / 2 + 1)] {
        let (nominal, _) = spheres(steel(), steel(), 0.01, 0.1, 100.0, across, 1.3 + e);
        let problem = nominal
            .with_loading(Loading::load(100.0).with_moment_y(-100.0 * e * a))
            .expect("eccentric load");
        cases.push(Case {
            family: "eccentric",
            name: format!("spheres, load at x = {e} a"),
            problem,
            reference: Reference::None,
            expect: Expect::Solved,
        });
    }
    for factor in [1.0, 3.0] {
        let (punch, closed) = scenes::flat_punch(steel(), 0.001, 10.0, 1e-6);
        let load = closed.load(1e-6);
        let problem = punch
            .with_loading(Loading::load(load).with_moment_y(-factor * closed.lift_off_moment(load)))
            .expect("punch under a moment");
        cases.push(Case {
            family: "eccentric",
            name: format!("flat punch, {factor} x the lift-off moment"),
            problem,
            reference: Reference::None,
            expect: Expect::EdgeWarning,
        });
    }
    {
        let (problem, _) = beam_case(10.0, 0.3);
        cases.push(Case {
            family: "eccentric",
            name: "free beam, load at 0.3 L, lambda L = 10".into(),
            problem,
            reference: Reference::None,
            expect: Expect::Solved,
        });
    }
    for misalignment in [1e-4, 1e-3, 1e-2] {
        let steel = steel();
        let (radius, length, load) = (0.005, 0.01, 5e3);
        let b = (4.0 * load / length * radius
            / (std::f64::consts::PI * combined_modulus(&steel, &steel)))
        .sqrt();
        let points = PointSet::grid_rectangle(1.6 * b, 0.5 * length, 9, 40).expect("grid");
        let body = Body::uniform_patch(steel);
        let problem = ContactProblem::new(
            points,
            &body,
            &body,
            &Geometry::Surfaces(Surface::Cylinder { radius }, Surface::Plane),
            Loading::load(load).with_tilt_x(misalignment),
        )
        .expect("roller")
        .with_body_edges(false, true);
        cases.push(Case {
            family: "tilted",
            name: format!("roller misaligned {} mrad", 1e3 * misalignment),
            problem,
            reference: Reference::None,
            expect: Expect::Solved,
        });
    }
}

/// The relative error against the closed form, if one applies.
pub fn error(reference: Reference, approach: f64, load: f64) -> Option<f64> {
    match reference {
        Reference::Hertz(h) => Some(approach / h.approach() - 1.0),
        Reference::Punch(p, delta) => Some(load / p.load(delta) - 1.0),
        Reference::Hetenyi(b) => Some(approach / b.centre_deflection() - 1.0),
        Reference::None => None,
    }
}

/// The Hertz solution of the nominal spheres (steel, R = 10 mm and 100 mm,
/// 100 N).
fn nominal_hertz() -> HertzSpheres {
    HertzSpheres::new(
        combined_modulus(&steel(), &steel()),
        combined_radius(0.01, 0.1),
        100.0,
    )
    .expect("Hertz")
}
