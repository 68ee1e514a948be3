//! swarf-io: reading and writing swarf's files.
//!
//! - [`part`]: part files (TOML patches, `parts/README.md`), and [`builtin`] copies of
//!   the shared test parts embedded in the binary;
//! - [`stl`], [`obj`], [`mesh_file`]: triangle meshes;
//! - [`model_file`]: a design in any of these formats, chosen by extension in one
//!   place;
//! - [`rest_parts`]: built-in mesh parts for rest-material detection, built in code;
//! - [`step`]: STEP (ISO 10303-21) B-rep parts as trimmed NURBS faces;
//! - [`iges`]: IGES 5.3 trimmed NURBS faces ([`cad`] options and result, and
//!   [`read_cad`], which picks the reader by the file's extension);
//! - [`source`]: `builtin:NAME` or a file, for parts, machines and posts;
//! - [`csv`]: numeric point lists; [`json`]: JSON whose numbers are all finite;
//! - [`atomic`], [`output_set`]: writes that never leave a half-written file, or a
//!   mix of two runs' files, behind.
//!
//! Every error is an [`IoError`] whose message names the file, the line or byte
//! offset where relevant, and what was expected.

pub mod atomic;
pub mod builtin;
pub mod cad;
mod clamp;
pub mod csv;
pub mod error;
pub mod iges;
pub mod input;
pub mod json;
pub mod mesh_file;
pub mod model_file;
pub mod obj;
pub mod output_set;
pub mod part;
pub mod rest_parts;
pub mod source;
pub mod step;
pub mod stl;

pub use atomic::{write_atomic, write_atomic_with};
pub use builtin::{builtin_part, builtin_parts, project_parts};
pub use cad::{CadOptions, CadPart, Unsupported, read_cad};
pub use csv::{parse_xy_points, read_xy_points};
pub use error::{At, IoError};
pub use iges::{parse_iges, read_iges};
pub use input::{checked_open, max_input_bytes, read_input, read_input_text, track_inputs};
pub use mesh_file::read_mesh;
pub use model_file::{ModelFile, ModelFormat, read_model};
pub use obj::{parse_obj, read_obj};
pub use output_set::OutputSet;
pub use part::{parse_part, read_part};
pub use rest_parts::{MESH_PART_CHORD, builtin_mesh, builtin_mesh_names};
pub use source::{BUILTIN_PREFIX, Source};
pub use step::{parse_step, read_step};
pub use stl::{parse_stl, read_stl, write_stl};

/// Scratch directories for tests.
#[cfg(test)]
pub(crate) mod testutil {
    use std::path::{Path, PathBuf};
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The sorted names in `dir`.
    pub fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .expect("read dir")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    /// A fresh empty directory under the system temp dir, unique to this process and
    /// call.
    pub fn scratch_dir(name: &str) -> PathBuf {
        static COUNT: AtomicUsize = AtomicUsize::new(0);
        let n = COUNT.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("swarf-io-{}-{n}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create scratch dir");
        dir
    }
}
