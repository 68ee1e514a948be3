//! swarf-io.
