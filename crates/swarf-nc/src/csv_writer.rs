//! Pose CSV: one line `x,y,z,i,j,k` per cutting pose (tool tip and unit axis), passes
//! in order, header `x,y,z,i,j,k`. Lengths in the requested units, 6 decimals.
//! Comment lines after the header carry what the columns cannot: `# units=inch|mm`,
//! `# feed=F` (output units per minute) and `# pass N` before each pass, so that the
//! reader ([`crate::read::parse_pose_csv`]) does not join passes by cutting moves.

use crate::error::NcError;
use crate::number::{Units, format_decimal, writable_length, writable_rate};
use std::fmt::Write as _;
use swarf_toolpath::Toolpath;

/// The cutting poses of `toolpath` as CSV text.
///
/// # Units
/// Lengths converted from mm to `units`; the axis is a unit vector.
///
/// # Errors
/// [`NcError::NonFinite`] or [`NcError::OutOfDomain`] (the pose's index) for a
/// coordinate, axis or feed that cannot be written.
pub fn write_pose_csv(toolpath: &Toolpath, units: Units) -> Result<String, NcError> {
    writable_rate(0, "feed", toolpath.feeds.feed)?;
    let mut out = String::with_capacity(toolpath.pose_count() * 64 + 16);
    out.push_str("x,y,z,i,j,k\n");
    let unit = match units {
        Units::Mm => "mm",
        Units::Inch => "inch",
    };
    let feed = format_decimal(units.from_mm(toolpath.feeds.feed), units.decimals());
    let _ = writeln!(out, "# units={unit}\n# feed={feed}");
    let mut index = 0;
    for (k, pass) in toolpath.passes.iter().enumerate() {
        let _ = writeln!(out, "# pass {k}");
        write_pass(&mut out, pass, units, &mut index)?;
    }
    Ok(out)
}

fn write_pass(
    out: &mut String,
    pass: &swarf_toolpath::Pass,
    units: Units,
    index: &mut usize,
) -> Result<(), NcError> {
    for p in &pass.points {
        let c = p.pose.cl;
        let a = p.pose.axis;
        for &v in &c.coords {
            writable_length(*index, "pose", v)?;
        }
        if !a.iter().all(|v| v.is_finite()) {
            return Err(NcError::NonFinite {
                index: *index,
                what: "tool axis",
            });
        }
        *index += 1;
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
    Ok(())
}
