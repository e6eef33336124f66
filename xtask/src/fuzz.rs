//! `cargo xtask fuzz [--seconds N | --execs N] [--seed S] [--findings DIR]`: a stable-Rust stand-in for
//! cargo-fuzz (which needs nightly) on the RON loaders of [`crate::fuzz_targets`].
//!
//! Each target starts from its shipped file plus a few hand-written edge cases and mutates them:
//! truncation, bit flips, byte insertions and deletions, repeated and deleted lines, numbers
//! replaced by NaN, infinities, huge, tiny and negative values, strings swapped for other names,
//! field names misspelt, non-UTF-8 bytes, deep nesting, splices from other inputs. An input that
//! gives a new outcome (acceptance, or a refusal whose message is new once digits are ignored) is
//! kept in the corpus: a crude coverage signal without instrumentation. Every input is run under
//! `catch_unwind`; a panic, a broken promise (see `fuzz_targets`) or an input taking more than
//! two seconds is a finding, written to `--findings` (default `target/fuzz-findings`), and makes
//! the command exit 1. Deterministic for a given seed and number of executions.

use std::collections::BTreeSet;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use registry::Table;

use crate::args::{Budget, FuzzArgs};
use crate::failure::Failure;
use crate::fuzz_targets::{Outcome, TARGETS, Target};

/// Every target: the RON loaders of [`crate::fuzz_targets`] and the `--set` strings of
/// [`crate::fuzz_settings`].
fn targets() -> Vec<(&'static str, Target, &'static str)> {
    let mut all = TARGETS.to_vec();
    all.push((
        "settings",
        crate::fuzz_settings::settings,
        crate::fuzz_settings::seed(),
    ));
    all
}

/// Inputs kept per target, at most.
const CORPUS_CAP: usize = 4096;
/// An input slower than this is a finding.
const SLOW: Duration = Duration::from_secs(2);

/// `fuzz [--seconds N | --execs N] [--seed S] [--findings DIR]`.
pub fn command(opts: &FuzzArgs) -> Result<(), Failure> {
    // Where findings go is checked first: a run of minutes must not end unable to save them.
    crate::plan::writable_dir("--findings", &opts.findings)?;
    // So is the folder the loaders' file checks write their inputs to: without it they would
    // not run, and the fuzz would report nothing found.
    let scratch = scratch_file();
    std::fs::write(&scratch, b"")
        .and_then(|()| std::fs::remove_file(&scratch))
        .map_err(|e| {
            Failure::Bad(format!(
                "TMPDIR: {}: the fuzzer writes the files its loaders read there, and cannot ({e}): set TMPDIR to a folder that can be written",
                std::env::temp_dir().display()
            ))
        })?;
    let note = match opts.budget {
        Budget::Seconds(s) => format!(
            "fuzz: {s} s over {} targets, seed {}",
            targets().len(),
            opts.seed
        ),
        Budget::Execs(n) => format!(
            "fuzz: {n} executions per target ({} targets), seed {}",
            targets().len(),
            opts.seed
        ),
    };
    if !opts.quiet {
        crate::progress::say(&note);
    }
    let summary = run(opts.budget, opts.seed);
    crate::shared::print(&summary.table().render())?;
    if summary.findings.is_empty() {
        return Ok(());
    }
    std::fs::create_dir_all(&opts.findings).map_err(|e| {
        Failure::Internal(format!("cannot create {}: {e}", opts.findings.display()))
    })?;
    for (i, f) in summary.findings.iter().enumerate() {
        let path = opts
            .findings
            .join(format!("{}-{}-{i}.ron", f.target, f.kind));
        std::fs::write(&path, &f.input)
            .map_err(|e| Failure::Internal(format!("cannot write {}: {e}", path.display())))?;
        crate::progress::say(&format!(
            "fuzz: {} {}: {} ({})",
            f.target,
            f.kind,
            f.message,
            path.display()
        ));
    }
    Err(Failure::Internal(format!(
        "fuzz: {} finding(s); inputs in {}",
        summary.findings.len(),
        opts.findings.display()
    )))
}

/// Something the fuzzer found.
#[derive(Debug, Clone)]
pub struct Finding {
    /// The target's name.
    pub target: &'static str,
    /// `panic`, `broken-promise` or `slow`.
    pub kind: &'static str,
    /// The panic message, the broken promise, or the time taken.
    pub message: String,
    /// The input's bytes.
    pub input: Vec<u8>,
}

