//! # elcon-process: the process plumbing of elcon's command line and Python package
//!
//! What a program that runs contact problems for users needs around the
//! solvers, shared by the `elcon` command line and the Python package so
//! that both pass through the same policies:
//!
//! - the memory ceiling ([`Ceiling`]): the lowest of what the machine, the
//!   cgroup, the address-space limit, `--memory-limit` and
//!   `ELCON_MEMORY_LIMIT` allow, less a margin; a run's estimated peak is
//!   compared with it before anything of size N x N is allocated;
//! - isolation ([`isolated`]): a panic inside one scene becomes that
//!   scene's error, and the others still run; interrupts
//!   ([`interruptible`]): a cancelled solve is an interruption, not a failure;
//! - files and directories written whole or not at all, under a lock
//!   ([`write_atomic`], [`Staging`]);
//! - the thread and job policy ([`threads`]): at least 1, at most a few
//!   per core;
//! - test-only fault points ([`faults`], with the `fault-injection` feature).
//!
//! It knows nothing of contact mechanics or of scenes.

mod error;
pub mod faults;
mod files;
mod isolate;
mod memory;
pub mod threads;

pub use error::{Counted, ProcessError};
pub use files::{
    DirLock, Staging, lock_dir, replace_dir, sync_dir, write_atomic, write_atomic_with,
};
pub use isolate::{install_panic_hook, interruptible, isolated};
pub use memory::{Ceiling, Limit, gemm_reserve, human, parse_size};
