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

/// A face's name, origin and trimming loops (`None`: the whole patch).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Face {
    /// The name the CAD file gives the face, if any.
    pub name: Option<String>,
    /// Where the surface came from in the file, e.g. `#31 CYLINDRICAL_SURFACE` (the
    /// patch is its exact NURBS form).
    #[serde(default)]
    pub surface: Option<String>,
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

    /// The part restricted to the faces `keep` (indices into `patches`, in the order
    /// given; names and trims follow their faces).
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `faces` for an index out of range or
    /// repeated, or an empty selection.
    pub fn select(&self, keep: &[usize]) -> Result<Part, GeomError> {
        let bad = |value: usize, expected: String| GeomError::InvalidParameter {
            name: "faces".into(),
            value: value as f64,
            expected,
        };
        if keep.is_empty() {
            return Err(bad(0, "at least one face".into()));
        }
        let n = self.patches.len();
        let mut seen = vec![false; n];
        for &k in keep {
            if k >= n {
                return Err(bad(
                    k,
                    format!("a face index below {n} ({} has {n} faces)", self.name),
                ));
            }
            if std::mem::replace(&mut seen[k], true) {
                return Err(bad(k, "each face once".into()));
            }
        }
        Ok(Part {
            name: self.name.clone(),
            patches: keep.iter().map(|&k| self.patches[k].clone()).collect(),
            faces: keep
                .iter()
                .map(|&k| self.faces.get(k).cloned().unwrap_or_default())
                .collect(),
        })
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
    fn selecting_faces_keeps_their_trims_and_names() {
        let [a, b] = edge_convex();
        let mut part = Part::new("two", vec![a.clone(), b.clone()]);
        let tri = Trim::new(vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]).unwrap();
        part.faces = vec![Face {
            name: Some("first".into()),
            surface: None,
            trim: Some(tri.clone()),
        }];
        let one = part.select(&[1, 0]).unwrap();
        assert_eq!(one.patches, vec![b, a]);
        assert_eq!(one.face_name(1), Some("first"));
        assert_eq!(one.trim(1), Some(&tri));
        assert!(one.trim(0).is_none() && one.face_name(0).is_none());
        let e = |k: &[usize]| part.select(k).unwrap_err().to_string();
        assert!(
            e(&[2]).starts_with("faces = 2: a face index below 2"),
            "{}",
            e(&[2])
        );
        assert!(e(&[0, 0]).contains("each face once"));
        assert!(e(&[]).contains("at least one face"));
        assert!(!part.face_contains(0, 0.6, 0.6) && part.face_contains(0, 0.2, 0.2));
        assert!(!part.face_contains(5, 0.2, 0.2) && part.face_contains(1, 0.9, 0.9));
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
