//! Faults and limits, through the `elcon` command line as a user meets
//! them: a scene over the memory ceiling, a panic beside a good scene, a
//! batch with failing runs, two writers of one directory, a run killed
//! mid-write, inconsistent shards, a sweep split over scheduler tasks. In
//! each case nothing that finished is lost and no directory is left half
//! written. docs/reliability.md lists the same cases.
//!
//! The panics and pauses come from the test-only fault points of
//! elcon-scene (its `fault-injection` feature, which this package's
//! dev-dependency turns on for the `elcon` the tests run), asked for
//! through the `ELCON_FAULTS` variable.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Child, Output, Stdio};
use std::time::{Duration, Instant};

use common::{
    FAULTS, command, edited, elcon, elcon_with, example_scene, exited, json, scratch, text,
};

/// `elcon` started in the background, its output captured.
fn spawn(args: &[&str], env: &[(&str, &str)]) -> Child {
    command(args, env)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the elcon binary starts")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `elcon batch file --out out` with the further `options`, and `env` set.
fn batch(file: &Path, out: &Path, options: &[&str], env: &[(&str, &str)]) -> Output {
    let mut args = vec!["batch", s(file), "--out", s(out)];
    args.extend_from_slice(options);
    elcon_with(&args, env)
}

/// The paper's Example 1 (149 points, fast), with `edits` applied, as
/// `dir/<file>.toml` named `name`.
fn small_scene(dir: &Path, file: &str, name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let named = example_scene("example1-paper-model").replace(
        "name = \"example1-paper-model\"",
        &format!("name = \"{name}\""),
    );
    let path = dir.join(format!("{file}.toml"));
    std::fs::write(&path, edited(&named, edits)).unwrap();
    path
}

/// examples/scenes/`example`.toml with `edits` applied, as `dir/<file>`.
fn example_in(dir: &Path, file: &str, example: &str, edits: &[(&str, &str)]) -> PathBuf {
    let path = dir.join(file);
    std::fs::write(&path, edited(&example_scene(example), edits)).unwrap();
    path
}

/// Asserts that the rows of the batch table `results` (a results.json)
/// have the statuses `expected`, in order: `ok`, or a failure's status
/// that says the words given.
#[track_caller]
fn assert_statuses(results: &Path, expected: &[&str]) {
    let table = json(results);
    let status: Vec<&str> = table["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["status"].as_str().unwrap())
        .collect();
    assert_eq!(status.len(), expected.len(), "{status:?}");
    for (status, expected) in status.iter().zip(expected) {
        match *expected {
            "ok" => assert_eq!(*status, "ok"),
            failure => assert!(status.contains(failure), "{failure}: {status}"),
        }
    }
}

/// Entries of `dir` whose names say they are temporary.
fn litter(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp") || n.ends_with(".old"))
        .collect()
}

/// Waits (at most 60 s) until `path` exists.
fn wait_for(what: impl Fn() -> bool) {
    let start = Instant::now();
    while !what() {
        assert!(start.elapsed() < Duration::from_secs(60), "timed out");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Whether a staging directory of `name` under `out` holds result.json.
fn staging_has_result(out: &Path, name: &str) -> bool {
    std::fs::read_dir(out).is_ok_and(|entries| {
        entries.flatten().any(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            n.starts_with(&format!(".{name}."))
                && n.ends_with(".tmp")
                && e.path().join("result.json").exists()
        })
    })
}

#[test]
fn a_scene_over_the_memory_ceiling_is_refused_and_the_others_run() {
    let dir = scratch("memory");
    let out = dir.join("out");
    // Example 1 in full (1653 points, not folded): about 81 MiB.
    let big = dir.join("big.toml");
    let spheres = example_scene("example1-spheres");
    std::fs::write(
        &big,
        spheres.replace(
            "method = \"block-pivoting\"",
            "method = \"block-pivoting\"\nsymmetry = \"none\"",
        ),
    )
    .unwrap();
    let good = small_scene(&dir, "good", "good", &[]);
    for (args, env) in [
        (vec!["--memory-limit", "64M"], vec![]),
        (vec![], vec![("ELCON_MEMORY_LIMIT", "64M")]),
    ] {
        let _ = std::fs::remove_dir_all(&out);
        let mut run = vec!["run", s(&big), s(&good), "--out", s(&out)];
        run.extend(args.iter().copied());
        let o = elcon_with(&run, &env);
        let t = exited(
            &o,
            1,
            &[
                "scene `example1-spheres`: too big for the memory available: N = 1653 points needs about",
                "block-pivoting keeps about 3.25 matrices of 1653 x 1653",
                "the ceiling is 57.6 MiB",
                "What helps: folding by symmetry",
            ],
        );
        assert!(!t.contains("panicked"), "{t}");
        assert!(!out.join("example1-spheres").exists());
        assert!(out.join("good/result.json").exists(), "{t}");
        // `check` refuses it too, with the same limit.
        let mut check = vec!["check", s(&big)];
        check.extend(args.iter().copied());
        let o = elcon_with(&check, &env);
        exited(&o, 1, &["too big for the memory available"]);
    }
    // In a batch, the run over the ceiling is a failed row; the other runs.
    let spheres_dir = dir.join("sweep");
    std::fs::create_dir_all(&spheres_dir).unwrap();
    std::fs::write(spheres_dir.join("spheres.toml"), &spheres).unwrap();
    std::fs::write(
        spheres_dir.join("folding.toml"),
        "[batch]\nscene = \"spheres.toml\"\n[[batch.group]]\n\"solver.symmetry\" = [\"auto\", \"none\"]\n",
    )
    .unwrap();
    let folding = spheres_dir.join("folding.toml");
    let o = batch(&folding, &out, &["--memory-limit", "64M"], &[]);
    exited(&o, 1, &["2 runs, 1 failed"]);
    assert_statuses(
        &out.join("folding/results.json"),
        &["ok", "too big for the memory available: N = 1653 points"],
    );
    // Without a limit it fits, and check prints the estimate.
    let o = elcon(&["check", s(&big)]);
    exited(&o, 0, &["1653 points; peak memory about"]);
    // A size that is not one is a usage error.
    let o = elcon(&["run", s(&good), "--memory-limit", "4X"]);
    exited(&o, 2, &[]);
    let o = elcon_with(&["check", s(&good)], &[("ELCON_MEMORY_LIMIT", "lots")]);
    exited(&o, 2, &["ELCON_MEMORY_LIMIT=lots"]);
}

#[test]
fn a_panicking_scene_is_reported_and_the_good_one_written() {
    let dir = scratch("panic");
    let out = dir.join("out");
    let bad = small_scene(&dir, "bad", "bad", &[]);
    let good = small_scene(&dir, "good", "good", &[]);
    let o = elcon_with(
        &["run", s(&bad), s(&good), "--out", s(&out)],
        &[(FAULTS, "panic=bad")],
    );
    let t = exited(
        &o,
        1,
        &[
            "error: scene `bad`: internal error (this is a bug; please report it with the scene): fault injected",
        ],
    );
    // The panic's place is in the report; the default hook printed nothing.
    assert!(t.contains("faults.rs:"), "{t}");
    assert!(!t.contains("panicked at"), "{t}");
    assert!(!out.join("bad").exists());
    assert!(out.join("good/result.json").exists(), "{t}");
    assert!(litter(&out).is_empty(), "{:?}", litter(&out));
    // The table's header once, before the first result; none without one.
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        stdout
            .matches("scene                        method")
            .count(),
        1
    );
    assert!(stdout.starts_with("scene "), "{stdout}");
    let o = elcon_with(
        &["run", s(&bad), "--out", s(&out)],
        &[(FAULTS, "panic=bad")],
    );
    assert!(o.stdout.is_empty(), "{}", text(&o));
}

#[test]
fn two_scenes_of_one_name_are_refused_before_any_solve() {
    let dir = scratch("faults-names");
    let out = dir.join("out");
    let a = small_scene(&dir, "a", "same", &[]);
    let b = small_scene(&dir, "b", "same", &[("load = 100.0", "load = 200.0")]);
    let c = small_scene(&dir, "c", "other", &[]);
    let o = elcon(&["run", s(&a), s(&b), s(&c), "--out", s(&out)]);
    exited(
        &o,
        1,
        &["both name scene `same`, so they would write one directory"],
    );
    assert!(!out.join("same").exists());
    assert!(out.join("other/result.json").exists());
    let o = elcon(&["check", s(&a), s(&b)]);
    exited(&o, 1, &["both name scene `same`"]);
}

#[test]
fn a_batch_with_failing_runs_writes_its_tables() {
    let dir = scratch("faults-batch");
    let base = small_scene(&dir, "base", "base", &[]);
    let _ = base;
    std::fs::write(
        dir.join("sweep.toml"),
        "[batch]\nscene = \"base.toml\"\n[[batch.group]]\n\"points.across\" = [5, 6, 7, 9]\n",
    )
    .unwrap();
    let out = dir.join("out");
    // Run 2 (across 7) panics; run 1 (across 6) is invalid.
    let panics = [(FAULTS, "panic=002-points.across-7")];
    let o = batch(&dir.join("sweep.toml"), &out, &["--jobs", "2"], &panics);
    let t = exited(&o, 1, &["4 runs, 2 failed"]);
    assert!(!t.contains("panicked at"), "{t}");
    assert_statuses(
        &out.join("sweep/results.json"),
        &[
            "ok",
            "`points.across` = 6: must be odd",
            "internal error (this is a bug",
            "ok",
        ],
    );
    for file in ["results.csv", "results.md"] {
        let table = std::fs::read_to_string(out.join("sweep").join(file)).unwrap();
        assert!(table.contains("this is a bug"), "{file}");
    }
    assert!(out.join("sweep/000-points.across-5/result.json").exists());
    assert!(!out.join("sweep/002-points.across-7").exists());
    assert!(litter(&out).is_empty(), "{:?}", litter(&out));
}

#[test]
fn two_concurrent_runs_into_one_out_do_not_mix_their_files() {
    let dir = scratch("concurrent");
    let out = dir.join("out");
    let plots = [(
        "method = \"restricted-simplex\"",
        "method = \"restricted-simplex\"\n[outputs]\nplots = [\"pressure\"]",
    )];
    let a = small_scene(&dir, "a", "x", &plots);
    let b = small_scene(
        &dir,
        "b",
        "x",
        &[plots[0], ("load = 100.0", "load = 250.0")],
    );
    // Each pauses 300 ms after each of its three files.
    let slow = [(FAULTS, "write_delay_ms=300")];
    let first = spawn(&["run", s(&a), "--out", s(&out)], &slow);
    wait_for(|| staging_has_result(&out, "x"));
    let second = spawn(&["run", s(&b), "--out", s(&out)], &slow);
    let (first, second) = (
        first.wait_with_output().unwrap(),
        second.wait_with_output().unwrap(),
    );
    assert_eq!(first.status.code(), Some(0), "{}", text(&first));
    assert_eq!(second.status.code(), Some(0), "{}", text(&second));
    assert!(
        text(&second).contains("waiting: another elcon is writing"),
        "{}",
        text(&second)
    );
    // One writer's files only: the second's, whole.
    let r = json(&out.join("x/result.json"));
    assert!(
        (r["load"].as_f64().unwrap() / 250.0 - 1.0).abs() < 1e-12,
        "{r}"
    );
    let csv = std::fs::read_to_string(out.join("x/pressure.csv")).unwrap();
    let total: f64 = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(4).unwrap().parse::<f64>().unwrap())
        .sum();
    assert!((total / 250.0 - 1.0).abs() < 1e-9, "{total}");
    assert!(out.join("x/pressure.svg").exists());
    assert!(litter(&out).is_empty(), "{:?}", litter(&out));
}

#[test]
fn a_run_killed_mid_write_leaves_the_old_directory_and_the_rerun_cleans_up() {
    let dir = scratch("killed");
    let out = dir.join("out");
    let plots = (
        "method = \"restricted-simplex\"",
        "method = \"restricted-simplex\"\n[outputs]\nplots = [\"pressure\"]",
    );
    let old = small_scene(&dir, "old", "x", &[plots]);
    let o = elcon(&["run", s(&old), "--out", s(&out)]);
    exited(&o, 0, &[]);
    // A second run, killed (SIGKILL) after its first file.
    let new = small_scene(&dir, "new", "x", &[plots, ("load = 100.0", "load = 300.0")]);
    let mut child = spawn(
        &["run", s(&new), "--out", s(&out)],
        &[(FAULTS, "write_delay_ms=5000")],
    );
    wait_for(|| staging_has_result(&out, "x"));
    child.kill().unwrap();
    child.wait().unwrap();
    // The old directory stands, whole; the killed run's staging is left.
    let load = json(&out.join("x/result.json"))["load"].as_f64().unwrap();
    assert!((load / 100.0 - 1.0).abs() < 1e-12, "{load}");
    assert!(out.join("x/pressure.csv").exists() && out.join("x/pressure.svg").exists());
    assert_eq!(litter(&out).len(), 1, "{:?}", litter(&out));
    // The next run into the directory removes it, and replaces the old
    // outputs as a unit: no CSV or SVG of the old run beside the new JSON.
    let lean = small_scene(
        &dir,
        "lean",
        "x",
        &[(
            "method = \"restricted-simplex\"",
            "method = \"restricted-simplex\"\n[outputs]\npressure_csv = false",
        )],
    );
    let o = elcon(&["run", s(&lean), "--out", s(&out)]);
    exited(&o, 0, &[]);
    assert!(litter(&out).is_empty(), "{:?}", litter(&out));
    let files: Vec<String> = std::fs::read_dir(out.join("x"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(files, ["result.json"]);
}

/// A batch of six quick runs: Example 1 at three grids by two methods.
fn six_runs(dir: &Path, name: &str, loads: &str) -> PathBuf {
    small_scene(dir, "base", "base", &[]);
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "[batch]\nname = \"{name}\"\nscene = \"base.toml\"\n[[batch.group]]\n\
             \"points.across\" = [5, 9, 13]\n\"solver.method\" = [\"lemke\", \"block-pivoting\"]\n\
             [[batch.group]]\n\"loading.load\" = [{loads}]\n"
        ),
    )
    .unwrap();
    path
}

/// A table's rows without the run times (which differ from run to run).
fn rows_without_times(table: &serde_json::Value) -> Vec<serde_json::Value> {
    table["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let mut r = r.clone();
            let o = r.as_object_mut().unwrap();
            o.remove("seconds_total");
            o.remove("seconds_solve");
            r
        })
        .collect()
}

