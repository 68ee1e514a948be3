//! Parts and meshes: [`Part`] (parametric patches) and [`Mesh`] (triangles), loaded as
//! the command line loads them ([`swarf_app::load_model`]) or built from numpy
//! arrays; patch evaluation on arrays of `(u, v)` (`swarf eval`, vectorised) and
//! tessellation (`swarf tessellate`).

use crate::arrays::{coordinate_rows, float_rows, grid_out, index_rows, rows_out, vec_out};
use crate::errors::{detached, swarf_err, swarf_msg, value_err};
use crate::loaded::ReadWith;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use swarf_app::Model;
use swarf_geom::{Point3, TriMesh};

/// A part or mesh argument: a [`Part`], a [`Mesh`], or a name as the command line
/// takes it (a part file, an STL / OBJ mesh, `builtin:NAME`).
pub enum ModelArg {
    /// An object already loaded.
    Loaded(Arc<Model>),
    /// A name, loaded when used.
    Named(String),
}

impl ModelArg {
    /// Reads `obj` as a model argument.
    ///
    /// # Errors
    /// `TypeError` for anything but a `Part`, a `Mesh`, a `str` or a path.
    pub fn extract(arg: &str, obj: &Bound<'_, PyAny>) -> PyResult<ModelArg> {
        if let Ok(p) = obj.cast::<Part>() {
            return Ok(ModelArg::Loaded(p.get().model.clone()));
        }
        if let Ok(m) = obj.cast::<Mesh>() {
            return Ok(ModelArg::Loaded(m.get().model.clone()));
        }
        match path_text(obj) {
            Some(s) => Ok(ModelArg::Named(s)),
            None => Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "{arg}: expected a Part, a Mesh, or a part name or path (str), found {}",
                obj.get_type().name()?
            ))),
        }
    }

    /// The model, loading a name (call without the GIL).
    ///
    /// # Errors
    /// As [`swarf_app::load_model`].
    pub fn load(&self) -> PyResult<Arc<Model>> {
        match self {
            ModelArg::Loaded(m) => Ok(m.clone()),
            ModelArg::Named(s) => Ok(Arc::new(swarf_app::load_model(s).map_err(swarf_err)?)),
        }
    }
}

/// `obj` as text if it is a `str` or an `os.PathLike`.
pub fn path_text(obj: &Bound<'_, PyAny>) -> Option<String> {
    if let Ok(s) = obj.extract::<String>() {
        return Some(s);
    }
    let os = obj.py().import("os").ok()?;
    let p = os.call_method1("fspath", (obj,)).ok()?;
    p.extract::<String>().ok()
}

/// The Python object for a loaded model: a `Part` or a `Mesh`; `read` says how it
/// was read.
pub fn model_object(py: Python<'_>, model: Model, read: ReadWith) -> PyResult<Py<PyAny>> {
    let model = Arc::new(model);
    Ok(match *model {
        Model::Patches(_) => Py::new(py, Part { model, read })?.into_any(),
        Model::Mesh { .. } => Py::new(py, Mesh { model })?.into_any(),
    })
}

/// Loads a part or mesh as the command line does: a part file (`.toml`), a mesh
/// (`.stl`, `.obj`), `builtin:NAME` or a bare built-in name (`"wave"`).
///
/// Returns a `Part` for patches, a `Mesh` for triangles. Lengths in mm (inch part
/// files are converted).
///
/// Raises `SwarfError` naming the file, line and field for a file that cannot be
/// read or parsed, or an unknown built-in name.
#[pyfunction]
pub fn load(py: Python<'_>, source: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    let name = path_text(source).ok_or_else(|| {
        pyo3::exceptions::PyTypeError::new_err("source: expected a str or a path")
    })?;
    let model = detached(py, || swarf_app::load_model(&name).map_err(swarf_err))?;
    model_object(
        py,
        model,
        ReadWith::of(&name, &swarf_app::LoadOptions::default()),
    )
}

/// Parametric patches (Bezier, B-spline, NURBS) of a part, mm.
///
/// `Part.load("builtin:wave")`, or `swarf.load(...)` for a part file. For 3-axis work
/// the part's material is everything below the upper envelope of its patches.
#[pyclass(module = "swarf", frozen)]
pub struct Part {
    /// Always [`Model::Patches`].
    pub model: Arc<Model>,
    /// How it was read (a job's part must be read as the job reads it).
    pub read: ReadWith,
}

impl Part {
    fn part(&self) -> &swarf_geom::Part {
        match &*self.model {
            Model::Patches(p) => p,
            Model::Mesh { .. } => unreachable!("a Part holds patches"),
        }
    }

    fn patch(&self, index: usize) -> PyResult<&swarf_geom::Patch> {
        swarf_app::model::patch_at(self.part(), index).map_err(|m| value_err(format!("patch: {m}")))
    }
}

