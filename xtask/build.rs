//! The identity of the code this runner computes with: `XTASK_CODE_SHA256`, the SHA-256 of every
//! source and data file that decides what an experiment computes (each workspace crate's
//! manifest, build script, `src/` and `data/`, the experiments' `paper.ron`, and the workspace's
//! `Cargo.toml` and `Cargo.lock`). Shards record it in their partial files and `merge` refuses
//! shards of other code; `run.json` records it too. Tests, benchmarks and documents are left
//! out: they change no result.
//!
//! A hash of the files, not a git commit: it is there without git (a source tarball), and it
//! tells uncommitted changes apart.

use std::fs;
use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

/// Every file below `dir`, recursively.
fn walk(dir: &Path, files: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        match entry.file_type() {
            Ok(t) if t.is_dir() => walk(&path, files),
            Ok(t) if t.is_file() => files.push(path),
            _ => {}
        }
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default());
    let root = manifest.parent().unwrap_or(&manifest).to_path_buf();
    let mut crates: Vec<PathBuf> = fs::read_dir(root.join("crates"))
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    crates.push(root.join("experiments"));
    crates.push(root.join("xtask"));
    let mut files = vec![root.join("Cargo.toml"), root.join("Cargo.lock")];
    let mut watched = files.clone();
    for dir in &crates {
        for name in ["Cargo.toml", "build.rs", "paper.ron"] {
            let f = dir.join(name);
            if f.is_file() {
                files.push(f.clone());
                watched.push(f);
            }
        }
        for sub in ["src", "data"] {
            let d = dir.join(sub);
            if d.is_dir() {
                walk(&d, &mut files);
                watched.push(d);
            }
        }
    }
    // A crate added or removed changes the workspace's manifest, which is watched.
    let mut named: Vec<(String, PathBuf)> = files
        .into_iter()
        .map(|f| {
            let rel = f.strip_prefix(&root).unwrap_or(&f).to_string_lossy();
            (rel.replace('\\', "/"), f)
        })
        .collect();
    named.sort();
    let mut hash = Sha256::new();
    for (rel, path) in &named {
        let bytes = fs::read(path).unwrap_or_default();
        hash.update(rel.as_bytes());
        hash.update([0]);
        hash.update((bytes.len() as u64).to_le_bytes());
        hash.update(&bytes);
    }
    let hex: String = hash.finalize().iter().map(|b| format!("{b:02x}")).collect();
    println!("cargo:rustc-env=XTASK_CODE_SHA256={hex}");
    for w in watched {
        println!("cargo:rerun-if-changed={}", w.display());
    }
}
