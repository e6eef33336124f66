//! Run locks: a run that will write `<parent>/<name>` (a results folder, a summary, a shard's
//! partial file) holds the lock file `<parent>/.<name>.lock` from its checks to its end.
//!
//! Two runs into one `--out` would otherwise both compute, and the one that renamed its results
//! into place last would replace the other's without a word. The lock is the operating system's
//! (`flock`, which NFS carries across machines), so it dies with its process however the process
//! ends: a lock nobody holds is a dead run's, whatever its process id - another machine's live
//! run on a shared file system has an id this machine does not know, and an id may be reused.
//! [`crate::tidy`] removes a killed run's leftovers only when the lock of their name is free.
//!
//! A lock file is removed by its holder at the end of the run, and by a later run when nobody
//! holds it; whoever takes one checks afterwards that the file it locked is still the one at
//! the path, so a lock file removed in between is never mistaken for the lock.

use std::fs::{self, File, OpenOptions};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use crate::RunError;

/// A lock this process holds until [`release_locks`].
struct Held {
    /// `<parent>/.<name>.lock`.
    path: PathBuf,
    /// The open lock file (`None` where the file system takes no locks).
    file: Option<File>,
    /// Folders created to hold the lock file, outermost first: removed again at the release if
    /// they are still empty (a run refused after its checks leaves no empty `--out`).
    created: Vec<PathBuf>,
}

static HELD: Mutex<Vec<Held>> = Mutex::new(Vec::new());

fn held() -> MutexGuard<'static, Vec<Held>> {
    HELD.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The lock file of `<parent>/<name>`.
pub fn lock_path(parent: &Path, name: &str) -> PathBuf {
    parent.join(format!(".{name}.lock"))
}

/// Whether `path` still names the file `file` is open on (it may have been removed, or removed
/// and made again, since it was opened).
#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Whether `path` still names a file (no identity to compare here).
#[cfg(not(unix))]
fn same_file(_: &File, path: &Path) -> bool {
    path.exists()
}

/// Creates `dir` and every missing folder above it, one at a time, returning those this call
/// created (outermost first); a folder another process created meanwhile is not counted.
fn create_dirs(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut missing = Vec::new();
    let mut at = dir.to_path_buf();
    while !at.as_os_str().is_empty() && fs::symlink_metadata(&at).is_err() {
        missing.push(at.clone());
        at = at.parent().map(Path::to_path_buf).unwrap_or_default();
    }
    let mut created = Vec::new();
    for d in missing.into_iter().rev() {
        match fs::create_dir(&d) {
            Ok(()) => created.push(d),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(e),
        }
    }
    Ok(created)
}

/// This host's name, for the holder's description (empty when unknown).
fn host() -> String {
    fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| fs::read_to_string("/etc/hostname"))
        .map(|h| h.trim().to_owned())
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_default()
}

/// Takes the lock of writing `<parent>/<name>` for the rest of the process (until
/// [`release_locks`]), creating `parent` if needed, and writes `what` (the run, in words) into
/// the lock file with this process's id and host, for a refused run to name its holder.
///
/// Returns `Ok(None)` once this process holds it (also when it already did), `Ok(Some(holder))`
/// when another process holds it (`holder`: what it wrote). A file system that takes no locks
/// counts as a lock taken.
///
/// # Errors
/// [`RunError::Internal`]: the folder or the lock file cannot be made.
pub fn lock_writing(parent: &Path, name: &str, what: &str) -> Result<Option<String>, RunError> {
    let path = lock_path(parent, name);
    let mut list = held();
    if list.iter().any(|h| h.path == path) {
        return Ok(None);
    }
    let io = |what: &str, p: &Path, e: std::io::Error| {
        RunError::Internal(format!("cannot {what} {}: {e}", p.display()))
    };
    let mut created = Vec::new();
    // A lock file removed between the open and the lock is not the lock: try again. A few
    // tries are plenty (each needs another run to end at that very moment).
    for _ in 0..100 {
        created.extend(create_dirs(parent).map_err(|e| io("create", parent, e))?);
        let file = match OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
        {
            Ok(f) => f,
            // The folder was removed meanwhile (a refused run tidying the `--out` it made).
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) => return Err(io("create the lock file", &path, e)),
        };
        match try_lock_patiently(&file) {
            Ok(()) => {}
            Err(fs::TryLockError::WouldBlock) => {
                let mut holder = String::new();
                let _ = (&file).read_to_string(&mut holder);
                let holder = holder.trim();
                return Ok(Some(if holder.is_empty() {
                    "another run".to_owned()
                } else {
                    holder.to_owned()
                }));
            }
            Err(fs::TryLockError::Error(e)) => {
                tracing::debug!("no lock on {}: {e}", path.display());
                list.push(Held {
                    path,
                    file: None,
                    created,
                });
                return Ok(None);
            }
        }
        if !same_file(&file, &path) {
            continue;
        }
        let host = host();
        let holder = format!(
            "{what}, process {}{}",
            std::process::id(),
            if host.is_empty() {
                String::new()
            } else {
                format!(" on {host}")
            }
        );
        let _ = file.set_len(0);
        let _ = (&file).write_all(holder.as_bytes());
        list.push(Held {
            path,
            file: Some(file),
            created,
        });
        return Ok(None);
    }
    Err(RunError::Internal(format!(
        "cannot take the lock {}: it keeps being removed",
        path.display()
    )))
}

