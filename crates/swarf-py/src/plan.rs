//! Planning a job from Python: `swarf plan` as values ([`swarf_app::plan_model_toolpath`]):
//! the program's moves as arrays, the summary as a dict, and the G-code and APT CL
//! text the job writes; the strategy functions [`waterline`] and [`raster`] give the
//! passes of one strategy on a part or mesh as a list of arrays. [`plan`] hands a
//! sequence job to [`crate::sequence`].

use crate::arrays::{grid_out, vec_out};
use crate::errors::{detached, swarf_err, swarf_msg};
use crate::job::{Job, job_arg, job_from_dict};
use crate::loaded::Loaded;
use crate::model::{ModelArg, path_text};
use crate::sequence::{plan_sequence_values, sequence_arg};
use crate::tool::cutter_arg;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use swarf_app::gate::Gate;
use swarf_app::{Model, Outputs, PlanInput};
use swarf_sim::Quiet;
use swarf_toolpath::{MoveKind, Toolpath};

/// A JSON value as Python objects (through the `json` module: numbers read back to
/// the same floats).
pub fn json_to_py(py: Python<'_>, value: &serde_json::Value) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(value).map_err(swarf_err)?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// A folder of its own under the system's temporary folder, removed on drop.
pub(crate) struct Scratch(PathBuf);

impl Scratch {
    fn new() -> PyResult<Scratch> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("swarf-py-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .map_err(|e| swarf_msg(format!("{}: cannot create: {e}", dir.display())))?;
        Ok(Scratch(dir))
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The folder outputs are staged in: `out`, or (without it) a scratch folder of its
/// own, returned with it so that it lives as long as the staging.
pub(crate) fn output_dir(out: Option<&Path>) -> PyResult<(PathBuf, Option<Scratch>)> {
    match out {
        Some(o) => Ok((o.to_path_buf(), None)),
        None => {
            let scratch = Scratch::new()?;
            Ok((scratch.0.clone(), Some(scratch)))
        }
    }
}

/// What planning gave, before it becomes a [`Plan`].
struct Planned {
    summary: serde_json::Value,
    toolpath: Toolpath,
    gcode: Option<String>,
    cl: Option<String>,
}

/// The G-code and CL of `job` as staged in `out`.
fn staged_texts(job: &swarf_app::Job, out: &Outputs) -> PyResult<(Option<String>, Option<String>)> {
    let read = |rel: &Option<String>| -> PyResult<Option<String>> {
        rel.as_ref()
            .map(|r| out.read_text(&out.path(r)).map_err(swarf_err))
            .transpose()
    };
    Ok((read(&job.output.gcode)?, read(&job.output.cl)?))
}

/// Plans `job` (without the GIL) on its part, or on `part` when given (the same
/// model, read once by the caller): with `out`, writing the job's outputs there as
/// `swarf plan --out` does; without, staging only its G-code and CL in a scratch
/// folder to read them back.
fn plan_job_values(
    job: &Job,
    part: Option<&Loaded>,
    out: Option<&Path>,
    gate: Gate,
) -> PyResult<Planned> {
    let context = |e: swarf_app::AppError| {
        swarf_msg(format!(
            "{}: planning the job: {}",
            job.source,
            crate::errors::chain(&e)
        ))
    };
    let arg = swarf_app::plan_job::part_arg(&job.job, &job.dir);
    let model = match part {
        Some(loaded) => loaded.for_job(&job.job, &arg)?,
        None => {
            Arc::new(swarf_app::load_model_with(&arg, &job.job.load_options()).map_err(context)?)
        }
    };
    let mut staged_job = match out {
        Some(_) => job.job.clone(),
        None => {
            let mut j = job.job.clone();
            // A tilted path is written as G-code only for a machine (the job schema's
            // rule, `output.machine`).
            let tilted = j.tilted();
            let o = &mut j.output;
            o.gcode = (!tilted || o.machine.is_some()).then(|| "plan.ngc".to_string());
            o.cl = Some("plan.cl".to_string());
            (o.csv, o.summary, o.double_contacts, o.contacts) = (None, None, None, None);
            j
        }
    };
    staged_job.gate = gate;
    let (dir, _scratch) = output_dir(out)?;
    let mut outputs = Outputs::new(&dir);
    let planned =
        swarf_app::plan_model_toolpath(&staged_job, &model, &job.dir, &mut outputs, &Quiet)
            .map_err(context)?;
    let (gcode, cl) = staged_texts(&staged_job, &outputs)?;
    if out.is_some() {
        outputs.commit().map_err(swarf_err)?;
    }
    Ok(Planned {
        summary: planned.summary,
        toolpath: planned.toolpath,
        gcode,
        cl,
    })
}

/// Plans a job as `swarf plan` does: `job` is a `Job`, a dict in the job file's
/// schema, TOML text (a str with a line break) or the path of a job file; a
/// sequence job (`[[operation]]` tables) as a path, TOML text or a dict. With
/// `out`, the job's outputs are written into that folder as `swarf plan JOB --out
/// OUT` writes them; without, nothing is written.
///
/// `part` is the job's part already loaded, a `Part` or a `Mesh`
/// (`Job.load_part()`, or `Part.load` / `Mesh.load` of the job's part file), for
/// many jobs on one part: the plan is the one the job gives reading its part
/// itself, bit for bit. A part read with other `[import]` options or another face
/// selection than the job's is refused (`SwarfError` naming `part`); a part read
/// whole has the job's `faces` selected. Not for a sequence job, which reads its
/// own part.
///
/// The program is verified on the job's stock first, as `swarf plan` does: an
/// unsafe one raises `SwarfError` naming its lines; `allow_unsafe=True` returns it
/// labelled, `verify=False` skips the check (`--allow-unsafe`, `--no-verify`).
///
/// Returns a `Plan`: the program's moves as arrays, the summary dict, and the
/// G-code and APT CL text; for a sequence, a `SequencePlan`. Raises `SwarfError`
/// with the job file (or `job dict`), the line or key and the field for a bad job
/// (`operation[k]` for a sequence's operation), and the planning's errors.
#[pyfunction]
#[pyo3(signature = (job, *, part = None, out = None, allow_unsafe = false, verify = true))]
pub fn plan(
    py: Python<'_>,
    job: &Bound<'_, PyAny>,
    part: Option<&Bound<'_, PyAny>>,
    out: Option<&Bound<'_, PyAny>>,
    allow_unsafe: bool,
    verify: bool,
) -> PyResult<Py<PyAny>> {
    let gate = match (verify, allow_unsafe) {
        (false, _) => Gate::Skip,
        (true, true) => Gate::AllowUnsafe,
        (true, false) => Gate::Verify,
    };
    let out = out
        .map(|o| {
            path_text(o).map(PathBuf::from).ok_or_else(|| {
                pyo3::exceptions::PyTypeError::new_err("out: expected a str or a path")
            })
        })
        .transpose()?;
    let part = part.map(Loaded::extract).transpose()?;
    if let Some(mut seq) = sequence_arg(job)? {
        if part.is_some() {
            return Err(swarf_msg(
                "part: a sequence job reads its own part: expected no part= (it is for a \
                 single job)",
            ));
        }
        seq.seq.gate = gate;
        let planned = detached(py, || plan_sequence_values(&seq, out.as_deref()))?;
        return Ok(Py::new(py, planned)?.into_any());
    }
    let job = job_arg(job)?;
    let planned = detached(py, || {
        plan_job_values(&job, part.as_ref(), out.as_deref(), gate)
    })?;
    let plan = Plan {
        summary: planned.summary,
        toolpath: planned.toolpath,
        gcode: planned.gcode,
        cl: planned.cl,
    };
    Ok(Py::new(py, plan)?.into_any())
}

/// A planned tool path: the program's moves (links included) as arrays, the passes,
/// the summary (`swarf plan`'s JSON summary as a dict) and the program text.
#[pyclass(module = "swarf", frozen)]
pub struct Plan {
    summary: serde_json::Value,
    toolpath: Toolpath,
    gcode: Option<String>,
    cl: Option<String>,
}

/// A rapid move (G0), in `Plan.kinds`.
pub const MOVE_RAPID: i8 = 0;
/// A feed move (cutting or plunging).
pub const MOVE_FEED: i8 = 1;

#[pymethods]
impl Plan {
    /// The program's moves in order, from the clearance plane back to it: an `(N, 6)`
    /// float64 array of poses `x, y, z, i, j, k` (tool tip in mm, unit tool axis).
    #[getter]
    fn poses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let moves = self.toolpath.moves();
        let flat: Vec<f64> = moves
            .iter()
            .flat_map(|m| {
                let (p, a) = (m.to.cl, m.to.axis);
                [p.x, p.y, p.z, a.x, a.y, a.z]
            })
            .collect();
        grid_out(py, flat, moves.len(), 6)
    }

    /// The kind of each move, `(N,)` int8: `swarf.MOVE_RAPID` (0, G0) or
    /// `swarf.MOVE_FEED` (1, G1).
    #[getter]
    fn kinds<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<i8>> {
        let k = self
            .toolpath
            .moves()
            .iter()
            .map(|m| match m.kind {
                MoveKind::Rapid => MOVE_RAPID,
                MoveKind::Feed => MOVE_FEED,
            })
            .collect();
        vec_out(py, k)
    }

    /// The feed rate of each move, `(N,)`, mm/min (0 for rapids).
    #[getter]
    fn feeds<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        vec_out(py, self.toolpath.moves().iter().map(|m| m.feed).collect())
    }

    /// The pass each move cuts in, `(N,)` int64; -1 for links (rapids, plunges).
    #[getter]
    fn pass_index<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<i64>> {
        let p = self
            .toolpath
            .moves()
            .iter()
            .map(|m| m.pass.map_or(-1, |p| p as i64))
            .collect();
        vec_out(py, p)
    }

    /// The cutting passes: a list of `(K, 6)` arrays of poses `x, y, z, i, j, k`.
    #[getter]
    fn passes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        passes_list(py, &self.toolpath, 6)
    }

    /// `swarf plan`'s JSON summary as a dict (passes, poses, lengths in mm, time in
    /// s, the strategy's report).
    #[getter]
    fn summary(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        json_to_py(py, &self.summary)
    }

    /// The G-code the job writes (its `output` settings: dialect, units, machine),
    /// or None for a five-axis job without a machine.
    #[getter]
    fn gcode(&self) -> Option<String> {
        self.gcode.clone()
    }

    /// The APT CL the job writes.
    #[getter]
    fn cl(&self) -> Option<String> {
        self.cl.clone()
    }

    /// Writes the G-code to `path` (atomically).
    fn write_gcode(&self, path: &Bound<'_, PyAny>) -> PyResult<()> {
        write_text(path, self.gcode.as_deref(), "G-code")
    }

    /// Writes the APT CL to `path` (atomically).
    fn write_cl(&self, path: &Bound<'_, PyAny>) -> PyResult<()> {
        write_text(path, self.cl.as_deref(), "APT CL")
    }

    fn __repr__(&self) -> String {
        format!(
            "Plan({} passes, {} poses)",
            self.toolpath.passes.len(),
            self.toolpath.pose_count()
        )
    }
}

