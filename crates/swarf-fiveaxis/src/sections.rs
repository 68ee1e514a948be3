//! Families of parallel section planes (thesis 000 §7.2: "slicing the surface into a
//! number of parallel sections, where gouging is going to be checked"; 1 to 3 mm apart
//! is enough for a good representation, denser for more accuracy).
//!
//! A family is the set of vertical planes `n . p = offset + k spacing` (`n` a unit
//! horizontal normal, `k` any integer). Planes parallel to the feed direction cut the
//! front (and back) generating curve of each move once and trace the machined surface
//! along the pass, which is how the thesis sections its test surfaces.

use crate::error::FiveAxisError;
use serde::{Deserialize, Serialize};
use swarf_geom::{Plane, Point3, Vec3};

/// Parallel vertical section planes `normal . p = offset + k spacing`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sections {
    /// Unit horizontal normal of the planes.
    pub normal: Vec3,
    /// Distance between neighbouring planes, mm.
    pub spacing: f64,
    /// Signed distance of plane 0 from the origin along `normal`, mm.
    pub offset: f64,
}

impl Sections {
    /// Planes parallel to the horizontal direction at `angle` (radians from +X toward
    /// +Y), `spacing` apart, one of them through the origin.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] (`sections`) when `spacing` is not finite
    /// and > 0 or `angle` is not finite.
    pub fn along(angle: f64, spacing: f64) -> Result<Sections, FiveAxisError> {
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(FiveAxisError::parameter(
                "sections",
                format!("expected a section spacing > 0 mm, found {spacing}"),
            ));
        }
        if !angle.is_finite() {
            return Err(FiveAxisError::parameter(
                "sections",
                "expected a finite direction",
            ));
        }
        let (s, c) = angle.sin_cos();
        Ok(Sections {
            normal: Vec3::new(-s, c, 0.0),
            spacing,
            offset: 0.0,
        })
    }

    /// Signed coordinate of `p` across the planes, mm.
    pub fn coordinate(&self, p: &Point3) -> f64 {
        self.normal.dot(&p.coords)
    }

    /// The value `offset + k spacing` of plane `k`, mm.
    pub fn value(&self, k: i64) -> f64 {
        self.offset + k as f64 * self.spacing
    }

    /// Plane `k`.
    pub fn plane(&self, k: i64) -> Plane {
        Plane {
            normal: self.normal,
            offset: self.value(k),
        }
    }

    /// Indices of the planes with `min(a, b) <= value < max(a, b)`, ascending (half
    /// open, so that a polyline crossing a plane at a vertex counts it once); empty for
    /// NaN.
    pub fn between(&self, a: f64, b: f64) -> std::ops::Range<i64> {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        let k0 = ((lo - self.offset) / self.spacing).ceil();
        let k1 = ((hi - self.offset) / self.spacing).ceil() - 1.0;
        if k0.is_finite() && k1.is_finite() && k1 - k0 < 1e7 {
            k0 as i64..k1 as i64 + 1
        } else {
            0..0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_along_a_direction() {
        let s = Sections::along(0.0, 2.0).unwrap();
        assert_eq!(s.normal, Vec3::y());
        assert_eq!(s.coordinate(&Point3::new(5.0, 3.0, 1.0)), 3.0);
        assert_eq!(s.between(0.5, 6.5).collect::<Vec<_>>(), vec![1, 2, 3]);
        assert_eq!(s.between(6.5, 0.5).collect::<Vec<_>>(), vec![1, 2, 3]);
        assert_eq!(s.between(2.0, 4.0).collect::<Vec<_>>(), vec![1]);
        assert_eq!(s.between(4.0, 2.0).collect::<Vec<_>>(), vec![1]);
        assert_eq!(s.between(f64::NAN, 2.0).count(), 0);
        assert_eq!(s.plane(2).offset, 4.0);
        let d = Sections::along(std::f64::consts::FRAC_PI_3, 1.0).unwrap();
        assert!(d.normal.dot(&Vec3::new(0.5, 3f64.sqrt() / 2.0, 0.0)).abs() < 1e-15);
        assert!(Sections::along(0.0, 0.0).is_err());
        assert!(Sections::along(f64::NAN, 1.0).is_err());
    }
}
