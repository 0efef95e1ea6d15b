//! A batch directory's journal: what makes a batch resumable.
//!
//! `journal.jsonl` in the batch's directory holds a header line (the
//! batch's name, hash, shard and size) and then a line per finished run:
//! its table row ([`Row`]) and the SHA-256 of its result.json, appended and
//! fsynced as the run ends, after its directory was renamed into place
//! whole. A batch killed at any point
//! (SIGKILL, a SLURM time limit, a preempted pod) leaves finished runs
//! that are each in the journal and on disk, or not finished at all; at
//! worst the journal's last line is torn, and is ignored.
//!
//! When the same batch (same hash, same shard) is run again into the same
//! directory, [`Journal::open`] keeps every run the journal lists as
//! finished whose directory holds its result.json, as the journal recorded
//! it (the same SHA-256: a result.json edited since is run again), and
//! whose data files (result.json's `inputs`: height maps, profiles,
//! separation files) still hold the bytes the run read (an edited file's
//! runs are run again, and the notice says which file). The row is rebuilt
//! from that result.json, so the tables of a resumed batch are those of an
//! unbroken one to the last digit. Failed runs are run again (the cause
//! may have been fixed: a memory limit, a full disk). A directory of
//! another version of the batch, or without a journal, is replaced.

use std::collections::BTreeMap;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use elcon_process::{faults, sync_dir, write_atomic};
use elcon_report::{Row, RunResult};
use elcon_scene::{Batch, BatchRun, DataInput, MAX_DATA_BYTES, file_sha256, sha256_hex};

use crate::error::RunError;
use crate::shard::Shard;

/// The journal's file name in a batch directory.
pub const JOURNAL: &str = "journal.jsonl";

/// The journal's first line: which batch, which version, which slice.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Header {
    /// The journal's format.
    journal: u32,
    batch: String,
    batch_hash: String,
    shard: Option<String>,
    runs: usize,
}

/// A finished run's line: its row and the SHA-256 of its result.json as
/// written (absent in a failed run's line).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Entry {
    #[serde(flatten)]
    pub row: Row,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub result_sha256: Option<String>,
}

/// The open journal of a batch directory.
#[derive(Debug)]
pub(crate) struct Journal {
    file: Mutex<(fs::File, usize)>,
    path: PathBuf,
    /// The finished runs kept from an earlier invocation, by index.
    kept: BTreeMap<usize, Entry>,
}

impl Journal {
    /// Opens `dir`'s journal for `batch` (or its `shard`): keeps the
    /// finished runs of the same batch, replaces a directory of another
    /// version or without a journal (`notice` is told), removes what
    /// killed runs left, and rewrites the journal with the runs kept.
    ///
    /// # Errors
    /// [`RunError`] when the directory or the journal cannot be
    /// written.
    pub(crate) fn open(
        dir: &Path,
        batch: &Batch,
        shard: Option<Shard>,
        notice: &dyn Fn(&str),
    ) -> Result<Self, RunError> {
        let header = Header {
            journal: 1,
            batch: batch.name.clone(),
            batch_hash: batch.hash.clone(),
            shard: shard.map(|s| s.to_string()),
            runs: batch.len(),
        };
        let path = dir.join(JOURNAL);
        let mut kept = BTreeMap::new();
        if dir.exists() {
            let read = fs::read_to_string(&path);
            let unlike = match &read {
                Ok(text) => unlike(text, &header),
                Err(_) => Some("no journal (an older elcon's, or not a batch's)".to_string()),
            };
            match (read, unlike) {
                (Ok(text), None) => {
                    kept = finished_runs(&text, dir, batch, shard.unwrap_or(WHOLE), notice);
                }
                (_, why) => {
                    let why = why.unwrap_or_default();
                    notice(&format!("{} holds {why}: replaced", dir.display()));
                    fs::remove_dir_all(dir).map_err(|e| RunError::io(dir, e))?;
                }
            }
        }
        fs::create_dir_all(dir).map_err(|e| RunError::io(dir, e))?;
        remove_staging(dir);
        let mut text = serde_json::to_string(&header).map_err(|e| RunError::io(&path, e))?;
        text.push('\n');
        for entry in kept.values() {
            text.push_str(&serde_json::to_string(entry).map_err(|e| RunError::io(&path, e))?);
            text.push('\n');
        }
        write_atomic(&path, text.as_bytes())?;
        sync_dir(dir);
        let file = fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| RunError::io(&path, e))?;
        Ok(Self {
            file: Mutex::new((file, 0)),
            path,
            kept,
        })
    }

    /// The finished runs kept, by index.
    pub(crate) fn kept(&self) -> &BTreeMap<usize, Entry> {
        &self.kept
    }

    /// Appends a finished run's row (with its result.json's SHA-256, for
    /// a run that wrote one) and makes it durable.
    ///
    /// # Errors
    /// [`RunError`] when the journal cannot be written.
    pub(crate) fn record(&self, row: &Row, result_sha256: Option<String>) -> Result<(), RunError> {
        let entry = Entry {
            row: row.clone(),
            result_sha256,
        };
        let mut line = serde_json::to_string(&entry).map_err(|e| RunError::io(&self.path, e))?;
        line.push('\n');
        let mut guard = self.file.lock().unwrap_or_else(|e| e.into_inner());
        faults::before_record(guard.1 + 1);
        let (file, count) = &mut *guard;
        file.write_all(line.as_bytes())
            .and_then(|()| file.sync_data())
            .map_err(|e| RunError::io(&self.path, e))?;
        *count += 1;
        faults::after_record(*count);
        Ok(())
    }
}

