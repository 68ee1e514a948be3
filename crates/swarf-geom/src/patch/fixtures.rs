//! Test patches: the shared parts (control points copied from `parts/*.toml`; swarf-io
//! checks that the files parse into the same points) and exact NURBS quadrics.

use super::Patch;
use crate::math::Point3;

fn pts(raw: &[[f64; 3]]) -> Vec<Point3> {
    raw.iter().map(|p| Point3::new(p[0], p[1], p[2])).collect()
}

/// parts/die.toml: the bi-quadratic Bezier test surface of thesis 000, eq. 6.1.
pub fn die() -> Patch {
    let raw = [
        [-99.4, 0.0, 12.1],
        [-54.95, 0.0, 24.6],
        [-4.9, 0.0, 43.8],
        [-99.4, -65.65, -13.3],
        [-54.95, -65.65, -7.625],
        [-4.9, -65.65, 2.8],
        [-99.4, -103.2, 37.5],
        [-54.95, -103.2, 39.3],
        [-4.9, -103.2, 49.8],
    ];
    Patch::bezier([2, 2], pts(&raw)).expect("die")
}

/// Closed form of the die surface (the part file's header), `[x, y, z]` at `(u, v)`.
pub fn die_closed_form(u: f64, v: f64) -> [f64; 3] {
    [
        -99.4 + 88.9 * v + 5.6 * v * v,
        -131.3 * u + 28.1 * u * u,
        5.9 * (u * u * v * v + u * u * v) - 3.9 * v * v * u + 76.2 * u * u + 6.7 * v * v
            - 27.3 * u * v
            - 50.8 * u
            + 25.0 * v
            + 12.1,
    ]
}

/// parts/wave.toml: bicubic Bezier, 200 x 100 x 50 mm, uneven in x.
pub fn wave() -> Patch {
    let raw = [
        [0.0, 0.0, 6.0],
        [0.0, 20.0, 28.0],
        [0.0, 60.0, 38.0],
        [0.0, 100.0, 15.0],
        [30.0, 0.0, 23.0],
        [30.0, 20.0, 62.0],
        [30.0, 60.0, 72.0],
        [30.0, 100.0, 38.0],
        [110.0, 0.0, 18.0],
        [110.0, 20.0, 59.0],
        [110.0, 60.0, 74.0],
        [110.0, 100.0, 33.0],
        [200.0, 0.0, 0.0],
        [200.0, 20.0, 20.0],
        [200.0, 60.0, 36.0],
        [200.0, 100.0, 10.0],
    ];
    Patch::bezier([3, 3], pts(&raw)).expect("wave")
}

/// The two patches of parts/edge-convex.toml or parts/edge-concave.toml: they differ
/// only in the z of the middle row (`mid`, from y = -50 toward the edge).
fn edge_pair(mid: [f64; 3]) -> [Patch; 2] {
    let a = [
        [0.0, -50.0, 30.0],
        [0.0, -20.0, 22.0],
        [0.0, 10.0, -2.0],
        [50.0, -50.0, mid[0]],
        [50.0, -20.0, mid[1]],
        [50.0, 10.0, mid[2]],
        [100.0, -50.0, 30.0],
        [100.0, -20.0, 22.0],
        [100.0, 10.0, -2.0],
    ];
    let b = [
        [0.0, -10.0, -2.0],
        [0.0, 20.0, 22.0],
        [0.0, 50.0, 30.0],
        [50.0, -10.0, mid[2]],
        [50.0, 20.0, mid[1]],
        [50.0, 50.0, mid[0]],
        [100.0, -10.0, -2.0],
        [100.0, 20.0, 22.0],
        [100.0, 50.0, 30.0],
    ];
    [
        Patch::bezier([2, 2], pts(&a)).expect("edge a"),
        Patch::bezier([2, 2], pts(&b)).expect("edge b"),
    ]
}

/// parts/edge-convex.toml.
pub fn edge_convex() -> [Patch; 2] {
    edge_pair([38.0, 30.0, 6.0])
}

/// parts/edge-concave.toml.
pub fn edge_concave() -> [Patch; 2] {
    edge_pair([22.0, 14.0, -10.0])
}

/// Every patch of every shared part, with a name.
pub fn shared_patches() -> Vec<(&'static str, Patch)> {
    let [cx0, cx1] = edge_convex();
    let [cc0, cc1] = edge_concave();
    vec![
        ("die", die()),
        ("wave", wave()),
        ("edge-convex[0]", cx0),
        ("edge-convex[1]", cx1),
        ("edge-concave[0]", cc0),
        ("edge-concave[1]", cc1),
    ]
}

/// Exact quarter cylinder of radius `r` about the z axis, `0 <= z <= h`: degree (2, 1),
/// u along the arc from (r, 0) to (0, r), v along z. `du x dv` points outward.
pub fn quarter_cylinder(r: f64, h: f64) -> Patch {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [[r, 0.0], [r, r], [0.0, r]];
    let mut p = Vec::new();
    let mut w = Vec::new();
    for (i, a) in arc.iter().enumerate() {
        for z in [0.0, h] {
            p.push(Point3::new(a[0], a[1], z));
            w.push(if i == 1 { s } else { 1.0 });
        }
    }
    Patch::new([2, 1], p, [None, None], Some(w)).expect("cylinder")
}

/// Exact sphere octant of radius `r` about the origin (x, y, z >= 0): the quarter
/// meridian from the equator (u = 0) to the pole (u = 1, a collapsed row) revolved by the
/// quarter circle from +x (v = 0) to +y (v = 1); weights are products of the two arcs'
/// `1, sqrt(2)/2, 1`. `du x dv` points inward (toward the centre).
pub fn sphere_octant(r: f64) -> Patch {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let meridian = [(r, 0.0, 1.0), (r, r, s), (0.0, r, 1.0)];
    let arc = [(1.0, 0.0, 1.0), (1.0, 1.0, s), (0.0, 1.0, 1.0)];
    let mut p = Vec::new();
    let mut w = Vec::new();
    for (rad, z, wm) in meridian {
        for (cx, cy, wa) in arc {
            p.push(Point3::new(rad * cx, rad * cy, z));
            w.push(wm * wa);
        }
    }
    Patch::new([2, 2], p, [None, None], Some(w)).expect("sphere")
}

/// A bicubic x biquadratic B-spline with several spans (one double knot) and weights:
/// exercises the span search and the rational path together.
pub fn nurbs_spline() -> Patch {
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 2.5, 2.5, 2.5, 2.5];
    let kv = vec![-1.0, -1.0, -1.0, 0.0, 0.5, 3.0, 3.0, 3.0];
    let (nu, nv) = (ku.len() - 4, kv.len() - 3);
    let mut p = Vec::new();
    let mut w = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 * 10.0, j as f64 * 8.0);
            let z = 8.0 * (0.7 * i as f64 + 0.5 * j as f64).sin() + 0.1 * x * y / 8.0;
            p.push(Point3::new(x + (j % 2) as f64, y, z));
            w.push(1.0 + 0.25 * ((i + 2 * j) % 3) as f64);
        }
    }
    Patch::new([3, 2], p, [Some(ku), Some(kv)], Some(w)).expect("nurbs spline")
}
