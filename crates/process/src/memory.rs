//! The memory a run may use: the ceiling a scene's estimated peak
//! (elcon-runner's estimate) is compared with before anything of size N x N is
//! allocated.
//!
//! The ceiling is the lowest of what the machine and the process allow,
//! less a margin of [`MARGIN`] of it (the program's own code, buffers and
//! the allocator's slack):
//!
//! ```text
//!     ceiling = (1 - MARGIN) min(MemAvailable,
//!                                cgroup memory.max - (memory.current - page cache),
//!                                RLIMIT_AS - VmSize - address-space reserve,
//!                                --memory-limit, ELCON_MEMORY_LIMIT)
//! ```
//!
//! read from /proc/meminfo, the current cgroup's memory controller (v2
//! `memory.max`, or v1 `memory.limit_in_bytes`, every ancestor included;
//! the usage less the page cache the kernel reclaims before it refuses
//! memory, `inactive_file` and `active_file` of `memory.stat`: active
//! cache is demoted and reclaimed too),
//! /proc/self/limits and /proc/self/status. A limit that cannot be read is
//! left out (on a system without /proc only the option and the environment
//! variable count, and without them the ceiling is unlimited).

use std::path::{Path, PathBuf};

use crate::error::ProcessError;

/// The fraction of the lowest limit kept free.
pub(crate) const MARGIN: f64 = 0.10;

/// The environment variable that may lower the ceiling (a size, as
/// [`parse_size`] reads it).
pub(crate) const LIMIT_VARIABLE: &str = "ELCON_MEMORY_LIMIT";

/// Address space a run reserves beyond the memory it touches (malloc's
/// per-thread arenas, thread stacks, the program's own mappings, buffers
/// allocated whole and filled in part), besides the matrix products'
/// buffers ([`gemm_reserve`]), taken off an address-space limit: a run's
/// peak address space exceeded its peak resident memory by 350 to 490 MiB
/// (docs/reliability.md).
pub(crate) const ADDRESS_SPACE_RESERVE: u64 = 512 << 20;

/// The address space faer's matrix products reserve: each thread that
/// multiplies keeps two buffers of the last-level cache's size (the L3 of
/// /sys/devices/system/cpu/cpu0/cache/index3/size, 480 MiB on a VM that
/// reports it so), the main thread and one per core. Untouched, they cost
/// no memory, but they count against an address-space limit, and a
/// product that cannot map them aborts the process.
pub fn gemm_reserve() -> u64 {
    let l3 = std::fs::read_to_string("/sys/devices/system/cpu/cpu0/cache/index3/size")
        .ok()
        .and_then(|t| cache_size(&t))
        .unwrap_or(32 << 20);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u64 + 1;
    l3.saturating_mul(2).saturating_mul(threads)
}

/// A sysfs cache size ("491520K", "32M"), bytes.
fn cache_size(text: &str) -> Option<u64> {
    let t = text.trim();
    let (digits, unit) = t.split_at(t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len()));
    let value: u64 = digits.parse().ok()?;
    let scale = match unit {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        _ => return None,
    };
    value.checked_mul(scale)
}

/// Limits at or above this many bytes mean "no limit" (cgroup v1 writes
/// 2^63 rounded down to a page for an unlimited group).
const UNLIMITED: u64 = 1 << 62;

/// The memory a run may use, and what set it.
#[derive(Debug, Clone, PartialEq)]
pub struct Ceiling {
    /// Bytes (the lowest limit less the margin); `u64::MAX` when nothing limits.
    pub bytes: u64,
    /// The limit that set it and its bytes (before the margin); `None` when
    /// nothing limits.
    pub limit: Option<(Limit, u64)>,
}

/// What limits a process's memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limit {
    /// MemAvailable of /proc/meminfo.
    Available,
    /// The memory left in the process's cgroup.
    Cgroup,
    /// The address space left under RLIMIT_AS (`ulimit -v`), less faer's
    /// matrix products' buffers.
    AddressSpace,
    /// The command line's `--memory-limit`.
    Option,
    /// The environment's `ELCON_MEMORY_LIMIT`.
    Variable,
}