/// Takes the lock of `file`, trying again for a moment when it is held: a run tidying the same
/// folder ([`crate::tidy`]) holds a free lock for an instant to learn that it is free, and a run
/// starting just then must not take that for another run writing.
fn try_lock_patiently(file: &File) -> Result<(), fs::TryLockError> {
    let mut tries = 0;
    loop {
        match file.try_lock() {
            Err(fs::TryLockError::WouldBlock) if tries < 25 => {
                tries += 1;
                std::thread::sleep(std::time::Duration::from_millis(4));
            }
            other => return other,
        }
    }
}

/// Releases every lock this process holds: removes each lock file (while still holding it, and
/// only if it is still the one locked), then the folders made for it if they are empty.
pub fn release_locks() {
    let all = std::mem::take(&mut *held());
    for h in all.into_iter().rev() {
        if let Some(file) = &h.file
            && same_file(file, &h.path)
        {
            let _ = fs::remove_file(&h.path);
        }
        drop(h.file);
        for dir in h.created.iter().rev() {
            let _ = fs::remove_dir(dir);
        }
    }
}

/// Whether a run other than this process writes `<parent>/<name>` now: `Some(true)` when its
/// lock is held elsewhere, `Some(false)` when nobody else holds it (free, or held by this
/// process), `None` when it cannot be told: no lock file (what is written under that name is
/// no run's - a folder made by a check for a moment - or its run ended and removed its lock),
/// a lock file that cannot be opened for writing, or a file system that takes no locks.
pub(crate) fn writer_alive(parent: &Path, name: &str) -> Option<bool> {
    let path = lock_path(parent, name);
    if held().iter().any(|h| h.path == path) {
        return Some(false);
    }
    let file = match OpenOptions::new().read(true).write(true).open(&path) {
        Ok(f) => f,
        Err(_) => return None,
    };
    match file.try_lock() {
        Ok(()) => Some(false),
        Err(fs::TryLockError::WouldBlock) => Some(true),
        Err(fs::TryLockError::Error(_)) => None,
    }
}

/// Removes the lock file `path` (`.NAME.lock`) if nobody holds it: a killed run's. Checked
/// under the lock, so a run that has just taken it keeps it.
pub(crate) fn remove_if_free(path: &Path) {
    if held().iter().any(|h| h.path == path) {
        return;
    }
    let Ok(file) = OpenOptions::new().read(true).write(true).open(path) else {
        return;
    };
    if file.try_lock().is_ok() && same_file(&file, path) {
        let _ = fs::remove_file(path);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let p = std::env::temp_dir().join(format!(
            "registry-lock-{tag}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .unwrap()
                .as_nanos()
        ));
        fs::create_dir_all(&p).unwrap();
        p
    }

    #[test]
    fn a_lock_held_elsewhere_is_seen_and_a_free_one_is_not() {
        let dir = scratch("held");
        let path = lock_path(&dir, "table3");
        // Another holder: a second open file description of the same file, locked.
        let other = File::create(&path).unwrap();
        other.try_lock().unwrap();
        (&other)
            .write_all(b"run table3 (seed 2), process 1 on elsewhere")
            .unwrap();
        assert_eq!(writer_alive(&dir, "table3"), Some(true));
        let busy = lock_writing(&dir, "table3", "run table3 (seed 1)").unwrap();
        assert_eq!(
            busy.as_deref(),
            Some("run table3 (seed 2), process 1 on elsewhere")
        );
        remove_if_free(&path);
        assert!(path.exists(), "a held lock file was removed");
        drop(other);
        assert_eq!(writer_alive(&dir, "table3"), Some(false));
        assert_eq!(writer_alive(&dir, "absent"), None);
        remove_if_free(&path);
        assert!(!path.exists(), "a free lock file was left");
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_lock_is_taken_once_and_released_with_the_folders_it_made() {
        let dir = scratch("take");
        let out = dir.join("new").join("out");
        assert_eq!(lock_writing(&out, "fig3", "run fig3").unwrap(), None);
        assert_eq!(lock_writing(&out, "fig3", "run fig3").unwrap(), None);
        let path = lock_path(&out, "fig3");
        assert!(
            fs::read_to_string(&path)
                .unwrap()
                .starts_with("run fig3, process ")
        );
        assert_eq!(
            writer_alive(&out, "fig3"),
            Some(false),
            "this process's own"
        );
        release_locks();
        assert!(!path.exists());
        assert!(
            !dir.join("new").exists(),
            "the folders made for the lock stay"
        );
        let _ = fs::remove_dir_all(&dir);
    }
}
