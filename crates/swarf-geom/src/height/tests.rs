//! The height query against closed forms it does not use: Bernstein sums written out,
//! a rational quarter cylinder, planes.

use super::triangle::tests::Square;
use super::*;
use crate::math::Point3;
use crate::mesh::TriMesh;
use crate::part::Part;
use crate::patch::Patch;

fn part(patches: Vec<Patch>) -> Part {
    Part::new("test", patches)
}

fn bern3(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
}

/// A bicubic Bezier patch whose x depends on u only and y on v only, both cubic
/// (unevenly spaced control points), z mixed: the truth is the Bernstein sum itself.
fn warped() -> (Patch, impl Fn(f64, f64) -> [f64; 3]) {
    let xs = [0.0, 2.0, 12.0, 20.0];
    let ys = [0.0, 6.0, 7.0, 10.0];
    let zc = |i: usize, j: usize| [0.0, 3.0, -1.0, 2.0][i] + [0.0, 1.0, 2.0, 0.5][j] * i as f64;
    let mut pts = Vec::new();
    for (i, x) in xs.iter().enumerate() {
        for (j, y) in ys.iter().enumerate() {
            pts.push(Point3::new(*x, *y, zc(i, j)));
        }
    }
    let truth = move |u: f64, v: f64| {
        let (bu, bv) = (bern3(u), bern3(v));
        let x: f64 = (0..4).map(|i| bu[i] * xs[i]).sum();
        let y: f64 = (0..4).map(|j| bv[j] * ys[j]).sum();
        let mut z = 0.0;
        for (i, bi) in bu.iter().enumerate() {
            for (j, bj) in bv.iter().enumerate() {
                z += bi * bj * zc(i, j);
            }
        }
        [x, y, z]
    };
    (Patch::bezier([3, 3], pts).unwrap(), truth)
}

#[test]
fn bicubic_heights_match_the_bernstein_sum() {
    let (patch, truth) = warped();
    let h = PartHeights::new(&part(vec![patch])).unwrap();
    let mut pts = Vec::new();
    let mut want = Vec::new();
    for a in 0..=40 {
        for b in 0..=40 {
            let [x, y, z] = truth(a as f64 / 40.0, b as f64 / 40.0);
            pts.push([x, y]);
            want.push(z);
        }
    }
    let got = h.at_points(&pts);
    for ((p, z), g) in pts.iter().zip(&want).zip(&got) {
        let g = g.unwrap_or_else(|| panic!("no height at {p:?}"));
        assert_eq!(g.status, HeightStatus::Converged);
        assert!((g.z - z).abs() < 1e-9, "{p:?}: {} vs {z}", g.z);
        assert_eq!(h.at(p[0], p[1]), Some(g), "parallel and serial agree");
    }
    for [x, y] in [[-0.01, 5.0], [20.01, 5.0], [10.0, -1e-6], [10.0, 10.5]] {
        assert!(h.at(x, y).is_none(), "{x} {y}");
    }
    assert!(h.at(f64::NAN, 1.0).is_none());
}

/// A quarter cylinder of radius `r` about the y axis (rational quadratic in u, linear
/// in v over y in [0, 10]): the height over `x` is `sqrt(r^2 - x^2)`.
#[test]
fn quarter_cylinder_heights_are_the_circle() {
    let r = 7.0;
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let pts = vec![
        p(r, 0.0, 0.0),
        p(r, 10.0, 0.0),
        p(r, 0.0, r),
        p(r, 10.0, r),
        p(0.0, 0.0, r),
        p(0.0, 10.0, r),
    ];
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let cyl = Patch::new(
        [2, 1],
        pts,
        [None, None],
        Some(vec![1.0, 1.0, w, w, 1.0, 1.0]),
    )
    .unwrap();
    let h = PartHeights::new(&part(vec![cyl])).unwrap();
    for k in 0..=60 {
        let x = 0.95 * r * k as f64 / 60.0;
        for y in [0.0, 3.3, 10.0] {
            let got = h.at(x, y).unwrap();
            let want = (r * r - x * x).sqrt();
            assert!((got.z - want).abs() < 1e-9, "{x} {y}: {} vs {want}", got.z);
            let n = Vec3::new(x, 0.0, want) / r;
            assert!((got.normal - n).norm() < 1e-6, "{x}: {:?}", got.normal);
        }
    }
    assert!(h.at(-0.1, 5.0).is_none() && h.at(3.0, 10.1).is_none());
}

fn flat(z0: f64, z1: f64, x0: f64) -> Patch {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    Patch::bezier(
        [1, 1],
        vec![
            p(x0, 0.0, z0),
            p(x0, 10.0, z0),
            p(x0 + 10.0, 0.0, z1),
            p(x0 + 10.0, 10.0, z1),
        ],
    )
    .unwrap()
}

