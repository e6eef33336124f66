//! `run.json`: what produced a results directory (id, seed, threads, overrides, config file,
//! every input file with the SHA-256 of its contents, toolkit version, date), stored beside its
//! tables so that `cargo xtask report` can show it.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;
use std::time::{SystemTime, UNIX_EPOCH};

use registry::{Context, Entry, Outcome, OutputFile, Report};
use serde_json::json;

/// The SHA-256 of the code this runner was built from (see `xtask/build.rs`): what a shard's
/// partial file and `run.json` record as the code that computed them.
pub const CODE_SHA256: &str = env!("XTASK_CODE_SHA256");

/// The file name of the provenance record in `<out>/<id>/`.
pub const RUN_JSON: &str = "run.json";

/// `report` with `run.json` added to its files, for [`registry::write_results`] to store with
/// the rest (so it is written, or not, atomically with the tables).
///
/// Overrides are the `--set` pairs `e` declares (a later pair wins, as in [`Context::new`]);
/// the config file is recorded only for an experiment that takes one.
pub fn stamp(
    report: &Report,
    e: &Entry,
    ctx: &Context,
    sets: &[(String, String)],
    config: Option<&std::path::Path>,
) -> Report {
    stamp_with(report, (e, ctx), sets, config, &context_departures(ctx))
}

/// The parameters `ctx` sets away from their defaults, readings of the paper aside.
fn context_departures(ctx: &Context) -> Vec<(&'static registry::Param, String)> {
    let departed = ctx.departures();
    ctx.values()
        .filter(|(p, _)| departed.iter().any(|(name, _)| *name == p.name))
        .map(|(p, v)| (p, v.trim().to_owned()))
        .collect()
}

