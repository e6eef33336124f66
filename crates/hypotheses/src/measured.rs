//! Per-gear error values from a RON table (Edmunds' measurements, or anyone's).

use std::collections::BTreeMap;
use std::sync::{LazyLock, Mutex, PoisonError};

use geometry::Gear;
use serde::Deserialize;

use crate::{About, Describe, EdmundsErrors, Hypothesis, HypothesisError, Kind, Param, Params};

/// The example table the registered `measured` hypothesis uses. Its values are INVENTED (the
/// file says so): Edmunds' per-gear measurements are not public here.
pub const MEASURED_EXAMPLE: &str = include_str!("../data/measured-example.ron");

/// One gear's measured errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredEntry {
    /// Random tooth error: sd of a tip's displacement as a fraction of the pitch.
    pub random: f64,
    /// Systematic amplitude A, degrees.
    pub systematic_deg: f64,
    /// Phase of the sinusoid, degrees; `None`: drawn uniformly.
    pub phase_deg: Option<f64>,
    /// Share of A on the sinusoid; `None`: the table's `split`.
    pub split: Option<f64>,
}

/// A table of per-gear error values, read by [`measured_from_ron`].
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredTable {
    file_name: String,
    split: f64,
    gears: BTreeMap<String, MeasuredEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTable {
    #[serde(default = "paper_split")]
    split: f64,
    gears: Vec<RawEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEntry {
    gear: String,
    random: f64,
    systematic: f64,
    #[serde(default)]
    phase: Option<f64>,
    #[serde(default)]
    split: Option<f64>,
}

fn paper_split() -> f64 {
    0.5
}

/// A measured-error table in the user's words, for a file that is not one at all.
pub const RON_FILE: input_file::RonFile = input_file::RonFile {
    what: "a measured-error table",
    shape: "( gears: [ (gear: \"b1\", random: 0.05, systematic: 0.6), ... ] )",
};

/// Reads a table of per-gear errors; `file_name` only names the source in errors.
///
/// ```text
/// (
///     split: 0.5,   // optional: share of each systematic amplitude on the sinusoid (the paper's 50/50)
///     gears: [
///         (gear: "b1", random: 0.05, systematic: 0.6, phase: 30.0),   // phase in degrees, optional
///         (gear: "b2", random: 0.04, systematic: 0.0, split: 1.0),    // split per gear, optional
///     ],
/// )
/// ```
///
/// Errors name the file and the gear (or the RON position) and the rule: unknown fields, a gear
/// listed twice, a negative or non-finite value, a split outside [0, 1].
pub fn measured_from_ron(file_name: &str, text: &str) -> Result<MeasuredTable, HypothesisError> {
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let raw: RawTable = input_file::parse_ron(&options, text, &RON_FILE)
        .map_err(|e| HypothesisError::new(format!("{file_name}: {}", e.location), e.rule))?;
    if !(0.0..=1.0).contains(&raw.split) {
        return Err(HypothesisError::new(
            format!("{file_name}: split"),
            format!(
                "must be between 0 and 1 (got {})",
                registry::fmt_number(raw.split)
            ),
        ));
    }
    let mut gears = BTreeMap::new();
    for (i, e) in raw.gears.into_iter().enumerate() {
        if e.gear.trim().is_empty() {
            return Err(HypothesisError::new(
                format!("{file_name}: gears[{i}]"),
                format!(
                    "gear must name a gear of the gearing, not be empty (got {:?})",
                    e.gear
                ),
            ));
        }
        let entry = MeasuredEntry {
            random: e.random,
            systematic_deg: e.systematic,
            phase_deg: e.phase,
            split: e.split,
        };
        errors_of(&entry, raw.split).check(&format!("{file_name}: gear {}", e.gear))?;
        if gears.insert(e.gear.clone(), entry).is_some() {
            return Err(HypothesisError::new(
                format!("{file_name}: gear {}", e.gear),
                "listed twice",
            ));
        }
    }
    Ok(MeasuredTable {
        file_name: file_name.to_owned(),
        split: raw.split,
        gears,
    })
}

fn errors_of(entry: &MeasuredEntry, table_split: f64) -> EdmundsErrors {
    EdmundsErrors {
        random: entry.random,
        systematic_deg: entry.systematic_deg,
        split: entry.split.unwrap_or(table_split),
        phase_deg: entry.phase_deg,
    }
}

impl MeasuredTable {
    /// The file name the table was read from (as given).
    pub fn file_name(&self) -> &str {
        &self.file_name
    }

    /// The table-wide split (0.5 unless the table says otherwise).
    pub fn split(&self) -> f64 {
        self.split
    }

    /// Every gear of the table with its values, sorted by name.
    pub fn entries(&self) -> impl Iterator<Item = (&str, &MeasuredEntry)> {
        self.gears.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// The errors of `gear_name` (split resolved); a gear missing from the table is an error
    /// naming it.
    pub fn errors(&self, gear_name: &str) -> Result<EdmundsErrors, HypothesisError> {
        self.gears
            .get(gear_name)
            .map(|e| errors_of(e, self.split))
            .ok_or_else(|| {
                HypothesisError::new(
                    format!("{}: gear {gear_name}", self.file_name),
                    "missing from the table (every gear the hypothesis is applied to needs a row)",
                )
            })
    }

    /// A hypothesis (named `measured`) applying this table, for an experiment to use with a
    /// user's file.
    pub fn hypothesis(&self) -> MeasuredHypothesis {
        MeasuredHypothesis {
            about: MEASURED,
            table: self.clone(),
        }
    }

    /// `gear` with its row's errors, every value scaled by `params`' `scale`.
    pub(crate) fn apply_scaled(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        let scale = params.value(&SCALE);
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(HypothesisError::new(
                "measured: scale",
                format!(
                    "must be a finite number >= 0 (got {})",
                    registry::fmt_number(scale)
                ),
            ));
        }
        let mut errors = self.errors(gear_name)?;
        errors.random *= scale;
        errors.systematic_deg *= scale;
        errors.check(&format!(
            "{}: gear {gear_name} (scaled by {scale})",
            self.file_name
        ))?;
        errors.apply(gear, gear_name, rng)
    }
}

/// Parameters of every `measured` hypothesis.
pub(crate) const MEASURED_PARAMS: &[Param] = &[SCALE];

/// Parameter `scale` of every `measured` hypothesis.
const SCALE: Param = Param::new(
    "scale",
    "1",
    "multiplies every random and systematic value of the table",
    Kind::ANY_NUMBER,
);

/// What every `measured` hypothesis says of itself; one over a file read by [`measured_file`]
/// is named `measured:FILE`.
pub(crate) const MEASURED: About = About {
    name: "measured",
    summary: "per-gear random fraction, systematic amplitude (deg) and optional phase from a RON table, 50/50 split unless it says otherwise; registered with an INVENTED example table (crates/hypotheses/data/measured-example.ron)",
    details: "",
};

/// The `measured` hypothesis over a given table (see [`MeasuredTable::hypothesis`] and
/// [`measured_file`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredHypothesis {
    /// Named `measured`, or `measured:FILE` for a table read by [`measured_file`].
    about: About,
    table: MeasuredTable,
}

/// Tables read by [`measured_file`], by (path, contents): each read once per process.
static LOADED: LazyLock<Mutex<BTreeMap<(String, String), &'static MeasuredHypothesis>>> =
    LazyLock::new(|| Mutex::new(BTreeMap::new()));

/// The measured-errors file a `measured` parameter names, if it names one: the value trimmed,
/// `None` when it is empty or `none` (the way every experiment with the parameter spells "no
/// measured table", so the runner's checks and the experiments agree).
#[must_use]
pub fn measured_file_given(value: &str) -> Option<&str> {
    let v = value.trim();
    (!v.is_empty() && v != "none").then_some(v)
}

/// The `measured` hypothesis over the table in the file `path` (the format of
/// [`measured_from_ron`]), named `measured:PATH`; [`crate::lookup`] gives it for that name, so
/// `--hypothesis measured:FILE` (or the runner's `--errors FILE`) points the `measured`
/// hypothesis at a user's table instead of the embedded example.
///
/// The name carries the path so that results computed with different tables can never be
/// mistaken for each other (experiments name cells and their random streams after the
/// hypothesis). A hypothesis is `'static`: each (path, contents) read is kept for the life of
/// the process (a few kilobytes each).
///
/// Errors name the file: it cannot be read (missing, not UTF-8), or [`measured_from_ron`]
/// refuses it.
pub fn measured_file(path: &str) -> Result<&'static MeasuredHypothesis, HypothesisError> {
    if path.trim().is_empty() {
        return Err(HypothesisError::new(
            "measured:FILE",
            "needs a file name after `measured:`",
        ));
    }
    let text = input_file::read_to_string(std::path::Path::new(path), input_file::MAX_INPUT_BYTES)
        .map_err(|e| HypothesisError::new(path, format!("cannot read: {e}")))?;
    let key = (path.to_owned(), text);
    let mut loaded = LOADED.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(h) = loaded.get(&key) {
        return Ok(h);
    }
    let table = measured_from_ron(path, &key.1)?;
    let name: &'static str = Box::leak(format!("measured:{path}").into_boxed_str());
    let h: &'static MeasuredHypothesis = Box::leak(Box::new(MeasuredHypothesis {
        about: About { name, ..MEASURED },
        table,
    }));
    loaded.insert(key, h);
    Ok(h)
}

impl MeasuredHypothesis {
    /// Its table.
    pub fn table(&self) -> &MeasuredTable {
        &self.table
    }
}

impl Describe for MeasuredHypothesis {
    fn about(&self) -> &About {
        &self.about
    }
}

impl Hypothesis for MeasuredHypothesis {
    fn params(&self) -> &'static [Param] {
        MEASURED_PARAMS
    }

    fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        self.table.apply_scaled(gear, gear_name, params, rng)
    }
}
