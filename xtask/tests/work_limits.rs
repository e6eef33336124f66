//! Every experiment with every count parameter at its documented maximum:
//! each run is either refused up front (exit 2, one line naming the parameter and the limit) or
//! runs with progress lines on stderr even though stderr is a file, and none asks for an
//! allocation beyond the address space it is given ([`ADDRESS_SPACE_KB`], `ulimit -v`): an
//! allocation failure would abort it (exit 134) within the time it is watched.
//!
//! Each run is watched for [`WATCH`] and then stopped; the runs go four at a time.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

mod support;
use support::Scratch;

/// The address space each run gets: 4 GiB.
const ADDRESS_SPACE_KB: u64 = 4 * 1024 * 1024;

/// How long each run is watched before it is stopped.
const WATCH: Duration = Duration::from_millis(1500);

/// The documented maximum of a count parameter: `trials` 10^6 (`registry::MAX_TRIALS`),
/// `teeth` 10^5 (`geometry::MAX_TEETH`), any other count 10^7 (`registry::MAX_COUNT`).
fn maximum(name: &str) -> u64 {
    match name {
        "trials" => registry::MAX_TRIALS,
        "teeth" => geometry::MAX_TEETH as u64,
        _ => registry::MAX_COUNT as u64,
    }
}

/// The parameters that count something and so size the work and its memory.
const COUNTS: &[&str] = &[
    "trials",
    "cell_trials",
    "coarse_trials",
    "refine_trials",
    "runs",
    "batch",
    "cap",
    "samples",
    "samples_per_engagement",
    "curve_samples",
    "pitches",
    "teeth",
];

/// Every (experiment, count parameter it declares).
fn count_parameters() -> Vec<(&'static str, &'static str)> {
    experiments::link();
    let mut out = Vec::new();
    for (id, e) in registry::experiments().unwrap() {
        for p in e.all_params() {
            if COUNTS.contains(&p.name) {
                out.push((id, p.name));
            }
        }
    }
    out
}

struct Watched {
    what: String,
    child: Child,
    stderr: std::path::PathBuf,
    started: Instant,
}

fn start(s: &Scratch, i: usize, id: &str, param: &str) -> Watched {
    let stderr = s.0.join(format!("stderr-{i}"));
    let out = s.0.join(format!("out-{i}"));
    let value = maximum(param);
    let cmd = format!(
        "ulimit -v {ADDRESS_SPACE_KB} && exec '{}' run {id} --set {param}={value} --threads 2 --out '{}'",
        env!("CARGO_BIN_EXE_xtask"),
        out.display()
    );
    let child = Command::new("sh")
        .args(["-c", &cmd])
        .env("XTASK_PROGRESS", "always")
        .env_remove("RUST_LOG")
        .stdout(Stdio::null())
        .stderr(fs::File::create(&stderr).unwrap())
        .spawn()
        .unwrap();
    Watched {
        what: format!("{id} --set {param}={value}"),
        child,
        stderr,
        started: Instant::now(),
    }
}

/// `None` if the run behaved, else what was wrong.
fn judge(mut w: Watched) -> Option<String> {
    let status = loop {
        if let Some(status) = w.child.try_wait().unwrap() {
            break Some(status);
        }
        if w.started.elapsed() >= WATCH {
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let err = || fs::read_to_string(&w.stderr).unwrap_or_default();
    match status {
        None => {
            let _ = w.child.kill();
            let _ = w.child.wait();
            let err = err();
            (!err.contains("progress: ")).then(|| {
                format!(
                    "{}: still running after {WATCH:?} and printed no progress line: {}",
                    w.what,
                    err.trim_end()
                )
            })
        }
        Some(s) if s.code() == Some(2) => {
            let err = err();
            (err.trim_end().lines().count() != 1).then(|| {
                format!(
                    "{}: refused, but not in one line: {}",
                    w.what,
                    err.trim_end()
                )
            })
        }
        Some(s) if s.success() => None,
        Some(s) => Some(format!(
            "{}: ended with {s} (an allocation failure or a crash): {}",
            w.what,
            err().trim_end()
        )),
    }
}

#[test]
fn every_count_at_its_maximum_is_refused_or_shows_progress_within_its_memory() {
    let s = Scratch::new("work-limits");
    let all = count_parameters();
    assert!(all.len() > 20, "{all:?}");
    let mut bad = Vec::new();
    for (chunk_index, chunk) in all.chunks(4).enumerate() {
        let running: Vec<Watched> = chunk
            .iter()
            .enumerate()
            .map(|(j, (id, p))| start(&s, chunk_index * 4 + j, id, p))
            .collect();
        bad.extend(running.into_iter().filter_map(judge));
    }
    assert!(
        bad.is_empty(),
        "{} of {} runs misbehaved:\n{}",
        bad.len(),
        all.len(),
        bad.join("\n")
    );
}

/// Runs `xtask run ARGS --out DIR` and returns its exit code and stderr, or fails the test if it
/// is still running after `limit`.
fn finishes_within(s: &Scratch, args: &[&str], limit: Duration) -> (Option<i32>, String) {
    let stderr = s.0.join("stderr-finishes");
    let mut child = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .arg("run")
        .args(args)
        .arg("--out")
        .arg(s.0.join("out"))
        .env_remove("RUST_LOG")
        .env_remove("XTASK_PROGRESS")
        .stdout(Stdio::null())
        .stderr(fs::File::create(&stderr).unwrap())
        .spawn()
        .unwrap();
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() >= limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "{args:?}: still running after {limit:?}: {}",
                fs::read_to_string(&stderr).unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    (
        status.code(),
        fs::read_to_string(&stderr).unwrap_or_default(),
    )
}

/// Inputs whose figure has no point to draw (every run jams, disengages or loses contact) or
/// points too large for their spread: the run draws an empty or widened axis and ends, where the
/// chart's tick search used to run forever.
#[test]
fn runs_whose_figure_has_nothing_to_draw_finish() {
    let s = Scratch::new("nothing-to-draw");
    // A 1000 mm gear among the mechanism's 10-60 mm ones: every run of its mesh is degenerate.
    let gearing = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../crates/train/data/freeth2006.ron"
    ))
    .unwrap();
    let large = gearing.replacen(
        "measured_radius: Some(15.30)",
        "measured_radius: Some(1000)",
        1,
    );
    assert_ne!(large, gearing, "b2's radius is in the embedded gearing");
    let file = s.path("large.ron");
    fs::write(&file, large).unwrap();
    let gearing = format!("gearing={file}");
    for args in [
        &["clearance", "--set", &gearing][..],
        // The largest tolerance: every position counts as free, so no curve has a point.
        &[
            "contact-tolerance",
            "--set",
            "tolerance=1",
            "--set",
            "samples=8",
        ],
    ] {
        let (code, err) = finishes_within(&s, args, Duration::from_secs(120));
        assert!(
            code == Some(0) || (code == Some(2) && err.trim_end().lines().count() == 1),
            "{args:?}: exit {code:?}: {err}"
        );
    }
}
