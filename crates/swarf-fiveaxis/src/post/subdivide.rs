//! Tool-centre-point motion for controls without it: a move of the tool path written
//! as as many blocks as it takes for the machine's joint-linear motion to keep the tool
//! tip on the planned chord.
//!
//! **Why.** Between two poses the tool path (and the APT CL file, and a control with
//! tool-centre-point management) moves the tip along the chord `c(t) = c_a + t (c_b -
//! c_a)` with the axis on the great circle, `a(t) = slerp(a_a, a_b, t)`: what thesis
//! 000 assumes of consecutive positions (ch. 3, "the movement of the tool between these
//! positions is assumed to be linear") when it builds the swept surface and checks for
//! gouges. A control without it (LinuxCNC trivkins, `rs274`) moves every axis linearly,
//! `J(s) = J_a + s (J_b - J_a)`, and the tip over the part is the forward kinematics of
//! `J(s)`: a curve whenever a rotary axis turns. Turning by `dθ` about a line at `r` from
//! the tip moves it on an arc of sagitta `r (1 - cos(dθ / 2)) ≈ r dθ² / 8`.
//!
//! **How.** The move is cut into `n` equal steps of the planned motion: poses
//! `P(k/n) = (c(k/n), a(k/n))`, `k = 1 .. n - 1`, each solved by the inverse kinematics
//! near `J(k/n)` ([`solve_near`]: same branch and turns, so no axis jumps), and written
//! as one block each. Splitting a turn into `n` divides the sagitta by about `n²`, so
//! from the whole move's deviation `d_1` the first try is `n = ceil(sqrt(d_1 / tol))`;
//! for a turn by `θ` about a line at `r` that is the sagitta formula `n = ceil(θ / (2
//! acos(1 - tol / r)))` to first order. `n` grows (by `sqrt` of the worst ratio, at
//! least by one) until every block is within both tolerances: the tip within
//! [`PathTol::tip`] of the block's chord and the axis within [`PathTol::angle`] of the
//! great-circle arc between the block's end axes. Each block is measured at
//! `SAMPLES - 1` interior points of its joint-linear motion (the bow of a short
//! block is a parabola in `s`, largest near the middle).
//!
//! **Bound.** At most [`MAX_BLOCKS`] blocks per move. A move that still strays at the
//! bound (only where a rotary axis turns a large angle for a tiny change of the tool
//! axis, beside a singular pose) is written as [`MAX_BLOCKS`] blocks anyway, flagged
//! [`Subdivided::at_bound`], with its deviations in its blocks: the machine still
//! reaches every planned pose exactly.
//!
//! **Feed.** Each block's [`Deviation::length`] is the length of the tip's path over
//! the part (the polyline through the samples, within the tolerance of the chord), so
//! that G93 times it for the programmed feed of the tip.

use crate::error::FiveAxisError;
use crate::machine::Machine;
use crate::machine::joints::{lerp, solve_near};
use crate::machine::kinematics::Joints;
use swarf_geom::Vec3;
use swarf_geom::math::{point_segment_distance, slerp};
use swarf_geom::tol::PARALLEL_COS;
use swarf_tool::Pose;

/// The joint-linear motion of a block is sampled at `k / SAMPLES`, `k = 1 ..
/// SAMPLES - 1`.
const SAMPLES: usize = 8;

/// Most blocks one move is written as (module doc, bound).
pub const MAX_BLOCKS: usize = 1024;

/// How close the machine's motion must keep to the planned motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTol {
    /// Largest distance of the tip from the planned chord, mm (`f64::INFINITY`: any).
    pub tip: f64,
    /// Largest angle of the tool axis from the planned great circle, radians
    /// (`f64::INFINITY`: any).
    pub angle: f64,
}

/// How far the joint-linear motion of one block strays from its planned motion.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviation {
    /// Largest distance of the tip from the block's chord, mm.
    pub tip: f64,
    /// Largest angle of the tool axis from the great-circle arc between the block's
    /// end axes, radians.
    pub angle: f64,
    /// Length of the tip's path over the part, mm.
    pub length: f64,
}

impl Deviation {
    /// The larger of the two deviations as a fraction of their tolerances.
    pub fn ratio(&self, tol: &PathTol) -> f64 {
        (self.tip / tol.tip).max(self.angle / tol.angle)
    }
}

