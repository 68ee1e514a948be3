//! Job files from Python: a path, TOML text, or a dict in the job file's schema
//! ([`swarf_app::job`]). A dict (and the keyword arguments of the strategy
//! functions) becomes TOML values, read into the typed job by the same code as a
//! job file ([`swarf_app::Job::from_value`]); its errors name the dict's keys
//! (`strategy.scallop`) instead of lines.

use crate::errors::{swarf_err, swarf_msg};
use crate::model::path_text;
use crate::tool::Tool;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::{Path, PathBuf};

/// Converts a Python value to TOML, naming `path` (the dotted key) in errors.
/// `None` values of a dict are left out (TOML has no null); a [`Tool`] becomes its
/// spec; numpy scalars and arrays become numbers and lists; paths become strings.
///
/// # Errors
/// `SwarfError` naming the key for a value TOML cannot hold.
pub fn to_toml(path: &str, obj: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        let i: i64 = obj
            .extract()
            .map_err(|_| swarf_msg(format!("{path}: integer {obj} is out of range")))?;
        return Ok(toml::Value::Integer(i));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if let Ok(t) = obj.cast::<Tool>() {
        return Ok(toml::Value::String(t.get().cutter.to_string()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let Ok(key) = k.extract::<String>() else {
                return Err(swarf_msg(format!("{path}: key {k}: expected str keys")));
            };
            if v.is_none() {
                continue;
            }
            let sub = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            table.insert(key, to_toml(&sub, &v)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items: PyResult<Vec<toml::Value>> = obj
            .try_iter()?
            .enumerate()
            .map(|(i, item)| to_toml(&format!("{path}[{i}]"), &item?))
            .collect();
        return Ok(toml::Value::Array(items?));
    }
    if obj.hasattr("tolist")? {
        // numpy scalars and arrays
        return to_toml(path, &obj.call_method0("tolist")?);
    }
    if let Some(s) = path_text(obj) {
        return Ok(toml::Value::String(s));
    }
    Err(swarf_msg(format!(
        "{path}: a {} cannot be written in a job (expected a number, str, bool, list or dict)",
        obj.get_type().name()?
    )))
}

/// A job (the job file schema: part, tool, strategy, feeds, linking, output), with
/// the folder its relative paths start from.
///
/// `Job.load("jobs/wave-raster.toml")`, `Job.from_toml(text)` or
/// `Job.from_dict({...})`; `swarf.plan` takes any of these directly. Raises
/// `SwarfError` with the file (or `job dict`), line or key, and field for a bad job.
#[pyclass(module = "swarf", frozen)]
pub struct Job {
    /// The parsed job.
    pub job: swarf_app::Job,
    /// The folder relative paths in the job start from.
    pub dir: PathBuf,
    /// The job's TOML text.
    pub text: String,
    /// Where it came from, for messages: the file, `<toml>` or `job dict`.
    pub source: String,
}

#[pymethods]
impl Job {
    /// Reads a job file; relative paths in it start from its folder.
    #[staticmethod]
    fn load(path: &Bound<'_, PyAny>) -> PyResult<Job> {
        let path = path_text(path).ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err("path: expected a str or a path")
        })?;
        let p = Path::new(&path);
        let text = swarf_io::read_input_text(p).map_err(|e| {
            swarf_msg(format!(
                "{path}: cannot read the job file: {}",
                crate::errors::chain(&e)
            ))
        })?;
        let job = parse_single(&text, &path)?;
        Ok(Job {
            job,
            dir: p.parent().unwrap_or(Path::new(".")).to_path_buf(),
            text,
            source: path,
        })
    }

    /// A job from TOML text; relative paths start from `base_dir` (default: the
    /// current folder).
    #[staticmethod]
    #[pyo3(signature = (text, base_dir = None))]
    fn from_toml(text: String, base_dir: Option<&Bound<'_, PyAny>>) -> PyResult<Job> {
        let source = "<toml>".to_string();
        let job = parse_single(&text, &source)?;
        Ok(Job {
            job,
            dir: base_dir_arg(base_dir)?,
            text,
            source,
        })
    }

    /// A job from a dict in the job file's schema (`{"part": "builtin:wave", "tool":
    /// "ball:d=8", "strategy": {"kind": "raster", "scallop": 0.1}}`); relative paths
    /// start from `base_dir` (default: the current folder). Errors name the key.
    #[staticmethod]
    #[pyo3(signature = (job, base_dir = None))]
    fn from_dict(job: &Bound<'_, PyDict>, base_dir: Option<&Bound<'_, PyAny>>) -> PyResult<Job> {
        job_from_dict(job, base_dir_arg(base_dir)?, "job dict")
    }

    /// The job's name (`name`), or None.
    #[getter]
    fn name(&self) -> Option<String> {
        self.job.name.clone()
    }

    /// The part as the job names it.
    #[getter]
    fn part(&self) -> String {
        self.job.part.clone()
    }

    /// The job's part read as `swarf.plan(job)` reads it (its `[import]` options and
    /// `faces`): a `Part` or a `Mesh`, to pass as `plan(job, part=...)` to jobs on
    /// the same part, which then do not read it again. Raises `SwarfError` naming
    /// the job and the part for a part that cannot be read.
    fn load_part(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let arg = swarf_app::plan_job::part_arg(&self.job, &self.dir);
        let opts = self.job.load_options();
        let model = crate::errors::detached(py, || {
            swarf_app::load_model_with(&arg, &opts).map_err(|e| {
                swarf_msg(format!(
                    "{}: reading the job's part: {}",
                    self.source,
                    crate::errors::chain(&e)
                ))
            })
        })?;
        crate::model::model_object(py, model, crate::loaded::ReadWith::of(&arg, &opts))
    }

    /// The tool.
    #[getter]
    fn tool(&self) -> Tool {
        Tool {
            cutter: self.job.tool,
        }
    }

    /// The strategy's kind (`"raster"`, `"iso-scallop"`, ...).
    #[getter]
    fn kind(&self) -> String {
        self.job.strategy.kind().to_string()
    }

    /// The folder relative paths in the job start from.
    #[getter]
    fn base_dir(&self) -> String {
        self.dir.display().to_string()
    }

    /// The job as TOML text (a dict's job as TOML, for reading).
    #[getter]
    fn toml(&self) -> String {
        self.text.clone()
    }

    fn __repr__(&self) -> String {
        format!(
            "Job({:?}, {:?})",
            self.source,
            self.job.name.as_deref().unwrap_or("")
        )
    }
}

/// `text` parsed as a single job named `source`.
fn parse_single(text: &str, source: &str) -> PyResult<swarf_app::Job> {
    single_job(text, source)?;
    swarf_app::Job::parse(text, source).map_err(swarf_err)
}

/// Checks that `text` is not a sequence job, which a [`Job`] cannot hold.
///
/// # Errors
/// `SwarfError` saying where a sequence goes instead.
fn single_job(text: &str, source: &str) -> PyResult<()> {
    if swarf_app::sequence::Sequence::is_sequence(text) {
        return Err(swarf_msg(format!(
            "{source}: a sequence job ([[operation]] tables): a Job holds a single job; \
             swarf.plan takes a sequence as a path, TOML text or a dict"
        )));
    }
    Ok(())
}

/// `base_dir` as a folder (default `.`).
fn base_dir_arg(base_dir: Option<&Bound<'_, PyAny>>) -> PyResult<PathBuf> {
    match base_dir {
        None => Ok(PathBuf::from(".")),
        Some(b) => path_text(b).map(PathBuf::from).ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err("base_dir: expected a str or a path")
        }),
    }
}

