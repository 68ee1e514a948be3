//! How far apart passes and points are.
//!
//! - [`side_step`]: the side step between neighbouring passes from the scallop limit.
//! - [`scallop_step`]: the next iso-scallop CC point (Feng & Li 2002).
//! - [`scallop_crest`]: the scallop between two tools in a cross-section.
//! - [`slope_step`]: raster and Z-level spacings that hold the scallop on slopes.
//! - [`raster_step`]: the raster stepover from a scallop height, and back.
//! - [`forward_step`]: the forward step along a pass from the chordal tolerance.

pub mod forward_step;
pub mod raster_step;
pub mod scallop_crest;
pub mod scallop_step;
pub mod side_step;
pub mod slope_step;
