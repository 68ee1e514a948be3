//! Profile segments: lines and circular arcs in the meridian half-plane `(rho, z)`,
//! with their closed forms (point at arc length, normal angles, lowest height at a
//! radius, largest radius at a height). Conventions in [`crate::profile`]: arcs run
//! counter-clockwise from the bottom up, polar angles from +rho toward +z, outward
//! normal of a line = its direction turned clockwise.

use swarf_geom::tol::LENGTH_EPS;

/// A point (or direction) in the cutter's meridian half-plane, mm.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RhoZ {
    /// Distance from the axis.
    pub rho: f64,
    /// Height above the tip along the axis.
    pub z: f64,
}

impl RhoZ {
    /// The point `(rho, z)`.
    pub const fn new(rho: f64, z: f64) -> Self {
        RhoZ { rho, z }
    }

    pub(crate) fn dist(self, o: RhoZ) -> f64 {
        let (dr, dz) = (self.rho - o.rho, self.z - o.z);
        (dr * dr + dz * dz).sqrt()
    }
}

/// One piece of a profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Segment {
    /// A straight line (a cone, cylinder or disc once revolved).
    Line {
        /// Lower end.
        start: RhoZ,
        /// Upper end.
        end: RhoZ,
    },
    /// A circular arc (a torus or sphere once revolved), counter-clockwise.
    Arc {
        /// Centre.
        centre: RhoZ,
        /// Radius, > 0.
        radius: f64,
        /// Polar angle of the lower end, radians, >= -pi/2.
        start_angle: f64,
        /// Polar angle of the upper end, radians, in `(start_angle, pi/2]`.
        end_angle: f64,
        /// Lower end, `centre + radius (cos, sin)(start_angle)`.
        start: RhoZ,
        /// Upper end, `centre + radius (cos, sin)(end_angle)`.
        end: RhoZ,
    },
}

impl Segment {
    /// The arc about `centre` from `start_angle` to `end_angle`.
    pub fn arc(centre: RhoZ, radius: f64, start_angle: f64, end_angle: f64) -> Segment {
        let at = |t: f64| {
            let (s, c) = t.sin_cos();
            RhoZ::new(centre.rho + radius * c, centre.z + radius * s)
        };
        Segment::Arc {
            centre,
            radius,
            start_angle,
            end_angle,
            start: at(start_angle),
            end: at(end_angle),
        }
    }

    /// The quarter circle about `centre` from straight below it (polar angle -pi/2) to
    /// its outermost point (angle 0), with exact ends (ball and bull corners).
    pub fn quarter_arc(centre: RhoZ, radius: f64) -> Segment {
        Segment::Arc {
            centre,
            radius,
            start_angle: -std::f64::consts::FRAC_PI_2,
            end_angle: 0.0,
            start: RhoZ::new(centre.rho, centre.z - radius),
            end: RhoZ::new(centre.rho + radius, centre.z),
        }
    }

    /// Lower end.
    pub fn start(&self) -> RhoZ {
        match *self {
            Segment::Line { start, .. } | Segment::Arc { start, .. } => start,
        }
    }

    /// Upper end.
    pub fn end(&self) -> RhoZ {
        match *self {
            Segment::Line { end, .. } | Segment::Arc { end, .. } => end,
        }
    }

    /// Arc length, mm.
    pub fn length(&self) -> f64 {
        match *self {
            Segment::Line { start, end } => start.dist(end),
            Segment::Arc {
                radius,
                start_angle,
                end_angle,
                ..
            } => radius * (end_angle - start_angle),
        }
    }

    /// Outward normal angles at the lower and upper ends, radians.
    pub fn normal_angles(&self) -> (f64, f64) {
        match *self {
            Segment::Line { start, end } => {
                let psi = (start.rho - end.rho).atan2(end.z - start.z);
                (psi, psi)
            }
            Segment::Arc {
                start_angle,
                end_angle,
                ..
            } => (start_angle, end_angle),
        }
    }

