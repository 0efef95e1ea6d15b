//! The data files a scene reads (height maps, profiles, separation files),
//! each named by its key, its resolved path and the SHA-256 of its bytes:
//! what a run's result records of its inputs, so that a batch resumed
//! after a file was edited runs again the runs that read it.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::error::SceneError;

/// A data file a scene read.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DataInput {
    /// The scene key that names it (`geometry.profile.file`).
    pub field: String,
    /// Its path, resolved (symbolic links followed, absolute) where it
    /// can be; as the scene names it, relative to the scene's directory,
    /// otherwise.
    pub path: PathBuf,
    /// SHA-256 of its bytes, in hexadecimal.
    pub sha256: String,
    /// Its size in bytes.
    pub bytes: u64,
}

impl DataInput {
    /// The record of `bytes` read from `path` under `field`.
    pub(crate) fn of(field: &str, path: &Path, bytes: &[u8]) -> Self {
        Self {
            field: field.to_string(),
            path: std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()),
            sha256: sha256_hex(bytes),
            bytes: bytes.len() as u64,
        }
    }
}

/// SHA-256 (hexadecimal) of the file at `path` as it is now, if it can
/// be read: at most `limit` bytes and one more (a file larger than any
/// data file elcon reads has changed).
pub fn file_sha256(path: &Path, limit: u64) -> Option<String> {
    use std::io::Read as _;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
        .ok()?;
    Some(sha256_hex(&bytes))
}

/// The directory data files must lie in, once confined (resolved).
static CONFINED: OnceLock<PathBuf> = OnceLock::new();

/// Confines the data files every scene of this process reads (height
/// maps, profiles, separation files) to `dir`: a file whose resolved path
/// (symbolic links followed, `..` removed) is outside it is refused,
/// naming the key. For a service that runs scenes it did not write. Set
/// once per process: the confinement cannot be widened or lifted later.
///
/// # Errors
/// [`SceneError::Io`] when `dir` cannot be resolved or is not a directory,
/// or the process is already confined to another directory.
pub fn confine_data_files(dir: &Path) -> Result<(), SceneError> {
    let resolved = std::fs::canonicalize(dir).map_err(|e| SceneError::io(dir, e))?;
    if !resolved.is_dir() {
        return Err(SceneError::io(dir, "is not a directory"));
    }
    let set = CONFINED.get_or_init(|| resolved.clone());
    if *set != resolved {
        return Err(SceneError::io(
            dir,
            format!(
                "data files are already confined to {} in this process",
                set.display()
            ),
        ));
    }
    Ok(())
}

/// Why `path` may not be read under the confinement, if it may not: its
/// resolved path, outside the confining directory.
pub(crate) fn outside_confinement(path: &Path) -> Option<String> {
    let root = CONFINED.get()?;
    match std::fs::canonicalize(path) {
        Ok(real) if real.starts_with(root) => None,
        Ok(real) => Some(format!(
            "is outside the directory data files are confined to ({}): it resolves to {}",
            root.display(),
            real.display()
        )),
        Err(e) => Some(format!("cannot be resolved: {e}")),
    }
}

/// SHA-256 of `bytes`, in hexadecimal.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edited_file_hashes_otherwise() {
        let dir = std::env::temp_dir().join(format!("elcon-inputs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("crown.csv");
        std::fs::write(&path, "0, 0\n1, 0.001\n").unwrap();
        let input = DataInput::of("geometry.profile.file", &path, b"0, 0\n1, 0.001\n");
        assert_eq!(file_sha256(&path, 1 << 20), Some(input.sha256.clone()));
        std::fs::write(&path, "0, 0\n1, 0.002\n").unwrap();
        assert_ne!(file_sha256(&path, 1 << 20), Some(input.sha256.clone()));
        std::fs::remove_file(&path).unwrap();
        assert_eq!(file_sha256(&path, 1 << 20), None);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
