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
/// let r = drop_points(&dropper, &[[2.0, 2.0], [40.0, 0.0]]);
/// assert!((r[0].unwrap().z - 0.3).abs() < 1e-12 && r[1].is_none());
/// ```
pub fn drop_points(dropper: &MeshDropper, points: &[[f64; 2]]) -> Vec<Option<DropResult>> {
    points
        .par_iter()
        .with_min_len(256)
        .map_init(DropScratch::default, |s, p| dropper.drop(p[0], p[1], s))
        .collect()
}

/// As [`drop_points`] on a pool of `threads` workers (`None`: rayon's default, one
/// per core or `RAYON_NUM_THREADS`); also returns the number of workers used. Falls
/// back to the default pool if a new one cannot be made.
pub fn drop_points_threads(
    dropper: &MeshDropper,
    points: &[[f64; 2]],
    threads: Option<usize>,
) -> (Vec<Option<DropResult>>, usize) {
    with_threads(threads, || drop_points(dropper, points))
}

/// Runs `f` on a pool of `threads` workers (`None` or 0: the current pool, one worker
/// per core or `RAYON_NUM_THREADS`), and returns its result and the number of
/// workers. Falls back to the current pool if a new one cannot be made.
pub fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> (T, usize) {
    if let Some(n) = threads.filter(|&n| n > 0)
        && let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(n).build()
    {
        return (pool.install(f), n);
    }
    (f(), rayon::current_num_threads())
}
