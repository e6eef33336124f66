//! Errors of the registry and of experiments.

use std::fmt;

/// Why an experiment did not produce a report.
///
/// `Display` and `Error` are written by hand rather than derived with `thiserror`, because
/// `thiserror` takes a field named `source` for the underlying error, and here it is the name
/// of the input that was wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RunError {
    /// Bad user input: exit status 2.
    ///
    /// Displays as `"{source}: {field}: {rule}"` on one line, e.g.
    /// `mesh.ron: driver.teeth: must be at least 3`.
    BadInput {
        /// Where the input came from: a file name, or a flag such as `--set`.
        source: String,
        /// Which value was wrong, e.g. `driver.teeth`.
        field: String,
        /// The rule it broke, e.g. `must be at least 3`.
        rule: String,
    },
    /// A bug or an I/O failure: exit status 1.
    Internal(String),
}

impl RunError {
    /// A [`RunError::BadInput`]; `source` is where the input came from, `field` which value, `rule` what it must be.
    pub fn bad(
        source: impl Into<String>,
        field: impl Into<String>,
        rule: impl Into<String>,
    ) -> Self {
        RunError::BadInput {
            source: one_line(source.into()),
            field: one_line(field.into()),
            rule: one_line(rule.into()),
        }
    }

    /// Process exit status for this error: 2 for bad input, 1 for an internal error.
    pub fn exit_code(&self) -> i32 {
        match self {
            RunError::BadInput { .. } => 2,
            RunError::Internal(_) => 1,
        }
    }
}

/// Keeps a message on one line: line breaks become spaces.
fn one_line(s: String) -> String {
    if s.contains(['\n', '\r']) {
        s.split(['\n', '\r'])
            .filter(|part| !part.is_empty())
            .collect::<Vec<_>>()
            .join(" ")
    } else {
        s
    }
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::BadInput {
                source,
                field,
                rule,
            } => write!(f, "{source}: {field}: {rule}"),
            RunError::Internal(msg) => write!(f, "internal error: {msg}"),
        }
    }
}

impl std::error::Error for RunError {}

impl From<std::io::Error> for RunError {
    fn from(e: std::io::Error) -> Self {
        RunError::Internal(e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_input_displays_on_one_line() {
        let e = RunError::bad("mesh.ron", "driver.teeth", "must be at least 3");
        assert_eq!(e.to_string(), "mesh.ron: driver.teeth: must be at least 3");
        assert_eq!(e.exit_code(), 2);
        let e = RunError::bad("a.ron", "x", "line one\nline two");
        assert_eq!(e.to_string(), "a.ron: x: line one line two");
    }

    #[test]
    fn internal_exits_1() {
        let e = RunError::Internal("disk full".into());
        assert_eq!(e.to_string(), "internal error: disk full");
        assert_eq!(e.exit_code(), 1);
    }
}
