//! The edge drop: the highest point of a concave function along a line.
//!
//! Put the edge's XY line at distance `d0` from the axis and measure `s` along it from
//! the foot of the perpendicular; the edge rises by `m` per mm of `s`. A point of the
//! line is `rho(s) = sqrt(d0^2 + s^2)` from the axis, within reach for
//! `|s| <= w = sqrt(R^2 - d0^2)`, and the cutter touching it there has its tip at
//! `f(s) = z(s) - h(rho(s))`. `f` is concave ([`super::envelope`]), so its maximum over
//! the edge is the maximum over `[-w, w]` clamped to the edge: an interior `s*` is an
//! edge contact, anything else is one of the vertex cases. `s*` is where
//! `g(s) = f'(s) = m - h'(rho) s / rho` changes sign; `g` is non-increasing, and
//! `s*` has the sign of `m` (mirror `s -> -s` for `m < 0`). Per envelope piece:
//!
//! - **line** `h' = k` (flat bottom `k = 0`, cone `k = 1/tan(half angle)`):
//!   `m rho = k s` gives `s = d0 m / sqrt(k^2 - m^2)` (when `m < k`; else past the
//!   piece). A flat end (`k = 0`) always climbs to the rim `s = w`;
//! - **sphere** (`ce = 0`, a ball or a taper ball's tip): `h' s / rho = s / sqrt(r^2 -
//!   rho^2)`, so `s = m sqrt(r^2 - d0^2) / sqrt(1 + m^2)`: the circle where the
//!   vertical plane of the edge cuts the sphere, touched by the line;
//! - **torus** (`ce > 0`, bull and APT corners): with `theta` the angle from the
//!   bottom of the corner circle, `rho = ce + r sin(theta)`, `h = cz - r cos(theta)`,
//!   `h' = tan(theta)`, and `sign(g) = sign(G)`, `G(theta) = m rho cos(theta) -
//!   s sin(theta)`: bounded and smooth up to the equator `theta = pi/2` where
//!   `h'` is infinite. `G` changes sign once on the piece's bracket, and a safeguarded
//!   Newton step ([`super::bracket`]) finds the root to [`THETA_TOL`] (contact within
//!   `r * THETA_TOL` mm), never leaving the bracket. OpenCAMLib solves the same case by
//!   an offset-ellipse iteration that can fail to converge; this cannot.
//!
//! Pieces are walked outward evaluating `g` at their ends: a sign change at a joint
//! (a convex corner of the profile, e.g. an APT `r = 0` corner) is the maximum
//! there; if `g > 0` to the end, the maximum is the rim `s = w`. Flat, ball and cone
//! cutters (one piece) take their closed form directly.

use super::bracket::root_decreasing;
use super::envelope::Piece;
use super::{DropCutter, EdgeShape};

/// Convergence of the torus edge solve in the corner angle, radians.
pub const THETA_TOL: f64 = 1e-13;

/// The maximiser `(s*, h(rho(s*)))` of `f` over `[-w, w]` for an edge line at
/// distance `d0 <= R` rising by `m` per mm, when it lies strictly inside the edge's
/// range `(lo, hi)`; `None` when the edge's maximum is at one of its ends (a vertex
/// case). Envelopes of several pieces first test the sign of `g` at the ends of the
/// range, so that only edges holding their maximum get solved.
pub(crate) fn edge_argmax(
    tool: &DropCutter,
    d0: f64,
    m: f64,
    lo: f64,
    hi: f64,
) -> Option<(f64, f64)> {
    let (s, h) = if m >= 0.0 {
        edge_argmax_rising(tool, d0, m, lo, hi)?
    } else {
        let (s, h) = edge_argmax_rising(tool, d0, -m, -hi, -lo)?;
        (-s, h)
    };
    (s > lo && s < hi).then_some((s, h))
}

