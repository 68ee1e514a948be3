//! Whole-profile queries along the meridian chain: arc-length position at a height,
//! where the full radius is reached, the corner centre, convexity, the lowest point of
//! the tilted tool, and the chain as a polyline.
//!
//! Along the chain z never decreases ([`crate::profile`]), so the lowest point at a
//! height is on the first segment that reaches it, and a polyline cut at a height stops
//! at the first point above it. A profile bounds a convex solid of revolution exactly
//! when its outward normal angle never decreases along the chain (the outline turns one
//! way only) and stays within `[-pi/2, pi/2]`.

use crate::pose::Pose;
use crate::profile::Profile;
use crate::segment::{RhoZ, Segment};
use std::f64::consts::FRAC_PI_2;
use swarf_geom::tol::LENGTH_EPS;

/// Normal angles within this of each other count as equal when testing convexity
/// (radians).
pub const CONVEX_EPS: f64 = 1e-9;

/// A polyline point counts as above the cut height when higher by more than this (mm).
const CUT_SLACK: f64 = 1e-12;

impl Profile {
    /// Arc-length position (mm from the tip) of the lowest profile point at height
    /// `h`; the whole length above the profile.
    ///
    /// # Units
    /// mm.
    pub fn arc_position_at_height(&self, h: f64) -> f64 {
        let mut acc = 0.0;
        for seg in self.segments() {
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

    /// The lowest height where the profile reaches its full radius (the default wall
    /// top of the generating curves).
    ///
    /// # Units
    /// mm.
    pub fn full_radius_height(&self) -> f64 {
        let r = self.radius();
        self.segments()
            .iter()
            .flat_map(|s| [s.start(), s.end()])
            .filter(|q| q.rho >= r - 1e-9 * r.max(1.0))
            .map(|q| q.z)
            .fold(f64::INFINITY, f64::min)
            .min(self.top().z)
    }

    /// The centre of the first arc (a ball's centre, a bull's corner centre); without
    /// an arc, the end of the first segment (a flat's rim, a cone's top); the tip for an
    /// empty profile. A starting point for searches by normal direction.
    pub fn corner_centre(&self) -> RhoZ {
        let segs = self.segments();
        segs.iter()
            .find_map(|s| match *s {
                Segment::Arc { centre, .. } => Some(centre),
                Segment::Line { .. } => None,
            })
            .or_else(|| segs.first().map(Segment::end))
            .unwrap_or_default()
    }

    /// True when the outline's normal angle never decreases along the chain and ends
    /// at most at `pi/2` (within [`CONVEX_EPS`]): the solid of revolution is convex.
    pub fn is_convex(&self) -> bool {
        let mut prev = -FRAC_PI_2;
        for s in self.segments() {
            let (a, b) = s.normal_angles();
            if a < prev - CONVEX_EPS || b < a - CONVEX_EPS {
                return false;
            }
            prev = b;
        }
        prev <= FRAC_PI_2 + CONVEX_EPS
    }

    /// Height of the lowest point of the tool above its tip when its axis has the
    /// vertical component `axis_z` (the cosine of its tilt `theta` from +z; clamped
    /// to `[0, 1]`), mm (at most 0). A profile point `(rho, z)` revolved about the
    /// tilted axis reaches down to `z cos(theta) - rho sin(theta)` below the tip; the
    /// least of that linear form over the chain lies at a segment's end or, on an
    /// arc, where its outward normal points straight down: at polar angle
    /// `theta - pi/2` (a bull's `r cos(theta) - (R - r) sin(theta) - r`).
    pub fn lowest_when_tilted(&self, axis_z: f64) -> f64 {
        let c = if axis_z.is_nan() {
            1.0
        } else {
            axis_z.clamp(0.0, 1.0)
        };
        let s = (1.0 - c * c).sqrt();
        let below = |q: RhoZ| q.z * c - q.rho * s;
        let down = c.acos() - FRAC_PI_2;
        self.segments()
            .iter()
            .flat_map(|seg| {
                let on_arc = match *seg {
                    Segment::Arc {
                        centre,
                        radius,
                        start_angle,
                        end_angle,
                        ..
                    } if (start_angle..=end_angle).contains(&down) => Some(below(centre) - radius),
                    _ => None,
                };
                [below(seg.start()), below(seg.end())]
                    .into_iter()
                    .chain(on_arc)
            })
            .fold(0.0, f64::min)
    }

    /// Height of the lowest point of the tool at `pose` (its axis of any length), mm:
    /// the tip's height plus [`Profile::lowest_when_tilted`] of the unit axis.
    pub fn lowest_at(&self, pose: &Pose) -> f64 {
        let norm = pose.axis.norm();
        let axis_z = if norm > 0.0 { pose.axis.z / norm } else { 1.0 };
        pose.cl.z + self.lowest_when_tilted(axis_z)
    }

    /// The chain from the tip up to height `top` as a polyline: the tip, then the end
    /// of each chord, every line one chord and every arc `arc_pieces` chords of equal
    /// arc length; it stops before the first point higher than `top`.
    ///
    /// # Units
    /// mm.
    pub fn polyline(&self, arc_pieces: usize, top: f64) -> Vec<RhoZ> {
        let mut out = vec![RhoZ::default()];
        for seg in self.segments() {
            let pieces = match seg {
                Segment::Line { .. } => 1,
                Segment::Arc { .. } => arc_pieces.max(1),
            };
            let len = seg.length();
            for i in 1..=pieces {
                let (q, _) = seg.point_at(len * i as f64 / pieces as f64);
                if q.z > top + CUT_SLACK {
                    return out;
                }
                out.push(q);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use crate::Cutter;
    use crate::segment::RhoZ;

    #[test]
    fn corner_centres_and_convexity() {
        let bull = Cutter::bull(10.0, 2.0, Some(20.0)).unwrap().profile();
        assert_eq!(bull.corner_centre(), RhoZ::new(3.0, 2.0));
        assert!(bull.is_convex());
        let flat = Cutter::flat(6.0, Some(10.0)).unwrap().profile();
        assert_eq!(flat.corner_centre(), RhoZ::new(3.0, 0.0));
        assert!(flat.is_convex());
        let ball = Cutter::ball(8.0, Some(10.0)).unwrap().profile();
        assert_eq!(ball.corner_centre(), RhoZ::new(0.0, 4.0));
    }

    #[test]
    fn polyline_follows_the_chain_and_stops_at_the_top() {
        let bull = Cutter::bull(10.0, 2.0, Some(20.0)).unwrap().profile();
        let all = bull.polyline(8, 20.0);
        assert_eq!(all.len(), 1 + 1 + 8 + 1);
        assert_eq!(all[0], RhoZ::new(0.0, 0.0));
        assert_eq!(all[1], RhoZ::new(3.0, 0.0));
        assert_eq!(*all.last().unwrap(), RhoZ::new(5.0, 20.0));
        for q in &all[2..10] {
            let r = (q.rho - 3.0).hypot(q.z - 2.0);
            assert!((r - 2.0).abs() < 1e-12);
        }
        let low = bull.polyline(8, 1.0);
        assert!(low.iter().all(|q| q.z <= 1.0 + 1e-12));
        assert_eq!(low.len(), 2 + 5);
    }

    #[test]
    fn the_lowest_point_of_a_tilted_tool_by_closed_forms() {
        let (big_r, r, length) = (5.0, 2.0, 20.0);
        let bull = Cutter::bull(2.0 * big_r, r, Some(length))
            .unwrap()
            .profile();
        let ball = Cutter::ball(2.0 * big_r, Some(length)).unwrap().profile();
        let flat = Cutter::flat(2.0 * big_r, Some(length)).unwrap().profile();
        for deg in [0.0, 1.0, 15.0, 45.0, 80.0, 90.0] {
            let t = f64::to_radians(deg);
            let (s, c) = t.sin_cos();
            let cases = [
                (bull, r * c - (big_r - r) * s - r),
                (ball, big_r * c - big_r),
                (flat, -big_r * s),
            ];
            for (k, (p, want)) in cases.into_iter().enumerate() {
                let got = p.lowest_when_tilted(c);
                assert!(
                    (got - want).abs() < 1e-12,
                    "{deg} deg, tool {k}: {got} vs {want}"
                );
            }
        }
        // An axis pointing below the horizon is taken as horizontal.
        let down = f64::to_radians(120.0).cos();
        assert_eq!(flat.lowest_when_tilted(down), flat.lowest_when_tilted(0.0));
        assert_eq!(bull.lowest_when_tilted(f64::NAN), 0.0);
    }
}
