//! Logs and progress bars on stderr.
//!
//! Logs go through `tracing` (`RUST_LOG`, default `warn`; `-v`: `debug`; `-q`: off). When stderr
//! is a terminal and `-q` is not given, every batch of trials that an experiment runs through
//! [`registry::Context::trials`] gets a progress bar (trials done, rate, time left) once the
//! experiment has run for [`DELAY`]: a `tracing` span drawn by `tracing-indicatif`, moved on from
//! the worker threads as trials finish. The bars only watch ([`registry::Progress`]): results
//! are the same with and without them.
//!
//! `XTASK_PROGRESS=always` makes them even when stderr is not a terminal (where indicatif draws
//! nothing), from the first trial on, so that tests run the same code with and without them;
//! `XTASK_PROGRESS=never` turns them off; `auto` (or unset, or empty) is the default. Any other
//! value is refused before anything runs ([`check_setting`]): a misspelt one would silently do
//! nothing. A `RUST_LOG` that is not a log filter is said to be ignored, in a warning (the
//! variable is shared with other programs, so it is not refused).
//!
//! When stderr is not a terminal (a log file, a pipe, a cluster job's output) and `-q` is not
//! given, a running experiment instead prints a plain progress line every [`LINE_PERIOD`]
//! (every second, the first after half a second, with `XTASK_PROGRESS=always`): how long it has run and, for
//! the batch of trials under way, the trials done, their rate and the time left. A long run
//! is never silent in a log; like the bars, the lines only watch.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::{Duration, Instant};

use indicatif::ProgressStyle;
use registry::{BatchProgress, Context, Progress};
use tracing::Span;
use tracing_indicatif::IndicatifLayer;
use tracing_indicatif::filter::IndicatifFilter;
use tracing_indicatif::span_ext::IndicatifSpanExt;
use tracing_subscriber::EnvFilter;
use tracing_subscriber::layer::SubscriberExt;
use tracing_subscriber::util::SubscriberInitExt;
use tracing_subscriber::{Layer, fmt};

use crate::args::Verbosity;

/// How long an experiment runs before its batches get progress bars.
pub const DELAY: Duration = Duration::from_secs(1);

/// How often a progress line is printed when stderr is not a terminal.
pub const LINE_PERIOD: Duration = Duration::from_secs(10);

/// The progress lines of this process, if stderr gets them.
static LINES: OnceLock<Arc<Lines>> = OnceLock::new();

/// The bars of this process, if stderr gets them.
static BARS: OnceLock<Arc<Bars>> = OnceLock::new();

/// `-q`: no notes on stderr either.
static QUIET: AtomicBool = AtomicBool::new(false);

/// The values `XTASK_PROGRESS` takes.
pub const PROGRESS_VALUES: [&str; 3] = ["always", "never", "auto"];

/// Refuses an `XTASK_PROGRESS` that is not one of [`PROGRESS_VALUES`] (empty counts as unset),
/// naming the variable, the value and the values it takes.
pub fn check_setting() -> Result<(), String> {
    let value = match std::env::var("XTASK_PROGRESS") {
        Err(std::env::VarError::NotPresent) => return Ok(()),
        Err(std::env::VarError::NotUnicode(v)) => format!("{v:?}"),
        Ok(v) if v.is_empty() || PROGRESS_VALUES.contains(&v.as_str()) => return Ok(()),
        Ok(v) => format!("`{}`", v.escape_debug()),
    };
    Err(format!(
        "XTASK_PROGRESS: must be {} (progress bars and lines whatever stderr is, none, or as stderr allows; got {value})",
        PROGRESS_VALUES.join(", ")
    ))
}

/// The log filter of `RUST_LOG` at the default verbosity: `warn` when unset or empty, and with a
/// warning on stderr when it is not a filter (ignored rather than refused: other programs read
/// the same variable).
fn env_filter() -> EnvFilter {
    match std::env::var("RUST_LOG") {
        Ok(v) if !v.trim().is_empty() => EnvFilter::try_new(&v).unwrap_or_else(|e| {
            say(&format!(
                "warning: RUST_LOG: `{}` is not a log filter ({e}); it is ignored and warnings are logged (e.g. RUST_LOG=info or RUST_LOG=debug)",
                v.escape_debug()
            ));
            EnvFilter::new("warn")
        }),
        Ok(_) => EnvFilter::new("warn"),
        Err(std::env::VarError::NotPresent) => EnvFilter::new("warn"),
        Err(std::env::VarError::NotUnicode(v)) => {
            say(&format!("warning: RUST_LOG: {v:?} is not valid UTF-8; it is ignored and warnings are logged"));
            EnvFilter::new("warn")
        }
    }
}

