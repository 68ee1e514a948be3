//! f64 math types: points and vectors are nalgebra's; boxes, planes and polylines are
//! ours; and the small queries every crate needs once: the tool-axis [`slerp`], the
//! distance from a point to a segment and the first entry of a ray into a capsule.
//!
//! **Slerp.** Between unit vectors `a`, `b` at angle `θ`, `slerp(a, b, t) = (sin((1 -
//! t) θ) a + sin(t θ) b) / sin θ` turns uniformly on the great circle (Shoemake 1985).
//! `θ` is taken as `atan2(|a × b|, a · b)`, accurate for small angles and for angles
//! near π alike (the `acos` of the dot product loses half the digits there); where
//! `sin θ` vanishes (parallel or opposite within rounding) the normalised linear blend
//! is used instead.
//!
//! **Point to segment.** The foot of `p` on the line of `[a, b]` is at `s = (p - a) ·
//! (b - a) / |b - a|²`; clamped to `[0, 1]` it is the nearest point of the segment.
//!
//! **Ray into a capsule.** A capsule (all points within `r` of a segment) is a
//! cylinder about the segment's line and two balls at its ends. A ray `p + t n` (unit
//! `n`) meets a ball of centre `c` where `t² + 2 t (m · n) + |m|² - r² = 0`, `m = p -
//! c`; it meets the cylinder where the part of `m + t n` across the axis direction `d`
//! has length `r`: `(1 - (n·d)²/|d|²) t² + 2 (m·n - (m·d)(n·d)/|d|²) t + |m|² -
//! (m·d)²/|d|² - r² = 0`, accepted where the foot on the axis lies within the
//! segment. The first entry is the least root `t >= 0` of the three.

use serde::{Deserialize, Serialize};

/// A point in 3D, mm.
pub type Point3 = nalgebra::Point3<f64>;
/// A vector in 3D, mm (or dimensionless for directions).
pub type Vec3 = nalgebra::Vector3<f64>;

/// An axis-aligned bounding box. An empty box has `min > max`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Lowest corner.
    pub min: Point3,
    /// Highest corner.
    pub max: Point3,
}

impl Aabb {
    /// The empty box: growing it by a point gives that point.
    pub fn empty() -> Self {
        Aabb {
            min: Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
            max: Point3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
        }
    }

    /// The smallest box holding all `points` (empty if there are none).
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a Point3>) -> Self {
        let mut b = Aabb::empty();
        for p in points {
            b.grow(p);
        }
        b
    }

    /// Grows the box to hold `p`.
    pub fn grow(&mut self, p: &Point3) {
        self.min = self.min.inf(p);
        self.max = self.max.sup(p);
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.inf(&other.min),
            max: self.max.sup(&other.max),
        }
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// Edge lengths (zero vector when empty).
    pub fn size(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::zeros()
        } else {
            self.max - self.min
        }
    }

    /// Centre point.
    pub fn center(&self) -> Point3 {
        nalgebra::center(&self.min, &self.max)
    }

    /// The box grown by `d` on every side.
    pub fn inflated(&self, d: f64) -> Aabb {
        let v = Vec3::repeat(d);
        Aabb {
            min: self.min - v,
            max: self.max + v,
        }
    }

    /// True when `p` lies inside or on the box.
    pub fn contains(&self, p: &Point3) -> bool {
        (0..3).all(|k| p[k] >= self.min[k] && p[k] <= self.max[k])
    }
}

/// The plane `normal . x = offset`, with a unit normal.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    /// Unit normal.
    pub normal: Vec3,
    /// Signed distance of the plane from the origin along `normal`, mm.
    pub offset: f64,
}

impl Plane {
    /// The plane through `point` with normal `normal` (normalised here).
    ///
    /// Returns `None` when `normal` is (nearly) zero or not finite.
    pub fn from_point_normal(point: &Point3, normal: &Vec3) -> Option<Plane> {
        let n = normal.try_normalize(crate::tol::LENGTH_EPS)?;
        Some(Plane {
            normal: n,
            offset: n.dot(&point.coords),
        })
    }

    /// Signed distance of `p` from the plane (positive on the normal's side), mm.
    pub fn signed_distance(&self, p: &Point3) -> f64 {
        self.normal.dot(&p.coords) - self.offset
    }
}

/// An open or closed sequence of points.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Polyline {
    /// The vertices in order.
    pub points: Vec<Point3>,
    /// True when the last point connects back to the first.
    pub closed: bool,
}

