//! [`experiment!`]: how a plugin file registers its experiment, in a few lines.

/// Registers the experiment of one plugin file: a [`registry::Experiment`] whose `run` is the
/// file's own `fn run`, and, for a per-mesh table that `cargo xtask replay` rebuilds, its
/// [`crate::replay::CellGrammar`] (`replay: FORM => parse`).
///
/// ```ignore
/// crate::experiment! {
///     id: "table3", paper_item: "Table 3 (section 5)", run,
///     title: "Jams and disengagements of each mesh on its own, Cases A-D at G = 40 %",
///     params: [TRIALS], groups: [study::gearing::GROUP, study::errors::CASES_GROUP, study::events::GROUP],
///     replay: "CASE/MESH, e.g. B/m3-e3" => cell,
/// }
/// ```
///
/// `params` are the experiment's own parameters (the file's `registry::params!` block), `groups` the
/// setting groups it shares (declared in `study`); `config: TEXT` (what a `--config FILE`
/// describes) is optional, as is `replay`. `build.rs` reads the `id` to write the experiment's
/// snapshot test.
macro_rules! experiment {
    (
        id: $id:literal, paper_item: $item:literal, run,
        title: $title:literal,
        params: [$($param:expr),* $(,)?], groups: [$($group:expr),* $(,)?]
        $(, config: $config:expr)?
        $(, replay: $form:literal => $parse:expr)?
        $(,)?
    ) => {
        registry::inventory::submit! {
            registry::Experiment {
                id: $id,
                title: $title,
                paper_item: $item,
                params: &[$($param),*],
                groups: &[$($group),*],
                config: $crate::register::experiment!(@config $($config)?),
                run,
            }
        }
        $(
            registry::inventory::submit! {
                $crate::replay::CellGrammar { experiment: $id, form: $form, parse: $parse }
            }
        )?
    };
    (@config) => {
        None
    };
    (@config $config:expr) => {
        Some($config)
    };
}

pub(crate) use experiment;
