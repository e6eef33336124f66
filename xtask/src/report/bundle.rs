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

/// Writes `file`: the results under `out` (each experiment's folder and `index.html`) under
/// `results/`, and every input their `run.json` names under `inputs/`. An input that is gone,
/// or whose contents no longer have the SHA-256 its run recorded, is refused naming both files:
/// the archive would not hold what the results were computed from. The archive is written to a
/// temporary sibling and renamed into place, so a failure leaves no half-written archive.
pub(crate) fn write(out: &Path, file: &Path) -> Result<(), Failure> {
    let dirs = result_folders(out)?;
    let inputs = named_inputs(out, &dirs)?;
    let tmp = crate::shared::temp_sibling(file, "bundle");
    let internal = |what: &str, e: std::io::Error| {
        Failure::Internal(format!("cannot {what} {}: {e}", file.display()))
    };
    let result = (|| {
        let f = std::fs::File::create(&tmp).map_err(|e| internal("create", e))?;
        let gz = flate2::write::GzEncoder::new(f, flate2::Compression::default());
        let mut tar = tar::Builder::new(gz);
        tar.mode(tar::HeaderMode::Deterministic);
        let index = out.join(super::INDEX_HTML);
        if index.is_file() {
            tar.append_path_with_name(&index, format!("results/{}", super::INDEX_HTML))
                .map_err(|e| internal("write", e))?;
        }
        for d in &dirs {
            let name = d
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            tar.append_dir_all(format!("results/{name}"), d)
                .map_err(|e| internal("write", e))?;
        }
        for (name, (path, hash, run_json)) in &inputs {
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
            let mut header = tar::Header::new_gnu();
            header.set_size(bytes.len() as u64);
            header.set_mode(0o644);
            header.set_mtime(0);
            header.set_cksum();
            tar.append_data(&mut header, name, bytes.as_slice())
                .map_err(|e| internal("write", e))?;
        }
        let gz = tar.into_inner().map_err(|e| internal("write", e))?;
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