/// One written block: where the move's piece ends and how it gets there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block {
    /// The planned pose the block ends at.
    pub pose: Pose,
    /// The machine axes there.
    pub joints: Joints,
    /// The joint-linear motion from the previous block's end.
    pub deviation: Deviation,
}

/// A move as the blocks the post writes.
#[derive(Debug, Clone, PartialEq)]
pub struct Subdivided {
    /// The blocks, the last one ending at the move's end.
    pub blocks: Vec<Block>,
    /// The deviation of the move written as one block.
    pub unsplit: Deviation,
    /// The move still strays beyond the tolerance at [`MAX_BLOCKS`] blocks.
    pub at_bound: bool,
}

/// What the subdivision between poses did to a program ([`super`] module doc).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PostReport {
    /// Moves inside passes (cutting).
    pub cutting: Stray,
    /// Link moves (approach, retract, the rapids between passes).
    pub links: Stray,
}

/// How far one kind of move strays from the planned motion, and the blocks inserted to
/// bring it back.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stray {
    /// Moves.
    pub moves: usize,
    /// Blocks inserted between the moves' poses.
    pub inserted: usize,
    /// Moves written at the bound of [`MAX_BLOCKS`] blocks, still beyond
    /// the tolerances.
    pub at_bound: usize,
    /// Largest distance of the tip from its chord with one block per move, mm.
    pub unsplit_tip: f64,
    /// Largest angle of the axis from its great circle with one block per move,
    /// radians.
    pub unsplit_angle: f64,
    /// Largest distance of the tip from its chord in the written blocks, mm.
    pub tip: f64,
    /// Largest angle of the axis from its great circle in the written blocks, radians.
    pub angle: f64,
}

impl Stray {
    pub(crate) fn add(&mut self, s: &Subdivided) {
        self.moves += 1;
        self.inserted += s.blocks.len() - 1;
        self.at_bound += usize::from(s.at_bound);
        self.unsplit_tip = self.unsplit_tip.max(s.unsplit.tip);
        self.unsplit_angle = self.unsplit_angle.max(s.unsplit.angle);
        for b in &s.blocks {
            self.tip = self.tip.max(b.deviation.tip);
            self.angle = self.angle.max(b.deviation.angle);
        }
    }
}

/// The deviation of the joint-linear motion `a -> b` from the chord and great circle
/// between its ends (module doc).
///
/// # Units
/// mm, radians.
pub fn measure(m: &Machine, a: &Joints, b: &Joints, tool_length: f64) -> Deviation {
    let (pa, pb) = (m.forward(a, tool_length), m.forward(b, tool_length));
    if a.rotary == b.rotary {
        // A pure translation of the machine: the tip runs along the chord.
        return Deviation {
            tip: 0.0,
            angle: 0.0,
            length: (pb.cl - pa.cl).norm(),
        };
    }
    let mut out = Deviation::default();
    let mut last = pa.cl;
    for k in 1..SAMPLES {
        let q = m.forward(&lerp(a, b, k as f64 / SAMPLES as f64), tool_length);
        out.tip = out.tip.max(point_segment_distance(&q.cl, &pa.cl, &pb.cl));
        out.angle = out.angle.max(off_arc(&q.axis, &pa.axis, &pb.axis));
        out.length += (q.cl - last).norm();
        last = q.cl;
    }
    out.length += (pb.cl - last).norm();
    out
}

/// The blocks for the move from `from` to `to` (planned pose and solved axes at each
/// end) within `tol` (module doc).
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`FiveAxisError::Unreachable`] naming `pass`, `index` and the axis when a pose
/// between the two is out of the machine's reach.
pub fn subdivide(
    m: &Machine,
    from: (&Pose, &Joints),
    to: (&Pose, &Joints),
    tool_length: f64,
    tol: &PathTol,
    pass: usize,
    index: usize,
) -> Result<Subdivided, FiveAxisError> {
    let unsplit = measure(m, from.1, to.1, tool_length);
    let mut out = Subdivided {
        blocks: vec![Block {
            pose: *to.0,
            joints: *to.1,
            deviation: unsplit,
        }],
        unsplit,
        at_bound: false,
    };
    let first = unsplit.ratio(tol);
    if first <= 1.0 {
        return Ok(out);
    }
    let mut n = (first.sqrt().ceil() as usize).clamp(2, MAX_BLOCKS);
    loop {
        let blocks = split(m, from, to, n, tool_length, pass, index)?;
        let worst = blocks
            .iter()
            .map(|b| b.deviation.ratio(tol))
            .fold(0.0, f64::max);
        if worst <= 1.0 || n == MAX_BLOCKS {
            out.at_bound = worst > 1.0;
            out.blocks = blocks;
            return Ok(out);
        }
        let grown = (n as f64 * worst.sqrt()).ceil() as usize;
        n = grown.max(n + 1).min(MAX_BLOCKS);
    }
}

