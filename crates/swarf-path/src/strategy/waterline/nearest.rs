//! Distances from points to a set of 2D segments within a reach, on a uniform grid
//! of buckets (the adaptive levels' test: how far one contour lies from the next).

use std::collections::HashMap;
use swarf_geom::Point3;
use swarf_geom::math::point_segment_distance;

/// Segments bucketed by the cells (side `reach`) their boxes cover.
pub(crate) struct SegmentIndex<'a> {
    segments: &'a [[[f64; 2]; 2]],
    cell: f64,
    buckets: HashMap<(i64, i64), Vec<u32>>,
}

impl<'a> SegmentIndex<'a> {
    /// Buckets `segments` in cells of side `reach` (mm, positive).
    pub fn new(segments: &'a [[[f64; 2]; 2]], reach: f64) -> SegmentIndex<'a> {
        let cell = reach.max(1e-6);
        let mut buckets: HashMap<(i64, i64), Vec<u32>> = HashMap::new();
        for (k, s) in segments.iter().enumerate() {
            let (i0, j0) = key(s[0][0].min(s[1][0]), s[0][1].min(s[1][1]), cell);
            let (i1, j1) = key(s[0][0].max(s[1][0]), s[0][1].max(s[1][1]), cell);
            for i in i0..=i1 {
                for j in j0..=j1 {
                    buckets.entry((i, j)).or_default().push(k as u32);
                }
            }
        }
        SegmentIndex {
            segments,
            cell,
            buckets,
        }
    }

    /// The distance from `p` to the nearest segment if it is at most `reach`.
    pub fn distance_within(&self, p: [f64; 2], reach: f64) -> Option<f64> {
        let (i, j) = key(p[0], p[1], self.cell);
        let mut best = f64::INFINITY;
        for di in -1..=1 {
            for dj in -1..=1 {
                for &k in self.buckets.get(&(i + di, j + dj)).into_iter().flatten() {
                    best = best.min(segment_distance(p, self.segments[k as usize]));
                }
            }
        }
        (best <= reach).then_some(best)
    }
}

fn key(x: f64, y: f64, cell: f64) -> (i64, i64) {
    ((x / cell).floor() as i64, (y / cell).floor() as i64)
}

/// Distance from `p` to segment `s` (in the plane z = 0).
fn segment_distance(p: [f64; 2], s: [[f64; 2]; 2]) -> f64 {
    let at = |q: [f64; 2]| Point3::new(q[0], q[1], 0.0);
    point_segment_distance(&at(p), &at(s[0]), &at(s[1]))
}
