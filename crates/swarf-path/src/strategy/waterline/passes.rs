//! The order of the loops: level by level from the top, within a level the nearest
//! loop next, each closed loop started at its point nearest the previous end.

use super::LevelContour;
use swarf_toolpath::{Pass, PathPoint};

/// Closed passes (first point repeated at the end) in cutting order.
pub(crate) fn order(levels: &[LevelContour]) -> Vec<Pass> {
    let mut passes = Vec::new();
    let mut at: Option<[f64; 2]> = None;
    for level in levels {
        let mut left: Vec<&Vec<PathPoint>> = level.loops.iter().filter(|l| l.len() > 1).collect();
        while !left.is_empty() {
            let here = at.unwrap_or_else(|| xy(&left[0][0]));
            let (k, start) = left
                .iter()
                .enumerate()
                .map(|(k, lp)| (k, nearest(lp, here)))
                .min_by(|a, b| a.1.1.total_cmp(&b.1.1).then(a.0.cmp(&b.0)))
                .map(|(k, (i, _))| (k, i))
                .unwrap_or((0, 0));
            let lp = left.remove(k);
            let mut points: Vec<PathPoint> =
                lp[start..].iter().chain(&lp[..start]).copied().collect();
            points.push(points[0]);
            at = Some(xy(&points[0]));
            passes.push(Pass {
                points,
                ..Pass::default()
            });
        }
    }
    passes
}

fn xy(p: &PathPoint) -> [f64; 2] {
    [p.pose.cl.x, p.pose.cl.y]
}

/// Index of the point of `lp` nearest `q`, and its squared distance.
fn nearest(lp: &[PathPoint], q: [f64; 2]) -> (usize, f64) {
    lp.iter()
        .enumerate()
        .map(|(i, p)| {
            let d = xy(p);
            (i, (d[0] - q[0]).powi(2) + (d[1] - q[1]).powi(2))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .unwrap_or((0, f64::INFINITY))
}
