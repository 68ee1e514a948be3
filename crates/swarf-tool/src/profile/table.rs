//! Points of a cutter profile by normal direction and their arc-length positions, with
//! the choices the generating curves need where a normal angle does not name one point
//! (thesis 000 §5.2, eq. 5.1: the profile as bottom cone, torus and side cone).
//!
//! Along a profile the outward normal angle `psi` never decreases ([`crate::profile`]
//! conventions). A normal angle is met by one point of an arc, by a corner (a sharp
//! joint takes the whole fan of angles between its two segments), or by a whole
//! straight piece. On a straight piece the end next to the middle of the profile is
//! taken: the outer end of the bottom line (the rim of a flat bottom, where the
//! generating circle of a flat cut runs, thesis §3.3), the lower end of a side line.
//! (This differs from [`Profile::contact_for_normal_angle`], which takes a straight
//! piece's lowest point, as a drop onto a plane needs.)

use crate::profile::{MAX_SEGMENTS, Profile};
use crate::segment::{RhoZ, Segment};
use std::f64::consts::FRAC_PI_2;

/// Sines of normal angles closer than this are equal (dimensionless).
const SINE_EPS: f64 = 1e-12;

/// The profile prepared for lookups by normal direction, without trigonometry in the
/// hot path: since the normal angle `psi` is in `[-pi/2, pi/2]` and never decreases
/// along the profile, its sine `n_z` does neither, so ranges are compared by sines.
/// No allocation.
#[derive(Debug, Clone)]
pub struct ProfileTable<'a> {
    profile: &'a Profile,
    segs: [SegInfo; MAX_SEGMENTS],
    len: usize,
}

/// One segment with the sines of its end normal angles and its arc-length start.
#[derive(Debug, Clone, Copy)]
struct SegInfo {
    seg: Segment,
    n0: f64,
    s0: f64,
    s1: f64,
    acc: f64,
}

impl<'a> ProfileTable<'a> {
    /// The table of `profile`.
    pub fn new(profile: &'a Profile) -> ProfileTable<'a> {
        let mut segs = [SegInfo {
            seg: Segment::Line {
                start: RhoZ::default(),
                end: RhoZ::default(),
            },
            n0: 0.0,
            s0: 0.0,
            s1: 0.0,
            acc: 0.0,
        }; MAX_SEGMENTS];
        let mut acc = 0.0;
        let mut len = 0;
        for (slot, seg) in segs.iter_mut().zip(profile.segments()) {
            let (n0, n1) = seg.normal_angles();
            *slot = SegInfo {
                seg: *seg,
                n0,
                s0: n0.sin(),
                s1: n1.sin(),
                acc,
            };
            acc += seg.length();
            len += 1;
        }
        ProfileTable { profile, segs, len }
    }

    /// The profile.
    pub fn profile(&self) -> &'a Profile {
        self.profile
    }

    fn segs(&self) -> &[SegInfo] {
        &self.segs[..self.len]
    }

    /// The profile point whose outward unit normal is `(n_rho, n_z)` (`n_rho >= 0`), by
    /// the rules of the module doc; the tip below the range, the top above it.
    pub fn point_for_normal(&self, n_rho: f64, n_z: f64) -> RhoZ {
        for (k, info) in self.segs().iter().enumerate() {
            if k == 0 && n_z < info.s0 - SINE_EPS {
                return info.seg.start();
            }
            match info.seg {
                Segment::Arc {
                    centre,
                    radius,
                    start,
                    end,
                    ..
                } if n_z >= info.s0 - SINE_EPS && n_z <= info.s1 + SINE_EPS => {
                    if n_z <= info.s0 {
                        return start;
                    }
                    if n_z >= info.s1 {
                        return end;
                    }
                    return RhoZ::new(centre.rho + radius * n_rho, centre.z + radius * n_z);
                }
                Segment::Line { start, end } if (n_z - info.s0).abs() <= SINE_EPS => {
                    return if k == 0 { end } else { start };
                }
                _ => {}
            }
            if n_z > info.s1 && self.segs().get(k + 1).is_none_or(|next| n_z < next.s0) {
                return info.seg.end();
            }
        }
        self.profile.top()
    }