/// Counts for one target.
#[derive(Debug, Clone, Default)]
pub struct TargetStats {
    /// The target's name.
    pub name: &'static str,
    /// Inputs in the starting corpus.
    pub seeds: usize,
    /// Inputs run.
    pub execs: u64,
    /// Inputs accepted.
    pub accepted: u64,
    /// Inputs refused.
    pub refused: u64,
    /// Inputs that were not UTF-8 (run lossily converted, and through a file where the loader reads one).
    pub not_utf8: u64,
    /// Distinct outcomes seen (acceptance, refusal messages with digits ignored).
    pub outcomes: usize,
    /// Inputs in the corpus at the end.
    pub corpus: usize,
    /// Accepted inputs kept at the end (the shipped file included).
    pub valid: usize,
    /// Wall time spent, seconds.
    pub seconds: f64,
}

/// Result of a fuzzing run.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    /// Per target.
    pub targets: Vec<TargetStats>,
    /// Findings, each (target, kind, message) once.
    pub findings: Vec<Finding>,
}

impl Summary {
    /// The printed table.
    pub fn table(&self) -> Table {
        let mut t = Table::new(
            "cargo xtask fuzz: RON loaders under mutated inputs",
            [
                "target",
                "seed inputs",
                "executions",
                "exec/s",
                "accepted",
                "refused",
                "not UTF-8",
                "distinct outcomes",
                "corpus at end",
                "accepted kept",
                "findings",
            ],
        );
        for s in &self.targets {
            let findings = self.findings.iter().filter(|f| f.target == s.name).count();
            t.row(vec![
                s.name.into(),
                s.seeds.to_string(),
                s.execs.to_string(),
                registry::fmt_f64(s.execs as f64 / s.seconds.max(1e-9), 0),
                s.accepted.to_string(),
                s.refused.to_string(),
                s.not_utf8.to_string(),
                s.outcomes.to_string(),
                s.corpus.to_string(),
                s.valid.to_string(),
                findings.to_string(),
            ]);
        }
        t.note("Findings: panics, broken promises (see xtask/src/fuzz_targets.rs) and inputs slower than 2 s; each kind and message once.");
        t
    }
}

/// splitmix64: small, fast and good enough to choose mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n > 0`; 0 when `n == 0`).
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }

    fn chance(&mut self, one_in: u64) -> bool {
        self.next().is_multiple_of(one_in)
    }
}

/// Numbers that break naive arithmetic, as RON spells them.
const NUMBERS: &[&str] = &[
    "NaN",
    "inf",
    "-inf",
    "+inf",
    "1e308",
    "-1e308",
    "1e309",
    "1.7976931348623157e308",
    "5e-324",
    "1e-320",
    "-0.0",
    "0",
    "0.0",
    "-1",
    "1",
    "2",
    "3",
    "127",
    "128",
    "255",
    "256",
    "65535",
    "2147483647",
    "2147483648",
    "4294967295",
    "4294967296",
    "-2147483648",
    "9223372036854775807",
    "18446744073709551615",
    "18446744073709551616",
    "340282366920938463463374607431768211455",
    "0x7fffffff",
    "1_000",
    "1e",
    ".5",
    "5.",
];

/// Hand-written edge cases for every target.
const EDGE_CASES: &[&str] = &[
    "",
    "()",
    "[]",
    "(gears: [], arbors: [], meshes: [], pointers: [])",
    "(gears: [])",
    "(split: 0.5, gears: [])",
    "(split: NaN, gears: [(gear: \"b1\", random: inf, systematic: -0.0)])",
    "(gears: [(name: \"a\", teeth: 4294967295, measured_radius: Some(1e308), source: \"\")], arbors: [(name: \"x\", gears: [\"a\"])], meshes: [], pointers: [])",
    "(driver: (teeth: 3, tip_radius: 1e308, root_radius: 5e-324), driven: (teeth: 100000, tip_radius: 10.0, root_radius: 9.0), centre_distance: Some(1e308))",
    "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), clearance_percent: Some(99.999999), sample_deg: 1e-300, run_deg: Some(360000.0))",
    // Angles where a double loses them, and samples too few for a statistic.
    "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 24, tip_radius: 12.0, root_radius: 11.0), clearance_percent: Some(40.0), start_deg: 1e17, sample_deg: 360.0, run_deg: Some(1e-9))",
    "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 24, tip_radius: 12.0, root_radius: 11.0), clearance_percent: Some(40.0), start_deg: 999999.0, start: at_rest(theta_deg: -1e20), sample_deg: 4.5)",
];

