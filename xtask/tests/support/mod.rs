//! What the integration tests that run reduced experiments share: running the built binary, a
//! scratch directory, and reading a results directory.

#![allow(
    dead_code,
    reason = "each test file uses its own subset of these helpers"
)]

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the built `xtask` with `args` and extra environment, without the caller's log or
/// progress settings.
pub fn xtask_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_xtask"));
    c.args(args)
        .env_remove("RUST_LOG")
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

/// A fresh scratch directory under the system temp dir, removed on drop.
pub struct Scratch(pub PathBuf);

impl Scratch {
    /// Creates `xtask-<tag>-<pid>-<nanos>` under the temp dir.
    pub fn new(tag: &str) -> Self {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos();
        let p = std::env::temp_dir().join(format!("xtask-{tag}-{}-{nanos}", std::process::id()));
        fs::create_dir_all(&p).unwrap();
        Scratch(p)
    }

    /// `rel` under the scratch directory, as a string for the command line.
    pub fn path(&self, rel: &str) -> String {
        self.0.join(rel).to_str().unwrap().to_owned()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
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
