//! Files and directories written whole or not at all, each output
//! directory as a unit, under a lock.
//!
//! A file's contents go to a temporary file in the same directory, which is
//! then renamed over the target (a rename within a directory is atomic), so
//! an interrupted run leaves either the old file or the new one, never half
//! of one. A directory (a scene's, a batch's, a merge's) is written whole
//! into a temporary sibling, `.<name>.<pid>.tmp`, which then replaces the
//! old directory ([`Staging`]): no file of an earlier run stays beside the
//! new ones. While it is written, the writer holds an OS lock on
//! `.<name>.lock` beside it, so a second writer of the same directory waits;
//! the holder of the lock removes the temporary siblings a killed run left,
//! and puts back an old directory a run killed between its two renames had
//! moved aside. The lock file stays, empty: removing it while another
//! writer waits on it would let a third one take a new lock beside them.
//! Scene names cannot start with '.', so nothing of the user's is taken for
//! one of these siblings.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use crate::error::ProcessError;

/// Writes `contents` to `path` whole or not at all (temporary file in the
/// same directory, flushed to disk, then renamed).
///
/// # Errors
/// [`ProcessError::Io`] naming the file.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), ProcessError> {
    write_atomic_with(path, |w| w.write_all(contents))
}

/// Writes what `write` produces to `path` whole or not at all, as
/// [`write_atomic`], streamed through a buffer: a file as large as a
/// per-point table is never held in memory.
///
/// # Errors
/// [`ProcessError::Io`] naming the file.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn io::Write) -> io::Result<()>,
) -> Result<(), ProcessError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    fs::create_dir_all(dir).map_err(|e| ProcessError::io(dir, e))?;
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = io::BufWriter::new(fs::File::create(&tmp)?);
        write(&mut f)?;
        let f = f.into_inner().map_err(io::IntoInnerError::into_error)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = fs::remove_file(&tmp);
        ProcessError::io(path, e)
    })
}

/// An output directory being written: a temporary sibling of the target
/// that [`Staging::commit`] renames into place, replacing the old directory
/// as a unit. The lock on the target is held from [`Staging::begin`] until
/// the staging is committed or dropped; dropped uncommitted, the temporary
/// directory is removed and the old directory stays as it was.
#[derive(Debug)]
pub struct Staging {
    target: PathBuf,
    tmp: PathBuf,
    /// The OS lock on `.<name>.lock`, released when dropped.
    _lock: DirLock,
    done: bool,
}

/// The parent directory and the name of an output directory.
fn split(target: &Path) -> Result<(PathBuf, String), ProcessError> {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| n != "." && n != "..")
        .ok_or_else(|| ProcessError::io(target, "an output directory needs a name"))?;
    let parent = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    Ok((parent, name))
}

impl Staging {
    /// Locks `target` (waiting for another writer of it: `notice` is told
    /// once, before the wait), removes what killed runs left beside it, and
    /// creates the empty temporary directory to write into.
    ///
    /// # Errors
    /// [`ProcessError::Io`] when the parent or the temporary directory cannot
    /// be created, or the lock fails for a reason other than another writer.
    pub fn begin(target: &Path, notice: &dyn Fn(&str)) -> Result<Self, ProcessError> {
        let (parent, name) = split(target)?;
        let lock = lock_dir(target, notice)?;
        let tmp = parent.join(format!(".{name}.{}.tmp", std::process::id()));
        fs::create_dir(&tmp).map_err(|e| ProcessError::io(&tmp, e))?;
        Ok(Self {
            target: target.to_path_buf(),
            tmp,
            _lock: lock,
            done: false,
        })
    }

    /// The directory to write into.
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// The directory the outputs will have once committed.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Renames the temporary directory over the target (the old target is
    /// moved aside first and removed after), then releases the lock.
    ///
    /// # Errors
    /// [`ProcessError::Io`] when a rename fails (the old directory is then
    /// put back).
    pub fn commit(mut self) -> Result<PathBuf, ProcessError> {
        let (parent, name) = split(&self.target)?;
        let old = parent.join(format!(".{name}.{}.old", std::process::id()));
        let had_old = match fs::symlink_metadata(&self.target) {
            Ok(_) => {
                fs::rename(&self.target, &old).map_err(|e| ProcessError::io(&self.target, e))?;
                true
            }
            Err(_) => false,
        };
        if let Err(e) = fs::rename(&self.tmp, &self.target) {
            if had_old {
                let _ = fs::rename(&old, &self.target);
            }
            return Err(ProcessError::io(&self.target, e));
        }
        self.done = true;
        if had_old {
            let _ = fs::remove_dir_all(&old).or_else(|_| fs::remove_file(&old));
        }
        Ok(self.target.clone())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.done {
            let _ = fs::remove_dir_all(&self.tmp);
        }
    }
}

/// The OS lock on an output directory (`.<name>.lock` beside it), held
/// until dropped; `None` inside when the file system has no locks (the
/// writer is warned through `notice` and goes on).
#[derive(Debug)]
pub struct DirLock {
    _file: Option<fs::File>,
}