/// Byte strings that are not UTF-8.
const NOT_UTF8: &[&[u8]] = &[
    b"\xff",
    b"\xc0\x80",
    b"\xed\xa0\x80",
    b"\xf8\x88\x80\x80\x80",
    b"\xe2\x82",
];

/// One mutation of `input`; `pool` supplies splices.
fn mutate(rng: &mut Rng, input: &mut Vec<u8>, pool: &[Vec<u8>]) {
    let len = input.len();
    match rng.below(16) {
        0 => input.truncate(rng.below(len + 1)),
        1 if len > 0 => {
            let i = rng.below(len);
            input[i] ^= 1 << rng.below(8);
        }
        2 if len > 0 => {
            let i = rng.below(len);
            input[i] = (rng.next() & 0xff) as u8;
        }
        3 => {
            let i = rng.below(len + 1);
            let n = 1 + rng.below(8);
            let bytes: Vec<u8> = (0..n)
                .map(|_| {
                    let printable = b" ()[]{}:,\"'\\.-+eE0123456789abczSomeNone/*\n";
                    printable[rng.below(printable.len())]
                })
                .collect();
            input.splice(i..i, bytes);
        }
        4 if len > 0 => {
            let i = rng.below(len);
            let j = (i + 1 + rng.below(64)).min(len);
            input.drain(i..j);
        }
        5 | 6 => replace_number(rng, input),
        7 => swap_string(rng, input),
        8 => misspell_field(rng, input),
        9 => {
            let bad = NOT_UTF8[rng.below(NOT_UTF8.len())];
            let i = rng.below(len + 1);
            input.splice(i..i, bad.iter().copied());
        }
        10 => {
            let depth = [8, 64, 127, 128, 129, 1000, 100_000][rng.below(7)];
            let open = [b"(" as &[u8], b"[", b"{", b"Some("][rng.below(4)];
            let i = rng.below(len + 1);
            let nest: Vec<u8> = open.repeat(depth);
            input.splice(i..i, nest);
        }
        11 if !pool.is_empty() => {
            let other = &pool[rng.below(pool.len())];
            if !other.is_empty() {
                let a = rng.below(other.len());
                let b = (a + 1 + rng.below(256)).min(other.len());
                let i = rng.below(len + 1);
                input.splice(i..i, other[a..b].iter().copied());
            }
        }
        12..=14 => line_edit(rng, input),
        _ => {
            // A chunk repeated in place (a list entry twice, a long string).
            if len > 0 {
                let a = rng.below(len);
                let b = (a + 1 + rng.below(128)).min(len);
                let chunk = input[a..b].to_vec();
                let most = if rng.chance(8) { 2000 } else { 3 };
                let times = 1 + rng.below(most);
                for _ in 0..times {
                    input.splice(b..b, chunk.iter().copied());
                }
            }
        }
    }
}

