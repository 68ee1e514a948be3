//! Unit tests of the IGES reader.
