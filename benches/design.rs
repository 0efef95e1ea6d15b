//! How the design stage's cost grows: with the load cases (a crowned
//! roller's free profile over 1 to 100 misalignment cases, one S shared) and
//! with the points (Example 2's quadratic correction from 40 to 800 points
//! per half), the case-decomposed descent beside the paper's program where
//! the program is small enough to run in a benchmark.
//!
//! And the design that holds on any grid: the misaligned roller's free
//! crown over its 33 cases (1, 5 and 10 kN at 0 to 1 mrad), carried over
//! grids from 9 x 40 cells until it holds on the next finer one
//! (`DesignRequest::run_converged`), S matrix-free above 2000 points.
//!
//! ```sh
//! cargo bench --bench design                        # every group (about 9 minutes)
//! cargo bench --bench design -- design/cases        # one group
//! cargo bench --bench design -- design/converged    # the roller over grids (about 3 minutes)
//! ```
//!
//! docs/design.md §2 and §7 have the tables and the fitted growth.

use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{
    BenchmarkGroup, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main,
};
use elcon::analysis::{ContactProblem, Loading, Storage};
use elcon::design::{
    Axis, DesignFamily, DesignMethod, DesignRequest, Family, GridSequence, design,
};
use elcon_fixtures::design_cases::{self, options};

/// The misaligned roller's cases at 5 kN (steel, D = 10 mm, l = 10 mm, 40 x
/// 9 Love patches): `count` misalignments spread evenly over 0 to 1 mrad,
/// one S shared, and their aligned Hertz peak.
fn roller(count: usize) -> (Vec<ContactProblem>, Vec<f64>) {
    let step = if count > 1 {
        1e-3 / (count - 1) as f64
    } else {
        0.0
    };
    let misalignments: Vec<f64> = (0..count).map(|i| i as f64 * step).collect();
    design_cases::misaligned_roller(&[5e3], &misalignments, (9, 40))
}

/// Example 2's beam with `per_half` points per half.
fn beam(per_half: usize) -> ContactProblem {
    design_cases::example2(2 * per_half, 0.0, Loading::load(5e4))
}

/// A benchmark group of `name`: 10 samples, 1 s of warm-up, 10 s measured.
fn group<'c>(c: &'c mut Criterion, name: &str) -> BenchmarkGroup<'c, WallTime> {
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(10));
    group
}

fn cases(c: &mut Criterion) {
    let mut group = group(c, "design/cases");
    for count in [1, 3, 10, 30, 100] {
        let (cases, references) = roller(count);
        let opts = options(DesignMethod::Descent, Some(references));
        group.throughput(Throughput::Elements(count as u64));
        group.bench_with_input(BenchmarkId::new("descent", count), &cases, |b, cases| {
            b.iter(|| design(cases, Axis::Y, Family::Free, &opts).unwrap())
        });
    }
    group.finish();
}

fn points(c: &mut Criterion) {
    let mut group = group(c, "design/points");
    for per_half in [40, 100, 200, 400, 800] {
        let case = [beam(per_half)];
        group.throughput(Throughput::Elements(2 * per_half as u64));
        let methods: &[DesignMethod] = if per_half <= 200 {
            &[DesignMethod::Descent, DesignMethod::Program]
        } else {
            &[DesignMethod::Descent]
        };
        for &method in methods {
            let opts = options(method, None);
            let name = format!("{method:?}").to_lowercase();
            group.bench_with_input(BenchmarkId::new(name, 2 * per_half), &case, |b, case| {
                b.iter(|| design(case, Axis::X, Family::Quadratic, &opts).unwrap())
            });
        }
    }
    group.finish();
}

/// The misaligned roller's 33 cases on its grid refined `fineness` times.
fn roller_at(fineness: f64) -> (Vec<ContactProblem>, Vec<f64>) {
    let misalignments: Vec<f64> = (0..=10).map(|i| i as f64 / 1e4).collect();
    let cells = (
        (9.0 * fineness).round() as usize,
        (40.0 * fineness).round() as usize,
    );
    design_cases::roller_on(&[1e3, 5e3, 10e3], &misalignments, cells, Storage::Auto)
}

fn converged(c: &mut Criterion) {
    let mut group = c.benchmark_group("design/converged");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(60));
    let request = DesignRequest {
        reference_intensities: Some(roller_at(1.0).1),
        ..DesignRequest::new(DesignFamily::Linear(Family::Free), Axis::Y)
    };
    group.bench_function("misaligned_roller_33", |b| {
        b.iter(|| {
            request
                .run_converged(
                    &GridSequence::default(),
                    |f| Ok(Some(roller_at(f).0)),
                    |_| {},
                )
                .unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, cases, points, converged);
criterion_main!(benches);
