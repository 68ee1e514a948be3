//! Arc fitting: maximal runs of a 3-axis polyline that lie on a circular arc in the
//! XY plane (G17) with Z linear in the arc angle (a helix; Z constant included), so
//! a post can write one arc block (G2/G3, Heidenhain `C`) in place of the segments.
//!
//! A candidate run `p[s..=e]` (at least 3 segments) gets the circle through its
//! first, middle and last points (closed form: with `u = m - a`, `v = b - a`,
//! `d = 2 (u x v)`, the centre is `a + (v_y |u|^2 - u_y |v|^2, u_x |v|^2 - v_x |u|^2) / d`,
//! counter-clockwise when `d > 0`). It is accepted when every step turns the same
//! way by a positive angle, the sweep stays within the post's limit, the radius lies
//! within [`MIN_ARC_RADIUS_MM`, `MAX_ARC_RADIUS_MM`], and every point and every
//! segment's midpoint lies within the tolerance of the arc (distance measured to the
//! helix point at the same angle, an upper bound of the distance to the helix): the
//! points bound the polyline's distance from the arc, the chord midpoints the arc's
//! sagitta over each segment, so the arc stays within tolerance of the polyline both
//! ways. Runs grow by doubling, then a binary search finds the longest accepted
//! length: `O(k log k)` for an arc of `k` segments, `O(1)` per point that starts none.

use swarf_geom::Point3;

/// Smallest radius fitted, mm (well above LinuxCNC's 0.00127 mm zero-radius check).
pub const MIN_ARC_RADIUS_MM: f64 = 0.01;
/// Largest radius fitted, mm: flatter runs stay straight lines.
pub const MAX_ARC_RADIUS_MM: f64 = 10_000.0;
/// Z change below which an arc counts as planar, mm.
const PLANAR_Z_MM: f64 = 1e-9;
/// Smallest turn of one segment about the centre, radians (no back-tracking).
const MIN_STEP_ANGLE: f64 = 1e-12;
/// Fewest segments replaced by one arc.
pub const MIN_ARC_SEGMENTS: usize = 3;

/// What arcs may be fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcFitOptions {
    /// Largest distance between the arc and the polyline, mm.
    pub tolerance: f64,
    /// Whether Z may change along an arc (helix).
    pub helical: bool,
    /// Largest sweep of one arc, radians (less than a full turn).
    pub max_sweep: f64,
}

/// An arc through points `start..=end` of the fitted polyline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FittedArc {
    /// Index of the first point (the arc's start).
    pub start: usize,
    /// Index of the last point (the arc's end).
    pub end: usize,
    /// Centre in XY, mm.
    pub center: [f64; 2],
    /// Radius, mm.
    pub radius: f64,
    /// Counter-clockwise seen from +Z (G3).
    pub ccw: bool,
    /// Sweep, radians (positive).
    pub sweep: f64,
}

/// The arcs of `points` (module doc), in order and disjoint but for shared end
/// points; the points between them are left as segments.
///
/// # Units
/// mm; `opts.max_sweep` in radians.
///
/// # Example
/// ```
/// use swarf_geom::Point3;
/// use swarf_nc::arc_fit::{ArcFitOptions, fit_arcs};
/// let p: Vec<_> = (0..=8)
///     .map(|i| { let t = f64::from(i) * 0.01; Point3::new(5.0 * t.cos(), 5.0 * t.sin(), 0.0) })
///     .collect();
/// let opts = ArcFitOptions { tolerance: 1e-3, helical: true, max_sweep: std::f64::consts::PI };
/// let arcs = fit_arcs(&p, &opts);
/// assert_eq!((arcs.len(), arcs[0].start, arcs[0].end), (1, 0, 8));
/// assert!((arcs[0].radius - 5.0).abs() < 1e-9 && arcs[0].ccw);
/// ```
pub fn fit_arcs(points: &[Point3], opts: &ArcFitOptions) -> Vec<FittedArc> {
    let mut out = Vec::new();
    if !(opts.tolerance > 0.0 && opts.max_sweep > 0.0) {
        return out;
    }
    let mut s = 0;
    while s + MIN_ARC_SEGMENTS < points.len() {
        match longest_arc(points, s, opts) {
            Some(arc) => {
                s = arc.end;
                out.push(arc);
            }
            None => s += 1,
        }
    }
    out
}

