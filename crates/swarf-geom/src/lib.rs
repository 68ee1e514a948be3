//! swarf-geom: the exact geometric core shared by planning and verification.
//!
//! - [`math`]: f64 points and vectors (nalgebra), axis-aligned boxes, planes, polylines.
//! - [`tol`]: the numeric epsilons shared across crates, with units; an algorithm's
//!   own tuning constants live beside it. [`units`]: mm per inch, for the I/O edge.
//! - [`patch`]: tensor-product Bezier, B-spline and NURBS patches: evaluation, exact
//!   derivatives, differential geometry, projection, plane sections, tessellation.
//! - [`part`]: a part as a set of patches (upper-envelope semantics for 3-axis work).
//! - [`mesh`]: triangle meshes, their validation and an XY spatial index.
//! - [`height`]: the height field of a part or mesh (its upper envelope along +z).
//!
//! Units: millimetres and radians throughout.

pub mod curve;
pub mod domain;
pub mod error;
pub mod height;
pub mod math;
pub mod mesh;
pub mod part;
pub mod patch;
pub mod solve;
pub mod tol;
pub mod trim;
pub mod units;

pub use curve::NurbsCurve;
pub use error::GeomError;
pub use math::{Aabb, Plane, Point3, Polyline, Vec3};
pub use mesh::TriMesh;
pub use mesh::{MeshBuilder, MeshReport, XyIndex};
pub use part::{Face, Part};
pub use patch::Patch;
pub use patch::{
    Curvature, CurvatureRange, FundamentalForms, Projection, SectionCurve, SurfaceBox,
    SurfaceDerivs, SurfaceSample,
};
pub use solve::SolveStatus;
pub use trim::Trim;
