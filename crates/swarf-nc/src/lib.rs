//! swarf-nc: NC programs. Writers (posts) turn a tool path's moves into RS274/NGC
//! G-code for LinuxCNC and Fanuc-style controls, APT CL data and pose CSV.

pub mod block;
pub mod cl_writer;
pub mod csv_writer;
pub mod error;
pub mod gcode_writer;
pub mod number;
pub mod read;

pub use block::{BlockWriter, FeedMode};
pub use cl_writer::write_cl;
pub use csv_writer::write_pose_csv;
pub use error::NcError;
pub use gcode_writer::{Dialect, GcodeOptions, write_gcode};
pub use number::Units;
pub use read::{Diagnostic, Kinematics, Motion, MotionKind, Program};
