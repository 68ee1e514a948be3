//! STEP (ISO 10303-21 exchange structure; AP203, AP214, AP242 B-rep geometry) reader.
//!
//! **What it reads.** Faces reached from `CLOSED_SHELL` / `OPEN_SHELL` (every
//! `ADVANCED_FACE` when there is no shell) with their surfaces
//! (`B_SPLINE_SURFACE_WITH_KNOTS`, rational or not; `PLANE`, `CYLINDRICAL_SURFACE`,
//! `CONICAL_SURFACE`, `SPHERICAL_SURFACE`, `TOROIDAL_SURFACE` converted exactly to
//! NURBS by [`swarf_geom::Patch::plane`] and its siblings, sized from the face's
//! edges; `SURFACE_OF_LINEAR_EXTRUSION` of a B-spline curve), their trimming loops (edge curves `LINE`, `CIRCLE`, `ELLIPSE`,
//! `B_SPLINE_CURVE_WITH_KNOTS`, `TRIMMED_CURVE`, `SURFACE_CURVE`, `SEAM_CURVE`,
//! sampled in 3D within [`CadOptions::trim_chord`] once per edge and mapped into the
//! patch's `(u, v)`, see the `uv` module), face names, and the length and angle units
//! (mm, inch, m...; radians or degrees). P-curves are not used: the 3D edges decide.
//!
//! **Why our own reader.** Measured against truck-stepio 0.3.0: it parses
//! OpenCASCADE's files (rational complex entities included), but it costs 112 crates
//! (cold release build 6 min 51 s on the shared 2 cores), `Table::from_step` answers
//! `None` on any error (no line, no `#id`), and it hands back truck's own geometry
//! types that would be converted anyway. The exchange structure is small
//! ([`parser`], ISO 10303-21 sections 5-7) and typed errors naming file, line, `#id`,
//! entity and argument come with it.
//!
//! **Limits.** At most [`MAX_ENTITIES`] instances, lists nested at most [`MAX_DEPTH`]
//! deep; references are followed by type along the B-rep (shell -> face -> loop ->
//! edge -> vertex -> point), never recursively, so cyclic references cannot hang or
//! overflow the reader. Unsupported surface and edge-curve types skip their face with a warning `#id NAME: why`, or refuse the file,
//! as [`CadOptions::unsupported`] says.

mod clamp;
mod curves;
mod graph;
pub mod parser;
mod surfaces;
mod topology;
mod units;
mod uv;

use crate::cad::{CadOptions, CadPart, MAX_TRIM_CHORD, MIN_TRIM_CHORD, Unsupported};
use crate::error::{At, IoError};
use std::path::Path;

/// Most entity instances in one file.
pub const MAX_ENTITIES: usize = 20_000_000;
/// Deepest nesting of parameter lists.
pub const MAX_DEPTH: usize = 32;

/// Reads a STEP file into a part of trimmed faces.
///
/// # Units
/// The part is in mm whatever the file's length unit ([`CadPart::unit`] names it).
///
/// # Errors
/// [`IoError::Io`] when the file cannot be read; otherwise as [`parse_step`].
pub fn read_step(path: &Path, opts: &CadOptions) -> Result<CadPart, IoError> {
    let bytes = crate::input::read_input(path)?;
    let text = String::from_utf8_lossy(&bytes);
    parse_step(&text, &path.display().to_string(), opts)
}

/// Parses the text of a STEP file; `source` names it in errors.
///
/// # Units
/// mm in the returned part; `opts.trim_chord` in mm.
///
/// # Errors
/// [`IoError::Format`] naming the file, the line, and for entity errors the `#id`,
/// the entity name and the argument: not STEP, a syntax error, a dangling reference,
/// a wrong argument, an unsupported entity when `opts.unsupported` is
/// [`Unsupported::Refuse`], an open or crossing trimming loop, no faces at all.
///
/// # Example
/// ```
/// use swarf_io::{CadOptions, parse_step};
/// let e = parse_step("solid x\n", "x.step", &CadOptions::default()).unwrap_err();
/// assert!(e.to_string().starts_with("x.step: line 1: not a STEP file"), "{e}");
/// ```
pub fn parse_step(text: &str, source: &str, opts: &CadOptions) -> Result<CadPart, IoError> {
    if !(opts.trim_chord >= MIN_TRIM_CHORD && opts.trim_chord <= MAX_TRIM_CHORD) {
        return Err(IoError::format(
            source,
            At::File,
            format!(
                "trim_chord {} mm: expected {MIN_TRIM_CHORD:e} to {MAX_TRIM_CHORD} mm",
                swarf_geom::domain::show(opts.trim_chord)
            ),
        ));
    }
    let ex =
        parser::parse(text).map_err(|e| IoError::format(source, At::Line(e.line), e.message))?;
    let g = graph::Graph {
        ex: &ex,
        file: source,
    };
    let u = units::units(&g)?;
    let geo = curves::Geo {
        g: &g,
        mm: u.mm,
        rad: u.rad,
    };
    let mut cache = topology::EdgeCache::new();
    let mut patches = Vec::new();
    let mut faces = Vec::new();
    let mut warnings = Vec::new();
    for id in topology::face_ids(&geo)? {
        match topology::face(&geo, id, &mut cache, opts.trim_chord)? {
            topology::FaceResult::Read(p, f) => {
                patches.push(p);
                faces.push(f);
            }
            topology::FaceResult::Skipped(e) => match opts.unsupported {
                Unsupported::Refuse => return Err(e),
                Unsupported::Warn => warnings.push(match &e {
                    IoError::Format { message, .. } => message.clone(),
                    other => other.to_string(),
                }),
            },
        }
    }
    CadPart::assemble(
        source,
        patches,
        faces,
        warnings,
        u.name,
        "ADVANCED_FACEs with supported surfaces",
    )
}

#[cfg(test)]
mod tests;
