//! Resolving a part as a user names it: a part file, a mesh file, or a built-in part
//! name.

use crate::error::{Result, bail};
use serde::{Deserialize, Serialize};
use std::path::Path;
use swarf_geom::{Part, Patch, TriMesh};
use swarf_io::{CadOptions, Source};

/// A face as a job names it: its index (as `swarf inspect` lists it) or its name in
/// the CAD file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum FaceRef {
    /// The face's index, from 0.
    Index(usize),
    /// The face's name.
    Name(String),
}

/// How a part is read: the CAD readers' options and the faces to keep.
#[derive(Debug, Clone, Default)]
pub struct LoadOptions {
    /// STEP and IGES reading.
    pub cad: CadOptions,
    /// The faces to keep (all when `None`).
    pub faces: Option<Vec<FaceRef>>,
}

/// Keeps the faces `refs` of `part`, in the order given; `arg` names the part.
///
/// # Errors
/// A name no face has (the names listed), an index out of range or repeated.
pub fn select_faces(part: &Part, refs: &[FaceRef], arg: &str) -> Result<Part> {
    let mut keep = Vec::with_capacity(refs.len());
    for r in refs {
        keep.push(match r {
            FaceRef::Index(k) => *k,
            FaceRef::Name(n) => {
                match (0..part.patches.len()).find(|&k| part.face_name(k) == Some(n)) {
                    Some(k) => k,
                    None => {
                        let names: Vec<&str> = (0..part.patches.len())
                            .filter_map(|k| part.face_name(k))
                            .take(20)
                            .collect();
                        bail!(
                            "faces: {arg} has no face named {n:?} (names: {})",
                            if names.is_empty() {
                                "none in the file".to_string()
                            } else {
                                names.join(", ")
                            }
                        )
                    }
                }
            }
        });
    }
    part.select(&keep)
        .map_err(|e| crate::error::AppError::Message(format!("{arg}: {e}")))
}

/// Chordal tolerance of the tessellation that bounds a patch part's top
/// ([`Model::z_range`]), mm.
pub const TOP_CHORD: f64 = 0.01;

/// A part as the user named it: parametric patches or a triangle mesh.
pub enum Model {
    /// Patches from a part file or a built-in part.
    Patches(Part),
    /// A triangle mesh from STL or OBJ.
    Mesh {
        /// The file's stem.
        name: String,
        /// The triangles.
        mesh: TriMesh,
    },
}

impl Model {
    /// The design's triangles: a mesh as it is, patches tessellated within the
    /// chordal tolerance `chord` (mm).
    ///
    /// # Errors
    /// A tessellation that fails.
    pub fn triangles(&self, chord: f64) -> Result<std::borrow::Cow<'_, TriMesh>> {
        Ok(match self {
            Model::Mesh { mesh, .. } => std::borrow::Cow::Borrowed(mesh),
            Model::Patches(part) => std::borrow::Cow::Owned(part.tessellate(chord)?),
        })
    }

    /// A box holding the design: a mesh's bounding box, the control box of patches
    /// (they lie in the convex hull of their control points).
    pub fn bounds(&self) -> swarf_geom::Aabb {
        match self {
            Model::Patches(part) => part.control_box(),
            Model::Mesh { mesh, .. } => mesh.aabb(),
        }
    }

    /// Heights the design does not go below and above, within [`TOP_CHORD`] of its
    /// lowest and highest points, mm: a mesh's lowest and highest vertex; those of
    /// the patches' tessellation within [`TOP_CHORD`], widened by that chord.
    ///
    /// # Errors
    /// A tessellation that fails.
    pub fn z_range(&self) -> Result<[f64; 2]> {
        Ok(match self {
            Model::Mesh { mesh, .. } => {
                let b = mesh.aabb();
                [b.min.z, b.max.z]
            }
            Model::Patches(part) => {
                let b = part.tessellate(TOP_CHORD)?.aabb();
                [b.min.z - TOP_CHORD, b.max.z + TOP_CHORD]
            }
        })
    }

    /// Refuses a design that covers no area seen from above (a vertical plane, a
    /// line): the commands that lay a grid over the part's XY box (verify, rest,
    /// classify) have nothing to measure. `name` is the part as the user gave it.
    ///
    /// # Errors
    /// A box of zero width or depth in XY, naming `name` and the box.
    pub fn check_covers_xy(&self, name: &str) -> Result<()> {
        let b = self.bounds();
        if b.max.x > b.min.x && b.max.y > b.min.y {
            return Ok(());
        }
        bail!(
            "{name}: the design covers no area in XY (x {} to {}, y {} to {} mm): expected a part seen from above, with width in both x and y",
            b.min.x,
            b.max.x,
            b.min.y,
            b.max.y
        )
    }
}