/// [`six_runs`] at the loads 50 and 150 (eight runs) as `dir/sweep.toml`,
/// run whole into `out`: the batch file and its results.json.
fn whole_sweep(dir: &Path, out: &Path) -> (PathBuf, serde_json::Value) {
    let file = six_runs(dir, "sweep", "50.0, 150.0");
    exited(&batch(&file, out, &[], &[]), 0, &[]);
    (file, json(&out.join("sweep/results.json")))
}

/// Shard `k` of `n` of the batch `sweep` under `out`.
fn shard(out: &Path, k: u32, n: u32) -> PathBuf {
    out.join(format!("sweep-shard-{k}-of-{n}"))
}

/// `elcon merge` of the directories `dirs` into `out`.
fn merge(dirs: &[&Path], out: &Path) -> Output {
    let mut args = vec!["merge"];
    args.extend(dirs.iter().map(|p| s(p)));
    args.extend(["--out", s(out)]);
    elcon(&args)
}

/// Merges `dirs` into `out`, asserting it succeeds saying each of `parts`
/// and writes `whole`'s rows (the run times aside): the merged table.
#[track_caller]
fn merged_as(
    whole: &serde_json::Value,
    dirs: &[&Path],
    out: &Path,
    parts: &[&str],
) -> serde_json::Value {
    exited(&merge(dirs, out), 0, parts);
    let m = json(&out.join("results.json"));
    assert_eq!(rows_without_times(&m), rows_without_times(whole));
    m
}

