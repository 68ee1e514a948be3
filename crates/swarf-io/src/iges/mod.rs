//! IGES 5.3 reader (fixed ASCII form): trimmed NURBS faces in, a [`CadPart`] out.
//!
//! Read: entities 128 (rational B-spline surface), 144 (trimmed surface) with its 142
//! (curve on a parametric surface) boundaries, 108 (plane, bounded by its trimming
//! curves) and the curves that make up trimming loops: 126 (rational B-spline curve),
//! 110 (line), 100 (circular arc) and 102 (composite curve), each under its 124
//! (transformation matrix). Every independent 144 and 128 is a face.
//!
//! Derivations (IGES 5.3 sec. 4):
//! - 128 lists control points with the first index (along u) varying fastest:
//!   point `(i, j)` is the file's `i + j (K1 + 1)`, swarf's row-major `i n_v + j`. A
//!   periodic or unclamped knot vector is clamped at the ends of its domain
//!   `[U_p, U_n]` by knot insertion (`clamp.rs`), which leaves the surface unchanged.
//! - A 142 gives a loop either in the surface's `(u, v)` (BPTR) or in model space
//!   (CPTR); the `(u, v)` curve is used when given and supported (PREF is not
//!   consulted), else the model-space one. A `(u, v)` curve is sampled within `trim_chord / max(|S_u| + |S_v|)`,
//!   since a `(u, v)` chord `d` moves the surface point by at most
//!   `(|S_u| + |S_v|) |d|`; a model-space curve is sampled within `trim_chord` and
//!   each sample projected on the surface, from the previous sample's `(u, v)`.
//! - On a closed surface (opposite domain edges coincide) writers may give a seam
//!   edge's `(u, v)` curve a period away, or leave out a degenerate edge (a sphere's
//!   pole): pieces whose ends meet on the surface but not in `(u, v)` are either
//!   joined by the straight `(u, v)` segment or shifted by a period, whichever gives
//!   a loop that does not cross itself (bridging tried first).
//! - A 108 plane has no parametrisation in IGES: swarf makes it a bilinear patch over
//!   the box of its boundary in an orthonormal frame of the plane (with a margin), so
//!   `(u, v)` are mm in that frame.
//! - Units: Global fields 13-15; lengths are multiplied by the unit's mm and divided by
//!   the model-space scale. Gaps between a loop's curves, and model-space points off
//!   their surface, are accepted up to 1e-3 mm or the file's resolution (field 19).
//!
//! Names: a 406 form 15 property of the 144 (or bare 128), else its DE label and
//! subscript, else those of its surface. Unsupported entities (a face type other
//! than 144/128, a surface other than 128/108 under a 144, a trimming curve other
//! than 100/102/110/126) skip their face with a warning `DE n type T: why` or refuse
//! the file, as [`CadOptions::unsupported`] says. Work is bounded by the file: every
//! count is checked against the parameters present before allocating, composite
//! curves may not contain themselves, and curve visits are capped per entity.

mod curve;
mod face;
mod params;
mod records;
mod surface;
#[cfg(test)]
mod tests;
mod transform;

use crate::cad::{CadOptions, CadPart, MAX_TRIM_CHORD, MIN_TRIM_CHORD, Unsupported};
use crate::error::{At, IoError};
use params::{Params, tokenize};
use records::{Entry, Records};
use std::path::Path;
use swarf_geom::Face;

/// Deepest nesting of entities followed (composite curves in composite curves,
/// transformation chains); deeper is refused as a likely cycle.
const MAX_DEPTH: usize = 32;
/// Curve entities sampled per directory entry, at most, over the whole file (a
/// composite curve may list one sub-curve many times; this bounds the work).
const VISITS_PER_ENTRY: usize = 8;

/// Reads an IGES file.
///
/// # Units
/// The returned part is in mm whatever the file's unit; `trim_chord` in mm.
///
/// # Errors
/// [`IoError::Io`] when the file cannot be read; otherwise as [`parse_iges`].
pub fn read_iges(path: &Path, opts: &CadOptions) -> Result<CadPart, IoError> {
    let bytes = crate::input::read_input(path)?;
    let file = path.display().to_string();
    let text = String::from_utf8_lossy(&bytes);
    parse_iges(&text, &file, opts)
}

