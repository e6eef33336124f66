//! Experiments (placeholder).

/// Does nothing; calling it makes a binary link this crate, and with it every experiment it registers.
pub fn link() {}
