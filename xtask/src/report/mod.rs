//! `cargo xtask report [--out DIR]`: one self-contained HTML page of every experiment's results.
//!
//! Reads each `<out>/<id>/` that holds a `tables.json` (as `run` writes it, see
//! [`registry::write_results`]) and writes `<out>/index.html`: per experiment, in id order, its
//! id, title and paper item (from the registry), its tables as HTML tables (cells exactly as
//! printed, so `ours (paper)` cells and paper columns show the paper's numbers beside ours),
//! every SVG figure embedded inline, links to its other files, and the provenance recorded in
//! `run.json` (seed, threads, overrides, toolkit version, date). Registered experiments without
//! results are listed as "not run". The page needs no network: the CSS is inline and so are the
//! figures. Tables scroll within their box when wider than the page.
//!
//! Tables 3, 4, 5 and I are also shown as heatmaps (jams, disengagements): ours against the
//! paper's per cell, coloured by the two-sample verdict the table marks with `*`. A cell links to
//! a replayed trial of that cell (of this table or another whose cell has the same trials, Table
//! 3's `B/m3-e3` and Table I's `B/40/m3-e3`) that had the heatmap's failure; a differing cell
//! with none links to the commands that write one, which carry the page's `--out`. A run whose inputs differ from the paper's ([`provenance::DEPARTURE`] in its titles) shows
//! no `*` marks, no heatmap, and its notes on agreement labelled for reference only.
//!
//! The page is written through a temporary file renamed into place. Results that cannot be read
//! (malformed `tables.json` or `run.json`, a listed figure missing or empty) are bad input: one
//! line naming the file, the field and the rule, exit status 2, and no page is written; so is an
//! `--out` with no results at all.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use presentation::escape_xml as esc;
use registry::Table;
use serde_json::Value;

use crate::args::ReportArgs;
use crate::failure::Failure;
use crate::provenance::{self, RUN_JSON};
use crate::shared::Registry;
use read::{MAX_RESULT_FILE_BYTES, overview_cell, read_results, scan};
use replays::Replayed;

mod bundle;
#[cfg(test)]
use bundle::archive_path as bundle_path_of;
mod heatmap;
mod order;
mod read;
mod replays;
#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests;
mod verdict;

/// The page's file name in `<out>/`.
pub const INDEX_HTML: &str = "index.html";

/// The report page, as [`render`] writes it: replaced only by another.
pub(crate) const PAGE_KIND: registry::FileKind = registry::FileKind {
    what: "the report page",
    recognise: |head| {
        let title = b"<title>Antikythera gear trains: results</title>";
        head.starts_with(b"<!DOCTYPE html>") && head.windows(title.len()).any(|w| w == title)
    },
};

/// `report [--out DIR] [--bundle FILE]`: builds the page and writes it to `<out>/index.html`,
/// then the bundle. Everything both need is checked first (the page's place and lock, the
/// bundle's, every results folder, every input): a refusal writes neither.
pub fn command(args: &ReportArgs) -> Result<(), Failure> {
    let out = args.out.clone().unwrap_or_else(crate::shared::default_out);
    let quiet = args.quiet;
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    // No results folder at all: said as such, before the check of --out would make one.
    let out_flag = out_flag(args.out.as_deref());
    if !out.exists() {
        build(&exps, &out, &out_flag, quiet)?;
    }
    // The page's run lock ends with the command (also when it is called on its own, in tests).
    let _locked = crate::shared::LocksEnd;
    // The page can be written there (checked before the results are read), and results a
    // killed run left moved aside are put back before they are read.
    crate::plan::check_out(
        &out,
        &[crate::plan::Target::File(INDEX_HTML.into(), &PAGE_KIND)],
    )?;
    let bundle = match &args.bundle {
        Some(file) => Some(bundle::plan(&out, file)?),
        None => None,
    };
    let page = build(&exps, &out, &out_flag, quiet)?;
    let index = out.join(INDEX_HTML);
    crate::shared::write_atomically(&index, &PAGE_KIND, page.as_bytes())?;
    if !quiet {
        crate::progress::say(&format!("report: {}", index.display()));
    }
    if let (Some(plan), Some(file)) = (bundle, &args.bundle) {
        bundle::write(&plan, page.as_bytes())?;
        if !quiet {
            crate::progress::say(&format!("bundle: {}", file.display()));
        }
    }
    Ok(())
}

