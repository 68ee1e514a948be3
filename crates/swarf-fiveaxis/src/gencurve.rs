//! Generating curves of a tool at the poses of a path (thesis 000 §5.3-5.4, eqs.
//! 5.2-5.17).
//!
//! At a pose with tip `cl`, unit axis `a` and velocity field `v(p)` ([`crate::motion`]:
//! the twist of the path there), the frame of eqs. 5.2-5.5 is `X = unit(v_tip x a)`,
//! `Y = a x X`. The **front half** of the tool is the half toward `+Y` (meridian angles
//! `phi` in `[0, pi]` from `X`); the **back half** is the front half of the reversed
//! motion (thesis §7.2: "the same procedure ... with the back half of the tool after
//! reversing the tool path"). A profile point `(rho, z)` of the meridian `phi` is
//! `cl + rho u + z a`, `u = cos(phi) X + sin(phi) Y`, with outward normal
//! `cos(psi) u + sin(psi) a`.
//!
//! **Inserts** (eqs. 5.6-5.11). The generating point of a meridian is where the normal
//! is perpendicular to the velocity: with `w_u = v.u`, `w_a = v.a`,
//! `cos(psi) w_u + sin(psi) w_a = 0`, whose root in `[-pi/2, pi/2]` is
//! `psi* = atan2(-w_u, w_a)` (for `w_a > 0`; the mirrored form for `w_a < 0`; the bottom
//! `-pi/2` for `w_a = 0`). With `v` the velocity of the insert centre this is eq. 5.10,
//! `DC = r (Delta C x N) / |Delta C x N|`, `N` the insert-plane normal, the lower of the
//! two roots; `velocity_iterations` fixed-point steps then move the reference to the
//! point itself, so that the exact condition `n . v(p) = 0` holds. The profile point
//! with normal angle `psi*` is found by [`ProfileTable::point_for_normal`] (arcs,
//! corners, and the rim of a flat bottom: the generating circle of radius `R` of
//! §3.3). A bottom cone follows the same rule, which is §5.4.4: when the motion's angle
//! above the tool's `X-Y` plane exceeds `theta_start`, `psi*` passes the cone's normal and
//! the torus takes over as if the cone did not exist. A meridian whose points all move
//! across its own plane (in-plane speed below [`DEGENERATE_REL`] of the speed: the side
//! meridians under translation, or a meridian holding the rotation axis) has every
//! point characteristic; it takes its limit from inside the half, and the wall below
//! supplies the rest.
//!
//! **Cards** (eqs. 5.12-5.17). The two ends of a half (`phi = 0`, `phi = pi`) continue
//! up the tool's side as walls, sampled by circular cards (centre `cl + z a`, radius
//! `rho`, normal angle `psi` of the profile there). With the card centre's velocity
//! `v_c` and the twist's angular velocity `w`, `n . v(p) = 0` reads
//! `A cos(phi) + B sin(phi) = -C` with `A = cos(psi) v_c.X - rho sin(psi) w.Y`,
//! `B = cos(psi) v_c.Y + rho sin(psi) w.X`, `C = sin(psi) v_c.a`. For a cylinder
//! (`psi = 0`) this is eq. 5.16, `L = rho (Delta C x N) / |Delta C x N|`; for a cone
//! the thesis uses the same formula, which drops the cone's slope: the form here is the
//! exact envelope condition. When no `phi` solves it, the card is entirely front or back
//! and its extreme point is taken (a point of the tool, so it never invents a gouge).
//! Wall cards are spaced evenly in arc length along the profile, from the wall top down
//! to the end meridian's point.
//!
//! A half's curve is ordered right wall (top down), meridians `phi = 0 .. pi`, left
//! wall (bottom up): `2 K + M` points with a fixed layout, so that corresponding points
//! of consecutive curves can be joined (thesis §3.3.1: "each component within each
//! generating curve has the same number of points").

use crate::motion::{Twist, pose_twist};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Point3, Vec3};
use swarf_tool::pose::reference_frame;
use swarf_tool::{Pose, Profile, ProfileTable, RhoZ};

/// A meridian whose in-plane speed is below this fraction of its speed is degenerate
/// (dimensionless).
pub const DEGENERATE_REL: f64 = 1e-9;
/// Step into the half from a degenerate meridian for its limit (radians).
const LIMIT_STEP: f64 = 1e-5;

/// Which half of the tool, relative to the motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Half {
    /// The half facing the feed direction.
    Front,
    /// The half facing away from it.
    Back,
}

