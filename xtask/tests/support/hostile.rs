//! Hostile input cases the bad-input tests share: a case (a file, a command line, the words its
//! one line of stderr must hold), running a table of them, and the gearing they corrupt.

use std::fs;
use std::path::Path;

use super::{Scratch, stderr, xtask};

/// A file to write: its name and bytes.
pub type File = Option<(&'static str, Vec<u8>)>;

/// A row of a table of cases: what it is, the file, the words the message must hold.
pub type Row<'a> = (&'a str, File, &'a [&'a str]);

/// One hostile input: the file to write (if any), the command line (`{file}` stands for the
/// file's path, `{out}` for a results directory that must stay absent) and the words its one
/// line of stderr must hold.
pub struct Case {
    what: String,
    file: File,
    args: Vec<String>,
    words: Vec<String>,
}

pub fn case(what: &str, file: File, args: &str, words: &[&str]) -> Case {
    Case {
        what: what.to_owned(),
        file,
        args: args.split_whitespace().map(str::to_owned).collect(),
        words: words.iter().map(|w| (*w).to_owned()).collect(),
    }
}

/// Runs every case; returns the descriptions of those that misbehaved.
pub fn failures(tag: &str, cases: Vec<Case>) -> Vec<String> {
    let mut bad = Vec::new();
    for (i, c) in cases.into_iter().enumerate() {
        let s = Scratch::new(&format!("bad-{tag}-{i}"));
        let file = c.file.as_ref().map(|(name, bytes)| {
            let p = s.0.join(name);
            fs::write(&p, bytes).unwrap();
            p
        });
        let out = s.0.join("out");
        let args: Vec<String> = c
            .args
            .iter()
            .map(|a| {
                let a = a.replace("{out}", out.to_str().unwrap());
                match &file {
                    Some(f) => a.replace("{file}", f.to_str().unwrap()),
                    None => a,
                }
            })
            .collect();
        let o = xtask(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let err = stderr(&o);
        let mut wrong = Vec::new();
        if o.status.code() != Some(2) {
            wrong.push(format!("exit status {:?}, not 2", o.status.code()));
        }
        if err.contains("panicked") {
            wrong.push("panicked".into());
        }
        if err.trim_end().lines().count() != 1 {
            wrong.push(format!(
                "{} lines on stderr",
                err.trim_end().lines().count()
            ));
        }
        for w in &c.words {
            let w = match &file {
                Some(f) => w.replace("{file}", f.file_name().unwrap().to_str().unwrap()),
                None => w.clone(),
            };
            if !err.contains(&w) {
                wrong.push(format!("no {w:?}"));
            }
        }
        if !o.stdout.is_empty() {
            wrong.push("printed on stdout".into());
        }
        if out.exists() && fs::read_dir(&out).map_or(true, |mut d| d.next().is_some()) {
            wrong.push(format!("wrote into {}", out.display()));
        }
        if !wrong.is_empty() {
            bad.push(format!(
                "{}: {} [{}] stderr: {}",
                c.what,
                wrong.join(", "),
                args.join(" "),
                err.trim_end()
            ));
        }
    }
    bad
}

pub fn assert_none(bad: Vec<String>) {
    assert!(
        bad.is_empty(),
        "{} cases misbehaved:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

pub fn freeth() -> String {
    fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../crates/train/data/freeth2006.ron"),
    )
    .unwrap()
}

/// The default gearing with `from` (which must occur) replaced by `to`.
pub fn gearing(from: &str, to: &str) -> File {
    let text = freeth();
    assert!(text.contains(from), "{from}");
    Some(("gearing.ron", text.replacen(from, to, 1).into_bytes()))
}
