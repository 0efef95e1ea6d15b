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
use elcon::analysis::Material;
use elcon::analysis::system::SystemSettings;
use elcon::elements::bearing::{BallBearing, BearingGrid};
use elcon::elements::roller::{Crown, RollerBearing, RollerGrid};

fn ball() -> BallBearing {
    BallBearing {
        ball_diameter: 7.938,
        inner_raceway_diameter: 31.0,
        outer_raceway_diameter: 46.9,
        inner_groove_radius: 0.52 * 7.938,
        outer_groove_radius: 0.53 * 7.938,
        balls: 9,
        diametral_clearance: None,
        material: Material::new(210e3, 0.3).expect("steel"),
        radial_load: 2000.0,
    }
}

fn roller() -> RollerBearing {
    RollerBearing {
        roller_diameter: 9.0,
        roller_length: 9.0,
        crown: Crown::Circular {
            drop: 0.008,
            flat: 4.5,
        },
        inner_raceway_diameter: 57.0,
        outer_raceway_diameter: 75.03,
        rollers: 20,
        diametral_clearance: None,
        material: Material::new(210e3, 0.3).expect("steel"),
        radial_load: 8000.0,
        misalignment: 1e-3,
    }
}

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
                let s = ball()
                    .system(&BearingGrid::default())
                    .expect("valid")
                    .solve(&settings)
                    .expect("solves");
                assert!(s.system.certificate.holds());
                s
            })
        })
    });
    let grid = RollerGrid {
        across: 19,
        along: 120,
        zone: 1.4,
    };
    group.bench_function("roller-bearing-20-rollers-27x120", |b| {
        b.iter(|| {
            one.install(|| {
                let s = roller()
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
