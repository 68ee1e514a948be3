//! Forward and inverse kinematics of the five-axis chains of [`super::Machine`].
//!
//! A rotary axis `k` with unit direction `w_k` through the point `p_k` (both at home)
//! turns by `theta_k` as the rigid motion `T_k(x) = p_k + R(w_k, theta_k)(x - p_k)`,
//! `R` by Rodrigues' formula. Chains compose as products of exponentials (Murray, Li
//! and Sastry, "A Mathematical Introduction to Robotic Manipulation", 1994, ch. 3): the
//! axis on the base, listed first, is applied last.
//!
//! **Forward.** Head axes carry the tool: with the linear axes at `L` (the head's
//! reference point; for a table-table machine, the tool tip under G43), the tip is
//! `L + T_h(t)` with `t = -(pivot + tool length) Z` and the tool axis `R_h Z`. Table
//! axes carry the part: a part point `x` is at `T_w(x + part_origin)`. So the pose in
//! the part frame is `cl = T_w^-1(L + T_h(t)) - part_origin`, `a = R_w^-1 R_h Z`.
//!
//! **Inverse.** The orientation equation `R_w^-1 R_h Z = a` is a product of two
//! rotations about fixed axes (table axes reversed and negated, then head axes):
//! `exp(w_1 t_1) exp(w_2 t_2) Z = a`. This is Paden-Kahan subproblem 2 (ibid. §3.3):
//! the intermediate vector `c = exp(w_2 t_2) Z = exp(-w_1 t_1) a` satisfies
//! `w_1.c = w_1.a`, `w_2.c = w_2.Z`, `|c| = 1`, so with `k = w_1.w_2`
//! `c = alpha w_1 + beta w_2 + gamma (w_1 x w_2)`,
//! `alpha = (k w_2.Z - w_1.a) / (k^2 - 1)`, `beta = (k w_1.a - w_2.Z) / (k^2 - 1)`,
//! `gamma^2 = (1 - alpha^2 - beta^2 - 2 alpha beta k) / |w_1 x w_2|^2`; the two signs of
//! `gamma` are the two branches, `gamma^2 < 0` an unreachable orientation. Each angle is
//! then subproblem 1, `theta = atan2(w.(u' x v'), u'.v')` with `u'`, `v'` the parts of the
//! vectors across `w`. Where `a` is parallel to `w_1` (the tool along the C axis of an
//! A/C table), `c` lies on `w_1` and `t_1` is free: the singular pose. The linear axes
//! follow from the angles: `L = T_w(cl + part_origin) - T_h(t)`.

use super::{Machine, Mount};
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// Machine axis positions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joints {
    /// `X Y Z`, mm.
    pub linear: Vec3,
    /// The rotary angles in file order, radians.
    pub rotary: [f64; 2],
}

/// Rotation of `v` about the unit axis `w` by `theta` (Rodrigues).
pub fn rotate(w: &Vec3, theta: f64, v: &Vec3) -> Vec3 {
    let (s, c) = theta.sin_cos();
    v * c + w.cross(v) * s + w * (w.dot(v) * (1.0 - c))
}

/// The angle that turns `u` into `v` about the unit axis `w` (subproblem 1, on the parts
/// across `w`); `None` when either part is (nearly) zero.
pub fn turn_angle(w: &Vec3, u: &Vec3, v: &Vec3) -> Option<f64> {
    let up = u - w * w.dot(u);
    let vp = v - w * w.dot(v);
    if up.norm() < 1e-12 || vp.norm() < 1e-12 {
        return None;
    }
    Some(w.dot(&up.cross(&vp)).atan2(up.dot(&vp)))
}

/// The orientation part of the inverse: the two rotation factors and their solutions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orientation {
    /// Rotary index of the left factor (the one free at the singular pose).
    pub left: usize,
    /// Rotary index of the right factor.
    pub right: usize,
    /// Branches as rotary angles in file order (0, 1 or 2 of them).
    pub branches: [Option<[f64; 2]>; 2],
    /// Sine of the angle between the tool axis and the left factor's axis.
    pub off_singular: f64,
}

impl Machine {
    /// Rotary indices of the table axes and of the head axes, outermost first.
    fn chains(&self) -> (Vec<usize>, Vec<usize>) {
        let on = |m: Mount| {
            (0..2)
                .filter(|&k| self.rotary[k].on == m)
                .collect::<Vec<_>>()
        };
        (on(Mount::Table), on(Mount::Head))
    }

