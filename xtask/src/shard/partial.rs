//! A sharded run's partial file: `run <id> --shard K/N` writes one, `merge` finds, reads and
//! checks the partial files of every shard.
//!
//! A partial file, `<out>/<id>/partial-K-of-N.json`, holds what the merge needs to run the
//! experiment again exactly as the shards did (the experiment id, seed, `--set` overrides and
//! config file, K and N, the runner's version) and the trial values the shard recorded
//! ([`registry::Records`]), with what identifies the computation: the SHA-256 of the code that
//! computed it ([`crate::provenance::CODE_SHA256`]), the SHA-256 of every file it read, and the
//! folder it ran in (against which relative paths were read). A merge refuses shards of other
//! code, or whose files have changed since.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use registry::{ConfigFile, Records, RunError, Shard};
use serde::{Deserialize, Serialize};

/// The `format` field of a partial file.
pub const FORMAT: &str = "cargo-xtask-partial/1";

/// The runner's version, recorded in each partial file; a merge refuses another one.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Directories below a merge input searched for partial files (`shards/3/table5/partial-...`).
const SEARCH_DEPTH: usize = 4;

/// The largest partial file a merge reads: 4 GiB (a shard of 10^6 trials in each of a table's
/// cells records a few hundred megabytes).
const MAX_PARTIAL_BYTES: u64 = 4 * 1024 * 1024 * 1024;

/// The config file given to the sharded run, stored whole so that the merge needs no copy.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    /// The path as given on the command line.
    pub path: String,
    /// Its contents.
    pub text: String,
}

/// The contents of a partial file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Partial {
    /// [`FORMAT`].
    pub format: String,
    /// Experiment id.
    pub experiment: String,
    /// `--seed`.
    pub seed: u64,
    /// `--set KEY=VALUE` overrides (with `--gearing` and `--hypothesis`), in order.
    pub sets: Vec<(String, String)>,
    /// `--config`, if given.
    pub config: Option<Config>,
    /// K: which shard.
    pub shard: u64,
    /// N: how many shards.
    pub shards: u64,
    /// [`VERSION`] of the runner that wrote it.
    pub version: String,
    /// The SHA-256 of the code that computed the shard ([`crate::provenance::CODE_SHA256`]);
    /// empty in files written before it was recorded, which a merge refuses as other code.
    #[serde(default)]
    pub code: String,
    /// The files the shard read (a gearing, measured errors), each with the SHA-256 of its
    /// contents: the merge reads them again and must find the same.
    #[serde(default)]
    pub inputs: Vec<InputFile>,
    /// The folder the shard ran in: relative paths in `sets` were read from there.
    #[serde(default)]
    pub folder: String,
    /// The trial batches the shard recorded.
    pub batches: Records,
    /// SHA-256 of the file's other members ([`checksum`]), so that a damaged or edited value
    /// is refused by the merge rather than merged.
    #[serde(default)]
    pub checksum: String,
}

/// A file a shard read: what it is (`gearing`, `measured errors`), its path as typed, and the
/// SHA-256 of its contents (empty when it could not be read).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputFile {
    /// What the file is, as `run.json` names it.
    pub role: String,
    /// The path as typed (relative to [`Partial::folder`] unless absolute).
    pub path: String,
    /// SHA-256 of its contents.
    pub sha256: String,
}

/// The SHA-256 of the file at `path` (as [`crate::provenance::sha256`]), or why it cannot be read.
pub fn file_sha256(path: &Path) -> Result<String, String> {
    input_file::read_to_string(path, input_file::MAX_INPUT_BYTES)
        .map(|text| crate::provenance::sha256(text.as_bytes()))
        .map_err(|e| e.to_string())
}

/// The files `ctx`'s run reads, with their hashes, for the partial file.
pub fn input_files(ctx: &registry::Context) -> Vec<InputFile> {
    setting_groups::inputs::files(ctx)
        .into_iter()
        .map(|(role, path)| InputFile {
            role: role.to_owned(),
            sha256: file_sha256(Path::new(&path)).unwrap_or_default(),
            path,
        })
        .collect()
}

