//! Tables 3, 4, 5 and I as heatmaps on the report page: ours against the paper's per cell,
//! coloured by the two-sample verdict the table marks with `*`, each side marked where its cell
//! keeps the paper's 1 % rule (the table's `✓`), each differing cell linking to a replayed
//! trial's page of that cell, or to the commands that write one.

use std::fmt::Write as _;

use registry::Table;

use std::cell::RefCell;
use std::collections::BTreeMap;

use super::replays::{Replayed, Replays, Settings, TrialFailure};
use presentation::escape_xml as esc;

use super::{Results, url_part};
use crate::shared::Registry;

/// The per-mesh count tables shown as heatmaps too: experiment id, how the table's title
/// begins, and how many columns label a row before the meshes.
const HEATMAPS: [(&str, &str, usize); 4] = [
    ("table3", "Table 3:", 1),
    ("table4", "Table 4:", 1),
    ("table5", "Table 5:", 1),
    ("tableI", "Table I:", 2),
];

/// The table's mark after a side that keeps the paper's 1 % rule.
const RULE_MARK: char = presentation::cells::RULE_MARK;

/// The table's mark after a cell not compared with the paper's (other inputs).
const NOT_COMPARED_MARK: char = presentation::cells::NOT_COMPARED_MARK;

/// One count of a cell: ours, the paper's, and whether the two-sample test separates them (the
/// table's `*`).
#[derive(Debug, PartialEq, Eq)]
pub(super) struct Count {
    pub(super) ours: u64,
    pub(super) paper: Option<u64>,
    pub(super) differs: bool,
}

/// A per-mesh cell as the tables print it: its two counts, whether each side keeps the paper's
/// 1 % rule (the paper's side: `None` without its counts), and whether the cell is compared
/// with the paper's at all.
#[derive(Debug, PartialEq, Eq)]
pub(super) struct CountCell {
    pub(super) jams: Count,
    pub(super) dis: Count,
    pub(super) ours_keep_rule: bool,
    pub(super) paper_keeps_rule: Option<bool>,
    pub(super) compared: bool,
}

/// A per-mesh cell as the tables print it, `ours[*]/ours[*][✓] (paper/paper[✓])[†]` (jams,
/// then disengagements; `-` for no paper count): its counts and marks, or `None` for any other
/// text.
pub(super) fn count_cell(cell: &str) -> Option<CountCell> {
    let cell = cell.trim();
    let (cell, compared) = match cell.strip_suffix(NOT_COMPARED_MARK) {
        Some(c) => (c, false),
        None => (cell, true),
    };
    let (ours, paper) = cell.split_once(" (")?;
    let paper = paper.strip_suffix(')')?;
    let kept = |s: &str| -> (String, bool) {
        match s.strip_suffix(RULE_MARK) {
            Some(rest) => (rest.to_owned(), true),
            None => (s.to_owned(), false),
        }
    };
    let (ours, ours_keep_rule) = kept(ours);
    let (paper, paper_kept) = kept(paper);
    let (oj, od) = ours.split_once('/')?;
    let (pj, pd) = paper.split_once('/')?;
    let one = |o: &str, p: &str| -> Option<Count> {
        let differs = o.ends_with('*');
        let ours = o.trim_end_matches('*').parse().ok()?;
        let paper = match p {
            "-" => None,
            _ => Some(p.parse().ok()?),
        };
        Some(Count {
            ours,
            paper,
            differs,
        })
    };
    let (jams, dis) = (one(oj, pj)?, one(od, pd)?);
    let paper_keeps_rule = (jams.paper.is_some() && dis.paper.is_some()).then_some(paper_kept);
    Some(CountCell {
        jams,
        dis,
        ours_keep_rule,
        paper_keeps_rule,
        compared,
    })
}

/// A heatmap's row: its label and, per mesh, the cell as `replay` names it with its counts.
type HeatRow = (String, Vec<Option<(String, CountCell)>>);

