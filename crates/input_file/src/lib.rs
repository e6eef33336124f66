//! Reading a user's input file (config, gearing, error table, partial file) with a size limit.
//!
//! `std::fs::read_to_string` reads until the end of the file: on `/dev/zero` it grows until
//! the allocator gives up, on `/dev/urandom` it never ends. [`read_to_string`] reads at most
//! `limit + 1` bytes and refuses a file longer than `limit` with an [`std::io::Error`] whose
//! message states the limit, so callers keep their "FILE: cannot read: ..." messages.
//!
//! Opening a named pipe (FIFO) waits for a writer, for ever if none comes: what is not a regular
//! file (a FIFO, a socket, a directory, a block device) is refused from its metadata before it
//! is opened, and the file is opened without waiting and checked again once open. Character
//! devices (`/dev/zero`, `/dev/null`) open at once and are read up to the limit like a file.

use std::io::Read;
use std::path::Path;

/// The largest config, gearing or measured-errors file read: 16 MiB. The embedded gearing is
/// about 10 kB; a file a thousand times larger is not one a person wrote.
pub const MAX_INPUT_BYTES: u64 = 16 * 1024 * 1024;

/// `path` read as UTF-8 text, refusing a file of more than `limit` bytes.
///
/// # Errors
/// What [`std::fs::File::open`] or reading gives; a file longer than `limit` (kind
/// `InvalidData`, "is larger than N bytes, the limit on input files"); bytes that are not UTF-8
/// (kind `InvalidData`, "stream did not contain valid UTF-8", as `std::fs::read_to_string`).
pub fn read_to_string(path: &Path, limit: u64) -> std::io::Result<String> {
    let bytes = read_bytes(path, limit)?;
    String::from_utf8(bytes).map_err(|_| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "stream did not contain valid UTF-8",
        )
    })
}

/// `path`'s bytes, refusing a file of more than `limit` bytes, as [`read_to_string`] reads them
/// (a FIFO, socket or directory refused before it is opened).
///
/// # Errors
/// As [`read_to_string`], but for UTF-8.
pub fn read_bytes(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    readable(&std::fs::metadata(path)?)?;
    let file = open_without_waiting(path)?;
    // The path may have been replaced between the two looks: the file opened is checked too.
    readable(&file.metadata()?)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("is larger than {limit} bytes, the limit on input files"),
        ));
    }
    Ok(bytes)
}

/// Whether a file of this metadata may be read: a regular file or a character device, anything
/// else refused (kind `InvalidInput`, "must be a regular file ...") naming what it is.
fn readable(meta: &std::fs::Metadata) -> std::io::Result<()> {
    let kind = meta.file_type();
    if kind.is_file() {
        return Ok(());
    }
    let what = if kind.is_dir() {
        "a directory"
    } else {
        special(&kind)
    };
    if what.is_empty() {
        return Ok(());
    }
    Err(std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("must be a regular file, and this is {what}"),
    ))
}

/// What a special file is, in words (empty for a character device, which is read).
#[cfg(unix)]
fn special(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_fifo() {
        "a pipe (a named pipe or FIFO, or `<(...)`), whose contents can be read only once: an input is read more than once (checked before anything runs, then read by the run and hashed for its record), so save it to a file and give that"
    } else if kind.is_socket() {
        "a socket"
    } else if kind.is_block_device() {
        "a block device"
    } else if kind.is_char_device() {
        ""
    } else {
        "not a file"
    }
}

/// What a special file is, in words: anything but a file or a directory.
#[cfg(not(unix))]
fn special(_: &std::fs::FileType) -> &'static str {
    "not a file"
}

/// Opens `path` for reading without waiting (a FIFO swapped in after the first look would
/// otherwise block the open until a writer comes).
#[cfg(unix)]
fn open_without_waiting(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

/// Opens `path` for reading.
#[cfg(not(unix))]
fn open_without_waiting(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::File::open(path)
}

/// A kind of RON input file in the user's words: what it is and the shape it has, for the
/// message given when a file is not one at all (empty, JSON, CSV, another shape).
#[derive(Debug, Clone, Copy)]
pub struct RonFile {
    /// What the file is, with its article: `a pair file`.
    pub what: &'static str,
    /// Its outline: `( driver: (...), driven: (...), ... )`.
    pub shape: &'static str,
}

/// A RON file that could not be read: where (`line 3, column 7`) and the rule, in the user's
/// words (no Rust type names).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RonError {
    /// `line L, column C`.
    pub location: String,
    /// What was wrong.
    pub rule: String,
}