#[pymethods]
impl Part {
    /// Loads a parametric part: a part file (`.toml`) or a built-in part name
    /// (`"builtin:wave"`, `"die"`). Raises `SwarfError` for a mesh or a bad file.
    #[staticmethod]
    fn load(py: Python<'_>, source: &Bound<'_, PyAny>) -> PyResult<Part> {
        let name = path_text(source).ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err("source: expected a str or a path")
        })?;
        let part = detached(py, || swarf_app::load_part(&name).map_err(swarf_err))?;
        Ok(Part {
            model: Arc::new(Model::Patches(part)),
            read: ReadWith::of(&name, &swarf_app::LoadOptions::default()),
        })
    }

    /// The part's name.
    #[getter]
    fn name(&self) -> String {
        self.part().name.clone()
    }

    /// Number of patches.
    fn __len__(&self) -> usize {
        self.part().patches.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Part({:?}, {} patches)",
            self.part().name,
            self.part().patches.len()
        )
    }

    /// The parameter domain of patch `patch`: `((u0, u1), (v0, v1))`.
    fn domain(&self, patch: usize) -> PyResult<((f64, f64), (f64, f64))> {
        let [[u0, u1], [v0, v1]] = self.patch(patch)?.domain();
        Ok(((u0, u1), (v0, v1)))
    }

    /// Evaluates patch `patch` at each row `(u, v)` of `uv` (an `(N, 2)` float64
    /// array), as `swarf eval` does at one point.
    ///
    /// Returns a dict of arrays: `point`, `du`, `dv`, `normal` (`(N, 3)`, mm and
    /// mm per parameter unit; `normal` is the unit `du x dv`), `k1`, `k2` (`(N,)`,
    /// principal curvatures in 1/mm, positive where the surface bends toward the
    /// normal) and `dir1`, `dir2` (`(N, 3)` unit principal directions). Where the
    /// patch is degenerate (`du x dv = 0`) the normal, curvatures and directions are
    /// NaN.
    ///
    /// Raises `ValueError` for a bad array, a patch index out of range or a row
    /// outside the patch's domain (naming the row).
    fn eval<'py>(
        &self,
        py: Python<'py>,
        patch: usize,
        uv: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let p = self.patch(patch)?;
        let uv = float_rows::<2>("uv", uv)?;
        let [[u0, u1], [v0, v1]] = p.domain();
        if let Some(i) = uv
            .iter()
            .position(|&[u, v]| !(u0..=u1).contains(&u) || !(v0..=v1).contains(&v))
        {
            let [u, v] = uv[i];
            return Err(value_err(format!(
                "uv[{i}]: ({u}, {v}) is outside the patch's domain u in [{u0}, {u1}], v in [{v0}, {v1}]"
            )));
        }
        let cols = detached(py, || Ok(eval_rows(p, &uv)))?;
        let out = PyDict::new(py);
        for (name, rows) in [
            ("point", &cols.point),
            ("du", &cols.du),
            ("dv", &cols.dv),
            ("normal", &cols.normal),
            ("dir1", &cols.dir1),
            ("dir2", &cols.dir2),
        ] {
            out.set_item(name, rows_out(py, rows))?;
        }
        out.set_item("k1", vec_out(py, cols.k1))?;
        out.set_item("k2", vec_out(py, cols.k2))?;
        Ok(out)
    }

    /// Tessellates the part within the chordal tolerance `tol` (mm), as
    /// `swarf tessellate`: every point of the mesh is within `tol` of the surface.
    #[pyo3(signature = (tol = 0.01))]
    fn tessellate(&self, py: Python<'_>, tol: f64) -> PyResult<Mesh> {
        swarf_geom::domain::TOLERANCE
            .check_named("tol", tol)
            .map_err(value_err)?;
        let part = self.part();
        let mesh = detached(py, || part.tessellate(tol).map_err(swarf_err))?;
        Ok(Mesh {
            model: Arc::new(Model::Mesh {
                name: part.name.clone(),
                mesh,
            }),
        })
    }
}

/// The columns of [`Part::eval`].
#[derive(Default)]
struct EvalColumns {
    point: Vec<[f64; 3]>,
    du: Vec<[f64; 3]>,
    dv: Vec<[f64; 3]>,
    normal: Vec<[f64; 3]>,
    dir1: Vec<[f64; 3]>,
    dir2: Vec<[f64; 3]>,
    k1: Vec<f64>,
    k2: Vec<f64>,
}

/// Evaluates `patch` at every `(u, v)`.
fn eval_rows(patch: &swarf_geom::Patch, uv: &[[f64; 2]]) -> EvalColumns {
    let arr = |x: swarf_geom::Vec3| [x.x, x.y, x.z];
    let nan3 = [f64::NAN; 3];
    let mut c = EvalColumns::default();
    for &[u, v] in uv {
        let d = patch.derivs(u, v);
        c.point.push(arr(d.point.coords));
        c.du.push(arr(d.du));
        c.dv.push(arr(d.dv));
        c.normal.push(d.normal().map_or(nan3, arr));
        let k = d.curvature();
        c.k1.push(k.map_or(f64::NAN, |k| k.k1));
        c.k2.push(k.map_or(f64::NAN, |k| k.k2));
        c.dir1.push(k.map_or(nan3, |k| arr(k.dir1)));
        c.dir2.push(k.map_or(nan3, |k| arr(k.dir2)));
    }
    c
}

