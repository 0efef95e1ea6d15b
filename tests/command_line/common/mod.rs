//! What the command-line tests (cli.rs, faults.rs) share: running the
//! `elcon` binary as a user does, the scratch directories, reading what it
//! writes, and the example scenes with edits.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The variable of elcon-scene's test-only fault points.
pub const FAULTS: &str = "ELCON_FAULTS";

/// `elcon args`, from the workspace's root, with `env` set: the variables a
/// run reads from its environment (the fault points, the memory ceiling, a
/// scheduler's task) are cleared first, so only `env` sets them.
pub fn command(args: &[&str], env: &[(&str, &str)]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_elcon"));
    c.args(args).current_dir(env!("CARGO_MANIFEST_DIR"));
    for var in [
        FAULTS,
        "ELCON_MEMORY_LIMIT",
        "SLURM_ARRAY_TASK_ID",
        "JOB_COMPLETION_INDEX",
    ] {
        c.env_remove(var);
    }
    c.envs(env.iter().copied());
    c
}

/// `elcon args` run to its end with `env` set ([`command`]).
pub fn elcon_with(args: &[&str], env: &[(&str, &str)]) -> Output {
    command(args, env).output().expect("the elcon binary runs")
}

/// `elcon args` run to its end.
pub fn elcon(args: &[&str]) -> Output {
    elcon_with(args, &[])
}

/// A fresh directory for one test's files, named by the test target and
/// `name` (unique among the binary's tests, which run at once).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "elcon-{}-{}-{name}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A run's standard output, then its standard error.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// The text of the run `o` ([`text`]), asserted to have exited with
/// `code` and to say each of `parts`.
#[track_caller]
pub fn exited(o: &Output, code: i32, parts: &[&str]) -> String {
    let t = text(o);
    assert_eq!(o.status.code(), Some(code), "{t}");
    for part in parts {
        assert!(t.contains(part), "{part}: {t}");
    }
    t
}

/// The JSON file at `path`.
pub fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The text of examples/scenes/`name`.toml.
pub fn example_scene(name: &str) -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("examples/scenes/{name}.toml")),
    )
    .unwrap()
}

/// `text` with each `(from, to)` of `edits` in turn: the first `from`
/// replaced by `to`. Each `from` must be there.
pub fn edited(text: &str, edits: &[(&str, &str)]) -> String {
    let mut t = text.to_string();
    for (from, to) in edits {
        assert!(t.contains(from), "the scene has `{from}`");
        t = t.replacen(from, to, 1);
    }
    t
}
