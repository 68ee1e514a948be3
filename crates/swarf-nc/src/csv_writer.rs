//! Pose CSV: one line `x,y,z,i,j,k` per cutting pose (tool tip and unit axis), passes
//! in order, header `x,y,z,i,j,k`. Lengths in the requested units, 6 decimals.
//! Comment lines after the header carry what the columns cannot: `# units=inch|mm`,
//! `# feed=F` (output units per minute) and `# pass N` before each pass, so that the
//! reader ([`crate::read::parse_pose_csv`]) does not join passes by cutting moves.

use crate::number::Units;
use crate::number::format_decimal;
use std::fmt::Write as _;
use swarf_toolpath::Toolpath;

/// The cutting poses of `toolpath` as CSV text.
///
/// # Units
/// Lengths converted from mm to `units`; the axis is a unit vector.
pub fn write_pose_csv(toolpath: &Toolpath, units: Units) -> String {
    let mut out = String::with_capacity(toolpath.pose_count() * 64 + 16);
    out.push_str("x,y,z,i,j,k\n");
    let unit = match units {
        Units::Mm => "mm",
        Units::Inch => "inch",
    };
    let feed = format_decimal(units.from_mm(toolpath.feeds.feed), units.decimals());
    let _ = writeln!(out, "# units={unit}\n# feed={feed}");
    for (k, pass) in toolpath.passes.iter().enumerate() {
        let _ = writeln!(out, "# pass {k}");
        write_pass(&mut out, pass, units);
    }
    out
}

fn write_pass(out: &mut String, pass: &swarf_toolpath::Pass, units: Units) {
    for p in &pass.points {
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
}
