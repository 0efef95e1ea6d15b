//! A design's numbers on one thread and on two are the same to the bit, as
//! a solve's are (docs/performance.md, crates/lcp/tests/threads.rs): the
//! design's own dense solves (its profile's least-squares fit, the
//! sensitivities' rigid-body system, the step's basis) run on the calling
//! thread, not on faer's global parallelism, whose splitting of the work
//! followed the rayon pool's threads (1.038452810936351 on one thread
//! against 1.0384528109363411 on two before).

use std::path::Path;

use elcon_runner::run;
use elcon_scene::Scene;

/// The crowned-roller example on 11 x 96 cells under 5 and 10 kN, without
/// the error estimate: its finer design grid (22 x 192 cells, 4224 points)
/// is held matrix-free, with more than one chunk of the conjugate
/// gradient's passes (4096 entries), and its verification grid on 33 x 288.
fn roller() -> Scene {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/crowned-roller.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let edited = text
        .replacen("nx = 9", "nx = 11", 1)
        .replacen("ny = 40", "ny = 96", 1)
        .replacen(
            "loads = [1000.0, 5000.0, 10000.0]",
            "loads = [5000.0, 10000.0]",
            1,
        )
        .replacen("plots = [\"pressure\", \"design\"]", "plots = []", 1);
    assert!(edited.contains("ny = 96") && edited.contains("loads = [5000.0, 10000.0]"));
    let edited = format!("{edited}\n[solver]\nerror_estimate = false\n");
    Scene::from_str(&path, &edited).unwrap()
}

#[test]
fn a_design_is_the_same_to_the_bit_on_one_thread_and_on_two() {
    let scene = roller();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| run(&scene).unwrap())
    };
    let (one, two) = (on(1), on(2));
    let (a, b) = (
        one.result.design.as_ref().unwrap(),
        two.result.design.as_ref().unwrap(),
    );
    for (ga, gb) in a.grids.iter().zip(&b.grids) {
        assert_eq!(
            ga.objective.to_bits(),
            gb.objective.to_bits(),
            "{}: {} against {}",
            ga.grid,
            ga.objective,
            gb.objective
        );
    }
    assert_eq!(a.objective.to_bits(), b.objective.to_bits());
    assert_eq!(
        format!("{:?}", a.profile),
        format!("{:?}", b.profile),
        "the profiles"
    );
}
