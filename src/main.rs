//! The `elcon` command line: a thin shell over elcon-runner (runs,
//! batches, merge), elcon-scene (reading scenes) and elcon-process (the
//! memory ceiling, isolation, interrupts, the thread and job policy).
//!
//! ```text
//! elcon run SCENE.toml... [--out DIR] [--memory-limit SIZE]
//! elcon batch BATCH.toml [--out DIR] [--jobs N] [--shard K/N|auto] [--memory-limit SIZE]
//! elcon check FILE.toml... [--memory-limit SIZE] [--every-run]
//! elcon merge DIR... --out DIR
//! ```
//!
//! Every command takes `--threads N` (also `ELCON_THREADS`): the threads of
//! a solve (default: the cores the process may use).
//!
//! Exit codes: 0 all good; 1 some scene or run failed (the others still ran
//! and were written), a file did not validate, a scene was too big for the
//! memory, or merge was given inconsistent shards; 2 a usage error (unknown
//! option, missing argument, a malformed size or shard, `--shard auto`
//! outside a scheduler, `--jobs` 0 or above `MAX_JOBS_PER_CORE` per core);
//! 130 interrupted (SIGINT or SIGTERM: the solves in flight stop within a
//! pivot or an iteration, what finished is written, a batch's tables list
//! the finished runs and the same command finishes it; a second signal ends
//! the process at once).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;

mod bearing;

use clap::{Parser, Subcommand};
use elcon_lcp::Cancel;
use elcon_num::thousands;
use elcon_process::threads::{admit_count, set_global_threads, solve_threads};
use elcon_process::{
    Ceiling, Counted, Staging, install_panic_hook, interruptible, isolated, parse_size,
};
use elcon_report::{RunResult, write_run_files};
use elcon_runner::{
    BatchOptions, Progress, RunError, Shard, batch_dir, check_batch, merge, prepare, run, run_batch,
};
use elcon_scene::{
    Batch, BatchRun, Scene, SceneError, confine_data_files, is_batch_text, is_bearing_text,
    read_text,
};

#[derive(Parser)]
#[command(
    name = "elcon",
    version,
    about = "Elastic bodies in contact by mathematical programming (Conry & Seireg 1971, and beyond)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Threads of a solve's products and vector passes (default: the cores
    /// this process may use; also ELCON_THREADS). A batch's runs share
    /// `--jobs` threads instead.
    #[arg(long, global = true)]
    threads: Option<usize>,
    /// Read data files (height maps, profiles, separation files) only from
    /// inside DIR, after resolving symbolic links and `..`: for a service
    /// that runs scenes it did not write. Without it, any readable file is
    /// read, and result.json records each one's resolved path.
    #[arg(long, global = true, value_name = "DIR")]
    confine: Option<PathBuf>,
}

/// `--shard`: K/N, or auto (from the scheduler's variables).
#[derive(Clone, Copy)]
enum ShardArg {
    Fixed(Shard),
    Auto,
}

fn shard_arg(s: &str) -> Result<ShardArg, String> {
    if s.trim() == "auto" {
        Ok(ShardArg::Auto)
    } else {
        s.parse().map(ShardArg::Fixed).map_err(|e| e.to_string())
    }
}

