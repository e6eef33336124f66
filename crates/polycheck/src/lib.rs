//! polycheck (placeholder).