/// The whole sweep, as a shard.
const WHOLE: Shard = Shard { index: 1, count: 1 };

/// How the journal `text` differs from one of `header`'s batch, as a
/// notice says it ("{dir} holds {this}: replaced"); `None` when its first
/// line is `header`.
fn unlike(text: &str, header: &Header) -> Option<String> {
    let Some(first) = text.lines().next().filter(|l| !l.trim().is_empty()) else {
        return Some("an empty journal (a batch stopped before it wrote its first line)".into());
    };
    let Ok(found) = serde_json::from_str::<Header>(first) else {
        return Some(
            "a journal whose first line is not a batch's header (torn, edited, or an older \
             elcon's)"
                .into(),
        );
    };
    let why = if found == *header {
        return None;
    } else if found.journal != header.journal {
        "the journal of an older or newer elcon".to_string()
    } else if found.batch != header.batch {
        format!("the journal of another batch ({:?})", short(&found.batch))
    } else if found.shard != header.shard {
        let name = |s: &Option<String>| s.clone().unwrap_or_else(|| "the whole sweep".into());
        format!(
            "the journal of {} of the batch, not {}",
            name(&found.shard),
            name(&header.shard)
        )
    } else {
        "the journal of another version of the batch (its batch file, its base scene or elcon \
         changed)"
            .to_string()
    };
    Some(why)
}

/// A name as a notice quotes it: at most 40 characters.
fn short(name: &str) -> String {
    name.chars().take(40).collect()
}

/// The runs the journal lists as finished (ok) whose directory holds the
/// result.json the journal recorded (its SHA-256) and whose data files
/// still hold what the run read, each row rebuilt from that file; a torn
/// or foreign line ends nothing but itself. `notice` hears why a finished
/// run is run again.
fn finished_runs(
    text: &str,
    dir: &Path,
    batch: &Batch,
    shard: Shard,
    notice: &dyn Fn(&str),
) -> BTreeMap<usize, Entry> {
    let mut kept = BTreeMap::new();
    let mut current = Hashes::default();
    for line in text.lines().skip(1) {
        let Ok(entry) = serde_json::from_str::<Entry>(line) else {
            continue;
        };
        let index = entry.row.index;
        kept.remove(&index);
        if !entry.row.is_ok() || !shard.contains(index) {
            continue;
        }
        let Some(run) = batch.run(index) else {
            continue;
        };
        match kept_run(&run, dir, entry.result_sha256.as_deref(), &mut current) {
            Ok(entry) => {
                kept.insert(index, entry);
            }
            Err(why) => notice(&format!(
                "run {index} ({}): {why}: it runs again",
                run.slug()
            )),
        }
    }
    kept
}

/// The SHA-256 of data files as they are now, each file read once.
#[derive(Default)]
struct Hashes(BTreeMap<PathBuf, Option<String>>);

impl Hashes {
    /// Why `input` no longer holds what its run read, if it does not.
    fn changed(&mut self, input: &DataInput) -> Option<String> {
        let now = self
            .0
            .entry(input.path.clone())
            .or_insert_with(|| file_sha256(&input.path, MAX_DATA_BYTES));
        match now {
            Some(sha) if *sha == input.sha256 => None,
            Some(_) => Some(format!(
                "its {} ({}) changed since it ran",
                input.field,
                input.path.display()
            )),
            None => Some(format!(
                "its {} ({}) cannot be read",
                input.field,
                input.path.display()
            )),
        }
    }
}

/// A finished run kept, its row rebuilt from its result.json; or why not:
/// the file is missing or unreadable, differs from the journal's record,
/// or a data file it read changed.
fn kept_run(
    run: &BatchRun,
    dir: &Path,
    recorded: Option<&str>,
    current: &mut Hashes,
) -> Result<Entry, String> {
    let path = dir.join(run.slug()).join(RESULT);
    let bytes = fs::read(&path).map_err(|e| format!("its {RESULT} cannot be read ({e})"))?;
    let sha = sha256_hex(&bytes);
    if recorded != Some(sha.as_str()) {
        return Err(format!(
            "its {RESULT} is not the one the journal recorded (edited or replaced since)"
        ));
    }
    let result = RunResult::from_bytes(&bytes, &path).map_err(|e| e.to_string())?;
    if result.scene != run.slug() {
        return Err(format!("its {RESULT} is another run's"));
    }
    let inputs = result.inputs.as_ref().map_or(&[][..], |i| &i.files[..]);
    if let Some(why) = inputs.iter().find_map(|input| current.changed(input)) {
        return Err(why);
    }
    Ok(Entry {
        row: Row::ok(run.index, run.label(), &result),
        result_sha256: Some(sha),
    })
}

/// A run directory's result file.
const RESULT: &str = "result.json";

/// Removes the staging directories (`.<run>.<pid>.tmp`) of runs killed
/// while writing (the caller holds the batch's lock).
fn remove_staging(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') && name.ends_with(".tmp") {
            let p = e.path();
            let _ = fs::remove_dir_all(&p).or_else(|_| fs::remove_file(&p));
        }
    }
}
