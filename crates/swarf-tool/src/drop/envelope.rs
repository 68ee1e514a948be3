//! The lower envelope of a cutter profile: the height of the cutting surface above the
//! tip as a function of the distance `rho` from the axis, in pieces.
//!
//! A vertical cutter seen from below is the graph `z = tip + h(rho)` over the disc
//! `rho <= R`, `h` the lowest profile height at `rho` ([`Profile::height_at_radius`]).
//! Along the profile z never decreases ([`crate::profile`]), so `h` is read off the
//! segments that move outward: a bottom or side line that widens upward gives the
//! line piece `h = h0 + k (rho - rho0)` (`k >= 0`, `k = 0` a flat bottom), an arc
//! below its centre gives the circle piece `h = cz - sqrt(r^2 - (rho - ce)^2)`
//! (`ce = 0`: a sphere, `ce > 0`: a torus). A vertical line (cylinder side) adds
//! nothing (its lowest point ends the piece before it), and once the profile turns
//! inward (an arc past its equator, a side line narrowing upward) nothing above is
//! ever the lowest point. Each piece is convex in `rho`, the joints are tangent or
//! convex corners, so `h` is convex: the cutter is a convex solid, and the drop onto a
//! triangle is a concave maximisation ([`super::kernel`]).
//!
//! The pieces are closed forms without trigonometry; tests pin them to
//! [`Profile::height_at_radius`]. The same envelope serves the drop-cutter kernels here
//! and the exact swept minimum of a straight move in the simulator (swarf-sim).

use crate::profile::{MAX_SEGMENTS, Profile};
use crate::segment::Segment;
use swarf_geom::tol::LENGTH_EPS;

/// One piece of the lower envelope over `rho` in `[rho0, rho1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// `h = h0 + k (rho - rho0)`, `k >= 0`.
    Line {
        /// Inner radius.
        rho0: f64,
        /// Outer radius.
        rho1: f64,
        /// Height at `rho0`.
        h0: f64,
        /// Slope `dh/drho`.
        k: f64,
    },
    /// `h = cz - sqrt(r^2 - (rho - ce)^2)`, with `ce <= rho0 <= rho1 <= ce + r`.
    Arc {
        /// Inner radius.
        rho0: f64,
        /// Outer radius.
        rho1: f64,
        /// Distance of the arc centre from the axis.
        ce: f64,
        /// Height of the arc centre above the tip.
        cz: f64,
        /// Arc radius.
        r: f64,
    },
}

impl Piece {
    /// Outer radius of the piece.
    #[inline]
    pub fn rho1(&self) -> f64 {
        match *self {
            Piece::Line { rho1, .. } | Piece::Arc { rho1, .. } => rho1,
        }
    }

    /// Inner radius of the piece.
    #[inline]
    pub fn rho0(&self) -> f64 {
        match *self {
            Piece::Line { rho0, .. } | Piece::Arc { rho0, .. } => rho0,
        }
    }

    /// Height at `rho` (the piece's formula; `rho` is not range-checked).
    #[inline]
    pub fn height(&self, rho: f64) -> f64 {
        match *self {
            Piece::Line { rho0, h0, k, .. } => h0 + k * (rho - rho0),
            Piece::Arc { ce, cz, r, .. } => {
                let q = rho - ce;
                cz - (r * r - q * q).max(0.0).sqrt()
            }
        }
    }

    /// Sine of the tilt of the surface normal at the outer end (0 for a flat bottom, 1
    /// at an arc's equator): the largest tilt of a plane this piece touches.
    pub fn max_tilt_sine(&self) -> f64 {
        match *self {
            Piece::Line { k, .. } => k / (1.0 + k * k).sqrt(),
            Piece::Arc { rho1, ce, r, .. } => ((rho1 - ce) / r).min(1.0),
        }
    }