    /// The point at arc length `t` from the lower end (clamped) and its normal angle.
    pub fn point_at(&self, t: f64) -> (RhoZ, f64) {
        match *self {
            Segment::Line { start, end } => {
                let len = start.dist(end);
                let u = if len > 0.0 {
                    (t / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let p = RhoZ::new(
                    start.rho + u * (end.rho - start.rho),
                    start.z + u * (end.z - start.z),
                );
                (p, self.normal_angles().0)
            }
            Segment::Arc {
                centre,
                radius,
                start_angle,
                end_angle,
                ..
            } => {
                let a = (start_angle + t / radius).clamp(start_angle, end_angle);
                let (s, c) = a.sin_cos();
                (RhoZ::new(centre.rho + radius * c, centre.z + radius * s), a)
            }
        }
    }

    /// Smallest and largest rho on the segment.
    pub(crate) fn rho_range(&self) -> (f64, f64) {
        let (a, b) = (self.start().rho, self.end().rho);
        let hi = match *self {
            Segment::Arc {
                centre,
                radius,
                start_angle,
                end_angle,
                ..
            } if start_angle <= 0.0 && end_angle >= 0.0 => centre.rho + radius,
            _ => a.max(b),
        };
        (a.min(b), hi)
    }

    /// Lowest height of the segment at radius `rho`, if it reaches it.
    pub(crate) fn lowest_z_at(&self, rho: f64) -> Option<f64> {
        let (lo, hi) = self.rho_range();
        if rho < lo - LENGTH_EPS || rho > hi + LENGTH_EPS {
            return None;
        }
        match *self {
            Segment::Line { start, end } => {
                let dr = end.rho - start.rho;
                if dr.abs() <= LENGTH_EPS {
                    return Some(start.z.min(end.z));
                }
                let u = ((rho - start.rho) / dr).clamp(0.0, 1.0);
                Some(start.z + u * (end.z - start.z))
            }
            Segment::Arc {
                centre,
                radius,
                start,
                end,
                ..
            } => {
                // Profile arcs lie within polar angles [-pi/2, pi/2]: the lower branch
                // (angle -acos) holds every rho from the start outward; the upper one
                // only the rho a rising arc (end angle > 0) comes back to.
                let dr = rho.clamp(lo, hi) - centre.rho;
                let h = (radius * radius - dr * dr).max(0.0).sqrt();
                let z = if rho >= start.rho - LENGTH_EPS {
                    centre.z - h
                } else {
                    centre.z + h
                };
                Some(z.clamp(start.z, end.z))
            }
        }
    }

    /// Largest rho of the segment at height `z`, if it reaches it.
    pub(crate) fn rho_at(&self, z: f64) -> Option<f64> {
        let (a, b) = (self.start(), self.end());
        if z < a.z - LENGTH_EPS || z > b.z + LENGTH_EPS {
            return None;
        }
        match *self {
            Segment::Line { start, end } => {
                let dz = end.z - start.z;
                if dz.abs() <= LENGTH_EPS {
                    return Some(start.rho.max(end.rho));
                }
                let u = ((z - start.z) / dz).clamp(0.0, 1.0);
                Some(start.rho + u * (end.rho - start.rho))
            }
            Segment::Arc { centre, radius, .. } => {
                // Within polar angles [-pi/2, pi/2] the arc is the right half-circle.
                let dz = z.clamp(a.z, b.z) - centre.z;
                Some(centre.rho + (radius * radius - dz * dz).max(0.0).sqrt())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

    #[test]
    fn line_closed_forms() {
        let cone = Segment::Line {
            start: RhoZ::new(0.0, 0.0),
            end: RhoZ::new(3.0, 4.0),
        };
        assert_eq!(cone.length(), 5.0);
        let (n0, n1) = cone.normal_angles();
        assert!((n0 - (-3.0f64).atan2(4.0)).abs() < 1e-15 && n0 == n1);
        assert_eq!(cone.lowest_z_at(1.5), Some(2.0));
        assert_eq!(cone.rho_at(2.0), Some(1.5));
        assert_eq!(cone.lowest_z_at(3.5), None);
        let (p, _) = cone.point_at(2.5);
        assert_eq!(p, RhoZ::new(1.5, 2.0));
    }

    #[test]
    fn arc_closed_forms() {
        let corner = Segment::arc(RhoZ::new(3.0, 2.0), 2.0, -FRAC_PI_2, FRAC_PI_4);
        assert!((corner.length() - 2.0 * 0.75 * std::f64::consts::PI).abs() < 1e-14);
        assert_eq!(corner.rho_range().1, 5.0);
        // Radius 4 is met twice (below and above the equator): the lower one counts.
        let z = corner.lowest_z_at(4.0).unwrap();
        assert!((z - (2.0 - 3f64.sqrt())).abs() < 1e-14);
        // At height 3 the arc is past its equator, at polar angle 30 degrees.
        let rho = corner.rho_at(3.0).unwrap();
        assert!((rho - (3.0 + 3f64.sqrt())).abs() < 1e-14);
        assert_eq!(corner.rho_at(2.0 + 2.0 * FRAC_PI_4.sin() + 1e-6), None);
    }

    #[test]
    fn rising_arc_meets_small_radii_only_above_its_equator() {
        // From -30 to +60 degrees: radii below the start's are met on the way back in.
        let (a0, a1) = (-FRAC_PI_2 / 3.0, 2.0 * FRAC_PI_2 / 3.0);
        let arc = Segment::arc(RhoZ::new(3.0, 2.0), 2.0, a0, a1);
        assert!((arc.start().rho - (3.0 + 3f64.sqrt())).abs() < 1e-14);
        let z = arc.lowest_z_at(4.5).unwrap();
        assert!((z - (2.0 + 1.75f64.sqrt())).abs() < 1e-14);
        let z = arc.lowest_z_at(4.9).unwrap();
        assert!((z - (2.0 - (4.0f64 - 1.9 * 1.9).sqrt())).abs() < 1e-14);
        assert_eq!(arc.lowest_z_at(3.9), None);
    }
}
