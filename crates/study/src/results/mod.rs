//! Results that experiments store and later ones read typed (the claims ledger reads Table 3's
//! counts as counts, not as text): each experiment whose results another reads keeps their type
//! here, one module per family.

pub mod jam;
pub mod tolerances;

pub use jam::{CaseClearanceTable, JamRow, JamTable, RandomErrorTable};
pub use tolerances::{
    DerivedTolerances, Estimate95, GearRandom, GearTolerance, GearTolerances, MeasuredFile,
    MeshSearchResult, MeshTolerance, PointerEstimates, RandomFrom, SearchedTolerances,
    SystematicRow, TolerableMechanism,
};
