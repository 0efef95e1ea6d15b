//! A beam on a very stiff Winkler foundation (Example 2's steel beam on
//! 1e13 lbf/in per in, 600 points): the contact is a few cells under the
//! load, and block pivoting's exchange stalls into Murty's single pivots,
//! one factorization each (1931 of them, 4 s, at 3000 points). It gives up
//! after a few and Lemke's method finishes with the same certified answer.

use std::path::Path;

use elcon_runner::run;
use elcon_scene::Scene;

fn beam(method: &str) -> Scene {
    let text = format!(
        "[scene]\nname = \"stiff\"\n[units]\nlength = \"in\"\nforce = \"lbf\"\npressure = \"psi\"\n\
         [body1]\nmodel = \"beam\"\nyoungs_modulus = 30e6\nwidth = 1.0\ndepth = 4.0\n\
         [body2]\nmodel = \"winkler\"\nmodulus = 1e13\n\
         [points]\ngrid = \"line\"\nstart = -4.45\nend = 4.45\nn = 600\n\
         [loading]\nload = 50000.0\n[solver]\nmethod = \"{method}\"\n"
    );
    Scene::from_str(Path::new("stiff.toml"), &text).unwrap()
}

#[test]
fn a_stalled_block_exchange_hands_over_to_lemke_s_method() {
    let block = run(&beam("block-pivoting")).unwrap().result;
    let stats = serde_json::to_value(&block.header.statistics).unwrap();
    let attempts = stats["attempts"].as_array().unwrap();
    assert_eq!(attempts.len(), 2, "{stats}");
    assert_eq!(attempts[0]["method"], "block-pivoting");
    assert!(
        attempts[0]["outcome"]
            .as_str()
            .unwrap()
            .starts_with("breakdown"),
        "{stats}"
    );
    // A bounded number of factorizations before it gives up.
    assert!(attempts[0]["iterations"].as_u64().unwrap() <= 40, "{stats}");
    assert_eq!(attempts[1]["method"], "lemke");
    assert_eq!(attempts[1]["outcome"], "returned");
    let lemke = run(&beam("lemke")).unwrap().result;
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
    assert!(
        same(block.approach, lemke.approach),
        "{} {}",
        block.approach,
        lemke.approach
    );
    assert!(same(block.max_pressure, lemke.max_pressure));
}