#[test]
fn a_sweep_run_as_scheduler_tasks_merges_to_exactly_the_unsharded_tables() {
    let dir = scratch("shards");
    let out = dir.join("out");
    let (sweep, whole) = whole_sweep(&dir, &out);
    assert_eq!(whole["runs"], 8);
    let auto = ["batch", s(&sweep), "--out", s(&out), "--shard", "auto"];
    // A SLURM job array of three tasks (--array=0-2), all at once, each
    // its own process.
    let tasks: Vec<Child> = (0..3)
        .map(|id| {
            let id = id.to_string();
            spawn(
                &auto,
                &[
                    ("SLURM_ARRAY_TASK_ID", id.as_str()),
                    ("SLURM_ARRAY_TASK_COUNT", "3"),
                    ("SLURM_ARRAY_TASK_MIN", "0"),
                ],
            )
        })
        .collect();
    for t in tasks {
        exited(&t.wait_with_output().unwrap(), 0, &[]);
    }
    let shards: Vec<PathBuf> = (1..=3).map(|k| shard(&out, k, 3)).collect();
    let shards: Vec<&Path> = shards.iter().map(PathBuf::as_path).collect();
    let m = merged_as(
        &whole,
        &shards,
        &dir.join("merged"),
        &["merged 8 runs of `sweep`"],
    );
    assert_eq!(m["batch_hash"], whole["batch_hash"]);
    // A Kubernetes indexed Job of two completions.
    for index in ["0", "1"] {
        let env = [("JOB_COMPLETION_INDEX", index), ("ELCON_SHARD_COUNT", "2")];
        exited(&elcon_with(&auto, &env), 0, &[]);
    }
    let (one, two) = (shard(&out, 1, 2), shard(&out, 2, 2));
    merged_as(&whole, &[&two, &one], &dir.join("merged2"), &[]);
    // A SLURM array of listed ids (--array=1,3,7) says no shard by its
    // ids, and SLURM and Kubernetes naming different shards are refused:
    // usage errors, nothing run.
    let sparse = [
        ("SLURM_ARRAY_TASK_ID", "3"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
        ("SLURM_ARRAY_TASK_MIN", "1"),
        ("SLURM_ARRAY_TASK_MAX", "7"),
    ];
    let refused = dir.join("refused");
    let o = batch(&sweep, &refused, &["--shard", "auto"], &sparse);
    exited(&o, 2, &["not a regular range"]);
    let both = [
        ("SLURM_ARRAY_TASK_ID", "0"),
        ("SLURM_ARRAY_TASK_COUNT", "2"),
        ("SLURM_ARRAY_TASK_MIN", "0"),
        ("JOB_COMPLETION_INDEX", "1"),
        ("ELCON_SHARD_COUNT", "2"),
    ];
    let o = batch(&sweep, &refused, &["--shard", "auto"], &both);
    exited(
        &o,
        2,
        &[
            "shard 1/2 (SLURM_ARRAY_TASK_ID)",
            "shard 2/2 (JOB_COMPLETION_INDEX",
        ],
    );
    assert!(!refused.exists());
    // Outside a scheduler, --shard auto is a usage error.
    exited(&elcon(&auto), 2, &["SLURM_ARRAY_TASK_ID"]);
}

#[test]
fn merge_refuses_shards_that_are_not_one_batch_each_once() {
    let dir = scratch("merge");
    let sweep = six_runs(&dir, "sweep", "50.0");
    let out = dir.join("out");
    for k in ["1/2", "2/2", "1/3"] {
        exited(&batch(&sweep, &out, &["--shard", k], &[]), 0, &[]);
    }
    let shard = |k: u32, n: u32| shard(&out, k, n);
    let merged = dir.join("merged");
    let refused = |dirs: &[&Path], message: &str| {
        let o = merge(dirs, &merged);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(1), "{message}: {t}");
        assert!(t.contains(message), "{message}: {t}");
        assert!(!merged.exists(), "{message}");
    };
    refused(&[&shard(1, 2)], "shards missing: 2/2");
    refused(&[&shard(1, 2), &shard(1, 2)], "shard 1/2 is given twice");
    refused(&[&shard(1, 2), &shard(1, 3)], "shard counts differ");
    // The sweep edited between the shards: the hashes differ.
    let other = dir.join("other");
    std::fs::create_dir_all(&other).unwrap();
    let edited = six_runs(&other, "sweep", "60.0");
    exited(&batch(&edited, &other, &["--shard", "2/2"], &[]), 0, &[]);
    refused(
        &[&shard(1, 2), &other.join("sweep-shard-2-of-2")],
        "are from different versions of batch `sweep`",
    );
    // Another batch.
    let renamed = six_runs(&other, "another", "50.0");
    exited(&batch(&renamed, &other, &["--shard", "2/2"], &[]), 0, &[]);
    refused(
        &[&shard(1, 2), &other.join("another-shard-2-of-2")],
        "is from batch `another`",
    );
    // Conflicting rows: shard 2 claims a row of shard 1.
    let tampered = dir.join("tampered");
    std::fs::create_dir_all(&tampered).unwrap();
    let mut t = json(&shard(2, 2).join("results.json"));
    let row0 = json(&shard(1, 2).join("results.json"))["rows"][0].clone();
    t["rows"].as_array_mut().unwrap().push(row0);
    std::fs::write(tampered.join("results.json"), t.to_string()).unwrap();
    refused(
        &[&shard(1, 2), &tampered],
        "row 0 does not belong to shard 2/2",
    );
    let mut t = json(&shard(2, 2).join("results.json"));
    let dup = t["rows"][0].clone();
    t["rows"].as_array_mut().unwrap().push(dup);
    std::fs::write(tampered.join("results.json"), t.to_string()).unwrap();
    refused(&[&shard(1, 2), &tampered], "two rows with index 1");
    // The good pair merges; merge will not replace a directory it did not write.
    let (one, two) = (shard(1, 2), shard(2, 2));
    exited(&merge(&[&one, &two], &out), 1, &["holds the shard"]);
    exited(&merge(&[&one, &two], &merged), 0, &[]);
}

