//! [`replay_cells!`]: how a typed experiment's plugin file registers the grammar of its cells.

/// Registers how `cargo xtask replay` reads a cell of a per-mesh table written as a
/// [`registry::Experiment`]: `replay_cells! { "table3", "CASE/MESH, e.g. B/m3-e3" => cell }`,
/// `cell` parsing the typed cell against the table's cell settings. The grammar
/// ([`replay::CellGrammar`]) reads the table's settings and checks that the table holds a cell
/// through [`setting_groups::table_cells`].
macro_rules! replay_cells {
    ($id:literal, $form:literal => $parse:expr) => {
        registry::inventory::submit! {
            ::replay::CellGrammar {
                experiment: $id,
                form: $form,
                parse: $parse,
                settings: ::setting_groups::table_cells::settings,
                holds: ::setting_groups::table_cells::check,
            }
        }
    };
}

pub(crate) use replay_cells;
