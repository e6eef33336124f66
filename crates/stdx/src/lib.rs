//! Small helpers every crate may share: what a plugin says of itself, a plugin kind's registrations sorted by name, numbers printed short.
//!
//! The bottom floor of the workspace: it depends on nothing, so that every crate, however low,
//! may use it. Each of its pieces is shared by several crates that would otherwise each keep a
//! copy: the four plugin kinds (experiments, error hypotheses, event rules, motion models) are
//! collected by [`by_name`], and three of them describe themselves with an [`About`]; every
//! table and message prints its numbers with [`fmt_f64`] and [`fmt_number`]; a message naming
//! what a user typed keeps to one line with [`one_line`].

mod number;
mod plugin;
mod text;

pub use number::{fmt_f64, fmt_number};
pub use plugin::{About, Describe, Duplicate, by_name};
pub use text::one_line;