/// The message of a failure, for a note.
fn one_line_of(f: &Failure) -> String {
    match f {
        Failure::Usage(m) | Failure::Bad(m) | Failure::Internal(m) => m.clone(),
        Failure::Reported(code) => format!("exit status {code}"),
    }
}

/// One experiment's results as read from `<out>/<id>/`.
#[derive(Debug)]
struct Results {
    tables: Vec<Table>,
    trials: u64,
    engagements: u64,
    /// The paper's numbers consistent with ours, those that differ, and what they count.
    agreement: Option<(u64, u64, String)>,
    /// The smallest and largest ratio of ours to the paper's its tables print (a column
    /// `ours/paper`), for an experiment that judges no agreement.
    ratios: Option<(f64, f64)>,
    /// Every file of the directory, sorted.
    files: Vec<String>,
    /// SVG figures in the experiment's order: file name and how it is embedded.
    figures: Vec<(String, Embed)>,
    run: Option<Provenance>,
}

/// What `run.json` records.
#[derive(Debug)]
struct Provenance {
    seed: u64,
    threads: u64,
    overrides: Vec<(String, String)>,
    config: Option<String>,
    version: String,
    git: String,
    date: String,
}

/// How a figure goes into the page.
#[derive(Debug, PartialEq, Eq)]
enum Embed {
    /// The SVG element itself, prolog removed.
    Inline(String),
    /// An SVG that carries scripts or is not a bare `<svg>` element: an `<img>` with a
    /// `data:` URI (still self-contained; an image runs no script).
    DataUri(String),
}

fn bad(path: &Path, field: &str, rule: impl std::fmt::Display) -> Failure {
    if field.is_empty() {
        Failure::Bad(format!("{}: {rule}", path.display()))
    } else {
        Failure::Bad(format!("{}: {field}: {rule}", path.display()))
    }
}

/// ` --out DIR` for the commands the page prints, where it was built with `--out DIR` (so that
/// a replay run as printed lands beside the page, which then links it); empty at the default.
fn out_flag(out: Option<&Path>) -> String {
    match out {
        Some(dir) => format!(" --out {}", shell_word(&dir.to_string_lossy())),
        None => String::new(),
    }
}

