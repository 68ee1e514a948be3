//! swarf-path: the 3-axis strategies that produce tool paths (the model they produce
//! is swarf-toolpath's). Each strategy takes the job's [`Cutting`] (tool, feeds,
//! linking) and its own parameter struct, defined beside it: what the job file's
//! `[strategy]` table holds for that kind, checked by its `validate`.
//!
//! - [`params`]: what every strategy shares: [`Finish`] (tolerance, zigzag, the
//!   flattened part of every strategy table), [`Cutting`], the side and direction
//!   choices.
//! - [`plan`]: what a strategy gives: the [`Plan`] and its report.
//! - [`strategy`]: one module per strategy: iso-parametric, iso-planar and
//!   iso-scallop ([`strategy::iso`]), the drop-cutter [`strategy::raster`],
//!   [`strategy::waterline`], [`strategy::steep_shallow`] and Z-level
//!   [`strategy::roughing`].
//! - [`stepping`]: how far apart passes and points are: side steps from a scallop
//!   height, iso-scallop steps, slope-aware and raster spacings, forward steps
//!   along a pass, the scallop between two passes.
//! - The queries the strategies share: [`cl_curve`] (CC to CL on a patch),
//!   [`envelope`] (what a 3-axis tool can reach), [`gouge`] and [`gouge_ball`] (gouge
//!   checks), [`section_point`] (surface points on planes), [`track`] (drop-cutter
//!   along a polyline), [`ramp`] (ramp-limited passes), [`leads`] (arc and ramp
//!   leads), [`classify`] (steep, horizontal and other areas of a mesh).
//! - [`error`]: [`PathError`], naming the strategy table's field it is about.

pub mod cl_curve;
pub mod classify;
pub mod envelope;
pub mod error;
pub mod gouge;
pub mod gouge_ball;
pub mod leads;
mod ordering;
pub mod params;
pub mod plan;
pub mod ramp;
pub mod section_point;
pub mod stepping;
pub mod strategy;
pub mod track;
mod uncovered;

pub use error::PathError;
pub use params::{Cutting, Finish, ParamDir, StartSide};
pub use plan::{DoubleContact, Plan, PlanReport, Uncovered};
