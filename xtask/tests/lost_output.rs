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
    fs::write(old.join("tables.json"), "{}").unwrap();
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

/// The run lock of `<out>/<name>` taken by this test, as another run (here or on another
/// machine of a shared file system) would hold it.
fn hold_lock(out: &std::path::Path, name: &str) -> fs::File {
    fs::create_dir_all(out).unwrap();
    let f = fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(out.join(format!(".{name}.lock")))
        .unwrap();
    f.try_lock().unwrap();
    use std::io::Write;
    (&f).write_all(b"a run writing pair, process 1 on another-node")
        .unwrap();
    f
}

/// Two runs of one experiment into one `--out` at once: both exited 0 and printed where their
/// results were, and the later replaced the other's without a word. Now the second is refused
/// with exit 2 before it computes, naming the run that holds the results, and the first's
/// results are whole.
#[test]
fn two_runs_into_one_out_at_once_lose_nothing() {
    let s = Scratch::new("two-runs");
    let out = s.0.join("out");
    // The first: a pair run with 180 000 rows, long enough to be under way when the second starts.
    let example = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../experiments/data/pair-example.ron"
    ))
    .unwrap();
    let config = s.0.join("pair.ron");
    fs::write(
        &config,
        example.replacen("sample_deg:", "sample_deg: 0.005, // was", 1),
    )
    .unwrap();
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(["run", "pair", "-q", "--seed", "1", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&out)
        .env_remove("RUST_LOG")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while !out.join(".pair.lock").exists() {
        assert!(
            first.try_wait().unwrap().is_none(),
            "the first run ended before it was seen holding its lock"
        );
        assert!(started.elapsed().as_secs() < 60, "no lock file appeared");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let second = xtask(&[
        "run",
        "pair",
        "--seed",
        "2",
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let still_running = first.try_wait().unwrap().is_none();
    let err = stderr(&second);
    let done = first.wait_with_output().unwrap();
    assert!(done.status.success(), "{}", stderr(&done));
    if still_running {
        assert_eq!(second.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.contains("pair: another run is writing there now")
                && err.contains("a run writing pair")
                && err.contains("give another --out"),
            "{err}"
        );
        assert!(second.stdout.is_empty(), "the second run printed results");
    }
    let run: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("pair/run.json")).unwrap()).unwrap();
    assert_eq!(
        run["seed"],
        if still_running { 1 } else { 2 },
        "the results are not the run's that said it wrote them"
    );
    assert!(hidden_in(&out).is_empty(), "{:?}", hidden_in(&out));
}

/// A lock held elsewhere (another machine's run on a shared file system, whose process id means
/// nothing here) keeps its run's temporary folder from the clean-up and refuses a second run of
/// its experiment; once the lock is free the folder is a dead run's and is removed.
#[test]
fn a_live_runs_leftovers_are_kept_whatever_its_process_id() {
    let s = Scratch::new("live-elsewhere");
    let out = s.0.join("out");
    let dead = dead_pid();
    let writing = out.join(format!(".pair.tmp-{dead}-0-17"));
    fs::create_dir_all(&writing).unwrap();
    fs::write(writing.join("pair.csv"), "being written").unwrap();
    let lock = hold_lock(&out, "pair");
    // Another experiment into the same --out: its clean-up must keep the live run's folder.
    let o = xtask(&["run", "fig3", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        writing.exists(),
        "a live run's temporary folder was removed"
    );
    // The same experiment: refused, naming the holder.
    let o = xtask(&["run", "pair", "--out", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("another-node"), "{err}");
    drop(lock);
    // Free: the folder is a dead run's, removed by the next run; the stale lock file too.
    let o = xtask(&["run", "fig3", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!writing.exists(), "a dead run's temporary folder was kept");
    assert!(hidden_in(&out).is_empty(), "{:?}", hidden_in(&out));
}

/// Shards of table1 written into X, then a plain `run table1 --out X`: the plain run replaced
/// X/table1 whole and the partial files were gone. It is refused, and the merge still works.
#[test]
fn a_plain_run_never_deletes_the_partial_files_of_a_sharded_run() {
    let s = Scratch::new("plain-after-shards");
    let x = s.path("x");
    for k in 0..2 {
        let shard = format!("{k}/2");
        let mut args = vec!["run", "table1", "-q", "--shard", &shard, "--out", &x];
        args.extend(support::TABLE1_TINY);
        let o = xtask(&args);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    for run in [&["run", "table1"][..], &["run", "all"]] {
        let mut args = run.to_vec();
        args.extend(["--out", &x]);
        if run.len() == 2 && run[1] == "table1" {
            args.extend(support::TABLE1_TINY);
        }
        let o = xtask(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.contains("table1 holds the partial files partial-0-of-2.json, partial-1-of-2.json")
                && err.contains("cargo xtask merge"),
            "{err}"
        );
        assert!(o.stdout.is_empty(), "{args:?} computed");
    }
    let o = xtask(&["merge", &x, "-q", "--out", &s.path("merged")]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// `run fig3 --out D > /dev/full`: the print fails (exit 1), and the results are written anyway.
#[test]
fn results_are_written_when_stdout_cannot_take_them() {
    let Ok(full) = fs::OpenOptions::new().write(true).open("/dev/full") else {
        eprintln!("skipped: no /dev/full");
        return;
    };
    let s = Scratch::new("dev-full");
    for id in ["fig3", "fig2"] {
        let out = s.0.join(id);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
            .args(["run", id, "--out"])
            .arg(&out)
            .env_remove("RUST_LOG")
            .stdout(full.try_clone().unwrap())
            .output()
            .unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains("cannot write to stdout"), "{err}");
        assert!(
            out.join(id).join("tables.json").is_file(),
            "{id}: the results were lost with the print: {err}"
        );
        assert!(err.contains("results: "), "{err}");
    }
}

/// The names of the entries of the gzipped tar archive `file`.
fn archive_names(file: &std::path::Path) -> Vec<String> {
    let o = std::process::Command::new("tar")
        .arg("tzf")
        .arg(file)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    support::stdout(&o).lines().map(str::to_owned).collect()
}

/// Runs `report` with `args` and asserts it is refused at once (exit 2, one line holding each of
/// `words`) and wrote no page.
fn report_refused(out: &std::path::Path, args: &[&str], words: &[&str]) {
    let _ = fs::remove_file(out.join("index.html"));
    let mut all = vec!["report", "--out", out.to_str().unwrap()];
    all.extend(args);
    let start = Instant::now();
    let o = xtask(&all);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{all:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{all:?}: missing {w:?}: {err}");
    }
    assert!(
        !out.join("index.html").exists(),
        "{all:?}: the page was written before the refusal"
    );
    assert!(
        start.elapsed().as_secs() < 20,
        "{all:?}: took {:?}",
        start.elapsed()
    );
}

/// `report --bundle B/fig3/x.tar.gz` archived its own growing temporary file for ever (1.9 GB
/// in a minute), and bundles then archived the leftovers of killed ones. A bundle inside a
/// folder it archives is refused before anything is written, and a bundle holds no hidden
/// temporary file of a run or a bundle under way.
#[test]
fn a_bundle_never_archives_itself_or_a_temporary_file() {
    let s = Scratch::new("bundle-itself");
    let out = s.0.join("B");
    let o = xtask(&["run", "fig3", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let inside = out.join("fig3/x.tar.gz");
    report_refused(
        &out,
        &["--bundle", inside.to_str().unwrap()],
        &["--bundle: ", "inside", "it would archive itself"],
    );
    assert!(!inside.exists());
    // Through another name for the same folder: still inside.
    std::os::unix::fs::symlink(out.join("fig3"), s.0.join("alias")).unwrap();
    let aliased = s.0.join("alias/x.tar.gz");
    report_refused(
        &out,
        &["--bundle", aliased.to_str().unwrap()],
        &["it would archive itself"],
    );
    // A killed bundle's leftover and a run's temporary folder in the results: not archived.
    let dead = dead_pid();
    fs::write(
        out.join(format!("fig3/.x.tar.gz.tmp-{dead}")),
        vec![0u8; 4096],
    )
    .unwrap();
    fs::create_dir_all(out.join(format!("fig3/.fig3.tmp-{dead}-0-1"))).unwrap();
    let bundle = s.0.join("b.tar.gz");
    let o = xtask(&[
        "report",
        "-q",
        "--out",
        out.to_str().unwrap(),
        "--bundle",
        bundle.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let names = archive_names(&bundle);
    assert!(
        names.iter().any(|n| n == "results/fig3/tables.json"),
        "{names:?}"
    );
    assert!(
        !names
            .iter()
            .any(|n| n.split('/').any(|part| part.starts_with('.'))),
        "hidden files archived: {names:?}"
    );
}

/// `--bundle` onto an existing file replaced it without a word: a results file, a device node
/// (`/dev/null` as root), a folder or a missing folder failed only after the page was written.
/// What a command writes replaces only a file of its own kind, and everything is checked before
/// anything is written. New instances: a link in a results folder to `/dev/zero` (which the
/// archive would read for ever), a user's folder named as an experiment (which a run would
/// delete), a user's file named as the page or the summary.
#[test]
fn a_write_never_replaces_what_it_did_not_write() {
    let s = Scratch::new("not-mine");
    let out = s.0.join("B");
    let o = xtask(&["run", "fig3", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = out.join("fig3/table.md");
    let before = fs::read(&table).unwrap();
    let notes = s.0.join("notes.txt");
    fs::write(&notes, "my notes").unwrap();
    fs::create_dir_all(s.0.join("adir")).unwrap();
    for (target, words) in [
        (table.clone(), &["not a bundle the toolkit wrote"][..]),
        (notes.clone(), &["not a bundle the toolkit wrote"]),
        (s.0.join("adir"), &["is a directory"]),
        (s.0.join("nodir/x.tgz"), &["nodir", "No such file"]),
    ] {
        report_refused(&out, &["--bundle", target.to_str().unwrap()], words);
    }
    assert_eq!(fs::read(&table).unwrap(), before);
    assert_eq!(fs::read_to_string(&notes).unwrap(), "my notes");
    let node = s.0.join("node");
    let made = std::process::Command::new("mknod")
        .arg(&node)
        .args(["c", "1", "7"])
        .status()
        .is_ok_and(|st| st.success());
    if made {
        report_refused(
            &out,
            &["--bundle", node.to_str().unwrap()],
            &["is a device"],
        );
        use std::os::unix::fs::FileTypeExt;
        assert!(
            fs::symlink_metadata(&node)
                .unwrap()
                .file_type()
                .is_char_device()
        );
    } else {
        eprintln!("mknod not permitted here: the device case is skipped");
    }
    // A bundle replaces an earlier bundle.
    let bundle = s.0.join("b.tgz");
    for _ in 0..2 {
        let o = xtask(&[
            "report",
            "-q",
            "--out",
            out.to_str().unwrap(),
            "--bundle",
            bundle.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    // A link to /dev/zero in a results folder: refused at once, not read for ever.
    std::os::unix::fs::symlink("/dev/zero", out.join("fig3/zero.csv")).unwrap();
    report_refused(
        &out,
        &["--bundle", bundle.to_str().unwrap()],
        &["zero.csv is not a file or a folder"],
    );
    fs::remove_file(out.join("fig3/zero.csv")).unwrap();
    // A user's file where the page goes.
    fs::write(out.join("index.html"), "my page").unwrap();
    let o = xtask(&["report", "--out", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("index.html: exists and is not the report page"),
        "{err}"
    );
    assert_eq!(
        fs::read_to_string(out.join("index.html")).unwrap(),
        "my page"
    );
    fs::remove_file(out.join("index.html")).unwrap();
    // A user's folder named as an experiment, and a user's file named as the summary.
    fs::create_dir_all(out.join("pair")).unwrap();
    fs::write(out.join("pair/my-pair.ron"), "(mine)").unwrap();
    refused_before_computing(
        &["run", "pair", "--out", out.to_str().unwrap()],
        &["pair: holds files that are not results"],
    );
    assert!(out.join("pair/my-pair.ron").exists());
    fs::remove_dir_all(out.join("pair")).unwrap();
    fs::write(out.join("summary.md"), "my summary").unwrap();
    refused_before_computing(
        &["run", "all", "--out", out.to_str().unwrap()],
        &["summary.md: exists and is not the summary"],
    );
    assert_eq!(
        fs::read_to_string(out.join("summary.md")).unwrap(),
        "my summary"
    );
}

/// Five experiments started together into one `--out` failed in 4 of 10 tries ("cannot remove
/// the leftover .xtask-out-check.tmp-...": one run's clean-up removed another's check folder,
/// and two clean-ups raced over one leftover), and four shards into one empty folder lost one
/// in 2 of 6. Six different runs, a replay, the report and four shards of one command start
/// together into one folder, twenty times over: every command succeeds, every result is whole
/// (tables and provenance readable, the page lists every experiment run before the round as
/// run, the partial files merge), and nothing hidden is left. Tiny runs (some 1.5 s a round on
/// two cores, some 30 s in all).
#[test]
fn runs_sharing_a_folder_never_disturb_each_other() {
    let s = Scratch::new("sharing");
    let out = s.0.join("R");
    let o_ = out.to_str().unwrap();
    let runs = ["fig2", "fig3", "fig4", "fig5", "pair", "clearance"];
    // Something to report from the first round on.
    let o = xtask(&["run", "fig3", "-q", "--out", o_]);
    assert!(o.status.success(), "{}", stderr(&o));
    let start = Instant::now();
    for round in 0..20 {
        let mut commands: Vec<Vec<String>> = runs
            .iter()
            .map(|id| vec!["run".into(), (*id).into(), "-q".into()])
            .collect();
        commands.push(
            ["replay", "table3", "B/m3-e3", "0", "--trials", "2", "-q"]
                .map(String::from)
                .to_vec(),
        );
        commands.push(vec!["report".into(), "-q".into()]);
        for k in 0..4 {
            let mut c: Vec<String> = ["run", "table1", "-q", "--shard", &format!("{k}/4")]
                .map(String::from)
                .to_vec();
            c.extend(support::TABLE1_TINY.iter().map(|a| (*a).to_owned()));
            commands.push(c);
        }
        let children: Vec<(String, std::process::Child)> = commands
            .iter()
            .map(|c| {
                let child = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
                    .args(c)
                    .args(["--out", o_])
                    .env_remove("RUST_LOG")
                    .stdout(std::process::Stdio::null())
                    .stderr(std::process::Stdio::piped())
                    .spawn()
                    .unwrap();
                (c.join(" "), child)
            })
            .collect();
        for (what, child) in children {
            let o = child.wait_with_output().unwrap();
            assert!(o.status.success(), "round {round}: {what}: {}", stderr(&o));
        }
        for id in runs.iter().chain(["replay-table3-B-m3-e3-0"].iter()) {
            let dir = out.join(id);
            for file in ["tables.json", "run.json"] {
                let text = fs::read_to_string(dir.join(file))
                    .unwrap_or_else(|e| panic!("round {round}: {id}/{file}: {e}"));
                let _: serde_json::Value = serde_json::from_str(&text)
                    .unwrap_or_else(|e| panic!("round {round}: {id}/{file}: {e}"));
            }
        }
        let page = fs::read_to_string(out.join("index.html")).unwrap();
        assert!(
            page.trim_end().ends_with("</html>"),
            "round {round}: a cut page"
        );
        // From the second round on every experiment has results while the page is read.
        let shown_run = |id: &str| {
            page.contains(&format!(
                "<section id=\"exp-{id}\" class=\"experiment run\""
            ))
        };
        assert!(shown_run("fig3"), "round {round}: fig3 shown as not run");
        if round > 0 {
            for id in runs {
                assert!(shown_run(id), "round {round}: {id} shown as not run");
            }
        }
        for k in 0..4 {
            assert!(
                out.join(format!("table1/partial-{k}-of-4.json")).is_file(),
                "round {round}: shard {k} lost"
            );
        }
        assert!(
            hidden_in(&out).is_empty(),
            "round {round}: {:?}",
            hidden_in(&out)
        );
        assert!(
            hidden_in(&out.join("table1")).is_empty(),
            "round {round}: {:?}",
            hidden_in(&out.join("table1"))
        );
    }
    let o = xtask(&[
        "merge",
        &format!("{o_}/table1"),
        "-q",
        "--out",
        &s.path("merged"),
    ]);
    assert!(
        o.status.success(),
        "the shards' partial files: {}",
        stderr(&o)
    );
    eprintln!(
        "20 rounds of 12 commands sharing a folder: {:?}",
        start.elapsed()
    );
}

/// Two bundles into one file at once would have renamed one over the other without a word: the
/// bundle takes the run lock of its file as runs take theirs, and a second is refused before
/// the page is written, naming the holder.
#[test]
fn a_bundle_being_written_is_never_joined() {
    let s = Scratch::new("bundle-lock");
    let out = s.0.join("B");
    let o = xtask(&["run", "fig3", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let lock = hold_lock(&s.0, "b.tgz");
    let bundle = s.0.join("b.tgz");
    report_refused(
        &out,
        &["--bundle", bundle.to_str().unwrap()],
        &["another command is writing it now", "another-node"],
    );
    drop(lock);
    let o = xtask(&[
        "report",
        "-q",
        "--out",
        out.to_str().unwrap(),
        "--bundle",
        bundle.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(hidden_in(&s.0).is_empty(), "{:?}", hidden_in(&s.0));
}

/// Standard error on a full device (`2>/dev/full`, or a full file system): the run panicked
/// ("failed printing to stderr", exit 101) and left its `.fig2.lock` behind. A write to stderr
/// that fails ends the command with status 1 once its work is done (results written, nothing
/// left behind), never a panic. New instances: the debug logs of `-v`, the report's note, a
/// refusal's own line (its exit status stays 2), and stdout and stderr full at once.
#[test]
fn stderr_that_cannot_be_written_ends_in_status_1_without_a_panic_or_a_lock() {
    let Ok(full) = fs::OpenOptions::new().write(true).open("/dev/full") else {
        eprintln!("skipped: no /dev/full");
        return;
    };
    let s = Scratch::new("stderr-full");
    let out = s.0.join("F");
    let o_ = out.to_str().unwrap();
    let run = |args: &[&str], stdout_full: bool| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"));
        c.args(args)
            .env_remove("RUST_LOG")
            .stderr(full.try_clone().unwrap());
        if stdout_full {
            c.stdout(full.try_clone().unwrap());
        } else {
            c.stdout(std::process::Stdio::null());
        }
        c.status().unwrap().code()
    };
    for (args, stdout_full, status) in [
        (&["run", "fig2", "--out", o_][..], false, Some(1)),
        (&["run", "fig3", "-v", "--out", o_], false, Some(1)),
        (&["report", "--out", o_], false, Some(1)),
        (&["run", "fig3", "--out", o_], true, Some(1)),
        (&["run", "nosuch", "--out", o_], false, Some(2)),
    ] {
        assert_eq!(run(args, stdout_full), status, "{args:?}");
        assert!(
            hidden_in(&out).is_empty(),
            "{args:?}: left {:?}",
            hidden_in(&out)
        );
    }
    assert!(
        out.join("fig2/tables.json").is_file(),
        "the results were lost"
    );
    assert!(out.join("index.html").is_file(), "the page was lost");
}

/// A bundle killed while it was written left its `.x.tar.gz.tmp-PID` (1.7 GB) for later bundles
/// to archive. Its temporary file is removed by the stop, as a run's temporary folder is: the
/// bundle is frozen as soon as its temporary file appears, then sent SIGTERM.
#[test]
fn a_bundle_stopped_while_writing_leaves_no_temporary_file() {
    let s = Scratch::new("bundle-stopped");
    let out = s.0.join("B");
    // fig2 writes some 5 MB of figures and data: long enough to archive to be caught.
    let o = xtask(&["run", "fig2", "-q", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bundle = s.0.join("b.tgz");
    for _attempt in 0..10 {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
            .args(["report", "-q", "--out"])
            .arg(&out)
            .arg("--bundle")
            .arg(&bundle)
            .env_remove("RUST_LOG")
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let pid = child.id();
        let started = Instant::now();
        let mut frozen = false;
        while started.elapsed().as_secs() < 60 && child.try_wait().unwrap().is_none() {
            if hidden_in(&s.0).iter().any(|n| n.starts_with(".b.tgz.tmp-")) {
                signal(pid, "STOP");
                frozen = hidden_in(&s.0).iter().any(|n| n.starts_with(".b.tgz.tmp-"));
                if !frozen {
                    signal(pid, "CONT");
                }
                break;
            }
        }
        if !frozen {
            let _ = child.wait();
            let _ = fs::remove_file(&bundle);
            continue;
        }
        signal(pid, "TERM");
        signal(pid, "CONT");
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(143), "{}", stderr(&o));
        assert!(hidden_in(&s.0).is_empty(), "left {:?}", hidden_in(&s.0));
        return;
    }
    eprintln!("the bundle was never caught while being written: nothing checked");
}
