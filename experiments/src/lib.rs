//! Experiments (placeholder).
