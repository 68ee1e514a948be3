//! Drop-and-spin on the shared edge parts (issue 13, "Symmetries" and "Contacts"):
//! face 1 is face 0 mirrored in y and each part is symmetric about x = 50, so the
//! zone starts on the edge (y = 0), the insert's ball stops where its centre reaches
//! y = 0, and the two spins at x = 50 mirror each other. Contacts are checked against
//! the torus written out here and against brute-force sampling of both faces.

use swarf_fiveaxis::dsm::{Dsm, Spin, SpinSide};
use swarf_geom::{Patch, Point3, Vec3};
use swarf_tool::{Cutter, Pose};

const TOOL: &str = "bull:d=12,r=2,length=30";
/// Insert-centre radius of `TOOL`.
const BIG: f64 = 4.0;
/// Insert radius of `TOOL`.
const SMALL: f64 = 2.0;
const LENGTH: f64 = 30.0;

fn dsm(part: &str) -> (Dsm, [Patch; 2]) {
    let part = swarf_io::builtin_part(part).unwrap();
    let tool: Cutter = TOOL.parse().unwrap();
    let d = Dsm::new(&part, [0, 1], &tool, Vec3::x()).unwrap();
    (d, [part.patches[0].clone(), part.patches[1].clone()])
}

/// Signed distance from `p` to the bull solid at `pose`, written from its shape: a
/// disc of radius `BIG` at the tip, the torus of the insert circle (radius `SMALL`
/// about the circle of radius `BIG` at height `SMALL`), a cylinder up to `LENGTH`
/// and the top disc.
fn bull_distance(pose: &Pose, p: &Point3) -> f64 {
    let w = p - pose.cl;
    let z = w.dot(&pose.axis);
    let rho = (w - z * pose.axis).norm();
    let outer = BIG + SMALL;
    let inside = (0.0..=LENGTH).contains(&z)
        && (rho <= BIG
            || (z >= SMALL && rho <= outer)
            || ((rho - BIG).powi(2) + (z - SMALL).powi(2)).sqrt() <= SMALL);
    let seg = |a: (f64, f64), b: (f64, f64)| {
        let (dx, dz) = (b.0 - a.0, b.1 - a.1);
        let t = (((rho - a.0) * dx + (z - a.1) * dz) / (dx * dx + dz * dz)).clamp(0.0, 1.0);
        ((rho - a.0 - t * dx).powi(2) + (z - a.1 - t * dz).powi(2)).sqrt()
    };
    let arc = {
        let (vr, vz) = (rho - BIG, z - SMALL);
        if vr >= 0.0 && vz <= 0.0 {
            ((vr * vr + vz * vz).sqrt() - SMALL).abs()
        } else {
            f64::INFINITY
        }
    };
    let d = [
        seg((0.0, 0.0), (BIG, 0.0)),
        arc,
        seg((outer, SMALL), (outer, LENGTH)),
        seg((0.0, LENGTH), (outer, LENGTH)),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    if inside { -d } else { d }
}

/// The least of `bull_distance` over `patch`: a 200 x 200 grid, then a 41 x 41 grid
/// of a 100th of its spacing around the best node, twice.
fn brute_min(patch: &Patch, pose: &Pose) -> (f64, Point3) {
    let f = |u: f64, v: f64| {
        let p = patch.eval(u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        (bull_distance(pose, &p), p)
    };
    let mut best = (f64::INFINITY, Point3::origin(), 0.0, 0.0);
    let (mut cu, mut cv, mut half, mut n) = (0.5, 0.5, 0.5, 200);
    for _ in 0..3 {
        for i in 0..=n {
            for j in 0..=n {
                let u = cu - half + 2.0 * half * i as f64 / n as f64;
                let v = cv - half + 2.0 * half * j as f64 / n as f64;
                let (d, p) = f(u, v);
                if d < best.0 {
                    best = (d, p, u, v);
                }
            }
        }
        (cu, cv) = (best.2, best.3);
        half = 2.0 * half / n as f64;
        n = 40;
    }
    (best.0, best.1)
}

/// The insert-circle centre nearest `q` sits `SMALL` from it along the face normal.
fn tangent_residual(pose: &Pose, q: &Point3, n: &Vec3) -> f64 {
    let c = q + n * SMALL;
    let w = c - pose.cl;
    let z = w.dot(&pose.axis);
    let rho = (w - z * pose.axis).norm();
    (z - SMALL).abs().max((rho - BIG).abs())
}

fn up_normal(patch: &Patch, p: &Point3) -> Vec3 {
    let pr = patch.project(p);
    let n = patch.derivs(pr.u, pr.v).normal().unwrap();
    if n.z < 0.0 { -n } else { n }
}

#[test]
fn the_zone_starts_on_the_edge_and_the_ball_stops_on_the_mirror_plane() {
    for part in ["edge-convex", "edge-concave"] {
        let (d, _) = dsm(part);
        for s in [20.0, 50.0, 80.0] {
            let st = d.station(s).unwrap();
            assert!(st.edge.y.abs() < 1e-9, "{part} {s}: edge {:?}", st.edge);
            let z = d.zone(&st, 0).unwrap();
            eprintln!("{part} x = {s}: {z:?}");
            assert!(z.t1.abs() < 1e-7, "T1 {}", z.t1);
            // At T1 the dropped tool touches both faces at mirrored points.
            let drop = d.drop_on(0, d.footprint(&st, 0, z.t1)).unwrap();
            let q = d.clearance(1, &drop.pose).unwrap();
            assert!(q.distance.abs() < 1e-7, "{}", q.distance);
            let mirror = Point3::new(drop.p.x, -drop.p.y, drop.p.z);
            assert!(
                (q.point - mirror).norm() < 1e-4,
                "{:?} vs {mirror:?}",
                q.point
            );
            // At the ball limit the insert's centre is on y = 0.
            let drop = d.drop_on(0, d.footprint(&st, 0, z.t2_ball)).unwrap();
            let centre = drop.p + drop.normal * SMALL;
            assert!(centre.y.abs() < 1e-6, "centre {centre:?}");
        }
    }
}

fn check_contacts(faces: &[Patch; 2], drop_p: &Point3, s: &Spin) {
    let (n_p, n_q) = (up_normal(&faces[0], drop_p), up_normal(&faces[1], &s.q));
    assert!(tangent_residual(&s.pose, drop_p, &n_p) < 1e-6);
    assert!(
        tangent_residual(&s.pose, &s.q, &n_q) < 1e-6,
        "{}",
        tangent_residual(&s.pose, &s.q, &n_q)
    );
    assert!(bull_distance(&s.pose, drop_p).abs() < 1e-6);
    assert!(bull_distance(&s.pose, &s.q).abs() < 1e-6);
    let (m0, _) = brute_min(&faces[0], &s.pose);
    let (m1, at) = brute_min(&faces[1], &s.pose);
    assert!(m0 > -1e-6, "face 0 penetrated by {m0}");
    assert!(m1.abs() < 1e-6, "face 1 at {m1} ({at:?})");
}

#[test]
fn the_spins_mirror_each_other_and_touch_both_faces() {
    for part in ["edge-convex", "edge-concave"] {
        let (d, faces) = dsm(part);
        let st = d.station(50.0).unwrap();
        let z = d.zone(&st, 0).unwrap();
        for f in [0.25, 0.5, 0.9] {
            let w = z.t1 + f * (z.t2 - z.t1);
            let drop = d.drop_on(0, d.footprint(&st, 0, w)).unwrap();
            let plus = d.spin(&drop, SpinSide::Plus).unwrap();
            let minus = d.spin(&drop, SpinSide::Minus).unwrap();
            let (a, b) = (plus.pose, minus.pose);
            let mirrored = Point3::new(100.0 - b.cl.x, b.cl.y, b.cl.z);
            eprintln!(
                "{part} w = {w:.4}: spins {:.9} {:.9}",
                plus.angle, minus.angle
            );
            assert!(
                (a.cl - mirrored).norm() < 1e-6,
                "{:?} vs {mirrored:?}",
                a.cl
            );
            assert!((a.axis - Vec3::new(-b.axis.x, b.axis.y, b.axis.z)).norm() < 1e-6);
            assert!((plus.angle + minus.angle).abs() < 1e-7);
            check_contacts(&faces, &drop.p, &plus);
            check_contacts(&faces, &drop.p, &minus);
        }
    }
}

#[test]
fn a_corner_too_small_for_the_sampling_is_refused_with_one_that_fits() {
    let part = swarf_io::builtin_part("edge-concave").unwrap();
    let small = Cutter::bull(12.0, 0.5, Some(30.0)).unwrap();
    let e = Dsm::new(&part, [0, 1], &small, Vec3::x())
        .unwrap_err()
        .to_string();
    let fits: f64 = e
        .split("at least ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no radius in: {e}"));
    assert!(fits > 0.5 && fits < 6.0, "{e}");
    // The radius the message names is accepted; a tenth less is not (the sample
    // counts round up per side, so the count is not strictly monotone in r).
    let at = |r: f64| {
        Dsm::new(
            &part,
            [0, 1],
            &Cutter::bull(12.0, r, Some(30.0)).unwrap(),
            Vec3::x(),
        )
    };
    assert!(at(fits).is_ok(), "{fits} refused");
    assert!(at(0.9 * fits).is_err(), "{fits} is far from the least");
}