impl std::fmt::Display for Limit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Limit::Available => "MemAvailable",
            Limit::Cgroup => "memory left in the cgroup",
            Limit::AddressSpace => {
                "usable address space under RLIMIT_AS (less the matrix products' buffers)"
            }
            Limit::Option => "--memory-limit",
            Limit::Variable => LIMIT_VARIABLE,
        })
    }
}

impl Ceiling {
    /// No limit at all.
    pub fn unlimited() -> Self {
        Self {
            bytes: u64::MAX,
            limit: None,
        }
    }

    /// Whether `bytes` fit under the ceiling.
    pub fn admits(&self, bytes: u64) -> bool {
        bytes <= self.bytes
    }

    /// The ceiling from the lowest of `limits` (bytes, and what each is).
    pub fn from_limits(limits: impl IntoIterator<Item = (u64, Limit)>) -> Self {
        match limits
            .into_iter()
            .filter(|(b, _)| *b < UNLIMITED)
            .min_by_key(|(b, _)| *b)
        {
            Some((bytes, what)) => Self {
                bytes: (bytes as f64 * (1.0 - MARGIN)) as u64,
                limit: Some((what, bytes)),
            },
            None => Self::unlimited(),
        }
    }

    /// The ceiling of this process on this machine, lowered by `option`
    /// (`--memory-limit`) and by `ELCON_MEMORY_LIMIT` when set.
    ///
    /// # Errors
    /// [`ProcessError::Variable`] when the environment variable's value is
    /// not a size.
    pub fn of_this_process(option: Option<u64>) -> Result<Self, ProcessError> {
        let mut limits = system_limits();
        if let Some(b) = option {
            limits.push((b, Limit::Option));
        }
        if let Ok(v) = std::env::var(LIMIT_VARIABLE) {
            let b = parse_size(&v).map_err(|e| ProcessError::Variable {
                name: LIMIT_VARIABLE,
                value: v.clone(),
                reason: e.to_string(),
            })?;
            limits.push((b, Limit::Variable));
        }
        Ok(Self::from_limits(limits))
    }
}

impl Ceiling {
    /// What set it, for messages: "MemAvailable 22.1 GiB, less 10 %",
    /// "--memory-limit 4.00 GiB, less 10 %", or "no limit found".
    pub fn source(&self) -> String {
        match self.limit {
            Some((what, bytes)) => {
                format!("{what} {}, less {:.0} %", human(bytes), 100.0 * MARGIN)
            }
            None => "no limit found".into(),
        }
    }
}

impl std::fmt::Display for Ceiling {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.bytes == u64::MAX {
            write!(f, "unlimited ({})", self.source())
        } else {
            write!(f, "{} ({})", human(self.bytes), self.source())
        }
    }
}

/// A size in bytes: a number (bytes) or a number with one of the suffixes
/// K, M, G, T (powers of 1024, as in `ulimit` and SLURM's `--mem`),
/// optionally followed by `B` or `iB`: "4G", "512M", "1.5GiB", "1048576".
///
/// # Errors
/// [`ProcessError::Size`], saying what a size looks like.
pub fn parse_size(s: &str) -> Result<u64, ProcessError> {
    let t = s.trim();
    let bad = || ProcessError::Size {
        text: s.to_string(),
        reason: "a positive size, like 8GiB or 512M (a number of bytes, or one with K, M, G or T)",
    };
    let digits = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(digits);
    let value: f64 = number.parse().map_err(|_| bad())?;
    let unit = unit.trim().to_ascii_uppercase();
    let unit = unit
        .strip_suffix("IB")
        .or_else(|| unit.strip_suffix('B'))
        .unwrap_or(&unit);
    let scale = match unit {
        "" => 1.0,
        "K" => 1024.0,
        "M" => 1024.0 * 1024.0,
        "G" => 1024.0 * 1024.0 * 1024.0,
        "T" => 1024.0 * 1024.0 * 1024.0 * 1024.0,
        _ => return Err(bad()),
    };
    let bytes = value * scale;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(ProcessError::Size {
            text: s.to_string(),
            reason: "a positive size of at least 1 byte, like 8GiB",
        });
    }
    Ok(bytes as u64)
}