/// Names of the built-in parts (patches, then meshes), for messages and help texts.
pub fn builtin_names() -> Vec<&'static str> {
    let mut names = builtin_part_names();
    names.extend(swarf_io::builtin_mesh_names());
    names
}

/// Names of the built-in parametric parts (patches: the shared parts, then the
/// project's own), for commands that need patches.
pub fn builtin_part_names() -> Vec<&'static str> {
    let parts = swarf_io::builtin_parts().map(|(n, _)| n);
    let own = swarf_io::project_parts().map(|(n, _)| n);
    parts.into_iter().chain(own).collect()
}

/// Loads `arg`: `builtin:NAME`, a `.toml` part file, a STEP (`.step`, `.stp`) or
/// IGES (`.igs`, `.iges`) part, an `.stl` / `.obj` mesh, or a bare built-in name. A bare name is a file first: when a regular file of that name
/// exists it is read (and a note on standard error says how to name the built-in
/// part instead); anything else of that name (a directory, nothing) leaves the
/// built-in part.
///
/// # Errors
/// An unknown built-in name; a file that cannot be read or parsed.
pub fn load_model(arg: &str) -> Result<Model> {
    load_model_with(arg, &LoadOptions::default())
}

/// [`load_model`] with reading options: a CAD file read with `opts.cad` (its
/// warnings go to standard error), and only the faces `opts.faces` kept.
///
/// # Errors
/// As [`load_model`]; a face selection on a mesh, or one [`select_faces`] refuses.
pub fn load_model_with(arg: &str, opts: &LoadOptions) -> Result<Model> {
    let model = read_model(arg, &opts.cad)?;
    match (&opts.faces, model) {
        (None, m) => Ok(m),
        (Some(refs), Model::Patches(part)) => Ok(Model::Patches(select_faces(&part, refs, arg)?)),
        (Some(_), Model::Mesh { .. }) => {
            bail!(
                "faces: {arg} is a mesh, which has no faces to select; expected a part file, STEP or IGES"
            )
        }
    }
}

/// Reads `arg` as [`load_model`] describes.
fn read_model(arg: &str, cad: &CadOptions) -> Result<Model> {
    let path = Path::new(arg);
    let is_file = path.is_file();
    let known = |name: &str| {
        swarf_io::builtin_part(name).is_some() || swarf_io::builtin_mesh(name).is_some()
    };
    let prefixed = match Source::parse(arg, Path::new("")) {
        Source::Builtin(name) => Some(name),
        Source::File(_) => None,
    };
    if is_file && prefixed.is_none() && known(arg) {
        eprintln!("note: {arg}: reading the file {arg}; write builtin:{arg} for the built-in part");
    }
    let builtin = prefixed.or_else(|| (!is_file && (known(arg) || !path.exists())).then_some(arg));
    if let Some(name) = builtin {
        if let Some(part) = swarf_io::builtin_part(name) {
            return Ok(Model::Patches(part));
        }
        if let Some(mesh) = swarf_io::builtin_mesh(name) {
            let name = name.strip_suffix(".stl").unwrap_or(name).to_string();
            return Ok(Model::Mesh { name, mesh });
        }
        if prefixed.is_some() || path.extension().is_none() {
            bail!(
                "{}: no such file and no built-in part of that name (built-in parts: {})",
                swarf_geom::domain::excerpt(arg, 200),
                builtin_names().join(", ")
            );
        }
    }
    match swarf_io::read_model(path, cad)? {
        swarf_io::ModelFile::Mesh(mesh) => {
            if !(0..mesh.len()).any(|t| mesh.usable(t)) {
                bail!(
                    "{arg}: the mesh has no triangle with all corners finite and within \
                     1 km of the origin ({} triangles in all)",
                    mesh.len()
                );
            }
            let name = path
                .file_stem()
                .map_or_else(|| arg.to_string(), |s| s.to_string_lossy().into_owned());
            Ok(Model::Mesh { name, mesh })
        }
        swarf_io::ModelFile::Patches(cad) => {
            for w in &cad.warnings {
                eprintln!("warning: {arg}: {w}");
            }
            Ok(Model::Patches(cad.part))
        }
    }
}

