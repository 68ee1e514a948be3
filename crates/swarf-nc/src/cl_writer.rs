//! APT CL (cutter location) output: `PARTNO`, `UNITS`, `CUTTER` with the seven APT
//! parameters, `SPINDL`, `FEDRAT`, `RAPID` and six-value `GOTO/x,y,z,i,j,k` records,
//! `END`, `FINI`. The records follow the APT CL print conventions that CAM
//! post-processors and verifiers read; angles in degrees, lengths in the output units.

use crate::error::NcError;
use crate::number::{Units, writable_length, writable_rate, writable_spindle};
use std::fmt::Write as _;
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, Move, MoveKind};

/// Writes `moves` as an APT CL file.
///
/// # Units
/// Moves in mm and mm/min; converted to `units` on output.
///
/// # Errors
/// [`NcError::NonFinite`] for NaN or infinite coordinates or feeds,
/// [`NcError::OutOfDomain`] for values outside the coordinate or rate domains.
pub fn write_cl(
    moves: &[Move],
    feeds: &Feeds,
    cutter: &Cutter,
    part_name: &str,
    units: Units,
) -> Result<String, NcError> {
    let mut out = String::with_capacity(moves.len() * 64 + 256);
    let name: String = part_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_uppercase()
            } else {
                '_'
            }
        })
        .collect();
    let _ = writeln!(out, "PARTNO/{name}");
    let (unit_word, feed_word) = match units {
        Units::Mm => ("MM", "MMPM"),
        Units::Inch => ("INCHES", "IPM"),
    };
    let _ = writeln!(out, "UNITS/{unit_word}");
    let apt = cutter.to_apt();
    for v in [apt.d, apt.r, apt.e, apt.f, apt.h] {
        writable_length(0, "cutter", v)?;
    }
    writable_spindle(feeds.spindle)?;
    let len = |mm: f64| units.from_mm(mm);
    let _ = writeln!(
        out,
        "CUTTER/{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}",
        len(apt.d),
        len(apt.r),
        len(apt.e),
        len(apt.f),
        apt.alpha.to_degrees(),
        apt.beta.to_degrees(),
        len(apt.h)
    );
    let _ = writeln!(out, "SPINDL/RPM,{:.1},CLW", feeds.spindle);
    let mut feed = None;
    for (index, m) in moves.iter().enumerate() {
        let p = m.to.cl;
        let a = m.to.axis;
        for &c in &p.coords {
            writable_length(index, "pose", c)?;
        }
        if !a.iter().all(|c| c.is_finite()) {
            return Err(NcError::NonFinite {
                index,
                what: "tool axis",
            });
        }
        match m.kind {
            MoveKind::Rapid => {
                out.push_str("RAPID\n");
            }
            MoveKind::Feed => {
                writable_rate(index, "feed", m.feed)?;
                if feed != Some(m.feed) {
                    let _ = writeln!(out, "FEDRAT/{:.4},{feed_word}", len(m.feed));
                    feed = Some(m.feed);
                }
            }
        }
        let _ = writeln!(
            out,
            "GOTO/{:.6},{:.6},{:.6},{:.9},{:.9},{:.9}",
            len(p.x),
            len(p.y),
            len(p.z),
            a.x,
            a.y,
            a.z
        );
    }
    out.push_str("SPINDL/OFF\nEND\nFINI\n");
    Ok(out)
}