#[test]
fn a_huge_sweep_is_checked_by_size_and_a_too_large_one_refused() {
    let dir = scratch("huge");
    small_scene(&dir, "base", "base", &[]);
    let values = |n: usize, scale: f64| {
        (1..=n)
            .map(|i| format!("{}", scale * i as f64))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let write = |name: &str, keys: &[(&str, String)]| {
        let mut t = format!("[batch]\nname = \"{name}\"\nscene = \"base.toml\"\n[[batch.group]]\n");
        for (k, v) in keys {
            t.push_str(&format!("\"{k}\" = [{v}]\n"));
        }
        let p = dir.join(format!("{name}.toml"));
        std::fs::write(&p, t).unwrap();
        p
    };
    // A million runs: its size at once, a covering set checked; the one
    // invalid zone (0.9) is among the runs checked.
    let zones = (0..999)
        .map(|i| format!("{}", 1.1 + 0.001 * i as f64))
        .chain(["0.9".to_string()])
        .collect::<Vec<_>>()
        .join(", ");
    let million = write(
        "million",
        &[("loading.load", values(1000, 1.0)), ("points.zone", zones)],
    );
    let o = elcon(&["check", s(&million)]);
    exited(
        &o,
        1,
        &[
            "batch `million`: 1,000,000 runs, 1 failed",
            "covering every value of every key",
            "`points.zone` = 0.9",
        ],
    );
    // A billion runs: refused with its size, even for one shard.
    let billion = write(
        "billion",
        &[
            ("loading.load", values(1000, 1.0)),
            ("points.zone", values(1000, 1.0)),
            ("points.across", values(1000, 2.0)),
        ],
    );
    for args in [
        vec!["check", s(&billion)],
        vec!["batch", s(&billion), "--shard", "1/1000"],
    ] {
        let o = elcon(&args);
        exited(
            &o,
            1,
            &["1,000,000,000 runs: a sweep has at most 1,000,000 runs"],
        );
    }
}

/// Each run directory's result.json under a batch directory, by name.
fn run_results(dir: &Path) -> std::collections::BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter(|e| e.path().join("result.json").exists())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read_to_string(e.path().join("result.json")).unwrap(),
            )
        })
        .collect()
}

