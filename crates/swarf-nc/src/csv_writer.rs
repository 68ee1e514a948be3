//! Pose CSV: one line `x,y,z,i,j,k` per cutting pose (tool tip and unit axis), passes
//! in order, header `x,y,z,i,j,k`. Lengths in the requested units, 6 decimals.

use crate::number::Units;
use std::fmt::Write as _;
use swarf_path::Toolpath;

/// The cutting poses of `toolpath` as CSV text.
///
/// # Units
/// Lengths converted from mm to `units`; the axis is a unit vector.
pub fn write_pose_csv(toolpath: &Toolpath, units: Units) -> String {
    let mut out = String::with_capacity(toolpath.pose_count() * 64 + 16);
    out.push_str("x,y,z,i,j,k\n");
    for p in toolpath.passes.iter().flat_map(|p| &p.points) {
        let c = p.pose.cl;
        let a = p.pose.axis;
        let _ = writeln!(
            out,
            "{:.6},{:.6},{:.6},{:.9},{:.9},{:.9}",
            units.from_mm(c.x),
            units.from_mm(c.y),
            units.from_mm(c.z),
            a.x,
            a.y,
            a.z
        );
    }
    out
}
