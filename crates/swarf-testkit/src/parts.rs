//! Test parts: the built-in die and wave, and two exact rational patches (a cylinder
//! and a groove) whose closed forms the tests compare against.

use swarf_geom::{Part, Patch, Point3};

/// Radius of [`cylinder_patch`], mm.
pub const CYLINDER_RADIUS: f64 = 60.0;

/// The cylinder z = sqrt(R^2 - y^2) (R = [`CYLINDER_RADIUS`]) over x in [0, 40],
/// y in [-30, 30], exactly: linear in u (along x), a rational quadratic 60-degree arc
/// in v. `c` reparametrises the arc (weights `1, w c, c^2` describe the same arc at
/// another speed); `c = 1` is the symmetric form.
pub fn cylinder_patch(c: f64) -> Patch {
    let r = CYLINDER_RADIUS;
    let half = 30f64.to_radians();
    let w = half.cos();
    let mut pts = Vec::new();
    for x in [0.0, 40.0] {
        pts.push(Point3::new(x, -r * half.sin(), r * half.cos()));
        pts.push(Point3::new(x, 0.0, r / w));
        pts.push(Point3::new(x, r * half.sin(), r * half.cos()));
    }
    let weights = vec![1.0, w * c, c * c, 1.0, w * c, c * c];
    Patch::new([1, 2], pts, [None, None], Some(weights)).expect("the cylinder patch is valid")
}

/// [`cylinder_patch`] as a one-patch part.
pub fn cylinder(c: f64) -> Part {
    Part::new("cylinder", vec![cylinder_patch(c)])
}

/// The built-in die (thesis 000 eq. 6.1).
pub fn die() -> Part {
    swarf_io::builtin_part("die").expect("the built-in die part loads")
}

/// The built-in wave (paper 004's experiment).
pub fn wave() -> Part {
    swarf_io::builtin_part("wave").expect("built-in wave")
}

/// A groove of radius 3 (a 120-degree arc, exact) along y from 0 to 20, its axis at z
/// = 20: narrower than a ball of diameter 8.
pub fn groove() -> Part {
    let r = 3.0;
    let half = 60f64.to_radians();
    let (s, c) = half.sin_cos();
    let mut pts = Vec::new();
    for y in [0.0, 20.0] {
        pts.push(Point3::new(-r * s, y, 20.0 - r * c));
        pts.push(Point3::new(0.0, y, 20.0 - r / c));
        pts.push(Point3::new(r * s, y, 20.0 - r * c));
    }
    let patch = Patch::new(
        [1, 2],
        pts,
        [None, None],
        Some(vec![1.0, c, 1.0, 1.0, c, 1.0]),
    )
    .expect("the groove patch is valid");
    Part::new("groove", vec![patch])
}
