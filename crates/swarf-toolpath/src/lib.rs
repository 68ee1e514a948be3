//! swarf-toolpath: the tool path model, what strategies produce and posts consume,
//! and the executed-program model, what readers produce and the simulator consumes.
//! Plain data: the algorithms that make and use them live in the crates above.
//!
//! - [`path`]: passes of poses, their links, feeds, and the rapid and feed moves a
//!   post writes.
//! - [`reach`]: where a tool path may cut (above the floor, within the tool's
//!   reach of the stock), and passes cut to it.
//! - [`program`]: a program as executed: motions (straight, rapid, arc) in the part
//!   frame, the tools it uses, and the diagnostics found reading it.

pub mod path;
pub mod program;
pub mod reach;

pub use path::*;
pub use program::{Diagnostic, Motion, MotionKind, Program, ToolUse};
