//! A scene's problem solved twice on one thread, by the conjugate
//! gradient without and with its preconditioner
//! (`Options::preconditioner`, which scenes do not expose): iterations,
//! operator products, preconditioner applications, wall and CPU seconds
//! (operator construction and solve), the approach, the peak pressure and
//! the certificate. docs/performance.md's preconditioner table takes its
//! 512 x 512 roller rows from it:
//!
//! ```sh
//! sed -e 's/^nx = 9$/nx = 512/' -e 's/^ny = 40$/ny = 512/' \
//!     -e 's/^load = 10000.0$/load = 10000.0\ntilt_x = 2e-4/' -e '/^\[design\]/,/^plots/d' \
//!     examples/scenes/crowned-roller.toml > /tmp/roller-512.toml
//! cargo run --release --example roller_preconditioner -- /tmp/roller-512.toml
//! ```
//!
//! Units are the scene's (the roller's: mm, N, MPa).

mod common;

use std::error::Error;
use std::path::PathBuf;
use std::time::Instant;

use elcon::lcp::Options;
use elcon::scene::Scene;

fn main() -> Result<(), Box<dyn Error>> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global()?;
    let path = PathBuf::from(
        std::env::args()
            .nth(1)
            .ok_or("usage: roller_preconditioner SCENE.toml")?,
    );
    let scene = Scene::from_str(&path, &std::fs::read_to_string(&path)?)?;
    for preconditioner in [false, true] {
        let (start, cpu_start) = (Instant::now(), common::cpu_seconds());
        let problem = scene
            .builder(scene.points().clone(), scene.loading())
            .build()?;
        let options = Options {
            preconditioner,
            ..scene.options().clone()
        };
        let sol = problem.solve(scene.method(), &options)?;
        let s = &sol.statistics;
        println!(
            "preconditioner={preconditioner} n={} iterations={} products={} preconditionings={} seconds={:.3} cpu_seconds={:.2} approach={:.10e} max_pressure={:.10e} certificate={:.1e}",
            sol.forces.len(),
            s.iterations(),
            s.products(),
            s.preconditionings(),
            start.elapsed().as_secs_f64(),
            common::cpu_seconds() - cpu_start,
            sol.approach,
            sol.max_pressure,
            sol.certificate.worst(),
        );
    }
    Ok(())
}
