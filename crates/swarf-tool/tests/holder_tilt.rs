//! Five-axis holder check: a tool on a floor 8 mm from a 60 mm wall, whose holder
//! reaches into the wall when vertical; tilting away from the wall clears it. The
//! tilt found is the closed form's to the search tolerance; it clears and 0.002 rad
//! less does not, judged by a brute-force oracle sharing no code with the check:
//! points sampled densely on the shank and holder surfaces in the tilted frame, from
//! the assembly's radius written here in closed form, tested against the part
//! written as a closed-form solid.

use swarf_geom::{Point3, TriMesh, Vec3};
use swarf_tool::drop::MeshDropper;
use swarf_tool::holder::tilted::{
    Tilt, TiltSearch, Views, clearing_tilt, pose_clearance, shortest_stick_out_posed,
};
use swarf_tool::holder::vertical::StickOut;
use swarf_tool::holder::{Assembly, StackSegment};
use swarf_tool::{Cutter, Pose};

fn assembly() -> Assembly {
    Assembly {
        cutter: Cutter::ball(6.0, Some(12.0)).unwrap(),
        shank: vec![StackSegment::Cylinder {
            d: 6.0,
            length: 40.0,
        }],
        holder: vec![
            StackSegment::Cone {
                d0: 8.0,
                d1: 32.0,
                length: 30.0,
            },
            StackSegment::Cylinder {
                d: 63.0,
                length: 30.0,
            },
        ],
        stick_out: 25.0,
    }
}

/// Radius at height `h` above the tip (oracle, closed form).
fn radius(h: f64) -> Option<f64> {
    match h {
        h if h < 12.0 => None,
        h if h < 25.0 => Some(3.0),
        h if h < 55.0 => Some(4.0 + 0.4 * (h - 25.0)),
        h if h <= 85.0 => Some(31.5),
        _ => None,
    }
}

/// The floor z = 0 for x in [0, 100] and the wall block x in [-50, 0] up to z = 60,
/// y in [-50, 50].
fn mesh() -> TriMesh {
    let p = Point3::new;
    let quad = |a: Point3, b: Point3, c: Point3, d: Point3| [[a, b, c], [a, c, d]];
    let mut t = Vec::new();
    t.extend(quad(
        p(0.0, -50.0, 0.0),
        p(100.0, -50.0, 0.0),
        p(100.0, 50.0, 0.0),
        p(0.0, 50.0, 0.0),
    ));
    t.extend(quad(
        p(0.0, -50.0, 0.0),
        p(0.0, 50.0, 0.0),
        p(0.0, 50.0, 60.0),
        p(0.0, -50.0, 60.0),
    ));
    t.extend(quad(
        p(-50.0, -50.0, 60.0),
        p(0.0, -50.0, 60.0),
        p(0.0, 50.0, 60.0),
        p(-50.0, 50.0, 60.0),
    ));
    TriMesh::from_triangles(&t)
}

fn in_material(q: &Point3) -> bool {
    let e = 1e-9;
    let in_y = q.y.abs() < 50.0 - e;
    let wall = q.x > -50.0 + e && q.x < -e && q.z < 60.0 - e;
    let floor = q.x > e && q.x < 100.0 - e && q.z < -e && q.z > -50.0;
    in_y && (wall || floor)
}

/// Brute force at tip `cl`, axis `a`: any sampled surface point in the part?
fn oracle_collides(cl: &Point3, a: &Vec3) -> bool {
    let u = a.cross(&Vec3::y()).normalize();
    let v = a.cross(&u);
    let dirs: Vec<Vec3> = (0..720)
        .map(|i| {
            let (s, c) = (std::f64::consts::TAU * f64::from(i) / 720.0).sin_cos();
            c * u + s * v
        })
        .collect();
    let hit = |rho: f64, h: f64| dirs.iter().any(|d| in_material(&(cl + h * a + rho * d)));
    for k in 0..=36_500 {
        let h = 12.0 + 0.002 * f64::from(k);
        if radius(h).is_some_and(|r| hit(r, h)) {
            return true;
        }
    }
    let discs = [(12.0, 0.0, 3.0), (25.0, 0.0, 4.0), (55.0, 16.0, 31.5)];
    discs
        .iter()
        .any(|&(h, r0, r1)| (0..=400).any(|k| hit(r0 + (r1 - r0) * f64::from(k) / 400.0, h)))
}

