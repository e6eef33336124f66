//! Readable tables: aligned Markdown for people, CSV and JSON for programs.

/// A readable table: rendered as an aligned Markdown table (pipes, header separator,
/// right-aligned numbers).
#[derive(Debug, Clone, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct Table {
    /// Title, rendered as a `###` heading above the table and used for the CSV file name.
    pub title: String,
    /// Column headers.
    pub columns: Vec<String>,
    /// Rows of cells, already formatted (see [`crate::fmt_f64`]).
    pub rows: Vec<Vec<String>>,
    /// Notes rendered below the table, one bullet each.
    pub notes: Vec<String>,
    /// The report file that holds this table's full data (see [`Table::data_in`]); such a
    /// table is shown in `table.md` and `tables.json` but gets no CSV file of its own, so a run
    /// writes each kind of data once.
    pub data_file: Option<String>,
}

impl Table {
    /// An empty table with a title and column headers
    /// (anything iterable over strings: `["a", "b"]`, `&["a", "b"]`, `vec![String]`...).
    pub fn new<S: AsRef<str>>(
        title: impl Into<String>,
        columns: impl IntoIterator<Item = S>,
    ) -> Self {
        Table {
            title: title.into(),
            columns: columns.into_iter().map(|c| c.as_ref().to_owned()).collect(),
            rows: Vec::new(),
            notes: Vec::new(),
            data_file: None,
        }
    }

    /// Marks the table as an excerpt of the report file `name` (which must be among the report's
    /// files): no `<slug>.csv` is written for it.
    pub fn data_in(mut self, name: impl Into<String>) -> Self {
        self.data_file = Some(name.into());
        self
    }

    /// Appends a row. A row shorter than the header is padded with empty cells when rendered.
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    /// Appends a note, rendered below the table.
    pub fn note(&mut self, s: impl Into<String>) {
        self.notes.push(s.into());
    }

    /// Number of columns rendered: the header's, or the longest row's if longer.
    fn width(&self) -> usize {
        self.rows
            .iter()
            .map(Vec::len)
            .chain(std::iter::once(self.columns.len()))
            .max()
            .unwrap_or(0)
    }

    /// The table as aligned Markdown, ending with a newline:
    ///
    /// ```text
    /// ### Title
    ///
    /// | name  | value |
    /// |:------|------:|
    /// | alpha |  1.50 |
    ///
    /// - a note
    /// ```
    ///
    /// A column whose cells are all numbers (empty and `-` cells aside) is right-aligned.
    /// Pipes in cells are escaped and line breaks become spaces.
    pub fn render(&self) -> String {
        let n = self.width();
        let cell = |row: &[String], i: usize| -> String {
            row.get(i).map(|c| md_cell(c)).unwrap_or_default()
        };
        let header: Vec<String> = (0..n).map(|i| cell(&self.columns, i)).collect();
        let body: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|r| (0..n).map(|i| cell(r, i)).collect())
            .collect();
        let numeric: Vec<bool> = (0..n)
            .map(|i| {
                let mut any = false;
                for r in &body {
                    let c = r[i].trim();
                    if c.is_empty() || c == "-" || c == "—" {
                        continue;
                    }
                    if !looks_numeric(c) {
                        return false;
                    }
                    any = true;
                }
                any
            })
            .collect();
        let widths: Vec<usize> = (0..n)
            .map(|i| {
                body.iter()
                    .map(|r| r[i].chars().count())
                    .chain([header[i].chars().count(), 3])
                    .max()
                    .unwrap_or(3)
            })
            .collect();

        let mut out = String::new();
        if !self.title.is_empty() {
            out.push_str("### ");
            out.push_str(&md_cell(&self.title));
            out.push_str("\n\n");
        }
        if n > 0 {
            let line = |cells: &[String], out: &mut String| {
                out.push('|');
                for (i, c) in cells.iter().enumerate() {
                    let pad = widths[i] - c.chars().count();
                    out.push(' ');
                    if numeric[i] {
                        out.extend(std::iter::repeat_n(' ', pad));
                        out.push_str(c);
                    } else {
                        out.push_str(c);
                        out.extend(std::iter::repeat_n(' ', pad));
                    }
                    out.push_str(" |");
                }
                out.push('\n');
            };
            line(&header, &mut out);
            out.push('|');
            for i in 0..n {
                if numeric[i] {
                    out.extend(std::iter::repeat_n('-', widths[i] + 1));
                    out.push(':');
                } else {
                    out.push(':');
                    out.extend(std::iter::repeat_n('-', widths[i] + 1));
                }
                out.push('|');
            }
            out.push('\n');
            for r in &body {
                line(r, &mut out);
            }
        }
        if !self.notes.is_empty() {
            if n > 0 {
                out.push('\n');
            }
            for note in &self.notes {
                out.push_str("- ");
                out.push_str(&one_line(note));
                out.push('\n');
            }
        }
        out
    }

    /// The header and rows as CSV ([`crate::Csv`]: RFC 4180 quoting, `\n` line ends); title and
    /// notes are left out.
    pub fn to_csv(&self) -> String {
        let n = self.width();
        let padded = |row: &[String]| -> Vec<String> {
            (0..n)
                .map(|i| row.get(i).cloned().unwrap_or_default())
                .collect()
        };
        let mut csv = crate::Csv::new(padded(&self.columns));
        for row in &self.rows {
            csv.row(padded(row));
        }
        csv.text()
    }
}

