//! Printing a report's tables on stdout in the chosen format (Markdown, CSV, JSON).

use registry::{Entry, Report, Table};
use serde_json::Value;

use crate::args::Format;
use crate::failure::Failure;
use crate::summary;

/// Prints reports on stdout (through `out`) as `--format` asks: Markdown or CSV as each
/// experiment finishes, JSON once at the end when there are several.
pub(crate) struct Printer<'a> {
    format: Format,
    /// Several experiments (or `all`): each is introduced by its id.
    several: bool,
    out: &'a mut dyn FnMut(&str) -> Result<(), Failure>,
    printed: usize,
    json: serde_json::Map<String, Value>,
    summary: Option<Value>,
}

impl<'a> Printer<'a> {
    pub(crate) fn new(
        format: Format,
        several: bool,
        out: &'a mut dyn FnMut(&str) -> Result<(), Failure>,
    ) -> Self {
        Printer {
            format,
            several,
            out,
            printed: 0,
            json: serde_json::Map::new(),
            summary: None,
        }
    }

    pub(crate) fn report(&mut self, e: &Entry, report: &Report) -> Result<(), Failure> {
        let gap = if self.printed == 0 { "" } else { "\n" };
        self.printed += 1;
        match self.format {
            Format::Md => {
                if self.several {
                    (self.out)(&format!("{gap}## {}: {}\n\n", e.id, e.title))?;
                }
                (self.out)(&report.text())
            }
            Format::Csv => {
                let prefix = if self.several {
                    format!("{}: ", e.id)
                } else {
                    String::new()
                };
                (self.out)(&format!("{gap}{}", csv_tables(&report.tables, &prefix)))
            }
            Format::Json if self.several => {
                self.json
                    .insert(e.id.to_owned(), json_value(&report.to_json())?);
                Ok(())
            }
            Format::Json => (self.out)(&report.to_json()),
        }
    }

    /// The summary of `run all`: a table after the reports, or the `summary` member of the JSON.
    pub(crate) fn summary(
        &mut self,
        rows: &[summary::Row],
        seed: u64,
        threads: usize,
    ) -> Result<(), Failure> {
        let table = summary::table(rows);
        match self.format {
            Format::Md => (self.out)(&format!("\n{}", table.render())),
            Format::Csv => (self.out)(&format!(
                "\n{}",
                csv_tables(std::slice::from_ref(&table), "")
            )),
            Format::Json => {
                self.summary = Some(json_value(&summary::json(rows, seed, threads))?);
                Ok(())
            }
        }
    }

    /// Prints what was held back: the JSON of several experiments.
    pub(crate) fn finish(self) -> Result<(), Failure> {
        if self.format != Format::Json || !self.several {
            return Ok(());
        }
        let mut doc = serde_json::Map::new();
        doc.insert("experiments".into(), Value::Object(self.json));
        if let Some(s) = self.summary {
            doc.insert("summary".into(), s);
        }
        let text = serde_json::to_string_pretty(&Value::Object(doc))
            .map_err(|e| Failure::Internal(format!("internal error: cannot print JSON: {e}")))?;
        (self.out)(&format!("{text}\n"))
    }
}

/// Each table as CSV after a `# <prefix><title>` line, separated by blank lines.
pub(crate) fn csv_tables(tables: &[Table], prefix: &str) -> String {
    tables
        .iter()
        .map(|t| {
            // The title on one line, shown safely (a path in it could hold a line break).
            let title = registry::terminal_text(&t.title.replace(['\n', '\r'], " "));
            format!("# {prefix}{title}\n{}", t.to_csv())
        })
        .collect::<Vec<_>>()
        .join("\n")
}

pub(crate) fn json_value(text: &str) -> Result<Value, Failure> {
    serde_json::from_str(text)
        .map_err(|e| Failure::Internal(format!("internal error: a report's JSON: {e}")))
}
