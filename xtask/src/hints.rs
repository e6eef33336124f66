//! Likely mistakes caught before or after a refusal: a name close to a known one ("did you mean"),
//! an optional RON field written without `Some(...)`, and warnings on stderr for input that runs
//! but is probably not what was meant (tip angles in radians, a clearance of a fraction of a per
//! cent, `run pair` with no file).

use registry::{ConfigFile, Entry};

/// Edit distance (insertions, deletions, substitutions and swaps of neighbours), ASCII
/// case-insensitive.
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}

/// The known name closest to `typed`, if it is close enough to be what was meant: at most a
/// third of its letters off (at least one), or `typed` a prefix of it.
pub(crate) fn closest<'a>(
    typed: &str,
    known: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = (typed.chars().count() / 3).max(1);
    known
        .into_iter()
        .filter(|k| !k.is_empty() && *k != typed)
        .map(|k| {
            let d = distance(typed, k);
            let prefix = typed.len() >= 3 && k.to_lowercase().starts_with(&typed.to_lowercase());
            (if prefix { d.min(1) } else { d }, k)
        })
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, k)| (d, k.len()))
        .map(|(_, k)| k)
}

/// The names a refusal lists after `known ...:` (`known experiments: a, b`, `known keys of X: a,
/// b`, `known: a, b`), up to the closing bracket or the end.
fn listed(msg: &str) -> Vec<String> {
    let Some(at) = msg.rfind("known") else {
        return Vec::new();
    };
    let rest = &msg[at..];
    let Some(colon) = rest.find(':') else {
        return Vec::new();
    };
    let list = &rest[colon + 1..];
    let list = list.split([')', ';']).next().unwrap_or("");
    let list = list.split(", or ").next().unwrap_or("");
    list.split(',')
        .map(|s| s.trim().to_owned())
        .filter(|s| !s.is_empty() && !s.contains(' '))
        .collect()
}

/// The first name in backticks in `msg`.
fn quoted(msg: &str) -> Option<&str> {
    let start = msg.find('`')? + 1;
    let len = msg[start..].find('`')?;
    Some(&msg[start..start + len])
}

/// Every name a user may type that the runner knows: experiment ids, hypothesis and event rule
/// names, and every parameter of every experiment.
fn every_name(exps: &crate::shared::Registry) -> (Vec<&'static str>, Vec<&'static str>) {
    let mut names: Vec<&'static str> = exps.keys().copied().collect();
    if let Ok(h) = hypotheses::hypotheses() {
        names.extend(h.keys().copied());
    }
    if let Ok(r) = rules::rules() {
        names.extend(r.keys().copied());
    }
    let mut params: Vec<&'static str> = exps
        .values()
        .flat_map(|e| e.all_params().map(|p| p.name))
        .collect();
    params.sort_unstable();
    params.dedup();
    (names, params)
}

/// `msg` (a refusal) with a suggestion added where it names something unknown that is close to
/// a known name: `...; did you mean `table5`?`. Covers experiment ids (`run`, `help`, `replay`),
/// hypothesis and event rule names, their parameters, and `--set` keys.
pub(crate) fn did_you_mean(msg: &str) -> String {
    let exps = registry::experiments().unwrap_or_default();
    let (names, params) = every_name(&exps);
    // `--set: KEY: ...`: the key is the thing typed.
    let set_key = msg
        .strip_prefix("--set: ")
        .and_then(|r| r.split(':').next())
        .filter(|k| !k.contains(' '));
    let known = listed(msg);
    let suggestion: Option<String> = if msg.contains("no selected experiment has this parameter") {
        set_key.and_then(|k| closest(k, params.iter().copied()))
    } else if msg.contains("unknown parameter of experiment") {
        set_key.and_then(|k| closest(k, known.iter().map(String::as_str)))
    } else if msg.contains("unknown experiment, error hypothesis or event rule") {
        quoted(msg).and_then(|t| closest(t, names.iter().copied()))
    } else if msg.contains("unknown experiment")
        || msg.contains(": unknown; known")
        || msg.contains("unknown key (known keys")
    {
        quoted(msg).and_then(|t| closest(t, known.iter().map(String::as_str)))
    } else {
        None
    }
    .map(str::to_owned);
    match suggestion {
        Some(s) => format!("{msg}; did you mean `{s}`?"),
        None => ron_option_hint(msg).map_or_else(|| msg.to_owned(), |h| format!("{msg}: {h}")),
    }
}

