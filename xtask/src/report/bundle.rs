//! `report --bundle FILE`: one gzipped tar archive of a results folder and the inputs its runs
//! read, for a paper's supplement: `results/` (every experiment's folder as written, and the
//! report page) and `inputs/` (each input file a `run.json` names, checked against the SHA-256
//! recorded there).

use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};

use crate::failure::Failure;
use crate::provenance::{RUN_JSON, sha256};

/// The inputs named in the `run.json` files under `out`: archive name → (path as typed, the
/// SHA-256 recorded, the `run.json` that names it). Relative paths are as typed, from the
/// directory the command runs in.
fn named_inputs(
    out: &Path,
    ids: &[PathBuf],
) -> Result<BTreeMap<String, (PathBuf, String, PathBuf)>, Failure> {
    let mut inputs = BTreeMap::new();
    for dir in ids {
        let run_json = dir.join(RUN_JSON);
        let Ok(text) = std::fs::read_to_string(&run_json) else {
            continue;
        };
        let v: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| Failure::Bad(format!("{}: not JSON ({e})", run_json.display())))?;
        for input in v["inputs"].as_array().into_iter().flatten() {
            let (Some(path), Some(hash)) = (input["path"].as_str(), input["sha256"].as_str())
            else {
                continue;
            };
            let name = format!("inputs/{}", archive_path(Path::new(path)));
            inputs.insert(
                name,
                (PathBuf::from(path), hash.to_owned(), run_json.clone()),
            );
        }
    }
    let _ = out;
    Ok(inputs)
}

/// `path` as a relative path inside the archive: its normal components only (no root, no `..`).
pub(super) fn archive_path(path: &Path) -> String {
    path.components()
        .filter_map(|c| match c {
            Component::Normal(s) => Some(s.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join("/")
}

/// The experiment folders of `out` (not the hidden folders of runs under way), by name.
fn result_folders(out: &Path) -> Result<Vec<PathBuf>, Failure> {
    let read = std::fs::read_dir(out)
        .map_err(|e| Failure::Bad(format!("--out {}: cannot read ({e})", out.display())))?;
    let mut dirs: Vec<PathBuf> = read
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| !n.to_string_lossy().starts_with('.'))
        })
        .collect();
    dirs.sort();
    Ok(dirs)
}

/// A tar archive being written, every entry dated `mtime` (seconds since 1970): the time the
/// bundle was made, one for all, rather than a fixed date of no meaning (`tar`'s deterministic
/// mode dates every entry 2006-07-24) or each file's own (which would also carry its owner).
struct Archive<W: std::io::Write> {
    tar: tar::Builder<W>,
    mtime: u64,
}

impl<W: std::io::Write> Archive<W> {
    /// Appends `bytes` as the file `name`.
    fn file(&mut self, name: &str, bytes: &[u8]) -> std::io::Result<()> {
        let mut header = tar::Header::new_gnu();
        header.set_entry_type(tar::EntryType::Regular);
        header.set_size(bytes.len() as u64);
        header.set_mode(0o644);
        header.set_mtime(self.mtime);
        header.set_cksum();
        self.tar.append_data(&mut header, name, bytes)
    }

    /// Appends the folder `name`, then everything under `dir` beneath it, in name order.
    fn tree(&mut self, dir: &Path, name: &str) -> std::io::Result<()> {
        let mut header = tar::Header::new_gnu();
        header.set_entry_type(tar::EntryType::Directory);
        header.set_size(0);
        header.set_mode(0o755);
        header.set_mtime(self.mtime);
        header.set_cksum();
        self.tar
            .append_data(&mut header, format!("{name}/"), std::io::empty())?;
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)?
            .map(|e| e.map(|e| e.path()))
            .collect::<Result<_, _>>()?;
        entries.sort();
        for path in entries {
            let child = format!(
                "{name}/{}",
                path.file_name().unwrap_or_default().to_string_lossy()
            );
            if path.is_dir() {
                self.tree(&path, &child)?;
            } else if path.is_file() {
                self.file(&child, &std::fs::read(&path)?)?;
            }
        }
        Ok(())
    }
}

/// Now, in seconds since 1970 (0 on a clock set before it).
pub(super) fn now_seconds() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs())
}

/// Reads each input `run.json` names and checks it against the SHA-256 recorded: an input that
/// is gone or changed is refused naming both files.
fn checked_inputs(
    inputs: &BTreeMap<String, (PathBuf, String, PathBuf)>,
) -> Result<Vec<(&String, Vec<u8>)>, Failure> {
    let mut read = Vec::new();
    for (name, (path, hash, run_json)) in inputs {
        let bytes = std::fs::read(path).map_err(|e| {
            Failure::Bad(format!(
                "{}: input file {} cannot be read ({e}): the bundle would not hold what the results were computed from",
                run_json.display(),
                path.display()
            ))
        })?;
        if sha256(&bytes) != *hash {
            return Err(Failure::Bad(format!(
                "{}: input file {} has changed since the run (its SHA-256 differs from the one recorded): run it again, or bundle the results without it",
                run_json.display(),
                path.display()
            )));
        }
        read.push((name, bytes));
    }
    Ok(read)
}

/// Writes `file`: the results under `out` (each experiment's folder and `index.html`) under
/// `results/`, and every input their `run.json` names under `inputs/`, every entry dated when
/// the bundle is written. An input that is gone, or whose contents no longer have the SHA-256
/// its run recorded, is refused naming both files: the archive would not hold what the results
/// were computed from. The archive is written to a temporary sibling and renamed into place, so
/// a failure leaves no half-written archive.
pub(crate) fn write(out: &Path, file: &Path) -> Result<(), Failure> {
    let dirs = result_folders(out)?;
    let inputs = named_inputs(out, &dirs)?;
    let read = checked_inputs(&inputs)?;
    let tmp = crate::shared::temp_sibling(file, "bundle");
    let internal = |what: &str, e: std::io::Error| {
        Failure::Internal(format!("cannot {what} {}: {e}", file.display()))
    };
    let result = (|| {
        let f = std::fs::File::create(&tmp).map_err(|e| internal("create", e))?;
        let gz = flate2::write::GzEncoder::new(f, flate2::Compression::default());
        let mut archive = Archive {
            tar: tar::Builder::new(gz),
            mtime: now_seconds(),
        };
        let index = out.join(super::INDEX_HTML);
        if index.is_file() {
            let page = std::fs::read(&index).map_err(|e| internal("read for", e))?;
            archive
                .file(&format!("results/{}", super::INDEX_HTML), &page)
                .map_err(|e| internal("write", e))?;
        }
        for d in &dirs {
            let name = d
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            archive
                .tree(d, &format!("results/{name}"))
                .map_err(|e| internal("write", e))?;
        }
        for (name, bytes) in &read {
            archive
                .file(name, bytes)
                .map_err(|e| internal("write", e))?;
        }
        let gz = archive.tar.into_inner().map_err(|e| internal("write", e))?;
        gz.finish().map_err(|e| internal("write", e))?;
        std::fs::rename(&tmp, file).map_err(|e| internal("rename into", e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn archive_paths_stay_inside_the_archive() {
        assert_eq!(
            archive_path(Path::new("/etc/gearing.ron")),
            "etc/gearing.ron"
        );
        assert_eq!(archive_path(Path::new("../data/x.csv")), "data/x.csv");
        assert_eq!(archive_path(Path::new("./a/b")), "a/b");
    }
}