/// The rows of `t` (experiment `id`, with `lead` label columns) that hold counts.
pub(super) fn heat_rows(id: &str, t: &Table, lead: usize) -> Vec<HeatRow> {
    let meshes = t.columns.get(lead..).unwrap_or_default();
    let mut rows = Vec::new();
    let mut case = String::new();
    // Table 5's cells are named by each mesh's E. max, its first row (ours, before the paper's).
    let mut emax: Vec<Option<String>> = vec![None; meshes.len()];
    for row in &t.rows {
        let label = row.first().map_or("", String::as_str);
        if id == "table5" && label.starts_with("E. max (random)") {
            for (m, cell) in row.iter().skip(lead).enumerate().take(meshes.len()) {
                let ours = cell.split(" (").next().unwrap_or("").trim();
                if ours.parse::<f64>().is_ok() {
                    emax[m] = Some(ours.to_owned());
                }
            }
            continue;
        }
        if id == "tableI" && !label.is_empty() {
            label.clone_into(&mut case);
        }
        let (row_label, key) = match id {
            "table3" => (format!("Case {label}"), label.to_owned()),
            "tableI" => {
                let g = row.get(1).map_or("", String::as_str);
                (format!("Case {case}, G = {g} %"), format!("{case}/{g}"))
            }
            "table4" => (format!("random error {label}"), label.to_owned()),
            _ => (format!("E. sys {label} deg"), label.to_owned()),
        };
        let cells: Vec<Option<(String, CountCell)>> = row
            .iter()
            .skip(lead)
            .zip(meshes)
            .enumerate()
            .map(|(m, (cell, mesh))| {
                let counts = count_cell(cell)?;
                let name = match id {
                    "table5" => format!("{}/{key}/{mesh}", emax[m].as_deref()?),
                    _ => format!("{key}/{mesh}"),
                };
                Some((name, counts))
            })
            .collect();
        if cells.iter().any(Option::is_some) {
            rows.push((row_label, cells));
        }
    }
    rows
}

/// `cell` as a part of a folder name: the characters `replay` keeps, any other `-`.
fn plain(cell: &str) -> String {
    cell.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

/// The folder `cargo xtask replay <id> <cell>` writes its listing of failed trials to.
pub(super) fn listing_folder(id: &str, cell: &str) -> String {
    format!("replay-{id}-{}-failed", plain(cell))
}

/// What a heatmap links its cells with: every replayed trial under the results folder, found
/// by the key of its trials ([`replay::trial_key`]), so that a cell links to a
/// trial of its own that had the failure it counts, whichever table's cell was replayed, and
/// the flags its commands carry (`--out DIR` where the page was built with one).
pub(super) struct Links<'a> {
    /// The experiments, to read a cell's settings by.
    pub(super) exps: &'a Registry,
    /// Every replay, of every experiment.
    pub(super) replays: &'a Replays,
    /// ` --out DIR` where the page was built with `--out`, else empty.
    pub(super) out_flag: String,
}

/// The replayed trials that could be a table's cell's, and that cell's trial keys, worked out
/// once per cell.
struct Finder<'a> {
    id: &'a str,
    settings: Settings,
    links: &'a Links<'a>,
    keys: RefCell<BTreeMap<String, Option<String>>>,
}

impl<'a> Finder<'a> {
    fn new(id: &'a str, r: &Results, links: &'a Links<'a>) -> Self {
        Finder {
            id,
            settings: super::replays::settings_of(r.run.as_ref()),
            links,
            keys: RefCell::new(BTreeMap::new()),
        }
    }

    /// Every replayed trial, of any experiment.
    fn trials(&self) -> impl Iterator<Item = &'a Replayed> {
        self.links.replays.values().flatten().filter(|r| r.page)
    }

    /// The trial key of `cell` (worked out only where a replayed trial of its mesh is there).
    fn key(&self, cell: &str) -> Option<String> {
        let mesh = cell.rsplit('/').next().unwrap_or(cell);
        let prefix = format!("mesh={mesh};");
        if !self
            .trials()
            .any(|r| r.key.as_ref().is_some_and(|k| k.starts_with(&prefix)))
        {
            return None;
        }
        self.keys
            .borrow_mut()
            .entry(cell.to_owned())
            .or_insert_with(|| {
                super::replays::key_of(self.links.exps, self.id, cell, &self.settings)
            })
            .clone()
    }

    /// The replayed trial of `cell` that had `failure` (the lowest trial index): one with the
    /// cell's trial key, or, where keys cannot be worked out, one of this table's cell replayed
    /// under this run's settings.
    fn trial(&self, cell: &str, failure: TrialFailure) -> Option<&'a Replayed> {
        let key = self.key(cell);
        self.trials()
            .filter(|r| r.had(failure))
            .filter(|r| match (&key, &r.key) {
                (Some(k), Some(theirs)) => k == theirs,
                _ => {
                    r.settings.as_ref() == Some(&self.settings)
                        && r.trial
                            .as_ref()
                            .is_some_and(|t| t.experiment == self.id && t.cell == cell)
                }
            })
            .min_by_key(|r| (r.trial.as_ref().map_or(u64::MAX, |t| t.trial), &r.folder))
    }

    /// This table's listing of `cell`'s failed trials under this run's settings, if written.
    fn listing(&self, folder: &str) -> Option<&'a Replayed> {
        self.links
            .replays
            .get(self.id)?
            .iter()
            .find(|x| x.folder == folder && x.settings.as_ref() == Some(&self.settings))
    }
}

