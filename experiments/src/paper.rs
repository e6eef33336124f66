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
}

const TEXT: &str = include_str!("../paper.ron");

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