    /// Arc-length position (mm from the tip) of the profile point `q` (one of those
    /// [`ProfileTable::point_for_normal`] returns).
    pub fn arc_position(&self, q: RhoZ) -> f64 {
        let mut best = (f64::INFINITY, 0.0);
        for info in self.segs() {
            let (d, at) = match info.seg {
                Segment::Line { start, end } => {
                    let (dr, dz) = (end.rho - start.rho, end.z - start.z);
                    let len2 = dr * dr + dz * dz;
                    let t = if len2 > 0.0 {
                        (((q.rho - start.rho) * dr + (q.z - start.z) * dz) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let d = (q.rho - start.rho - t * dr).hypot(q.z - start.z - t * dz);
                    (d, t * len2.sqrt())
                }
                Segment::Arc {
                    centre,
                    radius,
                    end_angle,
                    ..
                } => {
                    let ang = (q.z - centre.z)
                        .atan2(q.rho - centre.rho)
                        .clamp(info.n0, end_angle);
                    let d = ((q.rho - centre.rho).hypot(q.z - centre.z) - radius).abs();
                    (d, radius * (ang - info.n0))
                }
            };
            if d < best.0 - 1e-12 {
                best = (d, info.acc + at);
            }
        }
        best.1
    }
}

impl Profile {
    /// The profile point with outward normal angle `psi` (radians; module doc for the
    /// choices at straight pieces and corners); the tip below the range, the top
    /// above it.
    ///
    /// # Units
    /// mm.
    pub fn point_for_angle(&self, psi: f64) -> RhoZ {
        let (s, c) = psi.clamp(-FRAC_PI_2, FRAC_PI_2).sin_cos();
        ProfileTable::new(self).point_for_normal(c.max(0.0), s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cutter;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn bull() -> Profile {
        Cutter::bull(10.0, 2.0, Some(20.0)).unwrap().profile()
    }

    /// The straightforward lookup by angle, as an oracle for the table.
    fn locate_angle(profile: &Profile, psi: f64) -> (RhoZ, f64) {
        const ANGLE_EPS: f64 = 1e-12;
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

    #[test]
    fn table_agrees_with_the_angle_lookup() {
        let tools = [
            "bull:d=10,r=2",
            "ball:d=8",
            "flat:d=6",
            "cone:d=10,angle=60",
            "apt:d=10,r=1.5,alpha=10,beta=5",
        ];
        for spec in tools {
            let cutter: Cutter = spec.parse().unwrap();
            let p = cutter.profile();
            let table = ProfileTable::new(&p);
            for k in 0..=400 {
                let psi = -FRAC_PI_2 + PI * k as f64 / 400.0;
                let (q, s) = locate_angle(&p, psi);
                let t = table.point_for_normal(psi.cos().max(0.0), psi.sin());
                assert!(
                    (q.rho - t.rho).abs() < 1e-9 && (q.z - t.z).abs() < 1e-9,
                    "{spec} {psi}: {q:?} {t:?}"
                );
                assert!((table.arc_position(t) - s).abs() < 1e-6, "{spec} {psi}");
            }
        }
    }

    #[test]
    fn profile_lookups() {
        let p = bull();
        assert_eq!(p.point_for_angle(-FRAC_PI_2), RhoZ::new(3.0, 0.0));
        assert_eq!(p.point_for_angle(0.0), RhoZ::new(5.0, 2.0));
        assert_eq!(p.point_for_angle(1.0), RhoZ::new(5.0, 20.0));
        let q = p.point_for_angle(-FRAC_PI_2 / 3.0);
        assert!((q.rho - (3.0 + 3f64.sqrt())).abs() < 1e-12 && (q.z - 1.0).abs() < 1e-12);
        let s = ProfileTable::new(&p).arc_position(q);
        assert!((s - (3.0 + 2.0 * FRAC_PI_2 * 2.0 / 3.0)).abs() < 1e-12);
        assert!((p.arc_position_at_height(1.0) - s).abs() < 1e-12);
        assert_eq!(p.arc_position_at_height(0.0), 3.0);
        assert!((p.arc_position_at_height(10.0) - (3.0 + PI + 8.0)).abs() < 1e-12);
        assert_eq!(p.full_radius_height(), 2.0);
        let flat = Cutter::flat(6.0, Some(10.0)).unwrap().profile();
        assert_eq!(flat.point_for_angle(-FRAC_PI_2), RhoZ::new(3.0, 0.0));
        assert_eq!(flat.point_for_angle(-0.4), RhoZ::new(3.0, 0.0));
        assert_eq!(flat.point_for_angle(0.0), RhoZ::new(3.0, 0.0));
        assert_eq!(flat.full_radius_height(), 0.0);
        let cone = Cutter::cone(10.0, std::f64::consts::FRAC_PI_4, Some(20.0))
            .unwrap()
            .profile();
        assert_eq!(cone.point_for_angle(-FRAC_PI_2), RhoZ::new(0.0, 0.0));
    }
}
