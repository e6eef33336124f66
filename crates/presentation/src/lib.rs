//! What the experiments show: charts, pictures of gears and events, pages, and cells beside the paper's.
//!
//! Everything here turns computed results into text, SVG or HTML; nothing runs a simulation.
//! `experiments` (the plugins) and the `replay` command draw through it.
//!
//! - [`chart`]: the one chart builder (every series its own colour, dash and marker, the legend
//!   below the axes); [`td_plot`]: the Theoretical Difference with its events numbered.
//! - [`pair_html`] and [`pair_svg`]: a pair's run as a page that moves and as a checked picture;
//!   [`event_picture`]: a picture per event; [`train_picture`]: the gearing as a diagram;
//!   [`label_place`]: labels placed clear of outlines and of each other; [`cosmos_svg`]: the
//!   cosmos display's trains, each mesh coloured by its tolerance.
//! - [`common`]: CSV, intervals, estimates, wrapped text and [`escape_xml`], the one XML escape;
//!   [`cells`]: a jam cell beside the paper's, the two-sample mark, the tally; [`paper`]: the
//!   paper's numbers, read from `experiments/paper.ron`, and [`emax`], its largest tolerable
//!   errors; [`units`]: tolerances per gear in mm and degrees beside the fraction of the pitch.
//! - [`reports`]: one module per experiment whose drawing is its own, from its typed results
//!   to its tables, notes, CSV and SVG (the experiment's `report` calls it).

pub mod cells;
pub mod chart;
pub mod common;
pub mod cosmos_svg;
pub mod emax;
pub mod event_picture;
pub mod label_place;
pub mod pair_events;
pub mod pair_html;
pub mod pair_svg;
pub mod paper;
pub mod reports;
pub mod td_plot;
#[cfg(test)]
mod test_pair;
pub mod train_picture;
pub mod units;
mod xml;

pub use xml::escape_xml;
