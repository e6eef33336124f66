//! [`replay_cells!`]: how a typed experiment's plugin file registers the grammar of its cells.

/// Registers how `cargo xtask replay` reads a cell of a per-mesh table written as a
/// [`registry::Experiment`]: `replay_cells! { "table3", "CASE/MESH, e.g. B/m3-e3" => cell }`,
/// `cell` parsing the typed cell against the table's cell settings.
macro_rules! replay_cells {
    ($id:literal, $form:literal => $parse:expr) => {
        registry::inventory::submit! {
            $crate::replay::CellGrammar { experiment: $id, form: $form, parse: $parse }
        }
    };
}

pub(crate) use replay_cells;