/// The words of a cell's rule marks for its tooltip.
fn rule_words(c: &CountCell) -> String {
    let side = |kept: bool| if kept { "keeps" } else { "breaks" };
    match c.paper_keeps_rule {
        Some(p) => format!(
            "1 % rule: ours {}, the paper's {}",
            side(c.ours_keep_rule),
            side(p)
        ),
        None => format!("1 % rule: ours {}", side(c.ours_keep_rule)),
    }
}

/// A differing cell with no replayed trial of its failure: the listing's folder (the anchor of
/// its commands), the cell, and the failures it needs a trial of.
type Wanted = (String, String, Vec<TrialFailure>);

/// Table `t` of experiment `id` (its first) as heatmaps, jams and disengagements: ours against
/// the paper's per cell, coloured by the two-sample test the table marks, each side marked `✓`
/// where its cell keeps the paper's 1 % rule and the cell outlined where the two sides' verdicts
/// differ. A cell with a replayed trial that had the heatmap's failure links to that trial's
/// page; a differing cell without one links to the commands that write one, listed below. None
/// for a run on other inputs than the paper's.
pub(super) fn heatmaps(
    h: &mut String,
    id: &str,
    t: &Table,
    r: &Results,
    links: &Links<'_>,
    reference: bool,
) {
    let Some(&(_, prefix, lead)) = HEATMAPS.iter().find(|(e, _, _)| *e == id) else {
        return;
    };
    if !t.title.starts_with(prefix) {
        return;
    }
    if reference {
        let _ = writeln!(
            h,
            "<p class=\"reference\">No heatmap of {}: this run's inputs differ from the paper's, so the two-sample verdicts would be no check.</p>",
            esc(prefix.trim_end_matches(':'))
        );
        return;
    }
    let rows = heat_rows(id, t, lead);
    if rows.is_empty() {
        return;
    }
    let finder = Finder::new(id, r, links);
    let mut wanted: Vec<Wanted> = Vec::new();
    for failure in [TrialFailure::Jam, TrialFailure::Disengagement] {
        heatmap(
            h,
            (id, prefix),
            &t.columns[lead..],
            &rows,
            failure,
            &finder,
            &mut wanted,
        );
    }
    heat_key(h);
    replay_commands(h, id, r, &wanted, &finder);
}

