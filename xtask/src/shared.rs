//! What every command shares: the registry of experiments by id, stdout, the default `--out` and
//! `--threads`, writing a file atomically, and a clean stop on a signal.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use registry::Experiment;

use crate::failure::Failure;

/// Experiments by id.
pub(crate) type Registry = BTreeMap<&'static str, &'static Experiment>;

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

/// Writes `text` to `path` through a temporary sibling renamed into place.
pub(crate) fn write_atomically(path: &Path, text: &str) -> Result<(), Failure> {
    let tmp = path.with_file_name(format!(
        ".{}.tmp-{}",
        path.file_name()
            .map_or_else(|| "summary".into(), |n| n.to_string_lossy().into_owned()),
        std::process::id()
    ));
    let fail = |what: &str, e: std::io::Error| {
        Failure::Internal(format!(
            "internal error: cannot {what} {}: {e}",
            path.display()
        ))
    };
    registry::write_file_through(path, &tmp, text.as_bytes()).map_err(|(what, e)| fail(what, e))
}

/// The exit status of a run stopped by SIGINT, SIGTERM or SIGHUP (128 + SIGINT's number, as a
/// shell reports Ctrl-C).
const STOPPED: i32 = 130;

/// On SIGINT, SIGTERM or SIGHUP: removes the temporary results being written and puts back
/// results moved aside ([`registry::abandon_writes`]), says so in one line and exits with
/// [`STOPPED`]. Without it a stop while writing left `.ID.tmp-*` folders of partial files for
/// the next run to clean up. Where no handler can be installed the signals keep their default.
pub(crate) fn stop_cleanly_on_signals() {
    let installed = ctrlc::set_handler(|| {
        let cleaned = registry::abandon_writes();
        eprintln!(
            "stopped by a signal{}",
            if cleaned == 0 {
                String::new()
            } else {
                format!("; {cleaned} unfinished results removed or put back")
            }
        );
        std::process::exit(STOPPED);
    });
    if let Err(e) = installed {
        tracing::debug!("no signal handler: {e}");
    }
}
