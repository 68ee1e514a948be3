//! Points of a cutter profile by normal angle, arc length and height, with the choices
//! the generating curves need where a normal angle does not name one point (thesis 000
//! §5.2, eq. 5.1: the profile as bottom cone, torus and side cone).
//!
//! Along a profile the outward normal angle `psi` never decreases (swarf-tool's
//! [`swarf_tool::profile`] conventions). A normal angle is met by one point of an arc, by
//! a corner (a sharp joint takes the whole fan of angles between its two segments), or by
//! a whole straight piece. On a straight piece the end next to the middle of the profile
//! is taken: the outer end of the bottom line (the rim of a flat bottom, where the
//! generating circle of a flat cut runs, thesis §3.3), the lower end of a side line.

use swarf_geom::tol::LENGTH_EPS;
use swarf_tool::{Profile, RhoZ, Segment};

/// Normal angles closer than this are equal (radians).
const ANGLE_EPS: f64 = 1e-12;

/// The profile point with outward normal angle `psi` (module doc for the choices at
/// straight pieces and corners); the tip below the range, the top above it.
pub fn point_for_angle(profile: &Profile, psi: f64) -> RhoZ {
    locate_angle(profile, psi).0
}

/// [`point_for_angle`] with the point's arc-length position along the profile (mm
/// from the tip).
pub fn locate_angle(profile: &Profile, psi: f64) -> (RhoZ, f64) {
    let segs = profile.segments();
    let mut acc = 0.0;
    for (k, seg) in segs.iter().enumerate() {
        let (n0, n1) = seg.normal_angles();
        let len = seg.length();
        if k == 0 && psi < n0 - ANGLE_EPS {
            return (seg.start(), 0.0);
        }
        match *seg {
            Segment::Arc { centre, radius, .. }
                if psi >= n0 - ANGLE_EPS && psi <= n1 + ANGLE_EPS =>
            {
                let a = psi.clamp(n0, n1);
                let (s, c) = a.sin_cos();
                let q = RhoZ::new(centre.rho + radius * c, centre.z + radius * s);
                return (q, acc + radius * (a - n0));
            }
            Segment::Line { start, end } if (psi - n0).abs() <= ANGLE_EPS => {
                return if k == 0 {
                    (end, acc + len)
                } else {
                    (start, acc)
                };
            }
            _ => {}
        }
        acc += len;
        if psi > n1
            && segs
                .get(k + 1)
                .is_none_or(|next| psi < next.normal_angles().0)
        {
            return (seg.end(), acc);
        }
    }
    (profile.top(), acc)
}

/// Arc-length position (mm from the tip) of the lowest profile point at height `h`;
/// the whole length above the profile.
pub fn arc_position_at_height(profile: &Profile, h: f64) -> f64 {
    let mut acc = 0.0;
    for seg in profile.segments() {
        let (a, b) = (seg.start(), seg.end());
        let len = seg.length();
        if h <= b.z {
            let within = if b.z - a.z <= LENGTH_EPS {
                len
            } else {
                match *seg {
                    Segment::Line { .. } => len * ((h - a.z) / (b.z - a.z)).max(0.0),
                    Segment::Arc {
                        centre,
                        radius,
                        start_angle,
                        end_angle,
                        ..
                    } => {
                        let ang = ((h - centre.z) / radius).clamp(-1.0, 1.0).asin();
                        radius * (ang.clamp(start_angle, end_angle) - start_angle)
                    }
                }
            };
            return acc + within;
        }
        acc += len;
    }
    acc
}

/// The lowest height where the profile reaches its full radius (the default wall top).
pub fn full_radius_height(profile: &Profile) -> f64 {
    let r = profile.radius();
    profile
        .segments()
        .iter()
        .flat_map(|s| [s.start(), s.end()])
        .filter(|q| q.rho >= r - 1e-9 * r.max(1.0))
        .map(|q| q.z)
        .fold(f64::INFINITY, f64::min)
        .min(profile.top().z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};
    use swarf_tool::Cutter;

    fn bull() -> Profile {
        Cutter::bull(10.0, 2.0, Some(20.0)).unwrap().profile()
    }

    #[test]
    fn profile_lookups() {
        let p = bull();
        assert_eq!(point_for_angle(&p, -FRAC_PI_2), RhoZ::new(3.0, 0.0));
        assert_eq!(point_for_angle(&p, 0.0), RhoZ::new(5.0, 2.0));
        assert_eq!(point_for_angle(&p, 1.0), RhoZ::new(5.0, 20.0));
        let q = point_for_angle(&p, -FRAC_PI_2 / 3.0);
        assert!((q.rho - (3.0 + 3f64.sqrt())).abs() < 1e-12 && (q.z - 1.0).abs() < 1e-12);
        let (_, s) = locate_angle(&p, -FRAC_PI_2 / 3.0);
        assert!((s - (3.0 + 2.0 * FRAC_PI_2 * 2.0 / 3.0)).abs() < 1e-12);
        assert!((arc_position_at_height(&p, 1.0) - s).abs() < 1e-12);
        assert_eq!(arc_position_at_height(&p, 0.0), 3.0);
        assert!((arc_position_at_height(&p, 10.0) - (3.0 + PI + 8.0)).abs() < 1e-12);
        assert_eq!(full_radius_height(&p), 2.0);
        let flat = Cutter::flat(6.0, Some(10.0)).unwrap().profile();
        assert_eq!(point_for_angle(&flat, -FRAC_PI_2), RhoZ::new(3.0, 0.0));
        assert_eq!(point_for_angle(&flat, -0.4), RhoZ::new(3.0, 0.0));
        assert_eq!(point_for_angle(&flat, 0.0), RhoZ::new(3.0, 0.0));
        assert_eq!(full_radius_height(&flat), 0.0);
        let cone = Cutter::cone(10.0, std::f64::consts::FRAC_PI_4, Some(20.0))
            .unwrap()
            .profile();
        assert_eq!(point_for_angle(&cone, -FRAC_PI_2), RhoZ::new(0.0, 0.0));
    }
}
