//! Verifying programs from Python: `swarf verify` as values
//! ([`swarf_app::verify::verify_in_memory`], or [`swarf_app::verify::verify_request`]
//! when an output folder is given): the report dict of `report.json` and the
//! deviation, design and machined heights as 2D arrays over the dexel grid.

use crate::arrays::grid_out;
use crate::errors::{detached, swarf_err, swarf_msg};
use crate::model::path_text;
use crate::plan::json_to_py;
use crate::tool::cutter_arg;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyList;
use std::path::PathBuf;
use swarf_app::verify::{
    GcodeSetup, SimSettings, Verified, VerifyRequest, verify_in_memory, verify_request,
};
use swarf_sim::Quiet;
use swarf_sim::report::json_report;

/// One or several paths (a str, a path, or a list of them).
fn paths_arg(arg: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<PathBuf>> {
    if let Some(p) = path_text(obj) {
        return Ok(vec![PathBuf::from(p)]);
    }
    let type_err = || {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{arg}: expected a path (str) or a list of paths"
        ))
    };
    let mut out = Vec::new();
    for item in obj.try_iter().map_err(|_| type_err())? {
        out.push(PathBuf::from(path_text(&item?).ok_or_else(type_err)?));
    }
    Ok(out)
}

/// Tool specs from `None`, a `Tool` or spec, or a list of them.
fn tools_arg(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    let Some(obj) = obj else {
        return Ok(Vec::new());
    };
    if obj.extract::<String>().is_ok() || obj.cast::<crate::tool::Tool>().is_ok() {
        return Ok(vec![cutter_spec(obj)?]);
    }
    obj.try_iter()?.map(|t| cutter_spec(&t?)).collect()
}

/// A tool argument as the spec `swarf verify --tool` takes (a string is passed on
/// as given, so that its errors read as the command line's).
fn cutter_spec(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(s) = obj.extract::<String>() {
        return Ok(s);
    }
    Ok(cutter_arg("tool", obj)?.to_string())
}

/// Simulates NC programs on a dexel stock and measures the result against the
/// design, as `swarf verify --part PART --program PROGRAM --tool TOOL` does.
///
/// `program` is a G-code, APT CL or pose CSV file, or a list of them run in order
/// on one stock (a finish, then its cleanup); `tool` a `Tool` or spec, or a list
/// matched to the programs in order (default: each program's CUTTER record). The
/// keyword arguments are the command's flags: `stock` (`"box"`, `"box:TOP"`,
/// `"offset:ALLOWANCE"` or a mesh file), `cell`, `tol`, `scallop`, `sample_tol` (mm),
/// `rapid` (mm/min), `max_memory` (MiB), `deviation` (`"normal"` or `"vertical"`),
/// `first_order_sweep` (the slow reference sampling of five-axis motions), `floor`
/// (mm: motions whose tool goes lower are reported),
/// `machine` and `tool_length` for five-axis G-code, `dialect`, `tool_table`,
/// `params`, `sub_path`, `machine_units` for reading G-code. With `out`, the reports
/// and pictures are written there as the command writes them.
///
/// Returns a `Verification`. Raises `SwarfError` with the command's message (file,
/// line, flag) for bad input, and when a program stops before its end unless
/// `partial=True` (then the result covers the motions before the stop).
#[pyfunction]
#[pyo3(signature = (part, program, tool = None, *, machine = None, tool_length = None,
    stock = "offset:0.5".to_string(), cell = None, tol = None, scallop = None, rapid = None,
    sample_tol = None, max_memory = 4096, deviation = None, dialect = "linuxcnc".to_string(),
    tool_table = None, params = None, sub_path = Vec::new(), machine_units = "mm".to_string(),
    out = None, partial = false, first_order_sweep = false, floor = None))]
