//! Tests of the built-in mesh parts against oracles written from the parts'
//! descriptions, sharing no code with the generators: for each part a distance to its
//! analytic surface (an upper bound, exact on the curved faces), its height as seen
//! from above, and the outward normal; and a brute-force upper envelope of the mesh.
//!
//! The fillet pocket's air (below z = 20) is the set of points within 3 of the convex
//! set C = {xy within 2 of R = [25, 75] x [25, 55], z >= 3} (the sharp pocket opened
//! by a ball of radius 3), so its surface is the level set dist(p, C) = 3; that air is
//! convex, so every triangle with its corners on the surface lies in the air and the
//! mesh is nowhere below the true pocket surface.

use super::*;
use swarf_geom::{Point3, Vec3};

const TOL: f64 = MESH_PART_CHORD;

fn mesh(name: &str) -> TriMesh {
    builtin_mesh(name).expect("built-in mesh")
}

// ---- fillet-pocket oracle ----

/// Nearest point of R = [25, 75] x [25, 55] to (x, y), and the distance to it.
fn core_nearest(x: f64, y: f64) -> ([f64; 2], f64) {
    let c = [x.clamp(25.0, 75.0), y.clamp(25.0, 55.0)];
    (c, (x - c[0]).hypot(y - c[1]))
}

/// Nearest point of C to p.
fn c_nearest(p: &Point3) -> Point3 {
    let (c, d) = core_nearest(p.x, p.y);
    let [x, y] = if d <= 2.0 {
        [p.x, p.y]
    } else {
        [c[0] + 2.0 * (p.x - c[0]) / d, c[1] + 2.0 * (p.y - c[1]) / d]
    };
    Point3::new(x, y, p.z.max(3.0))
}

/// Distance from p to the top face (the ring outside the opening, to rounding when
/// R's projection is outside) and to the pocket surface; the smaller.
fn pocket_dists(p: &Point3) -> (f64, f64) {
    let (_, d) = core_nearest(p.x, p.y);
    let top = if d >= 5.0 {
        (p.z - 20.0).abs()
    } else if d > 0.0 {
        (p.z - 20.0).hypot(5.0 - d)
    } else {
        f64::INFINITY
    };
    let pocket = if p.z <= 20.0 {
        ((c_nearest(p) - p).norm() - 3.0).abs()
    } else {
        f64::INFINITY
    };
    (top, pocket)
}

fn pocket_dist(p: &Point3) -> f64 {
    let (top, pocket) = pocket_dists(p);
    top.min(pocket)
}

fn pocket_height(x: f64, y: f64) -> f64 {
    let (_, d) = core_nearest(x, y);
    if d >= 5.0 {
        20.0
    } else if d <= 2.0 {
        0.0
    } else {
        3.0 - (9.0 - (d - 2.0).powi(2)).sqrt()
    }
}

fn pocket_normal(p: &Point3) -> Vec3 {
    let (top, pocket) = pocket_dists(p);
    if top < pocket {
        Vec3::z()
    } else {
        (c_nearest(p) - p).normalize()
    }
}

// ---- v-grooves and short-grooves oracles ----

/// (x of the bottom, included angle in degrees).
const V: [(f64, f64); 3] = [(20.0, 60.0), (55.0, 90.0), (105.0, 120.0)];

fn v_height(x: f64, _y: f64) -> f64 {
    V.iter().fold(10.0, |h: f64, &(x0, deg)| {
        let half = (deg / 2.0).to_radians();
        h.min((x - x0).abs() * half.cos() / half.sin())
    })
}

/// (y of the bottom, x start, x end).
const SHORT: [(f64, f64, f64); 4] = [
    (15.0, 10.0, 30.0),
    (15.0, 31.5, 51.5),
    (45.0, 10.0, 30.0),
    (45.0, 35.0, 55.0),
];

fn short_height(x: f64, y: f64) -> f64 {
    SHORT
        .iter()
        .filter(|g| g.1 <= x && x <= g.2)
        .fold(0.0, |h: f64, g| h.min((y - g.0).abs() - 4.0))
}