#[test]
fn a_batch_killed_at_any_point_resumes_without_redoing_finished_runs() {
    let dir = scratch("resume");
    let (sweep, whole) = whole_sweep(&dir, &dir.join("whole"));
    // Killed (SIGKILL) before the first run is journaled (its directory
    // in place), after the second and after the sixth; stopped by SIGTERM
    // after the third. One run at a time, so the journal's order is the
    // runs'.
    for (fault, signal) in [
        ("kill_before_record=1", "KILL"),
        ("kill_after_record=2", "KILL"),
        ("kill_after_record=6", "KILL"),
        ("term_after_record=3", "TERM"),
    ] {
        let out = dir.join(fault.replace('=', "-"));
        let o = batch(&sweep, &out, &["--jobs", "1"], &[(FAULTS, fault)]);
        let t = text(&o);
        let target = out.join("sweep");
        let journaled = std::fs::read_to_string(target.join("journal.jsonl"))
            .unwrap()
            .lines()
            .count()
            - 1;
        if signal == "KILL" {
            assert_eq!(o.status.code(), None, "{fault}: killed by a signal: {t}");
            assert!(!target.join("results.json").exists(), "{fault}");
        } else {
            // SIGTERM: the run in flight stops, the tables of what finished
            // are written, exit 130.
            assert_eq!(o.status.code(), Some(130), "{fault}: {t}");
            assert!(t.contains("interrupted:"), "{t}");
            let partial = json(&target.join("results.json"));
            let rows = partial["rows"].as_array().unwrap().len();
            assert!(rows >= 3, "{fault}: {partial}");
            assert_eq!(partial["pending"].as_u64().unwrap() as usize, 8 - rows);
            // An unfinished table does not merge.
            let o = merge(&[&target], &dir.join("m"));
            assert!(text(&o).contains("unfinished"), "{}", text(&o));
        }
        let before = run_results(&target);
        let finished = journaled.min(before.len());
        // The same command again keeps what finished and runs the rest.
        let o = batch(&sweep, &out, &["--jobs", "1"], &[]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(0), "{fault}: {t}");
        if finished > 0 {
            assert!(
                t.contains(&format!(
                    "{finished} finished runs kept, {} to run",
                    8 - finished
                )),
                "{fault}: {t}"
            );
        }
        assert!(litter(&target).is_empty(), "{:?}", litter(&target));
        // The kept runs were not run again: their files are as they were.
        let after = run_results(&target);
        let kept = before
            .iter()
            .filter(|(k, v)| after.get(*k) == Some(v))
            .count();
        assert!(kept >= finished, "{fault}: {kept} of {finished} kept");
        let resumed = json(&target.join("results.json"));
        assert_eq!(
            rows_without_times(&resumed),
            rows_without_times(&whole),
            "{fault}"
        );
        assert_eq!(resumed["batch_hash"], whole["batch_hash"]);
        assert!(resumed.get("pending").is_none(), "{resumed}");
    }
}