#[allow(clippy::too_many_arguments)]
pub fn verify(
    py: Python<'_>,
    part: &Bound<'_, PyAny>,
    program: &Bound<'_, PyAny>,
    tool: Option<&Bound<'_, PyAny>>,
    machine: Option<String>,
    tool_length: Option<f64>,
    stock: String,
    cell: Option<f64>,
    tol: Option<f64>,
    scallop: Option<f64>,
    rapid: Option<f64>,
    sample_tol: Option<f64>,
    max_memory: u64,
    deviation: Option<String>,
    dialect: String,
    tool_table: Option<PathBuf>,
    params: Option<PathBuf>,
    sub_path: Vec<PathBuf>,
    machine_units: String,
    out: Option<PathBuf>,
    partial: bool,
    first_order_sweep: bool,
    floor: Option<f64>,
) -> PyResult<Verification> {
    let part = path_text(part).ok_or_else(|| {
        pyo3::exceptions::PyTypeError::new_err(
            "part: expected a part file, mesh or built-in name (str)",
        )
    })?;
    let programs = paths_arg("program", program)?;
    let tools = tools_arg(tool)?;
    let sim = SimSettings {
        stock: stock.parse().map_err(swarf_err)?,
        cell,
        tol,
        scallop,
        rapid,
        sample_tol,
        max_memory,
        deviation: deviation
            .map(|d| d.parse())
            .transpose()
            .map_err(swarf_err)?,
        first_order_sweep,
        floor,
    };
    if let Some(l) = tool_length {
        swarf_geom::domain::TOOL_LENGTH
            .check_named("--tool-length", l)
            .map_err(swarf_msg)?;
    }
    let done = detached(py, || {
        let gcode = GcodeSetup::load(
            &dialect,
            &machine_units,
            tool_table.as_deref(),
            params.as_deref(),
            &sub_path,
        )
        .map_err(swarf_err)?;
        let scratch = PathBuf::new();
        let req = VerifyRequest {
            part: &part,
            programs: &programs,
            tools: &tools,
            gcode: &gcode,
            machine: machine.as_deref(),
            tool_length,
            sim: &sim,
            out: out.as_deref().unwrap_or(&scratch),
            partial,
        };
        match &out {
            Some(_) => verify_request(&req, &Quiet),
            None => verify_in_memory(&req, &Quiet),
        }
        .map_err(swarf_err)
    })?;
    if let Some(stop) = &done.context.stopped
        && !partial
    {
        return Err(swarf_msg(format!(
            "the program stopped at {stop}: no report was written (partial=True gives the \
             report of the motions before the stop)"
        )));
    }
    Ok(Verification::new(done))
}

/// What a verification found: the report (`report.json` as a dict) and, over the
/// dexel grid (`ny` rows along y, `nx` columns along x; cell `(j, i)` centred at
/// `x[i], y[j]`), the deviation and the heights.
#[pyclass(module = "swarf", frozen)]
pub struct Verification {
    done: Verified,
    report: serde_json::Value,
}

impl Verification {
    fn new(done: Verified) -> Verification {
        let report = json_report(&done.verification, &done.context);
        Verification { done, report }
    }

    fn grid_array<'py>(&self, py: Python<'py>, values: &[f64]) -> Bound<'py, PyArray2<f64>> {
        let g = &self.done.verification.grid;
        grid_out(py, values.to_vec(), g.ny, g.nx)
    }
}

#[pymethods]
impl Verification {
    /// The report as `report.json` holds it: deviation figures (gouge, excess,
    /// scallop, regions with their program lines), program statistics, grid.
    #[getter]
    fn report(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        json_to_py(py, &self.report)
    }

    /// Deviation per cell, `(ny, nx)`, mm: machined minus design (along the design
    /// normal or vertical, as the report's `deviation_mode` says); negative is a
    /// gouge; NaN where nothing was measured (off the design).
    #[getter]
    fn deviation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.grid_array(py, &self.done.verification.deviation.values)
    }

    /// Design height per cell centre, `(ny, nx)`, mm; NaN off the design.
    #[getter]
    fn design<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.grid_array(py, &self.done.verification.design.heights)
    }

    /// Machined stock height per cell, `(ny, nx)`, mm.
    #[getter]
    fn machined<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.grid_array(py, self.done.verification.stock.heights())
    }

    /// x of the cell centres, `(nx,)`, mm.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        let g = &self.done.verification.grid;
        crate::arrays::vec_out(py, (0..g.nx).map(|i| g.x(i)).collect())
    }

    /// y of the cell centres, `(ny,)`, mm.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        let g = &self.done.verification.grid;
        crate::arrays::vec_out(py, (0..g.ny).map(|j| g.y(j)).collect())
    }

    /// The grid's extent `(xmin, xmax, ymin, ymax)`, mm (matplotlib's `imshow`
    /// `extent` with `origin="lower"`).
    #[getter]
    fn extent(&self) -> (f64, f64, f64, f64) {
        let g = &self.done.verification.grid;
        let [x1, y1] = g.max();
        (g.origin[0], x1, g.origin[1], y1)
    }

    /// Cell side, mm.
    #[getter]
    fn cell(&self) -> f64 {
        self.done.verification.grid.cell
    }

    /// Whether every program ran to its end.
    #[getter]
    fn complete(&self) -> bool {
        self.done.context.stopped.is_none()
    }

    /// Notes for the user (the scallop allowance used, options that did not apply).
    #[getter]
    fn notes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, &self.done.notes)
    }

    fn __repr__(&self) -> String {
        let g = &self.done.verification.grid;
        let s = &self.done.verification.deviation.summary;
        format!(
            "Verification({} x {} cells of {} mm, {} gouge cells, {} excess cells)",
            g.nx, g.ny, g.cell, s.gouge.cells, s.excess.cells
        )
    }
}
