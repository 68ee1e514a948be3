//! The cutting surface in any orientation, and the exact signed distance to the tool.
//!
//! A profile point `(rho, z)` with outward normal angle `psi` becomes, at pose
//! `(cl, a)` and angle `phi` around the axis (from the reference direction `b1` of
//! [`crate::pose`]), the point `cl + rho u + z a` with normal `cos psi u + sin psi a`,
//! `u = cos phi b1 + sin phi b2`.
//!
//! Signed distance: the tool is a solid of revolution, so the point of its boundary
//! nearest to `p` lies in `p`'s meridian half-plane (rotating any other boundary point
//! into that half-plane brings it closer). The 3D distance is therefore the 2D distance
//! from `(rho, z)` of `p` to the profile chain plus the closing top segment
//! `(rho_top, h) -> (0, h)` (the axis is not boundary). Each piece has a closed form:
//! clamped projection for lines; for an arc, `| |p - c| - r |` when `p - c` lies in the
//! arc's angular wedge (under pi wide, tested with two cross products, no trig), else
//! the nearer end. The sign is negative inside: `0 <= z <= h` and
//! `rho <= radius_at_height(z)` (z never decreases along the profile, see
//! [`crate::profile`]).

use crate::cutter::Cutter;
use crate::pose::{Pose, reference_frame, unit};
use crate::profile::Profile;
use crate::segment::{RhoZ, Segment};
use swarf_geom::{Point3, Vec3};

/// `|(x, y)|` without `hypot`'s overflow care (mm-sized values; several times faster).
fn norm(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}

fn segment_distance(seg: &Segment, p: RhoZ) -> f64 {
    match *seg {
        Segment::Line { start, end } => line_distance(start, end, p),
        Segment::Arc {
            centre,
            radius,
            start,
            end,
            ..
        } => {
            let v = RhoZ::new(p.rho - centre.rho, p.z - centre.z);
            let e0 = RhoZ::new(start.rho - centre.rho, start.z - centre.z);
            let e1 = RhoZ::new(end.rho - centre.rho, end.z - centre.z);
            let cross = |a: RhoZ, b: RhoZ| a.rho * b.z - a.z * b.rho;
            if cross(e0, v) >= 0.0 && cross(v, e1) >= 0.0 {
                (norm(v.rho, v.z) - radius).abs()
            } else {
                let ds = norm(p.rho - start.rho, p.z - start.z);
                let de = norm(p.rho - end.rho, p.z - end.z);
                ds.min(de)
            }
        }
    }
}

