//! Large grids: the matrix-free conjugate gradient (S as an FFT
//! convolution on the lattice) from N = 317 to 321,657, beside the
//! dense block pivoting where S still fits comfortably (up to about 5,000
//! points). Hertz spheres (Example 1) on Love patches over 1.25 contact
//! radii, 8 to 256 cells per radius, unfolded; each sample is the whole
//! solve: the operator or S, the iterations or pivots, the certificate.
//!
//! And the unit costs of the conjugate gradient's two ways of keeping
//! `M z` after a step that changed the contact set, on the lattice
//! operator of 128 cells per radius (the disk of 1.3 radii, 87,013 points):
//! one product against 16, 64 and 256 kernel columns
//! (`LatticeKernel::add_columns`).
//!
//! ```sh
//! cargo bench --bench large          # about 7 minutes
//! cargo bench --bench large -- large/columns     # the unit costs alone
//! ```
//!
//! docs/performance.md §6 has the table of examples/large_grid, which
//! measures the same problems once each up to N = 321,657.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use elcon::analysis::{ContactProblem, Method, Options};
use elcon::influence::{LatticeOperator, PointSet};
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

fn columns(c: &mut Criterion) {
    let a = benchmark::hertz_radius();
    let (body, _) = benchmark::bodies();
    let points = PointSet::grid_disk(a / 128.0, 1.3 * a).expect("grid");
    let mut op = LatticeOperator::new(&points, &[&body, &body]).expect("operator");
    let n = op.len();
    let x = vec![1.0; n];
    let mut y = vec![0.0; n];
    let mut group = c.benchmark_group("large/columns");
    group.sample_size(20);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(5));
    group.bench_function(BenchmarkId::new("product", n), |b| {
        b.iter(|| op.apply(&x, &mut y))
    });
    for k in [16, 64, 256] {
        // Points spread over the disk, as a contact's edge spreads them.
        let columns: Vec<(usize, f64)> = (0..k).map(|t| ((t * 7919) % n, 1.0)).collect();
        group.bench_function(BenchmarkId::new("columns", k), |b| {
            b.iter(|| op.add_columns(&columns, &mut y))
        });
    }
    group.finish();
}

criterion_group!(benches, large, columns);
criterion_main!(benches);
