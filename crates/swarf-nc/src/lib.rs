//! swarf-nc: NC programs. Writers (posts) turn a tool path's moves into programs for
//! the control a post description names ([`post`]: LinuxCNC, Fanuc, Mach3, grbl,
//! Heidenhain conversational, or a user's file), APT CL data and pose CSV; readers
//! read them back ([`read`]).

pub mod arc_fit;
pub mod block;
pub mod cl_writer;
pub mod csv_writer;
pub mod error;
pub mod gcode_writer;
pub mod number;
pub mod post;
pub mod read;

pub use block::{BlockWriter, FeedMode};
pub use cl_writer::write_cl;
pub use csv_writer::write_pose_csv;
pub use error::NcError;
pub use gcode_writer::{
    DEFAULT_ARC_TOLERANCE_MM, GcodeOptions, ToolSection, write_gcode, write_gcode_sections,
};
pub use number::Units;
pub use post::{Language, Post};
pub use read::{Diagnostic, Kinematics, Motion, MotionKind, Program};
