//! Many drops at once: parallel over points, results in input order.
//!
//! Each drop is a pure function of the mesh, the cutter and the point (ties resolved
//! by triangle index, [`super::mesh`]), so the results are the same whatever the
//! number of threads or the order rayon runs the points in; `collect` keeps the input
//! order. Each rayon task reuses one [`DropScratch`].

use super::mesh::{DropResult, DropScratch, MeshDropper};
use rayon::prelude::*;

/// Drops the cutter at every point, in parallel on the current rayon pool.
///
/// # Units
/// mm.
///
/// # Example
/// ```
/// use swarf_geom::{Point3, TriMesh};
/// use swarf_tool::drop::{MeshDropper, drop_points};
/// let p = |x: f64, y: f64| Point3::new(x, y, x / 10.0);
/// let mesh = TriMesh::from_triangles(&[[p(0.0, 0.0), p(10.0, 0.0), p(0.0, 10.0)]]);
/// let dropper = MeshDropper::new(&mesh, &"flat:d=2".parse().unwrap());
/// let z: Vec<_> = drop_points(&dropper, &[[2.0, 2.0], [40.0, 0.0]]).iter().map(|r| r.map(|r| r.z)).collect();
/// assert_eq!(z, vec![Some(0.30000000000000004), None]);
/// ```
pub fn drop_points(dropper: &MeshDropper, points: &[[f64; 2]]) -> Vec<Option<DropResult>> {
    points
        .par_iter()
        .with_min_len(256)
        .map_init(DropScratch::default, |s, p| dropper.drop(p[0], p[1], s))
        .collect()
}