/// Writes `text` to the file `path`.
pub(crate) fn write_text(path: &Bound<'_, PyAny>, text: Option<&str>, what: &str) -> PyResult<()> {
    let p = path_text(path)
        .ok_or_else(|| pyo3::exceptions::PyTypeError::new_err("path: expected a str or a path"))?;
    let Some(text) = text else {
        return Err(swarf_msg(format!(
            "{p}: this plan has no {what} (a five-axis job needs output.machine)"
        )));
    };
    swarf_io::write_atomic(Path::new(&p), text.as_bytes()).map_err(swarf_err)
}

/// The passes of `toolpath` as a list of `(K, cols)` arrays: `x, y, z` and, with 6
/// columns, the axis `i, j, k`.
fn passes_list<'py>(
    py: Python<'py>,
    toolpath: &Toolpath,
    cols: usize,
) -> PyResult<Bound<'py, PyList>> {
    let arrays = toolpath.passes.iter().map(|pass| {
        let flat: Vec<f64> = pass
            .points
            .iter()
            .flat_map(|p| {
                let (c, a) = (p.pose.cl, p.pose.axis);
                [c.x, c.y, c.z, a.x, a.y, a.z].into_iter().take(cols)
            })
            .collect();
        grid_out(py, flat, pass.points.len(), cols)
    });
    PyList::new(py, arrays)
}

