//! The native half of `swarf.ocl`, the OpenCAMLib-compatible layer (its Python
//! classes are in `python/swarf/ocl/`): what `Mesh` and `Dropper` do not already
//! give it.
//!
//! - [`OclWaterline`]: the loops of one level of swarf's waterline
//!   ([`swarf_path::strategy::waterline`]: the contour `drop(x, y) = z` of the exact drop
//!   height, every loop point found by root finding on it). The drop field is sampled
//!   once when the object is made and serves every level, so OpenCAMLib's pattern of
//!   `setZ`, `run`, `getLoops` per level pays for a level's contour only.
//! - [`triangle_drop_at`]: the vertex, edge or facet drop onto one triangle, or the
//!   whole triangle's ([`swarf_tool::drop::kernel`]), which OpenCAMLib's
//!   `MillingCutter.vertexDrop`, `edgeDrop`, `facetDrop` and `dropCutter` are.
//!
//! Units: mm.

use crate::arrays::rows_out;
use crate::drop::{feature_code, threads_arg};
use crate::errors::{detached, swarf_err, value_err};
use crate::model::Mesh;
use crate::tool::cutter_arg;
use numpy::PyArray2;
use pyo3::prelude::*;
use swarf_geom::Point3;
use swarf_path::Finish;
use swarf_path::strategy::waterline::{Milling, Waterline, WaterlineParams};
use swarf_tool::drop::{
    DropCutter, TriContact, edge_drop, facet_drop, triangle_drop, vertex_drop, with_threads,
};

/// A cutter's waterline over a mesh, ready for any level: `OclWaterline(mesh, tool,
/// sampling, tolerance, threads=None)` drops the cutter on a grid of `sampling` mm
/// over the mesh (on `threads` workers, default one per core, with the GIL
/// released); `loops(z)` returns that level's loops, each point on the contour and
/// every chord within `tolerance` mm of it.
#[pyclass(module = "swarf", frozen)]
pub struct OclWaterline {
    wl: Waterline<'static>,
    threads: Option<usize>,
}

#[pymethods]
impl OclWaterline {
    /// Raises `ValueError` naming `sampling` or `tolerance` where it is not a
    /// positive length or the grid would be too large, and `SwarfError` for a mesh
    /// without finite triangles.
    #[new]
    #[pyo3(signature = (mesh, tool, sampling, tolerance, threads = None))]
    fn new(
        py: Python<'_>,
        mesh: PyRef<'_, Mesh>,
        tool: &Bound<'_, PyAny>,
        sampling: f64,
        tolerance: f64,
        threads: Option<usize>,
    ) -> PyResult<OclWaterline> {
        let cutter = cutter_arg("tool", tool)?;
        let threads = threads_arg(threads)?;
        for (arg, v) in [("sampling", sampling), ("tolerance", tolerance)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(value_err(format!(
                    "{arg}: {v}: expected a positive length in mm"
                )));
            }
        }
        let params = WaterlineParams {
            finish: Finish {
                tolerance,
                ..Finish::default()
            },
            sampling: Some(sampling),
            ..WaterlineParams::default()
        };
        let mesh = mesh.mesh().clone();
        let wl = detached(py, || {
            with_threads(threads, || Waterline::owned(mesh, &cutter, &params))
                .0
                .map_err(swarf_err)
        })?;
        Ok(OclWaterline { wl, threads })
    }

    /// The loops at tool tip height `z` (mm): a list of `(K, 2)` float64 arrays of
    /// XY points, closed (the first point not repeated), the material on their left
    /// (counter-clockwise around an island, clockwise inside a pocket: OpenCAMLib's
    /// orientation). Raises `ValueError` for a `z` that
    /// is not finite.
    fn loops<'py>(&self, py: Python<'py>, z: f64) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        if !z.is_finite() {
            return Err(value_err(format!("z: {z}: expected a finite height in mm")));
        }
        let level = detached(py, || {
            Ok(with_threads(self.threads, || self.wl.level(z, Milling::Conventional)).0)
        })?;
        Ok(level
            .loops
            .iter()
            .map(|lp| {
                let xy: Vec<[f64; 2]> = lp.iter().map(|p| [p.pose.cl.x, p.pose.cl.y]).collect();
                rows_out(py, &xy)
            })
            .collect())
    }
}

/// A contact as Python gets it: tip height, CC point, feature code.
type Contact = (f64, (f64, f64, f64), i8);

/// The drop of `tool` at `(x, y)` onto the triangle `tri` (three `(x, y, z)`
/// corners, mm) for one case, `kind`: `"vertex"`, `"edge"`, `"facet"` or `"all"`
/// (the highest of them). Returns `None` where the cutter cannot touch that way,
/// else `(z, (ccx, ccy, ccz), feature)`: the tip height, the CC point and the
/// feature's index in `swarf.FEATURES`. Raises `ValueError` naming `kind`, or `tri`
/// for a non-finite corner.
#[pyfunction]
pub fn triangle_drop_at(
    tool: &Bound<'_, PyAny>,
    x: f64,
    y: f64,
    tri: [[f64; 3]; 3],
    kind: &str,
) -> PyResult<Option<Contact>> {
    let cutter = cutter_arg("tool", tool)?;
    if let Some(k) = tri.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
        return Err(value_err(format!(
            "tri: corner {k} {:?} has a non-finite coordinate",
            tri[k]
        )));
    }
    let t = tri.map(|[a, b, c]| Point3::new(a, b, c));
    Ok(case_drop(&cutter, [x, y], &t, kind)?
        .map(|c| (c.z, (c.cc.x, c.cc.y, c.cc.z), feature_code(c.feature))))
}

/// The highest contact of one drop case ([`triangle_drop_at`]).
fn case_drop(
    cutter: &swarf_tool::Cutter,
    xy: [f64; 2],
    t: &[Point3; 3],
    kind: &str,
) -> PyResult<Option<TriContact>> {
    let tool = DropCutter::new(cutter);
    let best = |cs: [Option<TriContact>; 3]| {
        cs.into_iter()
            .flatten()
            .fold(None, |b: Option<TriContact>, c| match b {
                Some(b) if b.z >= c.z => Some(b),
                _ => Some(c),
            })
    };
    match kind {
        "vertex" => Ok(best([0, 1, 2].map(|k| vertex_drop(&tool, xy, t, k)))),
        "edge" => Ok(best([0, 1, 2].map(|k| edge_drop(&tool, xy, t, k)))),
        "facet" => Ok(facet_drop(&tool, xy, t)),
        "all" => Ok(triangle_drop(&tool, xy, t)),
        _ => Err(value_err(format!(
            "kind: {kind:?}: expected \"vertex\", \"edge\", \"facet\" or \"all\""
        ))),
    }
}
