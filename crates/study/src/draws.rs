//! What every study's random numbers are for: the [`Draws`] that names each trial's stream.
//!
//! Every trial of every study draws from `registry::Streams::stream(identity, trial)` (through
//! `TrialEngine::stream` where it runs in the engine): ChaCha8 on the run's seed, on a stream
//! word hashed from the identity's text and the trial index. The identities are all here, so
//! that one place says which trials share numbers: two trials draw the same numbers exactly when
//! they name the same draws and part, the same trial and the same seed. Each study's text
//! begins with its own word (`study=...`; a jam cell's is its canonical text, `mesh=...`), so no
//! two studies draw one stream by accident.
//!
//! An identity says what the draws are for, not what a table compares: a paired comparison
//! (two motion models, two clearances, with and without the pin-and-slot) runs both sides from
//! one stream on purpose, so that they see the same gears, and says so where it does.

use registry::{Identity, Streams, TrialRng};

/// A stream of its own beside a study's main draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The study's own draws (gears' errors, then initial angles, in the study's order).
    Main,
    /// The driven gear's own initial angle, for the motion models that place it
    /// (`motion-models`): apart, so that every other draw is the tables'.
    DrivenAngle,
    /// A whole mechanism's second hypothesis (`whole_mechanism::Input::extra`): apart, so that
    /// the first hypothesis's errors and the initial angles are those of the run without it.
    ExtraErrors,
}

impl Part {
    /// What the part adds to the draws' text (nothing for the main draws).
    fn suffix(self) -> &'static str {
        match self {
            Part::Main => "",
            Part::DrivenAngle => "|motion-models: the driven gear's own initial angle",
            Part::ExtraErrors => "|the extra hypothesis's errors",
        }
    }
}

/// What a study's trials draw: the identity of their streams.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Draws<'a> {
    /// A jam cell's trial (`cell`): both gears' errors, the initial angle, then the coin that
    /// picks the driver. Named by the cell's canonical text alone (`CellSpec::canonical`:
    /// mesh, hypothesis, parameters, h, G), so the same cell draws the same in every experiment.
    Cell(&'a str),
    /// A trial of the ideal mechanism: each pointer's meshes' initial angles, pointer after
    /// pointer (Table 1). Figure 4's instance, sigma-causes' Table 1 runs, motion-models'
    /// pointers and lunar-anomaly's row of ideal teeth are trials of the same mechanism and
    /// draw the same on purpose: they show Table 1's trials.
    IdealMechanism,
    /// Table 6's mechanism: every gear's errors under its own tolerance, then the initial angles.
    Tolerated,
    /// A Case of Edmunds' errors (`"A"` to `"D"`): every gear's errors, then the initial angles
    /// (Table 2). lunar-anomaly's Case rows draw the same, so that without the pin-and-slot
    /// they are Table 2's triangular trials.
    Case(&'a str),
    /// A whole mechanism of the failure study (`failure`, `sensitivity`, `clearance-design`):
    /// every gear's errors, then every mesh's initial angle. Inputs with the same `gears` run
    /// the same gears and angles (clearance designs compared on the same gears).
    WholeMechanism {
        /// Which gears: `whole_mechanism::Input::index`.
        gears: u64,
    },
    /// The cosmos display's trials of one input (`"ideal"`, `"Case A"`...): the gears' errors,
    /// then each planet's initial angles in turn.
    Cosmos {
        /// The input's label.
        input: &'a str,
    },
    /// Figure 5's pair: both gears' errors, then the initial angle (every split from the same
    /// trial, so that the panels differ by the split alone).
    Figure5Pair,
    /// sigma-causes' Figure IV under Case A: one pair of the mesh `mesh`, the trial index being
    /// the pair's number.
    FigureIvCaseA {
        /// The mesh label.
        mesh: &'a str,
    },
}

impl Draws<'_> {
    /// The text naming `part` of these draws.
    pub fn canonical(&self, part: Part) -> String {
        let draws = match self {
            Draws::Cell(canonical) => (*canonical).to_owned(),
            Draws::IdealMechanism => "study=ideal-mechanism".to_owned(),
            Draws::Tolerated => "study=tolerated-mechanism".to_owned(),
            Draws::Case(case) => format!("study=edmunds-case;case={case}"),
            Draws::WholeMechanism { gears } => format!("study=whole-mechanism;gears={gears}"),
            Draws::Cosmos { input } => format!("study=cosmos-display;input={input}"),
            Draws::Figure5Pair => "study=figure-5-pair".to_owned(),
            Draws::FigureIvCaseA { mesh } => format!("study=figure-iv-case-a;mesh={mesh}"),
        };
        draws + part.suffix()
    }

    /// The identity of the main draws.
    pub fn identity(&self) -> Identity {
        self.part(Part::Main)
    }

    /// The identity of `part` of these draws.
    pub fn part(&self, part: Part) -> Identity {
        Identity::of(&self.canonical(part))
    }

    /// Trial `trial`'s generator of the main draws under `streams` (a study handed the seed
    /// rather than the engine: one trial rebuilt).
    pub fn stream(&self, streams: Streams, trial: u64) -> TrialRng {
        streams.stream(self.identity(), trial)
    }
}

impl std::fmt::Display for Draws<'_> {
    /// The main draws' text, as batch keys name them.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.canonical(Part::Main))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One of every kind of draws.
    const ALL: [Draws<'static>; 11] = [
        Draws::Cell("mesh=b2-c1;hypothesis=ideal;h=1.1;G=40.0"),
        Draws::IdealMechanism,
        Draws::Tolerated,
        Draws::Case("A"),
        Draws::Case("B"),
        Draws::WholeMechanism { gears: 0 },
        Draws::WholeMechanism { gears: 1 },
        Draws::Cosmos { input: "ideal" },
        Draws::Cosmos { input: "Case A" },
        Draws::Figure5Pair,
        Draws::FigureIvCaseA { mesh: "b2-c1" },
    ];

    #[test]
    fn every_study_and_part_has_a_stream_of_its_own() {
        let parts = [Part::Main, Part::DrivenAngle, Part::ExtraErrors];
        let ids: std::collections::HashSet<Identity> = ALL
            .iter()
            .flat_map(|d| parts.iter().map(move |&p| d.part(p)))
            .collect();
        assert_eq!(ids.len(), ALL.len() * parts.len());
    }

    /// A cell is named by its canonical text alone, and the driven gear's own angle beside it by
    /// the text motion-models has always used, so cell-based tables keep their numbers.
    #[test]
    fn a_cells_streams_are_named_by_its_canonical_text() {
        let cell = "mesh=b2-c1;hypothesis=ideal;h=1.1;G=40.0";
        assert_eq!(Draws::Cell(cell).identity(), Identity::of(cell));
        assert_eq!(
            Draws::Cell(cell).part(Part::DrivenAngle),
            Identity::of(&format!(
                "{cell}|motion-models: the driven gear's own initial angle"
            ))
        );
    }
}