/// Sets up logging (and progress bars, where they are drawn) for the whole process.
pub fn init(verbosity: Verbosity) {
    QUIET.store(verbosity == Verbosity::Quiet, Ordering::Relaxed);
    let filter = match verbosity {
        Verbosity::Quiet => EnvFilter::new("off"),
        Verbosity::Verbose => EnvFilter::new("debug"),
        Verbosity::Normal => env_filter(),
    };
    let setting = std::env::var("XTASK_PROGRESS");
    let (wanted, delay) = match setting.as_deref() {
        Ok("always") => (true, Duration::ZERO),
        Ok("never") => (false, DELAY),
        _ => (std::io::stderr().is_terminal(), DELAY),
    };
    if verbosity != Verbosity::Quiet
        && !std::io::stderr().is_terminal()
        && setting.as_deref() != Ok("never")
    {
        let (first, period) = if setting.as_deref() == Ok("always") {
            (Duration::from_millis(500), Duration::from_secs(1))
        } else {
            (LINE_PERIOD, LINE_PERIOD)
        };
        let _ = LINES.set(Arc::new(Lines {
            first,
            period,
            current: Mutex::new(None),
        }));
    }
    // Colours only for a person at a terminal, not in files and pipes.
    let colour = std::io::stderr().is_terminal();
    // A second initialisation cannot happen here; if it did, logging would just stay as it was.
    if wanted && verbosity != Verbosity::Quiet {
        let bars = IndicatifLayer::new().with_max_progress_bars(4, None);
        let logs = fmt::layer()
            .with_writer(bars.get_stderr_writer())
            // A log line that cannot be written is not printed again with `eprintln!`, which
            // panics when stderr is full.
            .log_internal_errors(false)
            .with_ansi(colour)
            .with_target(false)
            .with_filter(filter);
        let ok = tracing_subscriber::registry()
            .with(logs)
            .with(bars.with_filter(IndicatifFilter::new(false)))
            .try_init()
            .is_ok();
        if ok {
            let _ = BARS.set(Arc::new(Bars::new(delay)));
        }
    } else {
        let _ = fmt()
            .with_env_filter(filter)
            .with_writer(|| Stderr)
            .log_internal_errors(false)
            .with_ansi(colour)
            .with_target(false)
            .try_init();
    }
}

/// Set when a line could not be written to stderr: the command then ends with exit status 1.
static STDERR_FAILED: AtomicBool = AtomicBool::new(false);

/// Writes `text` and a line end to stderr, its control characters escaped
/// ([`registry::terminal_text`]: a path or a name from a user's file holding an escape sequence
/// cannot change the terminal). A failure (stderr closed, or its disk full) is recorded for the
/// exit status ([`stderr_failed`]), never a panic as `eprintln!` would make it.
pub fn say(text: &str) {
    use std::io::Write as _;
    let mut err = std::io::stderr().lock();
    let text = registry::terminal_text(text);
    if writeln!(err, "{text}").and_then(|()| err.flush()).is_err() {
        STDERR_FAILED.store(true, Ordering::Relaxed);
    }
}

/// Stderr for the logs: a failed write is recorded as [`say`] records it.
struct Stderr;

impl std::io::Write for Stderr {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        std::io::stderr().write(buf).inspect_err(|_| {
            STDERR_FAILED.store(true, Ordering::Relaxed);
        })
    }

    fn flush(&mut self) -> std::io::Result<()> {
        std::io::stderr().flush().inspect_err(|_| {
            STDERR_FAILED.store(true, Ordering::Relaxed);
        })
    }
}

/// Whether a line could not be written to stderr ([`say`]).
pub fn stderr_failed() -> bool {
    STDERR_FAILED.load(Ordering::Relaxed)
}

/// Prints a note (where results went, what was skipped) on stderr, unless `-q`.
pub fn note(text: &str) {
    if !QUIET.load(Ordering::Relaxed) {
        say(text);
    }
}

/// `ctx` with the progress bars and lines attached, where stderr gets them.
pub fn attach(ctx: Context) -> Context {
    match (BARS.get(), LINES.get()) {
        (Some(bars), Some(lines)) => ctx.with_progress(Arc::new(Both(bars.clone(), lines.clone()))),
        (Some(bars), None) => ctx.with_progress(bars.clone()),
        (None, Some(lines)) => ctx.with_progress(lines.clone()),
        (None, None) => ctx,
    }
}

