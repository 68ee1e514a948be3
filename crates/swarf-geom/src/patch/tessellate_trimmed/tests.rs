use super::*;
use crate::patch::fixtures::{quarter_cylinder, wave};

fn circle(c: Uv, r: f64, n: usize) -> Vec<Uv> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

fn area(m: &TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.vertices[i as usize]);
            0.5 * (b - a).cross(&(c - a)).norm()
        })
        .sum()
}

/// Shoelace area of a uv polygon.
fn polygon_area(l: &[Uv]) -> f64 {
    0.5 * (0..l.len())
        .map(|k| {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        .abs()
}

#[test]
fn a_plate_with_a_hole_has_the_polygons_area() {
    let p = |x: f64, y: f64| Point3::new(x, y, 2.0);
    let plate = Patch::bezier(
        [1, 1],
        vec![p(0.0, 0.0), p(0.0, 80.0), p(100.0, 0.0), p(100.0, 80.0)],
    )
    .unwrap();
    let hole = circle([0.5, 0.5], 0.2, 1000);
    let outer = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let trim = Trim::new(vec![outer, hole.clone()]).unwrap();
    let m = plate.tessellate_trimmed(&trim, 0.01).unwrap();
    // The uv hole is an ellipse of semi-axes 20 x 16 mm, as a 1000-gon.
    let want = 8000.0 - polygon_area(&hole) * 8000.0;
    assert!(
        (area(&m) - want).abs() < 1e-9 * want,
        "{} vs {want}",
        area(&m)
    );
    assert!(m.vertices.iter().all(|v| v.z == 2.0));
    // No triangle over the hole: centroids are at least inside the polygon's ring.
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.vertices[i as usize]);
        let g = (a.coords + b.coords + c.coords) / 3.0;
        let (du, dv) = ((g.x / 100.0 - 0.5) / 0.2, (g.y / 80.0 - 0.5) / 0.2);
        assert!(du * du + dv * dv > 0.99, "triangle over the hole at {g:?}");
        // Counter-clockwise in (u, v): the normal is +z like du x dv.
        assert!((b - a).cross(&(c - a)).z > 0.0);
    }
}

#[test]
fn every_triangle_of_a_trimmed_wave_is_within_tolerance() {
    let w = wave();
    let [[u0, u1], [v0, v1]] = w.domain();
    let s = |a: f64, b: f64| [u0 + a * (u1 - u0), v0 + b * (v1 - v0)];
    // A corner cut off the outer loop and an off-centre hole.
    let outer = vec![
        s(0.0, 0.0),
        s(0.7, 0.0),
        s(1.0, 0.3),
        s(1.0, 1.0),
        s(0.0, 1.0),
    ];
    let hole: Vec<Uv> = circle([0.4, 0.55], 0.17, 400)
        .iter()
        .map(|p| s(p[0], p[1]))
        .collect();
    let trim = Trim::new(vec![outer, hole]).unwrap();
    for tol in [0.05, 0.01] {
        let m = w.tessellate_trimmed(&trim, tol).unwrap();
        let mut worst: f64 = 0.0;
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.vertices[i as usize]);
            for q in [
                Point3::from((a.coords + b.coords + c.coords) / 3.0),
                Point3::from((a.coords + b.coords) / 2.0),
                Point3::from((b.coords + c.coords) / 2.0),
                Point3::from((a.coords + c.coords) / 2.0),
            ] {
                let pr = w.project(&q);
                worst = worst.max(pr.distance);
                let g = [(pr.u - u0) / (u1 - u0), (pr.v - v0) / (v1 - v0)];
                let (du, dv) = (g[0] - 0.4, g[1] - 0.55);
                assert!(du * du + dv * dv > 0.169f64.powi(2), "over the hole: {g:?}");
                assert!(g[0] <= 0.7 + g[1] + 1e-3, "cut corner: {g:?}");
            }
        }
        assert!(worst <= tol, "tol {tol}: {worst}");
    }
}

#[test]
fn a_trim_along_a_curved_patch_is_split_to_the_tolerance() {
    // A quarter cylinder, trimmed by a uv triangle whose long edge crosses the curvature:
    // the 3D chord of that edge strays from the surface unless it is split.
    let cyl = quarter_cylinder(50.0, 20.0);
    let [[u0, u1], [v0, v1]] = cyl.domain();
    let trim = Trim::new(vec![vec![[u0, v0], [u1, v0], [u0, v1]]]).unwrap();
    let m = cyl.tessellate_trimmed(&trim, 0.01).unwrap();
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.vertices[i as usize]);
        for q in [
            (a.coords + b.coords) / 2.0,
            (b.coords + c.coords) / 2.0,
            (a.coords + c.coords) / 2.0,
        ] {
            let d = cyl.project(&Point3::from(q)).distance;
            assert!(d <= 0.01, "{d} at {q:?}, triangle {a} {b} {c}");
        }
    }
}

#[test]
fn bad_tolerance_is_named() {
    let trim = Trim::new(vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]).unwrap();
    let e = wave()
        .tessellate_trimmed(&trim, -1.0)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("tol = -1"), "{e}");
}
