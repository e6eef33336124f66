//! thorndike (placeholder).