#[test]
fn resumed_shards_merge_to_exactly_an_unbroken_run() {
    let dir = scratch("resume-shards");
    let out = dir.join("out");
    let (sweep, whole) = whole_sweep(&dir, &out);
    for k in ["1/2", "2/2"] {
        // Each shard killed after its first run, then run again.
        let killed = [(FAULTS, "kill_after_record=1")];
        let o = batch(&sweep, &out, &["--shard", k, "--jobs", "1"], &killed);
        assert_eq!(o.status.code(), None, "{}", text(&o));
        let o = batch(&sweep, &out, &["--shard", k], &[]);
        exited(&o, 0, &["1 finished runs kept"]);
    }
    let (one, two) = (shard(&out, 1, 2), shard(&out, 2, 2));
    let m = merged_as(&whole, &[&one, &two], &dir.join("merged"), &[]);
    // Every value of every row to the last digit: the rows are their runs'
    // result.json, read back exactly.
    for (r, w) in m["rows"]
        .as_array()
        .unwrap()
        .iter()
        .zip(whole["rows"].as_array().unwrap())
    {
        assert_eq!(r["approach"].as_f64(), w["approach"].as_f64());
        assert_eq!(r["max_pressure"].as_f64(), w["max_pressure"].as_f64());
    }
    // A hand-edited value is refused, naming the field.
    let mut t = json(&two.join("results.json"));
    t["rows"][0]["approach"] = serde_json::json!(1.0);
    std::fs::write(two.join("results.json"), t.to_string()).unwrap();
    exited(
        &merge(&[&one, &two], &dir.join("merged2")),
        1,
        &["does not hold its run's values: `approach` is 1.0 in the table"],
    );
    // Another version of the batch into the same directory starts afresh.
    let edited = six_runs(&dir, "sweep", "60.0, 150.0");
    let t = exited(
        &batch(&edited, &out, &[], &[]),
        0,
        &["another version of the batch"],
    );
    assert!(!t.contains("kept"), "{t}");
}

