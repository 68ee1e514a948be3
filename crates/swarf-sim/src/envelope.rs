//! The lower envelope of a cutter profile and its exact minimum along a straight move.
//!
//! A vertical tool whose tip is at `(p, z)` reaches, over the point `q`, down to
//! `z + h(|p - q|)`, where `h(rho)` is the lowest height of the profile at radius `rho`
//! ([`swarf_tool::Profile::height_at_radius`]). Along the profile chain z never
//! decreases, so the first segment to reach a radius holds the lowest point there: the
//! envelope is the chain with every piece that does not reach a new, larger radius cut
//! away. What is left is at most one piece per profile segment, each either
//!
//! - a line `h = z0 + k (rho - rho0)`, `k >= 0` (flat bottom, cone), or
//! - a lower arc `h = cz - sqrt(r^2 - (rho - c)^2)` with `rho >= c` (sphere for `c = 0`,
//!   torus for `c > 0`),
//!
//! and each is convex and non-decreasing in `rho`.
//!
//! # The swept minimum
//!
//! A straight move of the tip from `A` to `B` (XY length `L`, unit XY direction `e`,
//! slope `m = dz / L`) passes a cell at signed along-distance `s` from `A` and
//! perpendicular distance `d` from the line. Writing the tip's position relative to the
//! cell's foot point as `w = u - s` (`u` the distance travelled), the tool reaches
//!
//! ```text
//! z(w) = A_z + m (s + w) + h(sqrt(w^2 + d^2)),   w in [-s, L - s],
//! ```
//!
//! and the swept solid's lowest point over the cell is the minimum of `z(w)` (the swept
//! solid is the union of the tool's positions, so its lowest point on a vertical line
//! is the lowest of theirs). On each piece, `rho(w) = sqrt(w^2 + d^2)` is convex and the
//! piece's `h` convex and non-decreasing, so `g(w) = m w + h(rho(w))` is convex on each
//! interval of `w` where `rho` stays in the piece (one interval `[-W1, W1]` when
//! `d >= rho0`, else two, `W = sqrt(rho^2 - d^2)`). Its minimum on an interval is the
//! stationary point clamped into it:
//!
//! - line: `m + k w / rho = 0` gives `w* = -m d / sqrt(k^2 - m^2)` when `|m| < k`; else
//!   `g` is monotone (sign of `m`) and the minimum is an end;
//! - sphere (`c = 0`): `m + w / sqrt(r^2 - d^2 - w^2) = 0` gives
//!   `w* = -m sqrt(r^2 - d^2) / sqrt(1 + m^2)` (the lowest point of a capsule);
//! - torus (`c > 0`): the stationary condition is a quartic; `g'` is monotone, so a
//!   bracketing Newton iteration (bisection when Newton leaves the bracket) finds its
//!   root. It stops when the bracket is narrower than [`TORUS_BRACKET`] (relative), so
//!   the minimiser is found to about 1e-13 mm and, `g` being convex, the height to
//!   within `|g'| * 1e-13 mm` (below 1e-10 mm unless the torus is steeper than 1000:1
//!   there, i.e. within a micrometre of its equator).
//!
//! With `m = 0` (a level move) every piece has its minimum at `w = 0` when the cell's
//! foot point lies on the move: the pass leaves the profile itself, `z = A_z + h(d)`.
//! This is the exact swept envelope (CAMotics' `Sweep` per tool shape does the same for
//! cylinders, cones and spheres; thesis 000 §4.2 shows why sampling the end points
//! alone is wrong at coarse steps).

use std::f64::consts::FRAC_PI_2;
use swarf_geom::tol::LENGTH_EPS;
use swarf_tool::{Profile, Segment};

/// Relative width at which the torus bracket stops (dimensionless).
pub const TORUS_BRACKET: f64 = 1e-13;
/// Largest number of Newton/bisection steps on a torus piece.
const TORUS_MAX_STEPS: usize = 200;

/// One convex, non-decreasing piece of the lower envelope, over `[rho0, rho1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// `h = z0 + k (rho - rho0)`, `k >= 0`.
    Line {
        /// Lower radius.
        rho0: f64,
        /// Upper radius.
        rho1: f64,
        /// Height at `rho0`.
        z0: f64,
        /// Slope `dh / drho`, >= 0.
        k: f64,
    },
    /// `h = cz - sqrt(r^2 - (rho - c)^2)`, `c <= rho0 <= rho1 <= c + r`.
    Arc {
        /// Lower radius.
        rho0: f64,
        /// Upper radius.
        rho1: f64,
        /// Radius of the arc centre from the axis.
        c: f64,
        /// Height of the arc centre.
        cz: f64,
        /// Arc radius.
        r: f64,
    },
}

