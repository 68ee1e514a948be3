//! swarf-path: the tool path model (poses, passes, links, feeds), job files, and the
//! 3-axis finishing strategies that produce tool paths.

pub mod error;
pub mod iso_parametric;
pub mod iso_planar;
pub mod iso_scallop;
pub mod job;
pub mod plan;
pub mod raster;
pub mod toolpath;

pub use error::PathError;
pub use job::{Job, StrategyKind, StrategyParams};
pub use plan::{Plan, PlanInput, PlanReport, plan};
pub use toolpath::{
    Contact, Feeds, Linking, MotionStats, Move, MoveKind, Pass, PathPoint, Toolpath, motion_stats,
};
