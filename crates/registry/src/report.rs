//! What an experiment returns: its tables, its files and its agreement with the paper.

use serde_json::{Value, json};

use crate::Table;

/// The most rows of a data file (CSV) an experiment writes: 10^6, some 40-80 MB. A sampling
/// step that would give more (`pair`'s `sample_deg`, `fig2`'s `step`) is refused before
/// anything runs, naming the smallest step allowed.
pub const MAX_DATA_ROWS: usize = 1_000_000;

/// The largest angle, in degrees either way, an input may give (a start angle, a tip angle, a
/// phase): 10^6 degrees (about 2 778 turns). A double holds an angle of 10^6 degrees to about
/// 1e-10 degrees (2e-12 rad), below the 2.5e-11 rad to which the solver places a contact; at
/// 10^16 degrees its spacing is 2 degrees, and a run from there ends nowhere or gives another
/// answer. An angle a whole number of turns smaller names the same position.
pub const MAX_ANGLE_DEG: f64 = 1.0e6;

/// What an experiment returns.
#[derive(Debug, Clone, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Report {
    /// Tables, printed and stored in this order.
    pub tables: Vec<Table>,
    /// Other files to store beside the tables (SVG figures, raw data...).
    pub files: Vec<OutputFile>,
    /// Simulated trials behind the tables (pair turns or train runs); 0 when none are random.
    pub trials: u64,
    /// Tooth engagements simulated: for each pair turn or train run, the teeth that passed
    /// through each mesh (the work measure of `cargo xtask bench`); 0 when not counted.
    pub engagements: u64,
    /// How our numbers compare with the paper's, where the experiment can judge it.
    pub agreement: Option<Agreement>,
    /// The inputs the tables depend on, by parameter name (hypothesis, rule, gearing, measured
    /// errors...), as the runner records them; stored in `tables.json` as `inputs`.
    pub inputs: std::collections::BTreeMap<String, String>,
}

/// Agreement with the paper: how many of the paper's numbers are consistent with ours and how
/// many differ. Counts out of trials (the paper's are samples of 200 too) are compared by a
/// two-sample test (Fisher's exact, 5 %); other numbers by whether the paper's lies inside our
/// 95 % interval (or stated tolerance). Each experiment's note says which, and `what` says it
/// beside the two numbers wherever they are shown on their own (an overview of experiments).
#[derive(Debug, Clone, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Agreement {
    /// The paper's numbers consistent with ours.
    pub consistent: u64,
    /// The paper's numbers that differ from ours.
    pub differ: u64,
    /// What the two numbers count and how they were judged, read after `consistent / differ`
    /// (`counts of the table: Fisher's exact test at 5 % does not separate / separates the
    /// paper's from ours`); empty where the experiment's notes say it. Borrowed where an
    /// experiment writes it, owned where a stored report is read back.
    pub what: std::borrow::Cow<'static, str>,
}

/// What begins the label [`Report::label_departures`] adds to every table title of a run whose
/// inputs differ from the paper's (`cargo xtask report` reads it there).
pub const DEPARTURE: &str = "[inputs differ from the defaults: ";

impl Report {
    /// A run whose inputs differ from the defaults (the paper's), `departures` (a parameter and
    /// its value as typed), says so in every table's title, labels the paper's numbers as coming
    /// from other inputs, and judges no agreement with the paper (the summary shows `-`). Runs at
    /// the defaults, or differing only in a reading of the paper ([`crate::Param::reading`]),
    /// are left exactly as they print.
    pub fn label_departures(&mut self, departures: &[(&'static crate::Param, String)]) {
        if departures.is_empty() {
            return;
        }
        let list = departures
            .iter()
            .map(|(p, v)| format!("{}={v}", p.name))
            .collect::<Vec<_>>()
            .join(", ");
        let compares = self.agreement.is_some()
            || self.tables.iter().any(|t| {
                t.title.contains("paper") || t.columns.iter().any(|c| c.contains("paper"))
            });
        for t in &mut self.tables {
            t.title = format!("{} {DEPARTURE}{list}]", t.title);
            if compares {
                t.note(format!(
                    "This run's inputs differ from the paper's ({list}): the paper's numbers shown beside ours come from its own inputs, for reference, not as a check of these."
                ));
            }
        }
        self.agreement = None;
    }

    /// All tables rendered ([`Table::render`]), separated by blank lines; this is what is
    /// printed and snapshotted.
    pub fn text(&self) -> String {
        self.tables
            .iter()
            .map(Table::render)
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The tables as pretty-printed JSON:
    /// `{"tables": [{"title", "columns", "rows", "notes"}], "files": [names], "trials",
    /// "engagements", "agreement", "inputs": {name: value}}`; cells stay strings, exactly as
    /// printed.
    pub fn to_json(&self) -> String {
        // The cells again, numbers as JSON numbers (a cell that is one finite number), the
        // others as printed.
        let values: Vec<Value> = self
            .tables
            .iter()
            .map(|t| {
                t.rows
                    .iter()
                    .map(|row| {
                        row.iter()
                            .map(|cell| match cell.trim().parse::<f64>() {
                                Ok(x) if x.is_finite() => json!(x),
                                _ => json!(cell),
                            })
                            .collect::<Vec<Value>>()
                    })
                    .collect()
            })
            .collect();
        let tables: Vec<Value> = self
            .tables
            .iter()
            .zip(values)
            .map(|(t, values)| {
                json!({
                    "title": t.title,
                    "columns": t.columns,
                    "rows": t.rows,
                    "values": values,
                    "notes": t.notes,
                })
            })
            .collect();
        let files: Vec<&str> = self.files.iter().map(|f| f.name.as_str()).collect();
        let mut s = format!(
            "{:#}",
            json!({
                "tables": tables,
                "files": files,
                "trials": self.trials,
                "engagements": self.engagements,
                "agreement": self.agreement,
                "inputs": self.inputs,
            })
        );
        s.push('\n');
        s
    }
}

/// A file an experiment wants stored in its results directory.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct OutputFile {
    /// Plain file name, e.g. `fig2.svg` (no directories).
    pub name: String,
    /// Its bytes.
    pub contents: Vec<u8>,
}

impl OutputFile {
    /// A file named `name` holding `contents`.
    pub fn new(name: impl Into<String>, contents: impl Into<Vec<u8>>) -> Self {
        OutputFile {
            name: name.into(),
            contents: contents.into(),
        }
    }
}
