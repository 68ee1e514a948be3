//! The velocity of the tool at a pose of a path, as the generating curves see it.
//!
//! Between consecutive poses `S` and `D` the tool tip moves on the straight line
//! `cl(t) = cl_S + t d`, `d = cl_D - cl_S`, and the axis turns on the great circle
//! `a(t) = slerp(a_S, a_D, t)`: the motion a control with tool-centre-point management
//! makes between two CL records, and the one the NC readers and the dexel verifier use.
//! The tool is a solid of revolution, so its spin about its own axis moves surface
//! points along the surface and never changes an envelope; what remains is a rigid
//! velocity field, a twist: `v(p) = v_tip + w x (p - cl)` with `w = a x a'` and the
//! slerp tangent `a'(0) = theta (a_D - cos(theta) a_S) / sin(theta)` (at the end,
//! `theta (cos(theta) a_D - a_S) / sin(theta)`).
//!
//! At a pose inside a pass the arriving and leaving moves give two twists; the pose
//! gets their blend per mm of travel with Bessel's weights (each chord weighted by the
//! length of the other, the three-point tangent of a smooth path, exact to second
//! order). This makes the generating curve at a pose that of the smooth motion through
//! the poses: a tool turning about a point on its axis in equal steps gets exactly the
//! rotation about that point, and the generating circles of thesis 000 §3.2 come out
//! exact. Thesis eqs. 5.8 and 5.14 use instead the chord `Delta C` of one move, the
//! velocity at the middle of the move, which rotates the generating points half a step
//! and, at the side meridians, tilts them by the chord's rise along the axis. At the
//! ends of a pass the one-sided twist is used.

use serde::{Deserialize, Serialize};
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// A rigid velocity field: `v(p) = linear + angular x (p - cl)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    /// Velocity of the tool tip (per mm of travel, so dimensionless).
    pub linear: Vec3,
    /// Angular velocity without the spin about the axis, rad per mm of travel.
    pub angular: Vec3,
}

impl Twist {
    /// The velocity of the tool point `p` when the tip is at `cl`.
    pub fn velocity(&self, cl: &Point3, p: &Point3) -> Vec3 {
        self.linear + self.angular.cross(&(p - cl))
    }

    /// The same motion run backward.
    pub fn reversed(&self) -> Twist {
        Twist {
            linear: -self.linear,
            angular: -self.angular,
        }
    }

    fn scaled(&self, k: f64) -> Twist {
        Twist {
            linear: self.linear * k,
            angular: self.angular * k,
        }
    }

    fn plus(&self, o: &Twist) -> Twist {
        Twist {
            linear: self.linear + o.linear,
            angular: self.angular + o.angular,
        }
    }
}

/// Tangents of `slerp(a, b, t)` at `t = 0` and `t = 1` (unit axes).
pub fn slerp_tangents(a: &Vec3, b: &Vec3) -> (Vec3, Vec3) {
    let cos = a.dot(b).clamp(-1.0, 1.0);
    let theta = cos.acos();
    let k = if theta < 1e-8 {
        1.0
    } else {
        theta / theta.sin()
    };
    ((b - cos * a) * k, (cos * b - a) * k)
}

/// The twist of the move `s -> d` per unit of its parameter, at its start or end.
pub fn move_twist(s: &Pose, d: &Pose, at_end: bool) -> Twist {
    let (t0, t1) = slerp_tangents(&s.axis, &d.axis);
    let (axis, tangent) = if at_end { (d.axis, t1) } else { (s.axis, t0) };
    Twist {
        linear: d.cl - s.cl,
        angular: axis.cross(&tangent),
    }
}