#[test]
fn crossing_planes_give_their_maximum_and_grids_agree_with_points() {
    // z = x / 2 over [0, 10] and z = 4 - x / 5 over [2, 12]: they cross at x = 40 / 7.
    let h = PartHeights::new(&part(vec![flat(0.0, 5.0, 0.0), flat(3.6, 1.6, 2.0)])).unwrap();
    let grid = Square { cell: 0.25, n: 56 };
    let mut seen = 0;
    h.fill_rows(&grid, 3, 9, |k, got| {
        let (x, y) = (grid.x(k % 56), grid.y(3 + k / 56));
        let low = if x <= 10.0 {
            0.5 * x
        } else {
            f64::NEG_INFINITY
        };
        let high = if x >= 2.0 {
            4.0 - 0.2 * x
        } else {
            f64::NEG_INFINITY
        };
        assert!((got.z - low.max(high)).abs() < 1e-12, "{x} {y}");
        assert_eq!(got.patch, usize::from(high > low), "{x}");
        let point = h.at(x, y).unwrap();
        assert!((point.z - got.z).abs() < 1e-12);
        seen += 1;
    });
    // Columns with x < 12 (48 of them) over 7 rows.
    assert_eq!(seen, 48 * 7);
    let empty = PartHeights::new(&part(Vec::new())).unwrap();
    assert!(empty.at(1.0, 1.0).is_none());
}

#[test]
fn mesh_upper_and_lower_envelopes() {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let low = [p(0.0, 0.0, 0.0), p(10.0, 0.0, 0.0), p(0.0, 10.0, 0.0)];
    let high = [p(0.0, 0.0, 1.0), p(10.0, 0.0, 3.0), p(0.0, 10.0, 1.0)];
    let mesh = TriMesh::from_triangles(&[low, high]);
    let m = MeshHeights::new(&mesh);
    assert!((m.upper(5.0, 2.0).unwrap() - 2.0).abs() < 1e-12);
    assert_eq!(m.lower(5.0, 2.0), Some(0.0));
    assert!(m.upper(8.0, 8.0).is_none());
    assert_eq!(
        m.upper_points(&[[8.0, 8.0], [10.0, 0.0]]),
        vec![None, Some(3.0)]
    );
    let grid = Square { cell: 1.0, n: 12 };
    let mut n = 0;
    m.fill_rows(&grid, 0, 11, |k, z, normal| {
        let (x, y) = (grid.x(k % 12), grid.y(k / 12));
        assert!((z - (1.0 + 0.2 * x)).abs() < 1e-12 && x + y <= 10.0);
        assert!((normal - Vec3::new(-0.2, 0.0, 1.0).normalize()).norm() < 1e-12);
        n += 1;
    });
    assert_eq!(n, 55);
}

#[test]
fn a_trimmed_plate_over_a_floor_shows_the_floor_through_its_hole() {
    let flat = |z: f64| {
        let p = |x: f64, y: f64| Point3::new(x, y, z);
        Patch::bezier(
            [1, 1],
            vec![p(0.0, 0.0), p(0.0, 50.0), p(50.0, 0.0), p(50.0, 50.0)],
        )
        .unwrap()
    };
    let hole: Vec<[f64; 2]> = (0..200)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 200.0;
            [0.5 + 0.2 * t.cos(), 0.5 + 0.2 * t.sin()]
        })
        .collect();
    let outer = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut part = part(vec![flat(10.0), flat(0.0)]);
    part.faces = vec![crate::part::Face {
        name: Some("plate".into()),
        surface: None,
        trim: Some(crate::trim::Trim::new(vec![outer, hole]).unwrap()),
    }];
    let h = PartHeights::new(&part).unwrap();
    // On a 1 mm grid: over the hole (radius 10 mm about (25, 25), as a 200-gon whose
    // edges stay within 10 (1 - cos(pi / 200)) of the circle) the floor, elsewhere the
    // plate.
    let mut seen = [0usize; 2];
    // (The square's own edges are on the outer loop, either side; they are skipped.)
    for i in 1..50 {
        for j in 1..50 {
            let (x, y) = (i as f64, j as f64);
            let r = ((x - 25.0).powi(2) + (y - 25.0).powi(2)).sqrt();
            if (r - 10.0).abs() < 0.01 {
                continue;
            }
            let got = h.at(x, y).expect("a height over the part");
            let want = if r < 10.0 { 0.0 } else { 10.0 };
            assert_eq!(got.z, want, "at ({x}, {y})");
            assert_eq!(got.patch, usize::from(r < 10.0));
            seen[usize::from(r < 10.0)] += 1;
        }
    }
    assert!(seen[0] > 2000 && seen[1] > 300, "{seen:?}");
}