/// Parses the text of an IGES file; `source` names it in errors.
///
/// # Units
/// The returned part is in mm whatever the file's unit; `trim_chord` in mm.
///
/// # Errors
/// [`IoError::Format`] when the text is not fixed-form IGES (no section letter in
/// column 73, sections out of order, counts that disagree with the terminate
/// record); [`IoError::Field`] naming the entity (`DE n type T`) and the parameter
/// for a bad value, a pointer out of range or in a cycle, a surface or curve that
/// swarf's kernel rejects, an open or self-intersecting trimming loop, an unsupported
/// entity when `opts.unsupported` is [`Unsupported::Refuse`], or a file without any
/// face.
///
/// # Example
/// ```
/// let e = swarf_io::parse_iges("solid x\n", "x.igs", &Default::default()).unwrap_err();
/// assert!(e.to_string().starts_with("x.igs: line 1: not an IGES file"));
/// ```
pub fn parse_iges(text: &str, source: &str, opts: &CadOptions) -> Result<CadPart, IoError> {
    if !(opts.trim_chord >= MIN_TRIM_CHORD && opts.trim_chord <= MAX_TRIM_CHORD) {
        return Err(IoError::field(
            source,
            At::File,
            "trim_chord",
            format!(
                "{} mm: expected {MIN_TRIM_CHORD:e} to {MAX_TRIM_CHORD} mm",
                swarf_geom::domain::show(opts.trim_chord)
            ),
        ));
    }
    let rec = records::split(text, source)?;
    let iges = Iges {
        file: source,
        rec,
        opts: *opts,
        visits: std::cell::Cell::new(0),
    };
    let mut warnings = Vec::new();
    let mut patches = Vec::new();
    let mut faces = Vec::new();
    let trimmed = iges.trimmed_surfaces();
    for (k, e) in iges.rec.entries.iter().enumerate() {
        let de = 2 * k + 1;
        if !e.independent() || trimmed.contains(&de) {
            continue;
        }
        let got = match e.ty {
            144 => iges.trimmed_surface(de),
            128 => iges.bare_surface(de),
            108 | 114 | 118 | 120 | 122 | 140 | 143 | 186 | 190..=199 | 502..=514 => {
                Err(Problem::Unsupported { de, ty: e.ty, why: "not a supported face entity (faces are read from 144 and 128; write the file in faces mode)".into() })
            }
            _ => continue,
        };
        match got {
            Ok((patch, face)) => {
                patches.push(patch);
                faces.push(face);
            }
            Err(Problem::Io(err)) => return Err(err),
            Err(Problem::Unsupported { de: at, ty, why }) => {
                let why = if at == de {
                    why
                } else {
                    format!("{why}; face DE {de} skipped")
                };
                let (de, msg) = (at, format!("DE {at} type {ty}: {why}"));
                if opts.unsupported == Unsupported::Refuse {
                    return Err(iges.err(de, format!("unsupported: {why}")));
                }
                warnings.push(msg);
            }
        }
    }
    CadPart::assemble(
        source,
        patches,
        faces,
        warnings,
        iges.rec.unit.clone(),
        "at least one supported entity 144 (trimmed surface) or 128 (B-spline surface)",
    )
}

/// Why a face could not be read.
pub(crate) enum Problem {
    /// An entity the reader does not support: skipped or refused per the options.
    Unsupported {
        /// Its DE pointer.
        de: usize,
        /// Its type.
        ty: i64,
        /// Why.
        why: String,
    },
    /// The file is wrong.
    Io(IoError),
}

impl From<IoError> for Problem {
    fn from(e: IoError) -> Self {
        Problem::Io(e)
    }
}

/// The parsed file and the options.
pub(crate) struct Iges<'a> {
    file: &'a str,
    rec: Records<'a>,
    opts: CadOptions,
    /// Curve entities sampled so far (bounded by [`VISITS_PER_ENTRY`]).
    visits: std::cell::Cell<usize>,
}

impl Iges<'_> {
    /// The surfaces that 144s trim (writers that mark every entity independent
    /// would otherwise have them read twice, once whole), sorted.
    fn trimmed_surfaces(&self) -> Vec<usize> {
        let mut out: Vec<usize> = (0..self.rec.entries.len())
            .filter(|k| self.rec.entries[*k].ty == 144)
            .filter_map(|k| self.params(2 * k + 1, "trimmed surface").ok())
            .filter_map(|p| p.ptr(self, 1).ok())
            .collect();
        out.sort_unstable();
        out
    }

    /// The directory entry at DE pointer `de`.
    ///
    /// # Errors
    /// When `de` is not an odd number within the directory (`who` says which
    /// pointer).
    fn entry(&self, de: usize, who: &str) -> Result<&Entry, IoError> {
        if de % 2 == 1
            && let Some(e) = self.rec.entries.get(de / 2)
        {
            return Ok(e);
        }
        Err(IoError::format(
            self.file,
            At::File,
            format!(
                "{who}: DE pointer {de}: expected an odd number from 1 to {}",
                2 * self.rec.entries.len()
            ),
        ))
    }

    /// An error about entity `de`, at its parameter record's line.
    fn err(&self, de: usize, message: impl Into<String>) -> IoError {
        let (ty, line) = match self.rec.entries.get(de / 2) {
            Some(e) => {
                let l = self.param_line(e);
                (
                    e.ty,
                    if l > 0 {
                        l
                    } else {
                        self.rec.entry_lines[de / 2]
                    },
                )
            }
            None => (0, 0),
        };
        let at = if line > 0 { At::Line(line) } else { At::File };
        IoError::field(self.file, at, format!("DE {de} type {ty}"), message)
    }

    /// The file line of an entity's first parameter record (0 if out of range).
    fn param_line(&self, e: &Entry) -> usize {
        e.param
            .checked_sub(1)
            .and_then(|k| self.rec.params.get(k))
            .map_or(0, |p| p.1)
    }

    /// The parameters of entity `de`, checked to start with its type.
    fn params(&self, de: usize, who: &str) -> Result<Params, IoError> {
        let e = self.entry(de, who)?;
        let n = e.param_lines.max(1);
        let lines = e
            .param
            .checked_sub(1)
            .and_then(|k| self.rec.params.get(k..k + n))
            .ok_or_else(|| {
                self.err(
                    de,
                    format!(
                        "parameter records {} to {}: expected within the {} P records",
                        e.param,
                        e.param + n - 1,
                        self.rec.params.len()
                    ),
                )
            })?;
        let text: String = lines.iter().map(|(l, _)| *l).collect();
        let (pd, rd) = self.rec.delims;
        let toks = tokenize(&text, pd, rd).map_err(|m| self.err(de, m))?;
        let p = Params { de, ty: e.ty, toks };
        let t = p.int(self, 0)?;
        if t != e.ty {
            return Err(self.err(
                de,
                format!("parameter data starts with type {t}; expected {}", e.ty),
            ));
        }
        Ok(p)
    }
}

/// Face from entity: patch and face record.
pub(crate) type FaceOut = (swarf_geom::Patch, Face);
