//! APT CL (cutter location) output: `PARTNO`, `UNITS`, `CUTTER` with the seven APT
//! parameters, `SPINDL`, `FEDRAT`, `RAPID` and six-value `GOTO/x,y,z,i,j,k` records,
//! `END`, `FINI`. The records follow the APT CL print conventions that CAM
//! post-processors and verifiers read; angles in degrees, lengths in the output units.

use crate::error::NcError;
use crate::number::Units;
use std::fmt::Write as _;
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, Move, MoveKind};

/// Writes `moves` as an APT CL file.
///
/// # Units
/// Moves in mm and mm/min; converted to `units` on output.
///
/// # Errors
/// [`NcError::NonFinite`] for NaN or infinite coordinates or feeds.
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
        if !(p.coords.iter().chain(a.iter()).all(|c| c.is_finite())) {
            return Err(NcError::NonFinite {
                index,
                what: "pose",
            });
        }
        match m.kind {
            MoveKind::Rapid => {
                out.push_str("RAPID\n");
            }
            MoveKind::Feed => {
                if !(m.feed.is_finite() && m.feed > 0.0) {
                    return Err(NcError::NonFinite {
                        index,
                        what: "feed",
                    });
                }
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
