//! swarf-sim: NC verification on a dexel (Z-map) stock.
//!
//! - [`grid`]: the Z-map grid and its memory check.
//! - [`dexel`]: the stock: one height per cell, and the motion that last lowered it.
//! - [`envelope`]: a cutter's lower profile and its exact minimum along a straight move.
//! - [`sweep`]: what a motion removes (the per-shape `Sweep` interface, the sampling
//!   bounds for arcs and five-axis motions), with [`sweep_linear`] (exact) and
//!   [`sweep_tilted`] (one tilted tool position).
//!
//! Units: millimetres, radians, mm/min.

pub mod dexel;
pub mod envelope;
pub mod error;
pub mod grid;
pub mod sweep;
pub mod sweep_linear;
pub mod sweep_tilted;

pub use dexel::{Dexel, StockInit};
pub use envelope::Envelope;
pub use error::SimError;
pub use grid::Grid;
pub use sweep::{Primitive, SimTool, Sweep};
