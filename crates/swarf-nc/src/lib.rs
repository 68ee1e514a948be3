//! swarf-nc.
