//! registry (placeholder).
