//! What every command shares: the registry of experiments by id, stdout, the default `--out` and
//! `--threads`, writing a file atomically, and a clean stop on a signal.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use registry::Entry;

use crate::failure::Failure;

/// Experiments by id.
pub(crate) type Registry = BTreeMap<&'static str, &'static Entry>;

/// Writes to stdout; a closed pipe (`cargo xtask list | head -1`) is not an error.
pub(crate) fn print(s: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    match out.write_all(s.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(Failure::Internal(format!("cannot write to stdout: {e}")))
        }
        _ => Ok(()),
    }
}

pub(crate) fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `<workspace root>/results`.
pub(crate) fn default_out() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map_or_else(|| manifest.join(".."), Path::to_path_buf)
        .join("results")
}

/// Writes `bytes` to `path` through a temporary sibling renamed into place, replacing only a
/// file of its own `kind` ([`registry::write_file`]): what else is there (a device, a folder, a
/// file the toolkit did not write) is refused naming the path (exit 2).
pub(crate) fn write_atomically(
    path: &Path,
    kind: &registry::FileKind,
    bytes: &[u8],
) -> Result<(), Failure> {
    registry::write_file(path, kind, &mut |f| f.write_all(bytes)).map_err(|e| written(path, e))
}

/// A failed [`registry::write_file`] of `path` as the command's failure: a refusal is bad
/// input, an I/O failure internal.
pub(crate) fn written(path: &Path, e: registry::WriteError) -> Failure {
    match e {
        registry::WriteError::Refused(why) => Failure::Bad(format!("{}: {why}", path.display())),
        registry::WriteError::Io(..) => {
            Failure::Internal(format!("internal error: {}: {e}", path.display()))
        }
    }
}

/// Releases every run lock of this process when dropped ([`registry::release_locks`]): held by
/// a command for as long as it writes, and by `main` for the whole process.
pub(crate) struct LocksEnd;

impl Drop for LocksEnd {
    fn drop(&mut self) {
        registry::release_locks();
    }
}

/// Removes the temporary results being written and puts back results moved aside
/// ([`registry::abandon_writes`]), says so in one line and exits with `status`.
fn stop(status: i32) -> ! {
    let cleaned = registry::abandon_writes();
    crate::progress::say(&format!(
        "stopped by a signal{}",
        if cleaned == 0 {
            String::new()
        } else {
            format!("; {cleaned} unfinished results removed or put back")
        }
    ));
    std::process::exit(status);
}

/// On SIGINT, SIGTERM or SIGHUP: cleans up what is being written and exits with 128 plus the
/// signal's number, as a shell reports a process the signal ended (130, 143, 129), so that a
/// scheduler or script sees which signal stopped the run. Without it a stop while writing left
/// `.ID.tmp-*` folders of partial files for the next run to clean up.
///
/// The three signals are blocked in every thread (threads started later inherit the mask; a
/// child process starts with none) and taken by one thread that waits for them, so the clean-up
/// runs as ordinary code. Where this cannot be set up the signals keep their default.
#[cfg(unix)]
pub(crate) fn stop_cleanly_on_signals() {
    use nix::sys::signal::{SigSet, Signal};
    let mut set = SigSet::empty();
    for s in [Signal::SIGINT, Signal::SIGTERM, Signal::SIGHUP] {
        set.add(s);
    }
    if let Err(e) = set.thread_block() {
        tracing::debug!("no signal handling: {e}");
        return;
    }
    let waiter = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            loop {
                if let Ok(signal) = set.wait() {
                    stop(128 + signal as i32);
                }
            }
        });
    if let Err(e) = waiter {
        // Nobody would take the signals: let them end the process as before.
        let _ = set.thread_unblock();
        tracing::debug!("no signal handling: {e}");
    }
}

/// On SIGINT, SIGTERM or SIGHUP (as the platform reports them): cleans up what is being written
/// and exits with 130.
#[cfg(not(unix))]
pub(crate) fn stop_cleanly_on_signals() {
    if let Err(e) = ctrlc::set_handler(|| stop(130)) {
        tracing::debug!("no signal handler: {e}");
    }
}
