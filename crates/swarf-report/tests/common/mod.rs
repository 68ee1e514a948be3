//! Test programs shared by the report tests.

use swarf_geom::Point3;
use swarf_tool::Pose;
use swarf_toolpath::{Motion, MotionKind, Program};

/// Appends straight motions of a vertical tool from `at` through `points` (each with
/// its kind) at 300 mm/min, one source line each; `at` ends at the last point.
pub fn chain(program: &mut Program, at: &mut [f64; 3], points: Vec<([f64; 3], MotionKind)>) {
    for (to, kind) in points {
        let line = program.motions.len() + 1;
        program.motions.push(Motion {
            kind,
            start: Pose::vertical(Point3::from(*at)),
            end: Pose::vertical(Point3::from(to)),
            feed: 300.0,
            line,
        });
        *at = to;
    }
}
