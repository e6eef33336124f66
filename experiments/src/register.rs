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
        /// The parameters of this experiment as the runner checked them (untyped form).
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        pub struct LegacySettings {
            values: Vec<(String, String)>,
        }

        impl registry::Settings for LegacySettings {
            fn params(out: &mut Vec<&'static registry::Param>) {
                $(out.push(&$param);)*
                $(out.extend($group.iter());)*
            }
            fn read(ctx: &registry::Context) -> Result<Self, registry::RunError> {
                Ok(LegacySettings {
                    values: ctx.values().map(|(p, v)| (p.name.to_owned(), v.to_owned())).collect(),
                })
            }
            fn changed(&self, _: &mut Vec<(&'static registry::Param, String)>) {}
        }

        /// This plugin's experiment, in the untyped form: its results are its report.
        struct Legacy;

        impl registry::Experiment for Legacy {
            const ID: &'static str = $id;
            const TITLE: &'static str = $title;
            const PAPER_ITEM: &'static str = $item;
            const PLACE: registry::Place = registry::Place::Beyond(u32::MAX);
            const CONFIG: Option<&'static str> = $crate::register::experiment!(@config $($config)?);
            type Settings = LegacySettings;
            type Results = registry::Report;
            fn compute(
                _: &LegacySettings,
                r: &registry::Run,
            ) -> Result<registry::Report, registry::RunError> {
                run(r.legacy_context())
            }
            fn report(
                _: &LegacySettings,
                report: &registry::Report,
            ) -> Result<registry::Report, registry::RunError> {
                Ok(report.clone())
            }
        }

        registry::register!(Legacy);
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
