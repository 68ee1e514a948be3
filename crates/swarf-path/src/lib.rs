//! swarf-path.