/// [`stamp`], its tables labelled by `departures` ([`Report::label_departures`]).
fn stamp_with(
    report: &Report,
    (e, ctx): (&Entry, &Context),
    sets: &[(String, String)],
    config: Option<&std::path::Path>,
    departures: &[(&'static registry::Param, String)],
) -> Report {
    let overrides: BTreeMap<&str, &str> = sets
        .iter()
        .filter(|(k, _)| e.all_params().any(|p| p.name == k))
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    let config = config
        .filter(|_| e.config.is_some())
        .map(|p| p.display().to_string());
    let mut text = format!(
        "{:#}",
        json!({
            "id": e.id,
            "seed": ctx.seed(),
            "threads": ctx.threads(),
            "overrides": overrides,
            "readings": readings(ctx),
            "config": config,
            "inputs": inputs(ctx),
            // Relative input paths were read from here (`report --bundle` reads them again).
            "folder": std::env::current_dir()
                .map(|d| d.display().to_string())
                .unwrap_or_default(),
            "version": {
                "crate": env!("CARGO_PKG_VERSION"),
                "git": git_describe(),
                "code": CODE_SHA256,
            },
            "date": utc_now(),
        })
    );
    text.push('\n');
    let mut stamped = report.clone();
    stamped.inputs = recorded_inputs(ctx);
    // A run on the invented example table says so under every table.
    if runs_example_table(ctx) {
        for t in &mut stamped.tables {
            t.note(EXAMPLE_TABLE);
        }
    }
    stamped.label_departures(departures);
    stamped.files.retain(|f| f.name != RUN_JSON);
    stamped.files.push(OutputFile::new(RUN_JSON, text));
    stamped
}

/// The inputs `tables.json` records: every declared parameter marked
/// [`registry::Param::recorded`] with its value, every other parameter set away from its default, and `errors`, the measured-errors
/// file of a `measured:FILE` hypothesis.
fn recorded_inputs(ctx: &Context) -> BTreeMap<String, String> {
    let mut inputs = BTreeMap::new();
    for (p, v) in ctx.values().filter(|(p, _)| p.recorded) {
        inputs.insert(p.name.to_owned(), v.to_owned());
    }
    for (name, v) in ctx.changed() {
        inputs.insert(name.to_owned(), v.to_owned());
    }
    let hypothesis = ctx
        .holds(&study::errors::PARAM)
        .then(|| ctx.text(&study::errors::PARAM));
    if let Some(Ok(h)) = hypothesis {
        for f in setting_groups::inputs::measured_in_hypothesis(h) {
            inputs.insert("errors".to_owned(), f);
        }
    }
    inputs
}

/// [`stamp`] on `outcome`'s report, with `results.json` (the experiment's settings and results
/// as data: what `report` draws again and later experiments read typed) among its files.
pub fn stamp_outcome(
    outcome: &Outcome,
    e: &Entry,
    ctx: &Context,
    sets: &[(String, String)],
    config: Option<&std::path::Path>,
) -> Report {
    // Labelled by the typed settings stored with the results, as Entry::redraw labels them.
    let departures = e
        .departures(&outcome.data)
        .unwrap_or_else(|_| context_departures(ctx));
    let mut stamped = stamp_with(&outcome.report, (e, ctx), sets, config, &departures);
    let mut data = format!("{:#}", outcome.data);
    data.push('\n');
    stamped
        .files
        .push(OutputFile::new(registry::RESULTS_JSON, data));
    stamped
}

/// The readings of the paper the run was made under (the parameters the experiment declares as
/// readings, [`registry::Param::reading`]), whatever their value: `run.json` says which event
/// rule counted and which gear drove.
fn readings(ctx: &Context) -> BTreeMap<&'static str, String> {
    ctx.values()
        .filter(|(p, _)| p.reading)
        .map(|(p, v)| (p.name, v.to_owned()))
        .collect()
}

pub use registry::DEPARTURE;

/// Said of a run whose hypothesis has a `measured` layer without a file: it runs on the example
/// table embedded in the toolkit, whose values are invented.
pub const EXAMPLE_TABLE: &str = "The hypothesis `measured` without a file of your own uses the example table shipped with the toolkit (crates/hypotheses/data/measured-example.ron), whose values are INVENTED: these numbers describe no real mechanism; give your own table with --errors FILE or --hypothesis measured:FILE.";

/// Whether `ctx`'s hypothesis has a `measured` layer without a file ([`EXAMPLE_TABLE`]).
pub fn runs_example_table(ctx: &Context) -> bool {
    ctx.holds(&study::errors::PARAM)
        && ctx
            .text(&study::errors::PARAM)
            .is_ok_and(uses_example_table)
}

/// Whether the hypothesis `h` (a stack `a+b`) has a `measured` layer without a file.
pub fn uses_example_table(h: &str) -> bool {
    hypotheses::stack_layers(h)
        .iter()
        .any(|layer| layer.trim() == "measured")
}

/// SHA-256 of `bytes`, in lowercase hex.
pub fn sha256(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Every file the run read, as `{"role", "path", "sha256"}`: the config file, a gearing file
/// (not an embedded gearing), a measured-errors table (`--errors`, `measured:FILE`, `--set
/// measured=FILE`). The path is as typed; the hash is of the contents, so two runs of the same
/// path with different files are told apart. A file that can no longer be read gets
/// `"sha256": null`.
fn inputs(ctx: &Context) -> Vec<serde_json::Value> {
    let mut out = Vec::new();
    if let Some(c) = ctx.config() {
        out.push(json!({
            "role": "config",
            "path": c.path.display().to_string(),
            "sha256": sha256(c.text.as_bytes()),
        }));
    }
    let files = setting_groups::inputs::files(ctx);
    for (role, path) in files {
        let hash = input_file::read_to_string(Path::new(&path), input_file::MAX_INPUT_BYTES)
            .ok()
            .map(|text| sha256(text.as_bytes()));
        out.push(json!({ "role": role, "path": path, "sha256": hash }));
    }
    out
}

/// `git describe --always --dirty` of the workspace this binary was built from, once per
/// process; `"unknown"` when git or the repository is not there.
pub fn git_describe() -> &'static str {
    static DESCRIBE: OnceLock<String> = OnceLock::new();
    DESCRIBE.get_or_init(|| {
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
        let root = manifest.parent().unwrap_or(manifest);
        std::process::Command::new("git")
            .arg("-C")
            .arg(root)
            .args(["describe", "--always", "--dirty"])
            .stderr(std::process::Stdio::null())
            .output()
            .ok()
            .filter(|o| o.status.success())
            .and_then(|o| String::from_utf8(o.stdout).ok())
            .map(|s| s.trim().to_owned())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "unknown".to_owned())
    })
}

/// The current time in UTC as `YYYY-MM-DDTHH:MM:SSZ`.
pub fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc(secs)
}

