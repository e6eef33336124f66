//! geometry (placeholder).
