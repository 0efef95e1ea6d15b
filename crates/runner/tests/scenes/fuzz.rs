//! The scene parser and validator, fed mutated example scenes and
//! arbitrary text: every input gets a scene or an error, never a panic,
//! and every valid scene gets an estimate and a verdict against a memory
//! ceiling. A bounded fuzz run: a few hundred cases from a fixed seed, so
//! that CI is repeatable; to explore further, set ELCON_FUZZ_SEED (a
//! number) and ELCON_FUZZ_CASES (a multiplier of the cases), e.g.
//! `ELCON_FUZZ_SEED=7 ELCON_FUZZ_CASES=100 cargo test --release -p elcon-scene --test fuzz`.

use std::path::{Path, PathBuf};

use elcon_process::Ceiling;
use elcon_runner::{Estimate, prepare};
use elcon_scene::Scene;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

const SEED: u64 = 0x0e1c_0a16;

/// The example scenes' texts.
fn examples() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .filter(|t| !t.contains("[batch]"))
        .collect()
}

/// Values a hostile user might write.
const VALUES: [&str; 24] = [
    "0",
    "-1",
    "1",
    "3",
    "1e308",
    "-1e308",
    "1e-308",
    "5e-324",
    "nan",
    "inf",
    "-inf",
    "\"\"",
    "\"x\"",
    "\"plane\"",
    "[]",
    "[1.0, 2.0]",
    "{}",
    "true",
    "9223372036854775807",
    "-9223372036854775808",
    "0.5",
    "1.0000001",
    "{ shape = \"sphere\", radius = -1.0 }",
    "[-1.0, 1e300]",
];

/// Keys of the schema, some in the wrong place once inserted.
const KEYS: [&str; 14] = [
    "across",
    "zone",
    "spacing",
    "radius",
    "n",
    "nx",
    "degree",
    "loads",
    "max_constant",
    "refinement_steps",
    "max_pivots",
    "loaded_point",
    "reference_distance",
    "symmetry",
];

/// One edit of a scene's lines.
#[derive(Debug, Clone)]
enum Edit {
    /// Replace the value of line i (mod the lines) with VALUES[v] or a number.
    Value(usize, usize, f64),
    /// Delete line i.
    Delete(usize),
    /// Duplicate line i.
    Duplicate(usize),
    /// Insert `KEYS[k] = VALUES[v]` after line i.
    Insert(usize, usize, usize),
    /// Keep the first i bytes (at a character boundary).
    Truncate(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        4 => (any::<usize>(), 0..VALUES.len() + 1, any::<f64>()).prop_map(|(i, v, x)| Edit::Value(i, v, x)),
        1 => any::<usize>().prop_map(Edit::Delete),
        1 => any::<usize>().prop_map(Edit::Duplicate),
        2 => (any::<usize>(), 0..KEYS.len(), 0..VALUES.len()).prop_map(|(i, k, v)| Edit::Insert(i, k, v)),
        1 => any::<usize>().prop_map(Edit::Truncate),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for e in edits {
        if lines.is_empty() {
            break;
        }
        let at = |i: usize| i % lines.len();
        match *e {
            Edit::Value(i, v, x) => {
                let i = at(i);
                if let Some((key, _)) = lines[i].split_once('=') {
                    let value = VALUES
                        .get(v)
                        .map_or_else(|| format!("{x:e}"), |s| s.to_string());
                    lines[i] = format!("{key}= {value}");
                }
            }
            Edit::Delete(i) => {
                let i = at(i);
                lines.remove(i);
            }
            Edit::Duplicate(i) => {
                let i = at(i);
                lines.insert(i, lines[i].clone());
            }
            Edit::Insert(i, k, v) => {
                let i = at(i);
                lines.insert(i + 1, format!("{} = {}", KEYS[k], VALUES[v]));
            }
            Edit::Truncate(i) => {
                let joined = lines.join("\n");
                let mut cut = i % (joined.len() + 1);
                while !joined.is_char_boundary(cut) {
                    cut -= 1;
                }
                lines = joined[..cut].lines().map(str::to_string).collect();
            }
        }
    }
    lines.join("\n")
}

/// Parses and validates; a valid scene is estimated and judged against a
/// ceiling. Panics propagate to proptest, which reports them as failures.
fn exercise(text: &str) {
    if let Ok(scene) = Scene::from_str(Path::new("fuzz.toml"), text) {
        if let Ok(e) = Estimate::of(&scene) {
            assert!(e.peak_bytes > 0 && e.seconds.is_finite() && e.seconds >= 0.0);
            assert!(!e.summary().is_empty());
        }
        let ceiling = Ceiling::from_limits([(1 << 30, elcon_process::Limit::Option)]);
        let _ = prepare(scene, &ceiling).map_err(|e| e.to_string());
    }
}

fn config(cases: u32) -> Config {
    let var = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    Config {
        cases: cases.saturating_mul(var("ELCON_FUZZ_CASES").unwrap_or(1) as u32),
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(var("ELCON_FUZZ_SEED").unwrap_or(SEED)),
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(400))]

    #[test]
    fn mutated_example_scenes_never_panic(
        which in any::<usize>(),
        edits in prop::collection::vec(edit(), 1..5),
    ) {
        let scenes = examples();
        let text = apply(&scenes[which % scenes.len()], &edits);
        exercise(&text);
    }
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn arbitrary_text_never_panics(text in "(\\PC|\n){0,400}") {
        exercise(&text);
    }

    #[test]
    fn arbitrary_key_values_in_a_valid_frame_never_panic(
        values in prop::collection::vec((0..KEYS.len(), 0..VALUES.len()), 0..6),
    ) {
        let mut text = examples()[0].clone();
        for (k, v) in values {
            text = text.replacen("[points]", &format!("[points]\n{} = {}", KEYS[k], VALUES[v]), 1);
        }
        exercise(&text);
    }
}