/// The nearest end wall to p among those whose triangle p lies over (in the wall's
/// plane), within `slack` of it: (distance, outward normal's x).
fn short_wall(p: &Point3, slack: f64) -> Option<(f64, f64)> {
    let inside = |g: &&(f64, f64, f64)| (g.0 - p.y).abs() - 4.0 <= p.z + 1e-9 && p.z <= 1e-9;
    SHORT
        .iter()
        .filter(inside)
        .flat_map(|g| [(g.1, 1.0), (g.2, -1.0)])
        .map(|(x, side)| ((p.x - x).abs(), side))
        .filter(|(d, _)| *d <= slack)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

fn short_dist(p: &Point3) -> f64 {
    let graph = (p.z - short_height(p.x, p.y)).abs();
    short_wall(p, f64::INFINITY).map_or(graph, |(d, _)| graph.min(d))
}

/// Upward unit normal of a height field by central differences.
fn graph_normal(h: fn(f64, f64) -> f64, p: &Point3) -> Vec3 {
    let e = 1e-6;
    let hx = (h(p.x + e, p.y) - h(p.x - e, p.y)) / (2.0 * e);
    let hy = (h(p.x, p.y + e) - h(p.x, p.y - e)) / (2.0 * e);
    Vec3::new(-hx, -hy, 1.0).normalize()
}

fn short_normal(p: &Point3) -> Vec3 {
    match short_wall(p, 1e-9) {
        Some((_, side)) => Vec3::new(side, 0.0, 0.0),
        None => graph_normal(short_height, p),
    }
}

fn v_normal(p: &Point3) -> Vec3 {
    graph_normal(v_height, p)
}

/// Each part: name, block size, distance oracle, height oracle, normal oracle.
type Oracle = (
    &'static str,
    [f64; 2],
    fn(&Point3) -> f64,
    fn(f64, f64) -> f64,
    fn(&Point3) -> Vec3,
);
const PARTS: [Oracle; 3] = [
    (
        "fillet-pocket",
        [100.0, 80.0],
        pocket_dist,
        pocket_height,
        pocket_normal,
    ),
    (
        "v-grooves",
        [140.0, 60.0],
        |p| (p.z - v_height(p.x, p.y)).abs(),
        v_height,
        v_normal,
    ),
    (
        "short-grooves",
        [70.0, 60.0],
        short_dist,
        short_height,
        short_normal,
    ),
];

// ---- brute-force upper envelope ----

/// Triangles binned by their XY boxes into 1 mm cells.
struct Upper {
    tris: Vec<[Point3; 3]>,
    cols: usize,
    cells: Vec<Vec<usize>>,
}

impl Upper {
    fn new(m: &TriMesh, size: [f64; 2]) -> Upper {
        let (cols, rows) = (size[0].ceil() as usize + 1, size[1].ceil() as usize + 1);
        let mut cells = vec![Vec::new(); cols * rows];
        let tris: Vec<_> = (0..m.len()).map(|i| m.triangle(i)).collect();
        for (i, t) in tris.iter().enumerate() {
            let lo = |f: fn(&Point3) -> f64| t.iter().map(f).fold(f64::INFINITY, f64::min);
            let hi = |f: fn(&Point3) -> f64| t.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
            let span = |a: f64, b: f64, n: usize| {
                (a.floor().max(0.0) as usize)..=(b.floor().max(0.0) as usize).min(n - 1)
            };
            for r in span(lo(|p| p.y), hi(|p| p.y), rows) {
                for c in span(lo(|p| p.x), hi(|p| p.x), cols) {
                    cells[r * cols + c].push(i);
                }
            }
        }
        Upper { tris, cols, cells }
    }

    /// Highest point of a non-vertical triangle over (x, y), closed inside test.
    fn at(&self, x: f64, y: f64) -> Option<f64> {
        let cell = &self.cells[y as usize * self.cols + x as usize];
        let mut best: Option<f64> = None;
        for &i in cell {
            let [a, b, c] = self.tris[i];
            let cross = |p: &Point3, q: &Point3| (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
            let area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            if area.abs() < 1e-12 {
                continue;
            }
            let w = [
                cross(&b, &c) / area,
                cross(&c, &a) / area,
                cross(&a, &b) / area,
            ];
            if w.iter().all(|&wi| wi >= -1e-12) {
                let z = w[0] * a.z + w[1] * b.z + w[2] * c.z;
                best = Some(best.map_or(z, |h| h.max(z)));
            }
        }
        best
    }
}

// ---- tests ----

#[test]
fn names_suffix_counts_and_determinism() {
    assert!(builtin_mesh("nope").is_none() && builtin_mesh("fillet-pocket.toml").is_none());
    for name in builtin_mesh_names() {
        let m = mesh(name);
        assert_eq!(builtin_mesh(&format!("{name}.stl")), Some(m.clone()));
        assert!(
            !m.is_empty() && m.len() < 40_000,
            "{name}: {} triangles",
            m.len()
        );
        println!(
            "{name}: {} triangles, {} vertices",
            m.len(),
            m.vertices.len()
        );
    }
    assert_eq!(mesh("v-grooves").len(), 20);
    assert_eq!(mesh("short-grooves").len(), 58);
}

#[test]
fn arc_segments_is_the_fewest_within_tolerance() {
    for (r, t, tol) in [
        (5.0, 1.5707963, 5e-4),
        (3.0, 1.5707963, 5e-4),
        (5.0, 3.1, 1e-3),
    ] {
        let n = arc_segments(r, t, tol);
        let sag = |n: usize| r - r * (t / n as f64 / 2.0).cos();
        assert!(sag(n) <= tol && sag(n - 1) > tol, "{r} {t} {tol}: {n}");
    }
    assert_eq!(arc_segments(1.0, 0.01, 0.1), 1);
}

#[test]
fn vertices_lie_on_the_surface() {
    for (name, _, dist, ..) in PARTS {
        let m = mesh(name);
        let used: std::collections::BTreeSet<u32> = m.triangles.iter().flatten().copied().collect();
        assert_eq!(used.len(), m.vertices.len(), "{name}: unused vertices");
        for v in &m.vertices {
            assert!(dist(v) < 1e-9, "{name}: vertex {v:?} is {} off", dist(v));
        }
    }
}

#[test]
fn triangles_stay_within_the_chord_tolerance() {
    for (name, _, dist, ..) in PARTS {
        let m = mesh(name);
        let mut worst = 0.0_f64;
        for i in 0..m.len() {
            let [a, b, c] = m.triangle(i);
            let mid = |p: Point3, q: Point3| p + (q - p) / 2.0;
            let centroid = a + ((b - a) + (c - a)) / 3.0;
            for p in [centroid, mid(a, b), mid(b, c), mid(c, a)] {
                let d = dist(&p);
                assert!(d <= TOL, "{name}: triangle {i} at {p:?} is {d} off");
                worst = worst.max(d);
            }
        }
        println!("{name}: max chord deviation {worst:.3e} mm");
        if name == "fillet-pocket" {
            assert!(
                worst > TOL / 10.0,
                "tessellation finer than needed: {worst}"
            );
        } else {
            assert!(worst < 1e-12, "{name}: planar part off by {worst}");
        }
    }
}

#[test]
fn triangles_face_out_of_the_material() {
    for (name, _, _, _, normal) in PARTS {
        let m = mesh(name);
        for i in 0..m.len() {
            let n = m
                .normal(i)
                .unwrap_or_else(|| panic!("{name}: triangle {i} degenerate"));
            let [a, b, c] = m.triangle(i);
            let centroid = a + ((b - a) + (c - a)) / 3.0;
            let want = normal(&centroid);
            assert!(n.z >= -1e-12, "{name}: triangle {i} faces down: {n:?}");
            assert!(
                n.dot(&want) > 0.99,
                "{name}: triangle {i} {n:?}, expected {want:?}"
            );
        }
    }
}

#[test]
fn projected_area_is_the_block() {
    for (name, size, ..) in PARTS {
        let m = mesh(name);
        let mut total = 0.0;
        for i in 0..m.len() {
            let [a, b, c] = m.triangle(i);
            let area = ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2.0;
            assert!(area >= -1e-12, "{name}: triangle {i} seen from below");
            total += area;
        }
        let block = size[0] * size[1];
        assert!(
            (total - block).abs() < 1e-9 * block,
            "{name}: {total} against {block}"
        );
    }
}

/// The upper envelope on a 0.2 mm grid over the whole block: exact on the planar
/// faces, within the tolerance (and never below) on the curved ones; grid points
/// within 2 tolerances of a vertical wall of the fillet pocket only have to lie
/// within the tolerance of the surface.
#[test]
fn upper_surface_matches_the_height_formula() {
    for (name, size, dist, height, _) in PARTS {
        let upper = Upper::new(&mesh(name), size);
        let (nx, ny) = ((size[0] / 0.2) as usize, (size[1] / 0.2) as usize);
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = (0.0371 + 0.2 * i as f64, 0.0213 + 0.2 * j as f64);
                let z = upper
                    .at(x, y)
                    .unwrap_or_else(|| panic!("{name}: gap at {x} {y}"));
                let h = height(x, y);
                let off = dist(&Point3::new(x, y, z));
                assert!(
                    off <= TOL,
                    "{name}: ({x}, {y}, {z}) is {off} off, height {h}"
                );
                let d = core_nearest(x, y).1;
                if name != "fillet-pocket" || d <= 2.0 - 2.0 * TOL || d >= 5.0 + 2.0 * TOL {
                    assert!(
                        (z - h).abs() < 1e-9,
                        "{name}: at ({x}, {y}) {z} against {h}"
                    );
                } else if d < 5.0 - 2.0 * TOL {
                    assert!(z >= h - 1e-9, "{name}: at ({x}, {y}) {z} below {h}");
                }
            }
        }
    }
}