/// The checksum of a partial file's JSON: SHA-256, in lowercase hex, of its value without the
/// `checksum` member, written compactly with object keys in the order serde_json gives them.
/// Any value changed after the shard wrote the file changes it.
pub fn checksum(json: &serde_json::Value) -> String {
    use sha2::Digest;
    let mut v = json.clone();
    if let Some(o) = v.as_object_mut() {
        o.remove("checksum");
    }
    let digest = sha2::Sha256::digest(v.to_string().as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

impl Partial {
    /// The header of a shard's partial file, before its batches are known.
    pub fn new(
        experiment: &str,
        seed: u64,
        sets: &[(String, String)],
        config: Option<&ConfigFile>,
        shard: Shard,
    ) -> Partial {
        Partial {
            format: FORMAT.into(),
            experiment: experiment.into(),
            seed,
            sets: sets.to_vec(),
            config: config.map(|c| Config {
                path: c.path.display().to_string(),
                text: c.text.clone(),
            }),
            shard: shard.index(),
            shards: shard.count(),
            version: VERSION.into(),
            code: crate::provenance::CODE_SHA256.into(),
            inputs: Vec::new(),
            folder: std::env::current_dir()
                .map(|d| d.display().to_string())
                .unwrap_or_default(),
            batches: Records::new(),
            checksum: String::new(),
        }
    }

    /// The config file as the experiment's context takes it.
    pub fn config_file(&self) -> Option<ConfigFile> {
        self.config.as_ref().map(|c| ConfigFile {
            path: PathBuf::from(&c.path),
            text: c.text.clone(),
        })
    }

    /// The file's JSON (one line), with its [`checksum`], and a final newline.
    pub fn to_json(&self) -> Result<String, RunError> {
        let fail =
            |e: serde_json::Error| RunError::Internal(format!("cannot write a partial file: {e}"));
        let value = serde_json::to_value(self).map_err(fail)?;
        let mut sealed = self.clone();
        sealed.checksum = checksum(&value);
        let mut s = serde_json::to_string(&sealed).map_err(fail)?;
        s.push('\n');
        Ok(s)
    }
}

/// A partial file, as [`Partial::to_json`] writes it: a shard replaces only another.
pub(crate) const KIND: registry::FileKind = registry::FileKind {
    what: "a partial file",
    recognise: |head| head.starts_with(b"{\"format\":\"cargo-xtask-partial/"),
};

/// `partial-K-of-N.json`.
pub fn file_name(shard: Shard) -> String {
    format!("partial-{}-of-{}.json", shard.index(), shard.count())
}

/// (K, N) of a file named `partial-K-of-N.json`.
pub(crate) fn parse_name(name: &str) -> Option<(u64, u64)> {
    let middle = name.strip_prefix("partial-")?.strip_suffix(".json")?;
    let (k, n) = middle.split_once("-of-")?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !digits(k) || !digits(n) {
        return None;
    }
    Some((k.parse().ok()?, n.parse().ok()?))
}

/// The partial files named by `inputs`: each file as given, and every `partial-K-of-N.json`
/// in and below each directory (up to [`SEARCH_DEPTH`] levels), sorted by path; a file reached
/// twice counts once.
///
/// Errors ([`RunError::BadInput`]): an input that does not exist; no partial file at all.
pub fn find(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, RunError> {
    let mut files = Vec::new();
    for input in inputs {
        let meta = fs::metadata(input).map_err(|e| {
            RunError::bad(
                "merge",
                input.display().to_string(),
                format!("cannot read: {e}"),
            )
        })?;
        if meta.is_dir() {
            let mut found = Vec::new();
            search(input, SEARCH_DEPTH, &mut found)?;
            found.sort();
            files.extend(found);
        } else {
            files.push(input.clone());
        }
    }
    let mut seen = BTreeSet::new();
    files.retain(|f| seen.insert(fs::canonicalize(f).unwrap_or_else(|_| f.clone())));
    if files.is_empty() {
        let given: Vec<String> = inputs.iter().map(|p| p.display().to_string()).collect();
        return Err(RunError::bad(
            "merge",
            given.join(" "),
            "no partial files (partial-K-of-N.json, written by `cargo xtask run <id> --shard K/N`) found",
        ));
    }
    Ok(files)
}

fn search(dir: &Path, depth: usize, found: &mut Vec<PathBuf>) -> Result<(), RunError> {
    let entries = fs::read_dir(dir).map_err(|e| {
        RunError::bad(
            "merge",
            dir.display().to_string(),
            format!("cannot read: {e}"),
        )
    })?;
    for entry in entries {
        let entry = entry.map_err(|e| {
            RunError::bad(
                "merge",
                dir.display().to_string(),
                format!("cannot read: {e}"),
            )
        })?;
        let path = entry.path();
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if kind.is_dir() {
            if depth > 0 {
                search(&path, depth - 1, found)?;
            }
        } else if parse_name(&entry.file_name().to_string_lossy()).is_some() {
            found.push(path);
        }
    }
    Ok(())
}

/// Reads and checks one partial file: its format, the runner's version, K < N, and that its
/// name (if it is `partial-K-of-N.json`) says the shard it holds.
pub fn read(path: &Path) -> Result<(Partial, Shard), RunError> {
    let source = path.display().to_string();
    if let Ok(meta) = fs::metadata(path)
        && !meta.is_file()
    {
        return Err(RunError::bad(
            &source,
            "file",
            "must be a regular file written by `cargo xtask run <id> --shard K/N`",
        ));
    }
    let text = input_file::read_to_string(path, MAX_PARTIAL_BYTES)
        .map_err(|e| RunError::bad(&source, "file", format!("cannot read: {e}")))?;
    let partial: Partial = serde_json::from_str(&text).map_err(|e| {
        RunError::bad(
            &source,
            "contents",
            format!(
                "is not a partial file written by `cargo xtask run <id> --shard K/N` (damaged or truncated?): {e}"
            ),
        )
    })?;
    if partial.format != FORMAT {
        return Err(RunError::bad(
            &source,
            "format",
            format!("must be `{FORMAT}` (got `{}`)", partial.format),
        ));
    }
    if partial.version != VERSION {
        return Err(RunError::bad(
            &source,
            "version",
            format!(
                "was written by xtask {}, this is {VERSION}: merge with the build that ran the shards",
                partial.version
            ),
        ));
    }
    let shard = Shard::new(partial.shard, partial.shards).map_err(|_| {
        RunError::bad(
            &source,
            "shard",
            format!(
                "{}/{} is not a shard K/N with K < N",
                partial.shard, partial.shards
            ),
        )
    })?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if let Some((k, n)) = parse_name(&name)
        && (k, n) != (shard.index(), shard.count())
    {
        return Err(RunError::bad(
            &source,
            "shard",
            format!("the file name says shard {k}/{n}, but the file holds shard {shard}"),
        ));
    }
    let value: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| RunError::bad(&source, "contents", format!("is not JSON: {e}")))?;
    if partial.checksum.is_empty() {
        return Err(RunError::bad(
            &source,
            "checksum",
            "is missing: every partial file written by `cargo xtask run <id> --shard K/N` carries one; run the shard again",
        ));
    }
    if checksum(&value) != partial.checksum {
        return Err(RunError::bad(
            &source,
            "checksum",
            "does not match the contents: the file was changed or damaged after the shard wrote it; run the shard again",
        ));
    }
    Ok((partial, shard))
}

/// Every partial file comes from the same sharded command as the first: same experiment, seed,
/// `--set` overrides, config file and number of shards.
pub fn agree(parts: &[(PathBuf, Partial, Shard)]) -> Result<(), RunError> {
    let Some((first_path, first, _)) = parts.first() else {
        return Ok(());
    };
    for (path, p, _) in &parts[1..] {
        let differ = |field: &str, this: String, that: String| {
            RunError::bad(
                path.display().to_string(),
                field,
                format!(
                    "is {this}, but {} has {that}: all shards must come from the same `cargo xtask run <id> --shard K/N` command with K from 0 to N-1",
                    first_path.display()
                ),
            )
        };
        if p.experiment != first.experiment {
            return Err(differ(
                "experiment",
                format!("`{}`", p.experiment),
                format!("`{}`", first.experiment),
            ));
        }
        if p.seed != first.seed {
            return Err(differ("seed", p.seed.to_string(), first.seed.to_string()));
        }
        if p.sets != first.sets {
            return Err(differ("--set", sets_text(&p.sets), sets_text(&first.sets)));
        }
        if p.config != first.config {
            let text = |c: &Option<Config>| {
                c.as_ref().map_or_else(
                    || "none".to_string(),
                    |c| format!("`{}` ({} bytes)", c.path, c.text.len()),
                )
            };
            return Err(differ("--config", text(&p.config), text(&first.config)));
        }
        if p.code != first.code {
            return Err(differ(
                "code",
                format!("SHA-256 {}", short(&p.code)),
                format!("SHA-256 {}", short(&first.code)),
            ));
        }
        if p.inputs != first.inputs {
            let text = |inputs: &[InputFile]| {
                if inputs.is_empty() {
                    return "none".to_owned();
                }
                inputs
                    .iter()
                    .map(|i| format!("{} `{}` (SHA-256 {})", i.role, i.path, short(&i.sha256)))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            return Err(differ("inputs", text(&p.inputs), text(&first.inputs)));
        }
        if p.shards != first.shards {
            return Err(differ(
                "N (number of shards)",
                p.shards.to_string(),
                first.shards.to_string(),
            ));
        }
    }
    Ok(())
}

/// How the sharded command of `theirs` differs from that of `mine`: the first field that does
/// (as [`agree`] names it) with their value and ours; `None` for the same command.
fn differs(theirs: &Partial, mine: &Partial) -> Option<(&'static str, String, String)> {
    let config = |c: &Option<Config>| {
        c.as_ref()
            .map_or_else(|| "none".to_string(), |c| format!("`{}`", c.path))
    };
    let inputs = |i: &[InputFile]| {
        i.iter()
            .map(|i| format!("`{}` (SHA-256 {})", i.path, short(&i.sha256)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    [
        (
            "experiment",
            theirs.experiment.clone(),
            mine.experiment.clone(),
        ),
        ("seed", theirs.seed.to_string(), mine.seed.to_string()),
        ("--set", sets_text(&theirs.sets), sets_text(&mine.sets)),
        ("--config", config(&theirs.config), config(&mine.config)),
        (
            "N (number of shards)",
            theirs.shards.to_string(),
            mine.shards.to_string(),
        ),
        ("code", short(&theirs.code), short(&mine.code)),
        ("inputs", inputs(&theirs.inputs), inputs(&mine.inputs)),
    ]
    .into_iter()
    .find(|(_, a, b)| a != b)
}

/// A shard writes its partial file into `dir` (`<out>/<id>/`) beside the other shards' of the
/// same command: refused (exit 2, before anything is computed) when `dir` holds a partial file
/// of another sharded command (another seed, `--set`, config, N, code or input), or one that
/// cannot be read as one. Replacing it would lose that run's shard without a word, and writing
/// beside it would leave a folder no merge can join. A partial file of the same command (the
/// shard run again, or its siblings) is fine.
pub fn only_this_run(dir: &Path, mine: &Partial, out: &Path) -> Result<(), RunError> {
    let Ok(entries) = fs::read_dir(dir) else {
        return Ok(());
    };
    let mut names: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| parse_name(n).is_some())
        .collect();
    names.sort();
    let refuse = |name: &str, why: String| {
        RunError::bad(
            "--out",
            format!("{}: {}/{name}", out.display(), mine.experiment),
            format!(
                "{why}: a shard never replaces or joins another run's partial files; merge them first (cargo xtask merge {} --out OTHER), move them, or give this run another --out",
                dir.display()
            ),
        )
    };
    for name in names {
        let theirs = match read(&dir.join(&name)) {
            Ok((p, _)) => p,
            Err(e) => {
                return Err(refuse(
                    &name,
                    format!("cannot be read as a partial file ({e})"),
                ));
            }
        };
        if let Some((field, them, us)) = differs(&theirs, mine) {
            return Err(refuse(
                &name,
                format!(
                    "is a shard of another sharded run (its {field} is {them}, this run's {us})"
                ),
            ));
        }
    }
    Ok(())
}

/// The first 12 hex digits of a SHA-256, enough to tell two apart in a message (`none` for an
/// empty one).
pub fn short(sha: &str) -> String {
    if sha.is_empty() {
        "none".to_owned()
    } else {
        format!("{}...", &sha[..sha.len().min(12)])
    }
}

/// Checks that the shards' code is this build's: results of other code, merged as if they were
/// this code's, would be a silent mix. Refused naming the file, both hashes and what to do.
pub fn same_code(path: &Path, p: &Partial) -> Result<(), RunError> {
    let this = crate::provenance::CODE_SHA256;
    if p.code == this {
        return Ok(());
    }
    let theirs = if p.code.is_empty() {
        "code that recorded no hash (an older build)".to_owned()
    } else {
        format!("code of SHA-256 {}", short(&p.code))
    };
    Err(RunError::bad(
        path.display().to_string(),
        "code",
        format!(
            "the shard was computed by {theirs}, and this build's code is {}: results of different code cannot be merged; merge with the build that ran the shards, or run the shards again with this one",
            short(this)
        ),
    ))
}

/// Checks that every file the shards read reads the same now, from the folder the merge runs
/// in: the merge runs the experiment again and reads them. A file changed since, or a relative
/// path that names nothing (or something else) from another folder, is refused naming the
/// setting's file, the folders and the rule.
pub fn same_inputs(p: &Partial) -> Result<(), RunError> {
    let here = std::env::current_dir()
        .map(|d| d.display().to_string())
        .unwrap_or_default();
    let moved = !p.folder.is_empty() && p.folder != here && Path::new(&p.folder).is_dir();
    for input in &p.inputs {
        let path = Path::new(&input.path);
        let relative = path.is_relative();
        let from_their_folder = || {
            if relative && moved {
                format!(
                    "; the shards ran in {} and read `{}` from there, and this merge runs in {here}: run the merge from {}, or give the shards the file's full path",
                    p.folder, input.path, p.folder
                )
            } else {
                String::new()
            }
        };
        let what = format!("{} `{}`", input.role, input.path);
        match file_sha256(path) {
            Err(e) => {
                return Err(RunError::bad(
                    "merge",
                    what,
                    format!(
                        "the shards read this file, and the merge must read it again, but it cannot be read from {here}: {e}{}",
                        from_their_folder()
                    ),
                ));
            }
            Ok(now) if now != input.sha256 => {
                return Err(RunError::bad(
                    "merge",
                    what,
                    format!(
                        "has changed since the shards read it (SHA-256 {} then, {} now){}: the merge reads it again, so it must be the file the shards read; put it back, or run the shards again",
                        short(&input.sha256),
                        short(&now),
                        if relative && moved {
                            from_their_folder()
                        } else {
                            String::new()
                        }
                    ),
                ));
            }
            Ok(_) => {}
        }
    }
    Ok(())
}

fn sets_text(sets: &[(String, String)]) -> String {
    if sets.is_empty() {
        "none".into()
    } else {
        let s: Vec<String> = sets.iter().map(|(k, v)| format!("{k}={v}")).collect();
        format!("`{}`", s.join(" "))
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn names() {
        let s = Shard::new(3, 12).unwrap();
        assert_eq!(file_name(s), "partial-3-of-12.json");
        assert_eq!(parse_name(&file_name(s)), Some((3, 12)));
        for bad in [
            "partial-3-of-12.json.tmp",
            ".partial-3-of-12.json.tmp-5",
            "partial--of-2.json",
            "partial-a-of-2.json",
            "partial-1-of-+2.json",
            "table.md",
        ] {
            assert_eq!(parse_name(bad), None, "{bad}");
        }
    }

    #[test]
    fn partials_round_trip() {
        let mut p = Partial::new(
            "table1",
            7,
            &[("trials".into(), "4".into())],
            Some(&ConfigFile {
                path: "c.ron".into(),
                text: "(x: 1)\n".into(),
            }),
            Shard::new(1, 2).unwrap(),
        );
        p.batches.insert("b".into(), registry::Batch::default());
        let back: Partial = serde_json::from_str(&p.to_json().unwrap()).unwrap();
        assert_eq!(back.checksum.len(), 64);
        assert_eq!(
            back.checksum,
            checksum(&serde_json::from_str(&p.to_json().unwrap()).unwrap())
        );
        p.checksum.clone_from(&back.checksum);
        assert_eq!(back, p);
        assert_eq!(back.config_file().unwrap().text, "(x: 1)\n");
    }
}
