//! The `elcon` command line: a thin shell over elcon-scene.
//!
//! ```text
//! elcon run SCENE.toml... [--out DIR]       solve scenes, write DIR/<scene>/ (result.json, pressure.csv, plots)
//! elcon batch BATCH.toml [--out DIR] [--jobs N] [--shard K/N]
//! elcon check FILE.toml...                  validate scenes or batches without solving
//! elcon merge DIR... --out DIR              join the tables of batch shards
//! ```
//!
//! Exit codes: 0 all good; 1 some scene or run failed (the others still ran
//! and were written) or a file did not validate; 2 a usage error (unknown
//! option, missing argument).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;

use clap::{Parser, Subcommand};
use elcon_scene::{
    Batch, BatchRun, Progress, RunResult, Scene, SceneError, Shard, merge, run, run_batch,
    write_run,
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
    },
    /// Run a batch of sweeps in parallel; write every run and the results table.
    Batch {
        /// Batch file.
        batch: PathBuf,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Runs in parallel (default: one per core).
        #[arg(long)]
        jobs: Option<usize>,
        /// Run only the K-th of N slices of the sweep (K from 1), e.g. 2/8.
        #[arg(long)]
        shard: Option<Shard>,
    },
    /// Validate scene or batch files without solving.
    Check {
        /// Scene or batch files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let ok = match cli.command {
        Command::Run { scenes, out } => run_scenes(&scenes, &out),
        Command::Batch {
            batch,
            out,
            jobs,
            shard,
        } => batch_command(&batch, &out, jobs, shard),
        Command::Check { files } => check(&files),
        Command::Merge { dirs, out } => match merge(&dirs, &out) {
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
        },
    };
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

fn header() {
    println!(
        "{:<28} {:<18} {:>7} {:>7} {:>9} {:>12} {:>12} {:>9} {:>11}",
        "scene",
        "method",
        "points",
        "pivots",
        "seconds",
        "approach",
        "max press.",
        "cert.",
        "ref. error"
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
    println!(
        "{:<28} {:<18} {:>7} {:>7} {:>9.4} {:>12.5e} {:>12.5e} {:>9.1e} {:>11}",
        r.scene,
        r.method,
        r.points,
        r.statistics.pivots,
        r.seconds.total,
        r.approach,
        r.max_pressure,
        r.certificate.worst,
        err
    );
    println!(
        "{:<28} units: length {}, force {}, pressure {}",
        "", r.units.length, r.units.force, r.units.intensity
    );
    for w in &r.warnings {
        println!("{:<28} warning: {w}", "");
    }
    if let Some(d) = &r.design {
        println!(
            "{:<28} design ({}): objective {:.5e} (before {:.5e})",
            "", d.family, d.objective, d.objective_before
        );
    }
}

fn run_scenes(scenes: &[PathBuf], out: &Path) -> bool {
    header();
    let mut ok = true;
    for path in scenes {
        let outcome = Scene::from_file(path).and_then(|scene| {
            let r = run(&scene)?;
            let dir = write_run(&r, out)?;
            Ok((r, dir))
        });
        match outcome {
            Ok((r, dir)) => {
                row(&r.result);
                println!("{:<28} wrote {}", "", dir.display());
            }
            Err(e) => {
                eprintln!("error: {e}");
                ok = false;
            }
        }
    }
    ok
}

fn check(files: &[PathBuf]) -> bool {
    let mut ok = true;
    for path in files {
        let is_batch = std::fs::read_to_string(path)
            .ok()
            .and_then(|t| t.parse::<toml::Table>().ok())
            .is_some_and(|t| t.contains_key("batch"));
        let result: Result<String, SceneError> = if is_batch {
            Batch::from_file(path).and_then(|b| {
                let runs = b.runs();
                for r in &runs {
                    b.scene(r)?;
                }
                Ok(format!(
                    "batch `{}`: {} runs, all valid",
                    b.name,
                    runs.len()
                ))
            })
        } else {
            Scene::from_file(path)
                .map(|s| format!("scene `{}`: {} points, valid", s.name, s.points.len()))
        };
        match result {
            Ok(msg) => println!("{}: {msg}", path.display()),
            Err(e) => {
                eprintln!("error: {e}");
                ok = false;
            }
        }
    }
    ok
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

    fn finished(&self, run: &BatchRun, outcome: Result<&RunResult, &SceneError>) {
        let mut done = self.done.lock().expect("progress lock");
        *done += 1;
        let total = *self.total.lock().expect("progress lock");
        let line = match outcome {
            Ok(r) => format!(
                "[{}/{total}] {}: ok, {} points, {:.3} s",
                *done,
                run.slug(),
                r.points,
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

fn batch_command(path: &Path, out: &Path, jobs: Option<usize>, shard: Option<Shard>) -> bool {
    let batch = match Batch::from_file(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: {e}");
            return false;
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
    match run_batch(&batch, out, jobs, shard, &report) {
        Ok(o) => {
            if let Some(bar) = &report.bar {
                bar.finish_and_clear();
            }
            let dir = batch.output_dir(out, shard);
            println!(
                "batch `{}`: {} runs, {} failed; tables in {}",
                o.batch,
                o.rows.len(),
                o.failures(),
                dir.display()
            );
            for r in o.rows.iter().filter(|r| r.status != "ok") {
                println!("  run {} ({}): {}", r.index, r.overrides, r.status);
            }
            o.failures() == 0
        }
        Err(e) => {
            eprintln!("error: {e}");
            false
        }
    }
}