/// For a RON file refused with `FILE: line L, column C: Expected option`: the field there, and
/// how to write it (`clearance_percent: Some(50.0)`).
fn ron_option_hint(msg: &str) -> Option<String> {
    let head = msg
        .strip_suffix("Expected option")?
        .trim_end_matches([' ', ':']);
    let (file, place) = head.rsplit_once(": line ")?;
    let (line, column) = place.split_once(", column ")?;
    let (line, column): (usize, usize) = (line.trim().parse().ok()?, column.trim().parse().ok()?);
    let field = input_file::read_to_string(std::path::Path::new(file), input_file::MAX_INPUT_BYTES)
        .ok()
        .and_then(|text| {
            let l = text.lines().nth(line.checked_sub(1)?)?;
            let before: String = l.chars().take(column.saturating_sub(1)).collect();
            let before = before.trim_end().strip_suffix(':')?;
            let name: String = before
                .chars()
                .rev()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect();
            (!name.is_empty()).then_some(name)
        });
    Some(match field {
        Some(f) => format!(
            "`{f}` is optional: write its value inside Some(...), e.g. `{f}: Some(...)`, or leave the field out"
        ),
        None => {
            "an optional field's value goes inside Some(...), e.g. `clearance_percent: Some(40.0)`"
                .into()
        }
    })
}

/// Warnings for a run about to start (stderr, unless `-q`): values that run but are probably
/// not what was meant.
pub(crate) fn warnings(
    e: &Entry,
    sets: &[(String, String)],
    config: Option<&ConfigFile>,
) -> Vec<String> {
    let mut out = Vec::new();
    // A clearance below 1 % of h: a fraction typed for a percentage, or tips all but touching
    // the opposite valleys. One value (`clearance`) or a list of them (`clearances`, `grid`).
    for (key, value) in sets {
        let Some(p) = e.all_params().find(|p| p.name == key) else {
            continue;
        };
        if !p.clearance {
            continue;
        }
        // One clearance, or a list of them (a text parameter).
        let one = !matches!(p.kind, registry::Kind::Text);
        for item in value.split(',') {
            let Ok(v) = item.trim().parse::<f64>() else {
                continue;
            };
            if fraction_of_a_clearance(v) && one {
                let meant = percent(v);
                out.push(format!(
                    "warning: {}: --set {name}={value} is {value} % of the tooth height h (the unit is % of h, not a fraction of it); for {meant} % write --set {name}={meant}",
                    e.id,
                    name = p.name,
                ));
            } else if fraction_of_a_clearance(v) {
                let meant = percent(v);
                out.push(format!(
                    "warning: {}: --set {}={value}: {} is {} % of the tooth height h (the unit is % of h, not a fraction of it); for {meant} % write {meant} in the list",
                    e.id,
                    p.name,
                    item.trim(),
                    item.trim(),
                ));
            } else if let Some(why) = tiny_clearance(v) {
                out.push(format!(
                    "warning: {}: --set {}={value}: {why}",
                    e.id, p.name
                ));
            }
        }
    }
    if let Some((_, h)) = sets
        .iter()
        .rev()
        .find(|(k, _)| k == study::errors::PARAM.name)
        && e.declares(&study::errors::PARAM)
        && crate::provenance::uses_example_table(h)
    {
        out.push(format!(
            "note: {}: {}",
            e.id,
            crate::provenance::EXAMPLE_TABLE
        ));
    }
    if e.id == "pair" {
        match config {
            None => out.push(
                "note: pair: no --config given, so this runs the example pair (experiments/data/pair-example.ron, invented values); give your own with --config FILE".into(),
            ),
            Some(c) => out.extend(pair_warnings(c)),
        }
    }
    out
}

/// Whether a clearance of `v` % of h looks like a fraction typed for a per cent: below 1 %, and
/// as a per cent (`100 v`) a clearance the paper's gears use (1 to 100 %).
fn fraction_of_a_clearance(v: f64) -> bool {
    (0.01..1.0).contains(&v)
}

/// The smallest clearance (% of h) warned as tiny: below it, the centre distance of gears of a
/// millimetre and up no longer differs in a double from the tips' limit, and the run refuses the
/// clearance itself in one line, which a warning would only precede.
const TINIEST_WARNED: f64 = 1e-9;

