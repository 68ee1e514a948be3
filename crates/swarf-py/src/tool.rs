//! Tools: a cutter from a spec string (`"ball:d=8"`, the grammar of `--tool` and job
//! files, [`swarf_tool::spec`]) or keyword arguments (the table form of job files,
//! `shape="bull", d=10, r=2`).

use crate::errors::swarf_msg;
use crate::job::to_toml;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use swarf_geom::domain::excerpt;
use swarf_tool::Cutter;

/// A cutter: `Tool("ball:d=8")` or `Tool(shape="bull", d=10, r=2)`.
///
/// Spec keys (lengths mm, angles degrees): `flat:d`, `ball:d`, `bull:d,r` (corner
/// radius), `cone:d,angle` (included angle), `taperball:d,angle,tip` (taper per side,
/// tip radius), `apt:d,r,e,f,alpha,beta,h`; each takes `length=` (flute length).
/// Raises `SwarfError` with the command line's message for a bad spec.
#[pyclass(module = "swarf", frozen, eq)]
#[derive(PartialEq)]
pub struct Tool {
    /// The cutter.
    pub cutter: Cutter,
}

#[pymethods]
impl Tool {
    #[new]
    #[pyo3(signature = (spec = None, /, **kwargs))]
    fn new(spec: Option<&Bound<'_, PyAny>>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Tool> {
        let kwargs = kwargs.filter(|k| !k.is_empty());
        match (spec, kwargs) {
            (Some(s), None) => Ok(Tool {
                cutter: cutter_arg("spec", s)?,
            }),
            (None, Some(k)) => Ok(Tool {
                cutter: cutter_from_table(k)?,
            }),
            (Some(_), Some(_)) => Err(swarf_msg(
                "Tool: give a spec string or keyword arguments, not both",
            )),
            (None, None) => Err(swarf_msg(
                "Tool: expected a spec string (\"ball:d=8\") or keyword arguments (shape=\"ball\", d=8)",
            )),
        }
    }

    /// The canonical spec string (`"bull:d=10,r=2"`).
    #[getter]
    fn spec(&self) -> String {
        self.cutter.to_string()
    }

    /// Radius of the cutting part (d/2), mm.
    #[getter]
    fn radius(&self) -> f64 {
        self.cutter.radius()
    }

    fn __str__(&self) -> String {
        self.cutter.to_string()
    }

    fn __repr__(&self) -> String {
        format!("Tool('{}')", self.cutter)
    }
}

/// A tool argument: a [`Tool`] or a spec string.
///
/// # Errors
/// `SwarfError` naming `arg` and the spec for a spec that does not parse;
/// `TypeError` for another type.
pub fn cutter_arg(arg: &str, obj: &Bound<'_, PyAny>) -> PyResult<Cutter> {
    if let Ok(t) = obj.cast::<Tool>() {
        return Ok(t.get().cutter);
    }
    let Ok(spec) = obj.extract::<String>() else {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{arg}: expected a Tool or a spec string such as \"ball:d=8\", found {}",
            obj.get_type().name()?
        )));
    };
    spec.parse()
        .map_err(|e| swarf_msg(format!("{arg} {:?}: {e}", excerpt(&spec, 60))))
}

/// A cutter from keyword arguments, as a job file's table `{ shape = .., d = .. }`.
///
/// # Errors
/// `SwarfError` naming the call as written (`Tool(shape='bull', d=10): bull tool:
/// missing ...`).
fn cutter_from_table(kwargs: &Bound<'_, PyDict>) -> PyResult<Cutter> {
    let table = to_toml("tool", kwargs.as_any())?;
    table.try_into::<Cutter>().map_err(|e| {
        let call = kwargs
            .iter()
            .map(|(k, v)| Ok(format!("{k}={}", v.repr()?)))
            .collect::<PyResult<Vec<String>>>();
        match call {
            Ok(args) => swarf_msg(format!(
                "Tool({}): {}",
                excerpt(&args.join(", "), 80),
                e.message()
            )),
            Err(err) => err,
        }
    })
}