/// Parses `text` as RON with `options`, as a `kind` file: a leading UTF-8 byte-order mark is
/// skipped; an empty file, or one that does not open with `(` (JSON, CSV, a list), is said to
/// be one ("expected a pair file in RON, `( ... )`; this looks like JSON"); any other error is
/// [`ron_rule`]'s. Nesting deeper than ron's recursion limit is an error, not a stack overflow.
///
/// # Errors
/// The location and rule of the first problem.
pub fn parse_ron<T: serde::de::DeserializeOwned>(
    options: &ron::Options,
    text: &str,
    kind: &RonFile,
) -> Result<T, RonError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let expected = |why: String| format!("expected {} in RON, `{}`; {why}", kind.what, kind.shape);
    let e = match options.from_str::<T>(text) {
        Ok(value) => return Ok(value),
        Err(e) => e,
    };
    match significant_start(text) {
        None => Err(RonError {
            location: "line 1, column 1".into(),
            rule: expected("the file is empty".into()),
        }),
        Some((at, c)) if c != '(' => {
            let (line, col) = line_col(text, at);
            Err(RonError {
                location: format!("line {line}, column {col}"),
                rule: expected(looks_like(&text[at..])),
            })
        }
        Some(_) => Err(RonError {
            location: format!("line {}, column {}", e.position.line, e.position.col),
            rule: ron_rule(&e.code),
        }),
    }
}

/// The byte offset and character where the RON value starts: after whitespace, comments and
/// `#![enable(...)]` attributes; `None` when there is nothing else.
fn significant_start(text: &str) -> Option<(usize, char)> {
    let mut i = 0;
    while i < text.len() {
        let rest = &text[i..];
        let c = rest.chars().next()?;
        if c.is_whitespace() {
            i += c.len_utf8();
        } else if rest.starts_with("//") {
            i += rest.find('\n').unwrap_or(rest.len());
        } else if rest.starts_with("/*") {
            i += rest.find("*/").map_or(rest.len(), |e| e + 2);
        } else if rest.starts_with("#![") {
            i += rest.find(']').map_or(rest.len(), |e| e + 1);
        } else {
            return Some((i, c));
        }
    }
    None
}

/// 1-based line and column (in characters) of byte offset `at`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// What a file that does not open with `(` looks like, in a few words.
fn looks_like(rest: &str) -> String {
    let first_line = rest.lines().next().unwrap_or("");
    let list_of_objects = rest.starts_with('[') && rest[1..].trim_start().starts_with(['{', '"']);
    if rest.starts_with('{') || list_of_objects || first_line.contains("\":") {
        "this looks like JSON".into()
    } else if first_line.contains(',') && !first_line.contains(['(', '{', '[', ':']) {
        "this looks like CSV".into()
    } else {
        let head: String = first_line.chars().take(20).collect();
        format!("it begins with `{}` instead", head.escape_debug())
    }
}

/// A RON parse error's rule in the user's words: ron names the Rust type a value was meant for
/// (`Unexpected field named `colour`in `GearData`, ...`, with no space before `in`; `Expected
/// opening `(` for struct `PairFile``); the reader never wrote that type, so it is left out:
/// `Unexpected field named `colour`, expected one of `name`, `teeth` instead`.
pub fn ron_rule(code: &ron::Error) -> String {
    use ron::Error as E;
    let plain = match code.clone() {
        E::NoSuchStructField {
            expected, found, ..
        } => E::NoSuchStructField {
            expected,
            found,
            outer: None,
        },
        E::NoSuchEnumVariant {
            expected, found, ..
        } => E::NoSuchEnumVariant {
            expected,
            found,
            outer: None,
        },
        E::MissingStructField { field, .. } => E::MissingStructField { field, outer: None },
        E::DuplicateStructField { field, .. } => E::DuplicateStructField { field, outer: None },
        E::ExpectedNamedStructLike(_) => E::ExpectedStructLike,
        E::ExpectedDifferentStructName { found, .. } => {
            return format!("Expected opening `(`, found the name `{found}`");
        }
        E::InvalidValueForType { expected, found } => E::InvalidValueForType {
            expected: without_type_names(&expected),
            found,
        },
        E::ExceededRecursionLimit => {
            return "Brackets nested too deeply (more than 128 levels): no input file nests so deep".into();
        }
        E::Message(m) => E::Message(without_type_names(&m)),
        other => other,
    };
    plain.to_string()
}

