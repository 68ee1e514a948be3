//! Triangle meshes.

use crate::math::Point3;
use serde::{Deserialize, Serialize};

/// An indexed triangle mesh, mm.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Point3>,
    /// Triangles as indices into `vertices`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}