/// Spans of number-like tokens: a digit (or `-`, `+`, `.` before one) and what follows.
fn number_spans(input: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < input.len() {
        let starts = input[i].is_ascii_digit()
            || (matches!(input[i], b'-' | b'+' | b'.')
                && input.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_word = i > 0 && (input[i - 1].is_ascii_alphanumeric() || input[i - 1] == b'_');
        if starts && !after_word {
            let start = i;
            i += 1;
            while i < input.len()
                && (input[i].is_ascii_alphanumeric() || matches!(input[i], b'.' | b'_'))
                || (i < input.len()
                    && matches!(input[i], b'-' | b'+')
                    && matches!(input[i - 1], b'e' | b'E'))
            {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

fn replace_number(rng: &mut Rng, input: &mut Vec<u8>) {
    let spans = number_spans(input);
    if spans.is_empty() {
        return;
    }
    let (a, b) = spans[rng.below(spans.len())];
    let new = NUMBERS[rng.below(NUMBERS.len())].as_bytes();
    input.splice(a..b, new.iter().copied());
}

/// Spans of string literals, quotes included.
fn string_spans(input: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < input.len() {
        if input[i] == b'"' {
            let start = i;
            i += 1;
            while i < input.len() && input[i] != b'"' {
                i += if input[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(input.len());
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

/// A string literal replaced by another of the input, or by an odd one.
fn swap_string(rng: &mut Rng, input: &mut Vec<u8>) {
    let spans = string_spans(input);
    if spans.is_empty() {
        return;
    }
    let (a, b) = spans[rng.below(spans.len())];
    let new: Vec<u8> = if rng.chance(3) {
        let odd: [&[u8]; 6] = [
            b"\"\"",
            b"\"\\u{0}\"",
            b"\"\\\"\"",
            b"\"\xce\xb8\xe2\x80\xb2\"",
            b"\"a\\nb\"",
            b"\"\\x41\"",
        ];
        odd[rng.below(odd.len())].to_vec()
    } else {
        let (c, d) = spans[rng.below(spans.len())];
        input[c..d].to_vec()
    };
    input.splice(a..b, new);
}

/// A field name (identifier before `:`) with a letter dropped, doubled or changed.
fn misspell_field(rng: &mut Rng, input: &mut Vec<u8>) {
    let Ok(text) = std::str::from_utf8(input) else {
        return;
    };
    let names: Vec<String> = crate::fuzz_targets::field_names(text).into_iter().collect();
    if names.is_empty() {
        return;
    }
    let name = &names[rng.below(names.len())];
    let at: Vec<usize> = text
        .match_indices(name.as_str())
        .map(|(i, _)| i)
        .filter(|&i| text[i + name.len()..].trim_start().starts_with(':'))
        .collect();
    if at.is_empty() {
        return;
    }
    let i = at[rng.below(at.len())];
    let k = i + rng.below(name.len());
    match rng.below(3) {
        0 => {
            input.remove(k);
        }
        1 => input.insert(k, input[k]),
        _ => input[k] = b'a' + (rng.next() % 26) as u8,
    }
}

/// A line deleted, repeated, or swapped with another.
fn line_edit(rng: &mut Rng, input: &mut Vec<u8>) {
    let mut lines: Vec<Vec<u8>> = input.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    if lines.len() < 2 {
        return;
    }
    let i = rng.below(lines.len());
    let j = rng.below(lines.len());
    match rng.below(3) {
        0 => {
            lines.remove(i);
        }
        1 => {
            let l = lines[i].clone();
            lines.insert(j, l);
        }
        _ => lines.swap(i, j),
    }
    *input = lines.join(&b'\n');
}

/// Adds `input` to `pool`, replacing a random entry once the pool is full.
fn keep(rng: &mut Rng, pool: &mut Vec<Vec<u8>>, input: &[u8]) {
    if pool.len() < CORPUS_CAP {
        pool.push(input.to_vec());
    } else {
        let i = rng.below(pool.len());
        pool[i] = input.to_vec();
    }
}

/// The outcome with values ignored (digits, quoted text, the names after `gear`, `mesh`, ...),
/// so that only new kinds of refusal count as new outcomes.
fn signature(outcome: &Outcome) -> String {
    match outcome {
        Outcome::Accepted => "accepted".into(),
        Outcome::Refused(m) => {
            let mut words = Vec::new();
            // After `gear`, `mesh`... comes a name, up to the next word ending in `:`.
            let mut naming = false;
            for w in m.split_whitespace() {
                let named = naming;
                if naming {
                    naming = !w.ends_with(':');
                } else {
                    naming = !w.ends_with(':')
                        && matches!(
                            w.trim_matches(|c: char| !c.is_ascii_alphanumeric()),
                            "gear" | "mesh" | "arbor" | "pointer" | "driver" | "driven" | "field"
                        );
                }
                if named
                    || w.contains(|c: char| c.is_ascii_digit() || "'\"`".contains(c))
                    || !w.is_ascii()
                {
                    if words.last() != Some(&"#") {
                        words.push("#");
                    }
                } else {
                    words.push(w);
                }
            }
            words.join(" ")
        }
    }
}

/// The panic message of the last panic on this thread (set by the quiet hook).
static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

/// Runs `target` on `input`: the outcome, a finding kind and message, and the time taken.
fn execute(target: Target, input: &[u8]) -> (Result<Outcome, (&'static str, String)>, bool) {
    let (text, utf8) = match std::str::from_utf8(input) {
        Ok(t) => (std::borrow::Cow::Borrowed(t), true),
        Err(_) => (String::from_utf8_lossy(input), false),
    };
    let result = catch_unwind(AssertUnwindSafe(|| target(&text)));
    let outcome = match result {
        Ok(Ok(o)) => Ok(o),
        Ok(Err(broken)) => Err(("broken-promise", broken)),
        Err(_) => {
            let msg = LAST_PANIC
                .lock()
                .ok()
                .and_then(|mut m| m.take())
                .unwrap_or_else(|| "panic".into());
            Err(("panic", msg))
        }
    };
    (outcome, utf8)
}

/// The file the loaders' file checks write their inputs to: in the system's temporary folder.
fn scratch_file() -> std::path::PathBuf {
    std::env::temp_dir().join(format!("xtask-fuzz-{}.ron", std::process::id()))
}

/// A file the gearing loader reads: a non-UTF-8 one must be refused, naming it. A scratch file
/// that cannot be written is said as a finding too: the check did not run.
fn gearing_file_refuses(input: &[u8], scratch: &Path) -> Option<String> {
    if let Err(e) = std::fs::write(scratch, input) {
        return Some(format!(
            "the file check did not run: {} cannot be written ({e})",
            scratch.display()
        ));
    }
    match catch_unwind(|| train::Gearing::load(scratch)) {
        Ok(Err(e)) if e.to_string().starts_with(&scratch.display().to_string()) => None,
        Ok(Err(e)) => Some(format!("refusal does not name the file first: {e}")),
        Ok(Ok(_)) => Some("accepted a file that is not UTF-8".into()),
        Err(_) => Some("panicked reading a file that is not UTF-8".into()),
    }
}

/// The panic hook of a fuzzing run: keeps the message and place of the last panic in
/// `LAST_PANIC`, for the finding to name, instead of printing it.
fn record_panic(info: &std::panic::PanicHookInfo<'_>) {
    let payload = info
        .payload()
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| info.payload().downcast_ref::<String>().cloned())
        .unwrap_or_default();
    let at = info
        .location()
        .map(|l| format!(" at {}:{}", l.file(), l.line()))
        .unwrap_or_default();
    if let Ok(mut m) = LAST_PANIC.lock() {
        *m = Some(format!("{payload}{at}"));
    }
}

/// The next input when the queue is empty: one of the accepted inputs (`valid`) or of the
/// `corpus`, mutated one or more times, at most 1 MiB.
fn mutated(rng: &mut Rng, valid: &[Vec<u8>], corpus: &[Vec<u8>], all_seeds: &[Vec<u8>]) -> Vec<u8> {
    // Mostly from accepted inputs, changed once: the deep rules only see valid files.
    let from_valid = rng.below(10) < 6;
    let mut input = if from_valid {
        valid[rng.below(valid.len())].clone()
    } else {
        corpus[rng.below(corpus.len())].clone()
    };
    let rounds = if from_valid && rng.below(10) < 7 {
        1
    } else {
        1 + rng.below(4)
    };
    for _ in 0..rounds {
        let pool = if rng.chance(4) { all_seeds } else { corpus };
        mutate(rng, &mut input, pool);
    }
    input.truncate(1 << 20);
    input
}

/// Fuzzes every target within `budget`, starting from `seed`.
pub fn run(budget: Budget, seed: u64) -> Summary {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(record_panic));
    let scratch = scratch_file();
    let mut summary = Summary::default();
    let mut seen_findings = BTreeSet::new();
    let targets = targets();
    let all_seeds: Vec<Vec<u8>> = targets
        .iter()
        .map(|(_, _, s)| s.as_bytes().to_vec())
        .collect();
    for (t, &(name, target, shipped)) in targets.iter().enumerate() {
        let mut rng = Rng(seed ^ (t as u64 + 1).wrapping_mul(0xA076_1D64_78BD_642F));
        let mut corpus: Vec<Vec<u8>> = vec![shipped.as_bytes().to_vec()];
        corpus.extend(EDGE_CASES.iter().map(|e| e.as_bytes().to_vec()));
        let mut stats = TargetStats {
            name,
            seeds: corpus.len(),
            ..Default::default()
        };
        let mut outcomes = BTreeSet::new();
        let start = Instant::now();
        let deadline = match budget {
            Budget::Seconds(s) => Some(start + Duration::from_secs_f64(s / targets.len() as f64)),
            Budget::Execs(_) => None,
        };
        let mut queue: Vec<Vec<u8>> = corpus.clone();
        let mut valid: Vec<Vec<u8>> = vec![shipped.as_bytes().to_vec()];
        loop {
            match (budget, deadline) {
                (Budget::Execs(n), _) if stats.execs >= n => break,
                (_, Some(d)) if Instant::now() >= d => break,
                _ => {}
            }
            let input = queue
                .pop()
                .unwrap_or_else(|| mutated(&mut rng, &valid, &corpus, &all_seeds));
            let began = Instant::now();
            let (result, utf8) = execute(target, &input);
            let took = began.elapsed();
            stats.execs += 1;
            let mut finding = None;
            if !utf8 {
                stats.not_utf8 += 1;
                if name == "gearing"
                    && let Some(m) = gearing_file_refuses(&input, &scratch)
                {
                    finding = Some(("broken-promise", m));
                }
            }
            match result {
                Ok(outcome) => {
                    match outcome {
                        Outcome::Accepted => stats.accepted += 1,
                        Outcome::Refused(_) => stats.refused += 1,
                    }
                    let new = outcomes.insert(signature(&outcome));
                    if utf8 && outcome == Outcome::Accepted {
                        keep(&mut rng, &mut valid, &input);
                    }
                    if utf8 && new {
                        keep(&mut rng, &mut corpus, &input);
                    }
                }
                Err(f) => finding = Some(f),
            }
            if took > SLOW && finding.is_none() {
                finding = Some(("slow", format!("took {:.1} s", took.as_secs_f64())));
            }
            if let Some((kind, message)) = finding {
                // Line numbers and values vary; the first of each kind of message is enough.
                let key = (name, kind, signature(&Outcome::Refused(message.clone())));
                if seen_findings.insert(key) {
                    summary.findings.push(Finding {
                        target: name,
                        kind,
                        message,
                        input,
                    });
                }
            }
        }
        stats.seconds = start.elapsed().as_secs_f64();
        stats.outcomes = outcomes.len();
        stats.corpus = corpus.len();
        stats.valid = valid.len();
        summary.targets.push(stats);
    }
    let _ = std::fs::remove_file(&scratch);
    std::panic::set_hook(previous);
    summary
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn a_short_run_finds_nothing() {
        let summary = run(Budget::Execs(1500), 7);
        for f in &summary.findings {
            eprintln!(
                "{} {}: {}\n{}",
                f.target,
                f.kind,
                f.message,
                String::from_utf8_lossy(&f.input)
            );
        }
        assert!(summary.findings.is_empty());
        for s in &summary.targets {
            assert_eq!(s.execs, 1500);
            assert!(s.accepted > 0 && s.refused > 0, "{s:?}");
            assert!(s.outcomes > 5, "{s:?}");
        }
    }

    #[test]
    fn mutations_stay_in_bounds() {
        // One mutation grows an input by at most the deepest nesting it inserts (100 000
        // `Some(`) or a copy of one of its lines (at most its length), changes the input most of
        // the time, and does reach the deep nests and long repeats that stress the loaders.
        const MOST_GROWTH: usize = 100_000 * b"Some(".len();
        let mut rng = Rng(1);
        let pool = vec![b"(a: 1)".to_vec(), Vec::new()];
        let (mut mutations, mut changed, mut largest_growth) = (0, 0, 0);
        for _ in 0..20_000 {
            let mut input = if rng.chance(2) {
                b"(x: \"s\", y: -1.5e3)\n(z: [1, 2])".to_vec()
            } else {
                Vec::new()
            };
            for _ in 0..4 {
                let before = input.clone();
                mutate(&mut rng, &mut input, &pool);
                let growth = input.len().saturating_sub(before.len());
                let bound = MOST_GROWTH.max(before.len() + 1);
                assert!(growth <= bound, "one mutation grew the input by {growth}");
                largest_growth = largest_growth.max(growth);
                mutations += 1;
                changed += usize::from(input != before);
                if input.len() > 4_000_000 {
                    input.truncate(1000);
                }
            }
        }
        assert!(
            changed * 2 > mutations,
            "{changed} of {mutations} mutations changed the input"
        );
        assert!(largest_growth > 100_000, "largest growth {largest_growth}");
    }

    #[test]
    fn tokens() {
        assert_eq!(
            number_spans(b"(a: -1.5e-3, b2: 7, c: x9)"),
            [(4, 11), (17, 18)]
        );
        assert_eq!(string_spans(b"\"a\\\"b\" x \"c"), [(0, 6), (9, 11)]);
        assert_eq!(
            signature(&Outcome::Refused("f: line 12, column 3: x".into())),
            "f: line # column # x"
        );
        assert_eq!(
            signature(&Outcome::Refused(
                "f: gear b1: on two arbors: b and c, \"q r\"".into()
            )),
            "f: gear # on two arbors: b and c, #"
        );
        assert_eq!(
            signature(&Outcome::Refused(
                "f: arbor e outer pipe: unknown gear x y".into()
            )),
            "f: arbor # unknown gear #"
        );
    }
}
