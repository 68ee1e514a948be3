//! Drop-cutter from Python: heights of a cutter dropped onto a mesh at an `(N, 2)`
//! array of points, on every core with the GIL released ([`swarf_tool::drop`], as
//! `swarf drop` runs it: [`MeshDropper`] and [`drop_points_threads`]).

use crate::arrays::{coordinate_rows, rows_out, vec_out};
use crate::errors::{detached, swarf_msg, value_err};
use crate::model::ModelArg;
use crate::tool::{Tool, cutter_arg};
use pyo3::prelude::*;
use std::sync::Arc;
use std::time::Instant;
use swarf_app::Model;
use swarf_tool::drop::Feature;
use swarf_tool::drop::{DropResult, MeshDropper, drop_points_threads};

/// Names of the feature codes of `DropContacts.feature`, in code order (the
/// `feature` column of `swarf drop --contact`).
pub const FEATURES: [&str; 7] = [
    "vertex0", "vertex1", "vertex2", "edge0", "edge1", "edge2", "facet",
];

/// The code of a feature in [`FEATURES`].
pub(crate) fn feature_code(f: Feature) -> i8 {
    match f {
        Feature::Vertex(k) => k as i8,
        Feature::Edge(k) => 3 + k as i8,
        Feature::Facet => 6,
    }
}

/// A cutter prepared for drops on one mesh: the mesh's drop index is built once
/// and reused by every `drop` call. Thread-safe; drops release the GIL.
#[pyclass(module = "swarf", frozen)]
pub struct Dropper {
    dropper: Arc<MeshDropper>,
    tool: swarf_tool::Cutter,
    triangles: usize,
}

