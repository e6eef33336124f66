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
//! `XTASK_PROGRESS=never` turns them off.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::{Duration, Instant};

use indicatif::{ProgressState, ProgressStyle};
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

/// The bars of this process, if stderr gets them.
static BARS: OnceLock<Arc<Bars>> = OnceLock::new();

/// `-q`: no notes on stderr either.
static QUIET: AtomicBool = AtomicBool::new(false);

/// Sets up logging (and progress bars, where they are drawn) for the whole process.
pub fn init(verbosity: Verbosity) {
    QUIET.store(verbosity == Verbosity::Quiet, Ordering::Relaxed);
    let filter = match verbosity {
        Verbosity::Quiet => EnvFilter::new("off"),
        Verbosity::Verbose => EnvFilter::new("debug"),
        Verbosity::Normal => {
            EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new("warn"))
        }
    };
    let (wanted, delay) = match std::env::var("XTASK_PROGRESS").as_deref() {
        Ok("always") => (true, Duration::ZERO),
        Ok("never") => (false, DELAY),
        _ => (std::io::stderr().is_terminal(), DELAY),
    };
    // Colours only for a person at a terminal, not in files and pipes.
    let colour = std::io::stderr().is_terminal();
    // A second initialisation cannot happen here; if it did, logging would just stay as it was.
    if wanted && verbosity != Verbosity::Quiet {
        let bars = IndicatifLayer::new().with_max_progress_bars(4, None);
        let logs = fmt::layer()
            .with_writer(bars.get_stderr_writer())
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
            .with_writer(std::io::stderr)
            .with_ansi(colour)
            .with_target(false)
            .try_init();
    }
}

/// Prints a note (where results went, what was skipped) on stderr, unless `-q`.
pub fn note(text: &str) {
    if !QUIET.load(Ordering::Relaxed) {
        eprintln!("{text}");
    }
}

/// `ctx` with the progress bars attached, if stderr gets them.
pub fn attach(ctx: Context) -> Context {
    match BARS.get() {
        Some(bars) => ctx.with_progress(bars.clone()),
        None => ctx,
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
            style: ProgressStyle::with_template(
                "{msg} [{bar:30}] {human_pos}/{human_len} trials, {rate}, {eta} left",
            )
            .ok()
            .map(|s| {
                s.progress_chars("=> ").with_key(
                    "rate",
                    |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                        let _ = write!(w, "{:.1} trials/s", state.per_sec());
                    },
                )
            }),
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
            span.pb_set_message(&self.label);
            span.pb_start();
            // The trials done before the bar appeared are not part of its rate.
            span.pb_set_position(done);
            span.pb_reset_eta();
            tracing::debug!(bar = %self.label, trials = self.trials, "progress bar shown");
            span
        });
        if self.shown.fetch_max(done, Ordering::Relaxed) < done {
            // Never backwards: a tick that lost the race to a later one draws nothing.
            span.pb_set_position(done);
        }
    }
}
