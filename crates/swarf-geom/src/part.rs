//! A part: a named set of faces, each a patch and, from CAD files, its trimming loops.
//!
//! For 3-axis work the part's material is everything below the upper envelope of its
//! faces seen along +z (`../shared/parts/README.md`); for 5-axis work each patch is
//! a face of the part. A face without a [`Trim`] is its whole patch.

use crate::error::GeomError;
use crate::math::Aabb;
use crate::mesh::TriMesh;
use crate::patch::Patch;
use crate::trim::Trim;
use serde::{Deserialize, Serialize};

/// A part made of parametric patches, in mm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Part {
    /// Free-text name from the part file.
    pub name: String,
    /// The faces' surfaces, in file order (at least one).
    pub patches: Vec<Patch>,
    /// What the file says of each face beyond its surface, by patch index: its name
    /// and trimming loops. Shorter than `patches` (empty for a part file): the faces
    /// past its end are whole patches without names.
    #[serde(default)]
    pub faces: Vec<Face>,
}

/// A face's name and trimming loops (`None`: the whole patch).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Face {
    /// The name the CAD file gives the face, if any.
    pub name: Option<String>,
    /// The region of the patch's `(u, v)` rectangle that is the face.
    pub trim: Option<Trim>,
}

impl Part {
    /// A part of whole, unnamed patches.
    pub fn new(name: impl Into<String>, patches: Vec<Patch>) -> Part {
        Part {
            name: name.into(),
            patches,
            faces: Vec::new(),
        }
    }

    /// The trimming loops of face `k`, `None` for a whole patch.
    pub fn trim(&self, k: usize) -> Option<&Trim> {
        self.faces.get(k).and_then(|f| f.trim.as_ref())
    }

    /// The name of face `k` from the file, if any.
    pub fn face_name(&self, k: usize) -> Option<&str> {
        self.faces.get(k).and_then(|f| f.name.as_deref())
    }

    /// Whether face `k` contains the parameters `(u, v)`: inside its patch's domain
    /// and its trimming loops.
    pub fn face_contains(&self, k: usize, u: f64, v: f64) -> bool {
        let Some(p) = self.patches.get(k) else {
            return false;
        };
        let [du, dv] = p.domain();
        let in_domain = u >= du[0] && u <= du[1] && v >= dv[0] && v <= dv[1];
        in_domain && self.trim(k).is_none_or(|t| t.contains(u, v))
    }

    /// Box around all control points (holds the whole part).
    pub fn control_box(&self) -> Aabb {
        self.patches
            .iter()
            .fold(Aabb::empty(), |b, p| b.union(&p.control_box()))
    }

    /// All faces tessellated within `tol` in one mesh ([`Patch::tessellate`], or
    /// [`Patch::tessellate_trimmed`] for a trimmed face); each face keeps its own
    /// vertices (faces of a part need not share edges).
    ///
    /// # Units
    /// `tol` in mm.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `tol` when it is not finite and > 0.
    pub fn tessellate(&self, tol: f64) -> Result<TriMesh, GeomError> {
        GeomError::check_positive("tol", tol)?;
        let mut out = TriMesh::default();
        for (k, patch) in self.patches.iter().enumerate() {
            let m = match self.trim(k) {
                Some(trim) => patch.tessellate_trimmed(trim, tol),
                None => patch.tessellate(tol),
            };
            let m = m.map_err(|e| match e {
                GeomError::InvalidParameter {
                    name,
                    value,
                    expected,
                } => GeomError::InvalidParameter {
                    name: format!("{}: patch[{k}]: {name}", self.name),
                    value,
                    expected,
                },
                GeomError::InvalidPatch { field, message } => GeomError::InvalidPatch {
                    field: format!("{}: patch[{k}]: {field}", self.name),
                    message,
                },
                other => other,
            })?;
            let base = out.vertices.len() as u32;
            out.vertices.extend(m.vertices);
            out.triangles
                .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::patch::fixtures::{edge_convex, wave};

    #[test]
    fn part_mesh_concatenates_patch_meshes() {
        let [a, b] = edge_convex();
        let (ma, mb) = (a.tessellate(0.05).unwrap(), b.tessellate(0.05).unwrap());
        let part = Part::new("edge-convex", vec![a, b]);
        let m = part.tessellate(0.05).unwrap();
        assert_eq!(m.vertices.len(), ma.vertices.len() + mb.vertices.len());
        assert_eq!(m.triangles.len(), ma.triangles.len() + mb.triangles.len());
        let n = ma.vertices.len() as u32;
        assert_eq!(
            m.triangles[ma.triangles.len()],
            mb.triangles[0].map(|i| i + n)
        );
        assert_eq!(m.vertices[n as usize], mb.vertices[0]);
    }

    #[test]
    fn bad_tolerance_is_named_even_without_patches() {
        let empty = Part::new("empty", vec![]);
        let e = empty.tessellate(-1.0).unwrap_err();
        assert!(e.to_string().starts_with("tol = -1"), "{e}");
        let one = Part::new("wave", vec![wave()]);
        assert!(one.tessellate(f64::NAN).is_err());
        let e = one.tessellate(1e-300).unwrap_err().to_string();
        assert!(e.starts_with("wave: patch[0]: tol = 1e-300: "), "{e}");
    }
}
