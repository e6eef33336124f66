//! `report --bundle FILE`: one gzipped tar archive of a results folder and the inputs its runs
//! read, for a paper's supplement: `results/` (every experiment's folder as written, and the
//! report page) and `inputs/` (each input file a `run.json` names, checked against the SHA-256
//! recorded there).
//!
//! Everything is checked before the page or the archive is written ([`plan`]): where the
//! archive goes (a folder that exists, nothing there but an earlier bundle, not inside a folder
//! it archives, so that it can never hold itself), what it will hold (only the regular files the
//! runs wrote: no hidden temporary files of runs under way, no link or device that would be
//! followed), and every input against its recorded SHA-256.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

use crate::failure::Failure;
use crate::provenance::{RUN_JSON, sha256};

/// A bundle, as [`write()`] writes it: a gzipped tar archive whose first entry is under
/// `results/` or `inputs/`. Only such a file is replaced by another bundle.
pub(crate) const KIND: registry::FileKind = registry::FileKind {
    what: "a bundle",
    recognise: |head| {
        let mut first = [0u8; 512];
        let read = flate2::read::GzDecoder::new(head).read_exact(&mut first);
        read.is_ok() && (first.starts_with(b"results/") || first.starts_with(b"inputs/"))
    },
};

/// An input a `run.json` names: the path as typed, the SHA-256 recorded, the `run.json`, and
/// the folder the run read it from (where `run.json` records it).
struct Input {
    path: PathBuf,
    sha256: String,
    run_json: PathBuf,
    folder: Option<PathBuf>,
}

/// What a bundle will hold, checked: [`plan`] makes it, [`write()`] writes it.
pub(crate) struct Plan {
    /// The archive's path, as given.
    file: PathBuf,
    /// The experiment folders of `--out`, archived under `results/`.
    dirs: Vec<PathBuf>,
    /// Archive name (`inputs/...`) to the input and its recorded hash.
    inputs: BTreeMap<String, Input>,
}

/// `--bundle FILE: why`, as bad input.
fn refuse(file: &Path, why: impl std::fmt::Display) -> Failure {
    Failure::Bad(format!("--bundle: {}: {why}", file.display()))
}

/// Checks everything a bundle of `out` into `file` needs before anything is written, and takes
/// the run lock of `file` for the rest of the command: refused (exit 2) naming `--bundle` and
/// the rule when the folder it goes into does not exist, when something other than an earlier
/// bundle is at `file`, when `file` lies inside a folder it archives, when a results folder
/// holds something other than files and folders, or when an input is gone or changed.
pub(crate) fn plan(out: &Path, file: &Path) -> Result<Plan, Failure> {
    let parent = match file.parent().filter(|p| !p.as_os_str().is_empty()) {
        Some(p) => p.to_path_buf(),
        None => PathBuf::from("."),
    };
    let name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| refuse(file, "names no file"))?;
    match std::fs::metadata(&parent) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => {
            return Err(refuse(
                file,
                format!("{} is not a folder", parent.display()),
            ));
        }
        Err(e) => {
            return Err(refuse(
                file,
                format!("the folder {} cannot be used ({e})", parent.display()),
            ));
        }
    }
    registry::check_replace(file, &KIND).map_err(|why| refuse(file, why))?;
    let dirs = result_folders(out)?;
    outside(file, &parent, &dirs)?;
    let what = format!("a report writing the bundle {name}");
    if let Some(holder) = registry::lock_writing(&parent, &name, &what)? {
        return Err(refuse(
            file,
            format!(
                "another command is writing it now ({holder}): wait for it to end, or name another file"
            ),
        ));
    }
    for d in &dirs {
        registry::read_one_version(d, || files_of(d, d, false)).map_err(|why| refuse(file, why))?;
    }
    let inputs = named_inputs(&dirs)?;
    for input in inputs.values() {
        input_bytes(input)?;
    }
    Ok(Plan {
        file: file.to_path_buf(),
        dirs,
        inputs,
    })
}