/// Plans one 3-axis strategy of kind `kind` with the job file's `[strategy]` keys
/// `params` on `part` with `tool`, as a job with that strategy plans it (on its
/// default stock: cut to the part's lowest point and the tool's reach of its box);
/// returns the passes as `(K, 3)` arrays of tool tip positions.
fn strategy_passes<'py>(
    py: Python<'py>,
    kind: &str,
    part: &Bound<'py, PyAny>,
    tool: &Bound<'py, PyAny>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    let cutter = cutter_arg("tool", tool)?;
    let model = ModelArg::extract("part", part)?;
    let strategy = PyDict::new(py);
    strategy.set_item("kind", kind)?;
    if let Some(p) = params {
        strategy.update(p.as_mapping())?;
    }
    let job = PyDict::new(py);
    job.set_item("part", "<python>")?;
    job.set_item("tool", cutter.to_string())?;
    job.set_item("strategy", strategy)?;
    let job = job_from_dict(&job, PathBuf::from("."), &format!("{kind}()"))?;
    let plan = detached(py, || {
        let model = model.load()?;
        let fail = |e: &(dyn std::error::Error + 'static)| {
            swarf_msg(format!("{kind}(): {}", crate::errors::chain(e)))
        };
        // On the job's default stock, as `swarf plan` puts it: its floor and reach.
        let job = job.job.on_stock(&model, &job.dir).map_err(|e| fail(&e))?;
        let input = match &*model {
            Model::Patches(p) => PlanInput::Part(p),
            Model::Mesh { mesh, .. } => PlanInput::Mesh(mesh),
        };
        swarf_app::plan(&job, input).map_err(|e| fail(&e))
    })?;
    passes_list(py, &plan.toolpath, 3)
}