impl Piece {
    /// `(rho0, rho1)`.
    #[inline]
    pub fn range(&self) -> (f64, f64) {
        match *self {
            Piece::Line { rho0, rho1, .. } | Piece::Arc { rho0, rho1, .. } => (rho0, rho1),
        }
    }

    /// `h(rho)` by the piece's formula (no range check).
    #[inline]
    pub fn h(&self, rho: f64) -> f64 {
        match *self {
            Piece::Line { rho0, z0, k, .. } => z0 + k * (rho - rho0),
            Piece::Arc { c, cz, r, .. } => {
                let t = rho - c;
                cz - (r * r - t * t).max(0.0).sqrt()
            }
        }
    }

    /// `dh/drho` and `d2h/drho2` (infinite at a torus equator).
    #[inline]
    fn dh(&self, rho: f64) -> (f64, f64) {
        match *self {
            Piece::Line { k, .. } => (k, 0.0),
            Piece::Arc { c, r, .. } => {
                let t = (rho - c).max(0.0);
                let q = (r * r - t * t).max(0.0);
                let sq = q.sqrt();
                (t / sq, r * r / (q * sq))
            }
        }
    }
}

/// The lower envelope of a profile: up to four [`Piece`]s, by increasing radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    pieces: [Piece; 4],
    len: usize,
    radius: f64,
}

impl Envelope {
    /// The envelope of `profile` (see the module doc).
    pub fn new(profile: &Profile) -> Envelope {
        let mut env = Envelope {
            pieces: [Piece::Line {
                rho0: 0.0,
                rho1: 0.0,
                z0: 0.0,
                k: 0.0,
            }; 4],
            len: 0,
            radius: 0.0,
        };
        let mut reach = 0.0_f64;
        for seg in profile.segments() {
            if let Some(p) = lower_piece(seg, reach)
                && env.len < env.pieces.len()
            {
                env.pieces[env.len] = p;
                env.len += 1;
            }
            reach = reach.max(seg.start().rho).max(seg.end().rho);
        }
        env.radius = env.pieces().last().map_or(0.0, |p| p.range().1);
        env
    }

    /// The pieces, by increasing radius.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces[..self.len]
    }

    /// Largest radius the envelope reaches, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// `h(rho)`: the lowest profile height at radius `rho`; `+inf` beyond the radius.
    pub fn h(&self, rho: f64) -> f64 {
        self.pieces()
            .iter()
            .find(|p| rho <= p.range().1)
            .map_or(f64::INFINITY, |p| p.h(rho.max(p.range().0)))
    }

    /// The lowest point, relative to the move's start height, that the tool reaches
    /// over a cell at along-distance `s` and perpendicular distance `d >= 0` from a
    /// move of XY length `len` and slope `m`: `min over w in [-s, len - s] of
    /// m (s + w) + h(sqrt(w^2 + d^2))`; `+inf` when the tool never covers the cell.
    ///
    /// # Units
    /// mm (`m` dimensionless).
    #[inline]
    pub fn swept_min(&self, s: f64, d: f64, len: f64, m: f64) -> f64 {
        self.swept_min_below(s, d, len, m, f64::INFINITY)
    }

    /// [`Envelope::swept_min`] when it is below `cap`, else `+inf`. Pieces whose
    /// cheap lower bound (the slope term's least value plus `h` at the interval's
    /// point nearest the foot point) is not below the best so far are skipped, which
    /// spares the torus its root search wherever the cell is already lower.
    #[inline]
    pub fn swept_min_below(&self, s: f64, d: f64, len: f64, m: f64, cap: f64) -> f64 {
        let (a, b) = (-s, len - s);
        let start = cap - m * s;
        let mut best = start;
        let try_interval = |p: &Piece, lo: f64, hi: f64, best: &mut f64| {
            if lo.is_nan() || hi.is_nan() || lo > hi {
                return;
            }
            let near = 0.0f64.clamp(lo, hi);
            let bound = (m * lo).min(m * hi) + p.h((near * near + d * d).sqrt().max(p.range().0));
            if bound < *best {
                *best = best.min(interval_min(p, lo, hi, d, m));
            }
        };
        for p in self.pieces() {
            let (r0, r1) = p.range();
            if d > r1 {
                continue;
            }
            let w1 = (r1 * r1 - d * d).max(0.0).sqrt();
            if d >= r0 {
                try_interval(p, a.max(-w1), b.min(w1), &mut best);
            } else {
                let w0 = (r0 * r0 - d * d).max(0.0).sqrt();
                try_interval(p, a.max(-w1), b.min(-w0), &mut best);
                try_interval(p, a.max(w0), b.min(w1), &mut best);
            }
        }
        if best < start {
            best + m * s
        } else {
            f64::INFINITY
        }
    }
}

