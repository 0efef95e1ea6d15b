//! How the cost of each method grows with the size of its problem.
//!
//! Hertz spheres on Love patches (elcon-fixtures' `benchmark`: sizes N
//! from 64 to 4096, listed there once), solved in full by every method; in
//! the same group a faer Cholesky of the same S (the floor an exact dense
//! method pays) and the assembly of S. Throughput is in pivots (index exchanges for block
//! pivoting), so criterion reports pivots per second.
//!
//! ```sh
//! cargo bench --bench scaling                        # all sizes (about 15 minutes)
//! ELCON_BENCH_MAX=1024 cargo bench --bench scaling   # sizes up to 1024
//! cargo run --release --example bench_report         # table, fitted exponents, docs/img/scaling.svg
//! ```
//!
//! Each size's pivots, iterations and contact sets are written to
//! target/criterion/elcon-scaling-<N>.json for the report.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use elcon::analysis::{Method, Options};
use elcon::influence::assemble;
use elcon_fixtures::benchmark;
use faer::Side;

fn scaling(c: &mut Criterion) {
    let max: usize = std::env::var("ELCON_BENCH_MAX")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(usize::MAX);
    let mut group = c.benchmark_group("scaling");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/criterion");
    let _ = std::fs::create_dir_all(&dir);
    for &n in benchmark::SIZES.iter().filter(|&&n| n <= max) {
        let mut records = Vec::new();
        let problem = benchmark::problem(n);
        let size = problem.points().len();
        // Large sizes: the minimum of ten samples, a few seconds each.
        group.sample_size(if size > 1024 { 10 } else { 20 });
        group.measurement_time(Duration::from_secs(if size > 1024 { 30 } else { 5 }));
        group.warm_up_time(Duration::from_secs(1));
        for method in Method::ALL {
            let sol = problem
                .solve(method, &Options::default())
                .expect("the benchmark problem solves");
            let st = &sol.statistics;
            records.push(format!(
                "{{\"method\":\"{}\",\"n\":{size},\"pivots\":{},\"iterations\":{},\"contact\":{},\"tableau_rows\":{},\"tableau_columns\":{},\"factorizations\":{},\"symmetric_tableau\":{}}}",
                method.name(),
                st.pivots(),
                st.iterations(),
                sol.contact.len(),
                st.tableau_rows(),
                st.tableau_columns(),
                st.factorizations(),
                st.symmetric_tableau()
            ));
            group.throughput(Throughput::Elements(st.pivots().max(1) as u64));
            group.bench_with_input(BenchmarkId::new(method.name(), size), &problem, |b, p| {
                b.iter(|| p.solve(method, &Options::default()).expect("solves"))
            });
        }
        let s = problem
            .entries("the scaling probe")
            .expect("dense")
            .to_owned();
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::new("cholesky", size), &s, |b, s| {
            b.iter(|| s.llt(Side::Lower).expect("S is positive definite"))
        });
        let (body, _) = benchmark::bodies();
        let points = problem.points().clone();
        group.bench_with_input(BenchmarkId::new("assembly", size), &points, |b, pts| {
            b.iter(|| assemble(pts, &[&body, &body]).expect("assembles"))
        });
        let json = format!("[\n{}\n]\n", records.join(",\n"));
        let file = dir.join(format!("elcon-scaling-{size}.json"));
        if let Err(e) = std::fs::write(&file, json) {
            eprintln!("could not write {}: {e}", file.display());
        }
    }
    group.finish();
}

criterion_group!(benches, scaling);
criterion_main!(benches);