    /// Slope `dh/drho` at `rho` (infinite at an arc's equator).
    #[inline]
    pub fn slope(&self, rho: f64) -> f64 {
        match *self {
            Piece::Line { k, .. } => k,
            Piece::Arc { ce, r, .. } => {
                let q = rho - ce;
                q / (r * r - q * q).max(0.0).sqrt()
            }
        }
    }

    /// Height and slope `dh/drho` at `rho` together (one square root for an arc).
    #[inline]
    pub fn height_slope(&self, rho: f64) -> (f64, f64) {
        match *self {
            Piece::Line { rho0, h0, k, .. } => (h0 + k * (rho - rho0), k),
            Piece::Arc { ce, cz, r, .. } => {
                let q = rho - ce;
                let s = (r * r - q * q).max(0.0).sqrt();
                (cz - s, q / s)
            }
        }
    }

    /// Slope `dh/drho` and second derivative `d2h/drho2` at `rho` (both infinite at
    /// an arc's equator; an arc's offset from its centre is taken as at least 0), for
    /// Newton steps on functions of `h` (the swept minimum of swarf-sim).
    #[inline]
    pub fn derivatives(&self, rho: f64) -> (f64, f64) {
        match *self {
            Piece::Line { k, .. } => (k, 0.0),
            Piece::Arc { ce, r, .. } => {
                let t = (rho - ce).max(0.0);
                let q = (r * r - t * t).max(0.0);
                let sq = q.sqrt();
                (t / sq, r * r / (q * sq))
            }
        }
    }
}

/// The lower envelope of a profile: pieces in increasing `rho`, contiguous from the
/// axis to the cutter's reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    pieces: [Piece; MAX_SEGMENTS],
    len: usize,
    radius: f64,
    top: f64,
}

impl Envelope {
    /// The envelope of `profile`.
    pub fn new(profile: &Profile) -> Envelope {
        let empty = Piece::Line {
            rho0: 0.0,
            rho1: 0.0,
            h0: 0.0,
            k: 0.0,
        };
        let mut env = Envelope {
            pieces: [empty; MAX_SEGMENTS],
            len: 0,
            radius: 0.0,
            top: 0.0,
        };
        for seg in profile.segments() {
            let Some(piece) = outward_piece(seg, env.radius) else {
                if seg.end().rho < seg.start().rho - LENGTH_EPS {
                    break;
                }
                continue;
            };
            env.radius = piece.rho1();
            env.top = piece.height(env.radius);
            if let Some(slot) = env.pieces.get_mut(env.len) {
                *slot = piece;
                env.len += 1;
            }
        }
        env
    }

