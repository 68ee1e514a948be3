//! swarf-path: the tool path model (poses, passes, links, feeds), job files, and the
//! 3-axis finishing strategies that produce tool paths.

mod boundary;
pub mod cl_curve;
pub mod envelope;
pub mod error;
pub mod forward_step;
pub mod gouge;
pub mod gouge_ball;
pub mod iso_parametric;
pub mod iso_planar;
pub mod iso_scallop;
mod iso_setup;
pub mod job;
mod ordering;
pub mod pass_bound;
pub mod plan;
pub mod raster;
mod raster_double;
mod raster_frame;
mod raster_pass;
pub mod raster_step;
pub mod scallop_crest;
pub mod scallop_step;
pub mod section_point;
pub mod side_step;
pub mod toolpath;
mod uncovered;

pub use error::PathError;
pub use job::{Job, StrategyKind, StrategyParams};
pub use plan::{Plan, PlanInput, PlanReport, plan};
pub use toolpath::{
    Contact, Feeds, Linking, MotionStats, Move, MoveKind, Pass, PathPoint, Toolpath, motion_stats,
};
