//! Rotary solutions along a pass: branch choice, continuity, the singular pose, limits;
//! and the motion of a machine between two axis positions.
//!
//! **Continuity.** Each pose has up to two rotary branches ([`super::kinematics`]), and
//! each angle is only known modulo a turn. Along a pass the branch and the turn of each
//! pose are the ones nearest (in the sum of the rotary steps) to the previous pose's, so
//! no axis unwinds by a turn in the middle of a cut. The first pose takes the branch
//! nearest to where the machine is (the end of the previous pass); on a fresh start,
//! the machine file's preference (`prefer = "A+"`), else the branch with the smaller
//! angles. Both first branches are tried; one whose pass breaks a limit is dropped.
//!
//! **Singular pose.** Where the tool axis lies within `singular_cone` of the left
//! factor's axis (the C axis of an A/C table: tool parallel to C), that angle is free and
//! jumps wildly near the pole. A run of such poses keeps it interpolated linearly between
//! the values before and after the run (shortest way), and solves the other angle for
//! it ([`Machine::right_for_left`]): the tip stays exact and the axis is off by at most
//! about twice the cone. A pass through the pole itself comes out with C steady and A
//! passing through zero.
//!
//! **Limits.** A rotary axis with limits takes the whole pass shifted by the whole
//! number of turns that keeps every pose inside them (the one nearest the machine's
//! angle); none: the other branch; none either: an error naming the first pose and the
//! axis. Linear limits are checked on the `X Y Z` that follow.
//!
//! **Joint motion.** Without tool-centre-point control a G1 block moves every axis
//! linearly from one position to the next. [`joint_path`] gives the part-frame poses of
//! that motion, subdivided until the tip's path is within a chordal tolerance of the
//! straight lines between them (for verifying programs of any CAM system). The post
//! goes the other way: it writes poses between two solved ones (on the chord, the axis
//! on the great circle) so that this motion stays on the chord, each solved by
//! [`solve_near`] near the straight joint-space motion at the same fraction of the move
//! (same branch, same turns; near the pole, the left angle of that motion).

use super::Machine;
use super::kinematics::{Joints, Orientation};
use crate::error::FiveAxisError;
use std::f64::consts::{PI, TAU};
use swarf_tool::Pose;

/// `theta` plus the whole turns that bring it nearest to `reference`.
pub fn unwrap_near(theta: f64, reference: f64) -> f64 {
    theta + TAU * ((reference - theta) / TAU).round()
}

/// A pass's rotary angles before limits: one per pose.
type Angles = Vec<[f64; 2]>;