/// Runs `f` (experiment `id`), printing a progress line on stderr every period while it runs
/// when stderr gets them (not a terminal, no `-q`); otherwise just runs `f`.
pub fn watch<T>(id: &str, f: impl FnOnce() -> T) -> T {
    let Some(lines) = LINES.get() else {
        return f();
    };
    let start = Instant::now();
    let (stop, stopped) = std::sync::mpsc::channel::<()>();
    std::thread::scope(|s| {
        s.spawn(move || {
            let mut wait = lines.first;
            loop {
                match stopped.recv_timeout(wait) {
                    Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                        say(&lines.line(id, start.elapsed()));
                        wait = lines.period;
                    }
                    _ => return,
                }
            }
        });
        let out = f();
        drop(stop);
        out
    })
}

/// A duration as a person reads it: `45s`, `3m 05s`, `2h 10m`, `4d 3h`.
pub fn human(d: Duration) -> String {
    let s = d.as_secs();
    match s {
        0..60 => format!("{s}s"),
        60..3600 => format!("{}m {:02}s", s / 60, s % 60),
        3600..86400 => format!("{}h {:02}m", s / 3600, (s % 3600) / 60),
        _ => format!("{}d {}h", s / 86400, (s % 86400) / 3600),
    }
}

/// Plain progress lines for a log: the batch under way, watched.
struct Lines {
    /// When the first line is printed, from the experiment's start.
    first: Duration,
    /// Time between lines.
    period: Duration,
    current: Mutex<Option<Arc<Watched>>>,
}

/// A batch of trials as the lines see it.
struct Watched {
    label: String,
    trials: u64,
    started: Instant,
    done: AtomicU64,
}

impl Lines {
    /// The line for an experiment that has run for `elapsed`.
    fn line(&self, id: &str, elapsed: Duration) -> String {
        let current = self
            .current
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone();
        let mut s = format!("progress: {id}: running for {}", human(elapsed));
        if let Some(b) = current {
            let done = b.done.load(Ordering::Relaxed).min(b.trials);
            s.push_str(&format!(
                "; {}: {done} of {} trials done",
                b.label, b.trials
            ));
            s.push_str(&rate_and_left(done, b.trials, b.started.elapsed()));
        }
        s
    }
}

/// `, R trials/s, about T left in this batch` for `done` of `trials` in `elapsed` (since the batch
/// started: the work done so far, not the latest ticks); nothing to say before the first trial
/// is done. Later batches of the experiment are not known yet, so not counted.
fn rate_and_left(done: u64, trials: u64, elapsed: Duration) -> String {
    let secs = elapsed.as_secs_f64();
    if done == 0 || secs <= 0.0 {
        return ", none finished yet".into();
    }
    let rate = done as f64 / secs;
    let left = Duration::from_secs_f64(((trials - done) as f64 / rate).min(1e9));
    format!(
        ", {} trials/s, about {} left in this batch",
        registry::fmt_f64(rate, 2),
        human(left)
    )
}

impl Progress for Lines {
    fn batch(
        &self,
        experiment: &str,
        _batch: &str,
        index: usize,
        n: u64,
    ) -> Box<dyn BatchProgress> {
        let w = Arc::new(Watched {
            label: format!("batch {}", index + 1),
            trials: n,
            started: Instant::now(),
            done: AtomicU64::new(0),
        });
        let _ = experiment;
        *self.current.lock().unwrap_or_else(PoisonError::into_inner) = Some(w.clone());
        Box::new(LineTick(w))
    }
}

/// One batch's counter for the lines.
struct LineTick(Arc<Watched>);

impl BatchProgress for LineTick {
    fn done(&self) {
        self.0.done.fetch_add(1, Ordering::Relaxed);
    }
}

/// Bars and lines both watching.
struct Both(Arc<Bars>, Arc<Lines>);

impl Progress for Both {
    fn batch(&self, experiment: &str, batch: &str, index: usize, n: u64) -> Box<dyn BatchProgress> {
        Box::new(BothTicks(
            self.0.batch(experiment, batch, index, n),
            self.1.batch(experiment, batch, index, n),
        ))
    }
}

struct BothTicks(Box<dyn BatchProgress>, Box<dyn BatchProgress>);

impl BatchProgress for BothTicks {
    fn done(&self) {
        self.0.done();
        self.1.done();
    }
}

/// An experiment starts: its bars wait [`DELAY`] from now.
pub fn experiment_starts() {
    if let Some(bars) = BARS.get() {
        *bars.since.lock().unwrap_or_else(PoisonError::into_inner) = Instant::now();
    }
}

/// Hands out a bar for each batch of trials.
struct Bars {
    /// When the running experiment started.
    since: Mutex<Instant>,
    /// How long it runs before its batches get bars.
    delay: Duration,
    style: Option<ProgressStyle>,
}

