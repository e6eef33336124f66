//! Tables 3, 4, 5 and I as heatmaps on the report page: ours against the paper's per cell,
//! coloured by the two-sample verdict the table marks with `*`, each differing cell linking to
//! its `replay` listing.

use std::fmt::Write as _;

use registry::Table;

use super::{Results, esc, url_part};

/// The per-mesh count tables shown as heatmaps too: experiment id, how the table's title
/// begins, and how many columns label a row before the meshes.
const HEATMAPS: [(&str, &str, usize); 4] = [
    ("table3", "Table 3:", 1),
    ("table4", "Table 4:", 1),
    ("table5", "Table 5:", 1),
    ("tableI", "Table I:", 2),
];

/// One count of a cell: ours, the paper's, and whether the two-sample test separates them (the
/// table's `*`).
#[derive(Debug, PartialEq, Eq)]
pub(super) struct Count {
    pub(super) ours: u64,
    pub(super) paper: Option<u64>,
    pub(super) differs: bool,
}

/// A per-mesh cell as the tables print it, `ours[*]/ours[*] (paper/paper)` (jams, then
/// disengagements; `-` for no paper count): the two counts, or `None` for any other text.
pub(super) fn count_cell(cell: &str) -> Option<(Count, Count)> {
    let (ours, paper) = cell.trim().split_once(" (")?;
    let paper = paper.strip_suffix(')')?;
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
    Some((one(oj, pj)?, one(od, pd)?))
}

/// A heatmap's row: its label and, per mesh, the cell as `replay` names it with its counts.
type HeatRow = (String, Vec<Option<(String, Count, Count)>>);

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
        let cells: Vec<Option<(String, Count, Count)>> = row
            .iter()
            .skip(lead)
            .zip(meshes)
            .enumerate()
            .map(|(m, (cell, mesh))| {
                let (j, d) = count_cell(cell)?;
                let name = match id {
                    "table5" => format!("{}/{key}/{mesh}", emax[m].as_deref()?),
                    _ => format!("{key}/{mesh}"),
                };
                Some((name, j, d))
            })
            .collect();
        if cells.iter().any(Option::is_some) {
            rows.push((row_label, cells));
        }
    }
    rows
}

/// The folder `cargo xtask replay <id> <cell>` writes its listing of failed trials to.
pub(super) fn listing_folder(id: &str, cell: &str) -> String {
    let cell: String = cell
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect();
    format!("replay-{id}-{cell}-failed")
}

/// Table `t` of experiment `id` (its first) as heatmaps, jams and disengagements: ours against
/// the paper's per cell, coloured by the two-sample test the table marks; each differing cell
/// links to its `replay` listing (the folder `replay` wrote, when it is there; else the
/// command that writes it, listed below). None for a run on other inputs than the paper's.
pub(super) fn heatmaps(
    h: &mut String,
    id: &str,
    t: &Table,
    r: &Results,
    replays: &[(String, bool)],
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
    let meshes = &t.columns[lead..];
    let name = prefix.trim_end_matches(':');
    let mut commands: Vec<(String, String)> = Vec::new();
    let (seed, sets) = r
        .run
        .as_ref()
        .map_or((None, Vec::new()), |p| (Some(p.seed), p.overrides.clone()));
    for (kind, pick) in [("jams", 0), ("disengagements", 1)] {
        let _ = write!(
            h,
            "<p class=\"table-title\">{} as a heatmap, {kind}: ours | the paper's per cell, coloured by Fisher's exact two-sample test at 5 % (the table's <code>*</code>)</p>\n<div class=\"table-wrap\">\n<table class=\"heatmap\" data-table=\"{}\" data-kind=\"{kind}\">\n<thead><tr><th></th>",
            esc(name),
            esc(id)
        );
        for m in meshes {
            let _ = write!(h, "<th>{}</th>", esc(m));
        }
        h.push_str("</tr></thead>\n<tbody>\n");
        for (label, cells) in &rows {
            let _ = write!(h, "<tr><th>{}</th>", esc(label));
            for cell in cells {
                let Some((cell_name, j, d)) = cell else {
                    h.push_str("<td class=\"hm none\">-</td>");
                    continue;
                };
                let c = if pick == 0 { j } else { d };
                let paper = c.paper.map_or_else(|| "-".to_owned(), |p| p.to_string());
                let text = format!("{} | {paper}", c.ours);
                let (class, verdict) = match (c.paper, c.differs) {
                    (None, _) => ("none", "no count in the paper"),
                    (Some(_), true) => {
                        ("differs", "differs from the paper's by the two-sample test")
                    }
                    (Some(_), false) => ("consistent", "consistent with the paper's"),
                };
                let tip = format!(
                    "{cell_name} {kind}: ours {}, the paper's {paper}: {verdict}",
                    c.ours
                );
                if c.differs {
                    let folder = listing_folder(id, cell_name);
                    let href = if replays.iter().any(|(f, _)| *f == folder) {
                        format!("{}/table.md", url_part(&folder))
                    } else {
                        if !commands.iter().any(|(f, _)| *f == folder) {
                            commands.push((folder.clone(), cell_name.clone()));
                        }
                        format!("#{}", esc(&folder))
                    };
                    let _ = write!(
                        h,
                        "<td class=\"hm {class}\" title=\"{}\"><a href=\"{href}\">{}</a></td>",
                        esc(&tip),
                        esc(&text)
                    );
                } else {
                    let _ = write!(
                        h,
                        "<td class=\"hm {class}\" title=\"{}\">{}</td>",
                        esc(&tip),
                        esc(&text)
                    );
                }
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</tbody>\n</table>\n</div>\n");
    }
    h.push_str("<p class=\"heat-key\"><span class=\"hm consistent\">consistent</span> <span class=\"hm differs\">differs</span> <span class=\"hm none\">no count in the paper</span> Each cell: our count | the paper's. A differing cell links to its replay listing: the trials of that cell that jammed or disengaged.</p>\n");
    if !commands.is_empty() {
        let mut flags = String::new();
        if let Some(seed) = seed {
            let _ = write!(flags, " --seed {seed}");
        }
        for (k, v) in &sets {
            let _ = write!(flags, " --set {k}={v}");
        }
        let _ = writeln!(
            h,
            "<p class=\"meta\">Listings not written yet; each of these commands writes one to <code>replay-{}-&lt;cell&gt;-failed/</code> beside this page, which the cell then links:</p>\n<ul class=\"replay-commands\">",
            esc(id)
        );
        for (folder, cell) in &commands {
            let _ = writeln!(
                h,
                "<li id=\"{}\"><code>cargo xtask replay {} {}{}</code></li>",
                esc(folder),
                esc(id),
                esc(cell),
                esc(&flags)
            );
        }
        h.push_str("</ul>\n");
    }
}
