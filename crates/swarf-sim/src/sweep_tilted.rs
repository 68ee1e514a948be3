//! One position of a tool whose axis is not vertical (five-axis CL data), and the
//! lowest point of it over each cell, by sphere tracing the vertical line.
//!
//! The tool solid's exact signed distance `f(p)` ([`swarf_tool::Profile`]'s
//! `signed_distance`) is 1-Lipschitz, so from a point at distance `f > 0` outside the
//! tool a step of `f` along any direction cannot cross into it (Hart, "Sphere tracing",
//! The Visual Computer 12, 1996). Marching up the vertical line over a cell from below
//! the tool, `z <- z + f(q, z)`, never passes the first entry point: every iterate is
//! a lower bound of the lowest tool point on the line, and the march stops at a point
//! within [`HIT_DISTANCE`] of the tool. Where the normal there is steep the march
//! slows down (factor `1 - cos(slope)` a step); a march that rises above the cell's
//! current height stops there (the tool cannot lower the cell). A line that grazes
//! the tool, where the march crawls, is finished after [`MAX_STEPS`] by a bracketing
//! search on the convex distance (golden section for its minimum, then bisection for
//! the entry), so the result never lies below the tool.
//!
//! The tools of the family are convex solids of revolution, and the signed distance of
//! a convex set is convex, so along the line `f` is convex: once a step does not
//! decrease `f`, `f` never decreases again and the line misses the tool. That ends
//! misses after a few steps instead of marching to the top.

use crate::tool_solid::ToolSolid;
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// The march stops this close to the tool, mm.
pub const HIT_DISTANCE: f64 = 1e-9;
/// Largest number of sphere-tracing steps per cell.
pub const MAX_STEPS: usize = 200;
/// Golden-section and bisection steps for a grazing line (bracket shrinks to
/// `0.618^80`, about 1e-17, of the tool's height).
const BRACKET_STEPS: usize = 80;

/// One tool position, with its XY box and height range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolInstance {
    pose: Pose,
    /// The pose's axis, of unit length (NaN for a zero axis).
    unit: Vec3,
    bounds: [f64; 4],
    zlo: f64,
    ztop: f64,
    /// Axis segment length (the flute length) and radius of the bounding cylinder.
    length: f64,
    radius: f64,
}

impl ToolInstance {
    /// The tool of `radius` and flute `length` at `pose`.
    pub fn new(pose: Pose, radius: f64, length: f64) -> ToolInstance {
        let top = pose.cl + pose.axis * length;
        let grow = |k: usize| radius * (1.0 - pose.axis[k] * pose.axis[k]).max(0.0).sqrt();
        let lo = |k: usize| pose.cl[k].min(top[k]) - grow(k);
        let hi = |k: usize| pose.cl[k].max(top[k]) + grow(k);
        ToolInstance {
            pose,
            unit: pose.axis / pose.axis.norm(),
            bounds: [lo(0), lo(1), hi(0), hi(1)],
            zlo: lo(2),
            ztop: hi(2),
            length,
            radius,
        }
    }

    /// A lower bound of the tool's lowest point over `(x, y)` (`+inf` when the tool
    /// cannot be there), from the cylinder of the tool's radius about its axis
    /// segment, which holds the tool: a point `A(t) + w` (`A(t) = cl + t a`,
    /// `|w| <= R`, `w` normal to `a`) over `(x, y)` has `|A(t)_xy - (x, y)| <= R`,
    /// an interval of `t`, and lies no lower than `A(t)_z - R sqrt(1 - a_z^2)`.
    #[inline]
    pub fn floor(&self, x: f64, y: f64) -> f64 {
        let (p, a) = (&self.pose.cl, &self.pose.axis);
        let (dx, dy) = (p.x - x, p.y - y);
        // |(dx, dy) + t (ax, ay)|^2 <= R^2: a t^2 + 2 b t + c <= 0
        let qa = a.x * a.x + a.y * a.y;
        let qb = dx * a.x + dy * a.y;
        // (the radius grown by a hair, so that rounding cannot cut off a tangent line)
        let r = self.radius * (1.0 + 1e-9) + 1e-12;
        let qc = dx * dx + dy * dy - r * r;
        let (t0, t1) = if qa <= 1e-18 {
            if qc > 0.0 {
                return f64::INFINITY;
            }
            (0.0, self.length)
        } else {
            let disc = qb * qb - qa * qc;
            if disc < 0.0 {
                return f64::INFINITY;
            }
            let sq = disc.sqrt();
            ((-qb - sq) / qa, (-qb + sq) / qa)
        };
        let (t0, t1) = (t0.max(0.0), t1.min(self.length));
        if t0 > t1 {
            return f64::INFINITY;
        }
        let lowest_t = if a.z >= 0.0 { t0 } else { t1 };
        p.z + lowest_t * a.z - r * qa.sqrt()
    }

