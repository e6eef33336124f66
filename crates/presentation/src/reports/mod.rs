//! Each experiment's report drawn from its typed results: one module an experiment whose drawing
//! is its own (what several draw alike is in the modules above), holding the results type where
//! only the report reads it, and the functions that turn it into tables, notes, CSV and SVG. The
//! experiment's plugin file keeps its settings, its computation and its registration, and its
//! `report` hands its results here.

pub mod claims;
pub mod clearance_design;
pub mod event_rules;
pub mod failure;
pub mod sensitivity;
pub mod table5;
pub mod table6;
