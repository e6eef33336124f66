//! What every experiment reads before it runs: the shared setting groups, the files a run reads, the `emax` setting, the cells a replayable table holds.
//!
//! The glue between a run's checked values (`registry::Context`) and the structs `study` takes,
//! shared by the experiments, the runner's checks before anything runs and `replay`'s reading of
//! a table's cells, so that none of them keeps a copy:
//!
//! - [`typed`]: a jam table's cell settings and its labels, from an experiment's settings struct;
//!   [`read`]: the same groups read from a context by their declarations;
//! - [`inputs`]: the files a run reads (a gearing, measured-error tables) and their checks;
//! - [`emax`]: `--set emax`, Tables 5 and 6 on the paper's E. max row or on the derived one;
//! - [`table_cells`]: the settings a replayable table's cells are read under, and whether a
//!   typed cell is one its table holds (what `experiments`' `replay_cells!` registers).

pub mod emax;
pub mod inputs;
pub mod read;
pub mod table_cells;
pub mod typed;
