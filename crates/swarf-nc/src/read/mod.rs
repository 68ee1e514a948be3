//! Reading NC programs for verification: RS274/NGC G-code (as LinuxCNC reads it),
//! APT CL data and pose CSV, each turned into a [`Program`]: motions (straight,
//! rapid, circular and helical) in mm and mm/min in the part frame, with the source
//! line of each, and warnings for what was read but not simulated.

pub mod program;

pub use program::{Diagnostic, Motion, MotionKind, Program};