/// For a clearance `g` (% of h) from [`TINIEST_WARNED`] to below 0.01 %, too small to be a
/// fraction typed for a per cent: what it means, in words. Such a clearance runs, and is what was
/// typed, but its gears jam at nearly every tooth (the paper finds jams below about 10 %).
fn tiny_clearance(g: f64) -> Option<String> {
    (TINIEST_WARNED..0.01).contains(&g).then(|| {
        format!(
            "a clearance of {} % of the tooth height h leaves the tips {} of h from the opposite valleys: the gears will jam at nearly every tooth (the paper finds jams below about 10 %); the unit is % of h, so 40 % is written 40",
            registry::fmt_number(g),
            registry::fmt_number(g / 100.0)
        )
    })
}

/// A fraction `v` as the per cent it may have meant, without float noise (0.07 -> 7).
fn percent(v: f64) -> String {
    registry::fmt_f64(v * 100.0, 6)
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_owned()
}

/// A pair file's likely mistakes: tips far from 360/N apart on average (radians typed for
/// degrees), a clearance below 1 % of h.
fn pair_warnings(c: &ConfigFile) -> Vec<String> {
    let name = c.path.display().to_string();
    let Ok(p) = study::pair_file::prepare(&name, &c.text) else {
        // The run refuses it, naming the rule.
        return Vec::new();
    };
    let mut out = Vec::new();
    for (role, g) in [("driver", &p.spec.driver), ("driven", &p.spec.driven)] {
        let Some(tips) = &g.tips_deg else {
            continue;
        };
        let (Some(first), Some(last)) = (tips.first(), tips.last()) else {
            continue;
        };
        if tips.len() < 2 {
            continue;
        }
        let mean = (last - first) / (tips.len() - 1) as f64;
        let pitch = 360.0 / g.teeth as f64;
        if !(0.5 * pitch..=1.5 * pitch).contains(&mean.abs()) {
            let radians = (mean.abs() - pitch.to_radians()).abs() < 0.2 * pitch.to_radians();
            out.push(format!(
                "warning: {name}: {role}.tips_deg: the tips are {} deg apart on average, far from 360/{} = {} deg{}; tips_deg takes degrees (the run goes on with the values as given)",
                registry::fmt_f64(mean, 4),
                g.teeth,
                registry::fmt_f64(pitch, 4),
                if radians {
                    " - as if they were in radians"
                } else {
                    ""
                }
            ));
        }
    }
    if let Some(g) = p.spec.clearance_percent {
        if fraction_of_a_clearance(g) {
            let meant = percent(g);
            out.push(format!(
                "warning: {name}: clearance_percent: {g} is {g} % of the tooth height h (the unit is % of h, not a fraction of it); for {meant} % write Some({meant})",
            ));
        } else if let Some(why) = tiny_clearance(g) {
            out.push(format!("warning: {name}: clearance_percent: {why}"));
        }
    } else {
        // The clearance a centre distance gives: D = R1 + R2 - h + h G / 100, h the mean height.
        let (d1, d2) = (p.mesh.driver(), p.mesh.driven());
        let h = 0.5 * (d1.tooth_height() + d2.tooth_height());
        let g = (p.mesh.centre_distance() - d1.tip_radius() - d2.tip_radius() + h) / h * 100.0;
        if g > 0.0 && g < 1.0 {
            out.push(format!(
                "warning: {name}: centre_distance: {} gives a clearance of {} % of the mean tooth height h (R1 + R2 - h = {}): the tips all but touch the opposite valleys, and the gears will jam at nearly every tooth (the paper finds jams below about 10 %)",
                registry::fmt_number(p.mesh.centre_distance()),
                registry::fmt_f64(g, 4),
                registry::fmt_number(d1.tip_radius() + d2.tip_radius() - h),
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn close_names_are_suggested_and_far_ones_not() {
        let ids = ["table3", "table4", "table5", "tableI", "fig2", "pair"];
        assert_eq!(closest("tabel5", ids), Some("table5"));
        assert_eq!(closest("Table5", ids), Some("table5"));
        assert_eq!(closest("pari", ids), Some("pair"));
        assert_eq!(closest("zzzzzz", ids), None);
        assert_eq!(
            closest("idle-rotaton", ["idle-rotation", "strict"]),
            Some("idle-rotation")
        );
    }

    #[test]
    fn lists_are_read_from_refusals() {
        assert_eq!(
            listed("unknown experiment `x` (known experiments: a, b-c, d)"),
            ["a", "b-c", "d"]
        );
        assert_eq!(
            listed(
                "error hypothesis `x`: unknown; known hypotheses: ideal, measured, or measured:FILE (a table)"
            ),
            ["ideal", "measured"]
        );
        assert_eq!(
            listed("parameter `m`: unknown key (known keys of friction: mu)"),
            ["mu"]
        );
    }
}
