//! Drop-cutter against independent oracles.
//!
//! - Per triangle: the kernel's height against a direct numeric maximisation of
//!   `q.z - h(|q.xy - c|)` over the triangle ∩ disc (nested golden sections over
//!   barycentric coordinates, `h` from the tool crate's `Profile::height_at_radius`);
//!   the function is concave on a convex set, so the nested searches find its global
//!   maximum. No vertex/edge/facet split, no envelope.
//! - Per mesh: [`MeshDropper`] against a brute-force drop over every triangle
//!   (heights and winning triangle identical), and at the returned height no triangle
//!   is penetrated beyond 1e-9 (oracle, and the tool crate's exact signed distance on
//!   dense samples) while the CC point is on a triangle and on the cutter surface.

use proptest::prelude::*;
use swarf_geom::{Point3, TriMesh};
use swarf_tool::drop::{DropCutter, DropScratch, MeshDropper, triangle_drop};
use swarf_tool::{Cutter, Pose, Profile};

const SPECS: &[&str] = &[
    "flat:d=6",
    "ball:d=8",
    "bull:d=10,r=2",
    "bull:d=6,r=0.5",
    "cone:d=10,angle=90",
    "cone:d=6,angle=40",
    "taperball:d=6,angle=10,tip=1,length=12",
    "apt:d=10,r=1.5,alpha=10,beta=5,h=30",
    "apt:d=8,r=0,alpha=20,beta=10,h=30",
    "apt:d=12,r=3,alpha=30,beta=-20,h=15",
];

const GOLDEN: f64 = 0.618_033_988_749_894_9;

/// Maximum of a function that is concave on `[a, b]` (golden section).
fn golden_max(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let mut c = b - GOLDEN * (b - a);
    let mut d = a + GOLDEN * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..72 {
        if fc >= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - GOLDEN * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + GOLDEN * (b - a);
            fd = f(d);
        }
    }
    f(a).max(f(b)).max(fc).max(fd)
}