impl Half {
    /// `"front"` or `"back"`.
    pub fn name(self) -> &'static str {
        match self {
            Half::Front => "front",
            Half::Back => "back",
        }
    }
}

/// How generating curves are sampled.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CurveOptions {
    /// Meridians (inserts) per half, at least 3.
    pub meridians: usize,
    /// Cards per side wall (0: no walls).
    pub wall_cards: usize,
    /// Height of the side walls above the tip, mm; `None`: the lowest height where the
    /// profile reaches its full radius.
    pub wall_height: Option<f64>,
    /// Fixed-point steps from the insert centre's velocity to the point's own (0: thesis
    /// eq. 5.10).
    pub velocity_iterations: usize,
}

impl Default for CurveOptions {
    fn default() -> Self {
        CurveOptions {
            meridians: 25,
            wall_cards: 6,
            wall_height: None,
            velocity_iterations: 1,
        }
    }
}

impl CurveOptions {
    /// Number of points of a half's curve: `2 wall_cards + meridians`.
    pub fn len(&self) -> usize {
        2 * self.wall_cards + self.meridians.max(3)
    }

    /// Always false (a curve has at least three points); for clippy's `len` rule.
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// A pose with the frame of eqs. 5.2-5.5 for one half.
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    /// Tool tip, mm.
    pub cl: Point3,
    /// `unit(v_tip x a)`.
    pub x: Vec3,
    /// `a x X`, toward the half's front.
    pub y: Vec3,
    /// Unit tool axis.
    pub a: Vec3,
}

impl Frame {
    /// Radial unit vector of the meridian at `phi`.
    pub fn radial(&self, phi: f64) -> Vec3 {
        let (s, c) = phi.sin_cos();
        c * self.x + s * self.y
    }

    /// The point `(rho, z)` of the meridian with radial vector `u`.
    pub fn at(&self, u: &Vec3, q: RhoZ) -> Point3 {
        self.cl + q.rho * u + q.z * self.a
    }
}

/// The generating curve of one half of the tool at one pose of a path.
#[derive(Debug, Clone)]
pub struct PoseCurve<'a> {
    table: &'a ProfileTable<'a>,
    profile: &'a Profile,
    frame: Frame,
    twist: Twist,
    /// `twist.linear . a` and `twist.angular x a`.
    lin_a: f64,
    ang_x_a: Vec3,
    /// Sine of the profile's normal angle at the wall top: generating points stop there.
    top_nz: f64,
    opts: CurveOptions,
    centre: RhoZ,
    total: f64,
    wall_top: f64,
}

