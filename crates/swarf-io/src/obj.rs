//! Wavefront OBJ meshes, read with `tobj` (polygons triangulated as fans; points,
//! lines, normals, texture coordinates and materials ignored; all objects and groups
//! merged into one mesh, vertices not welded).
//!
//! The input reaches `tobj` through a filter (`PositionsOnly`) that blanks `vt` and
//! `vn` lines and cuts face references `v/vt/vn` down to `v`, keeping one output
//! line per input line. That saves memory, and it keeps `tobj` away from its texture
//! and normal index arithmetic, which overflows (a panic in debug builds) on indices
//! such as `f 1/-5 ...`. `tobj` reports errors without positions; most are raised
//! while the offending line is parsed, so the line just handed over is the one at
//! fault. Index errors are only found when an object is closed; for those the input
//! is scanned again for the first face that refers to a vertex not defined before it.

use crate::error::{At, IoError};
use std::collections::HashMap;
use std::io::{BufRead, BufReader};
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
    let open = || crate::input::checked_open(path, crate::input::max_input_bytes());
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
    let mut filtered = PositionsOnly {
        inner: reader,
        line: Vec::new(),
        raw: Vec::new(),
        pos: 0,
        lines: 0,
        failed: None,
    };
    let loaded = tobj::load_obj_buf(&mut filtered, &options, |_| {
        Ok((Vec::new(), HashMap::new()))
    });
    if let Some(e) = filtered.failed.take() {
        let at = At::Line(filtered.lines + 1);
        return Err(IoError::format(file, at, format!("cannot read: {e}")));
    }
    let models = match loaded {
        Ok((models, _materials)) => models,
        Err(e) => return Err(locate(e, filtered.lines, file, again()?)),
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
        LoadError::FaceParseError => {
            "expected `f` with vertex references `v`, `v/vt`, `v//vn` or `v/vt/vn` to defined vertices"
        }
        LoadError::ReadError => "cannot read the line (not UTF-8 text?)",
        LoadError::FaceVertexOutOfBounds | LoadError::InvalidPolygon => {
            return match find_bad_face(again) {
                Some((line, msg)) => IoError::format(file, At::Line(line), msg),
                None => IoError::format(file, At::File, e.to_string()),
            };
        }
        other => return IoError::format(file, at, other.to_string()),
    };
    IoError::format(file, at, msg)
}

/// The first face line with no vertex, or referring to a vertex not defined before
/// it, and what is wrong with it.
fn find_bad_face(reader: impl BufRead) -> Option<(usize, String)> {
    let mut count = 0i64;
    for (i, line) in reader.split(b'\n').enumerate() {
        let line = line.ok()?;
        let line = String::from_utf8_lossy(&line);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => count += 1,
            Some("f") => {
                let refs: Vec<&str> = words.collect();
                if refs.is_empty() {
                    return Some((i + 1, "face without vertices".to_owned()));
                }
                for r in refs {
                    let v = r.split('/').next().unwrap_or("");
                    let Ok(k) = v.parse::<i64>() else {
                        return Some((i + 1, format!("bad face vertex reference `{r}`")));
                    };
                    if k == 0 || k > count || -k > count {
                        let are = if count == 1 { "is" } else { "are" };
                        let msg = format!(
                            "face refers to vertex {k}, but only {count} {are} defined before it"
                        );
                        return Some((i + 1, msg));
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// A `BufRead` handing `tobj` one line at a time with `vt` and `vn` lines blanked and
/// face references cut to their vertex index; counts the lines handed over.
struct PositionsOnly<R> {
    inner: R,
    /// The current output line.
    line: Vec<u8>,
    /// The current input line.
    raw: Vec<u8>,
    /// Bytes of `line` consumed.
    pos: usize,
    /// Lines handed over so far (the 1-based number of the current one).
    lines: usize,
    /// A read error of the input (tobj would only say "read error").
    failed: Option<std::io::Error>,
}

impl<R: BufRead> std::io::Read for PositionsOnly<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let n = {
            let buf = self.fill_buf()?;
            let n = buf.len().min(out.len());
            out[..n].copy_from_slice(&buf[..n]);
            n
        };
        self.consume(n);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for PositionsOnly<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        if self.pos == self.line.len() {
            self.raw.clear();
            self.line.clear();
            self.pos = 0;
            match self.inner.read_until(b'\n', &mut self.raw) {
                Ok(0) => {}
                Ok(_) => {
                    self.lines += 1;
                    filter_line(&self.raw, &mut self.line);
                }
                Err(e) => {
                    let kind = e.kind();
                    self.failed = Some(e);
                    return Err(kind.into());
                }
            }
        }
        Ok(&self.line[self.pos..])
    }

    fn consume(&mut self, amt: usize) {
        self.pos = (self.pos + amt).min(self.line.len());
    }
}

/// Writes `raw` to `out`, blanking `vt`/`vn` lines and cutting `f`/`l` references to
/// their first component; other lines (and any that are not UTF-8) pass unchanged.
fn filter_line(raw: &[u8], out: &mut Vec<u8>) {
    let newline = raw.ends_with(b"\n");
    let mut words = raw
        .split(|b| b.is_ascii_whitespace())
        .filter(|w| !w.is_empty());
    match words.next() {
        Some(b"vt" | b"vn") => {}
        Some(key @ (b"f" | b"l")) => {
            out.extend_from_slice(key);
            for w in words {
                out.push(b' ');
                out.extend_from_slice(w.split(|&b| b == b'/').next().unwrap_or(w));
            }
        }
        _ => {
            out.extend_from_slice(raw);
            return;
        }
    }
    if newline {
        out.push(b'\n');
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
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nf 1 2 7\nf 1 2 3\n"),
            "m.obj: line 6: face refers to vertex 7, but only 3 are defined before it"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/4 -4/1\n"),
            "m.obj: line 5: face refers to vertex -4, but only 3 are defined before it"
        );
        let odd =
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 q\nf 1/-5 2/1/99999999999999999 3//-9\n";
        assert_eq!(parse_obj(odd.as_bytes(), "m.obj").unwrap().len(), 1);
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
        fn random_obj_text_never_panics(lines in prop::collection::vec("(v|vt|vn|f|o|g|l|#|s|usemtl)( -?[0-9/]{1,20}){0,5}", 0..12)) {
            let text = lines.join("\n");
            if let Err(e) = parse_obj(text.as_bytes(), "r.obj") {
                prop_assert!(e.to_string().starts_with("r.obj"));
            }
        }
    }
}