/// As [`edge_argmax`] for `m >= 0` (the maximiser is at `s >= 0`).
fn edge_argmax_rising(tool: &DropCutter, d0: f64, m: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    let r = tool.radius;
    let w = (r * r - d0 * d0).max(0.0).sqrt();
    if hi <= 0.0 || lo >= w {
        return None;
    }
    Some(match tool.shape {
        EdgeShape::Flat => {
            if m > 0.0 {
                (w, 0.0)
            } else {
                (0.0, 0.0)
            }
        }
        EdgeShape::Ball => {
            let c = (1.0 + m * m).sqrt();
            (m * w / c, r - w / c)
        }
        EdgeShape::Cone { k } => match line_root(d0, m, k) {
            Some(s) if s < w => (s, k * dist(d0, s)),
            _ => (w, tool.envelope.top()),
        },
        EdgeShape::Pieces => pieces_argmax(tool, d0, m, w, [lo.max(0.0), hi.min(w)])?,
    })
}

/// `sqrt(a^2 + b^2)` (no overflow care needed at tool sizes; faster than `hypot`).
#[inline]
fn dist(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// Root of `m rho = k s` for `s >= 0`, when `m < k`.
fn line_root(d0: f64, m: f64, k: f64) -> Option<f64> {
    (m < k).then(|| d0 * m / ((k - m) * (k + m)).sqrt())
}

/// `g(s) = m - h'(rho) s / rho` on `piece`, taking `s / rho = 1` on the axis.
fn g(piece: &Piece, d0: f64, m: f64, s: f64) -> f64 {
    let rho = dist(d0, s);
    let ratio = if rho > 0.0 { s / rho } else { 1.0 };
    let slope = piece.slope(rho);
    if ratio == 0.0 { m } else { m - slope * ratio }
}

/// Upper bound of the tip height along the reachable part `[lo, hi]` of an edge
/// line (distance `d0`, rise `m`) whose tip heights at the ends are `t_lo`, `t_hi`:
/// the tip height is concave in `s`, so it lies below its tangent lines at both ends
/// (any supergradient will do at a kink), and the bound is the highest point of the
/// lower of the two lines. Used to skip the torus solve of edges that cannot reach
/// the best height found so far.
pub(crate) fn edge_upper_bound(
    tool: &DropCutter,
    d0: f64,
    m: f64,
    [lo, hi]: [f64; 2],
    [t_lo, t_hi]: [f64; 2],
) -> f64 {
    let (g_lo, g_hi) = (g_at(tool, d0, m, lo), g_at(tool, d0, m, hi));
    if g_lo <= 0.0 {
        return t_lo;
    }
    if g_hi >= 0.0 {
        return t_hi;
    }
    match (g_lo.is_finite(), g_hi.is_finite()) {
        (true, true) => {
            let s = (t_hi - t_lo + g_lo * lo - g_hi * hi) / (g_lo - g_hi);
            t_lo + g_lo * (s.clamp(lo, hi) - lo)
        }
        (true, false) => t_lo + g_lo * (hi - lo),
        (false, true) => t_hi + g_hi * (lo - hi),
        (false, false) => f64::INFINITY,
    }
}

/// `g` at `s` on the piece holding `rho(s)` (the inner one at a joint).
fn g_at(tool: &DropCutter, d0: f64, m: f64, s: f64) -> f64 {
    let rho = dist(d0, s);
    let pieces = tool.envelope.pieces();
    match pieces.iter().find(|p| rho <= p.rho1()).or(pieces.last()) {
        Some(p) => g(p, d0, m, s),
        None => m,
    }
}

/// The walk over the envelope pieces described in the module doc, within the range
/// `[a, b]` of `s` (`0 <= a <= b <= w`); `None` when `g` says the maximum of `f` over
/// `[0, w]` is outside `(a, b)`.
fn pieces_argmax(
    tool: &DropCutter,
    d0: f64,
    m: f64,
    w: f64,
    [a, b]: [f64; 2],
) -> Option<(f64, f64)> {
    let env = &tool.envelope;
    if m == 0.0 {
        return Some((0.0, env.height(d0)));
    }
    if (b < w && g_at(tool, d0, m, b) >= 0.0) || (a > 0.0 && g_at(tool, d0, m, a) <= 0.0) {
        return None;
    }
    let s_at = |rho: f64| (rho * rho - d0 * d0).max(0.0).sqrt().clamp(a, b);
    for piece in env.pieces() {
        if piece.rho1() <= d0 {
            continue;
        }
        let rho_lo = piece.rho0().max(d0);
        let (s_lo, s_hi) = (s_at(rho_lo), s_at(piece.rho1()));
        if s_hi <= a {
            continue;
        }
        if g(piece, d0, m, s_lo) <= 0.0 {
            return Some((s_lo, piece.height(dist(d0, s_lo))));
        }
        if g(piece, d0, m, s_hi) > 0.0 {
            continue;
        }
        let s = solve_in_piece(piece, d0, m, s_lo, s_hi);
        return Some((s, piece.height(dist(d0, s))));
    }
    Some((w, env.top()))
}

/// The root of `g` inside `piece`, bracketed by `g(s_lo) > 0 >= g(s_hi)`.
fn solve_in_piece(piece: &Piece, d0: f64, m: f64, s_lo: f64, s_hi: f64) -> f64 {
    let s = match *piece {
        Piece::Line { k, .. } => line_root(d0, m, k).unwrap_or(s_hi),
        Piece::Arc { ce, r, .. } if ce <= 0.0 => {
            m * (r * r - d0 * d0).max(0.0).sqrt() / (1.0 + m * m).sqrt()
        }
        Piece::Arc { ce, r, .. } => torus_root(ce, r, d0, m, s_lo, s_hi),
    };
    s.clamp(s_lo, s_hi)
}

/// The torus case: solve `G(theta) = 0` between the angles of `s_lo` and `s_hi`.
fn torus_root(ce: f64, r: f64, d0: f64, m: f64, s_lo: f64, s_hi: f64) -> f64 {
    let theta_of = |s: f64| (((dist(d0, s) - ce) / r).clamp(0.0, 1.0)).asin();
    let big_g = |t: f64| {
        let (sin, cos) = t.sin_cos();
        let rho = ce + r * sin;
        let s = (rho * rho - d0 * d0).max(0.0).sqrt();
        let drho = r * cos;
        let ds = if s > 0.0 {
            rho * drho / s
        } else {
            f64::INFINITY
        };
        let value = m * rho * cos - s * sin;
        let slope = m * (drho * cos - rho * sin) - ds * sin - s * cos;
        (value, if slope.is_finite() { slope } else { 0.0 })
    };
    let (t, _) = root_decreasing(big_g, theta_of(s_lo), theta_of(s_hi), THETA_TOL);
    let rho = ce + r * t.sin();
    (rho * rho - d0 * d0).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cutter;

    fn tool(spec: &str) -> DropCutter {
        DropCutter::new(&spec.parse::<Cutter>().unwrap())
    }

    /// Brute force: golden-section search of the concave `f` on `[-w, w]`, then the
    /// height there.
    fn brute(tool: &DropCutter, d0: f64, m: f64) -> (f64, f64) {
        let r = tool.radius;
        let w = (r * r - d0 * d0).max(0.0).sqrt();
        let f = |s: f64| m * s - tool.envelope.height(d0.hypot(s).min(r));
        let (mut a, mut b) = (-w, w);
        let phi = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let c = b - phi * (b - a);
            let d = a + phi * (b - a);
            if f(c) >= f(d) {
                b = d;
            } else {
                a = c;
            }
        }
        let s = 0.5 * (a + b);
        (s, f(s))
    }

    #[test]
    fn every_shape_matches_a_brute_force_maximum() {
        let specs = [
            "flat:d=6",
            "ball:d=8",
            "bull:d=10,r=2",
            "bull:d=10,r=0.5",
            "cone:d=10,angle=90",
            "cone:d=6,angle=30",
            "taperball:d=6,angle=10,tip=1",
            "apt:d=10,r=1.5,alpha=10,beta=5,h=30",
            "apt:d=8,r=0,alpha=20,beta=10,h=30",
            "apt:d=12,r=3,alpha=30,beta=-20,h=15",
        ];
        for spec in specs {
            let t = tool(spec);
            for i in 0..=20 {
                let d0 = t.radius * f64::from(i) / 20.0;
                for m in [
                    -5.0, -1.3, -0.4, -0.01, 0.0, 0.02, 0.3, 0.999, 1.0, 2.5, 40.0,
                ] {
                    let (s, h) = edge_argmax(&t, d0, m, f64::NEG_INFINITY, f64::INFINITY).unwrap();
                    let f = m * s - h;
                    let (sb, fb) = brute(&t, d0, m);
                    assert!(
                        f >= fb - 1e-11,
                        "{spec} d0={d0} m={m}: {f} < brute {fb} (s {s} vs {sb})"
                    );
                    assert!(
                        (h - t.envelope.height(d0.hypot(s).min(t.radius))).abs() < 1e-12,
                        "{spec} d0={d0} m={m}: h {h} off the envelope"
                    );
                }
            }
        }
    }

    #[test]
    fn closed_forms_agree_with_the_piecewise_walk() {
        for spec in [
            "flat:d=6",
            "ball:d=8",
            "cone:d=10,angle=90",
            "cone:d=4,angle=120",
        ] {
            let fast = tool(spec);
            let mut slow = fast.clone();
            slow.shape = EdgeShape::Pieces;
            for i in 0..=10 {
                let d0 = fast.radius * f64::from(i) / 10.0;
                for m in [-3.0, -0.5, 0.0, 0.25, 0.8, 1.0, 1.5, 7.0] {
                    let full = |t: &DropCutter| {
                        edge_argmax(t, d0, m, f64::NEG_INFINITY, f64::INFINITY).unwrap()
                    };
                    let (a, b) = (full(&fast), full(&slow));
                    assert!(
                        (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12,
                        "{spec} {d0} {m}: {a:?} {b:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn torus_contact_has_the_edge_slope() {
        // At an interior torus contact the corner's tangent slope along the edge
        // equals the edge's: h'(rho) s / rho = m.
        let bull = tool("bull:d=10,r=2");
        for (d0, m) in [(0.5, 0.3), (3.5, 0.1), (2.0, 1.5), (4.9, 0.05)] {
            let (s, _) = edge_argmax(&bull, d0, m, f64::NEG_INFINITY, f64::INFINITY).unwrap();
            let rho = d0.hypot(s);
            assert!(rho > 3.0 && rho < 5.0, "{d0} {m}: rho {rho}");
            let slope = bull.envelope.slope(rho) * s / rho;
            assert!((slope - m).abs() < 1e-9, "{d0} {m}: {slope}");
        }
    }

    #[test]
    fn tangent_bound_is_above_the_edge() {
        for spec in [
            "bull:d=10,r=2",
            "taperball:d=6,angle=10,tip=1",
            "apt:d=8,r=0,alpha=20,beta=10,h=30",
        ] {
            let t = tool(spec);
            let r = t.radius;
            for i in 0..=12 {
                let d0 = r * f64::from(i) / 12.0;
                let w = (r * r - d0 * d0).max(0.0).sqrt();
                for m in [-2.0, -0.3, 0.0, 0.1, 0.7, 3.0] {
                    for (lo, hi) in [
                        (-w, w),
                        (-0.3 * w, 0.8 * w),
                        (0.1 * w, 0.2 * w),
                        (-w, -0.5 * w),
                    ] {
                        if lo >= hi {
                            continue;
                        }
                        let tip = |s: f64| m * s - t.envelope.height(dist(d0, s).min(r));
                        let bound = edge_upper_bound(&t, d0, m, [lo, hi], [tip(lo), tip(hi)]);
                        let most = (0..=2000)
                            .map(|k| tip(lo + (hi - lo) * f64::from(k) / 2000.0))
                            .fold(f64::NEG_INFINITY, f64::max);
                        assert!(
                            bound >= most - 1e-12,
                            "{spec} d0={d0} m={m} [{lo}, {hi}]: {bound} < {most}"
                        );
                    }
                }
            }
        }
    }
}
