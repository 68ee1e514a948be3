//! The geometry of cutter compensation's corners (`interp_convert.cc`,
//! `interp_find.cc`): which side of an arc the tool is on, the angle an arc sweeps,
//! and where the compensated tool stops at a concave corner between lines and arcs:
//! the intersection of the two offset paths, reached by moving the previous move's
//! end back along it.

use crate::read::modal::Pos;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Whether the tool is inside the arc: left of a counter-clockwise one, right of a
/// clockwise one.
pub(crate) fn inside(left: bool, turn: i32) -> bool {
    (left && turn > 0) || (!left && turn < 0)
}

/// The signed angle an arc sweeps from `p1` to `p2` about `c` (LinuxCNC's `find_turn`).
pub(crate) fn find_turn(p1: [f64; 2], c: [f64; 2], turn: i32, p2: [f64; 2]) -> f64 {
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = (p1[1] - c[1]).atan2(p1[0] - c[0]);
    let mut beta = (p2[1] - c[1]).atan2(p2[0] - c[0]);
    if turn > 0 {
        if beta <= alpha {
            beta += TAU;
        }
        beta - alpha + f64::from(turn - 1) * TAU
    } else {
        if alpha <= beta {
            alpha += TAU;
        }
        beta - alpha + f64::from(turn + 1) * TAU
    }
}

/// A concave corner between two lines: the tool at `c` on the previous line's offset
/// (direction `dir` back along it) moves back until it touches the next line's offset;
/// `beta` is the turn between the lines.
pub(crate) fn line_to_line_corner(
    r: f64,
    c: [f64; 2],
    dir: f64,
    beta: f64,
) -> Result<(f64, f64), String> {
    let halfcorner = (beta + PI) / 2.0;
    if halfcorner == 0.0 {
        return Err("zero degree inside corner is invalid for cutter compensation".into());
    }
    let retreat = r / halfcorner.tan();
    Ok((c[0] + retreat * dir.cos(), c[1] + retreat * dir.sin()))
}

/// A concave corner from a queued arc (centre `pc`, end `qend`, turn `pturn`) into a
/// line from the programmed point `o` to `p`: where the tool on the arc's offset
/// touches the line's offset.
pub(crate) fn arc_to_line_corner(
    left: bool,
    r: f64,
    o: [f64; 2],
    p: [f64; 2],
    qend: Pos,
    pc: [f64; 2],
    pturn: i32,
) -> Result<(f64, f64), String> {
    let oldrad = (pc[1] - qend[1]).hypot(pc[0] - qend[0]);
    let base_dir = (p[1] - o[1]).atan2(p[0] - o[0]);
    let theta = if pturn > 0 {
        base_dir + FRAC_PI_2
    } else {
        base_dir - FRAC_PI_2
    };
    let phi = (pc[1] - o[1]).atan2(pc[0] - o[0]);
    let tool_inside = inside(left, pturn);
    let uncomp = if tool_inside { oldrad + r } else { oldrad - r };
    let d = uncomp * (theta - phi).cos();
    let fail =
        "arc to straight motion makes a corner the compensated tool can't fit in without gouging";
    let angle = if tool_inside {
        let l = (d - r) / oldrad;
        if !(-1.0..=1.0).contains(&l) {
            return Err(fail.into());
        }
        if pturn > 0 {
            -l.acos() + theta + PI
        } else {
            l.acos() + theta + PI
        }
    } else {
        let l = (d + r) / oldrad;
        if !(-1.0..=1.0).contains(&l) {
            return Err(fail.into());
        }
        if pturn > 0 {
            l.acos() + theta + PI
        } else {
            -l.acos() + theta + PI
        }
    };
    Ok((pc[0] + oldrad * angle.cos(), pc[1] + oldrad * angle.sin()))
}

/// A concave corner from a queued line into an arc (centre `c`, programmed radius
/// `arc_radius`): where the line's offset meets the arc's.
pub(crate) fn line_to_arc_corner(
    tool_inside: bool,
    r: f64,
    c: [f64; 2],
    arc_radius: f64,
    turn: i32,
    theta: f64,
    beta: f64,
) -> Result<(f64, f64), String> {
    let cy = arc_radius * (beta - FRAC_PI_2).sin();
    let fail = "arc move in concave corner cannot be reached by the tool without gouging";
    let (dist, angle) = if tool_inside {
        let dist = arc_radius - r;
        let l = (cy + r) / dist;
        if !(-1.0..=1.0).contains(&l) {
            return Err(fail.into());
        }
        (
            dist,
            if turn > 0 {
                theta + l.asin()
            } else {
                theta - l.asin()
            },
        )
    } else {
        let dist = arc_radius + r;
        let l = (cy - r) / dist;
        if !(-1.0..=1.0).contains(&l) {
            return Err(fail.into());
        }
        (
            dist,
            if turn > 0 {
                theta + PI - l.asin()
            } else {
                theta + PI + l.asin()
            },
        )
    };
    Ok((c[0] + dist * angle.cos(), c[1] + dist * angle.sin()))
}

/// A concave corner between a queued arc (centre `pc`) and a new arc (centre `c`):
/// the intersection of their offsets.
#[allow(clippy::too_many_arguments)]
pub(crate) fn arc_to_arc_corner(
    left: bool,
    r: f64,
    c: [f64; 2],
    turn: i32,
    arc_radius: f64,
    qend: Pos,
    pc: [f64; 2],
    pturn: i32,
) -> Result<(f64, f64), String> {
    let oldrad = (pc[1] - qend[1]).hypot(pc[0] - qend[0]);
    let newrad = if inside(left, turn) {
        arc_radius - r
    } else {
        arc_radius + r
    };
    let arc_cc = (pc[1] - c[1]).hypot(pc[0] - c[0]);
    if oldrad == 0.0 || arc_cc == 0.0 {
        return Err("arc to arc motion is invalid because the arcs have the same center".into());
    }
    let a = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2.0 * oldrad * arc_cc);
    if !(-1.0..=1.0).contains(&a) {
        return Err(
            "arc to arc motion makes a corner the compensated tool can't fit in without gouging"
                .into(),
        );
    }
    let pullback = a.acos();
    let cc_dir = (c[1] - pc[1]).atan2(c[0] - pc[0]);
    let dir = if inside(left, pturn) == (turn > 0) {
        cc_dir + pullback
    } else {
        cc_dir - pullback
    };
    Ok((pc[0] + oldrad * dir.cos(), pc[1] + oldrad * dir.sin()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_as_linuxcnc_counts_them() {
        let c = [0.0, 0.0];
        assert!((find_turn([1.0, 0.0], c, 1, [0.0, 1.0]) - FRAC_PI_2).abs() < 1e-12);
        assert!((find_turn([1.0, 0.0], c, -1, [0.0, 1.0]) + 3.0 * FRAC_PI_2).abs() < 1e-12);
        assert!((find_turn([1.0, 0.0], c, 1, [1.0, 0.0]) - TAU).abs() < 1e-12);
        assert_eq!(find_turn([1.0, 0.0], c, 0, [0.0, 1.0]), 0.0);
    }
}
