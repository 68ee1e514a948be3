//! `deep-pocket`: a block x in [0, 60], y in [0, 60], top z = 40, with a deep narrow
//! rectangular pocket x in [25, 35], y in [10, 50] (10 wide, 40 long), vertical
//! walls, flat floor at z = 0 (40 deep): the part of issue 19's holder check, where a
//! small tool reaches the floor only with a long stick-out. A vertical tool centred
//! in the pocket (x = 30) with its tip at height `z` keeps a holder of bottom radius
//! `r >= 5` clear exactly when the holder face is at or above the top, `S >= 40 - z`;
//! a holder nose cone that widens from `r0 < 5` at slope `k` (radius per height) may
//! dip `(5 - r0) / k` into the pocket.
//!
//! 18 planar triangles: the top as four rectangles around the opening, four walls
//! (normals into the pocket), the floor; all wound counter-clockwise seen from the
//! air.

use swarf_geom::{Point3, TriMesh, Vec3};

/// Block extent in x and y (mm).
pub(super) const BLOCK: [f64; 2] = [60.0, 60.0];
/// Height of the top (mm); the floor is at z = 0.
pub(super) const TOP: f64 = 40.0;
/// The pocket opening `[x0, y0, x1, y1]` (mm).
pub(super) const POCKET: [f64; 4] = [25.0, 10.0, 35.0, 50.0];

/// The quad `q` as two triangles, wound so that their normal points along `toward`.
fn quad(q: [Point3; 4], toward: Vec3) -> [[Point3; 3]; 2] {
    let n = (q[1] - q[0]).cross(&(q[2] - q[0]));
    if n.dot(&toward) >= 0.0 {
        [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    } else {
        [[q[0], q[2], q[1]], [q[0], q[3], q[2]]]
    }
}

/// The horizontal rectangle `[x0, y0, x1, y1]` at height `z`, facing up.
fn flat(r: [f64; 4], z: f64) -> [[Point3; 3]; 2] {
    let p = |x: f64, y: f64| Point3::new(x, y, z);
    quad(
        [p(r[0], r[1]), p(r[2], r[1]), p(r[2], r[3]), p(r[0], r[3])],
        Vec3::z(),
    )
}

/// The `deep-pocket` mesh.
pub(super) fn deep_pocket() -> TriMesh {
    let [x0, y0, x1, y1] = POCKET;
    let [w, l] = BLOCK;
    let mut tris = Vec::with_capacity(18);
    for r in [
        [0.0, 0.0, x0, l],
        [x1, 0.0, w, l],
        [x0, 0.0, x1, y0],
        [x0, y1, x1, l],
    ] {
        tris.extend(flat(r, TOP));
    }
    tris.extend(flat(POCKET, 0.0));
    let p = Point3::new;
    let walls = [
        (
            [
                p(x0, y0, 0.0),
                p(x0, y1, 0.0),
                p(x0, y1, TOP),
                p(x0, y0, TOP),
            ],
            Vec3::x(),
        ),
        (
            [
                p(x1, y0, 0.0),
                p(x1, y1, 0.0),
                p(x1, y1, TOP),
                p(x1, y0, TOP),
            ],
            -Vec3::x(),
        ),
        (
            [
                p(x0, y0, 0.0),
                p(x1, y0, 0.0),
                p(x1, y0, TOP),
                p(x0, y0, TOP),
            ],
            Vec3::y(),
        ),
        (
            [
                p(x0, y1, 0.0),
                p(x1, y1, 0.0),
                p(x1, y1, TOP),
                p(x0, y1, TOP),
            ],
            -Vec3::y(),
        ),
    ];
    for (q, n) in walls {
        tris.extend(quad(q, n));
    }
    TriMesh::from_triangles(&tris)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eighteen_triangles_facing_the_air() {
        let m = deep_pocket();
        assert_eq!(m.len(), 18);
        let mut top_area = 0.0;
        for i in 0..m.len() {
            let [a, b, c] = m.triangle(i);
            let n = (b - a).cross(&(c - a));
            let centre = (a.coords + b.coords + c.coords) / 3.0;
            // A point a little along the normal is in the air: above the top, or
            // inside the pocket's box.
            let q = centre + 1e-3 * n.normalize();
            let in_pocket = q.x > POCKET[0]
                && q.x < POCKET[2]
                && q.y > POCKET[1]
                && q.y < POCKET[3]
                && q.z > 0.0;
            assert!(q.z > TOP || in_pocket, "triangle {i} faces the material");
            if a.z == TOP && b.z == TOP && c.z == TOP {
                top_area += 0.5 * n.norm();
            }
        }
        assert!((top_area - (60.0 * 60.0 - 10.0 * 40.0)).abs() < 1e-9);
    }
}
