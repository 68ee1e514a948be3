//! Contact <-> pose: placing the tool tangent to a surface point (thesis 000 §7,
//! eqs. 7.1-7.4, generalised from the torus to every profile).
//!
//! At the CC point the tool's outward normal must be `m = -n` (`n` the unit surface
//! normal, out of the material, toward the tool). Split `m` along the unit tool axis
//! `a`: `m = sin(psi) a + cos(psi) u` with `u` the unit radial direction (`u` is
//! `m - (m.a) a` normalised; when `m` is parallel to the axis any `u` will do and the
//! reference direction is used). The contact is the profile point whose normal angle
//! is `psi` ([`Profile::contact_for_normal_angle`]), in the half-plane of `u`; so
//! `cc - cl = rho u + z a` and `cl = cc - rho u - z a`.
//!
//! For the torus this is eq. 7.4: `a = cos(t) n + sin(t) e` gives
//! `u = -sin(t) n + cos(t) e`, the insert centre `cc + r n`, and the point on the axis
//! at its height `cc + r n + R (sin(t) n - cos(t) e)`; the tip lies `f = r` below it.
//!
//! Choices where the matching point is not unique: a flat bottom facing `n = a` gives
//! the tip on the axis (CL = CC); a straight segment gives its lowest point. `None`
//! when no point of the cutting surface has the normal: `psi` above the side line's
//! (the surface would face the non-cutting top), or non-unit-able input.

use crate::cutter::Cutter;
use crate::pose::{Pose, reference_frame, unit};
use crate::profile::{Profile, ProfileContact};
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Point3, Vec3};

impl Profile {
    /// Where the tool with unit axis `axis` touches a surface of unit normal `normal`:
    /// the profile contact and the radial direction `u` of its half-plane.
    pub fn contact_for_normal(&self, normal: &Vec3, axis: &Vec3) -> Option<(ProfileContact, Vec3)> {
        let a = unit(axis)?;
        let m = -unit(normal)?;
        let along = m.dot(&a);
        let w = m - along * a;
        let across = w.norm();
        let u = if across > LENGTH_EPS {
            w / across
        } else {
            reference_frame(&a).0
        };
        let contact = self.contact_for_normal_angle(along.atan2(across))?;
        Some((contact, u))
    }

    /// `cl - cc` for the tool with axis `axis` touching a surface of normal `normal`;
    /// see [`Cutter::cl_offset`].
    pub fn cl_offset(&self, normal: &Vec3, axis: &Vec3) -> Option<Vec3> {
        let (c, u) = self.contact_for_normal(normal, axis)?;
        let a = unit(axis)?;
        Some(-(c.point.rho * u + c.point.z * a))
    }
}

impl Cutter {
    /// The pose with tool axis `axis` whose cutting surface touches the surface point
    /// `cc` with outward normal `-normal` (`normal`: unit surface normal out of the
    /// material, toward the tool). See the module doc for the choices made where the
    /// contact point is not unique.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// `None` when no point of the cutting surface has that normal (the normal faces
    /// the non-cutting top of the tool), or when `normal` or `axis` is zero or not
    /// finite.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Point3, Vec3};
    /// let ball: swarf_tool::Cutter = "ball:d=8".parse().unwrap();
    /// let pose = ball
    ///     .pose_from_contact(&Point3::new(0.0, 0.0, 0.0), &Vec3::x(), &Vec3::z())
    ///     .unwrap();
    /// assert!((pose.cl - Point3::new(4.0, 0.0, -4.0)).norm() < 1e-12);
    /// ```
    pub fn pose_from_contact(&self, cc: &Point3, normal: &Vec3, axis: &Vec3) -> Option<Pose> {
        let offset = self.cl_offset(normal, axis)?;
        Some(Pose {
            cl: cc + offset,
            axis: unit(axis)?,
        })
    }

    /// The CC point where the tool at `pose` touches a surface of unit normal `normal`
    /// (the inverse of [`Cutter::pose_from_contact`]).
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// `None` as for [`Cutter::pose_from_contact`].
    pub fn contact_from_pose(&self, pose: &Pose, normal: &Vec3) -> Option<Point3> {
        let offset = self.cl_offset(normal, &pose.axis)?;
        Some(pose.cl - offset)
    }

