//! Binary STL: an 80-byte header, a little-endian `u32` triangle count, then per
//! triangle 50 bytes: normal (3 x `f32`), three vertices (9 x `f32`), a `u16`
//! attribute. Normals and attributes are ignored on reading.

use super::{HEADER, RECORD, builder_for};
use crate::error::{At, IoError};
use std::io::{self, Read, Write};
use swarf_geom::{Point3, TriMesh};

/// Records read per buffer fill.
const RECORDS_PER_CHUNK: usize = 1024;

/// Reads `count` triangle records following the 84-byte header.
pub(super) fn read(mut reader: impl Read, count: u32, file: &str) -> Result<TriMesh, IoError> {
    let mut header = [0u8; HEADER as usize];
    reader
        .read_exact(&mut header)
        .map_err(|e| IoError::format(file, At::Byte(0), format!("cannot read the header: {e}")))?;
    let mut builder = builder_for(u64::from(count));
    let mut chunk = vec![0u8; RECORD as usize * RECORDS_PER_CHUNK];
    let mut done: u64 = 0;
    while done < u64::from(count) {
        let n = (u64::from(count) - done).min(RECORDS_PER_CHUNK as u64) as usize;
        let bytes = &mut chunk[..n * RECORD as usize];
        let offset = HEADER + done * RECORD;
        reader.read_exact(bytes).map_err(|e| {
            IoError::format(
                file,
                At::Byte(offset),
                format!(
                    "cannot read triangles {} to {} of {count}: {e}",
                    done + 1,
                    done + n as u64
                ),
            )
        })?;
        for (k, record) in bytes.chunks_exact(RECORD as usize).enumerate() {
            let corners = [12, 24, 36].map(|at| vertex(&record[at..at + 12]));
            builder.push_triangle(corners).map_err(|e| {
                IoError::format(file, At::Byte(offset + k as u64 * RECORD), e.to_string())
            })?;
        }
        done += n as u64;
    }
    Ok(builder.finish())
}

/// Three little-endian `f32` as an exact `f64` point.
fn vertex(b: &[u8]) -> Point3 {
    let c = |i: usize| f64::from(f32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]));
    Point3::new(c(0), c(4), c(8))
}

/// The error for a file that is neither a binary STL of consistent size nor ASCII
/// STL: where it ends too early or runs on too long.
pub(super) fn size_error(head: &[u8], len: u64, file: &str) -> IoError {
    if len == 0 {
        return IoError::format(
            file,
            At::File,
            "empty file; expected an ASCII STL (`solid ...`) or a binary STL",
        );
    }
    let Some(count) = head.get(80..84).and_then(|b| <[u8; 4]>::try_from(b).ok()) else {
        return IoError::format(
            file,
            At::Byte(len),
            format!(
                "file ends inside the 84-byte header of a binary STL (found {len} bytes), and it does not begin with `solid` as an ASCII STL does"
            ),
        );
    };
    let count = u64::from(u32::from_le_bytes(count));
    let expected = HEADER + RECORD * count;
    let sizes =
        format!("expected {expected} bytes for a binary STL with {count} triangles, found {len}");
    if len < expected {
        let inside = (len - HEADER) / RECORD;
        let at = HEADER + inside * RECORD;
        IoError::format(
            file,
            At::Byte(at),
            format!(
                "file ends inside triangle {} of {count} ({sizes})",
                inside + 1
            ),
        )
    } else {
        IoError::format(
            file,
            At::Byte(expected),
            format!(
                "{} bytes after the last of {count} triangles ({sizes})",
                len - expected
            ),
        )
    }
}

/// Writes the header, the count and one record per triangle.
pub(super) fn write(w: &mut dyn Write, mesh: &TriMesh, name: &str, count: u32) -> io::Result<()> {
    let mut header = [b' '; HEADER as usize];
    let title = format!("binary STL by swarf: {name}");
    let n = title.len().min(80);
    header[..n].copy_from_slice(&title.as_bytes()[..n]);
    header[80..].copy_from_slice(&count.to_le_bytes());
    w.write_all(&header)?;
    let mut record = [0u8; RECORD as usize];
    for (i, t) in mesh.triangles.iter().enumerate() {
        let normal = mesh.normal(i).unwrap_or_default();
        let values =
            std::iter::once(normal).chain(t.iter().map(|&k| mesh.vertices[k as usize].coords));
        for (v, slot) in values.zip(record.chunks_exact_mut(12)) {
            for (c, out) in v.iter().zip(slot.chunks_exact_mut(4)) {
                out.copy_from_slice(&(*c as f32).to_le_bytes());
            }
        }
        w.write_all(&record)?;
    }
    Ok(())
}
