//! Drop-cutter: the lowest position of a vertical cutter above a triangle mesh.
//!
//! A cutter with axis `+z` at `(x, y)` is lowered until it touches the mesh; the tool
//! tip height there is the drop height, and the touching point the CC point. This is
//! how gouge-free 3-axis paths are made on meshes (OpenCAMLib, PyCAM, FreeCAD), and
//! the engine of raster finishing, rest-material detection and cleanup (thesis 002
//! §6.2: tool offset triangles sampled on a grid, "the point that has the maximum Z
//! value is used as the final tool location point"; double contacts, §3.1.1, §5.1.1).
//!
//! - [`envelope`]: the cutter's lower surface `z = tip + h(rho)`, piecewise closed
//!   forms of the profile; `h` is convex.
//! - [`kernel`]: the drop onto one triangle, as the maximum of its vertex, edge and
//!   facet cases (vertex and facet written once over the profile).
//! - [`facet`]: the facet case and the plane bound that settles most triangles.
//! - [`edge`]: the edge case, a 1-D concave maximisation: closed forms for flat, ball
//!   and cone pieces, a bracketed Newton solve ([`bracket`]) for torus pieces.
//! - `tree`, [`mesh`]: [`MeshDropper`], the mesh in a hierarchy of XY boxes and
//!   tops searched best first, so a drop's cost grows with the depth of the
//!   hierarchy rather than with the triangles under the cutter; [`batch`]: many
//!   points in parallel, deterministic.
//!
//! The cutter is treated as its cutting surface extended upward (the shank and
//! holder are not checked), as in OpenCAMLib. Units: mm.

pub mod batch;
pub mod bracket;
pub mod edge;
pub mod envelope;
pub mod facet;
pub mod kernel;
pub mod mesh;
mod tree;

pub use batch::{drop_points, drop_points_threads, with_threads};
pub use envelope::Envelope;
pub use kernel::{edge_drop, facet_drop, triangle_drop, triangle_drop_above, vertex_drop};
pub use mesh::{DropResult, DropScratch, MeshDropper, TopContacts};

use crate::cutter::Cutter;
use crate::profile::Profile;

/// Which feature of a triangle the cutter touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Feature {
    /// Corner `k` (0, 1, 2).
    Vertex(u8),
    /// Edge `k`, from corner `k` to corner `(k + 1) % 3`.
    Edge(u8),
    /// The facet's interior.
    Facet,
}

impl std::fmt::Display for Feature {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Feature::Vertex(k) => write!(f, "vertex{k}"),
            Feature::Edge(k) => write!(f, "edge{k}"),
            Feature::Facet => write!(f, "facet"),
        }
    }
}

/// A contact with one triangle: tip height and CC point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriContact {
    /// Tool tip height, mm.
    pub z: f64,
    /// The CC point on the triangle, mm.
    pub cc: swarf_geom::Point3,
    /// The feature touched.
    pub feature: Feature,
}

/// How the edge case is solved: one closed form for single-piece cutters, the walk
/// over the envelope pieces otherwise ([`edge`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum EdgeShape {
    /// A flat bottom only.
    Flat,
    /// A sphere centred on the axis only.
    Ball,
    /// A cone from the tip only, `h = k rho`.
    Cone {
        /// `dh/drho`.
        k: f64,
    },
    /// Anything else (bull, taper ball, APT).
    Pieces,
}

/// A cutter prepared for vertical drops: its profile, lower envelope and reach.
/// Build once per cutter; cheap to copy.
#[derive(Debug, Clone, PartialEq)]
pub struct DropCutter {
    cutter: Cutter,
    profile: Profile,
    envelope: Envelope,
    radius: f64,
    radius2: f64,
    shape: EdgeShape,
}

impl DropCutter {
    /// Prepares `cutter` (assumed valid, as the constructors and parsers make it).
    pub fn new(cutter: &Cutter) -> DropCutter {
        let profile = cutter.profile();
        let envelope = Envelope::new(&profile);
        let radius = envelope.radius();
        let shape = match envelope.pieces() {
            [envelope::Piece::Line { k, .. }] if *k == 0.0 => EdgeShape::Flat,
            [envelope::Piece::Line { k, .. }] => EdgeShape::Cone { k: *k },
            [envelope::Piece::Arc { ce, cz, r, .. }] if *ce == 0.0 && *cz == *r => EdgeShape::Ball,
            _ => EdgeShape::Pieces,
        };
        DropCutter {
            cutter: *cutter,
            profile,
            envelope,
            radius,
            radius2: radius * radius,
            shape,
        }
    }

    /// The cutter.
    pub fn cutter(&self) -> &Cutter {
        &self.cutter
    }

    /// The lower envelope.
    pub fn envelope(&self) -> &Envelope {
        &self.envelope
    }

    /// The reach: largest radius of the cutting surface, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }
}