/// serde's description of a Rust type (`struct PairFile`, `enum Start`, `tuple struct X`) said
/// without the type's name.
fn without_type_names(text: &str) -> String {
    let mut out = text.to_string();
    for (kind, words) in [
        ("tuple struct ", "a `(...)` group"),
        ("struct variant ", "a `Name(...)` value"),
        ("struct ", "a `(...)` group of named fields"),
        ("enum ", "one of the words this field takes"),
    ] {
        while let Some(i) = out.find(kind) {
            let after = &out[i + kind.len()..];
            let name_len = after
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '`' || c == ':'))
                .unwrap_or(after.len());
            out = format!("{}{words}{}", &out[..i], &after[name_len..]);
        }
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn ron_rules_name_no_rust_type() {
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)] // Reason: only the error matters.
        struct GearData {
            teeth: u32,
        }
        let e = ron::from_str::<GearData>("(teeth: 3, colour: 1)").unwrap_err();
        assert!(e.code.to_string().contains("`colour`in `GearData`"));
        let rule = ron_rule(&e.code);
        assert_eq!(
            rule,
            "Unexpected field named `colour`, expected `teeth` instead"
        );
        let e = ron::from_str::<GearData>("()").unwrap_err();
        assert_eq!(ron_rule(&e.code), "Unexpected missing field `teeth`");
    }

    #[test]
    fn files_that_are_not_the_ron_expected_are_said_to_be() {
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)] // Reason: only the errors matter.
        struct GearData {
            teeth: Vec<u32>,
        }
        const KIND: RonFile = RonFile {
            what: "a gear list",
            shape: "( teeth: [...] )",
        };
        let parse = |text: &str| parse_ron::<GearData>(&ron::Options::default(), text, &KIND);
        assert!(parse("\u{feff}(teeth: [3])").is_ok());
        assert!(parse("// a gear\n#![enable(implicit_some)]\n(teeth: [3])").is_ok());
        for (text, why) in [
            ("", "the file is empty"),
            ("\u{feff}  \n", "the file is empty"),
            ("{\"teeth\": [3]}", "this looks like JSON"),
            ("teeth,name\n3,a\n", "this looks like CSV"),
            ("teeth: [3]", "it begins with `teeth: [3]` instead"),
        ] {
            let e = parse(text).unwrap_err();
            assert_eq!(
                e.rule,
                format!("expected a gear list in RON, `( teeth: [...] )`; {why}"),
                "{text}"
            );
        }
        let deep = format!("(teeth: {}", "[".repeat(10_000));
        let e = parse(&deep).unwrap_err();
        assert!(!e.rule.contains("GearData"), "{e:?}");
        let e = parse(&format!("({})", "(".repeat(10_000))).unwrap_err();
        assert!(!e.rule.contains("GearData"), "{e:?}");
    }

    #[test]
    fn endless_files_are_refused_at_the_limit() {
        for endless in ["/dev/zero", "/dev/urandom"] {
            if Path::new(endless).exists() {
                let e = read_to_string(Path::new(endless), 1000).unwrap_err();
                assert!(e.to_string().contains("larger than 1000 bytes"), "{e}");
            }
        }
    }

    #[test]
    fn what_is_not_a_regular_file_is_refused_before_it_is_opened() {
        let dir = std::env::temp_dir().join(format!("input-file-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = read_to_string(&dir, 100).unwrap_err();
        assert!(e.to_string().contains("is a directory"), "{e}");
        let fifo = dir.join("pipe.ron");
        // A named pipe with no writer: opening it for reading would wait for ever.
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let e = read_to_string(&fifo, 100).unwrap_err();
            assert!(
                e.to_string()
                    .contains("must be a regular file, and this is a pipe (a named pipe"),
                "{e}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn small_files_read_whole_and_bad_utf8_is_named() {
        let dir = std::env::temp_dir().join(format!("input-file-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let ok = dir.join("ok.ron");
        std::fs::write(&ok, "(a: 1)").unwrap();
        assert_eq!(read_to_string(&ok, 6).unwrap(), "(a: 1)");
        assert!(read_to_string(&ok, 5).is_err());
        let bad = dir.join("bad.ron");
        std::fs::write(&bad, b"(a: \xff)").unwrap();
        assert!(
            read_to_string(&bad, 100)
                .unwrap_err()
                .to_string()
                .contains("UTF-8")
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
