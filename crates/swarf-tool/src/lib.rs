//! swarf-tool.