/// Locks `target` (waiting for another writer of it: `notice` is told
/// once, before the wait) and removes what killed writers left beside it.
///
/// # Errors
/// [`ProcessError::Io`] when the parent cannot be created, or the lock fails
/// for a reason other than another writer.
pub fn lock_dir(target: &Path, notice: &dyn Fn(&str)) -> Result<DirLock, ProcessError> {
    let (parent, name) = split(target)?;
    fs::create_dir_all(&parent).map_err(|e| ProcessError::io(&parent, e))?;
    let lock_path = parent.join(format!(".{name}.lock"));
    let file = fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .map_err(|e| ProcessError::io(&lock_path, e))?;
    let lock = match file.try_lock() {
        Ok(()) => Some(file),
        Err(fs::TryLockError::WouldBlock) => {
            notice(&format!(
                "waiting: another elcon is writing {} (it holds {})",
                target.display(),
                lock_path.display()
            ));
            file.lock().map_err(|e| ProcessError::io(&lock_path, e))?;
            Some(file)
        }
        Err(fs::TryLockError::Error(e)) => {
            notice(&format!(
                "warning: cannot lock {} ({e}); a concurrent writer of {} would not be kept out",
                lock_path.display(),
                target.display()
            ));
            None
        }
    };
    clean_leftovers(&parent, &name);
    Ok(DirLock { _file: lock })
}

/// Makes a directory's entries durable (fsync of the directory itself, so
/// that a rename into it survives a crash). A file system that cannot sync
/// a directory is not an error.
pub fn sync_dir(dir: &Path) {
    if let Ok(d) = fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Moves the complete directory `tmp` to `target` in the same parent,
/// replacing whatever `target` held (the caller holds the parent's lock),
/// and makes the rename durable.
///
/// # Errors
/// [`ProcessError::Io`] when the rename fails.
pub fn replace_dir(tmp: &Path, target: &Path) -> Result<(), ProcessError> {
    if fs::symlink_metadata(target).is_ok() {
        fs::remove_dir_all(target)
            .or_else(|_| fs::remove_file(target))
            .map_err(|e| ProcessError::io(target, e))?;
    }
    fs::rename(tmp, target).map_err(|e| ProcessError::io(target, e))?;
    sync_dir(target.parent().unwrap_or(Path::new(".")));
    Ok(())
}

/// Removes `.<name>.<pid>.tmp` and `.<name>.<pid>.old` in `parent`: what
/// a writer killed before its commit left (the caller holds the lock, so
/// no live writer owns them). An `.old` with no `<name>` beside it is the
/// old directory of a writer killed between moving it aside and renaming
/// the new one in: it is put back, not removed.
fn clean_leftovers(parent: &Path, name: &str) {
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    let prefix = format!(".{name}.");
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let Some(middle) = file.strip_prefix(&prefix).and_then(|rest| {
            rest.strip_suffix(".tmp")
                .or_else(|| rest.strip_suffix(".old"))
        }) else {
            continue;
        };
        if !middle.is_empty() && middle.bytes().all(|b| b.is_ascii_digit()) {
            let path = entry.path();
            let target = parent.join(name);
            if file.ends_with(".old")
                && fs::symlink_metadata(&target).is_err()
                && fs::rename(&path, &target).is_ok()
            {
                continue;
            }
            let _ = fs::remove_dir_all(&path).or_else(|_| fs::remove_file(&path));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(label: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("elcon-output-{label}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_streamed_file_that_fails_midway_is_not_written_at_all() {
        let dir = scratch("streamed");
        let path = dir.join("pressure.csv");
        fs::write(&path, "old").unwrap();
        let e = write_atomic_with(&path, |w| {
            w.write_all(b"x,y\n1,2\n")?;
            Err(io::Error::other("the disk is full"))
        })
        .unwrap_err();
        assert!(e.to_string().contains("the disk is full"), "{e}");
        assert_eq!(fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 1, "no temporary left");
        write_atomic_with(&path, |w| w.write_all(b"x,y\n")).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "x,y\n");
    }

    #[test]
    fn an_old_directory_moved_aside_by_a_killed_writer_is_put_back() {
        let parent = scratch("restore");
        // A writer killed between its two renames: the old directory aside,
        // its new one complete or not, no target.
        fs::create_dir(parent.join(".s.123.old")).unwrap();
        fs::write(parent.join(".s.123.old/result.json"), "old").unwrap();
        fs::create_dir(parent.join(".s.123.tmp")).unwrap();
        fs::write(parent.join(".s.123.tmp/result.json"), "half").unwrap();
        // A user's directory whose name only looks alike is not touched.
        fs::create_dir(parent.join("s.9.tmp")).unwrap();
        let staging = Staging::begin(&parent.join("s"), &|_| {}).unwrap();
        assert_eq!(
            fs::read_to_string(parent.join("s/result.json")).unwrap(),
            "old"
        );
        assert!(!parent.join(".s.123.old").exists());
        assert!(!parent.join(".s.123.tmp").exists());
        assert!(parent.join("s.9.tmp").exists());
        // The new run then replaces it as a unit.
        fs::write(staging.path().join("result.json"), "new").unwrap();
        staging.commit().unwrap();
        assert_eq!(
            fs::read_to_string(parent.join("s/result.json")).unwrap(),
            "new"
        );
        let left: Vec<String> = fs::read_dir(&parent)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp") || n.ends_with(".old"))
            .collect();
        assert_eq!(left, vec!["s.9.tmp".to_string()]);
        let _ = fs::remove_dir_all(&parent);
    }

    #[test]
    fn an_old_directory_beside_its_target_is_removed() {
        let parent = scratch("remove");
        fs::create_dir(parent.join("s")).unwrap();
        fs::create_dir(parent.join(".s.77.old")).unwrap();
        let staging = Staging::begin(&parent.join("s"), &|_| {}).unwrap();
        assert!(!parent.join(".s.77.old").exists());
        assert!(parent.join("s").exists());
        drop(staging);
        let _ = fs::remove_dir_all(&parent);
    }
}
