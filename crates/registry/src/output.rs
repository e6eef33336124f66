//! How what an experiment returns ([`crate::report`]) is stored: every file written beside its
//! final name and renamed into place, a run's results replaced whole, leftovers tidied.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

use crate::RunError;

pub use crate::report::{Agreement, DEPARTURE, MAX_ANGLE_DEG, MAX_DATA_ROWS, OutputFile, Report};

const TABLE_MD: &str = "table.md";
const TABLES_JSON: &str = "tables.json";

/// Lowercase ASCII letters and digits, other runs of characters made one `-`; at most 80
/// characters, cut at the end of a word (a single word longer than that is cut at 80).
fn slug(title: &str) -> String {
    let mut s = String::new();
    for c in title.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.is_empty() && !s.ends_with('-') {
            s.push('-');
        }
    }
    while s.ends_with('-') {
        s.pop();
    }
    if s.len() > 80 {
        // Cut where a word ends: at a `-` (the 81st character being one means the 80 end a word).
        let cut = if s.as_bytes()[80] == b'-' {
            80
        } else {
            s[..80].rfind('-').unwrap_or(80)
        };
        s.truncate(cut);
    }
    while s.ends_with('-') {
        s.pop();
    }
    s
}

/// Every file to write, in order: the report's files, `table.md`, `tables.json`, one CSV per table.
/// Refuses a bad or repeated name before anything is written.
fn plan(report: &Report) -> Result<Vec<(String, Vec<u8>)>, RunError> {
    let mut names = BTreeSet::new();
    let mut files = Vec::new();
    for f in &report.files {
        let n = f.name.as_str();
        if n.is_empty()
            || n == "."
            || n == ".."
            || n.contains(['/', '\\', '\0'])
            || Path::new(n).components().count() != 1
        {
            return Err(RunError::Internal(format!(
                "output file name {n:?} is not a plain file name"
            )));
        }
        if n == TABLE_MD || n == TABLES_JSON || !names.insert(n.to_owned()) {
            return Err(RunError::Internal(format!(
                "output file name {n:?} is used twice"
            )));
        }
        files.push((n.to_owned(), f.contents.clone()));
    }
    for fixed in [TABLE_MD, TABLES_JSON] {
        names.insert(fixed.to_owned());
    }
    files.push((TABLE_MD.to_owned(), report.text().into_bytes()));
    files.push((TABLES_JSON.to_owned(), report.to_json().into_bytes()));
    for (i, t) in report.tables.iter().enumerate() {
        if let Some(data) = &t.data_file {
            // An excerpt: its data is written once, in the file it names.
            if !report.files.iter().any(|f| &f.name == data) {
                return Err(RunError::Internal(format!(
                    "table {:?} names data file {data:?}, which the report does not write",
                    t.title
                )));
            }
            continue;
        }
        let mut base = slug(&t.title);
        if base.is_empty() {
            base = format!("table-{}", i + 1);
        }
        let mut name = format!("{base}.csv");
        let mut k = 2;
        while names.contains(&name) {
            name = format!("{base}-{k}.csv");
            k += 1;
        }
        names.insert(name.clone());
        files.push((name, t.to_csv().into_bytes()));
    }
    Ok(files)
}

/// A fresh hidden name beside `dir` for a temporary directory.
fn sibling(dir: &Path, what: &str) -> Result<PathBuf, RunError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = dir
        .file_name()
        .ok_or_else(|| RunError::Internal(format!("results path {} has no name", dir.display())))?
        .to_string_lossy();
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    Ok(dir.with_file_name(format!(".{name}.{what}-{}-{n}-{nanos}", std::process::id())))
}

fn io_err(what: &str, path: &Path, e: std::io::Error) -> RunError {
    RunError::Internal(format!("{what} {}: {e}", path.display()))
}

/// The process id in the name of a leftover: `.NAME.tmp-PID...` or `.NAME.old-PID...`
/// (results being written or moved aside by [`write_results`], or a file being written through
/// a temporary sibling), with NAME and whether it is an `old` one; `None` for any other name.
fn leftover(file_name: &str) -> Option<(&str, u32, bool)> {
    let rest = file_name.strip_prefix('.')?;
    let (name, after, old) = match (rest.rfind(".tmp-"), rest.rfind(".old-")) {
        (Some(t), Some(o)) if o > t => (&rest[..o], &rest[o + 5..], true),
        (Some(t), _) => (&rest[..t], &rest[t + 5..], false),
        (None, Some(o)) => (&rest[..o], &rest[o + 5..], true),
        (None, None) => return None,
    };
    let digits = after.split('-').next()?;
    if name.is_empty() || digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some((name, digits.parse().ok()?, old))
}

