//! The height field of a part: its upper envelope seen along +z, the one query that
//! sectioning (five-axis gouge checks), the 3-axis envelope of CC points and the dexel
//! verifier all ask (`../shared/parts/README.md`: for 3-axis work the material is
//! everything below the upper envelope of the patches).
//!
//! # Patches ([`PartHeights`])
//!
//! For a patch `S(u, v)` and a query `(x, y)` the point above it solves
//! `F(u, v) = S_xy(u, v) - (x, y) = 0`. Newton's method takes the step
//! `J d = -F` with `J = [S_u.xy  S_v.xy]` (2x2, solved by Cramer's rule,
//! `det J = S_u.x S_v.y - S_u.y S_v.x`), parameters clamped into the domain; the
//! patch is evaluated in power form ([`crate::patch::PowerPatch`]: exact polynomials
//! per span, Horner's rule, about 20x cheaper than de Boor with second derivatives).
//! The iteration ends
//!
//! - *converged* when `|F| <=` [`NEWTON_XY`] (1e-10 mm; the height is then exact to
//!   that times the surface slope), or when the step is shorter than
//!   [`NEWTON_ACCEPT`] of the parameter range (quadratic convergence: the next step
//!   would be below rounding), taking the tangent plane's height `z + S_u.z d_u +
//!   S_v.z d_v`;
//! - *off the patch* when the clamped step does not move (the root lies outside the
//!   domain: the ray passes beside the patch) or after [`NEWTON_STEPS`] with a
//!   residual above [`NEWTON_LATE_XY`];
//! - *singular* when `det J` vanishes (a vertical tangent plane): the sampled height
//!   is kept and flagged ([`HeightStatus::Singular`]).
//!
//! **Seeds** (one scheme, [`seed`]): each patch is sampled on a uniform `(u, v)` grid
//! of about one node per [`SAMPLE_SPACING`] of control-net length (between
//! [`MIN_SAMPLES`] and [`MAX_SAMPLES`] a direction); the sample triangles carry their
//! corners' `(u, v)` and are indexed in XY ([`crate::mesh::XyIndex`]). A query inside
//! a sample triangle starts Newton from the barycentric blend of its corners'
//! parameters; per query only the best start of each of the two highest patches is
//! kept (two sheets cross at a common edge; a third rarely reaches the top). Where a
//! patch folds over itself in XY, the highest sampled sheet gives the start, so the
//! root found is the one nearest the top. The answer is the highest converged root:
//! the upper envelope. A trimmed face answers only where the root's `(u, v)` lies
//! inside its loops, and its sample cells wholly outside them are dropped so that they
//! take no start slot. Newton's method for the ray-surface problem: Kajiya, "Ray
//! tracing parametric patches" (1982), §3; the clamped form is projected Newton
//! (Bertsekas 1982) restricted to the domain box.
//!
//! # Meshes ([`MeshHeights`])
//!
//! The vertical hit of each triangle the XY index returns at `(x, y)` (asked for a
//! rectangle [`QUERY_SLACK`] wide around it)
//! ([`vertical_hit`]: barycentric weights with a closed inside test, [`triangle`]),
//! the highest kept (the lowest for a lower envelope, e.g. a swept surface seen from
//! below). Grids of queries scan-convert each triangle over a band of rows
//! ([`cover`]) instead of asking the index once a point; the arithmetic per point is
//! the same.
//!
//! Queries are pure and `Sync`; the `*_points` forms run in parallel (rayon) and
//! return the answers in input order.

mod mesh;
mod newton;
mod part;
pub mod seed;
pub mod triangle;

#[cfg(test)]
mod tests;

use crate::math::Vec3;

pub use mesh::MeshHeights;
pub use newton::{
    NEWTON_ACCEPT, NEWTON_LATE_XY, NEWTON_STEPS, NEWTON_XY, Ray, SINGULAR_DET, vertical_ray,
};
pub use part::PartHeights;
pub use seed::{MAX_SAMPLES, MIN_SAMPLES, SAMPLE_SPACING};
pub use triangle::{INSIDE_EPS, Lattice, QUERY_SLACK, barycentric, cover, vertical_hit};

/// How the height of a point of the upper envelope was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HeightStatus {
    /// Newton converged on the patch ([`NEWTON_XY`]).
    Converged,
    /// The Jacobian was singular (vertical tangent plane): the height is the sampled
    /// one, exact only to the sampling.
    Singular,
}

/// The upper envelope of a part above one XY point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Height {
    /// Height, mm.
    pub z: f64,
    /// Unit normal turned upward (`+z` where it is not defined).
    pub normal: Vec3,
    /// Index of the patch in the part.
    pub patch: usize,
    /// The patch parameters of the point.
    pub uv: [f64; 2],
    /// Converged or sampled.
    pub status: HeightStatus,
}
