//! Large grids: the matrix-free conjugate gradient (S as an FFT
//! convolution on the lattice) from N = 317 to 321,657, beside the
//! dense block pivoting where S still fits comfortably (up to about 5,000
//! points). Hertz spheres (Example 1) on Love patches over 1.25 contact
//! radii, 8 to 256 cells per radius, unfolded; each sample is the whole
//! solve: the operator or S, the iterations or pivots, the certificate.
//!
//! ```sh
//! cargo bench --bench large          # about 7 minutes
//! ```
//!
//! docs/performance.md §6 has the table of examples/large_grid, which
//! measures the same problems once each up to N = 321,657.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use elcon::analysis::{ContactProblem, Method, Options};
use elcon::influence::PointSet;
use elcon_fixtures::benchmark;

fn large(c: &mut Criterion) {
    let a = benchmark::hertz_radius();
    let mut group = c.benchmark_group("large");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(15));
    for cells in [8.0, 16.0, 32.0, 64.0, 128.0, 256.0] {
        let points = PointSet::grid_disk(a / cells, 1.25 * a).expect("grid");
        let n = points.len();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(
            BenchmarkId::new("conjugate-gradient", n),
            &points,
            |b, p| {
                b.iter(|| {
                    let problem = benchmark::held(ContactProblem::lattice, p.clone());
                    let sol = problem
                        .solve(Method::ConjugateGradient, &Options::default())
                        .expect("solves");
                    assert!(sol.certificate.holds());
                    sol
                })
            },
        );
        if n <= 5_500 {
            group.bench_with_input(BenchmarkId::new("block-pivoting", n), &points, |b, p| {
                b.iter(|| {
                    benchmark::held(ContactProblem::new, p.clone())
                        .solve(Method::BlockPivoting, &Options::default())
                        .expect("solves")
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, large);
criterion_main!(benches);
