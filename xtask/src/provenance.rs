//! `run.json`: what produced a results directory (id, seed, threads, overrides, config file,
//! toolkit version, date), stored beside its tables so that `cargo xtask report` can show it.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;
use std::time::{SystemTime, UNIX_EPOCH};

use registry::{Context, Experiment, OutputFile, Report};
use serde_json::json;

/// The file name of the provenance record in `<out>/<id>/`.
pub const RUN_JSON: &str = "run.json";

/// `report` with `run.json` added to its files, for [`registry::write_results`] to store with
/// the rest (so it is written, or not, atomically with the tables).
///
/// Overrides are the `--set` pairs `e` declares (a later pair wins, as in [`Context::new`]);
/// the config file is recorded only for an experiment that takes one.
pub fn stamp(
    report: &Report,
    e: &Experiment,
    ctx: &Context,
    sets: &[(String, String)],
    config: Option<&std::path::Path>,
) -> Report {
    let overrides: BTreeMap<&str, &str> = sets
        .iter()
        .filter(|(k, _)| e.params.iter().any(|p| p.name == k))
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
            "config": config,
            "version": {
                "crate": env!("CARGO_PKG_VERSION"),
                "git": git_describe(),
            },
            "date": utc_now(),
        })
    );
    text.push('\n');
    let mut stamped = report.clone();
    stamped.files.retain(|f| f.name != RUN_JSON);
    stamped.files.push(OutputFile::new(RUN_JSON, text));
    stamped
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

    fn nothing(_: &Context) -> Result<Report, registry::RunError> {
        Ok(Report::default())
    }

    static E: Experiment = Experiment {
        id: "e",
        title: "t",
        paper_item: "p",
        params: &[Param {
            name: "n",
            default: "1",
            unit: "",
            help: "h",
        }],
        config: None,
        run: nothing,
    };

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
        assert_eq!(v["version"]["crate"], env!("CARGO_PKG_VERSION"));
        assert!(!v["version"]["git"].as_str().unwrap().is_empty());
        assert_eq!(v["date"].as_str().unwrap().len(), 20);
    }
}