    /// The pieces, from the axis outward.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces[..self.len.min(MAX_SEGMENTS)]
    }

    /// The reach `R`: largest `rho` of the envelope, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Height at the reach, `h(R)`, mm: the rim, the lowest point at the largest radius.
    pub fn top(&self) -> f64 {
        self.top
    }

    /// `h(rho)` for `0 <= rho <= R` (values outside are clamped to the nearest piece).
    #[inline]
    pub fn height(&self, rho: f64) -> f64 {
        let pieces = self.pieces();
        for p in pieces {
            if rho <= p.rho1() {
                return p.height(rho);
            }
        }
        pieces.last().map_or(0.0, |p| p.height(rho.min(p.rho1())))
    }

    /// `h(rho)` within the reach, `+inf` beyond it (the cutter never comes down over a
    /// point farther than `R` from its axis).
    ///
    /// # Units
    /// mm.
    #[inline]
    pub fn lowest_at(&self, rho: f64) -> f64 {
        self.pieces()
            .iter()
            .find(|p| rho <= p.rho1())
            .map_or(f64::INFINITY, |p| p.height(rho.max(p.rho0())))
    }

    /// The point `(rho, h)` of the lower surface that touches a plane whose upward unit
    /// normal has horizontal length `a` and vertical component `nz` (`a^2 + nz^2 = 1`,
    /// `nz > 0`): where the surface's own normal is the plane's. A line piece of that
    /// tilt touches along its length and gives its inner end (the lowest point); a
    /// joint between pieces takes the tilts between theirs; tilts past the last piece
    /// touch at the rim `(R, h(R))`. This is [`Profile::contact_for_normal`] for
    /// vertical axes and upward normals, without trigonometry (tests pin the two
    /// together).
    pub fn contact_for_tilt(&self, a: f64, nz: f64) -> (f64, f64) {
        for p in self.pieces() {
            if a <= p.max_tilt_sine() {
                return match *p {
                    Piece::Arc {
                        rho0, ce, cz, r, ..
                    } if a * r + ce > rho0 => (ce + r * a, cz - r * nz),
                    _ => (p.rho0(), p.height(p.rho0())),
                };
            }
        }
        (self.radius, self.top)
    }

    /// `h(rho)` and `h'(rho)` from the piece holding `rho` (at a joint, the inner
    /// piece's); beyond the reach, `h(R)` and an infinite slope.
    #[inline]
    pub fn height_slope(&self, rho: f64) -> (f64, f64) {
        self.pieces()
            .iter()
            .find(|p| rho <= p.rho1())
            .map_or((self.top, f64::INFINITY), |p| p.height_slope(rho))
    }

    /// Slope `h'(rho)` from the piece holding `rho` (at a joint, the inner piece's).
    pub fn slope(&self, rho: f64) -> f64 {
        self.pieces()
            .iter()
            .find(|p| rho <= p.rho1())
            .map_or(f64::INFINITY, |p| p.slope(rho))
    }
}

