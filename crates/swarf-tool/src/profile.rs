//! Cutter profiles: the outline of a cutter in its meridian half-plane.
//!
//! Every cutter of the family is a solid of revolution about its axis. Its outline in
//! the half-plane (rho, z) (rho >= 0 the distance from the axis, z the height above the
//! tip) is a short chain of segments from the tip `(0, 0)` upward: at most a bottom
//! line, a corner arc and a side line (the APT tool of thesis 000 §5.2, eq. 5.1: two
//! cones and a torus). The solid is closed at the top by the flat disc at the flute
//! length; that disc is not a cutting surface.
//!
//! Conventions:
//! - an arc's angles are polar angles about its centre, measured from +rho toward +z;
//!   the arc runs counter-clockwise (increasing angle) from the bottom upward, so its
//!   outward normal at angle `t` is `(cos t, sin t)`. Thesis eq. 5.1 measures its
//!   torus angle `theta` from -z toward +rho: `theta = t + pi/2`;
//! - a line's outward normal is its direction `(drho, dz)` turned clockwise:
//!   `(dz, -drho)`; a normal is named by its angle `psi = atan2(n_z, n_rho)`, which
//!   grows from `-pi/2` (straight down, the tip) to the side line's `-beta`;
//! - along the chain z never decreases (bottom line at `alpha >= 0`, arc within
//!   `(-pi/2, pi/2)`, side line at `|beta| < pi/2`), so "the profile at height z" is
//!   one point except on a flat bottom, and the first segment that reaches a radius
//!   holds the lowest point at that radius.
//!
//! All queries are closed forms per segment; no allocation (except
//! [`Profile::polyline`], which returns its points).
//!
//! - [`table`]: points by normal direction ([`ProfileTable`]) and their arc-length
//!   positions, as the generating curves and the five-axis checks need them.
//! - [`meridian`]: whole-chain queries: arc position at a height, full-radius height,
//!   corner centre, convexity, the chain as a polyline.
//! - the lower envelope `h(rho)` in pieces is [`crate::drop::Envelope`].

pub mod meridian;
pub mod table;

pub use table::ProfileTable;

use crate::segment::{RhoZ, Segment};
use swarf_geom::tol::LENGTH_EPS;

/// Normal angles within this of each other are treated as equal (radians).
pub const ANGLE_EPS: f64 = 1e-12;

/// The most segments a profile holds.
pub const MAX_SEGMENTS: usize = 4;

/// Where on a profile the normal takes a given direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileContact {
    /// The profile point.
    pub point: RhoZ,
    /// Its arc-length parameter in `[0, 1]` (as [`Profile::point_at`] takes it).
    pub s: f64,
    /// True when the point is a sharp corner (a cone tip, a flat end's rim, an APT
    /// corner with `r = 0`) that takes the normal from its fan rather than from a
    /// segment.
    pub corner: bool,
}

/// A cutter profile: up to [`MAX_SEGMENTS`] segments from the tip `(0, 0)` up to the
/// flute length. Built by [`crate::Cutter::profile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Profile {
    segments: [Segment; MAX_SEGMENTS],
    len: usize,
}

impl Profile {
    /// Starts a chain at the tip.
    pub(crate) fn builder() -> ProfileBuilder {
        ProfileBuilder {
            profile: Profile {
                segments: [Segment::Line {
                    start: RhoZ::default(),
                    end: RhoZ::default(),
                }; MAX_SEGMENTS],
                len: 0,
            },
            at: RhoZ::default(),
        }
    }

    /// The segments, from the tip up.
    pub fn segments(&self) -> &[Segment] {
        &self.segments[..self.len.min(MAX_SEGMENTS)]
    }

    /// The top of the cutting surface (the rim of the closing disc).
    pub fn top(&self) -> RhoZ {
        self.segments().last().map_or(RhoZ::default(), Segment::end)
    }

    /// Height of the top: the flute length, mm.
    pub fn length(&self) -> f64 {
        self.top().z
    }

    /// Largest cutting radius, mm.
    pub fn radius(&self) -> f64 {
        self.segments()
            .iter()
            .map(|s| s.rho_range().1)
            .fold(0.0, f64::max)
    }

    /// Total arc length of the segments, mm.
    pub fn arc_length(&self) -> f64 {
        self.segments().iter().map(Segment::length).sum()
    }

    /// Lowest height of the cutting surface at distance `rho` from the axis; `None`
    /// for `rho` beyond [`Profile::radius`], negative or NaN.
    ///
    /// # Units
    /// mm.
    pub fn height_at_radius(&self, rho: f64) -> Option<f64> {
        if !(rho >= 0.0 && rho <= self.radius()) {
            return None;
        }
        self.segments().iter().find_map(|s| s.lowest_z_at(rho))
    }