/// Whether the run that left `path` (a leftover of `<parent>/<name>` by process `pid`) has
/// ended: nobody holds the run lock of `name` ([`crate::lock`]). A process id alone proves
/// nothing on a file system shared with other machines (their processes are not this one's, and
/// ids are reused). Only where the lock cannot be told: on Linux, no `/proc/PID`; elsewhere, the
/// leftover is more than a day old. This process's own leftovers are never ended ones.
fn abandoned(parent: &Path, name: &str, path: &Path, pid: u32) -> bool {
    if pid == std::process::id() {
        return false;
    }
    if let Some(alive) = crate::lock::writer_alive(parent, name) {
        return !alive;
    }
    if Path::new("/proc/self").exists() {
        return !Path::new("/proc").join(pid.to_string()).exists();
    }
    fs::symlink_metadata(path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.elapsed().ok())
        .is_some_and(|age| age.as_secs() > 24 * 3600)
}

/// Cleans up after runs that were killed while writing into `parent` (an `--out` directory,
/// or a results directory shards share): removes the hidden temporary folders and files they
/// left (`.ID.tmp-PID-...`, with up to the whole results in them), and where a kill fell
/// between the two renames of [`write_results`] - `ID` gone, its previous results still
/// moved aside as `.ID.old-PID-...` - puts those back as `ID`; and removes run locks
/// (`.ID.lock`) nobody holds. Leftovers of runs still going (a concurrent run, here or on
/// another machine of a shared file system: it holds the run lock of `ID`) are left alone. A
/// `parent` that does not exist is fine.
///
/// Errors: an I/O failure while removing or renaming ([`RunError::Internal`]).
pub fn tidy(parent: &Path) -> Result<(), RunError> {
    let Ok(entries) = fs::read_dir(parent) else {
        return Ok(());
    };
    let mut found: Vec<(PathBuf, String, bool)> = Vec::new();
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let path = entry.path();
        if let Some((name, pid, old)) = leftover(&file_name)
            && abandoned(parent, name, &path, pid)
        {
            found.push((path, name.to_owned(), old));
        } else if file_name.starts_with('.') && file_name.ends_with(".lock") {
            crate::lock::remove_if_free(&path);
        }
    }
    found.sort();
    // Runs sharing the folder tidy it at once: a leftover another one has just removed or put
    // back is done, not an error.
    let done = |r: std::io::Result<()>| match r {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        other => other,
    };
    for (path, name, old) in found {
        let target = parent.join(&name);
        if old && fs::symlink_metadata(&target).is_err() {
            done(fs::rename(&path, &target))
                .map_err(|e| io_err("cannot put back the previous results", &target, e))?;
            continue;
        }
        let removed = if fs::symlink_metadata(&path).is_ok_and(|m| m.is_dir()) {
            fs::remove_dir_all(&path)
        } else {
            fs::remove_file(&path)
        };
        done(removed).map_err(|e| io_err("cannot remove the leftover", &path, e))?;
    }
    Ok(())
}

/// The writes under way in this process, for [`abandon_writes`]: temporary folders and files
/// being filled, and results moved aside while new ones take their place.
#[derive(Default)]
struct Pending {
    /// Set by [`abandon_writes`]: no write may start or go on.
    abandoned: bool,
    /// Temporary folders and files that would be left half written.
    temps: Vec<PathBuf>,
    /// (moved-aside previous results, the results folder they came from).
    aside: Vec<(PathBuf, PathBuf)>,
}

static PENDING: Mutex<Pending> = Mutex::new(Pending {
    abandoned: false,
    temps: Vec::new(),
    aside: Vec::new(),
});

/// Set first thing by [`abandon_writes`], without waiting for any lock.
static STOPPING: AtomicBool = AtomicBool::new(false);

/// Whether the process is being stopped ([`abandon_writes`] has begun): no write starts any
/// more, and a process that reaches its end should leave its exit to the stopping thread.
pub fn stopping() -> bool {
    STOPPING.load(Ordering::SeqCst)
}

