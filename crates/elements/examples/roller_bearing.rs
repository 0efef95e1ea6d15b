//! The cylindrical roller bearing of
//! `examples/scenes/roller-bearing-misaligned.toml` (20 crowned rollers of
//! 9 x 9 mm, 8000 N, the inner ring turned by 1 mrad) as a system of 40
//! contacts, beside ISO/TS 16281's slicing model: the table of
//! docs/validation.md §6b.
//!
//! Run: `cargo run --release -p elcon-elements --example roller_bearing`

use elcon_analysis::system::SystemSettings;
use elcon_elements::roller::{Crown, RollerBearing, RollerGrid, Slicing};
use elcon_fixtures::bearings;

fn main() {
    let base = bearings::roller(bearings::CROWN, 1e-3);
    println!(
        "| crown | misalignment (mrad) | grid | loaded | Q_max (N) | slicing Q_max | p_max inner (MPa) | slicing p_max | p at the end cell / p_max | steps | zone solves | seconds |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (crown, name) in [
        (Crown::Straight, "straight"),
        (
            Crown::Circular {
                drop: 0.008,
                flat: 4.5,
            },
            "circular 8 um, flat 4.5 mm",
        ),
    ] {
        for misalignment in [0.0, 1e-3] {
            for grid in [RollerGrid::default(), bearings::ROLLER_GRID] {
                let bearing = RollerBearing {
                    crown: crown.clone(),
                    misalignment,
                    ..base.clone()
                };
                let slicing = Slicing {
                    bearing: bearing.clone(),
                    slices: grid.along,
                }
                .solve()
                .expect("slicing");
                let system = bearing.system(&grid).expect("valid bearing");
                let s = system.solve(&SystemSettings::default()).expect("solved");
                assert!(s.system.certificate.holds());
                let zone = &s.system.zones[0];
                let p = &zone.pressures;
                let n = grid.along;
                let nx = p.len() / n;
                // The end cells' largest pressure (the first and last cells along y).
                let end = (0..nx)
                    .flat_map(|i| [p[i * n], p[i * n + n - 1]])
                    .fold(0.0f64, f64::max);
                println!(
                    "| {name} | {} | {} x {} | {} | {:.1} | {:.1} | {:.0} | {:.0} | {:.2} | {} | {} | {:.2} |",
                    misalignment * 1e3,
                    nx,
                    n,
                    s.loaded,
                    s.elements[0].load,
                    slicing.loads[0],
                    s.elements[0].max_pressure_inner,
                    slicing.max_pressures[0],
                    end / zone.max_pressure,
                    s.system.iterations,
                    s.system.zone_solves,
                    s.system.seconds,
                );
            }
        }
    }
}
