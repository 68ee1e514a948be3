//! Wavefront OBJ meshes, read with `tobj` (polygons triangulated as fans; points,
//! lines, normals, texture coordinates and materials ignored; all objects and groups
//! merged into one mesh, vertices not welded).
//!
//! `tobj` reports errors without positions. Most of them are raised while the
//! offending line is parsed, so the reader is wrapped in a line counter and the line
//! just read is the one at fault. Index errors are only found when an object is
//! closed; for those the file is scanned again for the first face that refers to a
//! vertex (or texture coordinate, or normal) not defined before it.

use crate::error::{At, IoError};
use std::collections::HashMap;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use swarf_geom::{Point3, TriMesh};
use tobj::LoadError;

/// Reads an OBJ file.
///
/// # Units
/// Coordinates as stored (swarf assumes mm).
///
/// # Errors
/// [`IoError::Io`] when the file cannot be opened; [`IoError::Format`] naming the
/// line (when it can be found) for malformed content.
pub fn read_obj(path: &Path) -> Result<TriMesh, IoError> {
    let open = || std::fs::File::open(path).map_err(|e| IoError::io(path, "read", e));
    let file = open()?;
    let name = path.display().to_string();
    load(BufReader::new(file), &name, || Ok(BufReader::new(open()?)))
}

/// Parses the bytes of an OBJ file; `source` names it in errors.
///
/// # Errors
/// As [`read_obj`].
///
/// # Example
/// ```
/// let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
/// assert_eq!(swarf_io::parse_obj(quad.as_bytes(), "q.obj").unwrap().len(), 2);
/// let e = swarf_io::parse_obj(b"v 0 0 0\nf 1 2 3\n", "q.obj").unwrap_err();
/// assert_eq!(e.to_string(), "q.obj: line 2: face refers to vertex 2, but only 1 is defined before it");
/// ```
pub fn parse_obj(bytes: &[u8], source: &str) -> Result<TriMesh, IoError> {
    load(bytes, source, || Ok(bytes))
}

/// Loads with tobj from `reader`; `again` re-opens the input for locating errors.
fn load<R: BufRead, R2: BufRead>(
    reader: R,
    file: &str,
    again: impl Fn() -> Result<R2, IoError>,
) -> Result<TriMesh, IoError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let mut counted = LineCounter {
        inner: reader,
        newlines: 0,
        partial: false,
    };
    let loaded = tobj::load_obj_buf(&mut counted, &options, |_| Ok((Vec::new(), HashMap::new())));
    let models = match loaded {
        Ok((models, _materials)) => models,
        Err(e) => {
            let line = counted.newlines + usize::from(counted.partial);
            return Err(locate(e, line, file, again()?));
        }
    };
    let mut mesh = TriMesh::default();
    for m in &models {
        let vertices = m
            .mesh
            .positions
            .chunks_exact(3)
            .map(|p| Point3::new(p[0], p[1], p[2]))
            .collect();
        let triangles = m
            .mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        let part = TriMesh::new(vertices, triangles)
            .map_err(|e| IoError::format(file, At::File, format!("object {:?}: {e}", m.name)))?;
        if mesh.vertices.len() + part.vertices.len() > u32::MAX as usize {
            return Err(IoError::format(
                file,
                At::File,
                "more than u32::MAX vertices",
            ));
        }
        mesh.append(&part);
    }
    Ok(mesh)
}

/// The error for tobj's `e`, raised after reading line `line`.
fn locate(e: LoadError, line: usize, file: &str, again: impl BufRead) -> IoError {
    let at = At::Line(line.max(1));
    let msg = match e {
        LoadError::PositionParseError => {
            "expected `v x y z` with three numbers (and an optional w)"
        }
        LoadError::ScalingByZeroError => "vertex weight w is 0",
        LoadError::ColorParseError => "expected `v x y z r g b`: three color components",
        LoadError::NormalParseError => "expected `vn x y z` with three numbers",
        LoadError::TexcoordParseError => "expected `vt u v` with two numbers",
        LoadError::FaceParseError => {
            "expected `f` with vertex references `v`, `v/vt`, `v//vn` or `v/vt/vn` to defined vertices"
        }
        LoadError::ReadError => "cannot read the line (not UTF-8 text?)",
        LoadError::FaceVertexOutOfBounds
        | LoadError::FaceTexCoordOutOfBounds
        | LoadError::FaceNormalOutOfBounds
        | LoadError::InvalidPolygon => {
            return match find_bad_face(again) {
                Some((line, msg)) => IoError::format(file, At::Line(line), msg),
                None => IoError::format(file, At::File, e.to_string()),
            };
        }
        other => return IoError::format(file, at, other.to_string()),
    };
    IoError::format(file, at, msg)
}