/// Solves the machine axes for the poses of pass `pass` (module doc), starting near
/// `start` when given.
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`FiveAxisError::Unreachable`] naming the first pose and the axis (or `orientation`)
/// the machine cannot reach.
pub fn solve_pass(
    m: &Machine,
    poses: &[Pose],
    start: Option<&Joints>,
    tool_length: f64,
    pass: usize,
) -> Result<Vec<Joints>, FiveAxisError> {
    let orient: Vec<Orientation> = poses.iter().map(|p| m.orientation(&p.axis)).collect();
    if let Some(index) = orient
        .iter()
        .position(|o| o.branches.iter().all(Option::is_none))
    {
        let a = poses[index].axis;
        return Err(FiveAxisError::Unreachable {
            pass,
            index,
            axis: "orientation".into(),
            message: format!(
                "no setting of {} and {} points the tool along ({:.6}, {:.6}, {:.6})",
                m.rotary[0].name, m.rotary[1].name, a.x, a.y, a.z
            ),
        });
    }
    let reference = start.map(|s| s.rotary);
    let mut attempts = Vec::new();
    let mut first_error = None;
    for branch in 0..2 {
        let mut angles = follow(m, poses, &orient, reference, branch);
        match fit_limits(m, &mut angles, reference, pass) {
            Ok(()) => attempts.push(angles),
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    let angles = choose(m, attempts, reference).ok_or_else(|| {
        first_error.unwrap_or_else(|| FiveAxisError::Unreachable {
            pass,
            index: 0,
            axis: "orientation".into(),
            message: "no solution".into(),
        })
    })?;
    let mut out = Vec::with_capacity(poses.len());
    for (index, (p, r)) in poses.iter().zip(&angles).enumerate() {
        let linear = m.linear_for(&p.cl, r, tool_length);
        check_linear(m, &linear, pass, index)?;
        out.push(Joints { linear, rotary: *r });
    }
    Ok(out)
}

/// The continuous sequence of angles taking `branch` at the first regular pose.
fn follow(
    m: &Machine,
    poses: &[Pose],
    orient: &[Orientation],
    reference: Option<[f64; 2]>,
    branch: usize,
) -> Angles {
    let sin_cone = m.singular_cone.sin();
    let mut prev = reference;
    let mut first = true;
    let mut out: Vec<Option<[f64; 2]>> = Vec::with_capacity(poses.len());
    for o in orient {
        if o.off_singular < sin_cone {
            out.push(None);
            continue;
        }
        let near = |c: [f64; 2], p: [f64; 2]| [unwrap_near(c[0], p[0]), unwrap_near(c[1], p[1])];
        let chosen = if first {
            first = false;
            let c = o.branches[branch]
                .or(o.branches[1 - branch])
                .unwrap_or([0.0; 2]);
            prev.map_or(c, |p| near(c, p))
        } else {
            let p = prev.unwrap_or([0.0; 2]);
            o.branches
                .iter()
                .flatten()
                .map(|c| near(*c, p))
                .min_by(|a, b| step(a, &p).total_cmp(&step(b, &p)))
                .unwrap_or(p)
        };
        out.push(Some(chosen));
        prev = Some(chosen);
    }
    fill_singular(m, poses, orient, &mut out, reference);
    out.into_iter().map(|a| a.unwrap_or([0.0; 2])).collect()
}

fn step(a: &[f64; 2], b: &[f64; 2]) -> f64 {
    (a[0] - b[0]).abs() + (a[1] - b[1]).abs()
}

/// Fills runs of singular poses (module doc).
fn fill_singular(
    m: &Machine,
    poses: &[Pose],
    orient: &[Orientation],
    out: &mut [Option<[f64; 2]>],
    reference: Option<[f64; 2]>,
) {
    let n = out.len();
    let mut i = 0;
    while i < n {
        if out[i].is_some() {
            i += 1;
            continue;
        }
        let a = i;
        while i < n && out[i].is_none() {
            i += 1;
        }
        let (l, r) = (orient[a].left, orient[a].right);
        let before = if a > 0 { out[a - 1] } else { reference };
        let after = out.get(i).copied().flatten();
        let lo = before.or(after).map_or(0.0, |v| v[l]);
        let hi = after.map_or(lo, |v| unwrap_near(v[l], lo));
        let mut prev_right = before.or(after).map(|v| v[r]);
        for j in a..i {
            let t = (j - a + 1) as f64 / (i - a + 1) as f64;
            let left = lo + t * (hi - lo);
            let right = m.right_for_left(&poses[j].axis, left);
            let right = prev_right.map_or(right, |p| unwrap_near(right, p));
            prev_right = Some(right);
            let mut v = [0.0; 2];
            v[l] = left;
            v[r] = right;
            out[j] = Some(v);
        }
    }
}

/// Shifts each limited axis by whole turns into its limits (module doc).
fn fit_limits(
    m: &Machine,
    angles: &mut Angles,
    reference: Option<[f64; 2]>,
    pass: usize,
) -> Result<(), FiveAxisError> {
    for k in 0..2 {
        let (lo_v, hi_v) = angles
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v[k]), b.max(v[k]))
            });
        if !lo_v.is_finite() {
            continue;
        }
        let target = reference.map_or(0.0, |r| r[k]);
        let shift = match m.rotary[k].limits {
            None if reference.is_some() => 0.0,
            None => -TAU * (angles[0][k] / TAU).round(),
            Some([lo, hi]) => {
                let n0 = ((lo - lo_v) / TAU - 1e-12).ceil() as i64;
                let n1 = ((hi - hi_v) / TAU + 1e-12).floor() as i64;
                if n0 > n1 {
                    return Err(limit_error(m, angles, k, pass));
                }
                // |mid + TAU n - target| is convex in n: the best whole turn in
                // [n0, n1] is one of the two around the unconstrained optimum (the
                // lower on a tie), so limits of any width cost two evaluations.
                let mid = 0.5 * (lo_v + hi_v);
                let x = (target - mid) / TAU;
                let clamp = |v: f64| (v as i64).clamp(n0, n1);
                let (a, b) = (clamp(x.floor()), clamp(x.ceil()));
                let off = |n: i64| (mid + TAU * n as f64 - target).abs();
                let best = if off(b) < off(a) { b } else { a };
                TAU * best as f64
            }
        };
        for v in angles.iter_mut() {
            v[k] += shift;
        }
    }
    Ok(())
}

