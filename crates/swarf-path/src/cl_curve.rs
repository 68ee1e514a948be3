//! From cutter contact to cutter location on a patch (3-axis, tool axis +z).
//!
//! At a CC point `S(u, v)` with unit normal `n` the tool touches the surface with the
//! profile point whose outward normal is `-n`, and the tip sits at
//! `CL = CC + offset(n)` ([`swarf_tool::Cutter::pose_from_contact`]; for a ball of
//! radius `r`, `offset = r n - r z`, the classical inverse tool offset). A patch's
//! `S_u x S_v` may point into the material; for 3-axis work the normal is the one
//! facing the tool, so it is turned toward `+z` (paper 004, fig. 6: the CL surface
//! is the design surface offset toward the tool). A point whose normal is degenerate
//! or faces away from the tool's reach (a horizontal normal under an overhang) has
//! no CL point.

use swarf_geom::{Patch, SurfaceDerivs, Vec3};
use swarf_tool::{Cutter, Pose, Profile};
use swarf_toolpath::{Contact, PathPoint};

/// Unit normal of `d` turned toward `+z` (the tool side); `None` where the patch is
/// degenerate. A horizontal normal keeps the patch's orientation.
pub fn tool_side_normal(d: &SurfaceDerivs) -> Option<Vec3> {
    let n = d.normal()?;
    Some(if n.z < 0.0 { -n } else { n })
}

/// Signed normal curvature (1/mm) of `d` along the tangent `dir`, positive where the
/// surface bends toward the tool (concave as the tool sees it).
pub fn tool_side_curvature(d: &SurfaceDerivs, dir: &Vec3) -> Option<f64> {
    let k = d.normal_curvature(dir)?;
    let n = d.normal()?;
    Some(if n.z < 0.0 { -k } else { k })
}

/// The CC -> CL map of one patch for one cutter, axis `+z`.
#[derive(Debug, Clone, Copy)]
pub struct ClMap<'a> {
    patch: &'a Patch,
    face: usize,
    profile: Profile,
}

impl<'a> ClMap<'a> {
    /// The map for patch `patch` (index `face` in its part) and `cutter`.
    pub fn new(patch: &'a Patch, face: usize, cutter: &Cutter) -> ClMap<'a> {
        ClMap {
            patch,
            face,
            profile: cutter.profile(),
        }
    }

    /// The patch.
    pub fn patch(&self) -> &'a Patch {
        self.patch
    }

    /// The patch's index in its part.
    pub fn face(&self) -> usize {
        self.face
    }

    /// The pose touching the patch at `(u, v)` (clamped into the domain), with its
    /// contact; `None` where the normal is degenerate or the cutter has no point with
    /// that normal.
    ///
    /// # Units
    /// mm.
    pub fn at(&self, u: f64, v: f64) -> Option<PathPoint> {
        let (u, v) = self.patch.clamp_params(u, v);
        self.from_derivs(&self.patch.derivs(u, v), u, v)
    }

    /// As [`ClMap::at`], from derivatives already evaluated at `(u, v)`.
    pub fn from_derivs(&self, d: &SurfaceDerivs, u: f64, v: f64) -> Option<PathPoint> {
        let normal = tool_side_normal(d)?;
        let offset = self.profile.cl_offset(&normal, &Vec3::z())?;
        Some(PathPoint {
            pose: Pose::vertical(d.point + offset),
            contact: Some(Contact {
                point: d.point,
                normal,
                face: self.face,
                uv: [u, v],
            }),
            lifted: 0.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;

    /// The bump `z = 10 - (x^2 + y^2) / 40` over `[-10, 10]^2` as an exact bicubic
    /// patch written upside down (its `S_u x S_v` points to -z). Along each axis
    /// `-x^2 / 40` has cubic Bernstein coefficients `[-2.5, 5/6, 5/6, -2.5]`.
    pub(crate) fn flipped_bump() -> Patch {
        let c = [-2.5, 5.0 / 6.0, 5.0 / 6.0, -2.5];
        let mut pts = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                let (x, y) = (-10.0 + 20.0 * j as f64 / 3.0, -10.0 + 20.0 * i as f64 / 3.0);
                pts.push(Point3::new(x, y, 10.0 + c[i] + c[j]));
            }
        }
        Patch::bezier([3, 3], pts).unwrap()
    }

    #[test]
    fn ball_cl_is_the_offset_point_minus_r() {
        let p = flipped_bump();
        let ball = Cutter::ball(8.0, None).unwrap();
        let map = ClMap::new(&p, 3, &ball);
        for (u, v) in [(0.5, 0.5), (0.1, 0.8), (1.0, 0.0)] {
            let pp = map.at(u, v).unwrap();
            let c = pp.contact.unwrap();
            assert!(c.normal.z > 0.0, "normal faces the tool");
            assert_eq!((c.face, c.uv), (3, [u, v]));
            let want = c.point + 4.0 * c.normal - 4.0 * Vec3::z();
            assert!((pp.pose.cl - want).norm() < 1e-12);
            assert_eq!(pp.pose.axis, Vec3::z());
            // The ball touches the contact and does not enter the surface nearby.
            let sd = ball.signed_distance(&pp.pose, &c.point);
            assert!(sd.abs() < 1e-9, "{sd}");
        }
    }

    #[test]
    fn curvature_sign_is_convex_negative_from_the_tool() {
        let p = flipped_bump();
        let d = p.derivs(0.5, 0.5);
        let k = tool_side_curvature(&d, &Vec3::x()).unwrap();
        // z = 10 - r^2/40 is convex seen from above: curvature -1/20 at the top.
        assert!((d.point - Point3::new(0.0, 0.0, 10.0)).norm() < 1e-12);
        assert!((k + 1.0 / 20.0).abs() < 1e-9, "{k}");
    }
}
