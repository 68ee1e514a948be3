//! swarf-fiveaxis: five-axis positioning, swept surfaces, gouge checking and machines.
//!
//! Positioning (thesis 000 ch. 7):
//! - [`inclined`]: inclined-tool (Sturz) positioning along CC paths (§7.3.1, eqs. 7.1-7.4).
//! - [`autotilt`]: the smallest gouge-free lead at every CC point, smoothed (§7.3).
//! - [`lead_bound`]: the least lead the design's curvature along the feed allows (ch. 7-8).
//! - [`positioning`]: both as a job's `positioning` table asks, with gouge reports.
//! - [`dsm`]: multipoint drop-and-spin positioning at the common edge of two faces
//!   (paper 003).
//!
//! Swept surfaces and gouges (thesis 000 ch. 3, 5, 7):
//! - [`motion`]: the velocity field of the tool at a pose of a path.
//! - [`gencurve`]: generating curves of inserts and cards (§5.3-5.4, eqs. 5.2-5.17).
//! - [`swept`]: the machined surface as a mesh of generating curves, sampled by height.
//! - [`sections`], [`design`], [`gouge`]: sectioning gouge detection (§7.2).
//!
//! Paths:
//! - [`cc_paths`]: the CC paths of a planned tool path, and the linking of positioned passes.
//!
//! Machines and output:
//! - [`machine`]: machine files, forward and inverse kinematics, rotary continuity.
//! - [`post`]: five-axis G-code (`X Y Z` and two rotary words, G93 or G94).
//!
//! Units: millimetres and radians inside; degrees only in files and reports.

pub mod autotilt;
pub mod cc_paths;
pub mod design;
pub mod dsm;
pub mod error;
pub mod gencurve;
pub mod gouge;
pub mod inclined;
pub mod lead_bound;
pub mod machine;
pub mod motion;
pub mod positioning;
pub mod post;
pub mod sections;
pub mod swept;

pub use error::FiveAxisError;
pub use gencurve::{CurveOptions, Half, PoseCurve};
pub use inclined::{Inclination, incline_pass, inclined_pose, tool_axis};