/// A triangle mesh, mm: from a file (`Mesh.load`, `swarf.load`), a part's
/// tessellation, or numpy arrays `Mesh(vertices, faces)`.
#[pyclass(module = "swarf", frozen)]
pub struct Mesh {
    /// Always [`Model::Mesh`].
    pub model: Arc<Model>,
}

impl Mesh {
    /// The triangles.
    pub fn mesh(&self) -> &TriMesh {
        match &*self.model {
            Model::Mesh { mesh, .. } => mesh,
            Model::Patches(_) => unreachable!("a Mesh holds triangles"),
        }
    }

    fn name_str(&self) -> &str {
        match &*self.model {
            Model::Mesh { name, .. } => name,
            Model::Patches(p) => &p.name,
        }
    }
}

#[pymethods]
impl Mesh {
    /// A mesh from `vertices`, an `(N, 3)` float64 array of positions (mm, finite,
    /// within 1 km of the origin), and `faces`, an `(M, 3)` integer array of vertex
    /// indices (counter-clockwise seen from outside, i.e. from above for a part's
    /// top). Raises `ValueError` naming the argument and the first bad row for a
    /// wrong shape or dtype, a non-finite coordinate, an index out of range, or an
    /// empty mesh.
    #[new]
    #[pyo3(signature = (vertices, faces, name = "mesh".to_string()))]
    fn new(vertices: &Bound<'_, PyAny>, faces: &Bound<'_, PyAny>, name: String) -> PyResult<Mesh> {
        let v = coordinate_rows::<3>("vertices", vertices)?;
        if v.is_empty() {
            return Err(value_err(
                "vertices: an empty mesh: expected at least three vertices",
            ));
        }
        if v.len() > u32::MAX as usize {
            return Err(value_err(format!(
                "vertices: {} vertices: expected at most {}",
                v.len(),
                u32::MAX
            )));
        }
        let f = index_rows("faces", faces, v.len())?;
        if f.is_empty() {
            return Err(value_err(
                "faces: an empty mesh: expected at least one triangle",
            ));
        }
        let points = v
            .into_iter()
            .map(|[x, y, z]| Point3::new(x, y, z))
            .collect();
        let mesh = TriMesh::new(points, f).map_err(swarf_err)?;
        Ok(Mesh {
            model: Arc::new(Model::Mesh { name, mesh }),
        })
    }

    /// Loads a mesh file (`.stl` binary or ASCII, `.obj`) or a built-in mesh
    /// (`"builtin:fillet-pocket"`). Raises `SwarfError` naming the file.
    #[staticmethod]
    fn load(py: Python<'_>, source: &Bound<'_, PyAny>) -> PyResult<Mesh> {
        let name = path_text(source).ok_or_else(|| {
            pyo3::exceptions::PyTypeError::new_err("source: expected a str or a path")
        })?;
        let model = detached(py, || swarf_app::load_model(&name).map_err(swarf_err))?;
        match model {
            Model::Mesh { .. } => Ok(Mesh {
                model: Arc::new(model),
            }),
            Model::Patches(_) => Err(swarf_msg(format!(
                "{name}: a parametric part, not a mesh (Part.load reads it; \
                 Part.tessellate makes a mesh of it)"
            ))),
        }
    }

    /// The mesh's name (a file's stem).
    #[getter]
    fn name(&self) -> String {
        self.name_str().to_string()
    }

    /// Vertex positions, an `(N, 3)` float64 array (a copy), mm.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        let v = &self.mesh().vertices;
        let flat: Vec<f64> = v.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
        grid_out(py, flat, v.len(), 3)
    }

    /// Triangles as vertex indices, an `(M, 3)` int64 array (a copy).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<i64>> {
        let t = &self.mesh().triangles;
        let flat: Vec<i64> = t.iter().flatten().map(|&k| i64::from(k)).collect();
        match numpy::ndarray::Array2::from_shape_vec((t.len(), 3), flat) {
            Ok(a) => numpy::IntoPyArray::into_pyarray(a, py),
            Err(_) => numpy::PyArray2::zeros(py, [0, 3], false),
        }
    }

    /// The box around the usable triangles: `((xmin, ymin, zmin), (xmax, ymax, zmax))`, mm.
    fn bounds(&self) -> ((f64, f64, f64), (f64, f64, f64)) {
        let b = self.mesh().aabb();
        ((b.min.x, b.min.y, b.min.z), (b.max.x, b.max.y, b.max.z))
    }

    /// Number of triangles.
    fn __len__(&self) -> usize {
        self.mesh().len()
    }

    fn __repr__(&self) -> String {
        let m = self.mesh();
        format!(
            "Mesh({:?}, {} vertices, {} triangles)",
            self.name_str(),
            m.vertices.len(),
            m.len()
        )
    }
}