/// Does a cell read as a number: `-1.5`, `2e-3`, `12%`, `inf`, `NaN`?
fn looks_numeric(c: &str) -> bool {
    let c = c.strip_suffix('%').unwrap_or(c).trim();
    !c.is_empty() && c.parse::<f64>().is_ok()
}

fn one_line(s: &str) -> String {
    terminal_text(&s.replace("\r\n", " ").replace(['\n', '\r'], " "))
}

/// `s` safe to show on a terminal (and in a text file read on one): every control character but
/// the line break and the tab (an escape that recolours the terminal, a NUL, a bell, a carriage
/// return) written as its escape, `\u{1b}`, so that a name read from a user's file can neither
/// hide text nor change the terminal.
pub fn terminal_text(s: &str) -> String {
    if !s.chars().any(|c| c.is_control() && c != '\n' && c != '\t') {
        return s.to_owned();
    }
    s.chars()
        .map(|c| {
            if c.is_control() && c != '\n' && c != '\t' {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// A cell made safe for a Markdown table: one line, pipes escaped.
fn md_cell(s: &str) -> String {
    one_line(s).replace('|', "\\|")
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| (*x).to_owned()).collect()
    }

    #[test]
    fn render_aligns_text_left_and_numbers_right() {
        let mut t = Table::new("Gear ratios", ["gear", "teeth", "ratio"]);
        t.row(s(&["b1", "224", "1.000"]));
        t.row(s(&["e3", "32", "-0.143"]));
        t.row(s(&["long name", "", "12.5"]));
        t.note("ratios relative to b1");
        let expected = "\
### Gear ratios

| gear      | teeth |  ratio |
|:----------|------:|-------:|
| b1        |   224 |  1.000 |
| e3        |    32 | -0.143 |
| long name |       |   12.5 |

- ratios relative to b1
";
        assert_eq!(t.render(), expected);
    }

    #[test]
    fn render_counts_chars_not_bytes_and_escapes_pipes() {
        let mut t = Table::new("", vec!["angle (°)".to_owned(), "what".to_owned()]);
        t.row(s(&["1", "a|b"]));
        t.row(s(&["2"]));
        let out = t.render();
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "| angle (°) | what |");
        assert_eq!(lines[1], "|----------:|:-----|");
        assert_eq!(lines[2], "|         1 | a\\|b |");
        assert_eq!(lines[3], "|         2 |      |");
        let widths: Vec<usize> = lines.iter().map(|l| l.chars().count()).collect();
        assert!(widths.iter().all(|w| *w == widths[0]), "{out}");
    }

    #[test]
    fn empty_table_renders_header() {
        let columns: &[&str] = &["a", "b"];
        let t = Table::new("Nothing", columns);
        assert_eq!(t.render(), "### Nothing\n\n| a   | b   |\n|:----|:----|\n");
    }

    #[test]
    fn csv_quotes_when_needed() {
        let mut t = Table::new("t", ["name", "value"]);
        t.row(s(&["a, b", "1"]));
        t.row(s(&["say \"hi\"", "2"]));
        t.row(s(&["plain"]));
        assert_eq!(
            t.to_csv(),
            "name,value\n\"a, b\",1\n\"say \"\"hi\"\"\",2\nplain,\n"
        );
    }

    #[test]
    fn control_characters_are_shown_escaped() {
        let mut t = Table::new("gear b2\u{1b}[31mRED", ["gear", "n"]);
        t.row(s(&["a\0b", "1"]));
        let out = t.render();
        assert!(!out.contains('\u{1b}') && !out.contains('\0'), "{out:?}");
        assert!(
            out.contains("b2\\u{1b}[31mRED") && out.contains("a\\u{0}b"),
            "{out}"
        );
        assert_eq!(terminal_text("tab\tand\nline"), "tab\tand\nline");
    }
}
