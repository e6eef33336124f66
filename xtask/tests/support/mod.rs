//! What the integration tests share: running the built binary and reading what it printed, a
//! scratch directory, finding Chromium, and reading a results directory.

#![allow(
    dead_code,
    reason = "each test file uses its own subset of these helpers"
)]

pub mod browser;
pub mod hostile;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the built `xtask` with `args` and extra environment, without the caller's log,
/// backtrace or progress settings.
pub fn xtask_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_xtask"));
    c.args(args)
        .env_remove("RUST_LOG")
        .env_remove("RUST_BACKTRACE")
        .env_remove("XTASK_PROGRESS");
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().unwrap()
}

/// Runs the built `xtask` with `args`.
pub fn xtask(args: &[&str]) -> Output {
    xtask_env(args, &[])
}

/// What `o` printed on stdout, as text (invalid UTF-8 replaced).
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// What `o` printed on stderr, as text (invalid UTF-8 replaced).
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `xtask` with `args`, asserts it succeeded, and returns its stdout (which must be UTF-8).
pub fn succeeded(args: &[&str]) -> String {
    let o = xtask(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

/// Asserts that the run `o` succeeded; returns its stdout and stderr as text.
pub fn succeeded_output(o: &Output) -> (String, String) {
    let err = stderr(o);
    assert!(o.status.success(), "{err}");
    (stdout(o), err)
}

/// Writes `text` to `name` in a fresh scratch dir, runs `xtask` with `args` (`{file}` stands for
/// that file, `{out}` for a results dir) and returns (exit code, stderr, whether `{out}` exists).
pub fn run_with_file(
    tag: &str,
    name: &str,
    text: &str,
    args: &[&str],
) -> (Option<i32>, String, bool) {
    let s = Scratch::new(tag);
    let file = s.path(name);
    fs::write(&file, text).unwrap();
    let out = s.path("results");
    let args: Vec<String> = args
        .iter()
        .map(|a| a.replace("{file}", &file).replace("{out}", &out))
        .collect();
    let o = xtask(&args.iter().map(String::as_str).collect::<Vec<_>>());
    (o.status.code(), stderr(&o), Path::new(&out).exists())
}

/// A fresh scratch directory under the system temp dir, removed on drop unless kept.
pub struct Scratch(pub PathBuf, bool);

impl Scratch {
    /// Creates `xtask-<tag>-<pid>-<nanos>` under the temp dir.
    pub fn new(tag: &str) -> Self {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos();
        let p = std::env::temp_dir().join(format!("xtask-{tag}-{}-{nanos}", std::process::id()));
        fs::create_dir_all(&p).unwrap();
        Scratch(p, false)
    }

    /// `rel` under the scratch directory, as a string for the command line.
    pub fn path(&self, rel: &str) -> String {
        self.0.join(rel).to_str().unwrap().to_owned()
    }

    /// Whether dropping leaves the directory in place (for a failure to be looked at).
    pub fn keep(&mut self, keep: bool) {
        self.1 = keep;
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !self.1 {
            let _ = fs::remove_dir_all(&self.0);
        }
    }
}

/// Chromium's path: `$CHROMIUM`, else `/usr/bin/chromium` if present.
pub fn chromium() -> Option<PathBuf> {
    std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .or_else(|| Some(PathBuf::from("/usr/bin/chromium")))
        .filter(|p| p.is_file())
}

/// Chromium, or `None` after saying the test is skipped; with `CI=true` a missing Chromium fails.
pub fn chromium_or_skip() -> Option<PathBuf> {
    let chrome = chromium();
    if chrome.is_none() {
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "CI=true and no Chromium: .ci/run installs it (scripts/check-report.sh install)"
        );
        eprintln!("skipped: no Chromium (set CHROMIUM or install it)");
    }
    chrome
}

/// `json` (a partial file) with the checksum the runner gives it: SHA-256 of its compact JSON
/// without the `checksum` member.
pub fn sealed(mut json: serde_json::Value) -> String {
    use sha2::Digest;
    json.as_object_mut().unwrap().remove("checksum");
    let sum: String = sha2::Sha256::digest(json.to_string().as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    json.as_object_mut()
        .unwrap()
        .insert("checksum".into(), sum.into());
    json.to_string()
}

/// Every results file by name. `run.json` is the run's provenance (date, thread count): it must
/// be there and name the experiment, but it differs between runs by design.
pub fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            let mut bytes = fs::read(e.path()).unwrap();
            if name == "run.json" {
                let v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
                assert!(v["id"].is_string() && v["date"].is_string(), "{v}");
                bytes = b"(provenance)".to_vec();
            }
            (name, bytes)
        })
        .collect()
}

/// A reduced table1: short runs of every pointer with few samples (the trials come from the test).
pub const TABLE1_SHORT: &[&str] = &[
    "--set",
    "lunar_turns=0.2",
    "--set",
    "metonic_turns=0.2",
    "--set",
    "saros_turns=0.2",
    "--set",
    "games_turns=0.2",
    "--set",
    "exeligmos_turns=0.2",
    "--set",
    "samples_per_engagement=4",
];

/// A tiny table1: two trials of very short runs, for tests that only need it to run.
pub const TABLE1_TINY: &[&str] = &[
    "--set",
    "trials=2",
    "--set",
    "lunar_turns=0.05",
    "--set",
    "metonic_turns=0.05",
    "--set",
    "saros_turns=0.05",
    "--set",
    "games_turns=0.05",
    "--set",
    "exeligmos_turns=0.05",
    "--set",
    "samples_per_engagement=2",
];

/// Asserts that `xtask args` is refused as a bad command line: exit status 2, one line on stderr
/// (pointing to the usage when `usage` is set), nothing on stdout (nothing ran).
pub fn refused_in_one_line(args: &[&str], usage: bool) {
    let o = xtask(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{args:?}: one line: {err}");
    assert_eq!(
        err.contains("`cargo xtask help` shows the usage"),
        usage,
        "{args:?}: {err}"
    );
    assert!(o.stdout.is_empty(), "{args:?}: nothing may run");
}

/// Runs `xtask run` with the experiment ids (and their flags) `ids`, then `extra`.
pub fn run_args(ids: &[&str], extra: &[&str]) -> Output {
    let mut args = vec!["run"];
    args.extend_from_slice(ids);
    args.extend_from_slice(extra);
    xtask(&args)
}
