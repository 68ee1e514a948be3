//! A job's part passed in already loaded (`swarf.plan(job, part=...)`), so that many
//! jobs on one part read it once: the model is planned on as
//! [`swarf_app::load_model_with`] would have read it for the job, or refused.
//!
//! What a job's reading options change, and how a loaded object is held to them:
//! the CAD readers' options (`[import]`) change only a part read from a STEP or IGES
//! file, so a [`crate::model::Part`] records the options it was read with when it
//! came from one ([`ReadWith`]) and must match the job's; `faces` keeps some faces of
//! a part after reading ([`swarf_app::model::select_faces`], the loader's own step),
//! so a part read whole has the job's faces selected here, and one read with a
//! selection must have the job's.

use crate::errors::swarf_msg;
use crate::model::{Mesh, Part};
use pyo3::prelude::*;
use std::path::Path;
use std::sync::Arc;
use swarf_app::{FaceRef, LoadOptions, Model};
use swarf_io::{CadOptions, ModelFormat, Unsupported};

/// How a [`Part`] was read, beside its patches.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadWith {
    /// The CAD readers' options, for a part read from a STEP or IGES file (None for
    /// a part file or a built-in part, which they do not change).
    pub cad: Option<CadOptions>,
    /// The faces kept (None: all of them).
    pub faces: Option<Vec<FaceRef>>,
}

impl ReadWith {
    /// How [`swarf_app::load_model_with`] reads `arg` with `opts`.
    pub fn of(arg: &str, opts: &LoadOptions) -> ReadWith {
        ReadWith {
            cad: ModelFormat::of(Path::new(arg)).is_cad().then_some(opts.cad),
            faces: opts.faces.clone(),
        }
    }
}

/// A `part=` argument: the model and how it was read.
pub struct Loaded {
    model: Arc<Model>,
    read: ReadWith,
}

impl Loaded {
    /// Reads `obj` as a `part=` argument.
    ///
    /// # Errors
    /// `TypeError` for anything but a `Part` or a `Mesh`.
    pub fn extract(obj: &Bound<'_, PyAny>) -> PyResult<Loaded> {
        if let Ok(p) = obj.cast::<Part>() {
            let p = p.get();
            return Ok(Loaded {
                model: p.model.clone(),
                read: p.read.clone(),
            });
        }
        if let Ok(m) = obj.cast::<Mesh>() {
            return Ok(Loaded {
                model: m.get().model.clone(),
                read: ReadWith::default(),
            });
        }
        Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "part: expected a Part or a Mesh (the job's part, loaded once: Job.load_part(), \
             Part.load, Mesh.load), found {}",
            obj.get_type().name()?
        )))
    }

    /// The model `job` plans on: this one as it is when it was read as the job reads
    /// its part (named `arg`), with the job's `faces` selected when it was read
    /// whole (call without the GIL).
    ///
    /// # Errors
    /// `SwarfError` naming `part` for a part read with other CAD options or another
    /// face selection, a mesh for a job that selects faces, or a selection
    /// [`swarf_app::model::select_faces`] refuses.
    pub fn for_job(&self, job: &swarf_app::Job, arg: &str) -> PyResult<Arc<Model>> {
        let want = job.load_options();
        let part = match &*self.model {
            Model::Patches(part) => part,
            Model::Mesh { .. } if want.faces.is_some() => {
                return Err(swarf_msg(
                    "part: a Mesh has no faces to select, and the job selects `faces`: \
                     expected a Part (the job's part file, STEP or IGES)",
                ));
            }
            Model::Mesh { .. } => return Ok(self.model.clone()),
        };
        if let Some(cad) = self.read.cad
            && cad != want.cad
        {
            return Err(swarf_msg(format!(
                "part: the Part was read from its STEP/IGES file with {}; the job reads it \
                 with {}: expected the part read as the job reads it (Job.load_part())",
                cad_text(&cad),
                cad_text(&want.cad)
            )));
        }
        if self.read.faces == want.faces {
            return Ok(self.model.clone());
        }
        match (&self.read.faces, &want.faces) {
            (None, Some(refs)) => swarf_app::model::select_faces(part, refs, arg)
                .map(|p| Arc::new(Model::Patches(p)))
                .map_err(|e| swarf_msg(format!("part: {}", crate::errors::chain(&e)))),
            (had, wanted) => Err(swarf_msg(format!(
                "part: the Part holds the faces {} of its file; the job selects {}: expected \
                 the part read whole or as the job reads it (Job.load_part())",
                faces_text(had.as_deref()),
                faces_text(wanted.as_deref())
            ))),
        }
    }
}

/// `opts` as the job file's `[import]` keys.
fn cad_text(opts: &CadOptions) -> String {
    let unsupported = match opts.unsupported {
        Unsupported::Warn => "warn",
        Unsupported::Refuse => "refuse",
    };
    format!(
        "import.trim_chord = {} mm, import.unsupported = \"{unsupported}\"",
        swarf_geom::domain::show(opts.trim_chord)
    )
}

/// A face selection as the job file writes it.
fn faces_text(faces: Option<&[FaceRef]>) -> String {
    let Some(faces) = faces else {
        return "all of them".to_string();
    };
    let items: Vec<String> = faces
        .iter()
        .map(|f| match f {
            FaceRef::Index(k) => k.to_string(),
            FaceRef::Name(n) => format!("{n:?}"),
        })
        .collect();
    format!("[{}]", items.join(", "))
}