/// The longest arc starting at point `s`: doubling, then binary search.
fn longest_arc(p: &[Point3], s: usize, opts: &ArcFitOptions) -> Option<FittedArc> {
    let last = p.len() - 1;
    let mut good = arc_through(p, s, s + MIN_ARC_SEGMENTS, opts)?;
    let mut len = MIN_ARC_SEGMENTS;
    let mut bad = None;
    while good.end < last {
        len = (len * 2).min(last - s);
        match arc_through(p, s, s + len, opts) {
            Some(arc) => good = arc,
            None => {
                bad = Some(s + len);
                break;
            }
        }
    }
    if let Some(mut hi) = bad {
        let mut lo = good.end;
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            match arc_through(p, s, mid, opts) {
                Some(arc) => {
                    good = arc;
                    lo = mid;
                }
                None => hi = mid,
            }
        }
    }
    Some(good)
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The arc through `p[s]`, `p[(s + e) / 2]` and `p[e]` if every point of `s..=e`
/// fits it (module doc).
fn arc_through(p: &[Point3], s: usize, e: usize, opts: &ArcFitOptions) -> Option<FittedArc> {
    let (a, m, b) = (p[s], p[(s + e) / 2], p[e]);
    let u = [m.x - a.x, m.y - a.y];
    let v = [b.x - a.x, b.y - a.y];
    let d = 2.0 * cross(u, v);
    let (uu, vv) = (dot(u, u), dot(v, v));
    let off = [(v[1] * uu - u[1] * vv) / d, (u[0] * vv - v[0] * uu) / d];
    let radius = off[0].hypot(off[1]);
    if !(MIN_ARC_RADIUS_MM..=MAX_ARC_RADIUS_MM).contains(&radius) {
        return None;
    }
    let center = [a.x + off[0], a.y + off[1]];
    let ccw = d > 0.0;
    let sign = if ccw { 1.0 } else { -1.0 };
    let radial = |q: &Point3| [q.x - center[0], q.y - center[1]];
    let turn = |from: [f64; 2], to: [f64; 2]| sign * cross(from, to).atan2(dot(from, to));
    let mut sweep = 0.0;
    for k in s..e {
        let step = turn(radial(&p[k]), radial(&p[k + 1]));
        if step < MIN_STEP_ANGLE {
            return None;
        }
        sweep += step;
        if sweep > opts.max_sweep {
            return None;
        }
    }
    let rise = b.z - a.z;
    if !opts.helical && rise.abs() > PLANAR_Z_MM {
        return None;
    }
    let error = |q: Point3, angle: f64| {
        let r = [q.x - center[0], q.y - center[1]];
        let dz = q.z - (a.z + rise * angle / sweep);
        (r[0].hypot(r[1]) - radius).hypot(dz)
    };
    let mut angle = 0.0;
    for k in s..e {
        let (from, to) = (radial(&p[k]), radial(&p[k + 1]));
        let mid = Point3::from((p[k].coords + p[k + 1].coords) / 2.0);
        let half = turn(from, radial(&mid));
        if error(mid, angle + half) > opts.tolerance {
            return None;
        }
        angle += turn(from, to);
        if k + 1 < e && error(p[k + 1], angle) > opts.tolerance {
            return None;
        }
    }
    Some(FittedArc {
        start: s,
        end: e,
        center,
        radius,
        ccw,
        sweep,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    fn opts() -> ArcFitOptions {
        ArcFitOptions {
            tolerance: 1e-3,
            helical: true,
            max_sweep: PI,
        }
    }

    /// Points on the helix about `(cx, cy)` of radius `r`, from angle `a0` turning
    /// by `step` (signed) per point, rising `dz` per point.
    fn helix(c: [f64; 2], r: f64, a0: f64, step: f64, dz: f64, n: usize) -> Vec<Point3> {
        (0..n)
            .map(|i| {
                let a = a0 + step * i as f64;
                Point3::new(c[0] + r * a.cos(), c[1] + r * a.sin(), dz * i as f64)
            })
            .collect()
    }

    #[test]
    fn a_sampled_helix_is_one_arc_with_its_closed_form() {
        let p = helix([3.0, -2.0], 7.5, 0.3, -0.01, -0.002, 201);
        let arcs = fit_arcs(&p, &opts());
        assert_eq!(arcs.len(), 1, "{arcs:?}");
        let a = arcs[0];
        assert_eq!((a.start, a.end, a.ccw), (0, 200, false));
        assert!((a.center[0] - 3.0).abs() < 1e-9 && (a.center[1] + 2.0).abs() < 1e-9);
        assert!((a.radius - 7.5).abs() < 1e-9 && (a.sweep - 2.0).abs() < 1e-9);
    }

    #[test]
    fn a_full_circle_is_split_and_a_planar_post_refuses_a_helix() {
        let p = helix([0.0, 0.0], 4.0, 0.0, TAU / 256.0, 0.0, 257);
        let arcs = fit_arcs(&p, &opts());
        assert_eq!(arcs.len(), 2, "{arcs:?}");
        assert_eq!((arcs[0].end, arcs[1].start, arcs[1].end), (128, 128, 256));
        assert!(arcs.iter().all(|a| a.ccw && a.sweep <= PI + 1e-12));
        let rising = helix([0.0, 0.0], 4.0, 0.0, 0.01, 0.001, 10);
        let planar = ArcFitOptions {
            helical: false,
            ..opts()
        };
        assert!(fit_arcs(&rising, &planar).is_empty());
        assert_eq!(fit_arcs(&rising, &opts()).len(), 1);
    }

    #[test]
    fn noise_corners_lines_and_tiny_circles_are_not_fitted() {
        let mut p = helix([0.0, 0.0], 10.0, 0.0, 0.01, 0.0, 12);
        for (i, q) in p.iter_mut().enumerate() {
            let n = if i % 2 == 0 { 1.0 } else { -1.0 };
            q.x += n * 2e-3;
        }
        assert!(fit_arcs(&p, &opts()).is_empty());
        // Noise within the tolerance still fits.
        for (i, q) in p.iter_mut().enumerate() {
            q.x -= if i % 2 == 0 { 1.8e-3 } else { -1.8e-3 };
        }
        assert_eq!(fit_arcs(&p, &opts()).len(), 1);
        let corner = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (2.0, 2.0)]
            .map(|(x, y)| Point3::new(x, y, 0.0));
        assert!(fit_arcs(&corner, &opts()).is_empty());
        let line: Vec<_> = (0..10)
            .map(|i| Point3::new(f64::from(i), 0.0, 0.0))
            .collect();
        assert!(fit_arcs(&line, &opts()).is_empty());
        let tiny = helix([0.0, 0.0], 0.005, 0.0, 0.05, 0.0, 8);
        assert!(fit_arcs(&tiny, &opts()).is_empty());
        // A coarse polygon of a circle: the chords' midpoints are too far.
        let coarse = helix([0.0, 0.0], 10.0, 0.0, 0.1, 0.0, 8);
        assert!(fit_arcs(&coarse, &opts()).is_empty());
    }

    #[test]
    fn arcs_between_straight_runs_are_found_where_they_are() {
        let mut p: Vec<_> = (0..6)
            .map(|i| Point3::new(-5.0 + f64::from(i), -2.0, 0.0))
            .collect();
        p.extend(
            helix([0.0, 0.0], 2.0, -PI / 2.0, PI / 80.0, 0.0, 41)
                .into_iter()
                .skip(1),
        );
        let n = p.len();
        p.extend((1..5).map(|i| Point3::new(2.0, f64::from(i), 0.0)));
        let arcs = fit_arcs(&p, &opts());
        assert_eq!(arcs.len(), 1, "{arcs:?}");
        assert_eq!((arcs[0].start, arcs[0].end), (5, n - 1));
    }
}
