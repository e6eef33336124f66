//! Why a command failed, and the one line on stderr that says so (long numbers shortened).

use registry::RunError;

use crate::args::ArgError;

/// Why the command failed.
#[derive(Debug)]
pub(crate) enum Failure {
    /// Unparseable command line: message, then usage; exit 2.
    Usage(String),
    /// Bad user input: message; exit 2.
    Bad(String),
    /// A bug or an I/O failure: message; exit 1.
    Internal(String),
    /// Failures already reported on stderr (`run all`, `bench`): only the exit status is left.
    Reported(u8),
}

impl Failure {
    pub(crate) fn code(&self) -> u8 {
        match self {
            Failure::Usage(_) | Failure::Bad(_) => 2,
            Failure::Internal(_) => 1,
            Failure::Reported(code) => *code,
        }
    }
}

impl From<ArgError> for Failure {
    fn from(e: ArgError) -> Self {
        match e {
            ArgError::Usage(m) => Failure::Usage(m),
            ArgError::Value(m) => Failure::Bad(m),
        }
    }
}

impl From<RunError> for Failure {
    fn from(e: RunError) -> Self {
        match e {
            RunError::BadInput { .. } => Failure::Bad(e.to_string()),
            RunError::Internal(_) => Failure::Internal(e.to_string()),
        }
    }
}

/// `text` on one line: line breaks become `; `, and numbers printed with dozens of digits
/// (see [`short_numbers`]) in exponent form.
pub(crate) fn one_line(text: &str) -> String {
    short_numbers(
        &text
            .lines()
            .map(str::trim_end)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; "),
    )
}

/// `text` with every number of more than 30 digits (a float such as 1e308 printed in full,
/// which no one can read; integer limits such as 2^64 - 1 have 20) in exponent form: `1e308`. Only numbers standing on their own are
/// touched (after a space, `(`, `=` or the start, before a space, punctuation or the end), not
/// digits inside a path or a name.
pub(crate) fn short_numbers(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let starts = (i == 0 || matches!(b[i - 1], b' ' | b'(' | b'=' | b'[')) && {
            let d = usize::from(b[i] == b'-');
            b.get(i + d).is_some_and(u8::is_ascii_digit)
        };
        if starts {
            let mut j = i + usize::from(b[i] == b'-');
            let mut digits = 0;
            while j < b.len() && (b[j].is_ascii_digit() || b[j] == b'.') {
                digits += usize::from(b[j].is_ascii_digit());
                j += 1;
            }
            let ends = j == b.len() || matches!(b[j], b' ' | b',' | b';' | b')' | b']' | b':');
            if digits > 30
                && ends
                && let Ok(x) = text[i..j].parse::<f64>()
            {
                out.push_str(&format!("{x:e}"));
                i = j;
                continue;
            }
            out.push_str(&text[i..j]);
            i = j;
            continue;
        }
        let c = text[i..].chars().next().unwrap_or(' ');
        out.push(c);
        i += c.len_utf8();
    }
    out
}
