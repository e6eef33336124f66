//! The one writer of every data file (CSV) the toolkit writes: a field holding a comma, a
//! quote or a line break (a mesh label `b2,c1`, a gear name with a newline) is quoted as RFC
//! 4180 says, so that every row has the header's fields, one line each.

/// CSV text being written: a header, then rows of fields; `\n` line ends.
#[derive(Debug)]
pub struct Csv {
    writer: csv::Writer<Vec<u8>>,
}

impl Csv {
    /// A CSV whose first line is `header`.
    pub fn new<I, S>(header: I) -> Csv
    where
        I: IntoIterator<Item = S>,
        S: AsRef<str>,
    {
        let writer = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .flexible(true)
            .from_writer(Vec::new());
        let mut c = Csv { writer };
        c.row(header);
        c
    }

    /// Adds one row of `fields`.
    pub fn row<I, S>(&mut self, fields: I)
    where
        I: IntoIterator<Item = S>,
        S: AsRef<str>,
    {
        let fields: Vec<String> = fields.into_iter().map(|f| f.as_ref().to_owned()).collect();
        // Writing to memory fails only when memory does: as anything else would.
        self.writer
            .write_record(&fields)
            .expect("a CSV row is written to memory");
    }

    /// The CSV text.
    pub fn text(self) -> String {
        let bytes = self
            .writer
            .into_inner()
            .expect("a CSV held in memory is flushed to memory");
        // Every field was a `str`, so the bytes are UTF-8.
        String::from_utf8_lossy(&bytes).into_owned()
    }
}

/// One CSV line (with its `\n`): `fields` quoted as [`Csv`] quotes them.
pub fn csv_line<I, S>(fields: I) -> String
where
    I: IntoIterator<Item = S>,
    S: AsRef<str>,
{
    let mut c = Csv {
        writer: csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .flexible(true)
            .from_writer(Vec::new()),
    };
    c.row(fields);
    c.text()
}

/// One CSV line (with its `\n`) of the fields given, each shown as it displays (`{}`), quoted
/// as [`Csv`] quotes them: `csv_row!(mesh, trials, jams)`.
#[macro_export]
macro_rules! csv_row {
    ($($field:expr),* $(,)?) => {
        $crate::csv_line([$( ($field).to_string() ),*])
    };
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn fields_that_need_it_are_quoted() {
        let mut c = Csv::new(["mesh", "jams"]);
        c.row(["b2,c1", "3"]);
        c.row(["b2-c1\nX", "4"]);
        c.row(["say \"hi\"", ""]);
        c.row(["plain", "5"]);
        assert_eq!(
            c.text(),
            "mesh,jams\n\"b2,c1\",3\n\"b2-c1\nX\",4\n\"say \"\"hi\"\"\",\nplain,5\n"
        );
        assert_eq!(csv_line(["a", "b,c"]), "a,\"b,c\"\n");
        assert_eq!(crate::csv_row!("x,y", 3, 0.5, true), "\"x,y\",3,0.5,true\n");
        // Read back by a CSV reader: every row has the header's fields.
        let text = {
            let mut c = Csv::new(["a", "b"]);
            c.row(["x,y", "1\n2"]);
            c.text()
        };
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 1);
        assert_eq!(&rows[0][0], "x,y");
        assert_eq!(&rows[0][1], "1\n2");
    }
}
