//! The exact minimum of a vertical cutter's lower envelope along a straight move.
//!
//! A vertical tool whose tip is at `(p, z)` reaches, over the point `q`, down to
//! `z + h(|p - q|)`, where `h(rho)` is the lowest height of the profile at radius `rho`:
//! swarf-tool's [`Envelope`], in pieces that are each either
//!
//! - a line `h = h0 + k (rho - rho0)`, `k >= 0` (flat bottom, cone), or
//! - a lower arc `h = cz - sqrt(r^2 - (rho - ce)^2)` with `rho >= ce` (sphere for
//!   `ce = 0`, torus for `ce > 0`),
//!
//! each convex and non-decreasing in `rho`.
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
//! - sphere (`ce = 0`): `m + w / sqrt(r^2 - d^2 - w^2) = 0` gives
//!   `w* = -m sqrt(r^2 - d^2) / sqrt(1 + m^2)` (the lowest point of a capsule);
//! - torus (`ce > 0`): the stationary condition is a quartic; `g'` is monotone, so a
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

use swarf_tool::drop::Envelope;
use swarf_tool::drop::envelope::Piece;

/// Relative width at which the torus bracket stops (dimensionless).
pub const TORUS_BRACKET: f64 = 1e-13;
/// Largest number of Newton/bisection steps on a torus piece.
const TORUS_MAX_STEPS: usize = 200;

/// The lowest point, relative to the move's start height, that the tool with lower
/// envelope `env` reaches over a cell at along-distance `s` and perpendicular distance
/// `d >= 0` from a move of XY length `len` and slope `m`: `min over w in [-s, len - s]
/// of m (s + w) + h(sqrt(w^2 + d^2))`; `+inf` when the tool never covers the cell.
///
/// # Units
/// mm (`m` dimensionless).
#[inline]
pub fn swept_min(env: &Envelope, s: f64, d: f64, len: f64, m: f64) -> f64 {
    swept_min_below(env, s, d, len, m, f64::INFINITY)
}

/// [`swept_min`] when it is below `cap`, else `+inf`. Pieces whose cheap lower bound
/// (the slope term's least value plus `h` at the interval's point nearest the foot
/// point) is not below the best so far are skipped, which spares the torus its root
/// search wherever the cell is already lower.
///
/// # Units
/// mm (`m` dimensionless).
#[inline]
pub fn swept_min_below(env: &Envelope, s: f64, d: f64, len: f64, m: f64, cap: f64) -> f64 {
    let (a, b) = (-s, len - s);
    let start = cap - m * s;
    let mut best = start;
    let try_interval = |p: &Piece, lo: f64, hi: f64, best: &mut f64| {
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return;
        }
        let near = 0.0f64.clamp(lo, hi);
        let bound = (m * lo).min(m * hi) + p.height((near * near + d * d).sqrt().max(p.rho0()));
        if bound < *best {
            *best = best.min(interval_min(p, lo, hi, d, m));
        }
    };
    for p in env.pieces() {
        let (r0, r1) = (p.rho0(), p.rho1());
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

/// `g(w) = m w + h(sqrt(w^2 + d^2))` on piece `p`.
#[inline]
fn g(p: &Piece, w: f64, d: f64, m: f64) -> f64 {
    m * w + p.height((w * w + d * d).sqrt())
}

/// `g'(w)` and `g''(w)`.
#[inline]
fn dg(p: &Piece, w: f64, d: f64, m: f64) -> (f64, f64) {
    let rho = (w * w + d * d).sqrt();
    if rho <= 0.0 {
        return (m, f64::INFINITY);
    }
    let (h1, h2) = p.derivatives(rho);
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
        Piece::Arc { ce, r, .. } if ce <= 0.0 => {
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
                assert!((env.lowest_at(rho) - want).abs() < 1e-12, "{c} rho {rho}");
            }
            assert_eq!(env.lowest_at(env.radius() + 1e-6), f64::INFINITY);
        }
        let bull = Envelope::new(&"bull:d=10,r=2".parse::<Cutter>().unwrap().profile());
        assert_eq!(bull.pieces().len(), 2);
    }

    /// Brute force: dense sampling, then golden-section refinement of the best sample
    /// on the convex pieces (an independent route to the minimum).
    fn brute(env: &Envelope, s: f64, d: f64, len: f64, m: f64) -> f64 {
        let f = |w: f64| m * (s + w) + env.lowest_at((w * w + d * d).sqrt().min(env.radius()));
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
            let got = swept_min(&env, s, d, len, m);
            let capped = swept_min_below(&env, s, d, len, m, cap);
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
            assert_eq!(swept_min(&env, 3.0, d, 6.0, 0.0), env.lowest_at(d));
        }
        // A ball climbing at slope m: the capsule's lowest point at perpendicular
        // distance d, mid-move: -sqrt(r^2 - d^2) sqrt(1 + m^2) + r + m s.
        let r = 4.0;
        let ball = Envelope::new(&Cutter::ball(2.0 * r, None).unwrap().profile());
        let (s, d, m) = (5.0, 1.5, 0.4);
        let want = r + m * s - (r * r - d * d).sqrt() * (1.0 + m * m).sqrt();
        assert!((swept_min(&ball, s, d, 10.0, m) - want).abs() < 1e-12);
    }
}
