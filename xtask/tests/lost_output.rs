//! Results are never lost or left stale: what a killed run leaves behind is
//! cleaned up by the next run, results a kill left moved aside are put back, a merge never
//! replaces the folder holding the partial files it merges, and an `--out` that cannot be
//! written is refused before anything is computed.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;
use std::time::Instant;

mod support;
use support::{Scratch, stderr, xtask};

/// The id of a process that has ended.
fn dead_pid() -> u32 {
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let pid = child.id();
    child.wait().unwrap();
    pid
}

#[test]
fn a_killed_runs_leftovers_are_cleaned_and_its_moved_aside_results_put_back() {
    let s = Scratch::new("leftovers");
    let out = s.0.join("out");
    let dead = dead_pid();
    // `pair` killed while writing: a hidden temporary folder with a large file in it.
    let tmp = out.join(format!(".pair.tmp-{dead}-0-17"));
    fs::create_dir_all(&tmp).unwrap();
    fs::write(tmp.join("pair.csv"), vec![b'0'; 1 << 20]).unwrap();
    // `fig3` killed between the two renames: fig3 is gone, its results moved aside.
    let aside = out.join(format!(".fig3.old-{dead}-0-18"));
    fs::create_dir_all(&aside).unwrap();
    fs::write(aside.join("table.md"), "previous fig3 results").unwrap();
    // A shard killed while writing its partial file.
    fs::create_dir_all(out.join("table1")).unwrap();
    let partial_tmp = out.join(format!("table1/.partial-0-of-2.json.tmp-{dead}"));
    fs::write(&partial_tmp, "{").unwrap();

    let o = xtask(&["run", "pair", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        !tmp.exists(),
        "the killed run's temporary folder is still there"
    );
    assert!(!aside.exists(), "the moved-aside results were not put back");
    assert_eq!(
        fs::read_to_string(out.join("fig3/table.md")).unwrap(),
        "previous fig3 results"
    );
    assert!(out.join("pair/pair.csv").exists());

    let mut args = vec![
        "run",
        "table1",
        "--shard",
        "0/2",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(support::TABLE1_TINY);
    let o = xtask(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!partial_tmp.exists(), "the killed shard's temporary file");
    let hidden: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
}

#[test]
fn a_merge_never_replaces_the_folder_holding_its_partial_files() {
    let s = Scratch::new("merge-into-shards");
    let sh = s.path("sh");
    for k in 0..2 {
        let shard = format!("{k}/2");
        let mut args = vec!["run", "table1", "--shard", &shard, "--out", &sh];
        args.extend(support::TABLE1_TINY);
        let o = xtask(&args);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let o = xtask(&["merge", &sh, "--out", &sh]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--out: ") && err.contains("holds the partial file"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for k in 0..2 {
        assert!(
            s.0.join(format!("sh/table1/partial-{k}-of-2.json"))
                .exists(),
            "partial file {k} was lost"
        );
    }
    // Into another folder the merge goes through.
    let o = xtask(&["merge", &sh, "--out", &s.path("merged")]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn an_unwritable_out_is_refused_before_anything_is_computed() {
    let s = Scratch::new("unwritable");
    let file = s.0.join("plain");
    fs::write(&file, "x").unwrap();
    let below_a_file = file.join("out");
    for out in ["/proc/xtask-no-such/out", below_a_file.to_str().unwrap()] {
        for cmd in [
            vec!["run", "table1", "--trials", "200", "--out", out],
            vec!["run", "all", "--out", out],
        ] {
            let start = Instant::now();
            let o = xtask(&cmd);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{cmd:?}: {err}");
            assert!(
                err.starts_with(&format!("--out: {out}: ")),
                "{cmd:?}: {err}"
            );
            assert_eq!(err.trim_end().lines().count(), 1, "{cmd:?}: {err}");
            assert!(
                start.elapsed().as_secs() < 5,
                "{cmd:?}: refused only after {:?} of computing",
                start.elapsed()
            );
        }
    }
}

/// Runs `args` and asserts it is refused at once (exit 2) in one line starting `--out: ` and
/// holding each of `words`.
fn refused_before_computing(args: &[&str], words: &[&str]) {
    let start = Instant::now();
    let o = xtask(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.starts_with("--out: "), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: missing {w:?}: {err}");
    }
    assert!(
        start.elapsed().as_secs() < 5,
        "{args:?}: refused only after {:?} of computing",
        start.elapsed()
    );
}

#[test]
fn an_out_with_a_name_the_file_system_refuses_is_refused_before_computing() {
    let s = Scratch::new("long-name");
    let long = s.0.join("a".repeat(300)).join("out");
    let out = long.to_str().unwrap();
    refused_before_computing(
        &["run", "table1", "--trials", "200", "--out", out],
        &["cannot be created", "name too long"],
    );
    refused_before_computing(&["run", "all", "--out", out], &["cannot be created"]);
    assert_eq!(
        fs::read_dir(&s.0).unwrap().count(),
        0,
        "the check left something"
    );
}

#[test]
fn every_target_that_cannot_be_written_is_refused_before_computing() {
    let s = Scratch::new("targets");
    let out = s.path("out");
    // A file where an experiment's results folder goes.
    fs::create_dir_all(s.0.join("out")).unwrap();
    fs::write(s.0.join("out/fig2"), "not a folder").unwrap();
    refused_before_computing(
        &["run", "fig2", "--out", &out],
        &["fig2: exists and is not a directory"],
    );
    // The same under a shard's partial file.
    fs::write(s.0.join("out/table1"), "not a folder").unwrap();
    let mut shard = vec!["run", "table1", "--shard", "0/2", "--out", &out];
    shard.extend(support::TABLE1_TINY);
    refused_before_computing(&shard, &["table1: exists and is not a directory"]);
    // A folder where `run all` writes its summary.
    fs::remove_file(s.0.join("out/fig2")).unwrap();
    fs::remove_file(s.0.join("out/table1")).unwrap();
    fs::create_dir_all(s.0.join("out/summary.md")).unwrap();
    refused_before_computing(
        &["run", "all", "--out", &out],
        &["summary.md: exists and is a directory"],
    );
    // A folder where `report` writes its page.
    fs::create_dir_all(s.0.join("out/index.html")).unwrap();
    refused_before_computing(
        &["report", "--out", &out],
        &["index.html: exists and is a directory"],
    );
}

#[test]
fn previous_results_that_cannot_be_removed_are_refused_before_computing() {
    let s = Scratch::new("immutable");
    let out = s.path("out");
    let old = s.0.join("out/fig2");
    fs::create_dir_all(&old).unwrap();
    let file = old.join("table.md");
    fs::write(&file, "previous fig2 results").unwrap();
    // An immutable file: not even root can remove it (where chattr works here).
    let chattr = |flag: &str| {
        std::process::Command::new("chattr")
            .args([flag, file.to_str().unwrap()])
            .output()
            .is_ok_and(|o| o.status.success())
    };
    if !chattr("+i") {
        eprintln!("skipped: chattr +i is not available here");
        return;
    }
    let o = xtask(&["run", "fig2", "--out", &out]);
    chattr("-i");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("--out: ")
            && err.contains("fig2: the previous results cannot be replaced")
            && err.contains("table.md"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(o.stdout.is_empty(), "fig2 was computed: {err}");
    assert_eq!(fs::read_to_string(&file).unwrap(), "previous fig2 results");
    let hidden: Vec<_> = fs::read_dir(s.0.join("out"))
        .unwrap()
        .chain(fs::read_dir(&old).unwrap())
        .map(|e| e.unwrap().file_name())
        .filter(|n| n.to_string_lossy().starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
}

/// Sends `signal` (a name `kill` knows) to process `pid`.
fn signal(pid: u32, signal: &str) {
    let ok = std::process::Command::new("kill")
        .args([&format!("-{signal}"), &pid.to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{signal} {pid}");
}

/// The hidden entries (temporary or moved-aside results) of `dir`.
fn hidden_in(dir: &std::path::Path) -> Vec<String> {
    fs::read_dir(dir)
        .map(|entries| {
            entries
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .filter(|n| n.starts_with('.'))
                .collect()
        })
        .unwrap_or_default()
}

/// A run stopped by SIGTERM, SIGINT or SIGHUP while its results are being written removes its
/// temporary folder before it exits with 128 plus the signal's number (143, 130, 129, as a shell
/// reports it): nothing half-written is left for the next run. The run is frozen (SIGSTOP) as
/// soon as its temporary folder appears, so the signal lands mid-write.
#[test]
fn a_run_stopped_while_writing_leaves_no_partial_results() {
    let s = Scratch::new("stopped");
    // A pair run with 500 000 rows in pair.csv: its write takes long enough to be caught.
    let example = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../experiments/data/pair-example.ron"
    ))
    .unwrap();
    let config = s.0.join("pair.ron");
    assert!(
        example.contains("sample_deg:"),
        "pair-example.ron sets sample_deg"
    );
    let big = example.replacen("sample_deg:", "sample_deg: 0.002, // was", 1);
    fs::write(&config, big).unwrap();
    for (sig, status) in [("TERM", 143), ("INT", 130), ("HUP", 129)] {
        let out = s.0.join(format!("out-{sig}"));
        let mut caught = false;
        for _attempt in 0..5 {
            let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
                .args(["run", "pair", "--config", config.to_str().unwrap(), "--out"])
                .arg(&out)
                .env_remove("RUST_LOG")
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap();
            let pid = child.id();
            let started = Instant::now();
            let mut frozen = false;
            while started.elapsed().as_secs() < 120 && child.try_wait().unwrap().is_none() {
                if hidden_in(&out).iter().any(|n| n.starts_with(".pair.tmp-")) {
                    signal(pid, "STOP");
                    frozen = hidden_in(&out).iter().any(|n| n.starts_with(".pair.tmp-"));
                    if !frozen {
                        signal(pid, "CONT");
                    }
                    break;
                }
            }
            if !frozen {
                let _ = child.kill();
                let _ = child.wait();
                let _ = fs::remove_dir_all(&out);
                continue;
            }
            signal(pid, sig);
            signal(pid, "CONT");
            let o = child.wait_with_output().unwrap();
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(status), "SIG{sig}: {err}");
            assert!(err.contains("stopped by a signal"), "SIG{sig}: {err}");
            assert!(
                hidden_in(&out).is_empty(),
                "SIG{sig}: left {:?}",
                hidden_in(&out)
            );
            // Either the results were not written, or written whole.
            let dir = out.join("pair");
            assert!(
                !dir.exists() || dir.join("tables.json").is_file(),
                "SIG{sig}: partial results in {}",
                dir.display()
            );
            caught = true;
            break;
        }
        assert!(caught, "SIG{sig}: the write was never caught under way");
    }
}

/// Shards started together on the same new `--out` all pass its check: each probes it in a
/// folder of its own, so one's clean-up never removes what another relies on.
#[test]
fn shards_starting_together_on_a_new_out_all_pass_its_check() {
    let s = Scratch::new("together");
    let out = s.0.join("new/out");
    let children: Vec<std::process::Child> = (0..4)
        .map(|k| {
            std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
                .args(["run", "table1", "--shard", &format!("{k}/4"), "--out"])
                .arg(&out)
                .args(support::TABLE1_TINY)
                .env_remove("RUST_LOG")
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for c in children {
        let o = c.wait_with_output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert_eq!(fs::read_dir(out.join("table1")).unwrap().count(), 4);
    assert!(hidden_in(&s.0).is_empty() && hidden_in(&s.0.join("new")).is_empty());
}