/// The move in `n` equal steps of the planned motion.
fn split(
    m: &Machine,
    from: (&Pose, &Joints),
    to: (&Pose, &Joints),
    n: usize,
    tool_length: f64,
    pass: usize,
    index: usize,
) -> Result<Vec<Block>, FiveAxisError> {
    let mut out = Vec::with_capacity(n);
    let mut prev = *from.1;
    for k in 1..=n {
        let t = k as f64 / n as f64;
        let (pose, joints) = if k == n {
            (*to.0, *to.1)
        } else {
            let pose = Pose {
                cl: from.0.cl + (to.0.cl - from.0.cl) * t,
                axis: slerp(&from.0.axis, &to.0.axis, t),
            };
            let near = lerp(from.1, to.1, t);
            let j = solve_near(m, &pose, &near, tool_length, pass, index)?;
            (pose, j)
        };
        out.push(Block {
            pose,
            joints,
            deviation: measure(m, &prev, &joints, tool_length),
        });
        prev = joints;
    }
    Ok(out)
}

/// The angle between two vectors, radians (accurate for small angles).
fn angle(u: &Vec3, v: &Vec3) -> f64 {
    u.cross(v).norm().atan2(u.dot(v))
}

/// Angle from the unit vector `v` to the great-circle arc from `a` to `b`.
fn off_arc(v: &Vec3, a: &Vec3, b: &Vec3) -> f64 {
    let normal = a.cross(b);
    let sin = normal.norm();
    if sin <= PARALLEL_COS {
        return angle(v, a);
    }
    let n = normal / sin;
    let across = v.dot(&n);
    let in_plane = v - n * across;
    let inside = a.cross(&in_plane).dot(&n) >= 0.0 && in_plane.cross(b).dot(&n) >= 0.0;
    if inside {
        across.abs().min(1.0).asin()
    } else {
        angle(v, a).min(angle(v, b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::PI;
    use swarf_geom::Point3;

    /// An A/C table with both axes through the origin (the A tilts about X, the C
    /// turns on it about the part's Z).
    const TRUNNION: &str = r#"
kind = "table-table"
[linear]
x = [-1000, 1000]
y = [-1000, 1000]
z = [-1000, 1000]
[[rotary]]
name = "A"
on = "table"
axis = [1, 0, 0]
point = [0, 0, 0]
limits = [-30, 120]
[[rotary]]
name = "C"
on = "table"
axis = [0, 0, 1]
point = [0, 0, 0]
continuous = true
"#;

    fn trunnion() -> Machine {
        Machine::parse(TRUNNION, "m").unwrap()
    }

    /// The pose at azimuth `phi` on a cone of half-angle `tilt` about Z, the tip at
    /// `r` from the C axis (also at azimuth `phi`, height `z`).
    fn on_cone(phi: f64, tilt: f64, r: f64, z: f64) -> Pose {
        Pose {
            cl: Point3::new(r * phi.cos(), r * phi.sin(), z),
            axis: Vec3::new(tilt.sin() * phi.cos(), tilt.sin() * phi.sin(), tilt.cos()),
        }
    }

    fn solve(m: &Machine, p: &Pose, near: [f64; 2]) -> Joints {
        let near = Joints {
            linear: Vec3::zeros(),
            rotary: near,
        };
        solve_near(m, p, &near, 0.0, 0, 0).unwrap()
    }

    #[test]
    fn a_turn_of_c_is_cut_by_the_sagitta_formula() {
        // Two poses a turn of C apart: the machine's X Y Z and A stay, C turns by theta,
        // and the tip bows on an arc of radius r about the C axis.
        let m = trunnion();
        let tol = PathTol {
            tip: 0.01,
            angle: f64::INFINITY,
        };
        for (theta_deg, r, z) in [(10.0, 100.0, 5.0), (7.0, 60.0, 30.0), (40.0, 25.0, 0.0)] {
            let theta: f64 = f64::to_radians(theta_deg);
            let tilt = 0.3;
            let (pa, pb) = (on_cone(0.0, tilt, r, z), on_cone(theta, tilt, r, z));
            let ja = solve(&m, &pa, [0.3, 0.0]);
            let jb = solve(&m, &pb, ja.rotary);
            assert!((ja.linear - jb.linear).norm() < 1e-9, "X Y Z stay");
            assert!(((jb.rotary[1] - ja.rotary[1]).abs() - theta).abs() < 1e-12);
            assert_eq!(ja.rotary[0], jb.rotary[0]);
            let s = subdivide(&m, (&pa, &ja), (&pb, &jb), 0.0, &tol, 0, 0).unwrap();
            // One block: the arc's sagitta.
            let sagitta = r * (1.0 - (theta / 2.0).cos());
            assert!((s.unsplit.tip - sagitta).abs() < 1e-9, "{}", s.unsplit.tip);
            let n = (theta / (2.0 * (1.0 - tol.tip / r).acos())).ceil() as usize;
            assert_eq!(s.blocks.len(), n, "theta {theta_deg} r {r}");
            assert!(!s.at_bound);
            for b in &s.blocks {
                assert!(b.deviation.tip <= tol.tip, "{:?}", b.deviation);
            }
            // One block fewer is not enough: the count is the least.
            let fewer = split(&m, (&pa, &ja), (&pb, &jb), n - 1, 0.0, 0, 0).unwrap();
            assert!(fewer.iter().any(|b| b.deviation.tip > tol.tip));
        }
    }

    #[test]
    fn blocks_end_on_the_planned_motion_and_sum_to_its_length() {
        let m = trunnion();
        let pa = on_cone(0.2, 0.5, 80.0, 10.0);
        let pb = Pose {
            cl: Point3::new(60.0, 70.0, 20.0),
            axis: on_cone(1.4, 0.3, 1.0, 0.0).axis,
        };
        let ja = solve(&m, &pa, [0.5, 0.2]);
        let jb = solve(&m, &pb, ja.rotary);
        let tol = PathTol {
            tip: 0.005,
            angle: 0.02f64.to_radians(),
        };
        let s = subdivide(&m, (&pa, &ja), (&pb, &jb), 0.0, &tol, 0, 0).unwrap();
        assert!(s.blocks.len() > 10, "{}", s.blocks.len());
        assert!(s.unsplit.tip > 1.0, "{:?}", s.unsplit);
        let chord = pb.cl - pa.cl;
        let mut length = 0.0;
        let mut prev = ja;
        for (k, b) in s.blocks.iter().enumerate() {
            let t = (k + 1) as f64 / s.blocks.len() as f64;
            let f = m.forward(&b.joints, 0.0);
            assert!((f.cl - (pa.cl + chord * t)).norm() < 1e-9);
            assert!((f.axis - slerp(&pa.axis, &pb.axis, t)).norm() < 1e-9);
            assert!(b.deviation.ratio(&tol) <= 1.0);
            // An independent check of the block: 64 samples of the joint-linear motion.
            let (fa, fb) = (m.forward(&prev, 0.0).cl, f.cl);
            for i in 1..64 {
                let q = m.forward(&lerp(&prev, &b.joints, i as f64 / 64.0), 0.0).cl;
                assert!(point_segment_distance(&q, &fa, &fb) <= tol.tip * 1.01);
            }
            let steps = (b.joints.rotary[1] - prev.rotary[1]).abs();
            assert!(steps < 0.1, "C jumped {steps}");
            length += b.deviation.length;
            prev = b.joints;
        }
        assert!((length - chord.norm()).abs() < 1e-3 * chord.norm());
    }

    #[test]
    fn translations_and_tight_bounds() {
        let m = trunnion();
        let pa = on_cone(0.0, 0.4, 50.0, 0.0);
        let ja = solve(&m, &pa, [0.4, 0.0]);
        let pb = Pose {
            cl: pa.cl + Vec3::new(3.0, -4.0, 0.0),
            axis: pa.axis,
        };
        let jb = solve(&m, &pb, ja.rotary);
        let tol = PathTol {
            tip: 1e-6,
            angle: 1e-9,
        };
        let s = subdivide(&m, (&pa, &ja), (&pb, &jb), 0.0, &tol, 0, 0).unwrap();
        assert_eq!(s.blocks.len(), 1);
        assert!((s.unsplit.length - 5.0).abs() < 1e-12);
        // Half a turn of C at 50 mm cannot be brought to 1e-9 mm: the bound.
        let pc = on_cone(PI, 0.4, 50.0, 0.0);
        let jc = solve(&m, &pc, ja.rotary);
        let tol = PathTol {
            tip: 1e-9,
            angle: f64::INFINITY,
        };
        let s = subdivide(&m, (&pa, &ja), (&pc, &jc), 0.0, &tol, 0, 0).unwrap();
        assert!(s.at_bound);
        assert_eq!(s.blocks.len(), MAX_BLOCKS);
    }

    const MACHINES: [&str; 3] = [
        include_str!("../../../../machines/xyzac-trunnion.toml"),
        include_str!("../../../../machines/xyzbc-head.toml"),
        include_str!("../../../../machines/xyzbc-table-head.toml"),
    ];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// On every machine, the blocks of a move between two random poses (away from
        /// the singular cone, where the axis is only near the plan) end on the
        /// planned motion, and 64 samples of each block's joint-linear motion (an
        /// independent, finer measure) stay within the tolerances.
        #[test]
        fn blocks_keep_the_tip_on_the_chord_on_every_machine(
            which in 0usize..3,
            x in -60.0..60.0f64, y in -60.0..60.0f64, z in 0.0..40.0f64,
            dx in -4.0..4.0f64, dy in -4.0..4.0f64, dz in -2.0..2.0f64,
            az in -3.1..3.1f64, tilt in 0.05..0.7f64,
            d_az in -0.5..0.5f64, d_tilt in -0.04..0.1f64,
        ) {
            let m = Machine::parse(MACHINES[which], "m").unwrap();
            let tool_length = 80.0;
            let pa = on_cone(az, tilt, 0.0, 0.0);
            let pa = Pose { cl: Point3::new(x, y, z), axis: pa.axis };
            let pb = on_cone(az + d_az, tilt + d_tilt, 0.0, 0.0);
            let pb = Pose { cl: pa.cl + Vec3::new(dx, dy, dz), axis: pb.axis };
            let js = crate::machine::joints::solve_pass(&m, &[pa, pb], None, tool_length, 0).unwrap();
            let tol = PathTol { tip: 0.01, angle: 0.05f64.to_radians() };
            let s = subdivide(&m, (&pa, &js[0]), (&pb, &js[1]), tool_length, &tol, 0, 0).unwrap();
            prop_assert!(!s.at_bound);
            let n = s.blocks.len();
            let mut prev = js[0];
            for (k, b) in s.blocks.iter().enumerate() {
                let t = (k + 1) as f64 / n as f64;
                let f = m.forward(&b.joints, tool_length);
                prop_assert!((f.cl - (pa.cl + (pb.cl - pa.cl) * t)).norm() < 1e-9);
                prop_assert!((f.axis - slerp(&pa.axis, &pb.axis, t)).norm() < 1e-9);
                let fa = m.forward(&prev, tool_length);
                for i in 1..64 {
                    let q = m.forward(&lerp(&prev, &b.joints, i as f64 / 64.0), tool_length);
                    let tip = point_segment_distance(&q.cl, &fa.cl, &f.cl);
                    let angle = off_arc(&q.axis, &fa.axis, &f.axis);
                    prop_assert!(tip <= tol.tip * 1.02, "block {k}/{n}: {tip}");
                    prop_assert!(angle <= tol.angle * 1.02, "block {k}/{n}: {angle}");
                }
                prev = b.joints;
            }
        }
    }

    #[test]
    fn off_arc_measures_angles_to_the_arc() {
        let (a, b) = (Vec3::x(), Vec3::y());
        let v = Vec3::new(1.0, 1.0, 0.2).normalize();
        assert!((off_arc(&v, &a, &b) - 0.2f64.atan2(2f64.sqrt())).abs() < 1e-12);
        // Beyond the end of the arc: the angle to the nearer end.
        let w = Vec3::new(1.0, -0.1, 0.0).normalize();
        assert!((off_arc(&w, &a, &b) - 0.1f64.atan()).abs() < 1e-12);
        assert!((slerp(&a, &b, 0.5) - Vec3::new(1.0, 1.0, 0.0).normalize()).norm() < 1e-15);
    }
}