/// The heatmap of one failure: a row per row of the table, a cell per mesh.
fn heatmap(
    h: &mut String,
    (id, prefix): (&str, &str),
    meshes: &[String],
    rows: &[HeatRow],
    failure: TrialFailure,
    finder: &Finder<'_>,
    wanted: &mut Vec<Wanted>,
) {
    let kind = kind_name(failure);
    let _ = write!(
        h,
        "<p class=\"table-title\">{} as a heatmap, {kind}: ours | the paper's per cell, coloured by Fisher's exact two-sample test at 5 % (the table's <code>*</code>): green where the two counts agree, however high, red where they differ; <code>{RULE_MARK}</code> after a side whose cell keeps the paper's 1 % rule (the cells the paper shades), a dashed outline where ours and the paper's verdicts on the rule differ</p>\n<div class=\"table-wrap wide\">\n<table class=\"heatmap\" data-table=\"{}\" data-kind=\"{kind}\">\n<thead><tr><th></th>",
        esc(prefix.trim_end_matches(':')),
        esc(id)
    );
    for m in meshes {
        let _ = write!(h, "<th>{}</th>", esc(m));
    }
    h.push_str("</tr></thead>\n<tbody>\n");
    for (label, cells) in rows {
        let _ = write!(h, "<tr><th>{}</th>", esc(label));
        for cell in cells {
            match cell {
                Some((name, cc)) => heat_cell(h, (id, name), cc, failure, finder, wanted),
                None => h.push_str("<td class=\"hm none\">-</td>"),
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody>\n</table>\n</div>\n");
}

/// The heatmap's name of a failure.
fn kind_name(failure: TrialFailure) -> &'static str {
    match failure {
        TrialFailure::Jam => "jams",
        TrialFailure::Disengagement => "disengagements",
    }
}

/// One cell of a heatmap: its counts, its colour and tooltip, and its link.
fn heat_cell(
    h: &mut String,
    (id, name): (&str, &str),
    cc: &CountCell,
    failure: TrialFailure,
    finder: &Finder<'_>,
    wanted: &mut Vec<Wanted>,
) {
    let c = match failure {
        TrialFailure::Jam => &cc.jams,
        TrialFailure::Disengagement => &cc.dis,
    };
    let paper = c.paper.map_or_else(|| "-".to_owned(), |p| p.to_string());
    let mark = |kept: bool| {
        if kept {
            RULE_MARK.to_string()
        } else {
            String::new()
        }
    };
    let text = format!(
        "{}{} | {paper}{}",
        c.ours,
        mark(cc.ours_keep_rule),
        mark(cc.paper_keeps_rule == Some(true))
    );
    let (class, verdict) = match (c.paper, c.differs) {
        _ if !cc.compared => (
            "apart",
            "not compared: the paper's count comes from other inputs (this mesh ran at our own E. max, or the run's inputs differ from the paper's)",
        ),
        (None, _) => ("none", "no count in the paper"),
        (Some(_), true) => ("differs", "differs from the paper's by the two-sample test"),
        (Some(_), false) => (
            "consistent",
            "consistent with the paper's by the two-sample test",
        ),
    };
    let rule_differs = cc.compared && cc.paper_keeps_rule.is_some_and(|p| p != cc.ours_keep_rule);
    let classes = if rule_differs {
        format!("hm {class} rule-differs")
    } else {
        format!("hm {class}")
    };
    let kind = kind_name(failure);
    let mut tip = format!(
        "{name} {kind}: ours {}, the paper's {paper}: {verdict}; {}",
        c.ours,
        rule_words(cc)
    );
    let href = cell_link((id, name), failure, c.differs, finder, wanted, &mut tip);
    match href {
        Some(href) => {
            let _ = write!(
                h,
                "<td class=\"{classes}\" title=\"{}\"><a href=\"{href}\">{}</a></td>",
                esc(&tip),
                esc(&text)
            );
        }
        None => {
            let _ = write!(
                h,
                "<td class=\"{classes}\" title=\"{}\">{}</td>",
                esc(&tip),
                esc(&text)
            );
        }
    }
}

/// Where a cell of a heatmap of `failure` links: a replayed trial of the cell that had it (its
/// folder named in the tooltip `tip`), or, for a differing cell with none, the commands that
/// write one (the cell added to `wanted`); `None` for a consistent cell with none.
fn cell_link(
    (id, name): (&str, &str),
    failure: TrialFailure,
    differs: bool,
    finder: &Finder<'_>,
    wanted: &mut Vec<Wanted>,
    tip: &mut String,
) -> Option<String> {
    if let Some(trial) = finder.trial(name, failure) {
        let _ = write!(
            tip,
            "; opens {} (a {} of this cell)",
            trial.folder,
            failure.word()
        );
        return Some(format!("{}/pair.html", url_part(&trial.folder)));
    }
    if !differs {
        return None;
    }
    let folder = listing_folder(id, name);
    match wanted.iter_mut().find(|(f, _, _)| *f == folder) {
        Some(w) => w.2.push(failure),
        None => wanted.push((folder.clone(), name.to_owned(), vec![failure])),
    }
    Some(format!("#{}", esc(&folder)))
}

/// The key under the heatmaps: what each colour and mark means. Green says the paper's count
/// and ours agree, not that the mesh works: a cell where both jam in nearly every trial is green.
fn heat_key(h: &mut String) {
    let _ = writeln!(
        h,
        "<p class=\"heat-key\"><span class=\"hm consistent\">green: consistent</span> Fisher's exact test at 5 % does not tell our count from the paper's: the two agree, however many trials failed (a cell where both jam in 199 or 200 of 200 trials is green); green does not say the mesh works, the 1 % rule does (<code>{RULE_MARK}</code>). <span class=\"hm differs\">red: differs</span> the test separates our count from the paper's. <span class=\"hm none\">no count in the paper</span> <span class=\"hm apart\">not compared (other inputs)</span> <span class=\"hm consistent rule-differs\">dashed: the 1 % rule's verdicts differ</span> Each cell: our count | the paper's; <code>{RULE_MARK}</code>: that side's cell keeps the paper's 1 % rule (at most 2 of 200 trials jammed and at most 2 disengaged). A cell links to the page of a replayed trial of that cell that had the heatmap's failure; a differing cell with none replayed links to the commands that write one.</p>"
    );
}

/// How many cells' commands are listed open; more are folded under a summary line.
const COMMANDS_OPEN: usize = 8;

/// The commands that replay the differing cells with no replayed trial of their failure
/// (`wanted`): the listing of a cell's failed trials and one trial's page, a trial of the
/// failure wanted where a listing under the run's settings is there to read. Each command
/// carries the run's seed and settings and the page's `--out`.
fn replay_commands(h: &mut String, id: &str, r: &Results, wanted: &[Wanted], finder: &Finder<'_>) {
    if wanted.is_empty() {
        return;
    }
    let mut flags = String::new();
    if let Some(p) = &r.run {
        let _ = write!(flags, " --seed {}", p.seed);
        for (k, v) in &p.overrides {
            let _ = write!(flags, " --set {k}={v}");
        }
    }
    flags.push_str(&finder.links.out_flag);
    let _ = writeln!(
        h,
        "<p class=\"meta\">No trial of these cells with the heatmap's failure replayed yet. For each: the first command lists the cell's trials that failed, the second (a trial from that list for <code>TRIAL</code>) writes that trial's page, <code>replay-{}-&lt;cell&gt;-&lt;trial&gt;/pair.html</code> beside this page, which the cell then links:</p>",
        esc(id)
    );
    let folded = wanted.len() > COMMANDS_OPEN;
    if folded {
        let _ = writeln!(
            h,
            "<details class=\"replay-commands\"><summary>The commands for {} cells</summary>",
            wanted.len()
        );
    }
    h.push_str("<ul class=\"replay-commands\">\n");
    for w in wanted {
        command_item(h, id, w, &flags, finder);
    }
    h.push_str("</ul>\n");
    if folded {
        h.push_str("</details>\n");
    }
}

/// One cell's commands (see [`replay_commands`]).
fn command_item(
    h: &mut String,
    id: &str,
    (folder, cell, failures): &Wanted,
    flags: &str,
    finder: &Finder<'_>,
) {
    let failed = finder
        .listing(folder)
        .and_then(|x| super::replays::failed_trials(&x.dir));
    // A trial of each failure wanted, from the listing where it is there; named by its failure
    // where the cell wants two.
    let mut second: Vec<String> = Vec::new();
    for f in failures {
        let found = failed.as_ref().and_then(|all| {
            all.iter()
                .find(|(_, what)| what.contains(f.word()))
                .map(|(t, _)| t.to_string())
        });
        let trial = found.clone().unwrap_or_else(|| "TRIAL".to_owned());
        let what = match found {
            Some(_) if failures.len() > 1 => format!(" (a {})", f.word()),
            _ => String::new(),
        };
        let command = format!(
            "<code>cargo xtask replay {} {} {}{}</code>{what}",
            esc(id),
            esc(cell),
            esc(&trial),
            esc(flags)
        );
        if !second
            .iter()
            .any(|c| c.starts_with(&command[..command.find("</code>").unwrap_or(0)]))
        {
            second.push(command);
        }
    }
    let listed = match &failed {
        Some(f) if !f.is_empty() => {
            let shown: Vec<String> = f
                .iter()
                .take(12)
                .map(|(t, what)| format!("{t} ({what})"))
                .collect();
            format!(
                " Failed trials (from <a href=\"{}/failed-trials.csv\">its listing</a>, {} in all): {}{}.",
                url_part(folder),
                f.len(),
                esc(&shown.join(", ")),
                if f.len() > 12 { ", ..." } else { "" }
            )
        }
        _ => String::new(),
    };
    let _ = writeln!(
        h,
        "<li id=\"{}\"><b>{}</b>: <code>cargo xtask replay {} {}{}</code>, then {}.{listed}</li>",
        esc(folder),
        esc(cell),
        esc(id),
        esc(cell),
        esc(flags),
        second.join(", or ")
    );
}