    /// Radius of the cutter's cross-section at height `z` above the tip (the largest
    /// profile rho there); `None` below the tip, above the flute length, or NaN.
    ///
    /// # Units
    /// mm.
    pub fn radius_at_height(&self, z: f64) -> Option<f64> {
        if !(z >= 0.0 && z <= self.length()) {
            return None;
        }
        self.segments()
            .iter()
            .filter_map(|s| s.rho_at(z))
            .reduce(f64::max)
    }

    /// The point at arc-length fraction `s` (clamped to `[0, 1]`) from the tip and its
    /// outward normal angle. At a joint the upper segment's normal is returned.
    pub fn point_at(&self, s: f64) -> (RhoZ, f64) {
        let segs = self.segments();
        let mut rest = s.clamp(0.0, 1.0) * self.arc_length();
        for (i, seg) in segs.iter().enumerate() {
            let len = seg.length();
            if rest < len || i + 1 == segs.len() {
                return seg.point_at(rest);
            }
            rest -= len;
        }
        (RhoZ::default(), -std::f64::consts::FRAC_PI_2)
    }

    /// The profile point whose outward normal has angle `psi` (radians, from +rho
    /// toward +z; `-pi/2` is straight down along the axis).
    ///
    /// A sharp corner takes every normal of its fan. Where a whole straight segment
    /// has the normal, its lowest point is returned; for `psi = -pi/2` on a flat
    /// bottom that is the tip, on the axis. `None` when no point of the cutting
    /// surface has that normal (`psi` above the side line's, i.e. facing the
    /// non-cutting top).
    pub fn contact_for_normal_angle(&self, psi: f64) -> Option<ProfileContact> {
        let segs = self.segments();
        let first = segs.first()?;
        let total = self.arc_length();
        let frac = |a: f64| if total > 0.0 { a / total } else { 0.0 };
        let (tip_end, _) = first.normal_angles();
        if psi.is_nan() || psi < -std::f64::consts::FRAC_PI_2 - ANGLE_EPS {
            return None;
        }
        if psi <= tip_end + ANGLE_EPS {
            return Some(ProfileContact {
                point: first.start(),
                s: 0.0,
                corner: psi < tip_end - ANGLE_EPS,
            });
        }
        let mut acc = 0.0;
        for (i, seg) in segs.iter().enumerate() {
            let (n0, n1) = seg.normal_angles();
            if psi >= n0 - ANGLE_EPS && psi <= n1 + ANGLE_EPS {
                let (point, along) = match *seg {
                    Segment::Line { start, .. } => (start, 0.0),
                    Segment::Arc { radius, .. } => {
                        let t = radius * (psi - n0).max(0.0);
                        (seg.point_at(t).0, t)
                    }
                };
                return Some(ProfileContact {
                    point,
                    s: frac(acc + along),
                    corner: false,
                });
            }
            acc += seg.length();
            let next = segs.get(i + 1)?;
            if psi > n1 && psi < next.normal_angles().0 {
                return Some(ProfileContact {
                    point: seg.end(),
                    s: frac(acc),
                    corner: true,
                });
            }
        }
        None
    }
}

/// Builds a profile segment by segment from the tip, dropping pieces shorter than
/// [`LENGTH_EPS`] so that special cases (a ball's empty bottom line) vanish.
pub(crate) struct ProfileBuilder {
    profile: Profile,
    at: RhoZ,
}

impl ProfileBuilder {
    /// A line from the current point to `end`.
    pub(crate) fn line_to(&mut self, end: RhoZ) -> &mut Self {
        if self.at.dist(end) > LENGTH_EPS {
            self.push(Segment::Line {
                start: self.at,
                end,
            });
            self.at = end;
        }
        self
    }

    /// A line from the current point to the start of the arc about `centre` from
    /// `start_angle` to `end_angle`, then the arc.
    pub(crate) fn arc(
        &mut self,
        centre: RhoZ,
        radius: f64,
        start_angle: f64,
        end_angle: f64,
    ) -> &mut Self {
        self.arc_segment(Segment::arc(centre, radius, start_angle, end_angle))
    }

    /// A line from the current point to the start of `arc`, then `arc`.
    pub(crate) fn arc_segment(&mut self, arc: Segment) -> &mut Self {
        self.line_to(arc.start());
        if arc.length() > LENGTH_EPS {
            self.push(arc);
            self.at = arc.end();
        }
        self
    }

    /// The current point (the end of the last segment).
    pub(crate) fn at(&self) -> RhoZ {
        self.at
    }

