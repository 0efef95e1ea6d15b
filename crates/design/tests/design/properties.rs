//! Property tests of the design on random beams on foundations: whatever the
//! stiffness ratio, length, load and load position, every family's design
//! is certified, reproduced by its re-analysis, no worse than the
//! uncorrected geometry, and no better than the lower bound P / L.

use elcon_analysis::{ContactProblem, Geometry, Loading, Method, Options};
use elcon_design::{Analysis, Axis, DesignOptions, Family, Profile, Solver, design, evaluate};
use elcon_influence::{Beam, Body, PointSet};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn designs_are_certified_and_bounded(
        log_ei in 4.0f64..9.0,
        log_k in 4.0f64..8.0,
        length in 2.0f64..12.0,
        log_load in 1.0f64..6.0,
        x0_fraction in -0.3f64..0.3,
        per_half in 4usize..16,
        family in prop_oneof![
            Just(Family::Quadratic),
            Just(Family::Polynomial { degree: 3 }),
            Just(Family::Free),
        ],
    ) {
        let n = 2 * per_half;
        let load = 10f64.powf(log_load);
        let points = PointSet::line(-0.5 * length, 0.5 * length, n).unwrap();
        let case = ContactProblem::new(
            points,
            &Body::beam(Beam {
                youngs_modulus: 10f64.powf(log_ei),
                second_moment: 1.0,
                loaded_point: x0_fraction * length,
            })
            .unwrap(),
            &Body::winkler(10f64.powf(log_k)),
            &Geometry::Separation(vec![0.0; n]),
            // The rotation held at the loaded point, which may be off the
            // beam's middle: a free profile then reaches P / L exactly.
            Loading::load(load).with_tilt_y(0.0),
        ).unwrap();
        let cases = std::slice::from_ref(&case);
        let d = design(cases, Axis::X, family, &DesignOptions::default()).unwrap();
        if let Solver::Program { certificate, .. } = &d.solver {
            prop_assert!(certificate.holds(), "{}", certificate);
        }
        let sol = &d.evaluation.solutions[0];
        prop_assert!(sol.certificate.holds(), "{}", sol.certificate);
        prop_assert!((d.max_intensity / d.evaluation.worst - 1.0).abs() <= 1e-9);
        // Independently of design()'s own re-analysis (block pivoting):
        // Lemke's method on the corrected problem. The contact solution is
        // unique (S positive definite), so the two agree to rounding times
        // the conditioning of S on the contact set: design() demands 1e-9 of
        // block pivoting; Lemke's tableau is given a decade more over these
        // random stiffness ratios (measured: up to about 1e-11).
        let lemke = evaluate(cases, Axis::X, &d.profile, &Analysis::new(Method::Lemke, &Options::default())).unwrap();
        prop_assert!(lemke.solutions[0].certificate.holds(), "{}", lemke.solutions[0].certificate);
        let rel = (lemke.worst - d.max_intensity).abs() / d.max_intensity;
        prop_assert!(rel < 1e-8, "Lemke {} vs {}: {rel:e}", lemke.worst, d.max_intensity);
        let mean = load / length;
        prop_assert!(d.max_intensity >= mean * (1.0 - 1e-12), "{} < P/L {mean}", d.max_intensity);
        let none = evaluate(cases, Axis::X, &Profile::none(), &Analysis::new(Method::BlockPivoting, &Options::default()))
            .unwrap();
        prop_assert!(d.max_intensity <= none.worst * (1.0 + 1e-9), "{} > uncorrected {}", d.max_intensity, none.worst);
        if family == Family::Free {
            prop_assert!((d.max_intensity / mean - 1.0).abs() < 1e-9, "free: {} vs {mean}", d.max_intensity);
        }
    }
}