/// Minimum of a function that is convex on `[a, b]` and its argument.
fn golden_min(a: f64, b: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let (mut a, mut b) = (a, b);
    for _ in 0..64 {
        let c = b - GOLDEN * (b - a);
        let d = a + GOLDEN * (b - a);
        if f(c) <= f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let x = 0.5 * (a + b);
    (x, f(x))
}

/// Largest `x` in `[a, b]` with `pred(x)` for a predicate true at `a` and monotone.
fn bisect(mut a: f64, mut b: f64, pred: impl Fn(f64) -> bool) -> f64 {
    if pred(b) {
        return b;
    }
    for _ in 0..64 {
        let m = 0.5 * (a + b);
        if pred(m) { a = m } else { b = m }
    }
    a
}

/// The oracle: max of `q.z - h(rho)` over triangle ∩ disc, `None` when they miss.
fn oracle(profile: &Profile, c: [f64; 2], t: &[Point3; 3]) -> Option<f64> {
    let r = profile.radius();
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let at = |u: f64, v: f64| t[0] + u * e1 + v * e2;
    let dist = |q: Point3| (q.x - c[0]).hypot(q.y - c[1]);
    // The chord of the triangle at u, clipped to the disc: v in [v0, v1].
    let chord = |u: f64| -> Option<(f64, f64)> {
        let vmax = (1.0 - u).max(0.0);
        let (vm, dmin) = golden_min(0.0, vmax, |v| dist(at(u, v)));
        if dmin > r {
            return None;
        }
        let v0 = if dist(at(u, 0.0)) <= r {
            0.0
        } else {
            first_true(vm, |v| dist(at(u, v)) <= r)
        };
        let v1 = bisect(vm, vmax, |v| dist(at(u, v)) <= r);
        Some((v0, v1))
    };
    let width = |u: f64| {
        let vmax = (1.0 - u).max(0.0);
        golden_min(0.0, vmax, |v| dist(at(u, v))).1
    };
    let (um, dmin) = golden_min(0.0, 1.0, width);
    if dmin > r {
        return None;
    }
    let u0 = if width(0.0) <= r {
        0.0
    } else {
        first_true(um, |u| width(u) <= r)
    };
    let u1 = bisect(um, 1.0, |u| width(u) <= r);
    let f = |q: Point3| q.z - profile.height_at_radius(dist(q).min(r)).unwrap_or(f64::NAN);
    let inner = |u: f64| match chord(u) {
        Some((v0, v1)) => golden_max(v0, v1, |v| f(at(u, v))),
        None => f64::NEG_INFINITY,
    };
    Some(golden_max(u0, u1, inner))
}

/// Smallest `x` in `[0, b]` with `pred(x)`, for a predicate true at `b` and monotone.
fn first_true(b: f64, pred: impl Fn(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (0.0, b);
    for _ in 0..64 {
        let m = 0.5 * (lo + hi);
        if pred(m) { hi = m } else { lo = m }
    }
    hi
}

fn cutter(spec: &str) -> Cutter {
    spec.parse().unwrap()
}

/// Random triangles: sizes over two decades, any orientation (near-vertical ones
/// included), some degenerate.
fn triangle() -> impl Strategy<Value = [Point3; 3]> {
    let p = || (-6.0..6.0f64, -6.0..6.0f64, -3.0..3.0f64);
    (p(), p(), p(), 0u8..12, 0.05..1.0f64).prop_map(|(a, b, c, kind, s)| {
        let a = Point3::new(a.0, a.1, a.2);
        let b = Point3::new(b.0, b.1, b.2);
        let c = Point3::new(c.0, c.1, c.2);
        match kind {
            0 => [a, b, a + (b - a) * s],
            1 => [a, b, Point3::new(a.x, a.y, c.z)],
            2 => [
                a,
                Point3::new(a.x + s * 1e-7, a.y, b.z),
                Point3::new(b.x, b.y, c.z),
            ],
            3 => [a, a + (b - a) * s * 0.2, a + (c - a) * s * 0.2],
            _ => [a, b, c],
        }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Every cutter, one random triangle, several query points: the kernel's height
    /// equals the numeric maximum to 1e-9, and its CC point is on the triangle and
    /// on the cutter surface.
    #[test]
    fn kernel_matches_numeric_maximum(t in triangle(), pts in prop::collection::vec((-9.0..9.0f64, -9.0..9.0f64), 3)) {
        for spec in SPECS {
            let c = cutter(spec);
            let tool = DropCutter::new(&c);
            let profile = c.profile();
            for &(x, y) in &pts {
                let got = triangle_drop(&tool, [x, y], &t);
                let want = oracle(&profile, [x, y], &t);
                match (got, want) {
                    (Some(g), Some(w)) => {
                        prop_assert!((g.z - w).abs() < 1e-9, "{} at ({}, {}) on {:?}: kernel {} ({:?}), oracle {}", spec, x, y, t, g.z, g.feature, w);
                        let pose = Pose::vertical(Point3::new(x, y, g.z));
                        let sd = c.signed_distance(&pose, &g.cc);
                        prop_assert!(sd.abs() < 1e-9, "{}: cc off the cutter by {}", spec, sd);
                    }
                    (None, None) => {}
                    (g, w) => {
                        // Only a triangle exactly at the reach may differ.
                        let near = (0..3).map(|k| seg_dist([x, y], &t[k], &t[(k + 1) % 3])).fold(f64::MAX, f64::min);
                        prop_assert!((near - tool.radius()).abs() < 1e-7, "{}: kernel {:?}, oracle {:?}", spec, g, w);
                    }
                }
            }
        }
    }
}

/// XY distance from `c` to the segment `ab`.
fn seg_dist(c: [f64; 2], a: &Point3, b: &Point3) -> f64 {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((c[0] - a.x) * dx + (c[1] - a.y) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a.x + t * dx - c[0]).hypot(a.y + t * dy - c[1])
}

/// A heightfield grid `nx * ny` over `[0, 20]^2` with random heights, plus loose
/// random triangles (overhangs, spikes, walls).
fn mesh() -> impl Strategy<Value = TriMesh> {
    let heights = prop::collection::vec(-2.0..2.0f64, 36);
    let loose = prop::collection::vec(triangle(), 0..12);
    (heights, loose).prop_map(|(h, loose)| {
        let n = 6;
        let p = |i: usize, j: usize| Point3::new(4.0 * i as f64, 4.0 * j as f64, h[j * n + i]);
        let mut soup = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                soup.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
                soup.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
            }
        }
        soup.extend(
            loose
                .into_iter()
                .map(|t| t.map(|q| q + swarf_geom::Vec3::new(10.0, 10.0, 0.0))),
        );
        TriMesh::from_triangles(&soup)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// The indexed, pruned drop equals the brute-force maximum over all triangles,
    /// and at its height nothing is penetrated while something is touched.
    #[test]
    fn mesh_drop_is_brute_force_and_touches_without_gouging(
        m in mesh(),
        pts in prop::collection::vec((-6.0..26.0f64, -6.0..26.0f64), 6),
        which in 0..SPECS.len(),
    ) {
        let c = cutter(SPECS[which]);
        let tool = DropCutter::new(&c);
        let dropper = MeshDropper::new(&m, &c);
        let profile = c.profile();
        let mut scratch = DropScratch::default();
        for &(x, y) in &pts {
            let got = dropper.drop(x, y, &mut scratch);
            // The scratch's hint (the last winner, tried first) changes nothing.
            prop_assert_eq!(got, dropper.drop(x, y, &mut DropScratch::default()));
            let mut brute: Option<(f64, usize)> = None;
            for t in 0..m.len() {
                if let Some(d) = triangle_drop(&tool, [x, y], &m.triangle(t))
                    && brute.is_none_or(|b| d.z > b.0)
                {
                    brute = Some((d.z, t));
                }
            }
            prop_assert_eq!(got.map(|g| (g.z, g.tri as usize)), brute);
            let Some(g) = got else { continue };
            let pose = Pose::vertical(Point3::new(x, y, g.z));
            prop_assert!(c.signed_distance(&pose, &g.cc).abs() < 1e-9);
            prop_assert!(on_triangle(&m.triangle(g.tri as usize), &g.cc));
            for t in 0..m.len() {
                let tri = m.triangle(t);
                if xy_dist([x, y], &tri) > tool.radius() {
                    continue;
                }
                if let Some(w) = oracle(&profile, [x, y], &tri) {
                    prop_assert!(w <= g.z + 1e-9, "{}: triangle {} penetrated by {}", SPECS[which], t, w - g.z);
                }
                for q in samples(&tri) {
                    let sd = c.signed_distance(&pose, &q);
                    prop_assert!(sd > -1e-9, "{}: sample of triangle {} inside by {}", SPECS[which], t, -sd);
                }
            }
        }
    }
}

/// XY distance from `c` to the triangle's projection (0 inside).
fn xy_dist(c: [f64; 2], t: &[Point3; 3]) -> f64 {
    let cross = |a: &Point3, b: &Point3| (a.x - c[0]) * (b.y - c[1]) - (a.y - c[1]) * (b.x - c[0]);
    let e = [
        cross(&t[1], &t[2]),
        cross(&t[2], &t[0]),
        cross(&t[0], &t[1]),
    ];
    if e.iter().all(|&v| v >= 0.0) || e.iter().all(|&v| v <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|k| seg_dist(c, &t[k], &t[(k + 1) % 3]))
        .fold(f64::MAX, f64::min)
}

/// Within 1e-9 mm of the triangle: of one of its edges, or of its plane with the
/// projection inside (barycentric test, fine away from the edges even for slivers).
fn on_triangle(t: &[Point3; 3], q: &Point3) -> bool {
    if (0..3).any(|k| seg3_dist(q, &t[k], &t[(k + 1) % 3]) < 1e-9) {
        return true;
    }
    let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
    let a2 = n.norm_squared();
    if a2 == 0.0 {
        return false;
    }
    let inside =
        (0..3).all(|k| (t[(k + 1) % 3] - q).cross(&(t[(k + 2) % 3] - q)).dot(&n) / a2 > -1e-9);
    let off_plane = (q - t[0]).dot(&n).abs() / a2.sqrt();
    off_plane < 1e-9 && inside
}

fn seg3_dist(q: &Point3, a: &Point3, b: &Point3) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    let t = if l2 > 0.0 {
        ((q - a).dot(&d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * d - q).norm()
}

/// A barycentric grid of 21 x 21 samples, edges and corners included.
fn samples(t: &[Point3; 3]) -> impl Iterator<Item = Point3> + '_ {
    let n = 20;
    (0..=n).flat_map(move |i| {
        (0..=n - i).map(move |j| {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0])
        })
    })
}

#[test]
fn ball_on_a_tessellated_sphere_matches_the_closed_form() {
    // A ball of radius R over a convex sphere of radius S (centre at the origin):
    // the tip at distance rho from the sphere's axis sits at sqrt((R+S)^2 - rho^2) - R
    // above the centre. On a fine tessellation the drop is below that by at most the
    // chordal error and never above it.
    let s = 20.0;
    let n = 120;
    let mut soup = Vec::new();
    let at = |i: usize, j: usize| {
        let (th, ph) = (
            std::f64::consts::FRAC_PI_2 * i as f64 / n as f64,
            std::f64::consts::TAU * j as f64 / n as f64,
        );
        Point3::new(
            s * th.sin() * ph.cos(),
            s * th.sin() * ph.sin(),
            s * th.cos(),
        )
    };
    for i in 0..n {
        for j in 0..n {
            soup.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            soup.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let mesh = TriMesh::from_triangles(&soup);
    let dropper = MeshDropper::new(&mesh, &cutter("ball:d=8"));
    let mut scratch = DropScratch::default();
    let chord = s * (1.0 - (std::f64::consts::PI / n as f64).cos());
    for k in 0..50 {
        let (x, y) = (0.3 * k as f64 - 7.0, 0.17 * k as f64 - 4.0);
        let rho = x.hypot(y);
        let want = ((4.0 + s) * (4.0 + s) - rho * rho).sqrt() - 4.0;
        let got = dropper.drop(x, y, &mut scratch).unwrap().z;
        assert!(
            got <= want + 1e-9 && got >= want - 2.0 * chord,
            "{x} {y}: {got} vs {want}"
        );
    }
}