/// The first face line with no vertex, or referring to a vertex, texture coordinate
/// or normal not defined before it, and what is wrong with it.
fn find_bad_face(reader: impl BufRead) -> Option<(usize, String)> {
    let mut counts = [0i64; 3];
    for (i, line) in reader.split(b'\n').enumerate() {
        let line = line.ok()?;
        let line = String::from_utf8_lossy(&line);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f") => {
                let refs: Vec<&str> = words.collect();
                if refs.is_empty() {
                    return Some((i + 1, "face without vertices".to_owned()));
                }
                if let Some(msg) = refs.iter().find_map(|r| bad_reference(r, &counts)) {
                    return Some((i + 1, msg));
                }
            }
            _ => {}
        }
    }
    None
}

/// What is wrong with face vertex reference `r` (`v/vt/vn`), given how many of each
/// are defined so far.
fn bad_reference(r: &str, counts: &[i64; 3]) -> Option<String> {
    const WHAT: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    for (k, part) in r.split('/').enumerate().take(3) {
        if part.is_empty() && k > 0 {
            continue;
        }
        let Ok(i) = part.parse::<i64>() else {
            return Some(format!("bad face vertex reference `{r}`"));
        };
        let n = counts[k];
        if i == 0 || i > n || -i > n {
            let are = if n == 1 { "is" } else { "are" };
            return Some(format!(
                "face refers to {} {i}, but only {n} {are} defined before it",
                WHAT[k]
            ));
        }
    }
    None
}

/// A `BufRead` that counts the newlines its consumer has consumed.
struct LineCounter<R> {
    inner: R,
    newlines: usize,
    /// True when bytes after the last newline have been consumed.
    partial: bool,
}

impl<R: BufRead> Read for LineCounter<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(out)?;
        count_lines(&out[..n], &mut self.newlines, &mut self.partial);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for LineCounter<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amt: usize) {
        if let Ok(buf) = self.inner.fill_buf() {
            count_lines(
                &buf[..amt.min(buf.len())],
                &mut self.newlines,
                &mut self.partial,
            );
        }
        self.inner.consume(amt);
    }
}

/// Adds the newlines in `bytes` to `newlines`; `partial` tells whether bytes follow
/// the last newline consumed.
fn count_lines(bytes: &[u8], newlines: &mut usize, partial: &mut bool) {
    if let Some(last) = bytes.iter().rposition(|&b| b == b'\n') {
        *newlines += bytes.iter().filter(|&&b| b == b'\n').count();
        *partial = last + 1 < bytes.len();
    } else if !bytes.is_empty() {
        *partial = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::scratch_dir;
    use proptest::prelude::*;

    fn err(text: &str) -> String {
        parse_obj(text.as_bytes(), "m.obj").unwrap_err().to_string()
    }

    #[test]
    fn triangulates_and_merges_objects() {
        let text = "# two objects\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no a\nf 1 2 3 4\no b\nf -4 -2 -1\nl 1 2\n";
        let m = parse_obj(text.as_bytes(), "m.obj").unwrap();
        assert_eq!(m.len(), 3);
        let corners: Vec<[Point3; 3]> = (0..3).map(|i| m.triangle(i)).collect();
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        assert_eq!(
            corners,
            vec![
                [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)],
                [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
                [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]
            ]
        );
        let with_slashes = parse_obj(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3//1\n",
            "m.obj",
        )
        .unwrap();
        assert_eq!(with_slashes.len(), 1);
    }

    #[test]
    fn errors_name_line() {
        assert_eq!(
            err("v 0 0 0\nv 1 0\nf 1 2 3\n"),
            "m.obj: line 2: expected `v x y z` with three numbers (and an optional w)"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"),
            "m.obj: line 4: expected `f` with vertex references `v`, `v/vt`, `v//vn` or `v/vt/vn` to defined vertices"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 q"),
            "m.obj: line 4: expected `vn x y z` with three numbers"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nf 1 2 7\nf 1 2 3\n"),
            "m.obj: line 6: face refers to vertex 7, but only 3 are defined before it"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/4 3/1\n"),
            "m.obj: line 5: face refers to texture coordinate 4, but only 1 is defined before it"
        );
        let e = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\xff\xfe\nf 1 2 3\n", "m.obj").unwrap_err();
        let e = e.to_string();
        assert!(e.starts_with("m.obj: line 4: "), "{e}");
    }

    #[test]
    fn reads_files() {
        let dir = scratch_dir("obj");
        let path = dir.join("t.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").unwrap();
        let e = read_obj(&path).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "{}: line 4: face refers to vertex 4, but only 3 are defined before it",
                path.display()
            )
        );
        std::fs::write(&path, "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert!(read_obj(&path).unwrap().validate().non_finite == vec![0]);
        let e = read_obj(&dir.join("none.obj")).unwrap_err().to_string();
        assert!(e.contains("none.obj: cannot read"), "{e}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        #[test]
        fn random_obj_text_never_panics(lines in prop::collection::vec("(v|vt|vn|f|o|g|l|#|s|usemtl)( -?[0-9/]{1,4}){0,5}", 0..12)) {
            let text = lines.join("\n");
            if let Err(e) = parse_obj(text.as_bytes(), "r.obj") {
                prop_assert!(e.to_string().starts_with("r.obj"));
            }
        }
    }
}