#[test]
fn tilting_away_from_the_wall_clears_the_holder() {
    let (a, mesh) = (assembly(), mesh());
    let pose = Pose::vertical(Point3::new(8.0, 0.0, 0.0));
    let c = pose_clearance(&a, &mesh, &pose).unwrap().unwrap();
    // Vertical: the nose cone (radius 4 + 0.4 t) reaches the wall 8 away at t = 10,
    // so it sits on the wall top at z = 60 - 10: 25 mm into the part along the axis.
    assert!((c.clearance + 25.0).abs() < 1e-9, "{c:?}");
    assert!(oracle_collides(&pose.cl, &pose.axis));
    let search = TiltSearch::default();
    let Tilt::Clears {
        tilt,
        axis,
        cl,
        clearance,
    } = clearing_tilt(&a, &mesh, &pose, &Vec3::x(), &search).unwrap()
    else {
        panic!("no tilt clears");
    };
    println!(
        "clearing tilt {:.4} deg, clearance {clearance:.2e}",
        tilt.to_degrees()
    );
    assert!(clearance >= 0.0 && tilt > 0.0 && tilt < search.max_tilt);
    // Closed form: the wall's top edge (0, y, 60), at w = (-8, 0, 60) from the tip,
    // meets the bottom face of the holder cylinder (55 above the tip, radius 31.5)
    // when w . a = 55: -8 sin t + 60 cos t = 55, t = acos(55 / |w|) - atan(8 / 60)
    // (there rho = 25.3: on the face; the nose cone, radius 16 at most, is clear).
    let closed = (55.0 / 3664f64.sqrt()).acos() - (8.0f64 / 60.0).atan();
    assert!(
        tilt >= closed - 1e-9 && tilt - closed < search.tolerance,
        "{tilt} vs {closed}"
    );
    assert!((axis.norm() - 1.0).abs() < 1e-12 && axis.x > 0.0 && axis.y.abs() < 1e-12);
    assert_eq!(cl, pose.cl, "turned about the tip, the tip stays");
    assert!(
        !oracle_collides(&pose.cl, &axis),
        "tilt {tilt} still collides"
    );
    let less = tilt - 0.002;
    let less_axis = Vec3::new(less.sin(), 0.0, less.cos());
    assert!(
        oracle_collides(&pose.cl, &less_axis),
        "tilt {less} already clears"
    );
    // Tilting toward the wall never clears; a pose that clears needs none.
    assert_eq!(
        clearing_tilt(&a, &mesh, &pose, &-Vec3::x(), &search).unwrap(),
        Tilt::Fails
    );
    let far = Pose::vertical(Point3::new(60.0, 0.0, 0.0));
    assert_eq!(
        clearing_tilt(&a, &mesh, &far, &Vec3::x(), &search).unwrap(),
        Tilt::Clear
    );
}

/// Whether the tool at (8, 0, 0), tilted by `t` away from the wall, meets it at
/// stick-out `s` (closed form in the plane y = 0, where the pieces come nearest:
/// along the axis `a = (sin t, 0, cos t)` at height `h`, the point `rho` toward the
/// wall is `(8 + h sin t - rho cos t, h cos t + rho sin t)`, in the wall when
/// `rho > lo(h) = (8 + h sin t) / cos t` and `rho < hi(h) = (60 - h cos t) / sin t`).
/// The shank (radius 3 < 8) never reaches; the cone (radius `4 + 0.4 (h - s)` on
/// `[s, s + 30]`) and the cylinder above it (31.5, extended up the axis) do when
/// `lo` is below both their radius and `hi` somewhere: `lo` rises and `hi` falls
/// with `h`, so at the lowest cylinder height, and at the cone's highest height
/// below `h* = 60 cos t - 8 sin t` (where `lo = hi`).
fn tilted_collides(t: f64, s: f64) -> bool {
    let (sn, cs) = t.sin_cos();
    let lo = |h: f64| (8.0 + h * sn) / cs;
    let hi = |h: f64| (60.0 - h * cs) / sn;
    let h_star = 60.0 * cs - 8.0 * sn;
    let cylinder = s + 30.0 < h_star && lo(s + 30.0) < 31.5f64.min(hi(s + 30.0));
    let top = (s + 30.0).min(h_star);
    let cone = s < h_star && lo(top) < 4.0 + 0.4 * (top - s);
    cylinder || cone
}

#[test]
fn the_shortest_stick_out_covers_tilted_poses() {
    let (a, mesh) = (assembly(), mesh());
    let t = 5f64.to_radians();
    let tilted = Pose::new(Point3::new(8.0, 0.0, 0.0), Vec3::new(t.sin(), 0.0, t.cos())).unwrap();
    // A vertical pose far from the wall needs only the flute length.
    let poses = [Pose::vertical(Point3::new(60.0, 0.0, 0.0)), tilted];
    let dropper = MeshDropper::new(&mesh, &a.cutter);
    let mut views = Views::new(&mesh);
    let got = shortest_stick_out_posed(&a, &dropper, &mut views, &poses).unwrap();
    // The oracle's shortest stick-out by bisection on the closed form.
    let (mut lo, mut hi) = (12.0, 52.0);
    assert!(tilted_collides(t, lo) && !tilted_collides(t, hi));
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if tilted_collides(t, mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    println!(
        "tilted 5 degrees, 8 mm from the wall: shortest stick-out {got:?}, closed form {hi:.6}"
    );
    let StickOut::Clears { stick_out, pose } = got else {
        panic!("{got:?}");
    };
    assert_eq!(pose, Some(1));
    assert!((stick_out - hi).abs() < 1e-6, "{stick_out} vs {hi}");
    // Vertical at the same place it needs 50 (the cone meets the wall top at 8 from
    // the axis: 4 + 0.4 (60 - s) = 8).
    let upright = [Pose::vertical(Point3::new(8.0, 0.0, 0.0)), tilted];
    let got = shortest_stick_out_posed(&a, &dropper, &mut views, &upright).unwrap();
    let StickOut::Clears { stick_out, pose } = got else {
        panic!("{got:?}");
    };
    assert_eq!(pose, Some(0));
    assert!((stick_out - 50.0).abs() < 1e-6, "{stick_out}");
}
