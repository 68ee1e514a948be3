//! What the CAD readers (STEP, IGES) share: the
//! options a job or the command line gives them and what they return beside the part.

use swarf_geom::Part;

/// What to do with an entity the reader does not support.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Unsupported {
    /// Skip the face that uses it and say so in [`CadPart::warnings`].
    #[default]
    Warn,
    /// Refuse the file, naming the entity and its id.
    Refuse,
}

/// Options of the CAD readers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CadOptions {
    /// Unsupported entities: skip with a warning, or refuse.
    pub unsupported: Unsupported,
    /// Chordal tolerance for sampling trimming edges into loops, mm, in
    /// [`MIN_TRIM_CHORD`, `MAX_TRIM_CHORD`].
    pub trim_chord: f64,
}

/// Smallest trimming chord accepted, mm.
pub const MIN_TRIM_CHORD: f64 = 1e-7;
/// Largest trimming chord accepted, mm.
pub const MAX_TRIM_CHORD: f64 = 1.0;

impl Default for CadOptions {
    fn default() -> Self {
        CadOptions {
            unsupported: Unsupported::Warn,
            trim_chord: 1e-4,
        }
    }
}

/// A part read from a CAD file.
#[derive(Debug, Clone)]
pub struct CadPart {
    /// The faces, in mm whatever the file's unit; `Part::faces` holds names and trims.
    pub part: Part,
    /// One line per skipped entity or face: `#id ENTITY_NAME: why`.
    pub warnings: Vec<String>,
    /// The file's length unit as written (`mm`, `inch`, `m`...), for reports.
    pub unit: String,
}

impl CadPart {
    /// The part a reader has read from `source`: named after the file's stem, its
    /// `patches` with their `faces`.
    ///
    /// # Errors
    /// [`IoError::Format`](crate::IoError) when no face was read, saying what the
    /// reader `expected` and which entities it skipped.
    pub fn assemble(
        source: &str,
        patches: Vec<swarf_geom::Patch>,
        faces: Vec<swarf_geom::Face>,
        warnings: Vec<String>,
        unit: String,
        expected: &str,
    ) -> Result<CadPart, crate::IoError> {
        if patches.is_empty() {
            let skipped = if warnings.is_empty() {
                String::new()
            } else {
                format!("; skipped: {}", warnings.join("; "))
            };
            return Err(crate::IoError::format(
                source,
                crate::At::File,
                format!("no faces: expected {expected}{skipped}"),
            ));
        }
        let name = std::path::Path::new(source)
            .file_stem()
            .map_or_else(|| source.to_string(), |s| s.to_string_lossy().into_owned());
        let mut part = Part::new(name, patches);
        part.faces = faces;
        Ok(CadPart {
            part,
            warnings,
            unit,
        })
    }
}

/// Reads a STEP or IGES file, by its extension ([`crate::read_step`],
/// [`crate::read_iges`]).
///
/// # Errors
/// As the reader; [`IoError::Format`](crate::IoError) for another extension.
pub fn read_cad(path: &std::path::Path, opts: &CadOptions) -> Result<CadPart, crate::IoError> {
    match crate::ModelFormat::of(path) {
        crate::ModelFormat::Step => crate::read_step(path, opts),
        crate::ModelFormat::Iges => crate::read_iges(path, opts),
        _ => Err(crate::IoError::format(
            &path.display().to_string(),
            crate::At::File,
            "expected a .step, .stp, .igs or .iges file",
        )),
    }
}
