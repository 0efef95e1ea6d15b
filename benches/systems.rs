//! Systems of contacts: the two bearings of examples/scenes as their
//! systems (every contact of every rolling element, the rings' and the
//! elements' equilibrium), built and solved whole on one thread: the
//! 9-ball radial bearing (18 contacts of 961 points, dense) and the
//! 20-roller misaligned bearing (40 contacts of 27 x 120 cells,
//! matrix-free).
//!
//! ```sh
//! cargo bench --bench systems        # about a minute
//! ```
//!
//! docs/performance.md §9 has the table.

use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use elcon::analysis::system::SystemSettings;
use elcon::elements::bearing::BearingGrid;
use elcon_fixtures::bearings;

fn systems(c: &mut Criterion) {
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a pool of one thread");
    let mut group = c.benchmark_group("systems");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(10));
    let settings = SystemSettings::default();
    group.bench_function("ball-bearing-9-balls-21-across", |b| {
        b.iter(|| {
            one.install(|| {
                let s = bearings::ball(None)
                    .system(&BearingGrid::default())
                    .expect("valid")
                    .solve(&settings)
                    .expect("solves");
                assert!(s.system.certificate.holds());
                s
            })
        })
    });
    let grid = bearings::ROLLER_GRID;
    group.bench_function("roller-bearing-20-rollers-27x120", |b| {
        b.iter(|| {
            one.install(|| {
                let s = bearings::roller(bearings::CROWN, 1e-3)
                    .system(&grid)
                    .expect("valid")
                    .solve(&settings)
                    .expect("solves");
                assert!(s.system.certificate.holds());
                s
            })
        })
    });
    group.finish();
}

criterion_group!(benches, systems);
criterion_main!(benches);