impl Polyline {
    /// Total length, including the closing segment when closed, mm.
    pub fn length(&self) -> f64 {
        let open: f64 = self.points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        match (self.closed, self.points.first(), self.points.last()) {
            (true, Some(a), Some(b)) => open + (a - b).norm(),
            _ => open,
        }
    }
}

/// Degrees for display: `naive` (an angle `rad` in radians, converted to degrees by
/// the caller) rounded to 1e-9 degree when the rounded value maps back to the same
/// radians through `back`, so that an angle given as 60 degrees reads 60 again.
pub fn display_degrees(naive: f64, rad: f64, back: impl Fn(f64) -> f64) -> f64 {
    let rounded = (naive * 1e9).round() / 1e9;
    if back(rounded) == rad { rounded } else { naive }
}

/// Spherical linear interpolation between unit vectors `a` and `b` at `t` in `[0, 1]`
/// (module doc): `a` itself when they are equal, the normalised linear blend where they
/// are parallel or opposite within rounding (`a` where that blend vanishes).
///
/// ```
/// use swarf_geom::math::{Vec3, slerp};
/// let half = slerp(&Vec3::x(), &Vec3::y(), 0.5);
/// assert!((half - Vec3::new(1.0, 1.0, 0.0).normalize()).norm() < 1e-15);
/// ```
pub fn slerp(a: &Vec3, b: &Vec3, t: f64) -> Vec3 {
    if a == b {
        return *a;
    }
    let angle = a.cross(b).norm().atan2(a.dot(b));
    let sin = angle.sin();
    if sin <= crate::tol::PARALLEL_COS {
        let mix = a * (1.0 - t) + b * t;
        return mix.try_normalize(crate::tol::PARALLEL_COS).unwrap_or(*a);
    }
    (a * ((1.0 - t) * angle).sin() + b * (t * angle).sin()) / sin
}

/// Distance from `p` to the segment `[a, b]` (to `a` when the segment is a point).
///
/// # Units
/// mm.
///
/// ```
/// use swarf_geom::math::{Point3, point_segment_distance};
/// let (a, b) = (Point3::origin(), Point3::new(10.0, 0.0, 0.0));
/// assert_eq!(point_segment_distance(&Point3::new(4.0, 3.0, 0.0), &a, &b), 3.0);
/// assert_eq!(point_segment_distance(&Point3::new(13.0, 4.0, 0.0), &a, &b), 5.0);
/// ```
pub fn point_segment_distance(p: &Point3, a: &Point3, b: &Point3) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(&ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + s * ab)).norm()
}