    fn push(&mut self, seg: Segment) {
        if let Some(slot) = self.profile.segments.get_mut(self.profile.len) {
            *slot = seg;
            self.profile.len += 1;
        }
    }

    pub(crate) fn finish(&self) -> Profile {
        self.profile
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn bull(radius: f64, corner: f64, length: f64) -> Profile {
        let mut b = Profile::builder();
        b.arc(RhoZ::new(radius - corner, corner), corner, -FRAC_PI_2, 0.0)
            .line_to(RhoZ::new(radius, length));
        b.finish()
    }

    #[test]
    fn bull_profile_has_three_segments_and_closed_forms() {
        let p = bull(5.0, 2.0, 20.0);
        assert_eq!(p.segments().len(), 3);
        assert_eq!(p.radius(), 5.0);
        assert_eq!(p.length(), 20.0);
        assert_eq!(p.height_at_radius(3.0), Some(0.0));
        let h = p.height_at_radius(4.0).unwrap();
        assert!((h - (2.0 - (4.0f64 - 1.0).sqrt())).abs() < 1e-14);
        assert_eq!(p.height_at_radius(5.0), Some(2.0));
        assert_eq!(p.height_at_radius(5.0 + 1e-9), None);
        assert_eq!(p.height_at_radius(-1.0), None);
        assert_eq!(p.height_at_radius(f64::NAN), None);
        assert_eq!(p.radius_at_height(0.0), Some(3.0));
        assert!((p.radius_at_height(1.0).unwrap() - (3.0 + 3f64.sqrt())).abs() < 1e-14);
        assert_eq!(p.radius_at_height(10.0), Some(5.0));
        assert_eq!(p.radius_at_height(20.5), None);
        let expected = 3.0 + PI_HALF_TIMES_2 + 18.0;
        assert!((p.arc_length() - expected).abs() < 1e-12);
    }

    const PI_HALF_TIMES_2: f64 = FRAC_PI_2 * 2.0;

    #[test]
    fn point_at_walks_by_arc_length() {
        let p = bull(5.0, 2.0, 20.0);
        let total = p.arc_length();
        let (q, n) = p.point_at(1.5 / total);
        assert!((q.rho - 1.5).abs() < 1e-12 && q.z == 0.0 && n == -FRAC_PI_2);
        let (q, n) = p.point_at((3.0 + FRAC_PI_2) / total);
        assert!((q.rho - (3.0 + 2f64.sqrt())).abs() < 1e-12);
        assert!((q.z - (2.0 - 2f64.sqrt())).abs() < 1e-12);
        assert!((n + std::f64::consts::FRAC_PI_4).abs() < 1e-12);
        let (q, n) = p.point_at(1.0);
        assert_eq!((q, n), (RhoZ::new(5.0, 20.0), 0.0));
    }

    #[test]
    fn contact_picks_segment_corner_or_tip() {
        let p = bull(5.0, 2.0, 20.0);
        let c = p.contact_for_normal_angle(-FRAC_PI_2).unwrap();
        assert_eq!((c.point, c.s, c.corner), (RhoZ::new(0.0, 0.0), 0.0, false));
        let c = p.contact_for_normal_angle(-FRAC_PI_2 / 3.0).unwrap();
        assert!((c.point.rho - (3.0 + 3f64.sqrt())).abs() < 1e-12);
        assert!((c.point.z - 1.0).abs() < 1e-12);
        assert!(!c.corner);
        let side = p.contact_for_normal_angle(0.0).unwrap();
        assert_eq!(side.point, RhoZ::new(5.0, 2.0));
        assert!(p.contact_for_normal_angle(0.1).is_none());
        // A flat end: the rim takes the whole fan between bottom and side.
        let mut b = Profile::builder();
        b.line_to(RhoZ::new(3.0, 0.0)).line_to(RhoZ::new(3.0, 10.0));
        let flat = b.finish();
        let c = flat.contact_for_normal_angle(-0.3).unwrap();
        assert_eq!((c.point, c.corner), (RhoZ::new(3.0, 0.0), true));
        assert!((c.s - 3.0 / 13.0).abs() < 1e-15);
    }

    #[test]
    fn builder_drops_empty_pieces_and_never_overflows() {
        let mut b = Profile::builder();
        b.line_to(RhoZ::new(0.0, 0.0));
        for k in 1..10 {
            b.line_to(RhoZ::new(k as f64, k as f64));
        }
        assert_eq!(b.finish().segments().len(), MAX_SEGMENTS);
        let empty = Profile::builder().finish();
        assert_eq!(empty.height_at_radius(0.0), None);
        assert!(empty.contact_for_normal_angle(-1.0).is_none());
    }
}