fn limit_error(m: &Machine, angles: &Angles, k: usize, pass: usize) -> FiveAxisError {
    let r = &m.rotary[k];
    let [lo, hi] = r.limits.unwrap_or([-PI, PI]);
    let index = angles
        .iter()
        .position(|v| {
            let w = unwrap_near(v[k], 0.5 * (lo + hi));
            w < lo || w > hi
        })
        .unwrap_or(0);
    FiveAxisError::Unreachable {
        pass,
        index,
        axis: r.name.to_string(),
        message: format!(
            "{:.4} degrees (or a whole turn from it) is outside the limits [{}, {}] for \
             every continuous solution of the pass",
            angles[index][k].to_degrees(),
            lo.to_degrees(),
            hi.to_degrees()
        ),
    }
}

/// The attempt to use: nearest the machine, else the preferred, else the smaller.
fn choose(m: &Machine, attempts: Vec<Angles>, reference: Option<[f64; 2]>) -> Option<Angles> {
    let first = |a: &Angles| a.first().copied().unwrap_or([0.0; 2]);
    if let Some(r) = reference {
        return attempts
            .into_iter()
            .min_by(|a, b| step(&first(a), &r).total_cmp(&step(&first(b), &r)));
    }
    let size = |a: &Angles| first(a)[0].abs() + first(a)[1].abs();
    let mut attempts = attempts;
    attempts.sort_by(|a, b| size(a).total_cmp(&size(b)));
    if let Some((k, sign)) = m.prefer
        && let Some(i) = attempts.iter().position(|a| first(a)[k] * sign >= 0.0)
    {
        return Some(attempts.swap_remove(i));
    }
    attempts.into_iter().next()
}

fn check_linear(
    m: &Machine,
    linear: &swarf_geom::Vec3,
    pass: usize,
    index: usize,
) -> Result<(), FiveAxisError> {
    for (k, name) in ['X', 'Y', 'Z'].into_iter().enumerate() {
        let [lo, hi] = m.linear[k];
        let v = linear[k];
        if !(v >= lo && v <= hi) {
            return Err(FiveAxisError::Unreachable {
                pass,
                index,
                axis: name.to_string(),
                message: format!("{v:.4} mm is outside the travel [{lo}, {hi}]"),
            });
        }
    }
    Ok(())
}

/// Part-frame poses of the straight joint-space move `a -> b` (module doc), from `a`
/// (excluded) to `b` (included), subdivided until each piece's tip chord is within
/// `tol` of the true tip path at its middle (at most `2^12` pieces).
///
/// # Units
/// mm, radians.
pub fn joint_path(m: &Machine, a: &Joints, b: &Joints, tool_length: f64, tol: f64) -> Vec<Pose> {
    let at = |t: f64| m.forward(&lerp(a, b, t), tool_length);
    let mut out = Vec::new();
    split(&at, 0.0, 1.0, at(0.0), at(1.0), tol.max(1e-9), 12, &mut out);
    out
}

/// The axis position at `t` of the straight joint-space move `a -> b` (every axis
/// linear in `t`, as a control without tool-centre-point management moves them).
pub fn lerp(a: &Joints, b: &Joints, t: f64) -> Joints {
    Joints {
        linear: a.linear + (b.linear - a.linear) * t,
        rotary: [
            a.rotary[0] + (b.rotary[0] - a.rotary[0]) * t,
            a.rotary[1] + (b.rotary[1] - a.rotary[1]) * t,
        ],
    }
}

