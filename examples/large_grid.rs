//! Dense or matrix-free: Hertz spheres (Example 1's data, Love patches)
//! solved in full on disk grids of growing N, by block pivoting on the
//! dense S and by the conjugate gradient on the lattice operator (an FFT
//! convolution, O(N) memory), side by side: assembly and solve seconds,
//! CG iterations, the bytes each holds, the errors against Hertz and the
//! certificate. The dense side stops where S would pass 4 GB.
//!
//! ```sh
//! cargo run --release --example large_grid                # up to 128 cells per radius
//! cargo run --release --example large_grid -- --max 256   # N up to about 260,000
//! ```
//!
//! The table is docs/performance.md's "Dense or matrix-free"; the
//! crossover sets `elcon_scene::AUTO_DENSE_LIMIT`.

use std::time::Instant;

use elcon::analysis::references::{HertzSpheres, combined_radius};
use elcon::analysis::{ContactProblem, Geometry, Loading, Method, Options, Surface};
use elcon::influence::{Body, LatticeOperator, Material, PointSet, combined_modulus};

/// S above this many bytes is not built (the dense column is left empty).
const DENSE_CEILING: f64 = 4e9;

fn main() {
    let max: f64 = std::env::args()
        .skip_while(|a| a != "--max")
        .nth(1)
        .and_then(|v| v.parse().ok())
        .unwrap_or(128.0);
    let steel = Material::new(30e6, 0.3).expect("steel");
    let hertz = HertzSpheres::new(
        combined_modulus(&steel, &steel),
        combined_radius(1.0, 10.0),
        100.0,
    )
    .expect("Hertz");
    let a = hertz.contact_radius();
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(
        Surface::Sphere { radius: 1.0 },
        Surface::Sphere { radius: 10.0 },
    );
    println!(
        "| cells per radius | N | dense: assembly + block pivoting, s | dense S, MB | matrix-free: operator + CG, s | CG iterations | operator, MB | approach error | peak error | CG certificate |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let mut cells = 8.0;
    while cells <= max {
        let points = PointSet::grid_disk(a / cells, 1.25 * a).expect("grid");
        let n = points.len();
        let dense_bytes = 8.0 * (n as f64) * (n as f64);
        let dense = if dense_bytes <= DENSE_CEILING {
            let start = Instant::now();
            let problem = ContactProblem::new(
                points.clone(),
                &body,
                &body,
                &geometry,
                Loading::load(100.0),
            )
            .expect("dense problem");
            let sol = problem
                .solve(Method::BlockPivoting, &Options::default())
                .expect("dense solve");
            Some((start.elapsed().as_secs_f64(), sol.approach))
        } else {
            None
        };
        let operator_bytes =
            LatticeOperator::estimate_bytes(&points, &[&body, &body]).expect("lattice");
        let start = Instant::now();
        let problem =
            ContactProblem::lattice(points, &body, &body, &geometry, Loading::load(100.0))
                .expect("lattice problem");
        let sol = problem
            .solve(Method::ConjugateGradient, &Options::default())
            .expect("matrix-free solve");
        let seconds = start.elapsed().as_secs_f64();
        if let Some((_, approach)) = dense {
            assert!(
                (approach / sol.approach - 1.0).abs() < 1e-8,
                "the two agree"
            );
        }
        println!(
            "| {cells} | {n} | {} | {} | {seconds:.3} | {} | {:.1} | {:+.2e} | {:+.2e} | {:.1e} |",
            dense.map_or("-".into(), |(s, _)| format!("{s:.3}")),
            if dense.is_some() {
                format!("{:.0}", dense_bytes / 1e6)
            } else {
                format!("({:.0})", dense_bytes / 1e6)
            },
            sol.statistics.iterations(),
            operator_bytes as f64 / 1e6,
            sol.approach / hertz.approach() - 1.0,
            sol.max_pressure / hertz.pressure(0.0) - 1.0,
            sol.certificate.worst(),
        );
        cells *= 2.0;
    }
}