/// Bytes in binary units with three significant digits: "1.50 GiB".
pub fn human(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut v = bytes as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < UNITS.len() {
        v /= 1024.0;
        u += 1;
    }
    match u {
        0 => format!("{bytes} B"),
        _ if v >= 100.0 => format!("{v:.0} {}", UNITS[u]),
        _ if v >= 10.0 => format!("{v:.1} {}", UNITS[u]),
        _ => format!("{v:.2} {}", UNITS[u]),
    }
}

/// Every limit this system states: MemAvailable, the cgroups' and the
/// address-space limit.
fn system_limits() -> Vec<(u64, Limit)> {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let mut limits = Vec::new();
    if let Some(b) = read("/proc/meminfo").and_then(|t| meminfo_available(&t)) {
        limits.push((b, Limit::Available));
    }
    if let Some(b) =
        read("/proc/self/cgroup").and_then(|t| cgroup_available(&t, Path::new("/sys/fs/cgroup")))
    {
        limits.push((b, Limit::Cgroup));
    }
    if let Some(limit) = read("/proc/self/limits").and_then(|t| address_space_limit(&t)) {
        let used = read("/proc/self/status")
            .and_then(|t| status_kib(&t, "VmSize:"))
            .unwrap_or(0);
        limits.push((
            limit
                .saturating_sub(used)
                .saturating_sub(ADDRESS_SPACE_RESERVE)
                .saturating_sub(gemm_reserve()),
            Limit::AddressSpace,
        ));
    }
    limits
}

/// MemAvailable of /proc/meminfo, bytes.
fn meminfo_available(meminfo: &str) -> Option<u64> {
    status_kib(meminfo, "MemAvailable:")
}

/// A `Key:   123 kB` line of /proc/meminfo or /proc/self/status, bytes.
fn status_kib(text: &str, key: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line[key.len()..].split_whitespace().next()?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The soft "Max address space" of /proc/self/limits, bytes (`None` when unlimited).
fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// What the memory controller leaves this process: over the cgroup and each
/// ancestor with a limit, the least of `limit - working set`, the working
/// set being the usage less the page cache the kernel reclaims before it
/// refuses memory (`inactive_file` and `active_file` of `memory.stat`;
/// v1's hierarchical `total_` figures): a job that has read or written
/// files is not refused for their cache. `proc_cgroup` is
/// /proc/self/cgroup; `root` the cgroup file system's mount point.
fn cgroup_available(proc_cgroup: &str, root: &Path) -> Option<u64> {
    let mut best: Option<u64> = None;
    for line in proc_cgroup.lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(id), Some(controllers), Some(path)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        let (base, max_file, usage_file) = if id == "0" && controllers.is_empty() {
            // cgroup v2: unified at the root, or under unified/ on a hybrid system.
            let base = if root.join("cgroup.controllers").exists() {
                root.to_path_buf()
            } else {
                root.join("unified")
            };
            (base, "memory.max", "memory.current")
        } else if controllers.split(',').any(|c| c == "memory") {
            (
                root.join("memory"),
                "memory.limit_in_bytes",
                "memory.usage_in_bytes",
            )
        } else {
            continue;
        };
        for dir in ancestors(&base, path) {
            let read = |f: &str| -> Option<u64> {
                std::fs::read_to_string(dir.join(f))
                    .ok()?
                    .trim()
                    .parse()
                    .ok()
            };
            if let Some(limit) = read(max_file).filter(|&l| l < UNLIMITED) {
                let usage = read(usage_file).unwrap_or(0);
                let cache = std::fs::read_to_string(dir.join("memory.stat"))
                    .ok()
                    .and_then(|stat| page_cache(&stat))
                    .unwrap_or(0);
                let left = limit.saturating_sub(usage.saturating_sub(cache));
                best = Some(best.map_or(left, |b| b.min(left)));
            }
        }
    }
    best
}

