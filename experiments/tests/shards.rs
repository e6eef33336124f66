//! Sharded runs of the converted experiments (`failure`, `table1`, `tolerance`,
//! `clearance-design`), joined and replayed through the registry, give exactly the report of a
//! single run.
#![allow(clippy::unwrap_used, reason = "tests")]

use registry::{Context, Report, Shard, ShardRecords, merge_records};

fn context(id: &str, sets: &[(&str, &str)]) -> Context {
    experiments::context(id, 5, 2, sets).unwrap().1
}

fn run(id: &str, ctx: &Context) -> Report {
    let map = registry::experiments().unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| (map[id].run)(ctx, ctx.engine()))
        .unwrap()
        .report
}

/// A single run, and `n` shards joined (their records sent through JSON text) and replayed.
fn single_and_merged(id: &str, sets: &[(&str, &str)], n: u64) -> (Report, Report) {
    let single = run(id, &context(id, sets));
    let parts: Vec<ShardRecords> = (0..n)
        .map(|k| {
            let shard = Shard::new(k, n).unwrap();
            let ctx = context(id, sets).with_shard(shard);
            run(id, &ctx);
            let text = serde_json::to_string(&ctx.recorded()).unwrap();
            ShardRecords {
                source: format!("shard {k}"),
                shard,
                records: serde_json::from_str(&text).unwrap(),
            }
        })
        .collect();
    let replay = context(id, sets).with_replay(merge_records(&parts).unwrap());
    let merged = run(id, &replay);
    assert!(replay.unclaimed().is_empty());
    (single, merged)
}

#[test]
fn failure_shards_merge_to_the_single_run() {
    // Case D jams early in almost every run, so this is quick; 7 runs over 3 shards.
    let (single, merged) = single_and_merged("failure", &[("cases", "D"), ("trials", "7")], 3);
    assert_eq!(single, merged);
}

#[test]
fn table1_shards_merge_to_the_single_run() {
    let sets = [
        ("trials", "5"),
        ("lunar_turns", "0.1"),
        ("metonic_turns", "0.1"),
        ("saros_turns", "0.1"),
        ("games_turns", "0.1"),
        ("exeligmos_turns", "0.1"),
        ("samples_per_engagement", "2"),
    ];
    let (single, merged) = single_and_merged("table1", &sets, 2);
    assert_eq!(single, merged);
}

#[test]
fn tolerance_search_shards_merge_to_the_single_run() {
    // The search decides from its counts what to run next, so its batches are never split:
    // every shard runs them whole and the merge replays them.
    let sets = [
        ("search_lo", "0.03"),
        ("search_hi", "0.07"),
        ("resolution", "0.02"),
        ("batch", "3"),
        ("cap", "6"),
        ("rule", "20"),
        ("random_from", "0.05"),
        ("random_to", "0.05"),
    ];
    let (single, merged) = single_and_merged("tolerance", &sets, 2);
    assert_eq!(single, merged);
}

#[test]
fn clearance_design_shards_merge_to_the_single_run() {
    // The search decides the clearances of the failure study, so its batches are never split;
    // the failure study's runs are, 5 runs per setting over 2 shards.
    let sets = [
        ("cases", "D"),
        ("grid", "30,50"),
        ("coarse_trials", "2"),
        ("refine_trials", "3"),
        ("runs", "5"),
    ];
    let (single, merged) = single_and_merged("clearance-design", &sets, 2);
    assert_eq!(single, merged);
}
