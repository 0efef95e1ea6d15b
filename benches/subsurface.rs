//! The stresses below the surface on large grids, beside the contact solve
//! they follow: Hertz spheres (Example 1) on Love patches over 1.25 contact
//! radii, 32, 64 and 128 cells per radius, S matrix-free. `solve` is the
//! conjugate gradient's whole solve; `field` is one body's subsurface
//! stresses from its solution (the depth layers by FFT, the maxima, the
//! section and the profile: `Subsurface::of`).
//!
//! ```sh
//! cargo bench --bench subsurface     # about 4 minutes
//! ```
//!
//! docs/performance.md §7 has the table.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use elcon::analysis::subsurface::{Subsurface, SubsurfaceOptions};
use elcon::analysis::{ContactProblem, Method, Options};
use elcon::influence::PointSet;
use elcon_fixtures::benchmark;

fn subsurface(c: &mut Criterion) {
    let a = benchmark::hertz_radius();
    let (body, _) = benchmark::bodies();
    let mut group = c.benchmark_group("subsurface");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(10));
    for cells in [32.0, 64.0, 128.0] {
        let points = PointSet::grid_disk(a / cells, 1.25 * a).expect("grid");
        let n = points.len();
        group.throughput(Throughput::Elements(n as u64));
        let problem = benchmark::held(ContactProblem::lattice, points);
        let solve = || {
            problem
                .solve(Method::ConjugateGradient, &Options::default())
                .expect("solves")
        };
        group.bench_function(BenchmarkId::new("solve", n), |b| b.iter(solve));
        let solution = solve();
        assert!(solution.certificate.holds());
        group.bench_function(BenchmarkId::new("field", n), |b| {
            b.iter(|| {
                let s = Subsurface::of(
                    problem.points(),
                    &solution,
                    &body,
                    &SubsurfaceOptions::default(),
                );
                assert!(matches!(s, Subsurface::Stresses(_)));
                s
            })
        });
    }
    group.finish();
}

criterion_group!(benches, subsurface);
criterion_main!(benches);
