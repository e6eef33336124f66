//! Reading what runs wrote under `--out`: the result folders, each one's `tables.json`, its
//! figures and files, and its `run.json`; anything unreadable is bad input naming the file,
//! the field and the rule.

use super::*;

/// The result directories under `out`: `(id, path)` for each visible subdirectory holding a
/// `tables.json`, sorted by id.
pub(super) fn scan(out: &Path) -> Result<Vec<(String, PathBuf)>, Failure> {
    let entries = match fs::read_dir(out) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(Failure::Bad(format!(
                "--out: {}: no such directory; run `cargo xtask run <id> --out {}` first",
                out.display(),
                out.display()
            )));
        }
        Err(e) => return Err(bad(out, "", format!("cannot read the directory: {e}"))),
    };
    let mut found = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| bad(out, "", format!("cannot read the directory: {e}")))?;
        let Ok(name) = entry.file_name().into_string() else {
            continue; // Not an experiment id.
        };
        let path = entry.path();
        if name.starts_with('.') {
            continue;
        }
        if holds_results(&path)? {
            found.push((name, path));
        }
    }
    found.sort();
    Ok(found)
}

/// Whether the entry `path` of the results folder is a folder of results (it holds a
/// `tables.json`); other files and folders of no results (a sharded run's partial files) are
/// not. What cannot be looked at (a folder that cannot be read, a link that leads nowhere or in
/// a loop, a `tables.json` that is not a file) is refused naming it: a page that said "not run"
/// of results it could not read would be wrong.
fn holds_results(path: &Path) -> Result<bool, Failure> {
    let unreadable = |e: std::io::Error| {
        bad(
            path,
            "",
            format!(
                "cannot be read ({e}): the page would show it as not run; make it readable, or move it out of the results folder"
            ),
        )
    };
    let meta = fs::metadata(path).map_err(unreadable)?;
    if !meta.is_dir() {
        return Ok(false);
    }
    fs::read_dir(path).map_err(unreadable)?;
    let tables = path.join("tables.json");
    match fs::metadata(&tables) {
        Ok(m) if m.is_file() => Ok(true),
        Ok(_) => Err(bad(&tables, "", "must be a file")),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            // A link named tables.json that leads nowhere is not "no results".
            match fs::symlink_metadata(&tables) {
                Ok(_) => Err(bad(&tables, "", format!("cannot be read ({e})"))),
                Err(_) => Ok(false),
            }
        }
        Err(e) => Err(bad(&tables, "", format!("cannot be read ({e})"))),
    }
}

/// The largest results file (`tables.json`, `run.json`, a figure) the report reads: 256 MiB.
pub(super) const MAX_RESULT_FILE_BYTES: u64 = 256 * 1024 * 1024;

fn read_text(path: &Path) -> Result<String, Failure> {
    input_file::read_to_string(path, MAX_RESULT_FILE_BYTES).map_err(|e| {
        if e.to_string().contains("UTF-8") {
            bad(path, "", "must be UTF-8 text")
        } else {
            bad(path, "", format!("cannot read: {e}"))
        }
    })
}

fn read_json(path: &Path) -> Result<Value, Failure> {
    serde_json::from_str(&read_text(path)?)
        .map_err(|e| bad(path, "", format!("not valid JSON: {e}")))
}

fn strings(v: &Value, path: &Path, field: &str) -> Result<Vec<String>, Failure> {
    v.as_array()
        .and_then(|a| a.iter().map(|s| s.as_str().map(str::to_owned)).collect())
        .ok_or_else(|| bad(path, field, "must be an array of strings"))
}

fn count(v: &Value, path: &Path, field: &str) -> Result<u64, Failure> {
    match v {
        Value::Null => Ok(0),
        _ => v
            .as_u64()
            .ok_or_else(|| bad(path, field, "must be a non-negative integer")),
    }
}

/// Reads `dir/tables.json`, `dir/run.json` (if present) and the SVG figures.
pub(super) fn read_results(dir: &Path) -> Result<Results, Failure> {
    let path = dir.join("tables.json");
    let json = read_json(&path)?;
    if !json.is_object() {
        return Err(bad(&path, "", "must be a JSON object"));
    }
    let tables = read_tables(&json, &path)?;
    let listed = match &json["files"] {
        Value::Null => Vec::new(),
        v => strings(v, &path, "files")?,
    };
    let agreement = read_agreement(&json, &path)?;
    let files = dir_files(dir, &path, &listed)?;
    let figures = read_figures(dir, &listed, &files)?;
    let run_path = dir.join(RUN_JSON);
    let run = if run_path.is_file() {
        Some(read_provenance(&run_path)?)
    } else {
        None
    };
    let ratios = ratio_range(&tables);
    Ok(Results {
        tables,
        ratios,
        trials: count(&json["trials"], &path, "trials")?,
        engagements: count(&json["engagements"], &path, "engagements")?,
        agreement,
        files,
        figures,
        run,
    })
}

/// The tables of `tables.json` (`json`, read from `path`).
fn read_tables(json: &Value, path: &Path) -> Result<Vec<Table>, Failure> {
    let raw_tables = json["tables"]
        .as_array()
        .ok_or_else(|| bad(path, "tables", "must be an array"))?;
    let mut tables = Vec::new();
    for (i, t) in raw_tables.iter().enumerate() {
        let field = |f: &str| format!("tables[{i}].{f}");
        let title = t["title"]
            .as_str()
            .ok_or_else(|| bad(path, &field("title"), "must be a string"))?;
        let columns = strings(&t["columns"], path, &field("columns"))?;
        let mut table = Table::new(title, columns);
        let rows = t["rows"]
            .as_array()
            .ok_or_else(|| bad(path, &field("rows"), "must be an array"))?;
        for (j, row) in rows.iter().enumerate() {
            table
                .rows
                .push(strings(row, path, &field(&format!("rows[{j}]")))?);
        }
        if !t["notes"].is_null() {
            table.notes = strings(&t["notes"], path, &field("notes"))?;
        }
        tables.push(table);
    }
    Ok(tables)
}