#[test]
fn long_and_huge_override_values_name_short_directories() {
    let dir = scratch("faults-long-names");
    small_scene(&dir, "base", "base", &[]);
    let long = (0..40)
        .map(|i| format!("{}.0", 100 + i))
        .collect::<Vec<_>>()
        .join(", ");
    std::fs::write(
        dir.join("names.toml"),
        format!(
            "[batch]\nscene = \"base.toml\"\n[[batch.group]]\n\"loading.load\" = [1e300, 100.0]\n\
             [[batch.group]]\n\"design.loads\" = [[{long}]]\n\"points.across\" = [9]\n"
        ),
    )
    .unwrap();
    let out = dir.join("out");
    let o = batch(&dir.join("names.toml"), &out, &[], &[]);
    let t = text(&o);
    assert!(!t.contains("File name too long"), "{t}");
    assert!(t.contains("loading.load=1e300"), "{t}");
    let names: Vec<String> = std::fs::read_dir(out.join("names"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().all(|n| n.len() <= 120), "{names:?}");
    assert!(
        names.iter().any(|n| n == "001-loading.load-100.0"),
        "{names:?}"
    );
}

#[test]
fn an_interrupt_ends_a_long_solve_at_once_and_writes_nothing_half() {
    let dir = scratch("interrupt");
    let out = dir.join("out");
    // Example 1 unfolded at 71 across by Lemke's method: 5089 points, about
    // 10 s of pivots on the reference machine.
    let slow = example_in(
        &dir,
        "slow.toml",
        "example1-spheres",
        &[
            ("across = 41", "across = 71"),
            (
                "method = \"block-pivoting\"",
                "method = \"lemke\"\nsymmetry = \"none\"",
            ),
        ],
    );
    for signal in ["INT", "TERM"] {
        let child = spawn(&["run", s(&slow), "--out", s(&out)], &[]);
        // Well into the pivots (the assembly takes a fraction of a second).
        std::thread::sleep(Duration::from_millis(1500));
        let status = std::process::Command::new("kill")
            .args([format!("-{signal}"), child.id().to_string()])
            .status()
            .unwrap();
        assert!(status.success());
        let o = child.wait_with_output().unwrap();
        let t = text(&o);
        // The typed outcome: exit 130, the scene interrupted, nothing
        // written (the ~10 s solve, had it finished, would have written
        // its result): no bound on the time taken.
        assert_eq!(o.status.code(), Some(130), "SIG{signal}: {t}");
        assert!(
            t.contains("scene `example1-spheres`: interrupted before it finished"),
            "{t}"
        );
        assert!(!out.join("example1-spheres").exists());
        assert!(litter(&out).is_empty(), "{:?}", litter(&out));
    }
}

/// `--threads` and `ELCON_THREADS` are bounded by the cores, as `--jobs`
/// is: 100,000 threads took minutes to start on a 149-point scene.
#[test]
fn a_thread_count_beyond_the_cores_is_refused() {
    let dir = scratch("faults-threads");
    let batch = six_runs(&dir, "sweep", "50.0, 150.0");
    let o = elcon(&["check", s(&batch), "--threads", "100000"]);
    exited(&o, 2, &["threads per core"]);
    let o = elcon_with(&["check", s(&batch)], &[("ELCON_THREADS", "100000")]);
    exited(&o, 2, &[]);
    let o = elcon(&["check", s(&batch), "--threads", "2"]);
    exited(&o, 0, &[]);
}

/// A batch over a small measured-crown roller whose profile is
/// `dir/crown.csv`: two loads, `dir/crown.toml`.
fn crown_sweep(dir: &Path, drop_scale: f64) -> PathBuf {
    write_crown(dir, drop_scale);
    example_in(
        dir,
        "base.toml",
        "measured-crown",
        &[
            ("file = \"data/measured-crown.csv\"", "file = \"crown.csv\""),
            ("nx = 9", "nx = 5"),
            ("ny = 40", "ny = 16"),
            ("plots = [\"pressure\"]", "plots = []"),
        ],
    );
    let path = dir.join("crown.toml");
    std::fs::write(
        &path,
        "[batch]\nname = \"crown\"\nscene = \"base.toml\"\n[[batch.group]]\n\
         \"loading.load\" = [5000.0, 10000.0]\n",
    )
    .unwrap();
    path
}

/// `dir/crown.csv`: the example's measured crown, its drops times `scale`.
fn write_crown(dir: &Path, scale: f64) {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/data/measured-crown.csv"),
    )
    .unwrap();
    let rows: Vec<String> = text
        .lines()
        .map(|l| match l.split_once(',') {
            Some((y, d)) if !l.starts_with('#') => {
                format!("{y}, {}", d.trim().parse::<f64>().unwrap() * scale)
            }
            _ => l.to_string(),
        })
        .collect();
    std::fs::write(dir.join("crown.csv"), rows.join("\n")).unwrap();
}