/// The closed form in the module doc: a ball of radius 6 touching the wall y = 20 and
/// the floor leaves (6 - 3)(sqrt 2 - 1) along the bisector, measured on the mesh.
#[test]
fn fillet_rest_along_the_bisector() {
    let upper = Upper::new(&mesh("fillet-pocket"), [100.0, 80.0]);
    let below = |s: f64| upper.at(50.0, 20.0 + s).unwrap() - s;
    let (mut lo, mut hi) = (0.01, 3.0);
    assert!(below(lo) > 0.0 && below(hi) < 0.0);
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if below(mid) > 0.0 { lo = mid } else { hi = mid }
    }
    let fillet = lo * 2f64.sqrt();
    let ball = 6.0 * 2f64.sqrt() - 6.0;
    let rest = ball - fillet;
    assert!((rest - 3.0 * (2f64.sqrt() - 1.0)).abs() <= TOL, "{rest}");
    assert!((rest - 1.2426).abs() < 1e-3);
}

/// The V-groove claim: a ball of radius 6 touches each groove's flanks below its top,
/// with the flank slopes measured on the mesh.
#[test]
fn ball_contacts_sit_below_the_groove_tops() {
    let upper = Upper::new(&mesh("v-grooves"), [140.0, 60.0]);
    for (x0, _) in V {
        let slope = upper.at(x0 + 1.0, 30.0).unwrap() - upper.at(x0, 30.0).unwrap();
        let half = (1.0 / slope).atan();
        let contact = 6.0 / half.sin() - 6.0 * half.sin();
        assert!(contact < 10.0 - 0.5, "groove at {x0}: contact at {contact}");
    }
}

/// The short-groove claim: the groove bottoms form 4 strips, and joining those at
/// most 2 mm apart leaves 3.
#[test]
fn short_groove_bottoms_merge_four_into_three() {
    let upper = Upper::new(&mesh("short-grooves"), [70.0, 60.0]);
    let mut strips = 0;
    let mut merged = 0;
    for y in [15.0, 45.0] {
        let deep: Vec<f64> = (0..7000)
            .map(|i| 0.005 + 0.01 * i as f64)
            .filter(|&x| upper.at(x, y).unwrap() < -3.99)
            .collect();
        let gaps: Vec<f64> = deep
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|&g| g > 0.02)
            .collect();
        strips += gaps.len() + 1;
        merged += gaps.iter().filter(|&&g| g > 2.0).count() + 1;
    }
    assert_eq!((strips, merged), (4, 3));
}
