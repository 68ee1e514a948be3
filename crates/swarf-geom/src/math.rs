//! f64 math types: points and vectors are nalgebra's; boxes, planes and polylines are ours.

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
}
