//! Resolving the PART arguments: a part file, a mesh file, or a built-in part name.

use anyhow::{Context, Result, bail};
use std::path::Path;
use swarf_geom::{Part, TriMesh};

/// A part as the user named it: parametric patches or a triangle mesh.
pub enum Model {
    /// Patches from a part file or a built-in part.
    Patches(Part),
    /// A triangle mesh from STL or OBJ.
    Mesh { name: String, mesh: TriMesh },
}

/// Names of the built-in parts, for messages.
pub fn builtin_names() -> Vec<&'static str> {
    swarf_io::builtin_parts().iter().map(|(n, _)| *n).collect()
}

/// Loads `arg`: `builtin:NAME` or a bare built-in name (when no such file exists),
/// a `.toml` part file, or an `.stl` / `.obj` mesh.
pub fn load_model(arg: &str) -> Result<Model> {
    let path = Path::new(arg);
    let builtin = arg
        .strip_prefix("builtin:")
        .or_else(|| (!path.exists()).then_some(arg));
    if let Some(name) = builtin {
        if let Some(part) = swarf_io::builtin_part(name) {
            return Ok(Model::Patches(part));
        }
        if arg.starts_with("builtin:") || path.extension().is_none() {
            bail!(
                "{arg}: no such file and no built-in part of that name (built-in parts: {})",
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
            let name = path
                .file_stem()
                .map_or_else(|| arg.to_string(), |s| s.to_string_lossy().into_owned());
            Ok(Model::Mesh { name, mesh })
        }
        _ => Ok(Model::Patches(swarf_io::read_part(path)?)),
    }
}

/// Loads a parametric part (refuses meshes with a clear message).
pub fn load_part(arg: &str) -> Result<Part> {
    match load_model(arg)? {
        Model::Patches(p) => Ok(p),
        Model::Mesh { .. } => {
            bail!("{arg}: this command needs a parametric part (.toml), not a mesh")
        }
    }
}

/// Parses `U,V` into two numbers.
pub fn parse_pair(text: &str, what: &str) -> Result<[f64; 2]> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        bail!("{what}: expected two numbers separated by a comma, found {text:?}");
    }
    let mut out = [0.0; 2];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = p
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .with_context(|| format!("{what}: {p:?} is not a finite number"))?;
    }
    Ok(out)
}