/// The twist at pose `i` of a pass per mm of travel (module doc); zero for a lone pose.
pub fn pose_twist(poses: &[Pose], i: usize) -> Twist {
    let zero = Twist {
        linear: Vec3::zeros(),
        angular: Vec3::zeros(),
    };
    let arrive = (i > 0 && i < poses.len()).then(|| {
        let h = (poses[i].cl - poses[i - 1].cl).norm().max(LENGTH_EPS);
        (
            move_twist(&poses[i - 1], &poses[i], true).scaled(1.0 / h),
            h,
        )
    });
    let leave = (i + 1 < poses.len()).then(|| {
        let h = (poses[i + 1].cl - poses[i].cl).norm().max(LENGTH_EPS);
        (
            move_twist(&poses[i], &poses[i + 1], false).scaled(1.0 / h),
            h,
        )
    });
    match (arrive, leave) {
        (Some((ta, ha)), Some((tl, hl))) => {
            ta.scaled(hl / (ha + hl)).plus(&tl.scaled(ha / (ha + hl)))
        }
        (Some((t, _)), None) | (None, Some((t, _))) => t,
        (None, None) => zero,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The motion of the module doc at parameter `t` for the point with offset `w`
    /// (in the frame moving with the axis, no spin) from the tip.
    fn point(s: &Pose, d: &Pose, t: f64, along: f64, across: &Vec3) -> Point3 {
        let th = s.axis.dot(&d.axis).clamp(-1.0, 1.0).acos();
        let a = if th < 1e-12 {
            s.axis
        } else {
            (((1.0 - t) * th).sin() * s.axis + (t * th).sin() * d.axis) / th.sin()
        };
        // Parallel transport of `across` from s.axis to a (rotation about s.axis x a).
        let k = s.axis.cross(&a);
        let sin = k.norm();
        let c = s.axis.dot(&a);
        let moved = if sin < 1e-15 {
            *across
        } else {
            let k = k / sin;
            across * c + k.cross(across) * sin + k * k.dot(across) * (1.0 - c)
        };
        s.cl + t * (d.cl - s.cl) + along * a + moved
    }

    #[test]
    fn move_twist_is_the_derivative_of_the_motion() {
        let s = Pose::new(Point3::new(1.0, 2.0, 3.0), Vec3::new(0.1, -0.2, 1.0)).unwrap();
        let d = Pose::new(Point3::new(1.8, 2.5, 3.1), Vec3::new(0.3, -0.1, 1.0)).unwrap();
        let across = s.axis.cross(&Vec3::x()).normalize() * 4.0;
        let h = 1e-7;
        let p0 = point(&s, &d, 0.0, 2.0, &across);
        let fd = (point(&s, &d, h, 2.0, &across) - p0) / h;
        let v = move_twist(&s, &d, false).velocity(&s.cl, &p0);
        assert!((fd - v).norm() < 1e-5, "{fd:?} {v:?}");
    }

    #[test]
    fn equal_steps_about_a_point_give_a_pure_rotation() {
        let o = Point3::new(0.0, 0.0, 50.0);
        let poses: Vec<Pose> = (0..3)
            .map(|k| {
                let t = 0.1 * k as f64;
                let a = Vec3::new(t.sin(), 0.0, t.cos());
                Pose {
                    cl: o - 30.0 * a,
                    axis: a,
                }
            })
            .collect();
        let tw = pose_twist(&poses, 1);
        // Every point of the tool moves normal to its offset from o, up to the ratio
        // (theta / 2) / sin(theta / 2) - 1 ~ theta^2 / 24 between the chord and the arc
        // (the tip's speed per mm along the chord against the turn of the axis).
        for p in [poses[1].cl, poses[1].cl + Vec3::new(3.0, 4.0, 1.0)] {
            let v = tw.velocity(&poses[1].cl, &p);
            let cos = v.dot(&(p - o)) / (v.norm() * (p - o).norm());
            assert!(cos.abs() < 0.1f64.powi(2) / 20.0, "{cos}");
        }
        assert!(tw.linear.dot(&(poses[1].cl - o)).abs() < 1e-12);
        assert_eq!(pose_twist(&poses[..1], 0).linear, Vec3::zeros());
    }
}