    /// `T_k` applied to `x` for the chain `idx` (outermost first) at `angles`.
    fn apply(&self, idx: &[usize], angles: &[f64; 2], x: &Vec3) -> Vec3 {
        idx.iter().rev().fold(*x, |x, &k| {
            let r = &self.rotary[k];
            let p = r.point.coords;
            p + rotate(&r.axis, angles[k], &(x - p))
        })
    }

    /// `T^-1` of the chain `idx` applied to `x`.
    fn apply_inverse(&self, idx: &[usize], angles: &[f64; 2], x: &Vec3) -> Vec3 {
        idx.iter().fold(*x, |x, &k| {
            let r = &self.rotary[k];
            let p = r.point.coords;
            p + rotate(&r.axis, -angles[k], &(x - p))
        })
    }

    /// The rotation part of a chain applied to the direction `v`.
    fn turn(&self, idx: &[usize], angles: &[f64; 2], v: &Vec3, inverse: bool) -> Vec3 {
        if inverse {
            idx.iter()
                .fold(*v, |v, &k| rotate(&self.rotary[k].axis, -angles[k], &v))
        } else {
            idx.iter()
                .rev()
                .fold(*v, |v, &k| rotate(&self.rotary[k].axis, angles[k], &v))
        }
    }

    /// The tool tip relative to the head reference point at home, mm.
    fn tip_home(&self, tool_length: f64) -> Vec3 {
        if self.kind == super::MachineKind::TableTable {
            Vec3::zeros()
        } else {
            -(self.pivot_length + tool_length) * Vec3::z()
        }
    }

    /// The part-frame pose for the machine axis positions `j` (module doc, forward).
    ///
    /// # Units
    /// mm, radians; `tool_length` (gauge line to tip) counts only on head machines.
    pub fn forward(&self, j: &Joints, tool_length: f64) -> Pose {
        let (table, head) = self.chains();
        let tip = j.linear + self.apply(&head, &j.rotary, &self.tip_home(tool_length));
        let axis = self.turn(&head, &j.rotary, &Vec3::z(), false);
        let cl = self.apply_inverse(&table, &j.rotary, &tip) - self.part_origin;
        Pose {
            cl: Point3::from(cl),
            axis: self.turn(&table, &j.rotary, &axis, true),
        }
    }

    /// The linear axes that put the tip at the part point `cl` with the rotary angles
    /// `rotary` (module doc, inverse).
    pub fn linear_for(&self, cl: &Point3, rotary: &[f64; 2], tool_length: f64) -> Vec3 {
        let (table, head) = self.chains();
        self.apply(&table, rotary, &(cl.coords + self.part_origin))
            - self.apply(&head, rotary, &self.tip_home(tool_length))
    }

    /// The two factors `(rotary index, sign)` of the orientation equation, left first.
    fn factors(&self) -> [(usize, f64); 2] {
        let (table, head) = self.chains();
        let mut f: Vec<(usize, f64)> = table.iter().rev().map(|&k| (k, -1.0)).collect();
        f.extend(head.iter().map(|&k| (k, 1.0)));
        [f[0], f[1]]
    }

    /// The rotary solutions that point the tool along the part-frame unit `axis`
    /// (module doc, inverse; subproblem 2).
    pub fn orientation(&self, axis: &Vec3) -> Orientation {
        let [(l, sl), (r, sr)] = self.factors();
        let (w1, w2) = (self.rotary[l].axis * sl, self.rotary[r].axis * sr);
        let (p, q) = (Vec3::z(), *axis);
        let k = w1.dot(&w2);
        let den = k * k - 1.0;
        let alpha = (k * w2.dot(&p) - w1.dot(&q)) / den;
        let beta = (k * w1.dot(&q) - w2.dot(&p)) / den;
        let cross = w1.cross(&w2);
        let g2 =
            (1.0 - alpha * alpha - beta * beta - 2.0 * alpha * beta * k) / cross.norm_squared();
        let mut branches = [None, None];
        if g2 >= -1e-12 {
            let g = g2.max(0.0).sqrt();
            for (b, sign) in [1.0, -1.0].into_iter().enumerate() {
                let c = alpha * w1 + beta * w2 + sign * g * cross;
                let t2 = turn_angle(&w2, &p, &c).unwrap_or(0.0);
                let t1 = turn_angle(&w1, &c, &q).unwrap_or(0.0);
                let mut angles = [0.0; 2];
                angles[l] = t1;
                angles[r] = t2;
                branches[b] = Some(angles);
            }
        }
        Orientation {
            left: l,
            right: r,
            branches,
            off_singular: w1.cross(&q).norm(),
        }
    }