/// The pending writes, locked (a panic elsewhere while holding it leaves the list usable).
fn pending() -> MutexGuard<'static, Pending> {
    PENDING
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The pending writes, locked, for a write about to change what is on disk: once the writes are
/// abandoned (the process is being stopped) this waits for the end of the process, so nothing
/// more is written.
fn pending_for_write() -> MutexGuard<'static, Pending> {
    // Seen before the lock is taken: a writer going from one file to the next would otherwise
    // take the lock again before the stopping thread, and finish the write regardless.
    if stopping() {
        loop {
            std::thread::park();
        }
    }
    let guard = pending();
    if guard.abandoned {
        drop(guard);
        loop {
            std::thread::park();
        }
    }
    guard
}

/// Records `path` as a temporary folder or file being written (removed by [`abandon_writes`]
/// if the process is stopped before [`finish_temp`]). Call it before creating `path`.
fn start_temp(path: &Path) {
    pending_for_write().temps.push(path.to_path_buf());
}

/// `path` (given to [`start_temp`]) has been renamed into place or removed.
fn finish_temp(path: &Path) {
    pending().temps.retain(|p| p != path);
}

/// What a file written by [`write_file`] is: the words for it, and how a file of that kind is
/// recognised, so that a write replaces only a file of its own kind and never another (a
/// results file named as a bundle, a user's notes named as the report page, a device node).
#[derive(Debug, Clone, Copy)]
pub struct FileKind {
    /// In words, for a refusal: `the report page`, `a bundle`, `a partial file`.
    pub what: &'static str,
    /// Whether an existing file, from its first bytes (up to [`RECOGNISED_BYTES`]), is one of
    /// this kind written by the toolkit.
    pub recognise: fn(&[u8]) -> bool,
}

/// How much of an existing file [`FileKind::recognise`] is shown: 64 KiB.
pub const RECOGNISED_BYTES: usize = 64 * 1024;

/// Why a write refused or failed.
#[derive(Debug)]
pub enum WriteError {
    /// What is at the path may not be replaced (the rule broken, in words): bad input.
    Refused(String),
    /// An I/O failure: the step that failed (`create`, `write`, `rename into`) and the error.
    Io(&'static str, std::io::Error),
}

impl std::fmt::Display for WriteError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WriteError::Refused(why) => f.write_str(why),
            WriteError::Io(what, e) => write!(f, "cannot {what} it: {e}"),
        }
    }
}

/// Whether a write of `kind` may replace what is at `path`: nothing there, or a regular file of
/// that kind ([`FileKind::recognise`]). Refused (the rule, in words, without the path): a path
/// that cannot be inspected (a loop of symbolic links, a folder on the way that is a file), a
/// directory, a symbolic link, a device, FIFO or socket, or a file of anything else. Checked
/// before any work, and again just before the rename into place.
pub fn check_replace(path: &Path, kind: &FileKind) -> Result<(), String> {
    let meta = match fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(format!("cannot be inspected ({e})")),
    };
    let kind_of = file_type_words(&meta.file_type());
    if !meta.is_file() {
        return Err(format!(
            "exists and is {kind_of}, not a file: {} is written only where nothing is, or over {} the toolkit wrote",
            kind.what, kind.what
        ));
    }
    let mut head = Vec::new();
    let read = fs::File::open(path).and_then(|f| {
        use std::io::Read;
        f.take(RECOGNISED_BYTES as u64).read_to_end(&mut head)
    });
    if let Err(e) = read {
        return Err(format!("exists and cannot be read ({e})"));
    }
    if !(kind.recognise)(&head) {
        return Err(format!(
            "exists and is not {} the toolkit wrote: it would be replaced and lost; remove it or name another file",
            kind.what
        ));
    }
    Ok(())
}

/// A file type in words: `a directory`, `a symbolic link`, `a device`, `a FIFO`...
fn file_type_words(t: &fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else if t.is_symlink() {
        "a symbolic link"
    } else if t.is_file() {
        "a file"
    } else {
        "neither a file nor a directory"
    }
}