impl Bars {
    fn new(delay: Duration) -> Bars {
        Bars {
            since: Mutex::new(Instant::now()),
            delay,
            // The rate and time left are the batch's own, from the trials done since it started
            // (as the progress lines give them), set in the message: indicatif's estimate
            // follows the latest ticks, which come in bursts of cheap trials (a trial that jams
            // early ends early) and ran low.
            style: ProgressStyle::with_template("[{bar:30}] {human_pos}/{human_len} trials{msg}")
                .ok()
                .map(|s| s.progress_chars("=> ")),
        }
    }
}

impl Progress for Bars {
    fn batch(
        &self,
        experiment: &str,
        _batch: &str,
        index: usize,
        n: u64,
    ) -> Box<dyn BatchProgress> {
        Box::new(Bar {
            label: format!("{experiment}, batch {}", index + 1),
            trials: n,
            since: *self.since.lock().unwrap_or_else(PoisonError::into_inner),
            delay: self.delay,
            style: self.style.clone(),
            done: AtomicU64::new(0),
            shown: AtomicU64::new(0),
            started: Instant::now(),
            told: AtomicU64::new(0),
            span: OnceLock::new(),
        })
    }
}

/// The bar of one batch: a span with a progress bar, made once the experiment has run for
/// its delay ([`DELAY`]); closed (and the bar cleared) when the batch ends.
struct Bar {
    label: String,
    trials: u64,
    since: Instant,
    delay: Duration,
    style: Option<ProgressStyle>,
    /// Trials done.
    done: AtomicU64,
    /// The largest count drawn so far (ticks arrive from several threads).
    shown: AtomicU64,
    /// When the batch started: its rate and time left count from here.
    started: Instant,
    /// When the rate and time left were last written (milliseconds after `started`).
    told: AtomicU64,
    span: OnceLock<Span>,
}

impl BatchProgress for Bar {
    fn done(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if self.span.get().is_none() && self.since.elapsed() < self.delay {
            return;
        }
        let span = self.span.get_or_init(|| {
            let span = tracing::info_span!(
                parent: None,
                "trials",
                indicatif.pb_show = tracing::field::Empty
            );
            if let Some(style) = &self.style {
                span.pb_set_style(style);
            }
            span.pb_set_length(self.trials);
            span.pb_set_message(&format!(" ({})", self.label));
            span.pb_start();
            span.pb_set_position(done);
            tracing::debug!(bar = %self.label, trials = self.trials, "progress bar shown");
            span
        });
        if self.shown.fetch_max(done, Ordering::Relaxed) < done {
            // Never backwards: a tick that lost the race to a later one draws nothing.
            span.pb_set_position(done);
        }
        // The rate and time left, four times a second at most.
        let now = self.started.elapsed();
        let ms = u64::try_from(now.as_millis()).unwrap_or(u64::MAX);
        let told = self.told.load(Ordering::Relaxed);
        if ms >= told.saturating_add(250)
            && self
                .told
                .compare_exchange(told, ms, Ordering::Relaxed, Ordering::Relaxed)
                .is_ok()
        {
            span.pb_set_message(&format!(
                "{} ({})",
                rate_and_left(done.min(self.trials), self.trials, now),
                self.label
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_as_a_person_reads_them() {
        assert_eq!(human(Duration::from_secs(45)), "45s");
        assert_eq!(human(Duration::from_secs(185)), "3m 05s");
        assert_eq!(human(Duration::from_secs(7800)), "2h 10m");
        assert_eq!(human(Duration::from_secs(4 * 86400 + 3 * 3600)), "4d 3h");
    }

    #[test]
    fn rate_and_time_left_come_from_the_trials_done_so_far() {
        // 30 of 200 trials in 60 s: 0.5 per second, 170 left take 340 s.
        assert_eq!(
            rate_and_left(30, 200, Duration::from_secs(60)),
            ", 0.50 trials/s, about 5m 40s left in this batch"
        );
        assert_eq!(
            rate_and_left(0, 2, Duration::from_secs(60)),
            ", none finished yet"
        );
        let lines = Lines {
            first: Duration::ZERO,
            period: Duration::ZERO,
            current: Mutex::new(None),
        };
        assert_eq!(
            lines.line("fig2", Duration::from_secs(70)),
            "progress: fig2: running for 1m 10s"
        );
        let tick = lines.batch("table1", "key", 2, 10);
        tick.done();
        tick.done();
        let line = lines.line("table1", Duration::from_secs(5));
        assert!(
            line.starts_with("progress: table1: running for 5s; batch 3: 2 of 10 trials done, "),
            "{line}"
        );
    }
}
