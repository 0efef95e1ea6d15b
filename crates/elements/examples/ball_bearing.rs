//! The radial ball bearing of `examples/scenes/ball-bearing-radial.toml`
//! (9 balls of 7.938 mm, 2000 N) solved as a system of 18 contacts and
//! compared with the discrete Hertz-spring model, with its raceways'
//! clearance and at zero clearance, on grids of 15 to 31 points across
//! each contact ellipse: the table of docs/validation.md §6.
//!
//! Run: `cargo run --release -p elcon-elements --example ball_bearing`

use elcon_analysis::system::SystemSettings;
use elcon_elements::bearing::{BallBearing, BearingGrid};
use elcon_fixtures::bearings;

fn main() {
    let base = bearings::ball(None);
    println!(
        "| clearance (mm) | across | loaded | Q_max (N) | springs Q_max | ring x (um) | springs (um) | p_max inner (MPa) | Z Q_max / F_r | steps | zone solves | seconds |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for clearance in [None, Some(0.0)] {
        let bearing = BallBearing {
            diametral_clearance: clearance,
            ..base.clone()
        };
        let springs = bearing.springs().expect("valid").solve().expect("springs");
        for across in [15, 21, 31] {
            let grid = BearingGrid {
                across,
                ..BearingGrid::default()
            };
            let system = bearing.system(&grid).expect("valid bearing");
            let s = system.solve(&SystemSettings::default()).expect("solved");
            assert!(s.system.certificate.holds());
            println!(
                "| {:.3} | {across} | {} | {:.1} | {:.1} | {:.3} | {:.3} | {:.0} | {:.3} | {} | {} | {:.2} |",
                bearing.clearance(),
                s.loaded,
                s.elements[0].load,
                springs.loads[0],
                1e3 * s.ring_displacement[0],
                1e3 * springs.ring_displacement,
                s.elements[0].max_pressure_inner,
                9.0 * s.elements[0].load / 2000.0,
                s.system.iterations,
                s.system.zone_solves,
                s.system.seconds,
            );
        }
    }
}