    /// XY box of the cells it may lower: `[xmin, ymin, xmax, ymax]`, mm.
    pub fn bounds(&self) -> [f64; 4] {
        self.bounds
    }

    /// Lowest height the tool reaches anywhere, mm.
    pub fn zlo(&self) -> f64 {
        self.zlo
    }

    /// Lowest point of the tool over `(x, y)`, mm; `+inf` when the line misses it or
    /// only meets it above `ceiling` (the cell's current height: nothing to cut). The
    /// march starts at `from` (a lower bound of that point: [`ToolInstance::floor`],
    /// or `-inf`) or 1 mm below the tool, whichever is higher.
    pub fn lowest(
        &self,
        solid: &ToolSolid,
        convex: bool,
        (x, y): (f64, f64),
        ceiling: f64,
        from: f64,
    ) -> f64 {
        let top = self.ztop.min(ceiling);
        // The tool's signed distance at (x, y, z), the axis normalised once.
        let (a, w0) = (&self.unit, Point3::new(x, y, 0.0) - self.pose.cl);
        let f = |z: f64| {
            let w = Vec3::new(w0.x, w0.y, w0.z + z);
            let u = w.dot(a);
            solid.distance((w - a * u).norm(), u)
        };
        let mut z = from.max(self.zlo - 1.0);
        let mut prev = f64::INFINITY;
        for _ in 0..MAX_STEPS {
            let d = f(z);
            if !d.is_finite() {
                return f64::INFINITY;
            }
            if d <= HIT_DISTANCE {
                return z;
            }
            if convex && d >= prev {
                return f64::INFINITY;
            }
            prev = d;
            z += d;
            if z > top {
                return f64::INFINITY;
            }
        }
        if convex {
            grazing(&f, z, top)
        } else {
            f64::INFINITY
        }
    }
}