impl<'a> PoseCurve<'a> {
    /// The `half` of the tool at pose `i` of `poses` (unit axes), moving as the path
    /// does there ([`pose_twist`]).
    pub fn new(
        table: &'a ProfileTable<'a>,
        poses: &[Pose],
        i: usize,
        half: Half,
        opts: CurveOptions,
    ) -> PoseCurve<'a> {
        let twist = pose_twist(poses, i);
        let twist = match half {
            Half::Front => twist,
            Half::Back => twist.reversed(),
        };
        PoseCurve::with_twist(table, &poses[i], twist, opts)
    }

    /// The front half of the tool at `pose` for the velocity field `twist`.
    pub fn with_twist(
        table: &'a ProfileTable<'a>,
        pose: &Pose,
        twist: Twist,
        opts: CurveOptions,
    ) -> PoseCurve<'a> {
        let profile = table.profile();
        let a = pose.axis;
        let c = twist.linear.cross(&a);
        let x = c
            .try_normalize(LENGTH_EPS * twist.linear.norm().max(1.0))
            .unwrap_or_else(|| reference_frame(&a).0);
        let centre = profile.corner_centre();
        let top_height = opts
            .wall_height
            .unwrap_or_else(|| profile.full_radius_height())
            .min(profile.top().z);
        let wall_top = profile.arc_position_at_height(top_height);
        PoseCurve {
            table,
            profile,
            frame: Frame {
                cl: pose.cl,
                x,
                y: a.cross(&x),
                a,
            },
            twist,
            lin_a: twist.linear.dot(&a),
            ang_x_a: twist.angular.cross(&a),
            top_nz: {
                let total = profile.arc_length();
                let frac = if total > 0.0 { wall_top / total } else { 0.0 };
                profile.point_at(frac).1.sin()
            },
            opts,
            centre,
            total: profile.arc_length(),
            wall_top,
        }
    }

    /// The frame of the curve's pose.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// The generating-curve point of the meridian `phi` (module doc, inserts), with its
    /// profile point. No trigonometry besides `phi`'s sine and cosine: the normal is
    /// found as a vector ([`ProfileTable::point_for_normal`]).
    pub fn meridian_point(&self, phi: f64) -> (Point3, RhoZ) {
        let u = self.frame.radial(phi);
        let mut q = self.centre;
        for _ in 0..=self.opts.velocity_iterations {
            let (n_rho, n_z) = self.normal_at(phi, &u, q);
            q = self.table.point_for_normal(n_rho, n_z);
        }
        (self.frame.at(&u, q), q)
    }

    /// In-plane velocity `(w_u, w_a)` of the profile point `q` of the meridian with
    /// radial vector `u`, and the point's speed.
    fn in_plane(&self, u: &Vec3, q: RhoZ) -> (f64, f64, f64) {
        // v = lin + w x (rho u + z a): (w x u).u = 0 and (w x a).a = 0.
        let w_x_u = self.twist.angular.cross(u);
        let v = self.twist.linear + q.rho * w_x_u + q.z * self.ang_x_a;
        let wu = self.twist.linear.dot(u) + q.z * self.ang_x_a.dot(u);
        let wa = self.lin_a + q.rho * w_x_u.dot(&self.frame.a);
        (wu, wa, v.norm_squared().sqrt())
    }

    /// The outward unit normal `(n_rho, n_z)` perpendicular to the in-plane velocity
    /// of `q` (the `psi*` of the module doc); a degenerate meridian takes the limit
    /// from inside the half.
    fn normal_at(&self, phi: f64, u: &Vec3, q: RhoZ) -> (f64, f64) {
        let (mut wu, mut wa, speed) = self.in_plane(u, q);
        if (wu * wu + wa * wa).sqrt() <= DEGENERATE_REL * speed {
            let inside = phi
                + if phi < FRAC_PI_2 {
                    LIMIT_STEP
                } else {
                    -LIMIT_STEP
                };
            (wu, wa, _) = self.in_plane(&self.frame.radial(inside), q);
        }
        let (nr, nz) = if wa > 0.0 {
            (wa, -wu)
        } else if wa < 0.0 {
            (-wa, wu)
        } else {
            (0.0, -1.0)
        };
        let len = (nr * nr + nz * nz).sqrt();
        if len <= 0.0 {
            return (0.0, -1.0);
        }
        let nz = nz / len;
        if nz > self.top_nz {
            (
                (1.0 - self.top_nz * self.top_nz).max(0.0).sqrt(),
                self.top_nz,
            )
        } else {
            (nr / len, nz)
        }
    }

    /// The generating point of the card through the profile point `q` (normal angle
    /// `psi`) on the right (`phi` near 0) or left (`phi` near pi) side (module doc,
    /// cards).
    pub fn card_point(&self, q: RhoZ, psi: f64, left: bool) -> Point3 {
        let f = &self.frame;
        let vc = self.twist.velocity(&f.cl, &(f.cl + q.z * f.a));
        let w = &self.twist.angular;
        let (sp, cp) = psi.sin_cos();
        let a = cp * vc.dot(&f.x) - q.rho * sp * w.dot(&f.y);
        let b = cp * vc.dot(&f.y) + q.rho * sp * w.dot(&f.x);
        let c = sp * vc.dot(&f.a);
        let r = a.hypot(b);
        let phi = if r <= LENGTH_EPS * (1.0 + c.abs()) {
            if left { PI } else { 0.0 }
        } else {
            let base = b.atan2(a);
            let spread = (-c / r).clamp(-1.0, 1.0).acos();
            let (p1, p2) = (base - spread, base + spread);
            let target = if left { PI } else { 0.0 };
            if angle_gap(p1, target) <= angle_gap(p2, target) {
                p1
            } else {
                p2
            }
        };
        f.at(&f.radial(phi), q)
    }

    /// Wall point at fraction `lambda` from the wall top (0) down to the profile
    /// position `bottom` (1) of the end meridian's point.
    fn wall_point(&self, lambda: f64, bottom: f64, left: bool) -> Point3 {
        let s = bottom + (self.wall_top - bottom).max(0.0) * (1.0 - lambda);
        let frac = if self.total > 0.0 {
            s / self.total
        } else {
            0.0
        };
        let (q, psi) = self.profile.point_at(frac);
        self.card_point(q, psi, left)
    }

    /// The whole curve of this half: right wall top-down, meridians `0 .. pi`, left
    /// wall bottom-up ([`CurveOptions::len`] points).
    pub fn curve(&self) -> Vec<Point3> {
        let m = self.opts.meridians.max(3);
        let k = self.opts.wall_cards;
        let mut out = Vec::with_capacity(m + 2 * k);
        let first = self.meridian_point(0.0);
        let last = self.meridian_point(PI);
        let (b0, b1) = (
            self.table.arc_position(first.1),
            self.table.arc_position(last.1),
        );
        for j in 0..k {
            out.push(self.wall_point(j as f64 / k as f64, b0, false));
        }
        out.push(first.0);
        for j in 1..m - 1 {
            out.push(self.meridian_point(PI * j as f64 / (m - 1) as f64).0);
        }
        out.push(last.0);
        for j in (0..k).rev() {
            out.push(self.wall_point(j as f64 / k as f64, b1, true));
        }
        out
    }

    /// The curve point at the continuous parameter `t` in `[0, len - 1]`: integers are
    /// the points of [`PoseCurve::curve`]; between them the same pieces are evaluated at
    /// intermediate `phi` or wall positions (between a wall and the meridians,
    /// linearly).
    pub fn curve_at(&self, t: f64) -> Point3 {
        let m = self.opts.meridians.max(3);
        let kf = self.opts.wall_cards as f64;
        let last = (m - 1) as f64;
        if t >= kf && t <= kf + last {
            return self.meridian_point(PI * (t - kf) / last).0;
        }
        let left = t > kf + last;
        let s = if left { 2.0 * kf + last - t } else { t };
        let end = self.meridian_point(if left { PI } else { 0.0 });
        let bottom = self.table.arc_position(end.1);
        if s >= kf - 1.0 {
            let wall = self.wall_point((kf - 1.0) / kf, bottom, left);
            return wall + (end.0 - wall) * (s - (kf - 1.0));
        }
        self.wall_point(s / kf, bottom, left)
    }
}

