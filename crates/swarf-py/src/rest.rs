//! Rest material from Python: `swarf rest` as values ([`swarf_app::rest::rest_detect`],
//! or [`swarf_app::rest::rest_request`] when an output folder is given): the report
//! dict of `rest.json` and every region's boundary as arrays of polygons.

use crate::arrays::rows_out;
use crate::errors::{detached, swarf_err, swarf_msg};
use crate::model::path_text;
use crate::plan::json_to_py;
use crate::tool::cutter_arg;
use pyo3::prelude::*;
use pyo3::types::PyList;
use std::path::PathBuf;
use swarf_app::rest::{RestRequest, polygon_rings, rest_detect, rest_report, write_rest};
use swarf_rest::RegionParams;
use swarf_rest::RestSource;

/// The rest material a finishing tool or job leaves, as `swarf rest` finds it.
///
/// Give `reference` (the tool that finished: a `Tool` or spec) or `job` (the
/// finishing job file; its tool is the reference), and `part` (a part file, mesh
/// or built-in name; default the job's part). `source` is where the rest comes
/// from: `"reference"` (crease scans with the reference tool), `"contacts"` (a
/// raster parent's double contacts) or `"stock"` (the dexel stock after the parent
/// job's program). `threshold`, `merge`, `overlap`, `smoothness`, `tol` in mm,
/// `min_area` in mm². With `out`, `rest.json`, `rest.csv` and `rest.png` are
/// written there as the command writes them.
///
/// Returns a `Rest`. Raises `SwarfError` with the command's message for bad input.
#[pyfunction]
#[pyo3(signature = (part = None, *, reference = None, job = None, source = "reference".to_string(),
    threshold = RegionParams::default().threshold, merge = RegionParams::default().merge,
    overlap = RegionParams::default().overlap, min_area = RegionParams::default().min_area,
    smoothness = RegionParams::default().smoothness, tol = 0.01, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn rest(
    py: Python<'_>,
    part: Option<&Bound<'_, PyAny>>,
    reference: Option<&Bound<'_, PyAny>>,
    job: Option<&Bound<'_, PyAny>>,
    source: String,
    threshold: f64,
    merge: f64,
    overlap: f64,
    min_area: f64,
    smoothness: f64,
    tol: f64,
    out: Option<PathBuf>,
) -> PyResult<Rest> {
    let source = match source.as_str() {
        "reference" => RestSource::Reference,
        "contacts" => RestSource::Contacts,
        "stock" => RestSource::Stock,
        other => {
            return Err(swarf_msg(format!(
                "--source {other}: expected reference, contacts or stock"
            )));
        }
    };
    let text = |arg: &str, o: Option<&Bound<'_, PyAny>>| -> PyResult<Option<String>> {
        o.map(|o| {
            path_text(o).ok_or_else(|| {
                pyo3::exceptions::PyTypeError::new_err(format!("{arg}: expected a str or a path"))
            })
        })
        .transpose()
    };
    let part = text("part", part)?;
    let job = text("job", job)?.map(PathBuf::from);
    let reference = match reference {
        Some(r) if r.extract::<String>().is_err() => Some(cutter_arg("reference", r)?.to_string()),
        Some(r) => Some(r.extract::<String>()?),
        None => None,
    };
    let found = detached(py, || {
        let scratch = PathBuf::new();
        let req = RestRequest {
            part: part.as_deref(),
            reference: reference.as_deref(),
            job: job.as_deref(),
            source,
            params: RegionParams {
                threshold,
                merge,
                overlap,
                min_area,
                smoothness,
            },
            tol,
            out: out.as_deref().unwrap_or(&scratch),
        };
        let (found, part, mesh) = rest_detect(&req).map_err(swarf_err)?;
        if let Some(dir) = &out {
            write_rest(&found, &part, &mesh, dir).map_err(swarf_err)?;
        }
        let report = rest_report(&found, &part);
        Ok((found, report))
    })?;
    Ok(Rest {
        regions: found
            .0
            .detection
            .regions
            .iter()
            .map(RegionRings::of)
            .collect(),
        report: found.1,
    })
}

