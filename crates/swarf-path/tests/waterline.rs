//! Waterline contours against closed forms: a square boss with vertical walls, where
//! every cutter's contour at a level is the square offset by a distance that depends
//! on the cutter and the level only (rounded corners of that radius).

use swarf_geom::{Point3, TriMesh};
use swarf_path::strategy::waterline::{Milling, Waterline, WaterlineParams, plan};
use swarf_path::{Cutting, Finish};

const HALF: f64 = 10.0;
const OUTER: f64 = 40.0;
const TOP: f64 = 10.0;

/// A 20 x 20 boss of height 10 standing on an 80 x 80 floor at z = 0.
fn boss() -> TriMesh {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let sq = |h: f64, z: f64| [p(-h, -h, z), p(h, -h, z), p(h, h, z), p(-h, h, z)];
    let (o, i, t) = (sq(OUTER, 0.0), sq(HALF, 0.0), sq(HALF, TOP));
    let mut tris = vec![[t[0], t[1], t[2]], [t[0], t[2], t[3]]];
    for k in 0..4 {
        let n = (k + 1) % 4;
        tris.push([o[k], o[n], i[n]]);
        tris.push([o[k], i[n], i[k]]);
        tris.push([i[k], i[n], t[n]]);
        tris.push([i[k], t[n], t[k]]);
    }
    TriMesh::from_triangles(&tris)
}

/// Distance from `q` to the 2D square `[-HALF, HALF]^2` (0 inside).
fn square_distance(q: [f64; 2]) -> f64 {
    let dx = (q[0].abs() - HALF).max(0.0);
    let dy = (q[1].abs() - HALF).max(0.0);
    dx.hypot(dy)
}

fn params() -> WaterlineParams {
    WaterlineParams {
        finish: Finish {
            tolerance: 0.001,
            ..Finish::default()
        },
        ..WaterlineParams::new(0.05)
    }
}

fn cutting(tool: &str) -> Cutting {
    Cutting::new(tool.parse().unwrap())
}

/// Signed area (positive counter-clockwise).
fn area(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|k| {
            let (a, b) = (points[k], points[(k + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        * 0.5
}

/// The boss contour's offset for `tool` at tip height `z`: where the cutter's side
/// first meets the wall top edge or the wall.
fn offset(tool: &str, z: f64) -> f64 {
    let r = 5.0;
    match tool {
        "ball:d=10" => {
            let c = z + r;
            if c <= TOP {
                r
            } else {
                (r * r - (c - TOP).powi(2)).max(0.0).sqrt()
            }
        }
        "flat:d=10" => r,
        // Corner radius 2: the torus's tube centre circle has radius 3 at z + 2.
        "bull:d=10,r=2" => {
            let c = z + 2.0;
            if c <= TOP {
                r
            } else {
                3.0 + (4.0 - (c - TOP).powi(2)).max(0.0).sqrt()
            }
        }
        _ => unreachable!(),
    }
}

#[test]
fn boss_contours_are_the_exact_offsets() {
    let mesh = boss();
    for tool in ["ball:d=10", "flat:d=10", "bull:d=10,r=2"] {
        let wl = Waterline::new(&mesh, &cutting(tool).tool, &params()).unwrap();
        for z in [1.0, 5.0, 6.5, 8.0, 9.5] {
            let level = wl.level(z, Milling::Climb);
            assert_eq!(
                level.loops.len(),
                1,
                "{tool} at {z}: one loop around the boss"
            );
            let want = offset(tool, z);
            let pts: Vec<[f64; 2]> = level.loops[0]
                .iter()
                .map(|p| [p.pose.cl.x, p.pose.cl.y])
                .collect();
            let worst = pts
                .iter()
                .map(|&q| (square_distance(q) - want).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-6, "{tool} at {z}: off the offset by {worst}");
            // Climb: the boss (material) on the right, so clockwise.
            assert!(area(&pts) < 0.0, "{tool} at {z}: not clockwise");
            // Chords within the tolerance: midpoints of consecutive points.
            let n = pts.len();
            let chord = (0..n)
                .map(|k| {
                    let (a, b) = (pts[k], pts[(k + 1) % n]);
                    (square_distance([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]) - want).abs()
                })
                .fold(0.0, f64::max);
            assert!(chord <= 0.001 + 1e-9, "{tool} at {z}: chord error {chord}");
        }
    }
}

#[test]
fn plan_levels_cover_the_walls_from_the_top_down() {
    let mesh = boss();
    let plan = plan(&mesh, &cutting("ball:d=10"), &params()).unwrap();
    let zs: Vec<f64> = plan
        .toolpath
        .passes
        .iter()
        .map(|p| p.points[0].pose.cl.z)
        .collect();
    assert!(
        zs.windows(2).all(|w| w[0] >= w[1]),
        "levels descend: {zs:?}"
    );
    assert!(
        plan.toolpath
            .passes
            .iter()
            .all(|p| p.points.first().map(|q| q.pose) == p.points.last().map(|q| q.pose))
    );
}
