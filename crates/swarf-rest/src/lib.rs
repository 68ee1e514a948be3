//! swarf-rest: rest material and its automatic cleanup (thesis 002 ch. 3-5).
//!
//! - [`pair`]: the rest sample, a pair of contacts with the tool above them, and its
//!   depth.
//! - [`detect`](mod@detect): rest from double contacts, from reference-tool crease scans or from
//!   the in-process stock, each ending in [`region::RestRegion`]s.
//! - [`directory`], [`order`]: the 2D spatial directory and the ordering of a group
//!   into chains (§5.2).
//! - [`region`]: raw pieces and the boundary operations (smoothing, merging,
//!   deletion, overlap; §5.3); [`stock`]: pieces from the dexel stock (ch. 4).
//! - [`cleanup`]: the cleanup tool path, with the patterns [`pencil`] (flow-cut) and
//!   [`pocket`] (follow-pocket) (§5.4), their offsets at a constant stepover along
//!   the surface ([`stepping`]).
//! - [`params`]: a cleanup job's parameters, as its strategy table gives them.
//! - [`steep`]: the walls a raster leaves too much on, cleaned up by Z-level passes
//!   (§3.1.2, §6.2.2).
//!
//! Units: millimetres, radians.

pub mod cleanup;
pub mod detect;
pub mod directory;
pub mod error;
pub mod order;
pub mod pair;
pub mod params;
pub mod pencil;
pub mod pocket;
pub mod region;
pub mod steep;
pub mod stepping;
pub mod stock;

pub use cleanup::{Pattern, plan_cleanup};
pub use detect::{Detection, Source, detect};
pub use error::RestError;
pub use pair::{RestKind, RestPair};
pub use params::{CleanupParams, RestMaterial, RestSource};
pub use region::{RegionParams, RestRegion};
pub use steep::{RasterParent, SteepParams, SteepRest, plan_steep};
