//! The `settings` fuzz target of `cargo xtask fuzz`: the `--set KEY=VALUE` strings of every
//! experiment, checked as `run` checks them before anything computes (the parameter kinds in
//! [`registry::Context::new`], then the files and shared settings in [`setting_groups::inputs::check`]).
//!
//! It lives beside [`crate::fuzz_targets`] rather than in it: those targets are also built by
//! the cargo-fuzz crate in `fuzz/`, which does not depend on the registry or the experiments.
//!
//! An input is lines `ID KEY=VALUE`: each a `--set` for experiment ID (lines of other shapes are
//! skipped, as a mutation leaves many). Promises, beyond "no panic" and "within two seconds":
//! - a refusal is one non-empty line naming the flag (`--set`, `--hypothesis`) or the file;
//! - an accepted input gives each experiment its values back unchanged.

use crate::fuzz_targets::Outcome;

/// The most experiments one input is checked for (each check loads its gearing).
const MAX_EXPERIMENTS: usize = 8;

/// The seed: every parameter of every experiment at its default, one `ID KEY=VALUE` line each.
pub fn seed() -> &'static str {
    static SEED: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    SEED.get_or_init(|| {
        experiments::link();
        let mut s = String::new();
        for (id, e) in registry::experiments().unwrap_or_default() {
            for p in e.all_params() {
                s.push_str(&format!("{id} {}={}\n", p.name, p.default));
            }
        }
        s
    })
}

/// The `--set` lines of `text`, grouped by experiment id in order of first appearance.
fn grouped(text: &str) -> Vec<(&str, Vec<(String, String)>)> {
    let mut groups: Vec<(&str, Vec<(String, String)>)> = Vec::new();
    for line in text.lines() {
        let Some((id, set)) = line.split_once(' ') else {
            continue;
        };
        let Some((key, value)) = set.split_once('=') else {
            continue;
        };
        let pair = (key.to_owned(), value.to_owned());
        match groups.iter_mut().find(|(g, _)| *g == id) {
            Some((_, sets)) => sets.push(pair),
            None => groups.push((id, vec![pair])),
        }
    }
    groups
}

/// A refusal of `sets` must be one non-empty line naming a flag or a value given (a file).
fn check_refusal(message: String, sets: &[(String, String)]) -> Result<Outcome, String> {
    if message.trim().is_empty() || message.contains('\n') {
        return Err(format!("refusal is not one line: {message:?}"));
    }
    let names_flag = ["--set", "--hypothesis", "--threads"]
        .iter()
        .any(|f| message.starts_with(f));
    // A file is named as given, its control characters escaped to keep the line.
    let names_file = sets.iter().any(|(_, v)| {
        let shown: String = v
            .chars()
            .flat_map(|c| {
                if c.is_control() {
                    c.escape_default().collect::<Vec<_>>()
                } else {
                    vec![c]
                }
            })
            .collect();
        !v.trim().is_empty() && message.starts_with(&shown)
    });
    if !names_flag && !names_file {
        return Err(format!(
            "refusal names neither the flag nor the file first: {message:?}"
        ));
    }
    Ok(Outcome::Refused(message))
}

/// The `settings` target.
pub fn settings(text: &str) -> Result<Outcome, String> {
    experiments::link();
    let all = registry::experiments().map_err(|e| format!("registry: {e}"))?;
    let mut seen = std::collections::BTreeSet::new();
    for (id, sets) in grouped(text).into_iter().take(MAX_EXPERIMENTS) {
        let Some(e) = all.get(id) else {
            continue;
        };
        let ctx = match registry::Context::new(e, 2025, 1, &sets, None) {
            Ok(ctx) => ctx,
            Err(err) => return check_refusal(err.to_string(), &sets),
        };
        if let Err(m) =
            setting_groups::inputs::check(&ctx, ("--hypothesis", "--set measured"), &mut seen)
        {
            return check_refusal(m, &sets);
        }
        // The last value of a key is the one given.
        for (key, value) in &sets {
            let last = sets.iter().rev().find(|(k, _)| k == key).map(|(_, v)| v);
            match ctx.values().find(|(p, _)| p.name == key) {
                Some((_, got)) if Some(&got.to_owned()) == last => {}
                Some((_, got)) => {
                    return Err(format!("{id}: accepted {key}={value:?} but holds {got:?}"));
                }
                None => return Err(format!("{id}: accepted {key}, which it does not declare")),
            }
        }
    }
    Ok(Outcome::Accepted)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_accepted_and_bad_values_refused_in_one_line() {
        assert_eq!(settings(seed()), Ok(Outcome::Accepted));
        for bad in [
            "figIV from=-1",
            "figIV from=nan",
            "contact-tolerance tolerance=1e400",
            "clearance events=bogus",
            "clearance mesh=z9-y9",
            "table1 trials=99999999999999999999999",
            "figIV nosuch=1",
            "clearance gearing= ",
        ] {
            match settings(bad) {
                Ok(Outcome::Refused(m)) => assert!(m.starts_with("--set: "), "{bad}: {m}"),
                other => panic!("{bad}: {other:?}"),
            }
        }
    }
}