/// The entry point of a grazing line into a convex tool, from `z` (below it) up to
/// `top`: golden-section search for the minimum of the convex distance `f`, then
/// bisection between `z` and that minimum; `+inf` when the minimum stays outside.
fn grazing(f: &impl Fn(f64) -> f64, z: f64, top: f64) -> f64 {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (z, top);
    for _ in 0..BRACKET_STEPS {
        let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
        if f(c) <= f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let low = 0.5 * (a + b);
    if f(low) > HIT_DISTANCE {
        return f64::INFINITY;
    }
    let (mut out, mut inside) = (z, low);
    for _ in 0..BRACKET_STEPS {
        let mid = 0.5 * (out + inside);
        if f(mid) > HIT_DISTANCE {
            out = mid;
        } else {
            inside = mid;
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_tool::{Cutter, Profile};

    /// Bisection on the sign of the signed distance between a point known outside
    /// (below) and one known inside: an independent route to the entry point.
    fn bisect(profile: &Profile, pose: &Pose, x: f64, y: f64, mut lo: f64, mut hi: f64) -> f64 {
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if profile.signed_distance(pose, &Point3::new(x, y, mid)) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    #[test]
    fn tilted_ball_matches_the_sphere_and_bisection() {
        let cutter: Cutter = "ball:d=8".parse().unwrap();
        let profile = cutter.profile();
        let solid = ToolSolid::of(&cutter, &profile);
        let axis = Vec3::new(0.3, -0.2, 1.0).normalize();
        let pose = Pose::new(Point3::new(1.0, 2.0, 3.0), axis).unwrap();
        let inst = ToolInstance::new(pose, 4.0, cutter.length());
        let centre = pose.cl + axis * 4.0;
        for k in 0..40 {
            let (x, y) = (centre.x - 3.9 + 0.2 * k as f64, centre.y + 0.7);
            let got = inst.lowest(&solid, true, (x, y), f64::INFINITY, f64::NEG_INFINITY);
            let d2 = (x - centre.x).powi(2) + (y - centre.y).powi(2);
            let sphere = centre.z - (16.0 - d2).sqrt();
            // The lowest point over the cell is on the ball wherever the ball's lowest
            // point there lies in the tool's lower hemisphere.
            let on_ball = (Point3::new(x, y, sphere) - centre).dot(&axis) <= 0.0;
            if on_ball {
                assert!((got - sphere).abs() < 1e-7, "x {x}: {got} vs {sphere}");
            }
            let inside = bisect(&profile, &pose, x, y, inst.zlo() - 1.0, centre.z + 0.01);
            assert!((got - inside).abs() < 1e-7, "x {x}: {got} vs {inside}");
        }
        assert_eq!(
            inst.lowest(
                &solid,
                true,
                (centre.x + 30.0, centre.y),
                f64::INFINITY,
                f64::NEG_INFINITY
            ),
            f64::INFINITY
        );
    }

    #[test]
    fn floor_is_a_lower_bound() {
        let cutter: Cutter = "bull:d=10,r=2".parse().unwrap();
        let profile = cutter.profile();
        let solid = ToolSolid::of(&cutter, &profile);
        for axis in [
            Vec3::new(-0.5, 0.1, 1.0),
            Vec3::z(),
            Vec3::new(1.0, 0.0, 0.2),
        ] {
            let pose = Pose::new(Point3::new(0.5, -0.2, 1.0), axis).unwrap();
            let inst = ToolInstance::new(pose, 5.0, cutter.length());
            let b = inst.bounds();
            let mut pruned = 0;
            for k in 0..=40 {
                for l in 0..=40 {
                    let x = b[0] + (b[2] - b[0]) * k as f64 / 40.0;
                    let y = b[1] + (b[3] - b[1]) * l as f64 / 40.0;
                    let exact = inst.lowest(&solid, true, (x, y), f64::INFINITY, f64::NEG_INFINITY);
                    let floor = inst.floor(x, y);
                    assert!(floor <= exact + 1e-9, "{x} {y}: {floor} > {exact}");
                    // Marching from the floor finds the same point.
                    let from = inst.lowest(&solid, true, (x, y), f64::INFINITY, floor);
                    assert!(
                        from == exact || (from - exact).abs() < 1e-7,
                        "{from} {exact}"
                    );
                    pruned += usize::from(floor.is_infinite());
                }
            }
            assert!(pruned > 0 || axis == Vec3::z());
        }
    }

    #[test]
    fn tilted_bull_matches_bisection_and_misses_are_quick() {
        let cutter: Cutter = "bull:d=10,r=2".parse().unwrap();
        let profile = cutter.profile();
        let solid = ToolSolid::of(&cutter, &profile);
        let axis = Vec3::new(-0.5, 0.1, 1.0).normalize();
        let pose = Pose::new(Point3::new(0.0, 0.0, 0.0), axis).unwrap();
        let inst = ToolInstance::new(pose, 5.0, cutter.length());
        let b = inst.bounds();
        let mut hits = 0;
        for k in 0..=60 {
            let x = b[0] + (b[2] - b[0]) * k as f64 / 60.0;
            let y = 1.3;
            let got = inst.lowest(&solid, true, (x, y), f64::INFINITY, f64::NEG_INFINITY);
            if got.is_finite() {
                hits += 1;
                assert!(
                    profile
                        .signed_distance(&pose, &Point3::new(x, y, got))
                        .abs()
                        < 1e-6
                );
                let above = got + 1e-6;
                if profile.signed_distance(&pose, &Point3::new(x, y, above)) < 0.0 {
                    let want = bisect(&profile, &pose, x, y, inst.zlo() - 1.0, above);
                    assert!((got - want).abs() < 1e-6, "x {x}: {got} vs {want}");
                }
            }
        }
        assert!(hits > 30, "{hits}");
    }
}