/// Writes `path` through a fresh temporary sibling (`.NAME.tmp-PID-...`, created new, so never
/// onto anything that is there), filled by `fill` and renamed into place; a stop while it is
/// written removes it ([`abandon_writes`]). What is at `path` must be replaceable by a write of
/// `kind` ([`check_replace`]), checked again just before the rename. On an error the temporary
/// file is removed and `path` is as it was.
pub fn write_file(
    path: &Path,
    kind: &FileKind,
    fill: &mut dyn FnMut(&mut fs::File) -> std::io::Result<()>,
) -> Result<(), WriteError> {
    check_replace(path, kind).map_err(WriteError::Refused)?;
    let tmp = sibling(path, "tmp").map_err(|e| {
        WriteError::Io(
            "name a temporary file for",
            std::io::Error::other(e.to_string()),
        )
    })?;
    start_temp(&tmp);
    let written = {
        let _writing = pending_for_write();
        fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| WriteError::Io("create a temporary file beside", e))
    }
    .and_then(|mut f| {
        fill(&mut f)
            .and_then(|()| f.sync_all())
            .map_err(|e| WriteError::Io("write", e))
    });
    let result = written
        .and_then(|()| check_replace(path, kind).map_err(WriteError::Refused))
        .and_then(|()| {
            let _renaming = pending_for_write();
            fs::rename(&tmp, path).map_err(|e| WriteError::Io("rename into", e))
        });
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    finish_temp(&tmp);
    result
}

/// Whether the folder `dir` holds results the toolkit wrote (its `tables.json`), or nothing but
/// hidden files: what [`write_results`] may replace whole. A folder of anything else (a user's
/// own files under the name of an experiment) would be deleted by the replacement.
pub fn results_replaceable(dir: &Path) -> Result<(), String> {
    let entries = fs::read_dir(dir).map_err(|e| format!("cannot be read ({e})"))?;
    let mut visible = false;
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot be read ({e})"))?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name == TABLES_JSON && entry.file_type().is_ok_and(|t| t.is_file()) {
            return Ok(());
        }
        visible |= !name.starts_with('.');
    }
    if visible {
        return Err(format!(
            "holds files that are not results the toolkit wrote (no {TABLES_JSON}): writing results there would delete them; move them, or give another --out"
        ));
    }
    Ok(())
}

/// For a process being stopped by a signal, before it exits: removes every temporary folder and
/// file being written, and puts back previous results moved aside whose replacement is not in
/// place, so the stop leaves the results directory as it was before the write (or with the
/// write done). Writes still running in other threads stop at their next step. Returns the
/// number of paths it cleaned up.
pub fn abandon_writes() -> usize {
    STOPPING.store(true, Ordering::SeqCst);
    let mut p = pending();
    p.abandoned = true;
    let mut cleaned = 0;
    for tmp in std::mem::take(&mut p.temps) {
        let removed = if fs::symlink_metadata(&tmp).is_ok_and(|m| m.is_dir()) {
            fs::remove_dir_all(&tmp)
        } else {
            fs::remove_file(&tmp)
        };
        cleaned += usize::from(removed.is_ok());
    }
    for (old, dir) in std::mem::take(&mut p.aside) {
        let restored = if fs::symlink_metadata(&dir).is_ok() {
            fs::remove_dir_all(&old)
        } else {
            fs::rename(&old, &dir)
        };
        cleaned += usize::from(restored.is_ok());
    }
    // The lock is kept: a write that reaches for it waits for the end of the process.
    std::mem::forget(p);
    crate::lock::release_locks();
    cleaned
}

/// Writes `report` into `dir` (= `<out>/<id>`) atomically.
///
/// Writes every [`OutputFile`] plus `table.md` ([`Report::text`]), `tables.json`
/// ([`Report::to_json`]) and one `<slug>.csv` per table (the slug of its title, or `table-<n>`
/// if it has none; `-2`, `-3`... added to repeats). Everything goes to a hidden sibling
/// temporary directory first, which is then renamed over `dir` (a previous `dir` is replaced
/// whole, so no stale file survives). The parent of `dir` is created if missing.
///
/// Leftovers of killed runs beside `dir` are cleaned up first ([`tidy`]).
///
/// On any error ([`RunError::Internal`]: a file name that is not a plain name or is used
/// twice, or an I/O failure) no temporary directory remains and `dir` is as it was before:
/// absent if it was absent, the previous results if there were some.
pub fn write_results(dir: &Path, report: &Report) -> Result<(), RunError> {
    let files = plan(report)?;
    if let Some(parent) = dir.parent().filter(|p| !p.as_os_str().is_empty()) {
        fs::create_dir_all(parent).map_err(|e| io_err("cannot create", parent, e))?;
        tidy(parent)?;
    }
    let tmp = sibling(dir, "tmp")?;
    start_temp(&tmp);
    // Each step under the lock of the pending writes: a stop waits for it, then removes `tmp`.
    let created = {
        let _creating = pending_for_write();
        fs::create_dir(&tmp).map_err(|e| io_err("cannot create", &tmp, e))
    };
    let filled = created.and_then(|()| {
        files.iter().try_for_each(|(name, bytes)| {
            let path = tmp.join(name);
            let _writing = pending_for_write();
            fs::write(&path, bytes).map_err(|e| io_err("cannot write", &path, e))
        })
    });
    let result = filled.and_then(|()| swap_in(&tmp, dir));
    if result.is_err() {
        // Best effort: the error being reported matters more than a failed clean-up.
        let _ = fs::remove_dir_all(&tmp);
    }
    finish_temp(&tmp);
    result
}

