//! `run <id> --shard K/N` and `merge` on the command line: a sharded, merged run writes exactly
//! what a single run writes, and a merge refuses partial files that do not fit, writing nothing.
//! Everything runs reduced experiments (a fraction of a second each).

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;
use std::path::Path;

mod support;
use support::{Scratch, files, sealed, stderr, stdout, xtask};

/// A reduced table1: 5 trials of short runs with few samples.
fn table1() -> Vec<&'static str> {
    let mut args = vec!["table1", "--set", "trials=5"];
    args.extend(support::TABLE1_SHORT);
    args
}

/// A reduced failure study: Case D (jams early) and Case C, 5 runs each.
const FAILURE: &[&str] = &["failure", "--set", "cases=D,C", "--set", "trials=5"];

/// `run <experiment...> <extra...>`, which must succeed; returns its stdout.
/// `xtask run experiment extra`, which must succeed: its stdout.
fn run_ok(experiment: &[&str], extra: &[&str]) -> Vec<u8> {
    let o = support::run_args(experiment, extra);
    assert!(
        o.status.success(),
        "{experiment:?} {extra:?}: {}",
        stderr(&o)
    );
    o.stdout
}

/// `merge <inputs...> --out <out>`, which must succeed; returns its stdout.
fn merge(inputs: &[String], out: &str) -> Vec<u8> {
    let mut args = vec!["merge"];
    args.extend(inputs.iter().map(String::as_str));
    args.extend(["--out", out]);
    let o = xtask(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o.stdout
}

/// Every file of a results directory, by name.
fn assert_same_results(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    assert_eq!(
        fa.keys().collect::<Vec<_>>(),
        fb.keys().collect::<Vec<_>>(),
        "{} and {} hold different files",
        a.display(),
        b.display()
    );
    for (name, bytes) in &fa {
        assert!(
            bytes == &fb[name],
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
    assert!(fa.contains_key("table.md") && fa.keys().any(|n| n.ends_with(".csv")));
}

/// A single run, then N = 2 shards in their own directories and N = 3 shards sharing one
/// directory, each merged: the same bytes everywhere.
fn shards_merge_to_the_single_run(experiment: &[&str]) {
    let id = experiment[0];
    let s = Scratch::new(id);
    let printed = run_ok(experiment, &["--out", &s.path("single")]);

    for k in 0..2 {
        run_ok(
            experiment,
            &[
                "--shard",
                &format!("{k}/2"),
                "--out",
                &s.path(&format!("two/{k}")),
            ],
        );
    }
    assert!(
        !s.0.join(format!("two/0/{id}/table.md")).exists(),
        "a shard writes no tables"
    );
    let merged = merge(&[s.path("two/0"), s.path("two/1")], &s.path("merged2"));
    assert_eq!(printed, merged, "merge prints what run prints");
    assert_same_results(&s.0.join("single").join(id), &s.0.join("merged2").join(id));

    for k in [2, 0, 1] {
        run_ok(
            experiment,
            &["--shard", &format!("{k}/3"), "--out", &s.path("three")],
        );
    }
    let mut names: Vec<String> = fs::read_dir(s.0.join("three").join(id))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "partial-0-of-3.json",
            "partial-1-of-3.json",
            "partial-2-of-3.json"
        ]
    );
    let merged = merge(&[s.path("three")], &s.path("merged3"));
    assert_eq!(printed, merged);
    assert_same_results(&s.0.join("single").join(id), &s.0.join("merged3").join(id));
}

#[test]
fn table1_shards_merge_to_the_single_run_byte_for_byte() {
    shards_merge_to_the_single_run(&table1());
}

#[test]
fn failure_shards_merge_to_the_single_run_byte_for_byte() {
    // Its trial values are floats (days), so this also checks they survive the partial files.
    shards_merge_to_the_single_run(FAILURE);
}

#[test]
fn table3_shards_merge_to_the_single_run_byte_for_byte() {
    shards_merge_to_the_single_run(&["table3", "--set", "trials=3"]);
}

#[test]
fn table5_shards_merge_to_the_single_run_byte_for_byte() {
    // Its rows are derived from Table 4's cells, which every shard computes whole; its own
    // systematic cells are split between the shards.
    shards_merge_to_the_single_run(&[
        "table5",
        "--set",
        "trials=4",
        "--set",
        "random_from=0.05",
        "--set",
        "random_to=0.065",
        "--set",
        "systematic_to=0.4",
    ]);
}

#[test]
fn one_and_two_threads_write_the_same_results() {
    let s = Scratch::new("threads");
    let one = run_ok(&table1(), &["--threads", "1", "--out", &s.path("one")]);
    let two = run_ok(&table1(), &["--threads", "2", "--out", &s.path("two")]);
    assert_eq!(one, two);
    assert_same_results(&s.0.join("one/table1"), &s.0.join("two/table1"));
    // A merge with one thread of shards run with two.
    for k in 0..2 {
        run_ok(
            &table1(),
            &[
                "--threads",
                "2",
                "--shard",
                &format!("{k}/2"),
                "--out",
                &s.path("shards"),
            ],
        );
    }
    let o = xtask(&[
        "merge",
        &s.path("shards"),
        "--threads",
        "1",
        "--out",
        &s.path("merged"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_same_results(&s.0.join("one/table1"), &s.0.join("merged/table1"));
}

/// Adds 1 to the first number found in `v` (depth first).
fn flip_first_number(v: &mut serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(n) => {
            let x = n.as_f64().unwrap() + 1.0;
            *v = serde_json::json!(x);
            true
        }
        serde_json::Value::Array(a) => a.iter_mut().any(flip_first_number),
        serde_json::Value::Object(o) => o.values_mut().any(flip_first_number),
        _ => false,
    }
}

/// `merge <inputs> --out <out>` must exit 2 naming every word of `words`, print nothing and
/// write nothing.
fn refused(s: &Scratch, inputs: &[String], words: &[&str]) {
    let out = s.0.join("never");
    let mut args = vec!["merge"];
    args.extend(inputs.iter().map(String::as_str));
    args.extend(["--out", out.to_str().unwrap()]);
    let o = xtask(&args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    let err = stderr(&o);
    for w in words {
        assert!(err.contains(w), "{args:?}: missing {w:?} in: {err}");
    }
    assert_eq!(err.lines().count(), 1, "one line: {err}");
    assert!(o.stdout.is_empty(), "{args:?} printed tables");
    assert!(!out.exists(), "{args:?} wrote results");
}

#[test]
fn merge_refuses_partial_files_that_do_not_fit() {
    let s = Scratch::new("refuse");
    for k in 0..3 {
        run_ok(
            &table1(),
            &[
                "--shard",
                &format!("{k}/3"),
                "--out",
                &s.path(&format!("ok/{k}")),
            ],
        );
    }
    let ok = |k: u64| s.path(&format!("ok/{k}"));
    let file = |dir: &str, k: u64, n: u64| format!("{dir}/table1/partial-{k}-of-{n}.json");
    let shard1 = file(&ok(1), 1, 3);

    // A shard missing.
    refused(
        &s,
        &[ok(0), ok(2)],
        &["shard 1/3", "missing", "exactly once"],
    );
    // A shard given twice (a copy elsewhere).
    fs::create_dir_all(s.0.join("dup")).unwrap();
    fs::copy(&shard1, s.0.join("dup/partial-1-of-3.json")).unwrap();
    refused(
        &s,
        &[ok(0), ok(1), ok(2), s.path("dup")],
        &[
            "partial-1-of-3.json",
            "shard 1/3",
            "given twice",
            "exactly once",
        ],
    );
    // Shards of different seeds.
    run_ok(
        &table1(),
        &["--seed", "9", "--shard", "1/3", "--out", &s.path("seed9")],
    );
    refused(
        &s,
        &[ok(0), s.path("seed9"), ok(2)],
        &[&file(&s.path("seed9"), 1, 3), "seed", "is 9", "2025"],
    );
    // Shards of different parameters.
    let mut more: Vec<&str> = table1();
    more[2] = "trials=6";
    run_ok(&more, &["--shard", "1/3", "--out", &s.path("trials6")]);
    refused(
        &s,
        &[ok(0), s.path("trials6"), ok(2)],
        &["--set", "trials=6", "trials=5"],
    );
    // Shards of different experiments.
    run_ok(
        &["failure", "--set", "cases=D", "--set", "trials=2"],
        &["--shard", "1/3", "--out", &s.path("failure")],
    );
    refused(
        &s,
        &[ok(0), s.path("failure"), ok(2)],
        &[
            "failure/partial-1-of-3.json",
            "experiment",
            "`failure`",
            "`table1`",
        ],
    );
    // Different numbers of shards.
    run_ok(&table1(), &["--shard", "1/2", "--out", &s.path("of2")]);
    refused(
        &s,
        &[ok(0), s.path("of2"), ok(2)],
        &["partial-1-of-2.json", "N (number of shards)"],
    );
    // A corrupt (truncated) partial file.
    let text = fs::read_to_string(&shard1).unwrap();
    fs::create_dir_all(s.0.join("cut")).unwrap();
    let cut = s.path("cut/partial-1-of-3.json");
    fs::write(&cut, &text[..text.len() / 2]).unwrap();
    refused(
        &s,
        &[ok(0), cut.clone(), ok(2)],
        &[&cut, "contents", "not a partial file"],
    );
    // A partial file whose records lack a trial.
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let batch = json["batches"]
        .as_object_mut()
        .unwrap()
        .values_mut()
        .next()
        .unwrap();
    batch["values"].as_object_mut().unwrap().remove("1");
    let holed = s.path("cut/holed.json");
    // Sealed again, as a shard that recorded too little would have sealed it.
    fs::write(&holed, sealed(json)).unwrap();
    refused(
        &s,
        &[ok(0), holed.clone(), ok(2)],
        &[&holed, "trial 1", "missing"],
    );
    // One value changed after the shard wrote the file: the checksum no longer matches.
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let value = json["batches"]
        .as_object_mut()
        .unwrap()
        .values_mut()
        .next()
        .unwrap()["values"]
        .as_object_mut()
        .unwrap()
        .values_mut()
        .next()
        .unwrap();
    let before = value.to_string();
    flip_first_number(value);
    assert_ne!(value.to_string(), before, "a value was changed");
    let flipped = s.path("cut/flipped.json");
    fs::write(&flipped, json.to_string()).unwrap();
    refused(
        &s,
        &[ok(0), flipped.clone(), ok(2)],
        &[&flipped, "checksum", "does not match"],
    );
    // A file named for one shard holding another.
    let renamed = s.path("cut/partial-2-of-3.json");
    fs::write(&renamed, &text).unwrap();
    refused(
        &s,
        std::slice::from_ref(&renamed),
        &[&renamed, "file name says shard 2/3"],
    );
    // Nothing to merge.
    fs::create_dir_all(s.0.join("empty")).unwrap();
    refused(&s, &[s.path("empty")], &["no partial files"]);
    refused(
        &s,
        &[s.path("no-such-dir")],
        &["no-such-dir", "cannot read"],
    );
}

#[test]
fn bad_shard_flags_exit_2_and_write_nothing() {
    let s = Scratch::new("flags");
    let out = s.path("out");
    for (args, usage) in [
        (
            &["run", "table1", "--shard", "3/3", "--out", &out][..],
            false,
        ),
        (&["run", "table1", "--shard", "0/0", "--out", &out], false),
        (&["run", "table1", "--shard", "1", "--out", &out], false),
        (&["run", "table1", "--shard", "a/b", "--out", &out], false),
        (&["run", "all", "--shard", "0/2", "--out", &out], true),
        (
            &["run", "table1", "fig2", "--shard", "0/2", "--out", &out],
            true,
        ),
        (
            &[
                "run",
                "table1",
                "--shard",
                "0/2",
                "--set",
                "nonsense=1",
                "--out",
                &out,
            ],
            false,
        ),
        (&["merge"], true),
        (&["merge", &out, "--seed", "1"], true),
    ] {
        support::refused_in_one_line(args, usage);
        assert!(!Path::new(&out).exists(), "{args:?} wrote something");
    }
    let o = xtask(&["run", "table1", "--shard", "3/3"]);
    assert!(
        stderr(&o).contains("--shard: 3/3: K must be from 0 to N-1 = 2"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn usage_describes_shards_and_merge() {
    let o = xtask(&[]);
    assert!(o.status.success());
    let text = stdout(&o);
    for word in [
        "--shard K/N",
        "cargo xtask merge",
        "partial-K-of-N.json",
        "bit-identical",
    ] {
        assert!(text.contains(word), "missing {word:?} in:\n{text}");
    }
}

/// A partial file records the SHA-256 of the code that computed it: a partial file recorded
/// only the crate's version (0.1.0 for hundreds of commits), so shards of different code merged
/// as one. A shard of other code, or a mix, is refused naming `code`; so is a file of a build
/// that recorded no hash.
#[test]
fn a_shard_of_other_code_is_refused() {
    let s = Scratch::new("other-code");
    for k in 0..2 {
        run_ok(
            &table1(),
            &["--shard", &format!("{k}/2"), "--out", &s.path("sh")],
        );
    }
    let path = |k: u64| s.0.join(format!("sh/table1/partial-{k}-of-2.json"));
    let original: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(path(1)).unwrap()).unwrap();
    let code = original["code"].as_str().unwrap().to_owned();
    assert_eq!(code.len(), 64, "{code}");
    // As a build of other code would have written it, sealed as such a build seals it.
    let rewritten = |code: &str, dir: &str| {
        let mut other = original.clone();
        other["code"] = code.into();
        fs::create_dir_all(s.0.join(dir)).unwrap();
        let p = s.path(&format!("{dir}/partial-1-of-2.json"));
        fs::write(&p, sealed(other)).unwrap();
        p
    };
    let other = "0".repeat(64);
    let mixed = rewritten(&other, "other");
    refused(
        &s,
        &[path(0).to_str().unwrap().to_owned(), mixed.clone()],
        &[
            mixed.as_str(),
            "code",
            "SHA-256 000000000000",
            "same `cargo xtask run <id> --shard K/N` command",
        ],
    );
    // Every shard of the other code: refused as not this build's.
    let mut zero: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(path(0)).unwrap()).unwrap();
    zero["code"] = other.clone().into();
    fs::write(s.0.join("other/partial-0-of-2.json"), sealed(zero)).unwrap();
    refused(
        &s,
        &[s.path("other")],
        &[
            "code",
            "computed by code of SHA-256 000000000000",
            "merge with the build that ran the shards",
        ],
    );
    // A file of a build that recorded no hash.
    let none = rewritten("", "none");
    refused(&s, &[path(0).to_str().unwrap().to_owned(), none], &["code"]);
}

/// The files a shard read are recorded with their SHA-256: a merge after the gearing changed
/// said "shards do not cover this batch", and one from another folder with a relative gearing
/// path "No such file", naming neither the gearing nor the folder. Both are now named.
#[test]
fn a_merge_names_the_gearing_that_changed_and_the_folder_the_shards_ran_in() {
    let s = Scratch::new("merge-inputs");
    let work = s.0.join("work");
    fs::create_dir_all(&work).unwrap();
    let gearing = work.join("my-gearing.ron");
    fs::write(&gearing, support::hostile::freeth()).unwrap();
    let sh = s.path("sh");
    for k in 0..2 {
        let mut args: Vec<&str> = vec!["run"];
        args.extend(table1());
        let shard = format!("{k}/2");
        args.extend([
            "--gearing",
            "my-gearing.ron",
            "--shard",
            &shard,
            "-q",
            "--out",
            &sh,
        ]);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
            .args(&args)
            .current_dir(&work)
            .env_remove("RUST_LOG")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    // From another folder: the relative path names nothing there.
    let o = xtask(&["merge", &sh, "--out", &s.path("never")]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("merge: gearing `my-gearing.ron`")
            && err.contains(&format!("the shards ran in {}", work.display()))
            && err.contains("run the merge from"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(!s.0.join("never").exists());
    // From their folder it merges; after the gearing changed it is refused.
    let merge_in_work = |out: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
            .args(["merge", &sh, "-q", "--out", out])
            .current_dir(&work)
            .env_remove("RUST_LOG")
            .output()
            .unwrap()
    };
    let o = merge_in_work(&s.path("merged"));
    assert!(o.status.success(), "{}", stderr(&o));
    let mut text = fs::read_to_string(&gearing).unwrap();
    text.push_str("// edited after the shards ran\n");
    fs::write(&gearing, text).unwrap();
    let o = merge_in_work(&s.path("never"));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("merge: gearing `my-gearing.ron`: has changed since the shards read it"),
        "{err}"
    );
    assert!(!s.0.join("never").exists());
}

/// Shards 0/2 and 1/2 in a folder, then `run table1 --shard 0/2 --seed 5` (or `--set
/// trials=6`) into it: the other run's partial file was replaced without a word, and the run
/// said "join the 2 shards". A shard refuses a folder holding another sharded run's partial
/// files, before computing, naming the file and what differs; the same command again is fine.
/// New instances: another N (`--shard 0/3`), and a partial file that cannot be read.
#[test]
fn a_shard_never_replaces_another_runs_partial_file() {
    let s = Scratch::new("other-run");
    let out = s.path("out");
    let shard = |k: &str, extra: &[&str]| {
        let mut args = vec!["table1", "-q", "--shard", k, "--out", &out];
        args.extend(support::TABLE1_TINY);
        args.extend(extra);
        support::run_args(&args, &[])
    };
    for k in ["0/2", "1/2"] {
        let o = shard(k, &[]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let dir = s.0.join("out/table1");
    let before: Vec<Vec<u8>> = (0..2)
        .map(|k| fs::read(dir.join(format!("partial-{k}-of-2.json"))).unwrap())
        .collect();
    for (k, extra, words) in [
        (
            "0/2",
            &["--seed", "5"][..],
            &["its seed is 2025, this run's 5"][..],
        ),
        (
            "0/2",
            &["--set", "clearance=30"],
            &["its --set is", "clearance=30"],
        ),
        ("1/2", &["--set", "tooth_height=1"], &["tooth_height=1"]),
        ("0/3", &[], &["its N (number of shards) is 2, this run's 3"]),
    ] {
        let o = shard(k, extra);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{k} {extra:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.starts_with("--out: ")
                && err.contains("table1/partial-0-of-2.json: is a shard of another sharded run")
                && err.contains("cargo xtask merge"),
            "{err}"
        );
        for w in words {
            assert!(err.contains(w), "{k} {extra:?}: missing {w:?}: {err}");
        }
    }
    for (k, was) in before.iter().enumerate() {
        assert_eq!(
            &fs::read(dir.join(format!("partial-{k}-of-2.json"))).unwrap(),
            was,
            "partial file {k} changed"
        );
    }
    // The same command again: its own shard is replaced by the same.
    let o = shard("1/2", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A partial file that cannot be read as one.
    fs::write(dir.join("partial-1-of-2.json"), "{\"format\":").unwrap();
    let o = shard("0/2", &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("partial-1-of-2.json: cannot be read as a partial file"),
        "{err}"
    );
}