    /// `cl - cc` for the tool with axis `axis` touching a surface of normal `normal`,
    /// for hot loops (hoist [`Cutter::profile`] and call [`Profile::cl_offset`]).
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// `None` as for [`Cutter::pose_from_contact`].
    pub fn cl_offset(&self, normal: &Vec3, axis: &Vec3) -> Option<Vec3> {
        self.profile().cl_offset(normal, axis)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strutz_positioning_matches_thesis_eq_7_4() {
        // Bull-nose R = 5 (torus radius e = 3, insert r = 2), inclined by t in the
        // plane of the surface normal and feed: eqs. 7.1-7.4, tip r below T_position.
        let bull = Cutter::bull(10.0, 2.0, None).unwrap();
        let (big_r, r) = (3.0, 2.0);
        let n = Vec3::new(0.2, -0.3, 1.0).normalize();
        let feed = Vec3::new(1.0, 0.5, 0.1);
        let cc = Point3::new(3.0, -1.0, 2.0);
        for t in [0.05f64, 0.2, 0.5, 1.0] {
            let e = n.cross(&n.cross(&feed)).normalize();
            let axis = t.cos() * n + t.sin() * e;
            let insert = cc + r * n;
            let position = insert + big_r * (t.sin() * n - t.cos() * e);
            let expected = position - r * axis;
            let pose = bull.pose_from_contact(&cc, &n, &axis).unwrap();
            assert!((pose.cl - expected).norm() < 1e-12, "t = {t}");
        }
    }

    #[test]
    fn flat_bottom_facing_the_normal_touches_on_the_axis() {
        let flat = Cutter::flat(6.0, None).unwrap();
        let cc = Point3::new(1.0, 2.0, 3.0);
        let pose = flat.pose_from_contact(&cc, &Vec3::z(), &Vec3::z()).unwrap();
        assert_eq!(pose.cl, cc);
        // Slightly tilted surface: the rim on the uphill side touches.
        let n = Vec3::new(0.01, 0.0, 1.0).normalize();
        let pose = flat.pose_from_contact(&cc, &n, &Vec3::z()).unwrap();
        assert!((pose.cl - Point3::new(4.0, 2.0, 3.0)).norm() < 1e-12);
    }

    #[test]
    fn normals_facing_the_top_have_no_contact() {
        let ball = Cutter::ball(8.0, None).unwrap();
        let cc = Point3::origin();
        assert!(
            ball.pose_from_contact(&cc, &-Vec3::z(), &Vec3::z())
                .is_none()
        );
        let up_side = Vec3::new(1.0, 0.0, -0.1).normalize();
        assert!(ball.pose_from_contact(&cc, &up_side, &Vec3::z()).is_none());
        assert!(
            ball.pose_from_contact(&cc, &Vec3::zeros(), &Vec3::z())
                .is_none()
        );
        assert!(
            ball.pose_from_contact(&cc, &Vec3::z(), &Vec3::zeros())
                .is_none()
        );
        let side = ball.pose_from_contact(&cc, &Vec3::x(), &Vec3::z()).unwrap();
        assert!((side.cl - Point3::new(4.0, 0.0, -4.0)).norm() < 1e-12);
    }

    #[test]
    fn cone_tip_takes_its_fan() {
        let cone = Cutter::cone(10.0, std::f64::consts::FRAC_PI_4, None).unwrap();
        let cc = Point3::new(0.0, 0.0, 1.0);
        // Any normal within 45 degrees of the axis: the tip touches.
        for n in [Vec3::z(), Vec3::new(0.5, 0.2, 1.0).normalize()] {
            let pose = cone.pose_from_contact(&cc, &n, &Vec3::z()).unwrap();
            assert_eq!(pose.cl, cc);
        }
        // Beyond the fan: the flank, then the rim.
        let flank = Vec3::new(1.0, 0.0, 1.0).normalize();
        let pose = cone.pose_from_contact(&cc, &flank, &Vec3::z()).unwrap();
        assert!((pose.cl - cc).norm() < 1e-12);
        let steep = Vec3::new(1.0, 0.0, 0.5).normalize();
        let pose = cone.pose_from_contact(&cc, &steep, &Vec3::z()).unwrap();
        assert!((pose.cl - Point3::new(5.0, 0.0, -4.0)).norm() < 1e-12);
    }
}