/// Renames `tmp` to `dir`. A previous `dir` (which must hold results, [`results_replaceable`])
/// is exchanged with `tmp` in one step where the system can (Linux), so that `dir` is never
/// missing for a reader, and the old results, now under the temporary name, are deleted;
/// elsewhere it is moved aside first.
fn swap_in(tmp: &Path, dir: &Path) -> Result<(), RunError> {
    match fs::symlink_metadata(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let _renaming = pending_for_write();
            fs::rename(tmp, dir).map_err(|e| io_err("cannot rename results to", dir, e))
        }
        Err(e) => Err(io_err("cannot inspect", dir, e)),
        Ok(meta) if !meta.is_dir() => Err(RunError::Internal(format!(
            "{} exists and is not a directory",
            dir.display()
        ))),
        Ok(_) => {
            results_replaceable(dir)
                .map_err(|why| RunError::Internal(format!("{}: {why}", dir.display())))?;
            if exchanged(tmp, dir)? {
                // `tmp` holds the previous results now: removed as a temporary folder.
                return fs::remove_dir_all(tmp)
                    .map_err(|e| io_err("cannot remove old results", tmp, e));
            }
            let old = sibling(dir, "old")?;
            {
                // Both renames under the lock: a stop sees the old results or the new in place.
                let mut p = pending_for_write();
                fs::rename(dir, &old).map_err(|e| io_err("cannot move aside", dir, e))?;
                if let Err(e) = fs::rename(tmp, dir) {
                    // Put the previous results back.
                    let _ = fs::rename(&old, dir);
                    return Err(io_err("cannot rename results to", dir, e));
                }
                p.aside.push((old.clone(), dir.to_path_buf()));
            }
            let removed =
                fs::remove_dir_all(&old).map_err(|e| io_err("cannot remove old results", &old, e));
            pending().aside.retain(|(o, _)| *o != old);
            removed
        }
    }
}

/// Exchanges the folders `tmp` and `dir` in one step (`renameat2` with `RENAME_EXCHANGE`):
/// `Ok(true)` when done, `Ok(false)` where the system or file system cannot (the caller then
/// moves `dir` aside first).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn exchanged(tmp: &Path, dir: &Path) -> Result<bool, RunError> {
    use nix::errno::Errno;
    use nix::fcntl::{AT_FDCWD, RenameFlags, renameat2};
    let _renaming = pending_for_write();
    match renameat2(AT_FDCWD, tmp, AT_FDCWD, dir, RenameFlags::RENAME_EXCHANGE) {
        Ok(()) => Ok(true),
        Err(Errno::EINVAL | Errno::ENOSYS | Errno::EOPNOTSUPP) => Ok(false),
        Err(e) => Err(io_err(
            "cannot exchange the results with",
            dir,
            std::io::Error::from(e),
        )),
    }
}

/// No exchange in one step here: the caller moves `dir` aside first.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn exchanged(_tmp: &Path, _dir: &Path) -> Result<bool, RunError> {
    Ok(false)
}

