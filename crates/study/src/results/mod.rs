//! Results that experiments store and later ones read typed (the claims ledger reads Table 3's
//! counts as counts, not as text): each experiment whose results another reads keeps their type
//! here, one module per family.

pub mod contact_tolerance;
pub mod event_rules;
pub mod failure;
pub mod jam;
pub mod jam_readings;
pub mod pairs;
pub mod pointers;
pub mod tolerances;

pub use failure::{
    FailureInput, FailureRun, FailureStudy, MeanDay, Share, SurvivalStep, TrainSummary,
};
pub use jam::{CaseClearanceTable, CaseTable, JamRow, JamTable, RandomErrorTable};
pub use pairs::{
    ClearanceLimits, ClearanceRun, MeshSweep, SigmaAgainstClearance, SplitPairs, SplitRun, TurnRun,
};
pub use pointers::{CasePointer, CasePointers, CaseRun, IdealPointer, IdealPointers};
pub use tolerances::{
    DerivedTolerances, Estimate95, GearRandom, GearTolerance, GearTolerances, MeasuredFile,
    MeshSearchResult, MeshTolerance, PointerEstimates, RandomFrom, SearchedTolerances,
    SystematicRow, TolerableMechanism,
};
