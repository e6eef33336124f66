//! The structural rules of the house in one place, each measured on the source itself (a real
//! parse with `syn` where a rule is about code, so that braces in strings, comments and macros
//! do not fool it). One module per concern:
//!
//! - `functions`: every function fits on a screen (80 lines in plugins and the presentation,
//!   100 in all other product code, tests aside), and no file is past 1,000 product lines;
//! - `crates`: every library opens with a one-line `//!`; no crate declares a dependency its
//!   code never names; no crate holds more than a fifth of the product lines, `experiments`
//!   under 10,000 and holding its plugins only;
//! - `modules`: no module circle in any crate; the runner's `main.rs` only declares and
//!   dispatches; the contact solver's layers never name a layer above them;
//! - `plugins`: no plugin imports another;
//! - `params`: no parameter is looked up by a name typed again as a string literal, and `study`
//!   never names a `Context`;
//! - `streams`: only the trial engine makes a random generator;
//! - `architecture`: ARCHITECTURE.md is current - a heading for every crate and folder and none
//!   stale, each crate's floor (its dependencies all on lower floors) and its entry points
//!   (each one found in the crate).
#![allow(clippy::unwrap_used, reason = "tests")]

mod architecture;
mod crates;
mod functions;
mod modules;
mod params;
mod plugins;
mod source;
mod streams;