/// Reads the folder `dir` with `read` so that what is read is one version of it: a run may put
/// new results in its place while it is read ([`write_results`] exchanges the whole folder), so
/// the read is repeated (up to 50 times) until the folder is the same one before and after it.
/// A read that fails is repeated only when the folder changed meanwhile: else its error is the
/// answer.
pub fn read_one_version<T, E>(dir: &Path, mut read: impl FnMut() -> Result<T, E>) -> Result<T, E> {
    let mut tries = 0;
    loop {
        let before = identity(dir);
        let got = read();
        let after = identity(dir);
        tries += 1;
        if before == after || tries >= 50 {
            return got;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
}

/// What tells one folder at a path from another put there later (device and inode).
#[cfg(unix)]
fn identity(dir: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    fs::symlink_metadata(dir).ok().map(|m| (m.dev(), m.ino()))
}

/// No identity to compare here: every read is taken as it is.
#[cfg(not(unix))]
fn identity(_dir: &Path) -> Option<(u64, u64)> {
    None
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use crate::Table;
    use serde_json::Value;

    /// A fresh empty directory under the system temp dir, removed on drop.
    struct TempDir(PathBuf);
    impl TempDir {
        fn new(tag: &str) -> Self {
            let p = std::env::temp_dir().join(format!(
                "registry-test-{tag}-{}-{}",
                std::process::id(),
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .unwrap()
                    .as_nanos()
            ));
            fs::create_dir_all(&p).unwrap();
            TempDir(p)
        }
        fn entries(&self) -> Vec<String> {
            let mut v: Vec<String> = fs::read_dir(&self.0)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            v.sort();
            v
        }
    }
    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    fn report() -> Report {
        let mut t = Table::new("Mesh error (deg)", ["tooth", "error"]);
        t.row(vec!["1".into(), "0.25".into()]);
        let mut u = Table::new("Mesh error (deg)", ["a"]);
        u.row(vec!["x".into()]);
        let v = Table::new("", ["b"]);
        Report {
            tables: vec![t, u, v],
            files: vec![OutputFile::new("fig.svg", "<svg/>")],
            ..Default::default()
        }
    }

    #[test]
    fn writes_every_file() {
        let tmp = TempDir::new("ok");
        let dir = tmp.0.join("out").join("fig2");
        write_results(&dir, &report()).unwrap();
        let mut names: Vec<String> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "fig.svg",
                "mesh-error-deg-2.csv",
                "mesh-error-deg.csv",
                "table-3.csv",
                "table.md",
                "tables.json"
            ]
        );
        assert_eq!(
            fs::read_to_string(dir.join("table.md")).unwrap(),
            report().text()
        );
        assert_eq!(
            fs::read_to_string(dir.join("mesh-error-deg.csv")).unwrap(),
            "tooth,error\n1,0.25\n"
        );
        let json: Value =
            serde_json::from_str(&fs::read_to_string(dir.join("tables.json")).unwrap()).unwrap();
        assert_eq!(json["tables"][0]["rows"][0][1], "0.25");
        assert_eq!(
            json["tables"][0]["values"][0][1], 0.25,
            "numbers as numbers"
        );
        assert_eq!(json["tables"][1]["values"][0][0], "x");
        assert_eq!(json["files"][0], "fig.svg");
        // Only the results directory is left in out/.
        assert_eq!(
            fs::read_dir(tmp.0.join("out")).unwrap().count(),
            1,
            "temporary directory left behind"
        );
    }

    #[test]
    fn an_excerpt_table_has_no_csv_of_its_own() {
        let tmp = TempDir::new("excerpt");
        let dir = tmp.0.join("pair");
        let mut r = report();
        r.files.push(OutputFile::new("log.csv", "a\n1\n2\n"));
        let mut excerpt = Table::new("Log excerpt", ["a"]);
        excerpt.row(vec!["first".into()]);
        r.tables[1] = excerpt.data_in("log.csv");
        write_results(&dir, &r).unwrap();
        let mut names: Vec<String> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "fig.svg",
                "log.csv",
                "mesh-error-deg.csv",
                "table-3.csv",
                "table.md",
                "tables.json"
            ]
        );
        // The excerpt is still shown.
        let md = fs::read_to_string(dir.join("table.md")).unwrap();
        assert!(
            md.contains("### Log excerpt") && md.contains("first"),
            "{md}"
        );
        // Naming a file the report does not write is a programming error, caught before writing.
        let mut bad = report();
        bad.tables[0] = Table::new("Log excerpt", ["a"]).data_in("nope.csv");
        assert!(write_results(&tmp.0.join("bad"), &bad).is_err());
        assert!(!tmp.0.join("bad").exists());
    }

    #[test]
    fn replaces_previous_results_whole() {
        let tmp = TempDir::new("replace");
        let dir = tmp.0.join("fig2");
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("stale.txt"), "old").unwrap();
        fs::write(dir.join(TABLES_JSON), "{}").unwrap();
        write_results(&dir, &report()).unwrap();
        assert!(!dir.join("stale.txt").exists());
        assert!(dir.join("table.md").exists());
        assert_eq!(tmp.entries(), ["fig2"]);
    }

    #[test]
    fn bad_file_name_writes_nothing() {
        for bad in ["sub/x.svg", "", "..", "table.md", "fig.svg"] {
            let tmp = TempDir::new("badname");
            let dir = tmp.0.join("fig2");
            let mut r = report();
            r.files.push(OutputFile::new(bad, "x"));
            let e = write_results(&dir, &r).unwrap_err();
            assert_eq!(e.exit_code(), 1, "{bad:?}");
            assert!(tmp.entries().is_empty(), "{bad:?}: {:?}", tmp.entries());
        }
    }

    #[test]
    fn failure_midway_leaves_nothing() {
        // The OS refuses a 300-byte name after the first file is written: the temporary
        // directory must go, and no results directory appear.
        let tmp = TempDir::new("midway");
        let dir = tmp.0.join("fig2");
        let mut r = report();
        r.files.push(OutputFile::new("x".repeat(300), "x"));
        assert!(write_results(&dir, &r).is_err());
        assert!(tmp.entries().is_empty(), "{:?}", tmp.entries());
    }

    #[test]
    fn failure_midway_keeps_previous_results() {
        let tmp = TempDir::new("keep");
        let dir = tmp.0.join("fig2");
        write_results(&dir, &report()).unwrap();
        let mut r = report();
        r.files.push(OutputFile::new("x".repeat(300), "x"));
        assert!(write_results(&dir, &r).is_err());
        assert_eq!(tmp.entries(), ["fig2"]);
        assert!(dir.join("fig.svg").exists());
    }

    #[test]
    fn unwritable_parent_fails_and_leaves_nothing() {
        // The parent is a plain file, so nothing can be created under it (even as root).
        let tmp = TempDir::new("unwritable");
        let parent = tmp.0.join("plain-file");
        fs::write(&parent, "not a dir").unwrap();
        let e = write_results(&parent.join("fig2"), &report()).unwrap_err();
        assert_eq!(e.exit_code(), 1);
        assert_eq!(tmp.entries(), ["plain-file"]);

        // A results path that is a file is refused, and the file kept.
        let dir = tmp.0.join("fig2");
        fs::write(&dir, "a file").unwrap();
        assert!(write_results(&dir, &report()).is_err());
        assert_eq!(tmp.entries(), ["fig2", "plain-file"]);
    }

    #[test]
    fn a_folder_of_other_files_is_never_replaced() {
        let tmp = TempDir::new("foreign");
        let dir = tmp.0.join("pair");
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("my-pair.ron"), "(mine)").unwrap();
        let e = write_results(&dir, &report()).unwrap_err();
        assert!(e.to_string().contains("not results"), "{e}");
        assert!(dir.join("my-pair.ron").exists());
        assert_eq!(tmp.entries(), ["pair"]);
        // Nothing but hidden files (a shard folder's locks): replaced.
        fs::remove_file(dir.join("my-pair.ron")).unwrap();
        fs::write(dir.join(".partial-0-of-2.json.lock"), "").unwrap();
        write_results(&dir, &report()).unwrap();
        assert!(dir.join("table.md").exists());
    }

    const NOTE: FileKind = FileKind {
        what: "a note",
        recognise: |head| head.starts_with(b"note:"),
    };

    #[test]
    fn a_file_is_written_only_over_one_of_its_kind() {
        let tmp = TempDir::new("kind");
        let path = tmp.0.join("n.txt");
        let mut fill = |f: &mut fs::File| std::io::Write::write_all(f, b"note: one");
        write_file(&path, &NOTE, &mut fill).unwrap();
        write_file(&path, &NOTE, &mut fill).unwrap();
        fs::write(&path, "mine").unwrap();
        let e = write_file(&path, &NOTE, &mut fill).unwrap_err();
        assert!(
            e.to_string().contains("is not a note the toolkit wrote"),
            "{e}"
        );
        assert_eq!(fs::read_to_string(&path).unwrap(), "mine");
        fs::remove_file(&path).unwrap();
        fs::create_dir(&path).unwrap();
        let e = write_file(&path, &NOTE, &mut fill).unwrap_err();
        assert!(e.to_string().contains("is a directory"), "{e}");
        #[cfg(unix)]
        {
            let link = tmp.0.join("link");
            std::os::unix::fs::symlink("/dev/null", &link).unwrap();
            let e = write_file(&link, &NOTE, &mut fill).unwrap_err();
            assert!(e.to_string().contains("is a symbolic link"), "{e}");
        }
        // A failed fill leaves nothing.
        let other = tmp.0.join("m.txt");
        let mut failing = |_: &mut fs::File| Err(std::io::Error::other("no"));
        assert!(write_file(&other, &NOTE, &mut failing).is_err());
        let mut left = tmp.entries();
        left.sort();
        assert_eq!(left, ["link", "n.txt"]);
    }

    #[test]
    fn a_read_is_of_one_version_of_a_folder() {
        let tmp = TempDir::new("version");
        let dir = tmp.0.join("fig2");
        write_results(&dir, &report()).unwrap();
        // The folder is replaced during the first read: the read is made again.
        let mut reads = 0;
        let got: Result<usize, ()> = read_one_version(&dir, || {
            reads += 1;
            if reads == 1 {
                write_results(&dir, &report()).unwrap();
            }
            Ok(reads)
        });
        assert_eq!(got, Ok(if cfg!(unix) { 2 } else { 1 }));
    }

    /// A pid no process has: above the kernel's largest (2^22).
    const DEAD: u32 = 4_999_999;

    #[test]
    fn leftovers_of_killed_runs_are_removed() {
        let tmp = TempDir::new("leftover");
        let dir = tmp.0.join("pair");
        write_results(&dir, &report()).unwrap();
        // A run killed while writing: its temporary folder, holding large files.
        let killed = tmp.0.join(format!(".pair.tmp-{DEAD}-0-123"));
        fs::create_dir_all(&killed).unwrap();
        fs::write(killed.join("pair.csv"), vec![b'1'; 1000]).unwrap();
        // A shard killed while writing its partial file.
        fs::write(tmp.0.join(format!(".summary.md.tmp-{DEAD}")), "x").unwrap();
        // A concurrent run still writing (this test's own process): left alone.
        let alive = tmp.0.join(format!(".pair.tmp-{}-0-1", std::process::id()));
        fs::create_dir_all(&alive).unwrap();
        write_results(&dir, &report()).unwrap();
        assert_eq!(
            tmp.entries(),
            [
                alive.file_name().unwrap().to_string_lossy().into(),
                "pair".to_string()
            ]
        );
    }

    #[test]
    fn a_kill_between_the_renames_loses_no_results() {
        // Killed after the previous results were moved aside and before the new ones were
        // renamed in: `fig2` is missing. Tidying puts the previous results back.
        let tmp = TempDir::new("between");
        let dir = tmp.0.join("fig2");
        write_results(&dir, &report()).unwrap();
        fs::rename(&dir, tmp.0.join(format!(".fig2.old-{DEAD}-0-9"))).unwrap();
        fs::create_dir_all(tmp.0.join(format!(".fig2.tmp-{DEAD}-1-9"))).unwrap();
        tidy(&tmp.0).unwrap();
        assert_eq!(tmp.entries(), ["fig2"]);
        assert!(dir.join("fig.svg").exists());
        // Nothing to do for a folder that does not exist.
        tidy(&tmp.0.join("absent")).unwrap();
    }

    #[test]
    fn leftover_names() {
        assert_eq!(leftover(".pair.tmp-12-0-5"), Some(("pair", 12, false)));
        assert_eq!(leftover(".a.b.old-7-1-2"), Some(("a.b", 7, true)));
        assert_eq!(
            leftover(".partial-0-of-2.json.tmp-42"),
            Some(("partial-0-of-2.json", 42, false))
        );
        for other in [
            "pair",
            ".pair",
            ".pair.tmp-",
            ".pair.tmp-x1",
            ".tmp-3",
            "table.md",
        ] {
            assert_eq!(leftover(other), None, "{other}");
        }
    }

    #[test]
    fn text_separates_tables_by_blank_lines() {
        let r = report();
        let text = r.text();
        assert!(
            text.contains("|     1 |  0.25 |\n\n### Mesh error (deg)\n"),
            "{text}"
        );
        assert_eq!(Report::default().text(), "");
    }

    #[test]
    fn slugs() {
        assert_eq!(slug("Mesh error (deg), N=24"), "mesh-error-deg-n-24");
        assert_eq!(slug("  ---  "), "");
        assert_eq!(slug("Ångström"), "ngstr-m");
        // Cut at the end of a word, never inside one.
        let long = "Table 3: trials (of 200) with at least one jam / disengagement, G = 40 %: ours (paper)";
        let s = slug(long);
        assert_eq!(
            s,
            "table-3-trials-of-200-with-at-least-one-jam-disengagement-g-40-ours-paper"
        );
        let longer = format!("{long} and more words beyond the limit");
        let s = slug(&longer);
        assert!(s.len() <= 80, "{s}");
        assert_eq!(
            s,
            "table-3-trials-of-200-with-at-least-one-jam-disengagement-g-40-ours-paper-and"
        );
        assert_eq!(slug(&"x".repeat(100)).len(), 80);
    }
}
