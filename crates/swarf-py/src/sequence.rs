//! Sequence jobs from Python: `swarf plan` of a job with `[[operation]]` tables
//! ([`swarf_app::sequence`]: operations in order on one in-process stock, from stock
//! to part, a tool change each) as a [`SequencePlan`]: the report as a dict, the
//! whole program's G-code, the report's lines and the rest cells as an array.
//!
//! `swarf.plan` takes a sequence as a path, TOML text or a dict with an `operation`
//! list (read into the typed sequence by [`Sequence::from_value`], as a file is; errors name
//! the dict's keys). A `Job` holds a single job, never a sequence.

use crate::arrays::rows_out;
use crate::errors::{chain, swarf_err, swarf_msg};
use crate::job::{Job, to_toml};
use crate::model::path_text;
use crate::plan::{json_to_py, output_dir, write_text};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use swarf_app::Outputs;
use swarf_app::sequence::{Sequence, SequenceReport, plan_sequence};

/// A parsed sequence job, with the folder its relative paths start from.
pub struct SequenceJob {
    pub(crate) seq: Sequence,
    dir: PathBuf,
    /// Where it came from, for messages: the file, `<toml>` or `job dict`.
    source: String,
}

/// A sequence job argument: a dict with an `operation` key, TOML text or a path
/// whose text has `[[operation]]` tables; `None` for anything else (a single job, a
/// `Job`, a file that cannot be read: [`crate::job::job_arg`] reports those).
///
/// # Errors
/// `SwarfError` naming the file (or `job dict`), the line or key, and
/// `operation[k]` and its field, for a bad sequence.
pub fn sequence_arg(obj: &Bound<'_, PyAny>) -> PyResult<Option<SequenceJob>> {
    let here = PathBuf::from(".");
    if obj.cast::<Job>().is_ok() {
        return Ok(None);
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        if !d.contains("operation")? {
            return Ok(None);
        }
        let source = "job dict";
        let value = to_toml("", d.as_any())?;
        let seq = Sequence::from_value(value, source, &here).map_err(swarf_err)?;
        return Ok(Some(SequenceJob {
            seq,
            dir: here,
            source: source.into(),
        }));
    }
    if let Ok(text) = obj.extract::<String>()
        && text.contains('\n')
    {
        return parsed(&text, "<toml>", here);
    }
    let Some(path) = path_text(obj) else {
        return Ok(None);
    };
    let p = Path::new(&path);
    match swarf_io::read_input_text(p) {
        Ok(text) => parsed(&text, &path, p.parent().unwrap_or(Path::new(".")).into()),
        Err(_) => Ok(None),
    }
}

/// `text` parsed as a sequence named `source`, if it is one.
fn parsed(text: &str, source: &str, dir: PathBuf) -> PyResult<Option<SequenceJob>> {
    if !Sequence::is_sequence(text) {
        return Ok(None);
    }
    let seq = Sequence::parse(text, source, &dir).map_err(swarf_err)?;
    Ok(Some(SequenceJob {
        seq,
        dir,
        source: source.into(),
    }))
}

/// Plans `job` (without the GIL) as `swarf plan` does: with `out`, writing the
/// sequence's outputs there; without, writing nothing.
///
/// # Errors
/// `SwarfError` naming the source and the operation that failed.
pub fn plan_sequence_values(job: &SequenceJob, out: Option<&Path>) -> PyResult<SequencePlan> {
    let (dir, _scratch) = output_dir(out)?;
    let mut outputs = Outputs::new(&dir);
    let report = plan_sequence(&job.seq, &job.dir, &mut outputs).map_err(|e| {
        swarf_msg(format!(
            "{}: planning the sequence: {}",
            job.source,
            chain(&e)
        ))
    })?;
    if out.is_some() {
        outputs.commit().map_err(swarf_err)?;
    }
    let json = serde_json::to_value(&report).map_err(swarf_err)?;
    Ok(SequencePlan { report, json })
}

/// A planned sequence job: the operations in order on one stock, their report (as
/// `swarf plan` writes it in `output.summary`), the whole program and the rest.
#[pyclass(module = "swarf", frozen)]
pub struct SequencePlan {
    report: SequenceReport,
    json: serde_json::Value,
}

#[pymethods]
impl SequencePlan {
    /// The sequence's report as a dict: `name`, `grid` (cells across, along, cell
    /// size in mm), `operations`, `time_s`.
    #[getter]
    fn report(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        json_to_py(py, &self.json)
    }

    /// Each operation's report, in order: `name`, `number` (T word), `tool`,
    /// `strategy`, `motions`, `cutting_length_mm`, `time_s`, `engagement` (roughing:
    /// `limit_deg`, `max_deg`, ...), `gouge_cells`, `worst_gouge_mm`, `rest_cells`,
    /// `rest_limit_mm`, `max_rest_mm`, `holder`.
    #[getter]
    fn operations(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        json_to_py(py, &self.json["operations"])
    }

    /// The whole program's G-code, a tool change per operation.
    #[getter]
    fn program(&self) -> String {
        self.report.program.clone()
    }

    /// Each operation's own G-code program, in order.
    #[getter]
    fn programs(&self) -> Vec<String> {
        self.report.programs.clone()
    }

    /// The cells left more than the last operation's limit above the design: an
    /// `(N, 3)` float64 array of cell centre `x, y` and the material above the
    /// design, mm.
    #[getter]
    fn rest<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_out(py, &self.report.rest)
    }

    /// The lines `swarf plan` prints: one per operation, then the whole program's.
    fn lines(&self) -> Vec<String> {
        self.report.lines()
    }

    /// Writes the whole program to `path` (atomically).
    fn write_gcode(&self, path: &Bound<'_, PyAny>) -> PyResult<()> {
        write_text(path, Some(&self.report.program), "G-code")
    }

    fn __repr__(&self) -> String {
        format!(
            "SequencePlan({} operations, {:.0} s)",
            self.report.operations.len(),
            self.report.time_s
        )
    }
}