/// The mesh of a drop's `mesh` argument.
fn mesh_model(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Arc<Model>> {
    let arg = ModelArg::extract("mesh", obj)?;
    let model = detached(py, || arg.load())?;
    match &*model {
        Model::Mesh { .. } => Ok(model),
        Model::Patches(p) => Err(swarf_msg(format!(
            "mesh: {} is a parametric part; drop-cutter needs a mesh \
             (part.tessellate(tol) makes one)",
            p.name
        ))),
    }
}

/// Checks a `threads` argument (1 to 1024; None: one per core).
pub(crate) fn threads_arg(threads: Option<usize>) -> PyResult<Option<usize>> {
    if let Some(n) = threads {
        swarf_geom::domain::THREADS
            .check_named("threads", n as f64)
            .map_err(value_err)?;
    }
    Ok(threads)
}

/// `(wall, cpu)` seconds.
type Seconds = (f64, f64);

impl Dropper {
    /// [`Dropper::drop`] on checked points. With `clock` (Python's
    /// `time.process_time`), also the `(wall, cpu)` seconds of the drops alone.
    fn drop_rows(
        &self,
        py: Python<'_>,
        pts: Vec<[f64; 2]>,
        contacts: bool,
        threads: Option<usize>,
        clock: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<(Py<PyAny>, Option<Seconds>)> {
        let threads = threads_arg(threads)?;
        let dropper = self.dropper.clone();
        let cpu = clock.map(|c| c.call0()?.extract::<f64>()).transpose()?;
        let t = Instant::now();
        let results = detached(py, || Ok(drop_points_threads(&dropper, &pts, threads).0))?;
        let wall = t.elapsed().as_secs_f64();
        let inner = match (clock, cpu) {
            (Some(c), Some(cpu)) => Some((wall, c.call0()?.extract::<f64>()? - cpu)),
            _ => None,
        };
        if contacts {
            return Ok((Py::new(py, DropContacts::new(&results))?.into_any(), inner));
        }
        let z: Vec<f64> = results
            .iter()
            .map(|r| r.map_or(f64::NAN, |r| r.z))
            .collect();
        Ok((vec_out(py, z).into_any().unbind(), inner))
    }
}

#[pymethods]
impl Dropper {
    /// Prepares `tool` (a `Tool` or spec) for drops on `mesh` (a `Mesh`, or a mesh
    /// file / built-in mesh name). Triangles with a non-finite corner are skipped;
    /// raises `SwarfError` when none is left.
    #[new]
    fn new(py: Python<'_>, mesh: &Bound<'_, PyAny>, tool: &Bound<'_, PyAny>) -> PyResult<Dropper> {
        let cutter = cutter_arg("tool", tool)?;
        let model = mesh_model(py, mesh)?;
        detached(py, || {
            let Model::Mesh { mesh, name } = &*model else {
                return Err(swarf_msg("mesh: expected a mesh"));
            };
            let dropper = MeshDropper::new(mesh, &cutter);
            if dropper.is_empty() {
                return Err(swarf_msg(format!("{name}: no triangle has finite corners")));
            }
            Ok(Dropper {
                triangles: dropper.len(),
                dropper: Arc::new(dropper),
                tool: cutter,
            })
        })
    }

    /// The tool.
    #[getter]
    fn tool(&self) -> Tool {
        Tool { cutter: self.tool }
    }

    /// Number of triangles the drops use.
    fn __len__(&self) -> usize {
        self.triangles
    }

    /// Tool tip heights (mm) of the cutter dropped at each row `(x, y)` of `points`
    /// (an `(N, 2)` float64 array, mm): an `(N,)` array, NaN where the cutter
    /// touches no triangle (off the mesh). With `contacts=True`, a `DropContacts`
    /// with the touched triangle, feature and CC point as well. Runs on `threads`
    /// workers (default: one per core) with the GIL released; the heights are the
    /// same for any thread count, bit for bit those of `swarf drop`.
    #[pyo3(signature = (points, *, contacts = false, threads = None))]
    fn drop(
        &self,
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        contacts: bool,
        threads: Option<usize>,
    ) -> PyResult<Py<PyAny>> {
        let pts = coordinate_rows::<2>("points", points)?;
        Ok(self.drop_rows(py, pts, contacts, threads, None)?.0)
    }

    /// Benchmark support: `drop(points, threads=threads)`, the same path, and the
    /// `(wall, cpu)` seconds of its drops alone (CPU: the process's, all threads, by
    /// Python's `time.process_time`). Timing this call from Python and taking away
    /// the drops gives the cost of the Python boundary within one call, free of the
    /// run-to-run spread of the drops themselves.
    #[pyo3(signature = (points, *, threads = None))]
    fn _drop_timed(
        &self,
        py: Python<'_>,
        points: &Bound<'_, PyAny>,
        threads: Option<usize>,
    ) -> PyResult<(Py<PyAny>, Seconds)> {
        let pts = coordinate_rows::<2>("points", points)?;
        let clock = py.import("time")?.getattr("process_time")?;
        let (z, inner) = self.drop_rows(py, pts, false, threads, Some(&clock))?;
        Ok((z, inner.unwrap_or_default()))
    }

    fn __repr__(&self) -> String {
        format!("Dropper('{}', {} triangles)", self.tool, self.triangles)
    }
}

/// Drops `tool` onto `mesh` at each row of `points`: `Dropper(mesh, tool).drop(points,
/// contacts=..., threads=...)`. Heights in mm, NaN off the mesh.
#[pyfunction]
#[pyo3(signature = (mesh, tool, points, *, contacts = false, threads = None))]
pub fn drop(
    py: Python<'_>,
    mesh: &Bound<'_, PyAny>,
    tool: &Bound<'_, PyAny>,
    points: &Bound<'_, PyAny>,
    contacts: bool,
    threads: Option<usize>,
) -> PyResult<Py<PyAny>> {
    let pts = coordinate_rows::<2>("points", points)?;
    threads_arg(threads)?;
    Ok(Dropper::new(py, mesh, tool)?
        .drop_rows(py, pts, contacts, threads, None)?
        .0)
}

/// Drop heights with their contacts (`swarf drop --contact`): arrays over the points.
#[pyclass(module = "swarf", frozen)]
pub struct DropContacts {
    z: Vec<f64>,
    tri: Vec<i64>,
    feature: Vec<i8>,
    cc: Vec<[f64; 3]>,
}

impl DropContacts {
    fn new(results: &[Option<DropResult>]) -> DropContacts {
        let nan3 = [f64::NAN; 3];
        DropContacts {
            z: results
                .iter()
                .map(|r| r.map_or(f64::NAN, |r| r.z))
                .collect(),
            tri: results
                .iter()
                .map(|r| r.map_or(-1, |r| i64::from(r.tri)))
                .collect(),
            feature: results
                .iter()
                .map(|r| r.map_or(-1, |r| feature_code(r.feature)))
                .collect(),
            cc: results
                .iter()
                .map(|r| r.map_or(nan3, |r| [r.cc.x, r.cc.y, r.cc.z]))
                .collect(),
        }
    }
}

#[pymethods]
impl DropContacts {
    /// Tool tip heights, `(N,)`, mm; NaN off the mesh.
    #[getter]
    fn z<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        vec_out(py, self.z.clone())
    }

    /// Index of the touched triangle, `(N,)` int64; -1 off the mesh.
    #[getter]
    fn tri<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<i64>> {
        vec_out(py, self.tri.clone())
    }

    /// Feature touched, `(N,)` int8: an index into `swarf.FEATURES` (`vertex0` ..
    /// `facet`); -1 off the mesh.
    #[getter]
    fn feature<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<i8>> {
        vec_out(py, self.feature.clone())
    }

    /// CC points (where the cutter touches), `(N, 3)`, mm; NaN off the mesh.
    #[getter]
    fn cc<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        rows_out(py, &self.cc)
    }

    fn __len__(&self) -> usize {
        self.z.len()
    }

    fn __repr__(&self) -> String {
        let hits = self.z.iter().filter(|z| !z.is_nan()).count();
        format!("DropContacts({} points, {hits} with contact)", self.z.len())
    }
}
