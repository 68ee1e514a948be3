//! The 3-axis strategies, one module each, each with its parameter struct (the job
//! file's `[strategy]` table for its kind) and its `plan`.
//!
//! - [`iso`]: iso-parametric, iso-planar and iso-scallop finishing on parametric
//!   patches (paper 004).
//! - [`raster`]: drop-cutter raster finishing on a triangle mesh.
//! - [`waterline`]: closed passes at constant heights around a mesh.
//! - [`steep_shallow`]: a raster on the shallow areas, waterline on the steep ones.
//! - [`roughing`]: Z-level roughing from a stock down to the part plus an allowance.

pub mod iso;
pub mod raster;
pub mod roughing;
pub mod steep_shallow;
pub mod waterline;