#[test]
fn an_edited_data_file_or_result_runs_again_and_merge_refuses_shards_across_the_edit() {
    let dir = scratch("edited-inputs");
    let (out, fresh) = (dir.join("out"), dir.join("fresh"));
    let file = crown_sweep(&dir, 1.0);
    exited(&batch(&file, &out, &[], &[]), 0, &[]);
    let before = json(&out.join("crown/results.json"));
    // The same files: both runs kept.
    exited(
        &batch(&file, &out, &[], &[]),
        0,
        &["2 finished runs kept, 0 to run"],
    );
    // The crown edited: both runs read it, both run again, and the rows
    // are a fresh run's.
    write_crown(&dir, 3.0);
    let t = exited(&batch(&file, &out, &[], &[]), 0, &["[2/2]"]);
    assert_eq!(t.matches("geometry.profile.file").count(), 2, "{t}");
    assert_eq!(
        t.matches("changed since it ran: it runs again").count(),
        2,
        "{t}"
    );
    exited(&batch(&file, &fresh, &[], &[]), 0, &[]);
    let after = json(&out.join("crown/results.json"));
    assert_eq!(
        rows_without_times(&after),
        rows_without_times(&json(&fresh.join("crown/results.json")))
    );
    assert_ne!(rows_without_times(&after), rows_without_times(&before));
    // A result.json edited by hand is not the journal's: its run runs again.
    let run = std::fs::read_dir(out.join("crown"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.join("result.json").exists())
        .unwrap();
    let result = run.join("result.json");
    let text = std::fs::read_to_string(&result).unwrap();
    std::fs::write(
        &result,
        text.replacen("\"approach\": ", "\"approach\": 1.0, \"was\": ", 1),
    )
    .unwrap();
    let t = exited(
        &batch(&file, &out, &[], &[]),
        0,
        &["1 finished runs kept, 1 to run"],
    );
    assert!(t.contains("not the one the journal recorded"), "{t}");
    assert_eq!(
        rows_without_times(&json(&out.join("crown/results.json"))),
        rows_without_times(&after)
    );
    // Shards run before and after an edit of the crown do not merge.
    let sharded = dir.join("sharded");
    exited(&batch(&file, &sharded, &["--shard", "1/2"], &[]), 0, &[]);
    write_crown(&dir, 1.0);
    exited(&batch(&file, &sharded, &["--shard", "2/2"], &[]), 0, &[]);
    let t = exited(
        &merge(
            &[
                &sharded.join("crown-shard-1-of-2"),
                &sharded.join("crown-shard-2-of-2"),
            ],
            &dir.join("merged"),
        ),
        1,
        &["crown.csv", "changed between the runs"],
    );
    assert!(t.contains("geometry.profile.file"), "{t}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGTERM at any moment of a run with an error estimate and a subsurface
/// stage (Example 1's spheres at 161 across: 26,000 points, about 2 s, of
/// which the stresses below the surface take more than half): the run
/// ends interrupted with nothing written, or it finished whole before the
/// signal came. Never a result written after the signal from a stage cut
/// short.
#[test]
fn sigterm_at_any_moment_of_a_run_ends_it_whole_or_interrupted() {
    let dir = scratch("term-sweep");
    let scene = example_in(
        &dir,
        "spheres.toml",
        "example1-spheres",
        &[
            ("across = 41", "across = 161"),
            ("plots = [\"pressure\"]", "plots = []\nsubsurface = true"),
        ],
    );
    let mut interrupted = 0;
    for (k, delay) in [100u64, 400, 700, 1000, 1300].into_iter().enumerate() {
        let out = dir.join(format!("out-{k}"));
        let mut child = spawn(&["run", s(&scene), "--out", s(&out)], &[]);
        std::thread::sleep(Duration::from_millis(delay));
        // Signalled while it still runs, it must end interrupted; ended
        // before, it must have finished whole.
        let running = child.try_wait().unwrap().is_none();
        if running {
            let _ = std::process::Command::new("kill")
                .args(["-TERM", &child.id().to_string()])
                .status();
        }
        let o = child.wait_with_output().unwrap();
        let t = text(&o);
        let result = out.join("example1-spheres/result.json");
        match o.status.code() {
            Some(130) => {
                interrupted += 1;
                assert!(!result.exists(), "after {delay} ms: {t}");
                assert!(litter(&out).is_empty(), "{:?}", litter(&out));
            }
            Some(0) if running => panic!("signalled after {delay} ms, it wrote a result: {t}"),
            Some(0) => {
                let r = json(&result);
                assert!(r["subsurface"]["body1"].is_object(), "after {delay} ms");
                let approach = &r["discretization"]["quantities"]["approach"]["verdict"];
                assert_ne!(approach, "not estimated", "after {delay} ms: {t}");
            }
            code => panic!("after {delay} ms: exit {code:?}: {t}"),
        }
    }
    // The signal came during the run at least once (the run takes ~2 s).
    assert!(interrupted >= 1);
    let _ = std::fs::remove_dir_all(&dir);
}
