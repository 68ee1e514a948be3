//! The `fillet-pocket` part: a 100 x 80 block (x in [0, 100], y in [0, 80]) with its
//! top at z = 20 and a pocket down to z = 0.
//!
//! The pocket's opening is the rounded rectangle at distance 5 from the core rectangle
//! R = [25, 75] x [25, 55] (x in [20, 80], y in [20, 60], corner radius 5). Every
//! point of the pocket surface is `c + d u` at height z, where c is a point of R's
//! boundary, u the unit outward direction there (an axis on a side, a quarter turn of
//! directions at a corner) and `(d, z)` a point of one cross-section profile: the wall
//! from (5, 20) down to (5, 3), then the floor fillet, the quarter circle of radius 3
//! about (2, 3) from (5, 3) to (2, 0). Swept along a side, the profile gives a plane
//! and a horizontal quarter cylinder; swept about a corner, a vertical quarter
//! cylinder of radius 5 and a quarter torus (centre circle radius 2 at z = 3, tube
//! radius 3) that meets the cylinder at z = 3 and the floor tangentially. The floor
//! is the rounded rectangle at distance 2 from R (x in [23, 77], y in [23, 57]).
//!
//! Tessellation: one strip per side (its faces are straight along it), and per corner
//! `around` turns of u by 90 / `around` degrees; the fillet profile has `across`
//! segments. The torus is curved both ways, so both counts keep their sags (radius 5
//! around, radius 3 across) within half of [`MESH_PART_CHORD`]; the corner cylinder
//! and the straight fillets share those divisions so that the mesh has no
//! T-junctions. The top face fans from each block corner to its corner arc, plus one
//! quad per side; the floor fans from the pocket's centre.

use super::{MESH_PART_CHORD, arc_segments, quarter_turn};
use std::f64::consts::FRAC_PI_2;
use swarf_geom::{Point3, TriMesh};

/// Height of the block's top face (mm).
const TOP_Z: f64 = 20.0;
/// Radius of the pocket's vertical corners (mm).
const WALL_RADIUS: f64 = 5.0;
/// Radius of the floor fillet (mm).
const FILLET_RADIUS: f64 = 3.0;
/// The corners of the core rectangle in loop order (counter-clockwise seen from
/// above), each with the quadrant of directions its arc sweeps and the block corner
/// that the top face fans to from it.
const CORNERS: [([f64; 2], usize, [f64; 2]); 4] = [
    ([75.0, 25.0], 3, [100.0, 0.0]),
    ([75.0, 55.0], 0, [100.0, 80.0]),
    ([25.0, 55.0], 1, [0.0, 80.0]),
    ([25.0, 25.0], 2, [0.0, 0.0]),
];
/// Centre of the floor fan (mm).
const FLOOR_CENTRE: [f64; 2] = [50.0, 40.0];

/// The `fillet-pocket` mesh: top face, walls, fillets and floor.
pub(super) fn fillet_pocket() -> TriMesh {
    let around = arc_segments(WALL_RADIUS, FRAC_PI_2, MESH_PART_CHORD / 2.0);
    let across = arc_segments(FILLET_RADIUS, FRAC_PI_2, MESH_PART_CHORD / 2.0);
    let stations: Vec<([f64; 2], [f64; 2])> = CORNERS
        .iter()
        .flat_map(|&(c, q, _)| (0..=around).map(move |j| (c, quarter_turn(q, j, around))))
        .collect();
    let rings: Vec<Vec<Point3>> = profile(across)
        .into_iter()
        .map(|[d, z]| {
            stations
                .iter()
                .map(|(c, u)| Point3::new(c[0] + d * u[0], c[1] + d * u[1], z))
                .collect()
        })
        .collect();
    let n = stations.len();
    let mut tris = Vec::with_capacity(2 * n * rings.len() + 2 * n);
    for pair in rings.windows(2) {
        let (upper, lower) = (&pair[0], &pair[1]);
        for s in 0..n {
            let t = (s + 1) % n;
            tris.push([upper[s], upper[t], lower[t]]);
            tris.push([upper[s], lower[t], lower[s]]);
        }
    }
    top_face(&rings[0], around, &mut tris);
    let centre = Point3::new(FLOOR_CENTRE[0], FLOOR_CENTRE[1], 0.0);
    let floor = &rings[rings.len() - 1];
    for s in 0..n {
        tris.push([centre, floor[s], floor[(s + 1) % n]]);
    }
    TriMesh::from_triangles(&tris)
}

/// The cross-section profile `(d, z)`, top down: the wall's top edge, then the
/// fillet from the wall's foot (5, 3) to the floor (2, 0) in `across` segments.
fn profile(across: usize) -> Vec<[f64; 2]> {
    let core = WALL_RADIUS - FILLET_RADIUS;
    let mut p = vec![[WALL_RADIUS, TOP_Z]];
    p.extend((0..=across).map(|i| {
        let [c, s] = quarter_turn(0, i, across);
        [core + FILLET_RADIUS * c, FILLET_RADIUS - FILLET_RADIUS * s]
    }));
    p
}

/// The top face between the block's outline and the opening `rim` (the stations at
/// d = 5, `around + 1` per corner): a fan from each block corner to its corner arc,
/// and a quad along each side.
fn top_face(rim: &[Point3], around: usize, tris: &mut Vec<[Point3; 3]>) {
    let per = around + 1;
    let outer = CORNERS.map(|(_, _, o)| Point3::new(o[0], o[1], TOP_Z));
    for k in 0..CORNERS.len() {
        let arc = &rim[k * per..(k + 1) * per];
        for j in 0..around {
            tris.push([outer[k], arc[j + 1], arc[j]]);
        }
        let next = (k + 1) % CORNERS.len();
        let first = rim[next * per];
        tris.push([outer[k], outer[next], first]);
        tris.push([outer[k], first, arc[around]]);
    }
}