/// The part of `seg` that reaches radii beyond `reach` with rho increasing, as a piece.
fn lower_piece(seg: &Segment, reach: f64) -> Option<Piece> {
    match *seg {
        Segment::Line { start, end } => {
            let dr = end.rho - start.rho;
            if end.rho <= reach + LENGTH_EPS || dr <= LENGTH_EPS {
                return None;
            }
            let k = ((end.z - start.z) / dr).max(0.0);
            let rho0 = start.rho.max(reach);
            Some(Piece::Line {
                rho0,
                rho1: end.rho,
                z0: start.z + k * (rho0 - start.rho),
                k,
            })
        }
        Segment::Arc {
            centre,
            radius,
            start_angle,
            end_angle,
            ..
        } => {
            let a0 = start_angle.max(-FRAC_PI_2);
            let a1 = end_angle.min(0.0);
            if a1 <= a0 {
                return None;
            }
            // cos(-pi/2) and cos(0) exactly, so that a ball's piece starts at 0
            let cos = |a: f64| {
                if a <= -FRAC_PI_2 {
                    0.0
                } else if a >= 0.0 {
                    1.0
                } else {
                    a.cos()
                }
            };
            let rho1 = centre.rho + radius * cos(a1);
            let rho0 = (centre.rho + radius * cos(a0)).max(reach);
            (rho1 > rho0 + LENGTH_EPS).then_some(Piece::Arc {
                rho0,
                rho1,
                c: centre.rho,
                cz: centre.z,
                r: radius,
            })
        }
    }
}

/// `g(w) = m w + h(sqrt(w^2 + d^2))` on piece `p`.
#[inline]
fn g(p: &Piece, w: f64, d: f64, m: f64) -> f64 {
    m * w + p.h((w * w + d * d).sqrt())
}

/// `g'(w)` and `g''(w)`.
#[inline]
fn dg(p: &Piece, w: f64, d: f64, m: f64) -> (f64, f64) {
    let rho = (w * w + d * d).sqrt();
    if rho <= 0.0 {
        return (m, f64::INFINITY);
    }
    let (h1, h2) = p.dh(rho);
    let c = w / rho;
    let g1 = m + if c == 0.0 { 0.0 } else { h1 * c };
    (g1, h2 * c * c + h1 * d * d / (rho * rho * rho))
}

/// Minimum of the convex `g` over `[lo, hi]` (`+inf` when empty).
#[inline]
fn interval_min(p: &Piece, lo: f64, hi: f64, d: f64, m: f64) -> f64 {
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return f64::INFINITY;
    }
    if hi - lo <= 0.0 {
        return g(p, lo, d, m);
    }
    let w = match *p {
        Piece::Line { k, .. } => {
            if m.abs() >= k {
                if m >= 0.0 { lo } else { hi }
            } else {
                (-m * d / (k * k - m * m).sqrt()).clamp(lo, hi)
            }
        }
        Piece::Arc { c, r, .. } if c <= 0.0 => {
            let wr = (r * r - d * d).max(0.0).sqrt();
            (-m * wr / (1.0 + m * m).sqrt()).clamp(lo, hi)
        }
        Piece::Arc { .. } => torus_argmin(p, lo, hi, d, m),
    };
    g(p, w, d, m)
}

