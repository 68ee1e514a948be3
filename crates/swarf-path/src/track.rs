//! Drop-cutter along any polyline in XY: the raster pass sampler (`raster_pass.rs`:
//! even first samples, refinement to the tolerance, crease search, splitting where
//! the cutter leaves the mesh) on a track of straight pieces, each piece sampled on
//! its own so that every corner of the track is a sample. Cleanup paths (follow-pocket
//! rings, offset pencil passes) are tracks dropped onto the part this way.

use crate::plan::DoubleContact;
use crate::strategy::raster::pass::{Along, Sampler};
use swarf_geom::TriMesh;
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::PathPoint;

/// A polyline in XY parameterised by arc length.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    points: Vec<[f64; 2]>,
    /// Arc length at each point.
    cum: Vec<f64>,
}

impl Track {
    /// The track through `points` (consecutive repeats dropped); `None` when a
    /// coordinate is not finite or no point is given.
    pub fn new(points: &[[f64; 2]]) -> Option<Track> {
        if points.is_empty() || points.iter().flatten().any(|v| !v.is_finite()) {
            return None;
        }
        let mut pts: Vec<[f64; 2]> = Vec::with_capacity(points.len());
        let mut cum = Vec::with_capacity(points.len());
        for p in points {
            match pts.last() {
                Some(q) if q == p => {}
                Some(q) => {
                    let len = (p[0] - q[0]).hypot(p[1] - q[1]);
                    cum.push(cum.last().copied().unwrap_or(0.0) + len);
                    pts.push(*p);
                }
                None => {
                    cum.push(0.0);
                    pts.push(*p);
                }
            }
        }
        Some(Track { points: pts, cum })
    }

    /// The track's corners.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// Its length, mm.
    pub fn length(&self) -> f64 {
        self.cum.last().copied().unwrap_or(0.0)
    }
}

