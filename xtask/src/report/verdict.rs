//! The page's first screen: the verdict on the paper's claims (the `claims` ledger, read typed
//! from its stored results) beside the drawing of the train coloured by each mesh's margin.

use std::fmt::Write as _;
use std::path::Path;

use study::claims::{Ledger, Verdict};

use crate::failure::Failure;

use presentation::escape_xml as esc;

use super::{MAX_RESULT_FILE_BYTES, bad};

/// The ledger and the drawing of the train, as `claims` stored them.
pub(super) struct VerdictScreen {
    ledger: Ledger,
    /// The train's SVG, inline.
    train: Option<String>,
}

/// The ledger stored under `out/claims/`, if `claims` was run there: one version of the folder,
/// should a run put new results in its place meanwhile.
pub(super) fn read(out: &Path) -> Result<Option<VerdictScreen>, Failure> {
    let dir = out.join("claims");
    registry::read_one_version(&dir, || read_from(&dir))
}

/// [`read`] of the folder `dir`. A `results.json` that is there but cannot be read as a file (a
/// folder, a link that leads nowhere) is refused naming it: the page would say the claims were
/// not judged.
fn read_from(dir: &Path) -> Result<Option<VerdictScreen>, Failure> {
    let path = dir.join(registry::RESULTS_JSON);
    match std::fs::metadata(&path) {
        Ok(m) if m.is_file() => {}
        Ok(_) => return Err(bad(&path, "", "must be a file")),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            if std::fs::symlink_metadata(&path).is_ok() {
                return Err(bad(&path, "", format!("cannot be read ({e})")));
            }
            return Ok(None);
        }
        Err(e) => return Err(bad(&path, "", format!("cannot be read ({e})"))),
    }
    let text = input_file::read_to_string(&path, MAX_RESULT_FILE_BYTES)
        .map_err(|e| bad(&path, "", format!("cannot read: {e}")))?;
    let data: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| bad(&path, "", format!("not valid JSON: {e}")))?;
    let ledger: Ledger = serde_json::from_value(data["results"].clone())
        .map_err(|e| bad(&path, "results", format!("is not the claims ledger: {e}")))?;
    let svg = dir.join("train.svg");
    let train = if svg.is_file() {
        Some(
            input_file::read_to_string(&svg, MAX_RESULT_FILE_BYTES)
                .map_err(|e| bad(&svg, "", format!("cannot read: {e}")))?,
        )
    } else {
        None
    };
    Ok(Some(VerdictScreen { ledger, train }))
}

fn class(v: Verdict) -> &'static str {
    match v {
        Verdict::Holds => "v-holds",
        Verdict::HoldsInPart => "v-part",
        Verdict::Differs => "v-differs",
        Verdict::NotTestable => "v-untestable",
    }
}

/// The first screen: each claim's verdict (and under each reading), then the train.
pub(super) fn block(h: &mut String, v: &VerdictScreen) {
    h.push_str("<section id=\"verdict\" class=\"verdict\">\n<h2>The verdict: the paper's claims against our results</h2>\n<div class=\"table-wrap\">\n<table class=\"verdict-table\">\n<thead><tr><th>claim</th><th>verdict</th><th>the paper says</th>");
    for r in v.ledger.readings.iter().skip(1) {
        let _ = write!(h, "<th class=\"reading\">under {}</th>", esc(r));
    }
    h.push_str("</tr></thead>\n<tbody>\n");
    for c in &v.ledger.claims {
        let _ = write!(
            h,
            "<tr><td><a href=\"#exp-claims\">{}</a></td><td class=\"verdict-cell {}\" title=\"{}\">{}</td><td class=\"claim-words\" title=\"{}\">{}</td>",
            esc(&c.id),
            class(c.judged.verdict),
            esc(&c.judged.reason),
            esc(c.judged.verdict.words()),
            esc(&c.words),
            esc(&c.words)
        );
        for u in c.under.iter().skip(1) {
            let _ = write!(
                h,
                "<td class=\"reading {}\">{}</td>",
                class(*u),
                esc(u.words())
            );
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody>\n</table>\n</div>\n<p class=\"meta\">Each verdict is computed by the <code>claims</code> run from the other experiments' results; hover a verdict for its reason, and see the ledger's section below for the paper's figure and ours.</p>\n");
    if let Some(svg) = &v.train {
        let _ = writeln!(
            h,
            "<figure class=\"train\">{}</figure>",
            svg.trim_start_matches(|c| c != '<')
        );
    }
    h.push_str("</section>\n");
}

/// The verdicts' colours and the compact table of the first screen: a claim a line (its words
/// cut to the column, whole on hover), so that at 1400x1000 the ledger of a dozen claims, its
/// verdict column and the train all stand on the first screenful.
pub(super) const CSS: &str = "
section.verdict h2 { margin-top: 0.6em; }
section.verdict .meta { font-size: 0.85em; }
.verdict-table td, .verdict-table th { font-size: 0.82em; padding: 1px 6px; line-height: 1.3; }
.verdict-table .claim-words { max-width: 36em; white-space: nowrap; overflow: hidden; text-overflow: ellipsis; }
.verdict-cell { font-weight: bold; white-space: nowrap; }
.reading { white-space: nowrap; }
.v-holds { background: #dcefdc; }
.v-part { background: #fbeecb; }
.v-differs { background: #f6d3d3; }
.v-untestable { background: #e6e6e6; }
figure.train { margin: 0.3em 0; }
figure.train svg { width: 100%; height: auto; }
";
