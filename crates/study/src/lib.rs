//! The simulations every experiment runs, and the settings they share: experiments call these and only format what comes back.
//!
//! - [`cell`]: one mesh on its own under the paper's jam protocol (Tables 3, 4, 5, I), with the
//!   process-wide cache of cells; [`grids`]: Edmunds' Cases as data and the grids of cells the
//!   tables run, with the sequential tolerances derived from them ([`tolerance`] holds the rule).
//! - [`whole_mechanism`]: the 30-run study of whole mechanisms until they jam.
//! - [`pointers`]: run lengths and sampling of the five pointers.
//! - [`limits`]: an ideal pair's clearance limits, from its contact motion.
//! - [`equal_pair`]: the paper's pair of equal gears (Figures 2 and 3).
//! - [`readings`]: the candidate readings of the paper's inputs that `sigma-causes` compares.
//! - [`anomaly`]: the Lunar pointer without and with the pin-and-slot.
//! - [`cosmos`]: the cosmos display (Freeth et al. 2021, Freeth & Jones 2012) through the
//!   paper's tests, beyond the paper.
//! - [`area_test`]: the paper's kind of contact test (an overlap area, blunt tips) on Figure IV's
//!   ideal pairs.
//! - [`motion_models`]: the per-mesh tables' cells, Figure 2, Table 1 and Figure IV under each
//!   registered motion model (`motion`), for `motion-models`.
//! - [`draws`]: what every study's random numbers are for, the identity of each trial's stream
//!   (`registry::Streams`), all in one place.
//! - Setting groups shared by experiments: [`gearing`] (file, h, G, pin-and-slot), [`errors`]
//!   (hypothesis and its parameters), [`events`] (the event rule), [`drive`] (which gear of a
//!   mesh drives its trials), [`trial_end`] (where a trial's counting ends).

pub mod anomaly;
pub mod area_test;
pub mod cell;
pub mod claims;
pub mod clearance_search;
pub mod cosmos;
pub mod draws;
pub mod drive;
pub mod equal_pair;
pub mod errors;
pub mod events;
pub mod gearing;
pub mod grids;
pub mod limits;
pub mod motion_models;
pub mod pair_file;
pub mod pointers;
pub mod readings;
pub mod results;
pub mod tolerance;
pub mod tolerance_search;
pub mod trial_end;
pub mod units;
pub mod whole_mechanism;
