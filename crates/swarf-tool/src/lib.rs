//! swarf-tool: the cutters of the APT family and how they meet surfaces.
//!
//! - [`apt`]: the general APT tool `CUTTER/d, r, e, f, alpha, beta, h` (thesis 000
//!   §5.2, eq. 5.1): two cones and a torus, and how `d`, `e`, `f` relate.
//! - [`cutter`]: the closed family [`Cutter`] (flat, ball, bull, cone, taper ball,
//!   APT), each named shape a special case of the APT tool ([`Cutter::to_apt`]).
//! - [`profile`]: every cutter as a chain of lines and arcs in its meridian
//!   half-plane, with exact `height_at_radius` / `radius_at_height`, and every other
//!   profile query (points by normal direction, arc positions, the chain as a
//!   polyline); the lower envelope in pieces is [`drop::Envelope`].
//! - [`surface`]: the cutting surface in any orientation and the exact signed
//!   distance to the tool solid (the gouge test).
//! - [`contact`]: pose from a CC point and surface normal for any tool axis, and back
//!   (thesis 000 §7, eqs. 7.1-7.4).
//! - [`pose`]: [`Pose`] (CL point = tool tip + unit axis) and the tool frame.
//! - [`holder`]: shank and holder as stacked cylinders and cones above the flutes,
//!   their clearance over a mesh and the shortest stick-out that clears a path.
//! - [`library`]: the tool library file (tools by number or name, with holders).
//! - [`spec`]: spec strings `ball:d=8`, `bull:d=10,r=2`, ... ; `table`: config tables.
//!
//! Units: millimetres and radians inside; degrees only in spec strings and tables.
//!
//! ```
//! use swarf_geom::{Point3, Vec3};
//! use swarf_tool::Cutter;
//! let bull: Cutter = "bull:d=10,r=2".parse().unwrap();
//! assert_eq!(bull.height_at_radius(3.0), Some(0.0));
//! let pose = bull.pose_from_contact(&Point3::origin(), &Vec3::z(), &Vec3::z()).unwrap();
//! assert!(bull.signed_distance(&pose, &Point3::origin()).abs() < 1e-12);
//! ```

pub mod apt;
pub mod contact;
pub mod cutter;
pub mod drop;
pub mod error;
pub mod holder;
pub mod library;
pub mod pose;
pub mod profile;
pub mod segment;
pub mod spec;
pub mod surface;
mod table;
pub mod validate;

pub use apt::Apt;
pub use cutter::Cutter;
pub use error::ToolError;
pub use pose::Pose;
pub use profile::{Profile, ProfileContact, ProfileTable};
pub use segment::{RhoZ, Segment};