/// `secs` after the Unix epoch as `YYYY-MM-DDTHH:MM:SSZ`.
fn utc(secs: u64) -> String {
    let days = secs / 86_400;
    let rem = secs % 86_400;
    let (y, m, d) = civil_from_days(days);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// Year, month and day of `days` after 1970-01-01 (proleptic Gregorian; H. Hinnant's algorithm).
fn civil_from_days(days: u64) -> (u64, u64, u64) {
    let z = days + 719_468;
    let era = z / 146_097;
    let doe = z % 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + u64::from(m <= 2);
    (y, m, d)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use registry::Param;

    const N: Param = Param::new("n", "1", "h", registry::Kind::Text);
    const GEARING: Param = Param::new("gearing", "freeth2006", "h", registry::Kind::Text);
    const HYPOTHESIS: Param = Param::new("hypothesis", "edmunds-split", "h", registry::Kind::Text);

    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
    struct OneN {
        #[param(N)]
        n: String,
    }

    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
    struct Inputs {
        #[param(GEARING)]
        gearing: String,
        #[param(HYPOTHESIS)]
        hypothesis: String,
    }

    registry::test_experiment!(ExpE, "e", "p", OneN);
    registry::test_experiment!(ExpG, "g", "p", Inputs);
    static E: Entry = Entry::of::<ExpE>();
    static G: Entry = Entry::of::<ExpG>();

    #[test]
    fn run_json_hashes_every_input_file() {
        let dir = std::env::temp_dir().join(format!("provenance-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let gearing = dir.join("g.ron");
        let errors = dir.join("e.ron");
        std::fs::write(&gearing, "gearing text").unwrap();
        std::fs::write(&errors, "errors text").unwrap();
        let sets = vec![
            ("gearing".to_string(), gearing.display().to_string()),
            (
                "hypothesis".to_string(),
                format!("measured:{}", errors.display()),
            ),
        ];
        let ctx = Context::new(&G, 1, 1, &sets, None).unwrap();
        let r = stamp(&Report::default(), &G, &ctx, &sets, None);
        let v: serde_json::Value = serde_json::from_slice(&r.files[0].contents).unwrap();
        assert_eq!(
            v["inputs"],
            json!([
                {"role": "gearing", "path": gearing.display().to_string(), "sha256": sha256(b"gearing text")},
                {"role": "measured errors", "path": errors.display().to_string(), "sha256": sha256(b"errors text")},
            ])
        );
        assert_eq!(
            sha256(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn dates() {
        assert_eq!(utc(0), "1970-01-01T00:00:00Z");
        assert_eq!(utc(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(utc(1_700_000_000), "2023-11-14T22:13:20Z");
        assert_eq!(utc(4_102_444_799), "2099-12-31T23:59:59Z");
        assert_eq!(utc_now().len(), 20);
    }

    #[test]
    fn run_json_records_the_run() {
        let sets: Vec<(String, String)> = vec![
            ("n".into(), "2".into()),
            ("other".into(), "x".into()),
            ("n".into(), "5".into()),
        ];
        let ctx = Context::new(&E, 7, 3, &[("n".into(), "5".into())], None).unwrap();
        let mut before = Report::default();
        before.files.push(OutputFile::new(RUN_JSON, "stale"));
        let r = stamp(
            &before,
            &E,
            &ctx,
            &sets,
            Some(std::path::Path::new("c.ron")),
        );
        assert_eq!(r.files.len(), 1);
        let v: serde_json::Value = serde_json::from_slice(&r.files[0].contents).unwrap();
        assert_eq!(v["id"], "e");
        assert_eq!(v["seed"], 7);
        assert_eq!(v["threads"], 3);
        assert_eq!(v["overrides"], json!({"n": "5"}));
        assert_eq!(v["config"], serde_json::Value::Null, "E takes no config");
        assert_eq!(v["inputs"], json!([]));
        assert_eq!(v["version"]["crate"], env!("CARGO_PKG_VERSION"));
        assert!(!v["version"]["git"].as_str().unwrap().is_empty());
        assert_eq!(v["date"].as_str().unwrap().len(), 20);
    }

    /// What a run writes is what its stored results draw again, computing nothing: the tables
    /// (their departure labels too, read from the stored typed settings) and every file.
    #[test]
    fn a_report_is_drawn_again_from_results_json_alone() {
        experiments::link();
        let exps = registry::experiments().unwrap();
        for (id, sets) in [
            ("table3", vec![("trials", "2"), ("clearance", "30")]),
            ("table1", vec![("trials", "2")]),
        ] {
            let e = exps[id];
            let sets: Vec<(String, String)> = sets
                .iter()
                .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
                .collect();
            let ctx = Context::new(e, 2025, 1, &sets, None).unwrap();
            let outcome = (e.run)(&ctx, ctx.engine()).unwrap();
            let written = stamp_outcome(&outcome, e, &ctx, &sets, None);
            let stored = written
                .files
                .iter()
                .find(|f| f.name == registry::RESULTS_JSON)
                .unwrap();
            let data: serde_json::Value = serde_json::from_slice(&stored.contents).unwrap();
            let drawn = e.redraw(&data).unwrap();
            assert_eq!(drawn.text(), written.text(), "{id}");
            assert!(
                written.text().contains(DEPARTURE),
                "{id}: a run off the defaults is labelled"
            );
            let files = |r: &Report| -> Vec<(String, Vec<u8>)> {
                r.files
                    .iter()
                    .filter(|f| f.name != RUN_JSON && f.name != registry::RESULTS_JSON)
                    .map(|f| (f.name.clone(), f.contents.clone()))
                    .collect()
            };
            assert_eq!(files(&drawn), files(&written), "{id}");
            assert_eq!(drawn.agreement, written.agreement, "{id}");
        }
    }
}
