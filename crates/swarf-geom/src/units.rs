//! Units at the input and output edge. swarf is in millimetres and radians inside;
//! part files, programs and reports in inches convert with these, once, where they
//! are read or written.

/// Millimetres per inch (exact, by the 1959 definition of the inch).
pub const MM_PER_INCH: f64 = 25.4;