/// The distance between two angles on the circle, in `[0, pi]`.
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_tool::Cutter;

    fn bull() -> Profile {
        Cutter::bull(10.0, 2.0, Some(20.0)).unwrap().profile()
    }

    fn all_curves<'a>(
        p: &'a ProfileTable<'a>,
        poses: &[Pose],
        opts: CurveOptions,
    ) -> Vec<(Vec<Point3>, PoseCurve<'a>, Pose)> {
        let mut out = Vec::new();
        for i in 0..poses.len() {
            for half in [Half::Front, Half::Back] {
                let pc = PoseCurve::new(p, poses, i, half, opts);
                out.push((pc.curve(), pc, poses[i]));
            }
        }
        out
    }

    #[test]
    fn horizontal_translation_gives_the_bottom_circle() {
        // A vertical bull moving along +y over a plane: the front generating curve is
        // the front half of the bottom circle of radius R (thesis §3.3, R_gen = R),
        // and the side walls are the side inserts' quarter arcs.
        let p = bull();
        let t = ProfileTable::new(&p);
        let poses = [
            Pose::vertical(Point3::new(0.0, 0.0, 0.0)),
            Pose::vertical(Point3::new(0.0, 1.0, 0.0)),
        ];
        let opts = CurveOptions::default();
        let front = PoseCurve::new(&t, &poses, 0, Half::Front, opts);
        for j in 0..=20 {
            let phi = PI * j as f64 / 20.0;
            let (q, _) = front.meridian_point(phi);
            assert!(q.z.abs() < 1e-12);
            assert!(((q.x).hypot(q.y) - 3.0).abs() < 1e-12);
            assert!(q.y >= -1e-12, "front half faces +y");
        }
        let curve = front.curve();
        assert_eq!(curve.len(), opts.len());
        // X = v x a = y x z = +x, so phi = 0 is +x: the right wall starts at the top
        // of the corner arc there (rho 5, z 2) and runs down the side insert.
        assert!(
            (curve[0] - Point3::new(5.0, 0.0, 2.0)).norm() < 1e-9,
            "{:?}",
            curve[0]
        );
        for q in &curve[..opts.wall_cards] {
            assert!(q.y.abs() < 1e-9 && q.x > 3.0);
        }
        let back = PoseCurve::new(&t, &poses, 1, Half::Back, opts);
        let (q, _) = back.meridian_point(FRAC_PI_2);
        assert!((q - Point3::new(0.0, -2.0, 0.0)).norm() < 1e-12, "{q:?}");
    }

    #[test]
    fn continuous_parameter_hits_the_samples_on_the_tool() {
        let p = bull();
        let t = ProfileTable::new(&p);
        let poses = [
            Pose::new(Point3::new(0.0, 0.0, 0.0), Vec3::new(0.1, 0.05, 1.0)).unwrap(),
            Pose::new(Point3::new(0.3, 1.0, 0.2), Vec3::new(0.12, 0.02, 1.0)).unwrap(),
            Pose::new(Point3::new(0.5, 2.1, 0.3), Vec3::new(0.15, 0.0, 1.0)).unwrap(),
        ];
        for (curve, pc, pose) in all_curves(&t, &poses, CurveOptions::default()) {
            for (j, q) in curve.iter().enumerate() {
                assert!((pc.curve_at(j as f64) - q).norm() < 1e-9, "{j}");
                assert!(p.signed_distance(&pose, q).abs() < 1e-9);
            }
            for s in [0.3, 7.5, 20.2, 33.6] {
                assert!(p.signed_distance(&pose, &pc.curve_at(s)).abs() < 1e-9);
            }
        }
    }

    /// Poses of a tool whose axis turns about the point `o` on it, `l` above the tip,
    /// in the x-z plane, `steps` steps of `dtheta` from `-theta0`.
    fn rotating(o: Point3, l: f64, theta0: f64, dtheta: f64, steps: usize) -> Vec<Pose> {
        (0..=steps)
            .map(|k| {
                let t = -theta0 + dtheta * k as f64;
                let a = Vec3::new(t.sin(), 0.0, t.cos());
                Pose {
                    cl: o - l * a,
                    axis: a,
                }
            })
            .collect()
    }

    #[test]
    fn flat_end_mill_turning_about_its_axis_cuts_a_sphere() {
        // Thesis §3.2 (Warkentin et al.): the bottom circle generates the sphere of
        // radius sqrt(L^2 + R^2) about the centre of rotation.
        let p = Cutter::flat(12.0, Some(30.0)).unwrap().profile();
        let t = ProfileTable::new(&p);
        let o = Point3::new(1.0, 2.0, 40.0);
        let l = 25.0;
        let radius = (l * l + 36.0f64).sqrt();
        let poses = rotating(o, l, 0.4, 0.05, 16);
        for (curve, pc, _) in all_curves(&t, &poses, CurveOptions::default()) {
            for q in &curve {
                assert!(((q - o).norm() - radius).abs() < 1e-9);
            }
            for s in [0.5, 3.25, 9.0, 14.7, 28.3, 33.9] {
                assert!(((pc.curve_at(s) - o).norm() - radius).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn torus_on_the_normal_reduces_to_the_generating_circle() {
        // A bull nose whose axis stays on the normal of a sphere (it turns about the
        // sphere's centre o, on its axis): the generating point of every insert is where
        // the line from o through the insert centre meets the insert (thesis §3.2,
        // fig. 3.3), on the circle of radius R + r sin(theta), sin(theta) = R / |C - o|.
        let (big_r, r) = (4.0, 2.0);
        let p = Cutter::bull(2.0 * (big_r + r), r, Some(30.0))
            .unwrap()
            .profile();
        let t = ProfileTable::new(&p);
        let o = Point3::new(0.0, 0.0, 50.0);
        let l = 30.0;
        let dc = (big_r * big_r + (l - r) * (l - r)).sqrt();
        let sphere = dc + r;
        let gen_radius = big_r + r * big_r / dc;
        let poses = rotating(o, l, 0.3, 0.2f64.to_radians(), 12);
        let opts = CurveOptions {
            wall_cards: 0,
            ..CurveOptions::default()
        };
        // Inside the pass the twist is the rotation about o (up to the chord/arc speed
        // ratio, ~ dtheta^2 / 24 = 5e-7, which moves the point along the sphere by
        // about r times that and off it by the square); not at the one-sided ends.
        for i in 1..poses.len() - 1 {
            for half in [Half::Front, Half::Back] {
                let pose = poses[i];
                for q in PoseCurve::new(&t, &poses, i, half, opts).curve() {
                    let e = (q - o).norm() - sphere;
                    assert!(e.abs() < 1e-9, "{e}");
                    let w = q - pose.cl;
                    let across = (w - w.dot(&pose.axis) * pose.axis).norm();
                    assert!(
                        (across - gen_radius).abs() < 1e-5,
                        "{across} vs {gen_radius}"
                    );
                }
            }
        }
    }
}