/// The archive must not lie inside a folder it archives: it would hold itself (or, while it is
/// written, its own growing temporary file), and the next run of that experiment would delete it.
fn outside(file: &Path, parent: &Path, dirs: &[PathBuf]) -> Result<(), Failure> {
    let Ok(at) = std::fs::canonicalize(parent) else {
        return Ok(());
    };
    for d in dirs {
        if let Ok(d) = std::fs::canonicalize(d)
            && at.starts_with(&d)
        {
            return Err(refuse(
                file,
                format!(
                    "lies inside {}, a results folder the bundle archives: it would archive itself; write it beside the results folder instead",
                    d.display()
                ),
            ));
        }
    }
    Ok(())
}

/// The inputs named in the `run.json` files of `dirs`, by archive name. Relative paths are as
/// typed, read from the folder the command runs in (the rule of `merge`).
fn named_inputs(dirs: &[PathBuf]) -> Result<BTreeMap<String, Input>, Failure> {
    let mut inputs = BTreeMap::new();
    for dir in dirs {
        let run_json = dir.join(RUN_JSON);
        let Ok(text) = input_file::read_to_string(&run_json, 1 << 20) else {
            continue;
        };
        let v: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| Failure::Bad(format!("{}: not JSON ({e})", run_json.display())))?;
        let folder = v["folder"].as_str().map(PathBuf::from);
        for input in v["inputs"].as_array().into_iter().flatten() {
            let (Some(path), Some(hash)) = (input["path"].as_str(), input["sha256"].as_str())
            else {
                continue;
            };
            let name = format!("inputs/{}", archive_path(Path::new(path)));
            inputs.insert(
                name,
                Input {
                    path: PathBuf::from(path),
                    sha256: hash.to_owned(),
                    run_json: run_json.clone(),
                    folder: folder.clone(),
                },
            );
        }
    }
    Ok(inputs)
}

/// Where a relative input of a run made in another folder than this command's was read from,
/// for a refusal (empty otherwise), as `merge` says it of a shard's.
fn their_folder(input: &Input) -> String {
    let here = std::env::current_dir().unwrap_or_default();
    match &input.folder {
        Some(f) if input.path.is_relative() && *f != here => format!(
            "; the run read it from {}, and this command runs in {}: run the report from {}, or give the run the file's full path",
            f.display(),
            here.display(),
            f.display()
        ),
        _ => String::new(),
    }
}

/// The bytes of an input, which must still have the SHA-256 its run recorded.
fn input_bytes(input: &Input) -> Result<Vec<u8>, Failure> {
    let bytes = input_file::read_bytes(&input.path, input_file::MAX_INPUT_BYTES).map_err(|e| {
        Failure::Bad(format!(
            "{}: input file {} cannot be read ({e}): the bundle would not hold what the results were computed from{}",
            input.run_json.display(),
            input.path.display(),
            their_folder(input)
        ))
    })?;
    if sha256(&bytes) != input.sha256 {
        return Err(Failure::Bad(format!(
            "{}: input file {} has changed since the run (its SHA-256 differs from the one recorded){}: run it again, or bundle the results without it",
            input.run_json.display(),
            input.path.display(),
            their_folder(input)
        )));
    }
    Ok(bytes)
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
        .map_err(|e| Failure::Bad(format!("--out: {}: cannot read ({e})", out.display())))?;
    let mut dirs: Vec<PathBuf> = read
        .filter_map(Result::ok)
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| !n.to_string_lossy().starts_with('.'))
        })
        .collect();
    dirs.sort();
    Ok(dirs)
}