/// `--jobs`: a count of runs in parallel the process policy admits.
fn jobs_arg(s: &str) -> Result<usize, String> {
    let jobs: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}`: a whole number of runs in parallel, e.g. 2"))?;
    admit_count(Counted::Jobs, "--jobs", jobs).map_err(|e| e.to_string())
}

#[derive(Subcommand)]
enum Command {
    /// Solve scenes; write result.json, pressure.csv and the plots asked for under DIR/<scene>/.
    Run {
        /// Scene files.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Lower the memory ceiling (e.g. 4G, 512M; also ELCON_MEMORY_LIMIT).
        #[arg(long, value_parser = parse_size, allow_hyphen_values = true)]
        memory_limit: Option<u64>,
    },
    /// Run a batch of sweeps in parallel; write every run and the results table.
    Batch {
        /// Batch file.
        batch: PathBuf,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Runs in parallel (default: one per core; at most 4 per core).
        #[arg(long, value_parser = jobs_arg)]
        jobs: Option<usize>,
        /// Run only the K-th of N slices of the sweep (K from 1), e.g. 2/8; or
        /// auto: K and N from a SLURM job array or a Kubernetes indexed Job.
        #[arg(long, value_parser = shard_arg)]
        shard: Option<ShardArg>,
        /// Lower the memory ceiling (e.g. 4G, 512M; also ELCON_MEMORY_LIMIT).
        #[arg(long, value_parser = parse_size, allow_hyphen_values = true)]
        memory_limit: Option<u64>,
    },
    /// Validate scene or batch files without solving; print each one's memory and time estimate.
    Check {
        /// Scene or batch files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Lower the memory ceiling (e.g. 4G, 512M; also ELCON_MEMORY_LIMIT).
        #[arg(long, value_parser = parse_size, allow_hyphen_values = true)]
        memory_limit: Option<u64>,
        /// Validate every run of a batch, however large its sweep.
        #[arg(long)]
        every_run: bool,
    },
    /// Join the results tables of batch shards.
    Merge {
        /// Shard output directories (each holds results.json).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Where to write the merged tables.
        #[arg(long)]
        out: PathBuf,
    },
}

/// How a command ended.
enum Outcome {
    Ok,
    Failed,
    Usage(String),
    Interrupted,
}

impl From<bool> for Outcome {
    fn from(ok: bool) -> Self {
        if ok { Outcome::Ok } else { Outcome::Failed }
    }
}

fn ceiling(limit: Option<u64>) -> Result<Ceiling, Outcome> {
    Ceiling::of_this_process(limit).map_err(|e| Outcome::Usage(e.to_string()))
}

/// Bounds the threads of the global rayon pool by `--threads`, else by
/// `ELCON_THREADS` (elcon-process's policy: at least 1, a few per core);
/// neither: rayon's default, the cores the process may use. A solve's
/// values do not depend on the count.
fn threads(arg: Option<usize>) -> Result<(), Outcome> {
    solve_threads(arg, |name| std::env::var(name).ok())
        .and_then(set_global_threads)
        .map_err(|e| Outcome::Usage(e.to_string()))
}

/// A token that SIGINT and SIGTERM cancel (the solves watching it stop);
/// a second signal, once it is cancelled, ends the process at once with
/// exit code 130.
fn interrupts() -> Cancel {
    let cancel = Cancel::new();
    for signal in [signal_hook::consts::SIGINT, signal_hook::consts::SIGTERM] {
        // The order matters: the shutdown sees the flag as it was before
        // this signal set it.
        let _ = signal_hook::flag::register_conditional_shutdown(signal, 130, cancel.flag());
        let _ = signal_hook::flag::register(signal, cancel.flag());
    }
    cancel
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    install_panic_hook();
    if let Err(Outcome::Usage(message)) = threads(cli.threads) {
        eprintln!("error: {message}");
        return ExitCode::from(2);
    }
    if let Some(dir) = &cli.confine
        && let Err(e) = confine_data_files(dir)
    {
        eprintln!("error: --confine: {e}");
        return ExitCode::from(2);
    }
    let cancel = interrupts();
    let outcome = match cli.command {
        Command::Run {
            scenes,
            out,
            memory_limit,
        } => ceiling(memory_limit).map(|c| run_scenes(&scenes, &out, &c, &cancel)),
        Command::Batch {
            batch,
            out,
            jobs,
            shard,
            memory_limit,
        } => ceiling(memory_limit)
            .and_then(|c| batch_command(&batch, &out, jobs, shard, c, cancel.clone())),
        Command::Check {
            files,
            memory_limit,
            every_run,
        } => ceiling(memory_limit).map(|c| check(&files, &c, every_run, &cancel)),
        Command::Merge { dirs, out } => Ok(merge_command(&dirs, &out).into()),
    };
    match outcome.unwrap_or_else(|e| e) {
        Outcome::Ok => ExitCode::SUCCESS,
        Outcome::Failed => ExitCode::from(1),
        Outcome::Usage(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
        Outcome::Interrupted => ExitCode::from(130),
    }
}

fn merge_command(dirs: &[PathBuf], out: &Path) -> bool {
    match merge(dirs, out, &|m| eprintln!("{m}")) {
        Ok(m) => {
            println!(
                "merged {} runs of `{}` into {}",
                m.rows.len(),
                m.batch,
                out.display()
            );
            m.failures() == 0
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}

fn header() {
    println!(
        "{:<28} {:<18} {:>7} {:>7} {:>9} {:>12} {:>12} {:>9} {:>11} {:>10}",
        "scene",
        "method",
        "points",
        "pivots",
        "seconds",
        "approach",
        "max press.",
        "cert.",
        "ref. error",
        "est. error"
    );
}

fn row(r: &RunResult) {
    let err = r
        .reference
        .as_ref()
        .and_then(|x| {
            x.errors
                .approach
                .or(x.errors.load)
                .or(x.errors.max_pressure)
        })
        .map_or("-".to_string(), |e| format!("{e:+.2e}"));
    // The peak pressure's estimated discretization error, relative.
    let estimated = r
        .discretization
        .as_ref()
        .map_or("-".to_string(), |d| d.quantities.max_pressure.short());
    println!(
        "{:<28} {:<18} {:>7} {:>7} {:>9.4} {:>12.5e} {:>12.5e} {:>9.1e} {:>11} {:>10}",
        r.scene,
        r.header.method,
        r.header.points,
        r.header.statistics.pivots,
        r.seconds.total,
        r.approach,
        r.max_pressure,
        r.certificate.worst,
        err,
        estimated
    );
    println!(
        "{:<28} units: length {}, force {}, pressure {}",
        "",
        r.units.length(),
        r.units.force(),
        r.units.intensity()
    );
    for input in r.inputs.iter().flat_map(|i| &i.files) {
        println!("{:<28} read {}: {}", "", input.field, input.path.display());
    }
    for w in &r.warnings {
        println!("{:<28} warning: {w}", "");
    }
    if let Some(d) = &r.design {
        println!(
            "{:<28} design ({}): objective {:.5e} (before {:.5e})",
            "", d.family, d.objective, d.objective_before
        );
        let own = d.grids.last().map_or("", |g| g.grid.as_str());
        match &d.verification {
            Some(v) => println!(
                "{:<28} designed on {own}; on {}: {:.5e} ({:+.2} %)",
                "",
                v.grid,
                v.objective,
                100.0 * (v.objective / d.objective - 1.0)
            ),
            None => println!(
                "{:<28} designed on {own} alone (not verified on a finer grid)",
                ""
            ),
        }
    }
}

/// The scenes of the files, validated; a file that fails, or two scenes of
/// one name (they would write one directory), is reported and left out.
fn validated(files: &[(PathBuf, Result<String, SceneError>)], out: &Path) -> (Vec<Scene>, bool) {
    let mut ok = true;
    let mut scenes: Vec<Scene> = Vec::new();
    for (path, text) in files {
        let read = || scene_file(path, text.clone()?);
        match isolated(&path.display().to_string(), read) {
            Ok(s) => scenes.push(s),
            Err(e) => {
                eprintln!("error: {e}");
                ok = false;
            }
        }
    }
    let names: Vec<String> = scenes.iter().map(|s| s.name().to_string()).collect();
    let shared = |name: &str| names.iter().filter(|n| *n == name).count() > 1;
    for (i, name) in names.iter().enumerate() {
        if shared(name) && !names[..i].contains(name) {
            let files: Vec<String> = scenes
                .iter()
                .filter(|t| t.name() == *name)
                .map(|t| t.file().display().to_string())
                .collect();
            eprintln!(
                "error: {} {} name scene `{name}`, so they would write one directory, {}: none of \
                 them runs; give each its own [scene] name",
                files.join(" and "),
                if files.len() == 2 { "both" } else { "all" },
                out.join(name).display()
            );
            ok = false;
        }
    }
    let unique = scenes.into_iter().filter(|s| !shared(s.name())).collect();
    (unique, ok)
}

fn run_scenes(paths: &[PathBuf], out: &Path, ceiling: &Ceiling, cancel: &Cancel) -> Outcome {
    // Each file read once (a pipe reads once); bearing scenes (a
    // [bearing] table) run on their own path, first.
    let (bearings, files): (Vec<_>, Vec<_>) = paths
        .iter()
        .map(|p| (p.clone(), read_text(p)))
        .partition(|(_, t)| t.as_ref().is_ok_and(|t| is_bearing_text(t)));
    let mut ok = true;
    for (path, text) in &bearings {
        let text = text.as_deref().unwrap_or_default();
        match bearing::run_file(path, text, out, ceiling, cancel) {
            Ok(()) => {}
            Err(true) => return Outcome::Interrupted,
            Err(false) => ok = false,
        }
    }
    let (scenes, valid) = validated(&files, out);
    ok &= valid;
    let mut header_printed = false;
    for scene in scenes {
        let name = scene.name().to_string();
        let outcome = interruptible::<_, RunError>(cancel, &name, || {
            isolated(&name, || {
                let prepared = prepare(scene, ceiling)?;
                let staging = Staging::begin(&out.join(&name), &|m| eprintln!("{m}"))?;
                let r = run(&prepared.scene)?;
                write_run_files(&r, staging.path())?;
                Ok((r.result, staging.commit()?))
            })
        });
        match outcome {
            Ok((r, dir)) => {
                if !header_printed {
                    header();
                    header_printed = true;
                }
                row(&r);
                println!("{:<28} wrote {}", "", dir.display());
            }
            Err(e) if e.is_interrupted() => {
                eprintln!("{e}; the scenes after it did not run");
                return Outcome::Interrupted;
            }
            Err(e) => {
                eprintln!("error: {e}");
                ok = false;
            }
        }
    }
    ok.into()
}

/// A scene file, read once (as `check` reads it); a batch file is refused
/// with the command that runs it.
fn scene_file(path: &Path, text: String) -> Result<Scene, RunError> {
    if is_batch_text(&text) {
        return Err(SceneError::Io {
            path: path.to_path_buf(),
            reason: format!(
                "is a batch file (it has a [batch] table): run it with `elcon batch {}`",
                path.display()
            ),
        }
        .into());
    }
    Ok(Scene::from_str(path, &text)?)
}

fn check_scene(path: &Path, scene: Scene, ceiling: &Ceiling) -> bool {
    match prepare(scene, ceiling) {
        Ok(p) => {
            println!(
                "{}: scene `{}`: valid; {}",
                path.display(),
                p.scene.name(),
                p.estimate.summary()
            );
            for w in p.scene.warnings() {
                println!("{}: warning: {w}", path.display());
            }
            true
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}

fn check_batch_file(
    path: &Path,
    text: &str,
    ceiling: &Ceiling,
    every_run: bool,
    cancel: &Cancel,
) -> bool {
    let batch = match Batch::from_text(path, text) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: {e}");
            return false;
        }
    };
    let c = check_batch(&batch, ceiling, every_run, cancel);
    if c.interrupted {
        eprintln!(
            "{}: interrupted after {} of its runs were checked",
            path.display(),
            thousands(c.checked as u64)
        );
        return false;
    }
    for (_, e) in &c.failures {
        eprintln!("error: {e}");
    }
    let which = if c.every_run {
        "every run checked".to_string()
    } else {
        format!(
            "{} runs checked, covering every value of every key; the others are checked as they \
             run, or all with --every-run",
            thousands(c.checked as u64)
        )
    };
    if c.failed > c.failures.len() {
        eprintln!(
            "error: ... and {} more runs failed",
            thousands((c.failed - c.failures.len()) as u64)
        );
    }
    let verdict = if c.failed == 0 {
        "all valid".to_string()
    } else {
        format!("{} failed", thousands(c.failed as u64))
    };
    println!(
        "{}: batch `{}`: {} runs, {verdict} ({which})",
        path.display(),
        batch.name,
        thousands(c.runs as u64)
    );
    if let Some(l) = &c.largest {
        println!(
            "{}: largest run checked: {}; the runs checked: {} of solving in all",
            path.display(),
            l.summary(),
            elcon_runner::TimeFigure::of(c.seconds)
        );
    }
    c.failed == 0
}

/// `elcon check`: each file validated and its memory estimated; an
/// interrupt ends it (exit 130) before the next file or run.
fn check(files: &[PathBuf], ceiling: &Ceiling, every_run: bool, cancel: &Cancel) -> Outcome {
    let mut ok = true;
    let mut names: Vec<(String, &Path)> = Vec::new();
    for path in files {
        if cancel.is_cancelled() {
            return Outcome::Interrupted;
        }
        let text = match read_text(path) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: {e}");
                ok = false;
                continue;
            }
        };
        if is_bearing_text(&text) {
            ok &= bearing::check_text(path, &text, ceiling);
            continue;
        }
        if is_batch_text(&text) {
            let checked = isolated::<_, RunError>(&path.display().to_string(), || {
                Ok(check_batch_file(path, &text, ceiling, every_run, cancel))
            });
            ok &= checked.unwrap_or_else(|e| {
                eprintln!("error: {e}");
                false
            });
            continue;
        }
        let read = || Scene::from_str(path, &text).map_err(RunError::from);
        match isolated(&path.display().to_string(), read) {
            Ok(scene) => {
                if let Some((_, other)) = names.iter().find(|(n, _)| *n == scene.name()) {
                    eprintln!(
                        "error: {} and {} both name scene `{}`: `run` would run neither; give \
                         each its own [scene] name",
                        other.display(),
                        path.display(),
                        scene.name()
                    );
                    ok = false;
                }
                names.push((scene.name().to_string(), path));
                let name = scene.name().to_string();
                ok &= isolated::<_, RunError>(&name, || Ok(check_scene(path, scene, ceiling)))
                    .unwrap_or_else(|e| {
                        eprintln!("error: {e}");
                        false
                    });
            }
            Err(e) => {
                eprintln!("error: {e}");
                ok = false;
            }
        }
    }
    match cancel.is_cancelled() {
        true => Outcome::Interrupted,
        false => ok.into(),
    }
}

/// A progress bar on a terminal, plain lines otherwise.
struct Report {
    bar: Option<indicatif::ProgressBar>,
    done: Mutex<usize>,
    total: Mutex<usize>,
}

impl Progress for Report {
    fn start(&self, total: usize) {
        *self.total.lock().expect("progress lock") = total;
        if let Some(bar) = &self.bar {
            bar.set_length(total as u64);
        }
    }

    fn notice(&self, message: &str) {
        match &self.bar {
            Some(bar) => bar.println(message),
            None => eprintln!("{message}"),
        }
    }

    fn finished(&self, run: &BatchRun, outcome: Result<&RunResult, &RunError>) {
        let mut done = self.done.lock().expect("progress lock");
        *done += 1;
        let total = *self.total.lock().expect("progress lock");
        let line = match outcome {
            Ok(r) => format!(
                "[{}/{total}] {}: ok, {} points, {:.3} s",
                *done,
                run.slug(),
                r.header.points,
                r.seconds.total
            ),
            Err(e) => format!("[{}/{total}] {}: failed: {e}", *done, run.slug()),
        };
        match &self.bar {
            Some(bar) => {
                if outcome.is_err() {
                    bar.println(line);
                }
                bar.inc(1);
            }
            None => eprintln!("{line}"),
        }
    }
}

fn batch_command(
    path: &Path,
    out: &Path,
    jobs: Option<usize>,
    shard: Option<ShardArg>,
    ceiling: Ceiling,
    cancel: Cancel,
) -> Result<Outcome, Outcome> {
    let shard = match shard {
        None => None,
        Some(ShardArg::Fixed(s)) => Some(s),
        Some(ShardArg::Auto) => {
            let shard = Shard::from_scheduler(|k| std::env::var(k).ok());
            Some(shard.map_err(|e| Outcome::Usage(e.to_string()))?)
        }
    };
    let batch = match Batch::from_file(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: {e}");
            return Ok(Outcome::Failed);
        }
    };
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(0);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{bar:40} {pos}/{len} runs, {elapsed} elapsed, eta {eta}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    });
    let report = Report {
        bar,
        done: Mutex::new(0),
        total: Mutex::new(0),
    };
    if let Some(s) = shard {
        eprintln!(
            "shard {s} of batch `{}` ({} runs in all)",
            batch.name,
            batch.len()
        );
    }
    let options = BatchOptions {
        jobs,
        shard,
        ceiling,
        cancel,
    };
    let done = run_batch(&batch, out, &options, &report);
    if let Some(bar) = &report.bar {
        bar.finish_and_clear();
    }
    match done {
        Ok(done) => {
            let o = &done.outcome;
            let dir = batch_dir(&batch, out, shard);
            let kept = if done.kept > 0 {
                format!(
                    " ({} kept from the last invocation)",
                    thousands(done.kept as u64)
                )
            } else {
                String::new()
            };
            println!(
                "batch `{}`: {} runs, {} failed{kept}; tables in {}",
                o.batch,
                thousands(o.rows.len() as u64),
                thousands(o.failures() as u64),
                dir.display()
            );
            for r in o.rows.iter().filter(|r| r.status != "ok") {
                println!("  run {} ({}): {}", r.index, r.overrides, r.status);
            }
            if done.interrupted {
                eprintln!(
                    "interrupted: {} runs did not finish; the same command again runs them and \
                     keeps the {} that finished",
                    thousands(o.pending as u64),
                    thousands(o.rows.iter().filter(|r| r.status == "ok").count() as u64)
                );
                return Ok(Outcome::Interrupted);
            }
            Ok((o.failures() == 0).into())
        }
        Err(e) => {
            eprintln!("error: {e}");
            Ok(Outcome::Failed)
        }
    }
}
