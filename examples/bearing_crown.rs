//! A roller bearing's crown designed over its own rollers: the bearing of
//! examples/scenes/roller-bearing-misaligned.toml with straight rollers,
//! misaligned by 0.5 and 1 mrad, solved as a system; each loaded roller's
//! inner contact (its load and its tilt relative to the ring) a design
//! case; a free crown designed over them; the bearing solved again with
//! it. The table of docs/design.md §9.
//!
//! Run: `cargo run --release --example bearing_crown`

use elcon::design::bearing::roller_crown;
use elcon::design::{DesignOptions, Family};
use elcon::elements::roller::{Crown, RollerGrid};
use elcon_fixtures::bearings;

fn main() {
    println!(
        "| misalignment (mrad) | grid | rounds | cases | p_max straight (MPa) | design objective (MPa) | p_max crowned (MPa) | largest drop (um) | Q_max straight / crowned (N) | seconds |"
    );
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---|---:|");
    for misalignment in [0.5e-3, 1e-3] {
        for grid in [
            RollerGrid::default(),
            RollerGrid {
                across: 13,
                along: 80,
                zone: 1.5,
            },
        ] {
            let bearing = bearings::roller(Crown::Straight, misalignment);
            let start = std::time::Instant::now();
            let c = roller_crown(&bearing, &grid, Family::Free, &DesignOptions::default())
                .expect("designed");
            let seconds = start.elapsed().as_secs_f64();
            let (before, after) = c.max_pressures();
            let drop = match &c.crown {
                Crown::Table(rows) => rows.iter().fold(0.0f64, |a, r| a.max(r.1)),
                _ => 0.0,
            };
            let nx = c.before.system.zones[0].pressures.len() / grid.along;
            println!(
                "| {} | {nx} x {} | {} | {} | {before:.0} | {:.0} | {after:.0} | {:.2} | {:.0} / {:.0} | {seconds:.1} |",
                misalignment * 1e3,
                grid.along,
                c.rounds,
                c.cases.len(),
                c.design.objective,
                drop * 1e3,
                c.before.elements[0].load,
                c.after.elements[0].load,
            );
        }
    }
}
