//! The paper's reference numbers, read from `experiments/paper.ron` (embedded at build time).

use std::sync::OnceLock;

use serde::Deserialize;

/// One number the paper reports.
#[derive(Debug, Clone, Deserialize)]
pub struct Reference {
    /// Experiment id that shows it.
    pub experiment: String,
    /// Name of the quantity within that experiment.
    pub quantity: String,
    /// The paper's value.
    pub value: f64,
    /// Its unit.
    pub unit: String,
    /// Where in the paper it is given.
    pub source: String,
    /// Why the number looks like a slip of the paper's own (a cell copied from the row above),
    /// if it does: such numbers are still shown, and compared both with and without them.
    #[serde(default)]
    pub suspect: Option<String>,
}

/// Whether the paper's number `quantity` of experiment `id` is flagged as a likely slip.
pub fn suspect(id: &str, quantity: &str) -> bool {
    get(id, quantity).is_some_and(|r| r.suspect.is_some())
}

const TEXT: &str = include_str!("../../../experiments/paper.ron");

/// Every reference number (the file is checked by a unit test, so parsing cannot fail at run time
/// unless the file was broken after the tests ran; then the list is empty).
pub fn all() -> &'static [Reference] {
    static ALL: OnceLock<Vec<Reference>> = OnceLock::new();
    ALL.get_or_init(|| ron::from_str(TEXT).unwrap_or_default())
}

/// The paper's value of `quantity` in experiment `id`.
pub fn get(id: &str, quantity: &str) -> Option<&'static Reference> {
    all()
        .iter()
        .find(|r| r.experiment == id && r.quantity == quantity)
}

#[cfg(test)]
mod tests {
    #[test]
    fn reference_file_parses() {
        let parsed: Result<Vec<super::Reference>, _> = ron::from_str(super::TEXT);
        assert!(parsed.is_ok(), "{parsed:?}");
        assert!(super::get("fig2", "theta_prime_0").is_some());
    }

    /// A number flagged as copied from Table I's 40 % row must equal that row's number: the
    /// flag is a reading of the data, checked against it, not a free annotation.
    #[test]
    fn every_suspect_repeats_the_cell_it_was_copied_from() {
        let suspects: Vec<_> = super::all()
            .iter()
            .filter(|r| r.suspect.is_some())
            .collect();
        assert_eq!(suspects.len(), 4, "the two Case C cells at G = 70 %");
        for r in suspects {
            let mut parts = r.quantity.splitn(3, '.');
            let (case, _g, rest) = (parts.next(), parts.next(), parts.next());
            let source = format!("{}.40.{}", case.unwrap_or(""), rest.unwrap_or(""));
            let copied = super::get(&r.experiment, &source).map(|s| s.value);
            assert_eq!(copied, Some(r.value), "{} against {source}", r.quantity);
        }
    }

    #[test]
    fn every_quantity_is_given_once() {
        let mut seen = std::collections::BTreeSet::new();
        for r in super::all() {
            assert!(
                seen.insert((r.experiment.as_str(), r.quantity.as_str())),
                "{} {} twice",
                r.experiment,
                r.quantity
            );
        }
    }
}