/// The minimiser of the convex `g` over `[lo, hi]` on a torus piece.
fn torus_argmin(p: &Piece, lo: f64, hi: f64, d: f64, m: f64) -> f64 {
    let (glo, _) = dg(p, lo, d, m);
    if glo >= 0.0 {
        return lo;
    }
    let (ghi, _) = dg(p, hi, d, m);
    if ghi <= 0.0 {
        return hi;
    }
    let (mut a, mut b) = (lo, hi);
    let mut w = 0.5 * (a + b);
    for _ in 0..TORUS_MAX_STEPS {
        let (g1, g2) = dg(p, w, d, m);
        if g1 == 0.0 {
            return w;
        }
        if g1 < 0.0 {
            a = w;
        } else {
            b = w;
        }
        if b - a <= TORUS_BRACKET * (1.0 + a.abs().max(b.abs())) {
            break;
        }
        let newton = w - g1 / g2;
        w = if newton > a && newton < b && g2.is_finite() && g2 > 0.0 {
            newton
        } else {
            0.5 * (a + b)
        };
    }
    if g(p, a, d, m) <= g(p, b, d, m) { a } else { b }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use swarf_tool::Cutter;

    fn cutters() -> Vec<Cutter> {
        vec![
            "flat:d=6".parse().unwrap(),
            "ball:d=8".parse().unwrap(),
            "bull:d=10,r=2".parse().unwrap(),
            Cutter::cone(6.0, 0.6, None).unwrap(),
            Cutter::taper_ball(12.0, 0.1, 2.0, Some(30.0)).unwrap(),
        ]
    }

    #[test]
    fn envelope_matches_height_at_radius() {
        for c in cutters() {
            let prof = c.profile();
            let env = Envelope::new(&prof);
            assert!((env.radius() - prof.radius()).abs() < 1e-12, "{c}");
            for k in 0..=400 {
                let rho = env.radius() * k as f64 / 400.0;
                let want = prof.height_at_radius(rho).unwrap();
                assert!((env.h(rho) - want).abs() < 1e-12, "{c} rho {rho}");
            }
            assert_eq!(env.h(env.radius() + 1e-6), f64::INFINITY);
        }
        let bull = Envelope::new(&"bull:d=10,r=2".parse::<Cutter>().unwrap().profile());
        assert_eq!(bull.pieces().len(), 2);
    }

    /// Brute force: dense sampling, then golden-section refinement of the best sample
    /// on the convex pieces (an independent route to the minimum).
    fn brute(env: &Envelope, s: f64, d: f64, len: f64, m: f64) -> f64 {
        let f = |w: f64| m * (s + w) + env.h((w * w + d * d).sqrt().min(env.radius()));
        let n = 20_000;
        let reach = (env.radius().powi(2) - d * d).max(0.0).sqrt();
        let (a, b) = ((-s).max(-reach), (len - s).min(reach));
        if a > b || d > env.radius() {
            return f64::INFINITY;
        }
        let mut best = (f64::INFINITY, a);
        for i in 0..=n {
            let w = a + (b - a) * i as f64 / n as f64;
            let v = f(w);
            if v < best.0 {
                best = (v, w);
            }
        }
        let step = (b - a) / n as f64;
        let (mut lo, mut hi) = ((best.1 - step).max(a), (best.1 + step).min(b));
        let gr = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let x1 = hi - gr * (hi - lo);
            let x2 = lo + gr * (hi - lo);
            if f(x1) <= f(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        best.0.min(f(0.5 * (lo + hi)))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn swept_min_matches_brute_force(
            which in 0usize..5, s in -6.0..16.0f64, d in 0.0..6.0f64,
            len in 0.0..10.0f64, m in -3.0..3.0f64, cap in -5.0..30.0f64,
        ) {
            let env = Envelope::new(&cutters()[which].profile());
            let got = env.swept_min(s, d, len, m);
            let capped = env.swept_min_below(s, d, len, m, cap);
            // (equal up to rounding at the cap itself)
            let eps = 1e-12 * (1.0 + got.abs());
            if capped.is_finite() {
                prop_assert!((capped - got).abs() <= eps && got < cap + eps);
            } else {
                prop_assert!(got >= cap - eps);
            }
            let want = brute(&env, s, d, len, m);
            if want.is_finite() {
                prop_assert!((got - want).abs() < 1e-7, "got {got} want {want}");
                prop_assert!(got <= want + 1e-12);
            } else {
                prop_assert!(got == f64::INFINITY);
            }
        }
    }

    #[test]
    fn level_pass_leaves_the_profile_and_capsule_is_closed_form() {
        let env = Envelope::new(&"bull:d=10,r=2".parse::<Cutter>().unwrap().profile());
        for k in 0..50 {
            let d = 5.0 * k as f64 / 50.0;
            assert_eq!(env.swept_min(3.0, d, 6.0, 0.0), env.h(d));
        }
        // A ball climbing at slope m: the capsule's lowest point at perpendicular
        // distance d, mid-move: -sqrt(r^2 - d^2) sqrt(1 + m^2) + r + m s.
        let r = 4.0;
        let ball = Envelope::new(&Cutter::ball(2.0 * r, None).unwrap().profile());
        let (s, d, m) = (5.0, 1.5, 0.4);
        let want = r + m * s - (r * r - d * d).sqrt() * (1.0 + m * m).sqrt();
        assert!((ball.swept_min(s, d, 10.0, m) - want).abs() < 1e-12);
    }
}