fn line_distance(a: RhoZ, b: RhoZ, p: RhoZ) -> f64 {
    let (dr, dz) = (b.rho - a.rho, b.z - a.z);
    let len2 = dr * dr + dz * dz;
    let t = if len2 > 0.0 {
        (((p.rho - a.rho) * dr + (p.z - a.z) * dz) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(p.rho - a.rho - t * dr, p.z - a.z - t * dz)
}

impl Profile {
    /// Signed distance from the meridian point `(rho, z)` to the tool solid (profile
    /// closed by the top disc); negative inside.
    ///
    /// # Units
    /// mm.
    pub fn signed_distance_rho_z(&self, rho: f64, z: f64) -> f64 {
        let p = RhoZ::new(rho, z);
        let top = self.top();
        let d = self
            .segments()
            .iter()
            .map(|s| segment_distance(s, p))
            .fold(line_distance(top, RhoZ::new(0.0, top.z), p), f64::min);
        let inside = self.radius_at_height(z).is_some_and(|r| rho <= r);
        if inside { -d } else { d }
    }

    /// Exact signed distance from `p` to the tool solid at `pose`; negative inside.
    /// NaN when the pose's axis is zero or not finite.
    ///
    /// # Units
    /// mm.
    pub fn signed_distance(&self, pose: &Pose, p: &Point3) -> f64 {
        let Some(a) = unit(&pose.axis) else {
            return f64::NAN;
        };
        let w = p - pose.cl;
        let z = w.dot(&a);
        self.signed_distance_rho_z((w - z * a).norm(), z)
    }

    /// The cutting-surface point at arc-length fraction `s` in `[0, 1]` from the tip and
    /// angle `phi` (radians) around the axis from the reference direction, with its
    /// outward unit normal. NaN when the pose's axis is zero or not finite.
    pub fn surface_point(&self, pose: &Pose, s: f64, phi: f64) -> (Point3, Vec3) {
        let Some(a) = unit(&pose.axis) else {
            return (
                Point3::new(f64::NAN, f64::NAN, f64::NAN),
                Vec3::repeat(f64::NAN),
            );
        };
        let (b1, b2) = reference_frame(&a);
        let (sp, cp) = phi.sin_cos();
        let u = cp * b1 + sp * b2;
        let (q, psi) = self.point_at(s);
        let (sn, cn) = psi.sin_cos();
        (pose.cl + q.rho * u + q.z * a, cn * u + sn * a)
    }
}

impl Cutter {
    /// The cutting-surface point at arc-length fraction `s` in `[0, 1]` along the
    /// profile from the tip and angle `phi` around the axis (from the reference
    /// direction of [`crate::pose::reference_frame`]), with its outward unit normal.
    /// At a profile joint the upper segment's normal is given.
    ///
    /// # Units
    /// mm, radians.
    pub fn surface_point(&self, pose: &Pose, s: f64, phi: f64) -> (Point3, Vec3) {
        self.profile().surface_point(pose, s, phi)
    }

    /// Exact signed distance from `p` to the solid of revolution bounded by the profile
    /// and closed at the top by the flat disc at the flute length; negative inside.
    /// No allocation; hot loops should hoist [`Cutter::profile`] and call
    /// [`Profile::signed_distance`].
    ///
    /// # Units
    /// mm.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::Point3;
    /// use swarf_tool::{Cutter, Pose};
    /// let ball: Cutter = "ball:d=8".parse().unwrap();
    /// let pose = Pose::vertical(Point3::origin());
    /// let d = ball.signed_distance(&pose, &Point3::new(0.0, 0.0, -1.0));
    /// assert!((d - 1.0).abs() < 1e-12);
    /// ```
    pub fn signed_distance(&self, pose: &Pose, p: &Point3) -> f64 {
        self.profile().signed_distance(pose, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ball_distance_closed_form() {
        let ball = Cutter::ball(10.0, Some(20.0)).unwrap();
        let pose = Pose::vertical(Point3::new(1.0, 1.0, 1.0));
        let centre = Point3::new(1.0, 1.0, 6.0);
        for p in [
            Point3::new(1.0, 1.0, -2.0),
            Point3::new(4.0, -2.0, 3.0),
            Point3::new(2.0, 1.5, 4.0),
            Point3::new(1.0, 1.0, 6.0),
        ] {
            let expected = (p - centre).norm() - 5.0;
            assert!((ball.signed_distance(&pose, &p) - expected).abs() < 1e-12);
        }
        // Beside the shank and above the top disc.
        let d = ball.signed_distance(&pose, &Point3::new(9.0, 1.0, 12.0));
        assert!((d - 3.0).abs() < 1e-12);
        let d = ball.signed_distance(&pose, &Point3::new(2.0, 1.0, 24.0));
        assert!((d - 3.0).abs() < 1e-12);
        let d = ball.signed_distance(&pose, &Point3::new(2.0, 1.0, 21.0));
        assert!(d.abs() < 1e-12);
        // Just above and just below the top disc.
        let d = ball.signed_distance(&pose, &Point3::new(1.0, 1.0, 21.5));
        assert!((d - 0.5).abs() < 1e-12);
        let d = ball.signed_distance(&pose, &Point3::new(1.0, 1.0, 20.5));
        assert!((d + 0.5).abs() < 1e-12);
    }

    #[test]
    fn flat_and_cone_distance_closed_forms() {
        let flat = Cutter::flat(6.0, Some(10.0)).unwrap();
        let pose = Pose::new(Point3::origin(), Vec3::new(1.0, 0.0, 0.0)).unwrap();
        // Axis along +x: "below" the tip is -x.
        assert!((flat.signed_distance(&pose, &Point3::new(-2.0, 1.0, 1.0)) - 2.0).abs() < 1e-12);
        let d = flat.signed_distance(&pose, &Point3::new(-3.0, 7.0, 0.0));
        assert!((d - 5.0).abs() < 1e-12);
        assert!((flat.signed_distance(&pose, &Point3::new(1.0, 0.0, 0.5)) + 1.0).abs() < 1e-12);
        let cone = Cutter::cone(10.0, std::f64::consts::FRAC_PI_4, None).unwrap();
        let pose = Pose::vertical(Point3::origin());
        // A point on the axis below the tip, and one off the 45 degree flank.
        assert!((cone.signed_distance(&pose, &Point3::new(0.0, 0.0, -1.0)) - 1.0).abs() < 1e-12);
        let d = cone.signed_distance(&pose, &Point3::new(2.0, 0.0, 0.0));
        assert!((d - 2.0 / 2f64.sqrt()).abs() < 1e-12);
        let d = cone.signed_distance(&pose, &Point3::new(0.0, 0.0, 1.0));
        assert!((d + 1.0 / 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn surface_points_of_a_vertical_ball() {
        let ball = Cutter::ball(8.0, Some(4.0)).unwrap();
        let pose = Pose::vertical(Point3::new(0.0, 0.0, 2.0));
        let (p, n) = ball.surface_point(&pose, 0.0, 1.0);
        assert!((p - Point3::new(0.0, 0.0, 2.0)).norm() < 1e-15);
        assert!((n + Vec3::z()).norm() < 1e-15);
        let (p, n) = ball.surface_point(&pose, 1.0, std::f64::consts::FRAC_PI_2);
        assert!((p - Point3::new(0.0, 4.0, 6.0)).norm() < 1e-12);
        assert!((n - Vec3::y()).norm() < 1e-12);
        let bad = Pose {
            cl: Point3::origin(),
            axis: Vec3::zeros(),
        };
        assert!(ball.signed_distance(&bad, &Point3::origin()).is_nan());
        assert!(ball.surface_point(&bad, 0.5, 0.0).0.x.is_nan());
    }
}