/// First `t >= 0` where `p + t n` (unit `n`) is within `r` of the segment `[a, b]`
/// (module doc): 0 when `p` already is, `f64::INFINITY` when the ray never enters the
/// capsule.
///
/// # Units
/// mm.
pub fn ray_capsule(p: &Point3, n: &Vec3, a: &Point3, b: &Point3, r: f64) -> f64 {
    if point_segment_distance(p, a, b) <= r {
        return 0.0;
    }
    let d = b - a;
    let dd = d.norm_squared();
    let mut best = f64::INFINITY;
    for c in [a, b] {
        let m = p - c;
        let bb = m.dot(n);
        let disc = bb * bb - (m.norm_squared() - r * r);
        if disc >= 0.0 && -bb - disc.sqrt() >= 0.0 {
            best = best.min(-bb - disc.sqrt());
        }
    }
    if dd > 0.0 {
        let m = p - a;
        let (nd, md) = (n.dot(&d), m.dot(&d));
        let qa = 1.0 - nd * nd / dd;
        let qb = m.dot(n) - md * nd / dd;
        let qc = m.norm_squared() - md * md / dd - r * r;
        let disc = qb * qb - qa * qc;
        if qa > 0.0 && disc >= 0.0 {
            let t = (-qb - disc.sqrt()) / qa;
            let s = (md + t * nd) / dd;
            if t >= 0.0 && (0.0..=1.0).contains(&s) {
                best = best.min(t);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aabb_grows_and_unions() {
        let b = Aabb::from_points(&[Point3::new(1.0, 2.0, 3.0), Point3::new(-1.0, 5.0, 0.0)]);
        assert_eq!(b.min, Point3::new(-1.0, 2.0, 0.0));
        assert_eq!(b.max, Point3::new(1.0, 5.0, 3.0));
        assert!(Aabb::empty().is_empty());
        assert_eq!(Aabb::empty().union(&b), b);
        assert!(b.contains(&Point3::new(0.0, 3.0, 1.0)));
        assert!(!b.contains(&Point3::new(0.0, 6.0, 1.0)));
    }

    #[test]
    fn plane_distance_is_signed() {
        let p = Plane::from_point_normal(&Point3::new(0.0, 0.0, 2.0), &Vec3::new(0.0, 0.0, 3.0))
            .unwrap();
        assert_eq!(p.signed_distance(&Point3::new(5.0, 1.0, 5.0)), 3.0);
        assert_eq!(p.signed_distance(&Point3::new(5.0, 1.0, 0.0)), -2.0);
        assert!(Plane::from_point_normal(&Point3::origin(), &Vec3::zeros()).is_none());
    }

    #[test]
    fn polyline_length_closes() {
        let mut pl = Polyline {
            points: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(3.0, 0.0, 0.0),
                Point3::new(3.0, 4.0, 0.0),
            ],
            closed: false,
        };
        assert_eq!(pl.length(), 7.0);
        pl.closed = true;
        assert_eq!(pl.length(), 12.0);
    }

    #[test]
    fn slerp_turns_uniformly_and_survives_parallel_axes() {
        let (a, b) = (Vec3::x(), Vec3::y());
        assert!((slerp(&a, &b, 0.5) - Vec3::new(1.0, 1.0, 0.0).normalize()).norm() < 1e-15);
        let third = slerp(&a, &b, 1.0 / 3.0);
        assert!((third.y.atan2(third.x) - std::f64::consts::PI / 6.0).abs() < 1e-15);
        assert_eq!(slerp(&a, &a, 0.3), a);
        // Nearly parallel: accurate where acos(a . b) would lose the angle.
        let tiny = Vec3::new(1.0, 1e-9, 0.0).normalize();
        let mid = slerp(&a, &tiny, 0.5);
        assert!((mid.y - 0.5e-9).abs() < 1e-20 && (mid.norm() - 1.0).abs() < 1e-15);
        // Nearly opposite: on the unit sphere and between the ends, to the rounding of
        // sin(θ) near π (one ulp of π over sin θ = 1e-7: 5e-9).
        let back = Vec3::new(-1.0, 1e-7, 0.0).normalize();
        let q = slerp(&a, &back, 0.5);
        assert!((q.norm() - 1.0).abs() < 1e-8 && (q.y - 1.0).abs() < 1e-8);
        // Exactly opposite: no direction is preferred; the result stays finite and unit.
        let o = slerp(&a, &-a, 0.5);
        assert!(o.iter().all(|c| c.is_finite()) && (o.norm() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn point_segment_distance_clamps_to_the_ends() {
        let (a, b) = (Point3::new(0.0, 0.0, 0.0), Point3::new(10.0, 0.0, 0.0));
        assert_eq!(
            point_segment_distance(&Point3::new(-3.0, 4.0, 0.0), &a, &b),
            5.0
        );
        assert_eq!(
            point_segment_distance(&Point3::new(5.0, 0.0, 2.0), &a, &b),
            2.0
        );
        assert_eq!(
            point_segment_distance(&Point3::new(0.0, 3.0, 4.0), &a, &a),
            5.0
        );
    }

    #[test]
    fn ray_enters_capsule_where_expected() {
        let a = Point3::new(0.0, 0.0, 5.0);
        let b = Point3::new(10.0, 0.0, 5.0);
        // Below the middle of the axis: enters at z = 5 - r.
        let t = ray_capsule(&Point3::new(4.0, 0.0, 0.0), &Vec3::z(), &a, &b, 4.0);
        assert!((t - 1.0).abs() < 1e-12);
        // Below an end cap, off the axis by 3: z = 5 - sqrt(16 - 9).
        let t = ray_capsule(&Point3::new(-3.0, 0.0, 0.0), &Vec3::z(), &a, &b, 4.0);
        assert!((t - (5.0 - 7f64.sqrt())).abs() < 1e-12);
        assert_eq!(
            ray_capsule(&Point3::new(4.0, 9.0, 0.0), &Vec3::z(), &a, &b, 4.0),
            f64::INFINITY
        );
        assert_eq!(
            ray_capsule(&Point3::new(4.0, 0.0, 3.0), &Vec3::z(), &a, &b, 4.0),
            0.0
        );
    }
}