/// The machine axes for one `pose` near the axis position `near` (a pose between two
/// solved ones, module doc): the branch and the turns of each angle nearest to
/// `near`'s; within `singular_cone` of the pole, `near`'s left angle and the right
/// angle solved for it, as [`solve_pass`] does on a run of singular poses.
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`FiveAxisError::Unreachable`] naming `pass`, `index` and the axis: no rotary
/// setting gives the orientation, or an angle or `X Y Z` is outside its limits.
pub fn solve_near(
    m: &Machine,
    pose: &Pose,
    near: &Joints,
    tool_length: f64,
    pass: usize,
    index: usize,
) -> Result<Joints, FiveAxisError> {
    let o = m.orientation(&pose.axis);
    let p = near.rotary;
    let rotary = if o.off_singular < m.singular_cone.sin() {
        let mut v = [0.0; 2];
        v[o.left] = p[o.left];
        v[o.right] = unwrap_near(m.right_for_left(&pose.axis, p[o.left]), p[o.right]);
        v
    } else {
        o.branches
            .iter()
            .flatten()
            .map(|c| [unwrap_near(c[0], p[0]), unwrap_near(c[1], p[1])])
            .min_by(|a, b| step(a, &p).total_cmp(&step(b, &p)))
            .ok_or_else(|| FiveAxisError::Unreachable {
                pass,
                index,
                axis: "orientation".into(),
                message: format!(
                    "no setting of {} and {} points the tool along {:?} between two \
                     reachable poses",
                    m.rotary[0].name, m.rotary[1].name, pose.axis
                ),
            })?
    };
    for (k, r) in m.rotary.iter().enumerate() {
        if let Some([lo, hi]) = r.limits
            && !(rotary[k] >= lo && rotary[k] <= hi)
        {
            return Err(FiveAxisError::Unreachable {
                pass,
                index,
                axis: r.name.to_string(),
                message: format!(
                    "{:.4} degrees, between two reachable poses, is outside the limits [{}, {}]",
                    rotary[k].to_degrees(),
                    lo.to_degrees(),
                    hi.to_degrees()
                ),
            });
        }
    }
    let linear = m.linear_for(&pose.cl, &rotary, tool_length);
    check_linear(m, &linear, pass, index)?;
    Ok(Joints { linear, rotary })
}

#[allow(clippy::too_many_arguments)]
fn split(
    at: &impl Fn(f64) -> Pose,
    t0: f64,
    t1: f64,
    p0: Pose,
    p1: Pose,
    tol: f64,
    depth: u32,
    out: &mut Vec<Pose>,
) {
    let tm = 0.5 * (t0 + t1);
    let pm = at(tm);
    let chord_mid = p0.cl + (p1.cl - p0.cl) * 0.5;
    if depth == 0 || (pm.cl - chord_mid).norm() <= tol {
        out.push(p1);
        return;
    }
    split(at, t0, tm, p0, pm, tol, depth - 1, out);
    split(at, tm, t1, pm, p1, tol, depth - 1, out);
}

#[cfg(test)]
mod tests {
    use super::super::tests::TRUNNION;
    use super::*;
    use swarf_geom::{Point3, Vec3};

    fn trunnion() -> Machine {
        Machine::parse(TRUNNION, "m").unwrap()
    }

    fn pose(tilt_x: f64, tilt_y: f64, x: f64) -> Pose {
        Pose::new(Point3::new(x, 0.0, 0.0), Vec3::new(tilt_y, tilt_x, 1.0)).unwrap()
    }

    fn assert_reaches(m: &Machine, poses: &[Pose], js: &[Joints], axis_tol: f64) {
        for (p, j) in poses.iter().zip(js) {
            let f = m.forward(j, 0.0);
            assert!((f.cl - p.cl).norm() < 1e-9);
            assert!(
                (f.axis - p.axis).norm() < axis_tol,
                "{:?} vs {:?}",
                f.axis,
                p.axis
            );
        }
    }

    #[test]
    fn pass_through_the_pole_keeps_c_and_turns_a_through_zero() {
        let m = trunnion();
        let poses: Vec<Pose> = (-20..=20)
            .map(|k| pose(0.01 * k as f64, 0.0, k as f64))
            .collect();
        let js = solve_pass(&m, &poses, None, 0.0, 0).unwrap();
        assert_reaches(&m, &poses, &js, 2.0 * m.singular_cone);
        let c0 = js[0].rotary[1];
        for w in js.windows(2) {
            assert!((w[1].rotary[1] - c0).abs() < 1e-9, "C moved");
            assert!((w[1].rotary[0] - w[0].rotary[0]).abs() < 0.011, "A jumped");
        }
        assert!(js[0].rotary[0] * js[40].rotary[0] < 0.0, "A changes sign");
    }