/// `s` as one word of a POSIX shell: as it is when it holds only characters no shell treats
/// specially, else in single quotes.
fn shell_word(s: &str) -> String {
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./:=+,@%".contains(c));
    if plain {
        s.to_owned()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// The HTML page for the results under `out`; `out_flag` is what its commands carry to write
/// there ([`out_flag`]).
fn build(exps: &Registry, out: &Path, out_flag: &str, quiet: bool) -> Result<String, Failure> {
    let (found, replays) = replays::split_replays(exps, scan(out)?);
    if found.is_empty() {
        return Err(Failure::Bad(format!(
            "--out: {}: no results (no <id>/tables.json); run `cargo xtask run <id> --out {}` first",
            out.display(),
            out.display()
        )));
    }
    let mut results = BTreeMap::new();
    for (id, dir) in &found {
        // One version of the folder, should a run put new results in its place meanwhile.
        match registry::read_one_version(dir, || read_results(dir)) {
            Ok(r) => {
                results.insert(id.clone(), r);
            }
            // A folder that is no experiment of this build (a stray copy, an old id) is
            // skipped when unreadable rather than failing the whole page.
            Err(e) if !exps.contains_key(id.as_str()) => {
                if !quiet {
                    crate::progress::say(&format!(
                        "report: skipped {}: not an experiment of this build and unreadable: {}",
                        dir.display(),
                        one_line_of(&e)
                    ));
                }
            }
            Err(e) => return Err(e),
        }
    }
    let mut ids: Vec<String> = exps.keys().map(|id| (*id).to_owned()).collect();
    ids.extend(results.keys().cloned());
    ids.sort();
    ids.dedup();
    let ids = order::in_paper_order(ids, exps);
    let verdict = verdict::read(out)?;
    let links = heatmap::Links {
        exps,
        replays: &replays,
        out_flag: out_flag.to_owned(),
    };
    Ok(render(exps, &ids, &results, &links, verdict.as_ref()))
}

fn is_svg(name: &str) -> bool {
    name.to_ascii_lowercase().ends_with(".svg")
}

/// Does the SVG draw anything: a path, polyline, polygon or line element?
pub fn has_drawing(svg: &str) -> bool {
    let lower = svg.to_ascii_lowercase();
    lower.contains("<svg")
        && ["<path", "<polyline", "<polygon", "<line"]
            .iter()
            .any(|t| lower.contains(t))
}

/// The SVG element of `text` without XML declaration, doctype or leading comments; inline
/// unless it could run a script.
fn embed_svg(text: &str) -> Embed {
    let mut rest = text.trim_start_matches('\u{feff}');
    loop {
        rest = rest.trim_start();
        let skip = if rest.starts_with("<?") {
            rest.find("?>").map(|i| i + 2)
        } else if rest.starts_with("<!--") {
            rest.find("-->").map(|i| i + 3)
        } else if rest.len() >= 9 && rest[..9].eq_ignore_ascii_case("<!doctype") {
            rest.find('>').map(|i| i + 1)
        } else {
            break;
        };
        match skip {
            Some(i) => rest = &rest[i..],
            None => break,
        }
    }
    let lower = rest.to_ascii_lowercase();
    let scripted = [
        "<script",
        "foreignobject",
        "javascript:",
        "<iframe",
        "<!entity",
    ]
    .iter()
    .any(|t| lower.contains(t))
        || has_event_handler(&lower);
    if lower.starts_with("<svg") && !scripted {
        Embed::Inline(rest.trim_end().to_owned())
    } else {
        Embed::DataUri(format!(
            "data:image/svg+xml;base64,{}",
            base64(text.as_bytes())
        ))
    }
}

/// An attribute `on...=` (an event handler) anywhere in the lower-cased text.
fn has_event_handler(lower: &str) -> bool {
    let b = lower.as_bytes();
    lower.match_indices("on").any(|(i, _)| {
        let before_ok = i > 0 && b[i - 1].is_ascii_whitespace();
        let mut j = i + 2;
        while j < b.len() && b[j].is_ascii_lowercase() {
            j += 1;
        }
        while j < b.len() && b[j].is_ascii_whitespace() {
            j += 1;
        }
        before_ok && j > i + 2 && j < b.len() && b[j] == b'='
    })
}

/// Standard base64 with padding.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &b)| n | (u32::from(b) << (16 - 8 * i)));
        for k in 0..4 {
            if k <= chunk.len() {
                s.push(char::from(ALPHABET[(n >> (18 - 6 * k)) as usize & 63]));
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// `s` percent-encoded for one segment of a relative URL.
fn url_part(s: &str) -> String {
    let mut o = String::new();
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            o.push(char::from(b));
        } else {
            let _ = write!(o, "%{b:02X}");
        }
    }
    o
}

/// Does the cell read as a number (right-aligned)?
fn numeric(cell: &str) -> bool {
    let t = cell.trim_start_matches(['<', '>', '~', '+', '-', '\u{2212}', '\u{2248}', ' ']);
    t.starts_with(|c: char| c.is_ascii_digit())
}

const CSS: &str = "
body { font-family: system-ui, -apple-system, 'Segoe UI', Roboto, sans-serif; margin: 0 auto;
  max-width: 1200px; padding: 1em 2em 3em; color: #1b1b1b; background: #fff; line-height: 1.4; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.3em; border-bottom: 2px solid #c9d3e0; padding-bottom: 0.2em; margin-top: 2em; }
.meta { color: #444; margin: 0.2em 0; }
.meta code, .files code { background: #f2f4f7; padding: 0 0.25em; border-radius: 3px; }
.table-wrap { max-width: 100%; overflow-x: auto; margin: 0.2em 0 0.8em; }
table { border-collapse: collapse; margin: 0; font-size: 0.92em; }
caption, .table-title { caption-side: top; text-align: left; font-weight: 600; padding: 0.3em 0; }
.table-title { margin: 1em 0 0; }
th, td { border: 1px solid #c9d3e0; padding: 0.25em 0.6em; vertical-align: top; }
th { background: #eef2f7; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
th.paper, td.paper { background: #fff7e0; }
ul.notes { margin: 0.2em 0 1.2em; color: #444; font-size: 0.88em; }
figure { margin: 1em 0; }
figure svg, figure img { max-width: 100%; height: auto; border: 1px solid #e3e8ef; }
figcaption { color: #555; font-size: 0.85em; }
.not-run .status { color: #a33; font-weight: 600; }
table.toc td.status-run { color: #1d6b2f; white-space: nowrap; }
table.toc td.status-not-run { color: #a33; white-space: nowrap; }
table.toc td.agreement { font-size: 0.88em; min-width: 16em; }
.files { font-size: 0.85em; color: #555; }
footer { margin-top: 3em; color: #777; font-size: 0.85em; }
.reference { background: #fff3cd; border: 1px solid #e0c36a; padding: 0.4em 0.7em; }
table.heatmap { font-size: 0.8em; }
table.heatmap th { white-space: nowrap; }
table.heatmap tbody th { white-space: normal; min-width: 5em; }
.table-wrap.wide table.heatmap td, .table-wrap.wide table.heatmap th { padding: 0.2em 0.25em; }
.hm { text-align: center; white-space: nowrap; font-variant-numeric: tabular-nums; }
.hm.consistent { background: #d9efd3; }
.hm.differs { background: #c0392b; color: #fff; font-weight: 600; }
.hm.differs a { color: #fff; }
.hm.none { background: #eeeeee; color: #666; }
.hm.apart { background: repeating-linear-gradient(135deg, #f4f4f4 0 4px, #e2e2e2 4px 8px); color: #444; }
.hm.rule-differs { outline: 2px dashed #111; outline-offset: -4px; }
.heat-key .hm { padding: 0 0.5em; border: 1px solid #c9d3e0; }
ul.replay-commands { font-size: 0.85em; }
ul.replay-commands li { margin: 0.2em 0; }
.table-wrap.wide { width: calc(100vw - 4em); margin-left: calc(50% - 50vw + 2em); }
.table-wrap.wide table { font-size: 0.8em; }
.table-wrap.wide th, .table-wrap.wide td { padding: 0.2em 0.35em; }
td .paper-part { color: #6b5200; }
.table-wrap { background: linear-gradient(to right, #fff 30%, rgba(255,255,255,0)) left / 2em 100% no-repeat local,
  linear-gradient(to left, #fff 30%, rgba(255,255,255,0)) right / 2em 100% no-repeat local,
  linear-gradient(to right, rgba(0,0,0,0.18), rgba(0,0,0,0)) left / 0.8em 100% no-repeat scroll,
  linear-gradient(to left, rgba(0,0,0,0.18), rgba(0,0,0,0)) right / 0.8em 100% no-repeat scroll; }
details.not-run-list { margin-top: 2.5em; border-top: 2px solid #c9d3e0; padding-top: 0.5em; }
details.not-run-list summary { cursor: pointer; font-weight: 600; color: #a33; }
";

/// The whole page.
fn render(
    exps: &Registry,
    ids: &[String],
    results: &BTreeMap<String, Results>,
    links: &heatmap::Links<'_>,
    verdict: Option<&verdict::VerdictScreen>,
) -> String {
    let mut h = String::new();
    let now = provenance::utc_now();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
<title>Antikythera gear trains: results</title>\n<style>{CSS}{}</style>\n</head>\n<body>\n\
<header>\n<h1>Antikythera gear trains: results</h1>\n\
<p class=\"meta\">A reproduction of Szigety &amp; Arenas, <i>The Impact of Triangular-Toothed Gears on the \
Functionality of the Antikythera Mechanism</i>. Our numbers are printed as computed; the paper's numbers \
appear in columns labelled &ldquo;paper&rdquo; or in parentheses, as in the printed tables.</p>\n\
<p class=\"meta\">{} of {} experiments have results. Page written {} by xtask {} (git <code>{}</code>).</p>\n\
</header>\n",
        verdict::CSS,
        results.len(),
        ids.len(),
        esc(&now),
        esc(env!("CARGO_PKG_VERSION")),
        esc(provenance::git_describe())
    );

    if let Some(v) = verdict {
        verdict::block(&mut h, v);
    }

    contents(&mut h, exps, ids, results);
    h.push_str("</tbody>\n</table>\n</div>\n</nav>\n<main>\n");

    // The experiments that were run, in the paper's order; then, collapsed, those that were not.
    for id in ids {
        if let Some(r) = results.get(id) {
            let (title, item) = describe(exps, id);
            let listed = links
                .replays
                .get(id.as_str())
                .map_or(&[][..], Vec::as_slice);
            section(&mut h, (id, title, item), r, links);
            replay_links(&mut h, listed);
        }
    }
    not_run_list(&mut h, exps, ids, results);
    let _ = write!(
        h,
        "</main>\n<footer>Generated by <code>cargo xtask report</code> at {}. Each section's files are linked relative to this page.</footer>\n</body>\n</html>\n",
        esc(&now)
    );
    h
}

/// The page's overview: a row per experiment, its status, its seed and how its numbers
/// compare with the paper's ([`overview_cell`]).
fn contents(h: &mut String, exps: &Registry, ids: &[String], results: &BTreeMap<String, Results>) {
    h.push_str("<nav>\n<div class=\"table-wrap\">\n<table class=\"toc\">\n<caption>Experiments</caption>\n<thead><tr><th>id</th><th>paper item</th><th>title</th><th>status</th><th>seed</th><th>against the paper: consistent / differing, and what is counted</th></tr></thead>\n<tbody>\n");
    for id in ids {
        let (title, item) = describe(exps, id);
        let r = results.get(id);
        let (status, class) = if r.is_some() {
            ("run", "status-run")
        } else {
            ("not run", "status-not-run")
        };
        let seed = r
            .and_then(|r| r.run.as_ref())
            .map_or_else(|| "-".to_owned(), |p| p.seed.to_string());
        // A stub of an experiment not run sits in the closed list at the end: the link opens it.
        let anchor = if r.is_some() {
            format!("exp-{id}")
        } else {
            "not-run".to_owned()
        };
        let _ = writeln!(
            h,
            "<tr><td><a href=\"#{}\">{}</a></td><td>{}</td><td>{}</td><td class=\"{class}\">{status}</td><td class=\"num\">{}</td><td class=\"agreement\">{}</td></tr>",
            esc(&anchor),
            esc(id),
            esc(item),
            esc(title),
            esc(&seed),
            esc(&overview_cell(r))
        );
    }
}

/// The experiments not run, collapsed at the end of the page.
fn not_run_list(
    h: &mut String,
    exps: &Registry,
    ids: &[String],
    results: &BTreeMap<String, Results>,
) {
    let not_run: Vec<&String> = ids.iter().filter(|id| !results.contains_key(*id)).collect();
    if not_run.is_empty() {
        return;
    }
    let _ = writeln!(
        h,
        "<details id=\"not-run\" class=\"not-run-list\">\n<summary>Not run: {} experiment{} (<code>cargo xtask run ID --out DIR</code>, then <code>cargo xtask report --out DIR</code> again)</summary>",
        not_run.len(),
        if not_run.len() == 1 { "" } else { "s" }
    );
    for id in not_run {
        let (title, item) = describe(exps, id);
        let _ = write!(
            h,
            "<section id=\"exp-{}\" class=\"experiment not-run\">\n<h2>{}: {}</h2>\n\
<p class=\"meta\">Paper item: {}</p>\n<p class=\"status\">not run</p>\n</section>\n",
            esc(id),
            esc(id),
            esc(title),
            esc(item)
        );
    }
    h.push_str("</details>\n");
}

/// Title and paper item from the registry.
fn describe<'a>(exps: &'a Registry, id: &str) -> (&'a str, &'a str) {
    exps.get(id)
        .map_or(("(not a registered experiment)", "-"), |e| {
            (e.title, e.paper_item)
        })
}

/// Links to an experiment's replayed trials (after its section): each trial's moving page,
/// named with what the trial did, and each listing of a cell's failed trials drawn on this page
/// (its table, as `replay` printed it), where the link leads.
fn replay_links(h: &mut String, replays: &[Replayed]) {
    if replays.is_empty() {
        return;
    }
    let mut listings = String::new();
    let links: Vec<String> = replays
        .iter()
        .map(|r| {
            if r.page {
                let did = r.trial.as_ref().map_or(String::new(), |t| {
                    let what = match (t.jammed, t.disengaged) {
                        (true, true) => "jammed and disengaged",
                        (true, false) => "jammed",
                        (false, true) => "disengaged",
                        (false, false) => "neither",
                    };
                    format!(" ({what})")
                });
                return format!(
                    "<a href=\"{}/pair.html\">{}</a>{}",
                    url_part(&r.folder),
                    esc(&r.folder),
                    esc(&did)
                );
            }
            match read_results(&r.dir) {
                Ok(listing) => {
                    let _ = writeln!(
                        listings,
                        "<details class=\"listing\" id=\"listing-{}\"><summary>{}: the cell's failed trials (<a href=\"{}/failed-trials.csv\">failed-trials.csv</a>)</summary>",
                        esc(&r.folder),
                        esc(&r.folder),
                        url_part(&r.folder)
                    );
                    for t in &listing.tables {
                        table(&mut listings, t, false);
                    }
                    listings.push_str("</details>\n");
                    format!(
                        "<a href=\"#listing-{}\">{}</a> (a listing)",
                        esc(&r.folder),
                        esc(&r.folder)
                    )
                }
                Err(_) => format!(
                    "<a href=\"{}/failed-trials.csv\">{}</a> (a listing)",
                    url_part(&r.folder),
                    esc(&r.folder)
                ),
            }
        })
        .collect();
    let _ = writeln!(
        h,
        "<p class=\"replays\">Replayed trials (<code>cargo xtask replay</code>; each page shows the gears moving through the trial): {}</p>",
        links.join(", ")
    );
    h.push_str(&listings);
}

fn section(
    h: &mut String,
    (id, title, item): (&str, &str, &str),
    r: &Results,
    links: &heatmap::Links<'_>,
) {
    // The registered title states the defaults ("200 trials per cell"); a run that changed
    // them is headed by its first table's title, which states what was run.
    let changed = r.run.as_ref().is_some_and(|p| !p.overrides.is_empty());
    let reference = departs(r);
    let first = r.tables.first().map(|t| {
        if reference {
            without_marks(&t.title)
        } else {
            t.title.clone()
        }
    });
    let title = match &first {
        Some(t) if changed => t.as_str(),
        _ => title,
    };
    let _ = write!(
        h,
        "<section id=\"exp-{}\" class=\"experiment run\">\n<h2>{}: {}</h2>\n<p class=\"meta\">Paper item: {}</p>\n",
        esc(id),
        esc(id),
        esc(title),
        esc(item)
    );
    provenance_line(h, r.run.as_ref());
    facts_line(h, r);
    if reference {
        h.push_str(REFERENCE_BANNER);
    }
    for (i, t) in r.tables.iter().enumerate() {
        table(h, t, reference);
        if i == 0 {
            heatmap::heatmaps(h, id, t, r, links, reference);
        }
    }
    figures_and_files(h, id, r);
    h.push_str("</section>\n");
}

/// The line that says what produced a section's results: seed, threads, settings, version.
fn provenance_line(h: &mut String, run: Option<&Provenance>) {
    let Some(p) = run else {
        h.push_str(
            "<p class=\"meta provenance\">Provenance not recorded (no run.json: these results predate it).</p>\n",
        );
        return;
    };
    let overrides = if p.overrides.is_empty() {
        "none (defaults)".to_owned()
    } else {
        p.overrides
            .iter()
            .map(|(k, v)| format!("<code>{}={}</code>", esc(k), esc(v)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let config = p.config.as_ref().map_or_else(String::new, |c| {
        format!("; config file <code>{}</code>", esc(c))
    });
    let _ = writeln!(
        h,
        "<p class=\"meta provenance\">Produced with seed <b>{}</b>, {} thread{}, overrides: {overrides}{config}; \
xtask {} (git <code>{}</code>), {}.</p>",
        p.seed,
        p.threads,
        if p.threads == 1 { "" } else { "s" },
        esc(&p.version),
        esc(&p.git),
        esc(&p.date)
    );
}

/// A section's facts: its trials, tooth engagements and how its numbers compare with the
/// paper's.
fn facts_line(h: &mut String, r: &Results) {
    let mut facts = Vec::new();
    if r.trials > 0 {
        facts.push(format!("trials: {}", r.trials));
    }
    if r.engagements > 0 {
        facts.push(format!("tooth engagements: {}", r.engagements));
    }
    if r.agreement.is_some() || r.ratios.is_some() {
        facts.push(format!("against the paper: {}", overview_cell(Some(r))));
    }
    if !facts.is_empty() {
        let _ = writeln!(h, "<p class=\"meta\">{}</p>", esc(&facts.join("; ")));
    }
}

/// A section's figures, each embedded with a link to its file, and the links to all its files.
fn figures_and_files(h: &mut String, id: &str, r: &Results) {
    for (name, embed) in &r.figures {
        let file = format!("{id}/{name}");
        let _ = writeln!(h, "<figure data-file=\"{}\">", esc(&file));
        match embed {
            Embed::Inline(svg) => h.push_str(svg),
            Embed::DataUri(uri) => {
                let _ = write!(h, "<img src=\"{}\" alt=\"{}\">", esc(uri), esc(name));
            }
        }
        let _ = write!(
            h,
            "\n<figcaption><a href=\"{}/{}\">{}</a></figcaption>\n</figure>\n",
            url_part(id),
            url_part(name),
            esc(name)
        );
    }
    let links: Vec<String> = r
        .files
        .iter()
        .map(|f| {
            format!(
                "<a href=\"{}/{}\"><code>{}</code></a>",
                url_part(id),
                url_part(f),
                esc(f)
            )
        })
        .collect();
    let _ = writeln!(h, "<p class=\"files\">Files: {}</p>", links.join(" "));
}

/// Has this run inputs other than the paper's ([`provenance::stamp`] says so in every title)?
fn departs(r: &Results) -> bool {
    r.tables
        .iter()
        .any(|t| t.title.contains(provenance::DEPARTURE))
}

/// Said at the top of a run whose inputs differ from the paper's.
const REFERENCE_BANNER: &str = "<p class=\"reference\">This run's inputs differ from the paper's: \
the paper's numbers beside ours are for reference only, not a check of these. No marks of a test \
against the paper (<code>*</code>), no agreement figures and no heatmap are shown.</p>\n";

/// A title without its phrase on the marks (`; * where ...`, up to the next bracket), for a run
/// whose marks are not shown.
fn without_marks(title: &str) -> String {
    match title.find("; * where") {
        Some(i) => {
            // Up to the next phrase of the title that is no test's mark (the 1 % rule's `✓`
            // stays: it judges each side on its own) or the next bracket.
            let end = [" [", "; ✓"]
                .iter()
                .filter_map(|p| title[i + 1..].find(p).map(|j| i + 1 + j))
                .min()
                .unwrap_or(title.len());
            format!("{}{}", &title[..i], &title[end..])
        }
        None => title.to_owned(),
    }
}

/// Does the note state agreement with the paper (figures or marks of a test)?
fn states_agreement(note: &str) -> bool {
    note.contains("consistent with ours")
        || note.contains("`*`")
        || note.contains("counted as agreement")
        || note.contains("agree with the paper")
}

/// A table with more columns than this is drawn the window's width ([`table`]).
const WIDE_COLUMNS: usize = 10;

/// The width a wide table may take, px: a 1280 px window less the page's margins. A wider one
/// is drawn in parts, each with the table's label columns ([`column_groups`]), so that no
/// column is cut off at the right.
const WIDE_ROOM: f64 = 1180.0;

/// The lines a cell shows: in a wide table an `ours (paper)` cell breaks before the paper's
/// part and a `jams / disengagements` cell (with their intervals) after the ` / `.
fn cell_lines(cell: &str, wide: bool) -> Vec<String> {
    if !wide {
        return vec![cell.to_owned()];
    }
    if let Some((ours, theirs)) = cell.split_once(" (") {
        return vec![ours.to_owned(), format!("({theirs}")];
    }
    if cell.contains(" [")
        && let Some((jams, dis)) = cell.split_once(" / ")
    {
        return vec![format!("{jams} /"), dis.to_owned()];
    }
    vec![cell.to_owned()]
}

/// The width a column of a wide table takes, about, px: its widest line at the wide tables'
/// 0.8 em type (digits some 8 px) and its padding.
fn column_px(t: &Table, c: usize) -> f64 {
    let widest = std::iter::once(t.columns[c].clone())
        .chain(
            t.rows
                .iter()
                .filter_map(|r| r.get(c))
                .flat_map(|cell| cell_lines(cell, true)),
        )
        .map(|l| l.chars().count())
        .max()
        .unwrap_or(0);
    8.0 * widest as f64 + 14.0
}

/// The label columns a wide table repeats in each of its parts: those before the first whose
/// header names a mesh (`b2-c1`), at least one.
fn label_columns(t: &Table) -> usize {
    t.columns
        .iter()
        .position(|c| c.contains('-'))
        .unwrap_or(1)
        .clamp(1, 3)
}

/// The columns of table `t` after its `lead` label columns, in groups that each fit
/// [`WIDE_ROOM`] beside the label columns (one group where the table fits as it is).
fn column_groups(t: &Table, lead: usize) -> Vec<std::ops::Range<usize>> {
    let labels: f64 = (0..lead.min(t.columns.len()))
        .map(|c| column_px(t, c))
        .sum();
    let mut groups = Vec::new();
    let (mut start, mut used) = (lead, labels);
    for c in lead..t.columns.len() {
        let w = column_px(t, c);
        if c > start && used + w > WIDE_ROOM {
            groups.push(start..c);
            (start, used) = (c, labels);
        }
        used += w;
    }
    if start < t.columns.len() || groups.is_empty() {
        groups.push(start..t.columns.len());
    }
    groups
}

/// One table. With `reference` (a run on other inputs than the paper's) its cells lose their
/// `*` marks, its title the phrase on them, and its notes on agreement are labelled for
/// reference only. A table of many columns (the 15 meshes) takes the window's width, its cells
/// broken onto lines, and, where it is still too wide, is drawn in parts of its columns.
fn table(h: &mut String, t: &Table, reference: bool) {
    let title = if reference {
        without_marks(&t.title)
    } else {
        t.title.clone()
    };
    let wide = t.columns.len() > WIDE_COLUMNS;
    if !wide {
        let _ = writeln!(h, "<p class=\"table-title\">{}</p>", esc(&title));
        table_part(h, t, (0..0, 0..t.columns.len()), reference, false);
    } else {
        let lead = label_columns(t);
        let groups = column_groups(t, lead);
        for (i, g) in groups.iter().enumerate() {
            let part = if groups.len() == 1 {
                String::new()
            } else {
                format!(
                    " (part {} of {}: {} to {})",
                    i + 1,
                    groups.len(),
                    t.columns[g.start],
                    t.columns[g.end - 1]
                )
            };
            let _ = writeln!(
                h,
                "<p class=\"table-title\">{}{}</p>",
                esc(&title),
                esc(&part)
            );
            table_part(h, t, (0..lead, g.clone()), reference, true);
        }
    }
    table_notes(h, t, reference);
}

/// The columns `labels` and `group` of table `t` as an HTML table (see [`table`]).
fn table_part(
    h: &mut String,
    t: &Table,
    (labels, group): (std::ops::Range<usize>, std::ops::Range<usize>),
    reference: bool,
    wide: bool,
) {
    let columns: Vec<usize> = labels.chain(group).collect();
    let paper = |c: usize| t.columns[c].to_ascii_lowercase().contains("paper");
    let _ = write!(
        h,
        "<div class=\"table-wrap{}\">\n<table>\n<thead><tr>",
        if wide { " wide" } else { "" }
    );
    for &c in &columns {
        let class = if paper(c) { " class=\"paper\"" } else { "" };
        let _ = write!(h, "<th{class}>{}</th>", esc(&t.columns[c]));
    }
    h.push_str("</tr></thead>\n<tbody>\n");
    for row in &t.rows {
        h.push_str("<tr>");
        for &c in &columns {
            let cell = row.get(c).map_or("", String::as_str);
            let unmarked;
            let cell = if reference {
                unmarked = cell.replace('*', "");
                unmarked.trim_end()
            } else {
                cell
            };
            let mut classes = Vec::new();
            if numeric(cell) {
                classes.push("num");
            }
            if paper(c) {
                classes.push("paper");
            }
            let lines = cell_lines(cell, wide);
            let text = match lines.as_slice() {
                [ours, theirs] if theirs.starts_with('(') => format!(
                    "{}<br><span class=\"paper-part\">{}</span>",
                    esc(ours),
                    esc(theirs)
                ),
                _ => lines
                    .iter()
                    .map(|l| esc(l))
                    .collect::<Vec<_>>()
                    .join("<br>"),
            };
            if classes.is_empty() {
                let _ = write!(h, "<td>{text}</td>");
            } else {
                let _ = write!(h, "<td class=\"{}\">{text}</td>", classes.join(" "));
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody>\n</table>\n</div>\n");
}

/// The notes under a table; with `reference`, a note on agreement labelled for reference only.
fn table_notes(h: &mut String, t: &Table, reference: bool) {
    if t.notes.is_empty() {
        return;
    }
    h.push_str("<ul class=\"notes\">\n");
    for n in &t.notes {
        if reference && states_agreement(n) {
            let _ = writeln!(
                h,
                "<li><b>For reference only, not a check (this run's inputs differ from the paper's; its marks are not shown):</b> {}</li>",
                esc(n)
            );
        } else {
            let _ = writeln!(h, "<li>{}</li>", esc(n));
        }
    }
    h.push_str("</ul>\n");
}