/// The patch at `index` of `part` (0-based, in file order), for a command's or a
/// binding's patch argument.
///
/// # Errors
/// An index past the last patch, saying how many patches there are and their
/// indices (callers put the argument's name in front).
///
/// ```
/// let wave = swarf_io::builtin_part("wave").unwrap();
/// assert!(swarf_app::model::patch_at(&wave, 0).is_ok());
/// let e = swarf_app::model::patch_at(&wave, 3).unwrap_err();
/// assert_eq!(e, "index 3 is out of range: part wave has 1 patch (index 0)");
/// ```
pub fn patch_at(part: &Part, index: usize) -> std::result::Result<&Patch, String> {
    part.patches.get(index).ok_or_else(|| {
        let n = part.patches.len();
        let has = match n {
            0 => "no patch".to_string(),
            1 => "1 patch (index 0)".to_string(),
            _ => format!("{n} patches (indices 0 to {})", n - 1),
        };
        format!(
            "index {index} is out of range: part {} has {has}",
            part.name
        )
    })
}

/// Loads a parametric part (refuses meshes with a clear message).
///
/// # Errors
/// As [`load_model`], and a mesh.
pub fn load_part(arg: &str) -> Result<Part> {
    match load_model(arg)? {
        Model::Patches(p) => Ok(p),
        Model::Mesh { .. } => {
            bail!("{arg}: this command needs a parametric part (.toml), not a mesh")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Face;

    #[test]
    fn faces_are_selected_by_index_and_name() {
        let wave = swarf_io::builtin_part("wave").unwrap();
        let mut part = Part::new("three", vec![wave.patches[0].clone(); 3]);
        part.faces = vec![
            Face::default(),
            Face {
                name: Some("floor".into()),
                ..Face::default()
            },
        ];
        let got = select_faces(
            &part,
            &[FaceRef::Name("floor".into()), FaceRef::Index(2)],
            "p.step",
        )
        .unwrap();
        assert_eq!(got.patches.len(), 2);
        assert_eq!(got.face_name(0), Some("floor"));
        let e = select_faces(&part, &[FaceRef::Name("wall".into())], "p.step")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "faces: p.step has no face named \"wall\" (names: floor)");
        let e = select_faces(&part, &[FaceRef::Index(3)], "p.step")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("p.step: faces = 3: a face index below 3"),
            "{e}"
        );
        let opts = LoadOptions {
            faces: Some(vec![FaceRef::Index(0)]),
            ..LoadOptions::default()
        };
        let e = load_model_with("builtin:fillet-pocket", &opts)
            .err()
            .map(|e| e.to_string());
        if let Some(e) = e {
            assert!(e.contains("is a mesh, which has no faces"), "{e}");
        }
        let die = load_model_with("builtin:die", &opts).unwrap();
        assert!(matches!(die, Model::Patches(p) if p.patches.len() == 1));
    }
}
