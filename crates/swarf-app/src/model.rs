//! Resolving a part as a user names it: a part file, a mesh file, or a built-in part
//! name.

use crate::error::{Result, bail};
use std::path::Path;
use swarf_geom::{Part, TriMesh};

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

    /// Refuses a design that covers no area seen from above (a vertical plane, a
    /// line): the commands that lay a grid over the part's XY box (verify, rest,
    /// classify) have nothing to measure. `name` is the part as the user gave it.
    ///
    /// # Errors
    /// A box of zero width or depth in XY, naming `name` and the box.
    pub fn check_covers_xy(&self, name: &str) -> Result<()> {
        let b = match self {
            Model::Patches(part) => part.control_box(),
            Model::Mesh { mesh, .. } => mesh.aabb(),
        };
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

/// Names of the built-in parts (patches, then meshes), for messages.
pub fn builtin_names() -> Vec<&'static str> {
    let parts = swarf_io::builtin_parts().map(|(n, _)| n);
    let own = swarf_io::project_parts().map(|(n, _)| n);
    parts
        .into_iter()
        .chain(own)
        .chain(swarf_io::builtin_mesh_names())
        .collect()
}

/// Loads `arg`: `builtin:NAME`, a `.toml` part file, an `.stl` / `.obj` mesh, or a
/// bare built-in name. A bare name is a file first: when a regular file of that name
/// exists it is read (and a note on standard error says how to name the built-in
/// part instead); anything else of that name (a directory, nothing) leaves the
/// built-in part.
///
/// # Errors
/// An unknown built-in name; a file that cannot be read or parsed.
pub fn load_model(arg: &str) -> Result<Model> {
    let path = Path::new(arg);
    let is_file = path.is_file();
    let known = |name: &str| {
        swarf_io::builtin_part(name).is_some() || swarf_io::builtin_mesh(name).is_some()
    };
    if is_file && !arg.starts_with("builtin:") && known(arg) {
        eprintln!("note: {arg}: reading the file {arg}; write builtin:{arg} for the built-in part");
    }
    let builtin = arg
        .strip_prefix("builtin:")
        .or_else(|| (!is_file && (known(arg) || !path.exists())).then_some(arg));
    if let Some(name) = builtin {
        if let Some(part) = swarf_io::builtin_part(name) {
            return Ok(Model::Patches(part));
        }
        if let Some(mesh) = swarf_io::builtin_mesh(name) {
            let name = name.strip_suffix(".stl").unwrap_or(name).to_string();
            return Ok(Model::Mesh { name, mesh });
        }
        if arg.starts_with("builtin:") || path.extension().is_none() {
            bail!(
                "{}: no such file and no built-in part of that name (built-in parts: {})",
                swarf_geom::domain::excerpt(arg, 200),
                builtin_names().join(", ")
            );
        }
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    match ext.as_str() {
        "stl" | "obj" => {
            let mesh = swarf_io::read_mesh(path)?;
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
        _ => Ok(Model::Patches(swarf_io::read_part(path)?)),
    }
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
