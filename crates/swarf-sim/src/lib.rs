//! swarf-sim: NC verification on a dexel (Z-map) stock.
//!
//! - [`grid`]: the Z-map grid and its memory check.
//! - [`dexel`]: the stock: one height per cell, and the motion that last lowered it.
//! - [`swept_min`]: the exact minimum of a cutter's lower envelope
//!   ([`swarf_tool::drop::Envelope`]) along a straight move.
//! - [`sweep`]: what a motion removes (the per-shape `Sweep` interface, the sampling
//!   bounds for arcs and five-axis motions), with [`sweep_linear`] (exact) and
//!   [`sweep_tilted`] (one tilted tool position, marched by the distance of
//!   [`tool_solid`]).
//! - [`sweep_bound`]: how finely a tilted motion is sampled (second order for
//!   rounded tools below the stock's reach).
//! - [`sweep_budget`]: the samples and depths a program asks for, refused before
//!   any sampling when beyond the budget.
//! - [`design`]: the design's height (and normal) at every cell centre, from the
//!   height-field query of the geometry kernel ([`swarf_geom::height`]).
//! - [`deviation`]: gouge, excess and scallop crests against the design, by region.
//! - [`mow`]: deviation along the design normals ("mow the grass").
//! - [`simulate`](mod@simulate): a program over a stock, in parallel row bands,
//!   deterministically.
//! - [`engagement`]: the cutter's radial engagement measured on the stock, motion
//!   by motion.
//! - [`stage`]: several programs in sequence on one stock, each with its own cutter.
//! - [`verify`](mod@verify): all of it for a program (or several), a tool and a design.
//! - [`report`] (JSON, CSV, text); the pictures of a verification are drawn by
//!   swarf-report.
//!
//! Units: millimetres, radians, mm/min.

pub mod design;
pub mod deviation;
pub mod dexel;
pub mod engagement;
pub mod error;
pub mod floor;
pub mod grid;
pub mod mow;
pub mod progress;
pub mod report;
pub mod simulate;
pub mod stage;
pub mod sweep;
pub mod sweep_bound;
pub mod sweep_budget;
pub mod sweep_linear;
pub mod sweep_tilted;
pub mod swept_min;
pub mod tool_solid;
pub mod verify;

pub use design::{Design, DesignField, DesignSurface};
pub use deviation::{Deviation, DeviationOptions, DeviationSummary};
pub use dexel::{Dexel, StockInit};
pub use error::SimError;
pub use grid::Grid;
pub use progress::{Progress, Quiet};
pub use simulate::{SimOptions, SimReport, simulate, simulate_from};
pub use stage::{Stage, StageSummary};
pub use sweep::{Primitive, SimTool, Sweep};
pub use verify::{ProgramStats, StockSpec, Verification, VerifyOptions, verify, verify_stages};