impl Along for Track {
    fn at(&self, t: f64) -> [f64; 2] {
        let k = self
            .cum
            .partition_point(|&c| c <= t)
            .clamp(1, self.cum.len());
        if k == self.cum.len() {
            return self.points[k - 1];
        }
        let (a, b) = (self.points[k - 1], self.points[k]);
        let s = (t - self.cum[k - 1]) / (self.cum[k] - self.cum[k - 1]);
        [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
    }

    fn breaks(&self) -> Vec<f64> {
        self.cum.clone()
    }
}

/// What a track gave: the pieces of path in travel order (split where the cutter
/// leaves the mesh), and the double contacts met on the way.
#[derive(Debug, Default)]
pub struct TrackDrop {
    /// Pieces, each at least two points.
    pub pieces: Vec<Vec<PathPoint>>,
    /// Double contacts at the samples.
    pub doubles: Vec<DoubleContact>,
}

/// Drops `dropper`'s cutter along `track` over `mesh` (the mesh the dropper was
/// made from), refined so that the CL polyline is within `tolerance` of the CL curve.
///
/// # Units
/// mm.
///
/// # Example
/// ```
/// use swarf_geom::{Point3, TriMesh};
/// use swarf_path::track::{Track, drop_track};
/// use swarf_tool::drop::{DropScratch, MeshDropper};
/// let p = |x: f64, y: f64| Point3::new(x, y, 1.0);
/// let mesh = TriMesh::from_triangles(&[[p(-9.0, -9.0), p(9.0, -9.0), p(0.0, 9.0)]]);
/// let dropper = MeshDropper::new(&mesh, &"ball:d=2".parse().unwrap());
/// let track = Track::new(&[[-1.0, 0.0], [1.0, 0.0], [1.0, 1.0]]).unwrap();
/// let out = drop_track(&mesh, &dropper, &track, 0.01, &mut DropScratch::default());
/// assert_eq!(out.pieces.len(), 1);
/// assert!(out.pieces[0].iter().all(|q| q.pose.cl.z == 1.0));
/// assert!(out.pieces[0].iter().any(|q| q.pose.cl.x == 1.0 && q.pose.cl.y == 0.0));
/// ```
pub fn drop_track(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    track: &Track,
    tolerance: f64,
    scratch: &mut DropScratch,
) -> TrackDrop {
    let out = Sampler::new(mesh, dropper, tolerance, true).run(track, scratch);
    TrackDrop {
        pieces: out.pieces,
        doubles: out.doubles,
    }
}

/// The double contacts where `dropper`'s cutter, moved along `track`, jumps across
/// a valley (the crease search of the raster sampler without refinement): the points
/// of the cutter's bitangency curve that the track crosses.
///
/// # Units
/// mm.
pub fn crease_track(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    track: &Track,
    tolerance: f64,
    scratch: &mut DropScratch,
) -> Vec<DoubleContact> {
    Sampler::new(mesh, dropper, tolerance, false)
        .run(track, scratch)
        .doubles
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;

    #[test]
    fn parameter_runs_along_the_corners() {
        let t = Track::new(&[[0.0, 0.0], [0.0, 0.0], [3.0, 4.0], [3.0, 0.0]]).unwrap();
        assert_eq!(t.points().len(), 3);
        assert_eq!(t.length(), 9.0);
        assert_eq!(t.at(2.5), [1.5, 2.0]);
        assert_eq!(t.at(7.0), [3.0, 2.0]);
        assert_eq!(t.at(99.0), [3.0, 0.0]);
        assert!(Track::new(&[[f64::NAN, 0.0]]).is_none() && Track::new(&[]).is_none());
    }

    #[test]
    fn a_track_over_a_ridge_follows_it_within_tolerance() {
        // A roof ridge along y: z = 5 - |x|. A ball d=4 dropped on the track across it
        // rides over the ridge; every CL point is the exact drop there.
        let p = |x: f64, y: f64| Point3::new(x, y, 5.0 - x.abs());
        let mesh = TriMesh::from_triangles(&[
            [p(-10.0, -10.0), p(0.0, -10.0), p(0.0, 10.0)],
            [p(-10.0, -10.0), p(0.0, 10.0), p(-10.0, 10.0)],
            [p(0.0, -10.0), p(10.0, -10.0), p(10.0, 10.0)],
            [p(0.0, -10.0), p(10.0, 10.0), p(0.0, 10.0)],
        ]);
        let dropper = MeshDropper::new(&mesh, &"ball:d=4".parse().unwrap());
        let track = Track::new(&[[-5.0, -2.0], [5.0, -2.0], [5.0, 2.0], [-5.0, 2.0]]).unwrap();
        let out = drop_track(&mesh, &dropper, &track, 0.001, &mut DropScratch::default());
        assert_eq!(out.pieces.len(), 1);
        let pts = &out.pieces[0];
        let exact = |x: f64| {
            // The ball (R = 2) rests on one flank (offset 2 sqrt 2 along the normal)
            // or, within R / sqrt 2 of the ridge, on the ridge line itself.
            let r: f64 = 2.0;
            if x.abs() >= r / 2f64.sqrt() {
                5.0 - x.abs() + r * 2f64.sqrt() - r
            } else {
                5.0 + (r * r - x * x).sqrt() - r
            }
        };
        for q in pts {
            assert!((q.pose.cl.z - exact(q.pose.cl.x)).abs() < 1e-9, "{q:?}");
        }
        // The ridge is crossed on both legs and the corners are samples.
        assert!(pts.iter().filter(|q| q.pose.cl.x == 0.0).count() >= 2);
        assert!(pts.iter().any(|q| q.pose.cl.x == 5.0 && q.pose.cl.y == 2.0));
        for w in pts.windows(2) {
            let m = (w[0].pose.cl + w[1].pose.cl.coords) * 0.5;
            assert!(exact(m.x) - m.z <= 0.001 + 1e-9, "chord below the ridge");
        }
    }
}
