//! Reading a design of any supported format, the format chosen by the file's
//! extension in one place ([`ModelFormat::of`]): part files (TOML patches), STL and
//! OBJ meshes, STEP and IGES B-rep parts.

use crate::cad::{CadOptions, CadPart};
use crate::error::IoError;
use std::path::Path;
use swarf_geom::TriMesh;

/// The file formats a design (or a stock mesh) is read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelFormat {
    /// A part file: TOML patches (`parts/README.md`); any extension not below.
    Part,
    /// An STL mesh (`.stl`).
    Stl,
    /// A Wavefront OBJ mesh (`.obj`).
    Obj,
    /// A STEP B-rep (`.step`, `.stp`).
    Step,
    /// An IGES B-rep (`.igs`, `.iges`).
    Iges,
}

impl ModelFormat {
    /// Every format, in the order help texts and messages name them.
    pub const ALL: [ModelFormat; 5] = [
        ModelFormat::Part,
        ModelFormat::Step,
        ModelFormat::Iges,
        ModelFormat::Stl,
        ModelFormat::Obj,
    ];

    /// The file extensions that name the format, lower case, without the dot
    /// ([`ModelFormat::Part`] is also read from any extension no other format names).
    ///
    /// ```
    /// use swarf_io::ModelFormat;
    /// assert_eq!(ModelFormat::Step.extensions(), ["step", "stp"]);
    /// ```
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            ModelFormat::Part => &["toml"],
            ModelFormat::Stl => &["stl"],
            ModelFormat::Obj => &["obj"],
            ModelFormat::Step => &["step", "stp"],
            ModelFormat::Iges => &["igs", "iges"],
        }
    }

    /// The format's name in help texts and messages (`part file`, `STEP`, `STL`).
    pub fn name(self) -> &'static str {
        match self {
            ModelFormat::Part => "part file",
            ModelFormat::Stl => "STL",
            ModelFormat::Obj => "OBJ",
            ModelFormat::Step => "STEP",
            ModelFormat::Iges => "IGES",
        }
    }

    /// The format `path`'s extension names (any case); [`ModelFormat::Part`] for
    /// any other extension or none.
    ///
    /// ```
    /// use swarf_io::ModelFormat;
    /// use std::path::Path;
    /// assert_eq!(ModelFormat::of(Path::new("a.STL")), ModelFormat::Stl);
    /// assert_eq!(ModelFormat::of(Path::new("a.stp")), ModelFormat::Step);
    /// assert_eq!(ModelFormat::of(Path::new("wave.toml")), ModelFormat::Part);
    /// ```
    pub fn of(path: &Path) -> ModelFormat {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        ModelFormat::ALL
            .into_iter()
            .find(|f| ext.as_deref().is_some_and(|e| f.extensions().contains(&e)))
            .unwrap_or(ModelFormat::Part)
    }

    /// Whether the format is a triangle mesh.
    pub fn is_mesh(self) -> bool {
        matches!(self, ModelFormat::Stl | ModelFormat::Obj)
    }

    /// Whether the format is a CAD B-rep (STEP or IGES).
    pub fn is_cad(self) -> bool {
        matches!(self, ModelFormat::Step | ModelFormat::Iges)
    }
}

/// A design as read from a file.
#[derive(Debug, Clone)]
pub enum ModelFile {
    /// Parametric patches: a part file, or a CAD part with its warnings and unit.
    Patches(CadPart),
    /// A triangle mesh.
    Mesh(TriMesh),
}

/// Reads the design at `path` in the format its extension names
/// ([`ModelFormat::of`]); `cad` are the STEP and IGES readers' options.
///
/// # Units
/// mm (CAD files are converted from their own unit; meshes and part files are
/// taken as mm).
///
/// # Errors
/// Those of the format's reader ([`crate::read_part`], [`crate::read_mesh`],
/// [`crate::read_cad`]).
pub fn read_model(path: &Path, cad: &CadOptions) -> Result<ModelFile, IoError> {
    let format = ModelFormat::of(path);
    if format.is_mesh() {
        return Ok(ModelFile::Mesh(crate::read_mesh(path)?));
    }
    if format.is_cad() {
        return Ok(ModelFile::Patches(crate::read_cad(path, cad)?));
    }
    Ok(ModelFile::Patches(CadPart {
        part: crate::read_part(path)?,
        warnings: Vec::new(),
        unit: "mm".into(),
    }))
}