    #[test]
    fn pass_near_the_pole_turns_c_without_jumps() {
        // The axis passes 0.2 degree beside the pole: C must turn half a turn, smoothly.
        let m = trunnion();
        let off = 0.2f64.to_radians().tan();
        let poses: Vec<Pose> = (-50..=50)
            .map(|k| pose(0.002 * k as f64, off, k as f64))
            .collect();
        let js = solve_pass(&m, &poses, None, 0.0, 0).unwrap();
        assert_reaches(&m, &poses, &js, 1e-9);
        let turn = (js[100].rotary[1] - js[0].rotary[1]).abs();
        assert!((turn - PI).abs() < 0.1, "C turned {turn}");
        // C follows the azimuth of the axis step by step (never more, never the long way).
        for (w, p) in js.windows(2).zip(poses.windows(2)) {
            let az = |q: &Pose| q.axis.y.atan2(q.axis.x);
            let d_az = unwrap_near(az(&p[1]) - az(&p[0]), 0.0).abs();
            assert!(
                (w[1].rotary[1] - w[0].rotary[1]).abs() <= d_az + 1e-9,
                "C jumped"
            );
            assert!((w[1].rotary[0] - w[0].rotary[0]).abs() < 0.01, "A jumped");
        }
    }

    #[test]
    fn continuous_c_never_unwinds_and_limits_are_reported() {
        let m = trunnion();
        // The axis circles the pole three times at 30 degrees of tilt: C keeps turning.
        let poses: Vec<Pose> = (0..=360)
            .map(|k| {
                let az = 3.0 * TAU * k as f64 / 360.0;
                let t = 0.5f64;
                Pose::new(
                    Point3::origin(),
                    Vec3::new(t.sin() * az.cos(), t.sin() * az.sin(), t.cos()),
                )
                .unwrap()
            })
            .collect();
        let js = solve_pass(&m, &poses, None, 0.0, 3).unwrap();
        assert_reaches(&m, &poses, &js, 1e-9);
        for w in js.windows(2) {
            assert!((w[1].rotary[1] - w[0].rotary[1]).abs() < 0.1);
        }
        assert!((js[360].rotary[1] - js[0].rotary[1]).abs() > 5.0 * PI);
        // A limited to [0, 20] degrees cannot tilt 30 degrees.
        let tight = Machine::parse(&TRUNNION.replace("[-120, 120]", "[0, 20]"), "m").unwrap();
        let e = solve_pass(&tight, &poses, None, 0.0, 3).unwrap_err();
        assert!(e.to_string().starts_with("pass 3, point 0: axis A:"), "{e}");
        let far = [Pose::new(Point3::new(5000.0, 0.0, 0.0), Vec3::z()).unwrap()];
        let e = solve_pass(&m, &far, None, 0.0, 1).unwrap_err();
        assert!(e.to_string().contains("axis X"), "{e}");
    }

    #[test]
    fn joint_path_bends_with_the_table() {
        let m = trunnion();
        let a = Joints {
            linear: Vec3::new(0.0, 0.0, 0.0),
            rotary: [0.0, 0.0],
        };
        let b = Joints {
            linear: Vec3::new(0.0, 0.0, 0.0),
            rotary: [0.0, PI / 2.0],
        };
        let path = joint_path(&m, &a, &b, 0.0, 1e-3);
        assert!(path.len() > 8);
        // Turning C about (3, -4) moves the fixed tip on a circle in the part frame.
        let centre = Point3::new(3.0 - 10.0, -4.0 + 20.0, 0.0);
        let r0 = (m.forward(&a, 0.0).cl - centre).xy().norm();
        for p in &path {
            assert!(((p.cl - centre).xy().norm() - r0).abs() < 1e-9);
        }
        assert_eq!(*path.last().unwrap(), m.forward(&b, 0.0));
    }
}