/// The agreement `tables.json` records: consistent, differing, and what they count.
fn read_agreement(json: &Value, path: &Path) -> Result<Option<(u64, u64, String)>, Failure> {
    let a = match &json["agreement"] {
        Value::Null => return Ok(None),
        a => a,
    };
    let number = |field: &str| {
        a[field].as_u64().ok_or_else(|| {
            bad(
                path,
                &format!("agreement.{field}"),
                "must be a non-negative integer",
            )
        })
    };
    Ok(Some((
        number("consistent")?,
        number("differ")?,
        a["what"].as_str().unwrap_or_default().to_owned(),
    )))
}

/// The visible files of `dir`, sorted; each file `tables.json` (`path`) lists must be there.
fn dir_files(dir: &Path, path: &Path, listed: &[String]) -> Result<Vec<String>, Failure> {
    let mut files = Vec::new();
    let entries = fs::read_dir(dir).map_err(|e| bad(dir, "", format!("cannot read: {e}")))?;
    for entry in entries {
        let entry = entry.map_err(|e| bad(dir, "", format!("cannot read: {e}")))?;
        if let Ok(name) = entry.file_name().into_string()
            && !name.starts_with('.')
            && entry.path().is_file()
        {
            files.push(name);
        }
    }
    files.sort();
    for name in listed {
        if !files.contains(name) {
            return Err(bad(
                path,
                "files",
                format!("lists {name}, which is not in {}", dir.display()),
            ));
        }
    }
    Ok(files)
}

/// The SVG figures of `dir`: those `tables.json` lists, in its order, then any other SVG; each
/// must draw something.
fn read_figures(
    dir: &Path,
    listed: &[String],
    files: &[String],
) -> Result<Vec<(String, Embed)>, Failure> {
    let mut svg_names: Vec<&String> = listed.iter().filter(|n| is_svg(n)).collect();
    svg_names.extend(files.iter().filter(|n| is_svg(n) && !listed.contains(*n)));
    let mut figures = Vec::new();
    for name in svg_names {
        let file = dir.join(name);
        let text = read_text(&file)?;
        if !has_drawing(&text) {
            return Err(bad(
                &file,
                "",
                "must be an SVG drawing something (a path, polyline, polygon or line)",
            ));
        }
        figures.push((name.clone(), embed_svg(&text)));
    }
    Ok(figures)
}

/// The smallest and largest number of the columns headed `ours/paper` of `tables`; `None`
/// where there is none.
fn ratio_range(tables: &[Table]) -> Option<(f64, f64)> {
    let values: Vec<f64> = tables
        .iter()
        .flat_map(|t| {
            let at = t.columns.iter().position(|c| c.trim() == "ours/paper");
            t.rows
                .iter()
                .filter_map(move |r| r.get(at?)?.trim().parse::<f64>().ok())
        })
        .filter(|v| v.is_finite())
        .collect();
    let lo = values.iter().copied().reduce(f64::min)?;
    let hi = values.iter().copied().reduce(f64::max)?;
    Some((lo, hi))
}

/// An experiment's cell of the page's overview: how its numbers compare with the paper's and
/// what that counts (`9 / 20 gears whose ...`), or the range of ours over the paper's where it
/// judges none, or `-`.
pub(super) fn overview_cell(r: Option<&Results>) -> String {
    match r {
        // On other inputs the paper's numbers are no check of ours.
        Some(r) if departs(r) => "-".to_owned(),
        Some(Results {
            agreement: Some((c, d, what)),
            ..
        }) if what.is_empty() => {
            format!("{c} / {d}: the paper's numbers consistent with ours / differing")
        }
        Some(Results {
            agreement: Some((c, d, what)),
            ..
        }) => format!("{c} / {d}: {what}"),
        Some(Results {
            ratios: Some((lo, hi)),
            ..
        }) => format!("ours/paper {lo:.2} to {hi:.2} (no test: the paper gives no interval)"),
        _ => "-".to_owned(),
    }
}

fn read_provenance(path: &Path) -> Result<Provenance, Failure> {
    let v = read_json(path)?;
    let text = |field: &str, value: &Value| -> Result<String, Failure> {
        value
            .as_str()
            .map(str::to_owned)
            .ok_or_else(|| bad(path, field, "must be a string"))
    };
    let number = |field: &str| -> Result<u64, Failure> {
        v[field]
            .as_u64()
            .ok_or_else(|| bad(path, field, "must be a non-negative integer"))
    };
    let overrides = match &v["overrides"] {
        Value::Null => Vec::new(),
        Value::Object(m) => m
            .iter()
            .map(|(k, val)| Ok((k.clone(), text(&format!("overrides.{k}"), val)?)))
            .collect::<Result<_, Failure>>()?,
        _ => return Err(bad(path, "overrides", "must be an object of strings")),
    };
    let config = match &v["config"] {
        Value::Null => None,
        c => Some(text("config", c)?),
    };
    Ok(Provenance {
        seed: number("seed")?,
        threads: number("threads")?,
        overrides,
        config,
        version: text("version.crate", &v["version"]["crate"])?,
        git: text("version.git", &v["version"]["git"])?,
        date: text("date", &v["date"])?,
    })
}