/// The reclaimable page cache of a cgroup's `memory.stat`: its inactive
/// and active file pages (v1's hierarchical `total_` figures when given);
/// `None` when neither can be read.
fn page_cache(stat: &str) -> Option<u64> {
    let value = |key: &str| {
        stat.lines().find_map(|line| {
            let (k, v) = line.split_once(' ')?;
            (k == key).then(|| v.trim().parse::<u64>().ok()).flatten()
        })
    };
    let of = |name: &str| value(&format!("total_{name}")).or_else(|| value(name));
    match (of("inactive_file"), of("active_file")) {
        (None, None) => None,
        (inactive, active) => Some(inactive.unwrap_or(0).saturating_add(active.unwrap_or(0))),
    }
}

/// The directories of a cgroup `path` and of its ancestors under `base`
/// that exist (inside a container the path may name a group above the
/// mount's root: then only the root is there).
fn ancestors(base: &Path, path: &str) -> Vec<PathBuf> {
    let mut dirs = vec![base.to_path_buf()];
    let mut dir = base.to_path_buf();
    for part in path.split('/').filter(|p| !p.is_empty()) {
        dir = dir.join(part);
        if dir.is_dir() {
            dirs.push(dir.clone());
        }
    }
    dirs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_powers_of_1024() {
        assert_eq!(parse_size("4G").unwrap(), 4 << 30);
        assert_eq!(parse_size("512M").unwrap(), 512 << 20);
        assert_eq!(parse_size("512mb").unwrap(), 512 << 20);
        assert_eq!(parse_size("1.5GiB").unwrap(), 3 << 29);
        assert_eq!(parse_size("1048576").unwrap(), 1 << 20);
        assert_eq!(parse_size(" 2 T ").unwrap(), 2 << 40);
        for bad in ["", "G", "4X", "-1G", "-1", "0", "1e400", "four"] {
            let e = parse_size(bad).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("`{bad}`: a memory limit must be a positive size")),
                "{e}"
            );
            assert!(e.contains("like 8GiB"), "{e}");
        }
    }

    #[test]
    fn the_lowest_limit_less_the_margin_is_the_ceiling() {
        let c = Ceiling::from_limits([
            (10 << 30, Limit::Available),
            (4 << 30, Limit::Option),
            (u64::MAX, Limit::AddressSpace),
        ]);
        assert_eq!(c.bytes, ((4u64 << 30) as f64 * 0.9) as u64);
        assert!(
            c.source().starts_with("--memory-limit 4.00 GiB"),
            "{}",
            c.source()
        );
        assert!(c.admits(3 << 30) && !c.admits(4 << 30));
        let none = Ceiling::from_limits([(1 << 63, Limit::Cgroup)]);
        assert_eq!(none, Ceiling::unlimited());
        assert!(none.admits(u64::MAX));
    }

    #[test]
    fn proc_files_are_read() {
        let meminfo =
            "MemTotal:       24683656 kB\nMemFree:  100 kB\nMemAvailable:   23156324 kB\n";
        assert_eq!(meminfo_available(meminfo), Some(23156324 * 1024));
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max address space         unlimited            unlimited            bytes     \n";
        assert_eq!(address_space_limit(limits), None);
        assert_eq!(cache_size("491520K\n"), Some(480 << 20));
        assert_eq!(cache_size("32M"), Some(32 << 20));
        assert_eq!(cache_size("1024"), Some(1024));
        assert_eq!(cache_size("12 KB"), None);
        let limited = "Max address space         4294967296           unlimited            bytes\n";
        assert_eq!(address_space_limit(limited), Some(1 << 32));
    }

    #[test]
    fn cgroup_limits_of_every_ancestor_count() {
        let root = std::env::temp_dir().join(format!("elcon-cgroup-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        // cgroup v2: /job (limit 8 GiB, 1 GiB used) / step (limit 6 GiB, 3 GiB used).
        let job = root.join("job");
        let step = job.join("step");
        std::fs::create_dir_all(&step).unwrap();
        std::fs::write(root.join("cgroup.controllers"), "memory").unwrap();
        std::fs::write(root.join("memory.max"), "max\n").unwrap();
        std::fs::write(job.join("memory.max"), format!("{}\n", 8u64 << 30)).unwrap();
        std::fs::write(job.join("memory.current"), format!("{}\n", 1u64 << 30)).unwrap();
        std::fs::write(step.join("memory.max"), format!("{}\n", 6u64 << 30)).unwrap();
        std::fs::write(step.join("memory.current"), format!("{}\n", 3u64 << 30)).unwrap();
        assert_eq!(cgroup_available("0::/job/step\n", &root), Some(3 << 30));
        // Page cache the kernel reclaims is not counted as used: a step that
        // wrote 2.5 GiB of files (inactive) of its 3 GiB is left 5.5 GiB,
        // under its parent's 7 GiB.
        let stat = format!(
            "anon 524288000\nfile 2952790016\ninactive_file {}\n",
            5u64 << 29
        );
        std::fs::write(step.join("memory.stat"), stat).unwrap();
        assert_eq!(cgroup_available("0::/job/step\n", &root), Some(11 << 29));
        // Active page cache is reclaimed too: 2 GiB inactive and 0.5 GiB
        // active of 3 GiB used leave 5.5 GiB.
        let stat = format!(
            "anon 524288000\nactive_file {}\ninactive_file {}\n",
            1u64 << 29,
            1u64 << 31
        );
        std::fs::write(step.join("memory.stat"), stat).unwrap();
        assert_eq!(cgroup_available("0::/job/step\n", &root), Some(11 << 29));
        // An unreadable stat counts the whole usage.
        std::fs::write(step.join("memory.stat"), "inactive_file many\n").unwrap();
        assert_eq!(cgroup_available("0::/job/step\n", &root), Some(3 << 30));
        // A path above the mount's root (a container): only the root counts.
        assert_eq!(cgroup_available("0::/elsewhere\n", &root), None);
        // cgroup v1: an unlimited group.
        let v1 = root.join("memory");
        std::fs::create_dir_all(&v1).unwrap();
        std::fs::write(v1.join("memory.limit_in_bytes"), "9223372036854771712\n").unwrap();
        assert_eq!(cgroup_available("4:memory:/x\n", &root), None);
        std::fs::write(v1.join("memory.limit_in_bytes"), "1073741824\n").unwrap();
        assert_eq!(cgroup_available("4:memory:/x\n", &root), Some(1 << 30));
        // v1: usage 900 MiB, of which 800 MiB inactive page cache (the
        // hierarchical total taken over the group's own figure).
        std::fs::write(
            v1.join("memory.usage_in_bytes"),
            format!("{}\n", 900u64 << 20),
        )
        .unwrap();
        std::fs::write(
            v1.join("memory.stat"),
            format!(
                "inactive_file {}\ntotal_inactive_file {}\n",
                1u64 << 20,
                800u64 << 20
            ),
        )
        .unwrap();
        assert_eq!(cgroup_available("4:memory:/x\n", &root), Some(924 << 20));
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn human_sizes() {
        assert_eq!(human(512), "512 B");
        assert_eq!(human(1536), "1.50 KiB");
        assert_eq!(human(34 << 30), "34.0 GiB");
        assert_eq!(human(300 << 20), "300 MiB");
    }
}