/// A region's figures and rings.
#[derive(Clone)]
struct RegionRings {
    area: f64,
    raw_area: f64,
    depth: f64,
    deepest: (f64, f64, f64),
    kinds: Vec<String>,
    boundary: Vec<Vec<[f64; 2]>>,
    raw: Vec<Vec<Vec<[f64; 2]>>>,
}

impl RegionRings {
    fn of(r: &swarf_rest::RestRegion) -> RegionRings {
        RegionRings {
            area: r.area,
            raw_area: r.raw_area,
            depth: r.depth,
            deepest: (r.deepest.x, r.deepest.y, r.deepest.z),
            kinds: r
                .kinds
                .iter()
                .map(|k| {
                    serde_json::to_value(k)
                        .ok()
                        .and_then(|v| v.as_str().map(str::to_string))
                        .unwrap_or_default()
                })
                .collect(),
            boundary: polygon_rings(&r.boundary),
            raw: r.raw.0.iter().map(polygon_rings).collect(),
        }
    }
}

/// Rest regions (`swarf rest`): the report and each region as a `RestRegion`.
#[pyclass(module = "swarf", frozen)]
pub struct Rest {
    regions: Vec<RegionRings>,
    report: serde_json::Value,
}

#[pymethods]
impl Rest {
    /// `rest.json` as a dict: per region its kinds, areas (mm²), depth (mm), deepest
    /// point, samples; the samples and the directory pitch.
    #[getter]
    fn report(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        json_to_py(py, &self.report)
    }

    /// The regions, largest rest first as the report lists them.
    #[getter]
    fn regions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let items: PyResult<Vec<Py<RestRegion>>> = (0..self.regions.len())
            .map(|k| Py::new(py, RestRegion(self.regions[k].clone())))
            .collect();
        PyList::new(py, items?)
    }

    fn __len__(&self) -> usize {
        self.regions.len()
    }

    fn __repr__(&self) -> String {
        format!("Rest({} regions)", self.regions.len())
    }
}

/// One rest region: its boundary as polygons (outer ring first, then holes) of
/// `(K, 2)` float64 arrays of XY points, mm, each ring closed.
#[pyclass(module = "swarf", frozen)]
pub struct RestRegion(RegionRings);

#[pymethods]
impl RestRegion {
    /// Area inside the boundary, mm².
    #[getter]
    fn area(&self) -> f64 {
        self.0.area
    }

    /// Area of what detection found, before the boundary operations, mm².
    #[getter]
    fn raw_area(&self) -> f64 {
        self.0.raw_area
    }

    /// Largest rest thickness, mm.
    #[getter]
    fn depth(&self) -> f64 {
        self.0.depth
    }

    /// Where the rest is thickest, `(x, y, z)`, mm.
    #[getter]
    fn deepest(&self) -> (f64, f64, f64) {
        self.0.deepest
    }

    /// The kinds of rest it holds (`"valley"`, `"ramp"`, `"stock"`).
    #[getter]
    fn kinds(&self) -> Vec<String> {
        self.0.kinds.clone()
    }

    /// The final boundary: a list of rings, outer first then holes, each a `(K, 2)`
    /// array, mm.
    #[getter]
    fn boundary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, self.0.boundary.iter().map(|r| rows_out(py, r)))
    }

    /// What detection found, before smoothing, merging and the overlap: a list of
    /// polygons, each a list of rings as `boundary`.
    #[getter]
    fn raw<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let polygons: PyResult<Vec<Bound<'py, PyList>>> = self
            .0
            .raw
            .iter()
            .map(|p| PyList::new(py, p.iter().map(|r| rows_out(py, r))))
            .collect();
        PyList::new(py, polygons?)
    }

    fn __repr__(&self) -> String {
        format!(
            "RestRegion(area {:.1} mm², depth {:.3} mm)",
            self.0.area, self.0.depth
        )
    }
}
