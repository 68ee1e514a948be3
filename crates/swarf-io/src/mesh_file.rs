//! Reading a mesh file of any supported format, chosen by its extension
//! ([`ModelFormat::of`]).

use crate::error::{At, IoError};
use crate::model_file::ModelFormat;
use crate::obj::read_obj;
use crate::stl::read_stl;
use std::path::Path;
use swarf_geom::TriMesh;

/// Reads a `.stl` or `.obj` mesh (extension in any case) holding at least one
/// triangle.
///
/// # Units
/// Coordinates as stored (swarf assumes mm).
///
/// # Errors
/// [`IoError::UnsupportedFormat`] for another extension; [`IoError::Format`] for a
/// file with no triangle (no STL facet, no OBJ face); otherwise those of
/// [`read_stl`] and [`read_obj`].
///
/// # Example
/// ```
/// let e = swarf_io::read_mesh(std::path::Path::new("part.ply")).unwrap_err();
/// assert_eq!(e.to_string(), "part.ply: unsupported mesh file type \".ply\"; expected .stl or .obj");
/// ```
pub fn read_mesh(path: &Path) -> Result<TriMesh, IoError> {
    let (mesh, element) = match ModelFormat::of(path) {
        ModelFormat::Stl => (read_stl(path)?, "`facet`"),
        ModelFormat::Obj => (read_obj(path)?, "`f` face line"),
        _ => {
            let ext = path.extension().map(|e| e.to_string_lossy());
            return Err(IoError::UnsupportedFormat {
                file: path.display().to_string(),
                found: ext.map_or("no extension".to_owned(), |e| format!(".{e}")),
            });
        }
    };
    if mesh.triangles.is_empty() {
        return Err(IoError::format(
            &path.display().to_string(),
            At::File,
            format!("a mesh with no triangle; expected at least one {element}"),
        ));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::scratch_dir;
    use swarf_geom::Point3;

    #[test]
    fn dispatches_on_extension_in_any_case() {
        let dir = scratch_dir("mesh-file");
        let t = [
            Point3::origin(),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        ];
        let mesh = TriMesh::from_triangles(&[t]);
        let mut out = crate::OutputSet::new();
        crate::stl::write_stl(&mut out, &dir.join("a.STL"), &mesh, "a").unwrap();
        out.commit().unwrap();
        assert_eq!(read_mesh(&dir.join("a.STL")).unwrap(), mesh);
        std::fs::write(dir.join("b.Obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(read_mesh(&dir.join("b.Obj")).unwrap(), mesh);
        let e = read_mesh(&dir.join("noext")).unwrap_err().to_string();
        assert!(
            e.ends_with(
                "noext: unsupported mesh file type \"no extension\"; expected .stl or .obj"
            ),
            "{e}"
        );
        let e = read_mesh(&dir.join("missing.stl")).unwrap_err().to_string();
        assert!(e.contains("missing.stl: cannot read"), "{e}");
    }

    #[test]
    fn a_mesh_with_no_triangle_is_refused() {
        let dir = scratch_dir("mesh-empty");
        let obj = dir.join("points.obj");
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n").unwrap();
        let e = read_mesh(&obj).unwrap_err().to_string();
        assert!(
            e.ends_with("points.obj: a mesh with no triangle; expected at least one `f` face line"),
            "{e}"
        );
        let stl = dir.join("empty.stl");
        std::fs::write(&stl, "solid e\nendsolid e\n").unwrap();
        let e = read_mesh(&stl).unwrap_err().to_string();
        assert!(
            e.ends_with("empty.stl: a mesh with no triangle; expected at least one `facet`"),
            "{e}"
        );
    }
}
