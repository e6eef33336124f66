//! `Context::trials` in its three modes: normal, shard, replay from merged records.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use registry::{
    Context, Entry, NoSettings, Records, RunError, Shard, ShardRecords, TrialMode, merge_records,
};
use serde::{Deserialize, Serialize};

registry::test_experiment!(Exp, "t", "Table 0", NoSettings);
static EXP: Entry = Entry::of::<Exp>();

fn ctx() -> Context {
    Context::new(&EXP, 1, 2, &[], None).unwrap()
}

/// A trial value with awkward floats, a string and a nested option.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
struct Value {
    x: f64,
    tiny: f64,
    #[serde(with = "registry::f64_bits")]
    maybe_nan: f64,
    label: String,
    day: Option<f64>,
}

/// A value whose floats have no short decimal form: `sin(t)` scaled, subnormals, -0.0, NaN.
fn value(t: u64) -> Value {
    let x = ((t as f64) * 0.731).sin() * 1e-7 + 1.0 / 3.0;
    Value {
        x,
        tiny: f64::MIN_POSITIVE / (t as f64 + 3.0),
        maybe_nan: if t.is_multiple_of(2) { f64::NAN } else { -0.0 },
        label: format!("trial \"{t}\"\n"),
        day: (!t.is_multiple_of(3)).then_some(x * 365.25),
    }
}

fn bits(v: &[Value]) -> Vec<(u64, u64, u64, String, Option<u64>)> {
    v.iter()
        .map(|v| {
            (
                v.x.to_bits(),
                v.tiny.to_bits(),
                v.maybe_nan.to_bits(),
                v.label.clone(),
                v.day.map(f64::to_bits),
            )
        })
        .collect()
}

/// Runs the batch in shard `k` of `n`, sends its records through a JSON text and back.
fn shard_records(k: u64, n: u64, trials: u64) -> ShardRecords {
    let c = ctx().with_shard(Shard::new(k, n).unwrap());
    assert_eq!(c.trial_mode(), TrialMode::Shard(Shard::new(k, n).unwrap()));
    let got = c.trials("cell a", trials, |t| Ok(value(t))).unwrap();
    for (t, v) in got.iter().enumerate() {
        if t as u64 % n == k {
            assert_eq!(bits(std::slice::from_ref(v)), bits(&[value(t as u64)]));
        } else {
            assert_eq!(v, &Value::default(), "trial {t} is not this shard's");
        }
    }
    let squares = c.trials_whole("whole", 4, |t| Ok(t * t)).unwrap();
    assert_eq!(
        squares,
        [0, 1, 4, 9],
        "whole batches are computed by every shard"
    );
    let text = serde_json::to_string_pretty(&c.recorded()).unwrap();
    ShardRecords {
        source: format!("shard-{k}.json"),
        shard: Shard::new(k, n).unwrap(),
        records: serde_json::from_str(&text).unwrap(),
    }
}

#[test]
fn shards_then_replay_give_every_value_bit_for_bit() {
    let trials = 11;
    let direct = ctx().trials("cell a", trials, |t| Ok(value(t))).unwrap();
    assert_eq!(
        bits(&direct),
        bits(&(0..trials).map(value).collect::<Vec<_>>())
    );
    for n in [1, 2, 3, 13] {
        let parts: Vec<ShardRecords> = (0..n).rev().map(|k| shard_records(k, n, trials)).collect();
        let merged = merge_records(&parts).unwrap();
        let replay = ctx().with_replay(merged);
        assert_eq!(replay.trial_mode(), TrialMode::Replay);
        let got: Vec<Value> = replay
            .trials("cell a", trials, |_| -> Result<Value, RunError> {
                panic!("a replay computes nothing")
            })
            .unwrap();
        assert_eq!(bits(&got), bits(&direct), "{n} shards");
        let squares: Vec<u64> = replay
            .trials_whole("whole", 4, |_| Err(RunError::Internal("computed".into())))
            .unwrap();
        assert_eq!(squares, [0, 1, 4, 9]);
        assert!(replay.unclaimed().is_empty());
    }
}

#[test]
fn floats_round_trip_through_json_text() {
    // float_roundtrip: the shortest decimal that reads back as the same bits, for awkward values.
    let mut xs = vec![
        0.1,
        1.0 / 3.0,
        -0.0,
        f64::MAX,
        f64::MIN_POSITIVE,
        f64::MIN_POSITIVE / 7.0,
        f64::EPSILON,
        5e-324,
        2.0_f64.sqrt() * 1e300,
        365.25 * std::f64::consts::PI,
    ];
    let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
    for _ in 0..20_000 {
        // xorshift: arbitrary bit patterns, keeping the finite ones.
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        let x = f64::from_bits(s);
        if x.is_finite() {
            xs.push(x);
        }
    }
    let c = ctx().with_shard(Shard::new(0, 1).unwrap());
    let n = xs.len() as u64;
    c.trials("floats", n, |t| Ok(xs[t as usize])).unwrap();
    let text = serde_json::to_string(&c.recorded()).unwrap();
    let records: Records = serde_json::from_str(&text).unwrap();
    let back: Vec<f64> = ctx()
        .with_replay(records)
        .trials("floats", n, |_| Ok(0.0))
        .unwrap();
    for (a, b) in xs.iter().zip(&back) {
        assert_eq!(a.to_bits(), b.to_bits(), "{a:e} came back as {b:e}");
    }
}