    /// With the left factor's angle held at `left_angle` (the singular pose), the right
    /// factor's angle that brings the tool nearest to `axis`.
    pub fn right_for_left(&self, axis: &Vec3, left_angle: f64) -> f64 {
        let [(l, sl), (r, sr)] = self.factors();
        let (w1, w2) = (self.rotary[l].axis * sl, self.rotary[r].axis * sr);
        let target = rotate(&w1, -left_angle, axis);
        turn_angle(&w2, &Vec3::z(), &target).unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::TRUNNION;
    use super::*;
    use proptest::prelude::*;

    pub(crate) const HEAD_HEAD: &str = r#"
kind = "head-head"
[linear]
x = [-2000, 2000]
y = [-2000, 2000]
z = [-2000, 2000]
[[rotary]]
name = "C"
on = "head"
axis = [0, 0, 1]
point = [1, 2, 0]
limits = [-360, 360]
[[rotary]]
name = "B"
on = "head"
axis = [0, 1, 0]
point = [0, 0, -20]
limits = [-100, 100]
[head]
pivot_length = 150
"#;

    pub(crate) const TABLE_HEAD: &str = r#"
kind = "table-head"
part_origin = [5, 5, 0]
[linear]
x = [-2000, 2000]
y = [-2000, 2000]
z = [-2000, 2000]
[[rotary]]
name = "C"
on = "table"
axis = [0, 0, 1]
point = [100, 0, 0]
continuous = true
[[rotary]]
name = "B"
on = "head"
axis = [0, 1, 0]
point = [0, 0, -30]
limits = [-110, 110]
[head]
pivot_length = 200
"#;

    fn machines() -> Vec<Machine> {
        [TRUNNION, HEAD_HEAD, TABLE_HEAD]
            .iter()
            .map(|t| Machine::parse(t, "m").unwrap())
            .collect()
    }

    #[test]
    fn home_is_identity_up_to_offsets() {
        let m = Machine::parse(TRUNNION, "m").unwrap();
        let j = Joints {
            linear: Vec3::new(1.0, 2.0, 3.0),
            rotary: [0.0, 0.0],
        };
        let p = m.forward(&j, 0.0);
        assert!((p.cl - Point3::new(1.0 - 10.0, 2.0 + 20.0, 3.0 - 30.0)).norm() < 1e-12);
        assert!((p.axis - Vec3::z()).norm() < 1e-15);
        // A turns the table +90 degrees about +X: the part's +Y goes to +Z, so the tool
        // (machine +Z) points along the part's +Y.
        let j = Joints {
            linear: Vec3::zeros(),
            rotary: [std::f64::consts::FRAC_PI_2, 0.0],
        };
        assert!((m.forward(&j, 0.0).axis - Vec3::y()).norm() < 1e-15);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn forward_of_inverse_is_the_pose(
            which in 0usize..3,
            x in -100.0..100.0f64, y in -100.0..100.0f64, z in -50.0..50.0f64,
            az in -3.1..3.1f64, tilt in 0.01..1.5f64, tool in 20.0..120.0f64,
        ) {
            let m = &machines()[which];
            let axis = Vec3::new(tilt.sin() * az.cos(), tilt.sin() * az.sin(), tilt.cos());
            let cl = Point3::new(x, y, z);
            let o = m.orientation(&axis);
            prop_assert!(o.branches.iter().any(|b| b.is_some()));
            for rotary in o.branches.iter().flatten() {
                let j = Joints { linear: m.linear_for(&cl, rotary, tool), rotary: *rotary };
                let p = m.forward(&j, tool);
                prop_assert!((p.cl - cl).norm() < 1e-9, "{:?} vs {:?}", p.cl, cl);
                prop_assert!((p.axis - axis).norm() < 1e-9, "{:?} vs {:?}", p.axis, axis);
            }
        }
    }

    #[test]
    fn unreachable_orientation_has_no_branch() {
        // A head whose only tilt axis is B about Y, with C about X on the table: it
        // reaches every direction; one with B about a 45 degree axis cannot point down.
        let text = HEAD_HEAD.replace("axis = [0, 1, 0]", "axis = [0, 1, 1]");
        let m = Machine::parse(&text, "m").unwrap();
        let o = m.orientation(&-Vec3::z());
        assert!(o.branches.iter().all(|b| b.is_none()));
    }
}
