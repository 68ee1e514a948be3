//! swarf-fiveaxis: five-axis positioning and checking.
//!
//! - [`inclined`]: inclined-tool (Sturz) positioning along CC paths (thesis 000 §7.3.1).
//! - [`gencurve`]: generating curves of a tool between two poses (thesis 000 ch. 5).
//!
//! Units: millimetres and radians inside; degrees only in files and reports.

pub mod autotilt;
pub mod design;
pub mod drive;
pub mod error;
pub mod gencurve;
pub mod gouge;
pub mod inclined;
pub mod machine;
pub mod motion;
pub mod positioning;
pub mod post;
pub mod profile_point;
pub mod sections;
pub mod swept;

pub use error::FiveAxisError;
pub use gencurve::{CurveOptions, Half, PoseCurve};
pub use inclined::{Inclination, incline_pass, inclined_pose, tool_axis};
