//! Reading a user's input file (config, gearing, error table, partial file) with a size limit.
//!
//! `std::fs::read_to_string` reads until the end of the file: on `/dev/zero` it grows until
//! the allocator gives up, on `/dev/urandom` it never ends. [`read_to_string`] reads at most
//! `limit + 1` bytes and refuses a file longer than `limit` with an [`std::io::Error`] whose
//! message states the limit, so callers keep their "FILE: cannot read: ..." messages.

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
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("is larger than {limit} bytes, the limit on input files"),
        ));
    }
    String::from_utf8(bytes).map_err(|_| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "stream did not contain valid UTF-8",
        )
    })
}

/// A RON parse error's rule in the user's words: ron names the Rust type a misspelt field was
/// meant for (`Unexpected field named `colour`in `GearData`, ...`, with no space before `in`);
/// the reader never wrote that type, so it is left out:
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
        other => other,
    };
    plain.to_string()
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
    fn endless_files_are_refused_at_the_limit() {
        for endless in ["/dev/zero", "/dev/urandom"] {
            if Path::new(endless).exists() {
                let e = read_to_string(Path::new(endless), 1000).unwrap_err();
                assert!(e.to_string().contains("larger than 1000 bytes"), "{e}");
            }
        }
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