#[test]
fn a_non_finite_float_is_refused_when_recorded() {
    let c = ctx().with_shard(Shard::new(0, 2).unwrap());
    let e = c
        .trials("nan", 4, |t| Ok(if t == 2 { f64::NAN } else { 1.0 }))
        .unwrap_err();
    assert_eq!(e.exit_code(), 1);
    assert!(e.to_string().contains("trial 2 of batch `nan`"), "{e}");
    assert!(e.to_string().contains("f64_bits"), "{e}");
    // Inside an Option it would come back as None: refused too.
    let e = c.trials("inf", 2, |_| Ok(Some(f64::INFINITY))).unwrap_err();
    assert!(e.to_string().contains("inf"), "{e}");
    // In normal mode nothing is recorded, so nothing is refused.
    let v = ctx().trials("nan", 2, |_| Ok(f64::NAN)).unwrap();
    assert!(v[0].is_nan());
}

#[test]
fn a_batch_key_used_twice_is_an_internal_error() {
    for c in [ctx(), ctx().with_shard(Shard::new(1, 2).unwrap())] {
        c.trials("a", 3, Ok::<u64, RunError>).unwrap();
        let e = c.trials_whole("a", 3, Ok::<u64, RunError>).unwrap_err();
        assert_eq!(e.exit_code(), 1);
        assert!(e.to_string().contains("`a` twice"), "{e}");
    }
}

#[test]
fn trials_come_in_order_and_errors_pass_through() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let v = pool.install(|| ctx().trials("order", 1000, |t| Ok(t * 3)).unwrap());
    assert_eq!(v, (0..1000).map(|t| t * 3).collect::<Vec<_>>());
    let e = ctx()
        .trials("bad", 10, |t| {
            if t == 7 {
                Err(RunError::bad("--set", "x", "no"))
            } else {
                Ok(t)
            }
        })
        .unwrap_err();
    assert_eq!(e.exit_code(), 2);
    assert!(
        ctx()
            .trials("empty", 0, Ok::<u64, RunError>)
            .unwrap()
            .is_empty()
    );
}

#[test]
fn a_replay_refuses_what_the_shards_do_not_cover() {
    let parts: Vec<ShardRecords> = (0..2).map(|k| shard_records(k, 2, 5)).collect();
    let merged = merge_records(&parts).unwrap();

    let e = ctx()
        .with_replay(merged.clone())
        .trials::<Value, _>("cell b", 5, |t| Ok(value(t)))
        .unwrap_err();
    assert_eq!(e.exit_code(), 2);
    assert!(
        e.to_string().contains("batch `cell b`") && e.to_string().contains("shards do not cover"),
        "{e}"
    );

    let e = ctx()
        .with_replay(merged.clone())
        .trials::<Value, _>("cell a", 6, |t| Ok(value(t)))
        .unwrap_err();
    assert!(e.to_string().contains("shards do not cover"), "{e}");

    let mut holed = merged.clone();
    holed.get_mut("cell a").unwrap().values.remove(&3);
    let e = ctx()
        .with_replay(holed)
        .trials::<Value, _>("cell a", 5, |t| Ok(value(t)))
        .unwrap_err();
    assert_eq!(e.exit_code(), 2);
    assert!(
        e.to_string()
            .contains("batch `cell a` trial 3: shards do not cover trial 3 of 5"),
        "{e}"
    );

    let e = ctx()
        .with_replay(merged.clone())
        .trials::<(u8, bool), _>("cell a", 5, |_| Ok((0, false)))
        .unwrap_err();
    assert!(e.to_string().contains("does not fit this build"), "{e}");

    let replay = ctx().with_replay(merged);
    replay
        .trials_whole("whole", 4, Ok::<u64, RunError>)
        .unwrap();
    assert_eq!(replay.unclaimed(), ["cell a"]);
}

/// Counts what the hook is told: batches started and trials done.
#[derive(Default)]
struct Counter {
    batches: std::sync::Mutex<Vec<(String, usize, u64)>>,
    done: std::sync::Arc<std::sync::atomic::AtomicU64>,
}

struct CounterBatch(std::sync::Arc<std::sync::atomic::AtomicU64>);

impl registry::BatchProgress for CounterBatch {
    fn done(&self) {
        self.0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }
}

impl registry::Progress for Counter {
    fn batch(
        &self,
        experiment: &str,
        batch: &str,
        index: usize,
        n: u64,
    ) -> Box<dyn registry::BatchProgress> {
        assert_eq!(experiment, "t");
        self.batches
            .lock()
            .unwrap()
            .push((batch.to_owned(), index, n));
        Box::new(CounterBatch(self.done.clone()))
    }
}

#[test]
fn progress_watches_without_changing_results() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    let plain = pool.install(|| ctx().trials("cell a", 50, |t| Ok(value(t))).unwrap());
    let counter = std::sync::Arc::new(Counter::default());
    let watched = ctx().with_progress(counter.clone());
    let seen = pool.install(|| {
        let a = watched.trials("cell a", 50, |t| Ok(value(t))).unwrap();
        let b = watched.trials_whole("whole", 7, |t| Ok(t * t)).unwrap();
        assert_eq!(b, (0..7).map(|t| t * t).collect::<Vec<u64>>());
        a
    });
    assert_eq!(bits(&plain), bits(&seen), "progress changed the results");
    assert_eq!(
        *counter.batches.lock().unwrap(),
        [("cell a".to_string(), 0, 50), ("whole".to_string(), 1, 7)]
    );
    assert_eq!(
        counter.done.load(std::sync::atomic::Ordering::Relaxed),
        57,
        "one tick per trial"
    );
    // A shard ticks every trial of the batch, its own and the skipped ones.
    let counter = std::sync::Arc::new(Counter::default());
    let shard = ctx()
        .with_shard(Shard::new(1, 3).unwrap())
        .with_progress(counter.clone());
    let _ = shard.trials("cell a", 10, |t| Ok(value(t))).unwrap();
    assert_eq!(counter.done.load(std::sync::atomic::Ordering::Relaxed), 10);
}
