//! Designs for the worst stress below the surface (`Objective::VonMises`,
//! `Objective::MaxShear`): on a coarse misaligned roller the stress design,
//! started from the pressure design, ends with a worst stress at or below
//! the pressure design's (measured alike: the refined maxima of
//! elcon-analysis's subsurface), every case certified; and each way a
//! stress objective is refused.

use elcon_analysis::ContactProblem;
use elcon_analysis::subsurface::{Subsurface, SubsurfaceOptions};
use elcon_design::{
    Axis, DesignError, DesignFamily, DesignMethod, DesignOptions, DesignRequest, Family, Objective,
    design,
};
use elcon_fixtures::design_cases;
use elcon_influence::{Beam, Body, Material, Stress};

fn steel() -> Body {
    Body::uniform_patch(Material::new(210e3, 0.3).unwrap())
}

/// The worst refined maximum of `measure` over the cases' solutions.
fn worst(
    cases: &[ContactProblem],
    solutions: &[elcon_analysis::ContactSolution],
    tresca: bool,
) -> f64 {
    cases
        .iter()
        .zip(solutions)
        .map(|(c, s)| {
            match Subsurface::of(c.points(), s, &steel(), &SubsurfaceOptions::default()) {
                Subsurface::Stresses(b) if tresca => b.tresca.value,
                Subsurface::Stresses(b) => b.von_mises.value,
                Subsurface::NotApplicable(why) => panic!("{why}"),
            }
        })
        .fold(0.0f64, f64::max)
}

/// A free profile through 6 knots on the roller's 5 x 12 grid, 2 loads x 2
/// misalignments, its ends kept clear.
fn options(objective: Objective, references: &[f64]) -> DesignOptions {
    DesignOptions {
        method: DesignMethod::Descent,
        reference_intensities: Some(references.to_vec()),
        knots: Some((0..6).map(|i| -5.0 + 2.0 * i as f64).collect()),
        edge_clearance: true,
        objective,
        bodies: vec![steel()],
        ..DesignOptions::default()
    }
}

fn stress_design_is_no_worse(objective: Objective) {
    let (cases, references) = design_cases::misaligned_roller(&[2e3, 6e3], &[0.0, 4e-4], (5, 12));
    let pressure = design(
        &cases,
        Axis::Y,
        Family::Free,
        &options(Objective::Pressure, &references),
    )
    .unwrap();
    let stressed = design(
        &cases,
        Axis::Y,
        Family::Free,
        &DesignOptions {
            starts: vec![pressure.profile.clone()],
            uncorrected_start: false,
            fitted_start: false,
            ..options(objective, &references)
        },
    )
    .unwrap();
    let tresca = objective == Objective::MaxShear;
    let before = worst(&cases, &pressure.evaluation.solutions, tresca);
    let after = worst(&cases, &stressed.evaluation.solutions, tresca);
    println!("{objective:?}: pressure design {before:.2}, stress design {after:.2}");
    assert!(after <= before * (1.0 + 1e-9), "{after} > {before}");
    assert!(
        stressed
            .evaluation
            .solutions
            .iter()
            .all(|s| s.certificate.holds())
    );
    assert_eq!(stressed.criterion, objective);
    let on_grid = stressed.worst_stress.unwrap();
    assert!(
        on_grid > 0.0 && on_grid <= after * (1.0 + 1e-9),
        "{on_grid} {after}"
    );
}

#[test]
fn a_von_mises_design_is_no_worse_below_the_surface_than_the_pressure_design() {
    stress_design_is_no_worse(Objective::VonMises);
}

#[test]
fn a_max_shear_design_is_no_worse_below_the_surface_than_the_pressure_design() {
    stress_design_is_no_worse(Objective::MaxShear);
}

fn refused(result: Result<impl std::fmt::Debug, DesignError>, says: &str) {
    match result {
        Err(e @ DesignError::Objective { .. }) => {
            let message = e.to_string();
            assert!(
                message.starts_with("`design.objective` = \"von-mises\""),
                "{message}"
            );
            assert!(message.contains(says), "{message}");
        }
        other => panic!("expected an objective error, got {other:?}"),
    }
}

#[test]
fn a_stress_objective_without_a_field_or_on_the_program_is_refused() {
    let (cases, references) = design_cases::misaligned_roller(&[2e3], &[0.0], (5, 12));
    let von_mises = |bodies: Vec<Body>, method| DesignOptions {
        method,
        bodies,
        ..options(Objective::VonMises, &references)
    };
    let run = |o: DesignOptions| design(&cases, Axis::Y, Family::Quadratic, &o);
    refused(
        run(von_mises(Vec::new(), DesignMethod::Descent)),
        "no body given",
    );
    let beam = Body::beam(Beam {
        youngs_modulus: 210e3,
        second_moment: 1.0,
        loaded_point: 0.0,
    })
    .unwrap();
    refused(
        run(von_mises(
            vec![beam, Body::winkler(1e5)],
            DesignMethod::Descent,
        )),
        "a beam is not a half-space",
    );
    refused(
        run(von_mises(vec![Body::rigid()], DesignMethod::Descent)),
        "a rigid body has no stresses",
    );
    refused(
        run(von_mises(vec![steel()], DesignMethod::Program)),
        "method = \"descent\"",
    );
    let crown = DesignRequest {
        objective: Objective::VonMises,
        bodies: vec![steel()],
        ..DesignRequest::new(
            DesignFamily::CircularCrown {
                radius_range: (100.0, 1e4),
                flat_length: 0.0,
            },
            Axis::Y,
        )
    };
    refused(crown.run(&cases), "circular-crown");
}

#[test]
fn objectives_have_names_and_gradients() {
    for o in Objective::ALL {
        assert_eq!(o.name().parse::<Objective>(), Ok(o));
    }
    assert!("tresca".parse::<Objective>().is_err());
    // Each gradient against central differences of its measure.
    let s = Stress {
        xx: -310.0,
        yy: -120.0,
        zz: -800.0,
        xy: 35.0,
        xz: -140.0,
        yz: 60.0,
    };
    for o in [Objective::VonMises, Objective::MaxShear] {
        let g = o.gradient(&s);
        for (i, gi) in g.iter().enumerate() {
            let h = 1e-4;
            let at = |sign: f64| {
                let mut t = s;
                let c = [
                    &mut t.xx, &mut t.yy, &mut t.zz, &mut t.xy, &mut t.xz, &mut t.yz,
                ];
                *c.into_iter().nth(i).unwrap() += sign * h;
                o.measure(&t)
            };
            let fd = (at(1.0) - at(-1.0)) / (2.0 * h);
            assert!(
                (fd - gi).abs() <= 1e-6 * (1.0 + gi.abs()),
                "{o:?} {i}: {fd} {gi}"
            );
        }
    }
}
