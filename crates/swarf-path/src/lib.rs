//! swarf-path: the 3-axis finishing strategies that produce tool paths (the model
//! they produce is swarf-toolpath's).

mod boundary;
mod boundary_edges;
pub mod cl_curve;
pub mod classify;
pub mod envelope;
pub mod error;
pub mod forward_step;
pub mod gouge;
pub mod gouge_ball;
pub mod iso_parametric;
pub mod iso_planar;
pub mod iso_scallop;
mod iso_setup;
pub mod leads;
mod ordering;
pub mod params;
pub mod pass_bound;
pub mod plan;
pub mod ramp;
pub mod raster;
mod raster_double;
mod raster_frame;
mod raster_pass;
pub mod raster_step;
pub mod roughing;
pub mod scallop_crest;
pub mod scallop_step;
pub mod section_point;
pub mod side_step;
pub mod slope_step;
pub mod steep_shallow;
pub mod track;
mod trim_clip;
mod uncovered;
pub mod waterline;

pub use error::PathError;
pub use params::{Finish, IsoParams, ParamDir, RasterParams, StartSide, StrategyKind};
pub use plan::{DoubleContact, Plan, PlanReport, Uncovered};
