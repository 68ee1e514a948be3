//! Tests of the built-in mesh parts against the oracles of [`super::oracles`]
//! (written from the parts' descriptions, sharing no code with the generators) and a
//! brute-force upper envelope of the mesh. The fillet pocket's air is convex below
//! z = 20, so every triangle with its corners on the surface lies in the air: the mesh
//! is nowhere below the true pocket surface.

use super::oracles::*;
use super::*;
use swarf_geom::Point3;

const TOL: f64 = MESH_PART_CHORD;

fn mesh(name: &str) -> TriMesh {
    builtin_mesh(name).expect("built-in mesh")
}

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
    assert_eq!(mesh("boss").len(), 34);
    assert_eq!(mesh("ramp-step").len(), 6);
}

#[test]
fn arc_segments_is_the_fewest_within_tolerance() {
    for (r, t, tol) in [
        (5.0, std::f64::consts::FRAC_PI_2, 5e-4),
        (3.0, std::f64::consts::FRAC_PI_2, 5e-4),
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

/// The boss's wall areas of the module doc, summed per slope over the triangles (3D
/// by the cross product, XY by the shoelace formula), against `1600 / sin a` and
/// `1600 / tan a`; the rest of the surface is flat and fills the plate.
#[test]
fn boss_wall_areas_per_angle() {
    let m = mesh("boss");
    let mut per_deg = std::collections::BTreeMap::<i64, [f64; 2]>::new();
    for i in 0..m.len() {
        let [a, b, c] = m.triangle(i);
        let n = (b - a).cross(&(c - a));
        let deg = (n.z / n.norm()).acos().to_degrees().round() as i64;
        let e = per_deg.entry(deg).or_default();
        e[0] += n.norm() / 2.0;
        e[1] += n.z / 2.0;
    }
    let flat = per_deg.remove(&0).unwrap();
    let expect = [
        (45, 2262.742, 1600.0),
        (65, 1765.405, 746.092),
        (80, 1624.683, 282.123),
        (90, 1600.0, 0.0),
    ];
    assert_eq!(per_deg.len(), expect.len(), "{per_deg:?}");
    let mut steep_xy = 0.0;
    for (deg, area, xy) in expect {
        let got = per_deg[&deg];
        let a = (deg as f64).to_radians();
        assert!((got[0] - 1600.0 / a.sin()).abs() < 1e-9, "{deg}: {got:?}");
        assert!((got[0] - area).abs() < 5e-4 && (got[1] - xy).abs() < 5e-4);
        steep_xy += got[1];
    }
    assert!((steep_xy - 2628.215).abs() < 1e-3);
    assert!((flat[0] - flat[1]).abs() < 1e-9 && (flat[1] + steep_xy - 80.0 * 140.0).abs() < 1e-9);
}

/// The raster figures of the boss's doc: step 0.632 for h = 0.01 with a ball d = 10,
/// and the scallops it leaves on the 45, 65 and 80 degree walls.
#[test]
fn boss_scallops_of_the_flat_step() {
    let (r, h) = (5.0_f64, 0.01_f64);
    let s = 2.0 * (2.0 * r * h - h * h).sqrt();
    assert!((s - 0.632).abs() < 5e-4, "{s}");
    for (deg, doc) in [(45.0_f64, 0.020), (65.0, 0.056), (80.0, 0.343)] {
        let w = s / deg.to_radians().cos();
        let scallop = r - (r * r - w * w / 4.0).sqrt();
        assert!((scallop - doc).abs() < 5e-4, "{deg}: {scallop}");
    }
}

/// The ramp-step's profile: plateau, 45-degree wall, floor, measured on the mesh.
#[test]
fn ramp_step_drops_twenty_at_45_degrees() {
    let upper = Upper::new(&mesh("ramp-step"), [120.0, 40.0]);
    for (x, z) in [
        (10.0, 20.0),
        (39.9, 20.0),
        (45.0, 15.0),
        (55.0, 5.0),
        (60.1, 0.0),
        (119.0, 0.0),
    ] {
        let got = upper.at(x, 20.0).unwrap();
        assert!((got - z).abs() < 1e-9, "at {x}: {got}");
    }
}
