//! Tool poses and the tool frame.
//!
//! A pose is the CL point (the tool tip on the axis, as controls expect) and the unit
//! tool axis from the tip toward the shank. Angles around the axis are measured from
//! a reference direction chosen deterministically from the axis alone: the first
//! vector of the orthonormal basis of Duff et al., "Building an Orthonormal Basis,
//! Revisited" (JCGT 6(1), 2017), which is continuous everywhere except across the
//! plane `axis.z = 0` toward `-z` and gives `(+x, +y)` for the vertical axis `+z`.
//! `(b1, b2, axis)` is right-handed.

use serde::{Deserialize, Serialize};
use swarf_geom::{Point3, Vec3};

/// `1 - cos` of the largest angle between a tool axis and `+z` at which the tool
/// counts as vertical ([`Pose::is_vertical`]): about 1.4e-6 rad, below the output
/// precision of any program's axis words.
pub const VERTICAL_EPS: f64 = 1e-12;

/// A tool pose: CL point = tool tip on the axis + unit tool axis (tip -> shank).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Cutter location: the tool tip, on the axis, mm.
    pub cl: Point3,
    /// Unit tool axis, from the tip toward the shank.
    pub axis: Vec3,
}

impl Pose {
    /// The pose at `cl` with axis `axis` (normalised here); `None` when `axis` is
    /// (nearly) zero or not finite.
    pub fn new(cl: Point3, axis: Vec3) -> Option<Pose> {
        let axis = unit(&axis)?;
        Some(Pose { cl, axis })
    }

    /// The 3-axis pose at `cl`: axis `+z`.
    pub fn vertical(cl: Point3) -> Pose {
        Pose {
            cl,
            axis: Vec3::z(),
        }
    }

    /// Whether the tool axis is `+z` within [`VERTICAL_EPS`]: the one test of a
    /// three-axis pose for the simulator, the holder check and the leads.
    pub fn is_vertical(&self) -> bool {
        self.axis.z >= 1.0 - VERTICAL_EPS
    }

    /// The reference directions `(b1, b2)` around this pose's axis (see the module
    /// doc).
    pub fn frame(&self) -> (Vec3, Vec3) {
        reference_frame(&self.axis)
    }

    /// `p` in the tool's meridian coordinates: `(rho, z)` = distance from the axis and
    /// height above the tip along the axis, mm. Assumes a unit axis.
    pub fn to_rho_z(&self, p: &Point3) -> (f64, f64) {
        let w = p - self.cl;
        let z = w.dot(&self.axis);
        ((w - z * self.axis).norm(), z)
    }
}

/// `v` normalised, or `None` when (nearly) zero or not finite.
pub(crate) fn unit(v: &Vec3) -> Option<Vec3> {
    let n = v.norm();
    if n.is_finite() && n > swarf_geom::tol::LENGTH_EPS {
        Some(v / n)
    } else {
        None
    }
}

/// Orthonormal `(b1, b2)` completing the unit `axis` to a right-handed frame
/// (Duff et al. 2017, listing 3).
pub fn reference_frame(axis: &Vec3) -> (Vec3, Vec3) {
    let s = 1.0_f64.copysign(axis.z);
    let a = -1.0 / (s + axis.z);
    let b = axis.x * axis.y * a;
    (
        Vec3::new(1.0 + s * axis.x * axis.x * a, s * b, -s * axis.x),
        Vec3::new(b, s + axis.y * axis.y * a, -axis.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn vertical_frame_is_x_y() {
        let (b1, b2) = reference_frame(&Vec3::z());
        assert_eq!((b1, b2), (Vec3::x(), Vec3::y()));
        let (b1, b2) = reference_frame(&-Vec3::z());
        assert_eq!(b1.cross(&b2), -Vec3::z());
        let p = Pose::vertical(Point3::new(1.0, 2.0, 3.0));
        assert_eq!(p.to_rho_z(&Point3::new(4.0, 6.0, 5.0)), (5.0, 2.0));
        assert!(Pose::new(Point3::origin(), Vec3::zeros()).is_none());
        assert!(Pose::new(Point3::origin(), Vec3::new(f64::NAN, 0.0, 1.0)).is_none());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        #[test]
        fn frame_is_orthonormal_and_right_handed(
            x in -1.0..1.0f64, y in -1.0..1.0f64, z in -1.0..1.0f64,
        ) {
            let Some(a) = unit(&Vec3::new(x, y, z)) else { return Ok(()) };
            let (b1, b2) = reference_frame(&a);
            prop_assert!((b1.norm() - 1.0).abs() < 1e-12);
            prop_assert!((b2.norm() - 1.0).abs() < 1e-12);
            prop_assert!(b1.dot(&a).abs() < 1e-12 && b2.dot(&a).abs() < 1e-12);
            prop_assert!((b1.cross(&b2) - a).norm() < 1e-12);
        }
    }
}