/// The part of `seg` that moves outward beyond `from`, as an envelope piece.
fn outward_piece(seg: &Segment, from: f64) -> Option<Piece> {
    match *seg {
        Segment::Line { start, end } => {
            let dr = end.rho - start.rho;
            if dr <= LENGTH_EPS || end.rho <= from + LENGTH_EPS {
                return None;
            }
            Some(Piece::Line {
                rho0: from,
                rho1: end.rho,
                h0: start.z + (from - start.rho) * (end.z - start.z) / dr,
                k: (end.z - start.z) / dr,
            })
        }
        Segment::Arc {
            centre,
            radius,
            start_angle,
            end_angle,
            ..
        } => {
            if start_angle >= 0.0 {
                return None;
            }
            let rho1 = if end_angle >= 0.0 {
                centre.rho + radius
            } else {
                centre.rho + radius * end_angle.cos()
            };
            if rho1 <= from + LENGTH_EPS {
                return None;
            }
            Some(Piece::Arc {
                rho0: from,
                rho1,
                ce: centre.rho,
                cz: centre.z,
                r: radius,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Apt, Cutter};

    fn cutters() -> Vec<Cutter> {
        let deg = f64::to_radians;
        vec![
            Cutter::flat(6.0, None).unwrap(),
            Cutter::ball(8.0, None).unwrap(),
            Cutter::bull(10.0, 2.0, None).unwrap(),
            Cutter::bull(10.0, 5.0, None).unwrap(),
            Cutter::bull(10.0, 0.0, None).unwrap(),
            Cutter::cone(10.0, deg(45.0), None).unwrap(),
            Cutter::cone(6.0, deg(15.0), None).unwrap(),
            Cutter::taper_ball(6.0, deg(10.0), 1.0, None).unwrap(),
            Cutter::taper_ball(6.0, 0.0, 1.0, None).unwrap(),
            Cutter::Apt(Apt::from_corner(10.0, 1.5, deg(10.0), deg(5.0), 30.0).unwrap()),
            Cutter::Apt(Apt::from_corner(12.0, 3.0, deg(30.0), deg(-20.0), 15.0).unwrap()),
            Cutter::Apt(Apt::from_corner(8.0, 0.0, deg(20.0), deg(10.0), 30.0).unwrap()),
        ]
    }

    #[test]
    fn heights_equal_the_profile_everywhere() {
        for c in cutters() {
            let p = c.profile();
            let env = Envelope::new(&p);
            assert!((env.radius() - p.radius()).abs() < 1e-12, "{c}");
            for i in 0..=2000 {
                let rho = env.radius() * f64::from(i) / 2000.0;
                let want = p.height_at_radius(rho).unwrap();
                assert!((env.height(rho) - want).abs() < 1e-12, "{c} at {rho}");
            }
            let top = p.height_at_radius(p.radius()).unwrap();
            assert!((env.top() - top).abs() < 1e-12, "{c}");
        }
    }

    #[test]
    fn pieces_are_contiguous_and_convex() {
        for c in cutters() {
            let env = Envelope::new(&c.profile());
            let mut at = 0.0;
            let mut slope = 0.0;
            for p in env.pieces() {
                assert_eq!(p.rho0(), at, "{c}");
                assert!(p.rho1() > p.rho0(), "{c}");
                let s0 = p.slope(p.rho0());
                assert!(s0 >= slope - 1e-9, "{c}: slope falls from {slope} to {s0}");
                slope = p.slope(p.rho1());
                at = p.rho1();
            }
        }
    }

    #[test]
    fn tilt_contacts_equal_the_profiles_contact_for_normal() {
        use swarf_geom::Vec3;
        for c in cutters() {
            let p = c.profile();
            let env = Envelope::new(&p);
            for i in 0..=400 {
                let tilt = 0.9999 * std::f64::consts::FRAC_PI_2 * f64::from(i) / 400.0;
                let (a, nz) = tilt.sin_cos();
                let (rho, h) = env.contact_for_tilt(a, nz);
                let n = Vec3::new(a, 0.0, nz);
                // Where the profile has a point with this normal on the lower surface,
                // it is the same point; past the flank, ours is the rim.
                if let Some((pc, _)) = p.contact_for_normal(&n, &Vec3::z()) {
                    let on_lower =
                        (p.height_at_radius(pc.point.rho).unwrap() - pc.point.z).abs() < 1e-9;
                    if on_lower && pc.point.rho <= env.radius() + 1e-12 {
                        assert!(
                            (rho - pc.point.rho).abs() < 1e-9 && (h - pc.point.z).abs() < 1e-9,
                            "{c} tilt {tilt}: ({rho}, {h}) vs {:?}",
                            pc.point
                        );
                        continue;
                    }
                }
                assert_eq!((rho, h), (env.radius(), env.top()), "{c} tilt {tilt}");
            }
        }
    }

    #[test]
    fn named_shapes_give_their_pieces() {
        let ball = Envelope::new(&Cutter::ball(8.0, None).unwrap().profile());
        assert_eq!(ball.pieces().len(), 1);
        assert!(matches!(ball.pieces()[0], Piece::Arc { ce, .. } if ce == 0.0));
        assert_eq!(ball.top(), 4.0);
        let bull = Envelope::new(&Cutter::bull(10.0, 2.0, None).unwrap().profile());
        assert_eq!(bull.pieces().len(), 2);
        assert_eq!((bull.radius(), bull.top()), (5.0, 2.0));
        let flat = Envelope::new(&Cutter::flat(6.0, None).unwrap().profile());
        assert_eq!(
            (flat.pieces().len(), flat.radius(), flat.top()),
            (1, 3.0, 0.0)
        );
        assert_eq!(flat.slope(1.0), 0.0);
        assert!(ball.slope(4.0).is_infinite());
        for env in [ball, bull, flat] {
            for k in 0..=40 {
                let rho = env.radius() * f64::from(k) / 40.0;
                let (h, s) = env.height_slope(rho);
                assert_eq!(h, env.height(rho), "{rho}");
                let t = env.slope(rho);
                assert!(s == t || (s - t).abs() <= 1e-12 * (1.0 + t.abs()), "{rho}");
            }
            assert_eq!(env.height_slope(env.radius() + 1.0).1, f64::INFINITY);
        }
    }
}