/// Every file below `dir` (relative to `root`, `/`-separated) with its bytes (`with_bytes`;
/// else none, for the check), sorted: regular
/// files and folders only, hidden names (temporary files of runs under way, run locks) left
/// out. Anything else (a symbolic link, a device, a FIFO) is refused naming it: a bundle holds
/// what the runs wrote, and following a link could archive anything (or read forever).
fn files_of(root: &Path, dir: &Path, with_bytes: bool) -> Result<Vec<(String, Vec<u8>)>, String> {
    let mut out = Vec::new();
    let entries =
        std::fs::read_dir(dir).map_err(|e| format!("{}: cannot read ({e})", dir.display()))?;
    let mut entries: Vec<_> = entries
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{}: cannot read ({e})", dir.display()))?;
    entries.sort_by_key(std::fs::DirEntry::file_name);
    for entry in entries {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = entry.path();
        let kind = entry
            .file_type()
            .map_err(|e| format!("{}: cannot be inspected ({e})", path.display()))?;
        if kind.is_dir() {
            out.extend(files_of(root, &path, with_bytes)?);
        } else if kind.is_file() {
            let bytes = if with_bytes {
                std::fs::read(&path)
                    .map_err(|e| format!("{}: cannot be read ({e})", path.display()))?
            } else {
                Vec::new()
            };
            let rel = path.strip_prefix(root).unwrap_or(&path);
            out.push((archive_path(rel), bytes));
        } else {
            return Err(format!(
                "{} is not a file or a folder (a link, a device or a FIFO): a results folder holds only what the runs wrote, and the bundle archives only that",
                path.display()
            ));
        }
    }
    Ok(out)
}

/// Now, in seconds since 1970 (0 on a clock set before it).
pub(super) fn now_seconds() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs())
}

/// Appends one file to the archive with a fixed mode, dated `mtime` (seconds since 1970): the
/// time the bundle was made, one for all, rather than a date of no meaning (1970, or `tar`'s
/// deterministic 2006-07-24) or each file's own (which would also carry its owner).
fn append<W: std::io::Write>(
    tar: &mut tar::Builder<W>,
    (name, mtime): (&str, u64),
    bytes: &[u8],
) -> std::io::Result<()> {
    let mut header = tar::Header::new_gnu();
    header.set_size(bytes.len() as u64);
    header.set_mode(0o644);
    header.set_mtime(mtime);
    header.set_cksum();
    tar.append_data(&mut header, name, bytes)
}

/// Writes the bundle `plan` checked: `page` (the report page just written) as
/// `results/index.html`, each folder's files under `results/<name>/` (each folder read as one
/// version of it, [`registry::read_one_version`]), and every input under `inputs/`, through a
/// temporary file renamed into place ([`registry::write_file`]).
pub(crate) fn write(plan: &Plan, page: &[u8]) -> Result<(), Failure> {
    let mut failed: Option<Failure> = None;
    let mtime = now_seconds();
    let written = registry::write_file(&plan.file, &KIND, &mut |f| {
        let gz = flate2::write::GzEncoder::new(f, flate2::Compression::default());
        let mut tar = tar::Builder::new(gz);
        append(
            &mut tar,
            (&format!("results/{}", super::INDEX_HTML), mtime),
            page,
        )?;
        for d in &plan.dirs {
            let name = d
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let files = registry::read_one_version(d, || files_of(d, d, true))
                .map_err(std::io::Error::other)?;
            for (rel, bytes) in files {
                append(&mut tar, (&format!("results/{name}/{rel}"), mtime), &bytes)?;
            }
        }
        for (name, input) in &plan.inputs {
            let bytes = input_bytes(input).map_err(|e| {
                let m = format!("{e:?}");
                failed = Some(e);
                std::io::Error::other(m)
            })?;
            append(&mut tar, (name, mtime), &bytes)?;
        }
        tar.into_inner()?.finish().map(drop)
    });
    match (written, failed) {
        (_, Some(f)) => Err(f),
        (Ok(()), None) => Ok(()),
        (Err(e), None) => Err(crate::shared::written(&plan.file, e)),
    }
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