/// A job from a dict (see [`to_toml`]), named `source` in errors.
///
/// # Errors
/// `SwarfError` naming the key for a value TOML cannot hold or a bad job.
pub fn job_from_dict(job: &Bound<'_, PyDict>, dir: PathBuf, source: &str) -> PyResult<Job> {
    let value = to_toml("", job.as_any())?;
    if value.get("operation").is_some() {
        return Err(swarf_msg(format!(
            "{source}: a sequence job ([[operation]] tables): a Job holds a single job; \
             swarf.plan takes a sequence as a path, TOML text or a dict"
        )));
    }
    let text = toml::to_string(&value).map_err(|e| swarf_msg(format!("{source}: {e}")))?;
    let parsed = swarf_app::Job::from_value(value, source, &dir).map_err(swarf_err)?;
    Ok(Job {
        job: parsed,
        dir,
        text,
        source: source.to_string(),
    })
}

/// A job argument: a [`Job`], a dict, TOML text (a str with a line break) or a path.
///
/// # Errors
/// As [`Job`]'s constructors; `TypeError` for another type.
pub fn job_arg(obj: &Bound<'_, PyAny>) -> PyResult<Job> {
    if let Ok(j) = obj.cast::<Job>() {
        let j = j.get();
        return Ok(Job {
            job: j.job.clone(),
            dir: j.dir.clone(),
            text: j.text.clone(),
            source: j.source.clone(),
        });
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return job_from_dict(d, PathBuf::from("."), "job dict");
    }
    if let Ok(s) = obj.extract::<String>()
        && s.contains('\n')
    {
        return Job::from_toml(s, None);
    }
    if path_text(obj).is_some() {
        return Job::load(obj);
    }
    Err(pyo3::exceptions::PyTypeError::new_err(format!(
        "job: expected a Job, a dict, TOML text or a path, found {}",
        obj.get_type().name()?
    )))
}