/// Waterline (Z-level) passes of `tool` around `part` (a `Part`, `Mesh` or a part
/// name): closed loops at constant heights, as a job with `kind = "waterline"`
/// plans them. Keyword arguments are the job file's `[strategy]` keys: `scallop`
/// (mm), `steep_angle`, `flat_angle` (degrees), `level_step`, `sampling`,
/// `tolerance` (mm), `adaptive`, `direction` (`"climb"` / `"conventional"`).
/// Returns a list of `(K, 3)` float64 arrays of tool tip positions, mm.
#[pyfunction]
#[pyo3(signature = (part, tool, **params))]
pub fn waterline<'py>(
    py: Python<'py>,
    part: &Bound<'py, PyAny>,
    tool: &Bound<'py, PyAny>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    strategy_passes(py, "waterline", part, tool, params)
}

/// Drop-cutter raster passes of `tool` over `part` (a `Part`, `Mesh` or a part
/// name), as a job with `kind = "raster"` plans them. Keyword arguments are the job
/// file's `[strategy]` keys: `scallop` or `stepover` (mm), `angle` (degrees from
/// +X), `tolerance` (mm), `zigzag`, `boundary` (`[xmin, ymin, xmax, ymax]`, mm),
/// `max_slope`, `max_ramp` (degrees), `start`. Returns a list of `(K, 3)` float64
/// arrays of tool tip positions, mm.
#[pyfunction]
#[pyo3(signature = (part, tool, **params))]
pub fn raster<'py>(
    py: Python<'py>,
    part: &Bound<'py, PyAny>,
    tool: &Bound<'py, PyAny>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    strategy_passes(py, "raster", part, tool, params)
}
