//! Issue 19, "Prove it": a deep narrow pocket where the holder must collide at the
//! default stick-out. The check finds the collisions at the poses deep in the
//! pocket and nowhere else; the stick-out it reports clears, and 0.01 mm less does
//! not, judged by a brute-force oracle that shares no code with the check: points
//! sampled densely on the shank and holder surfaces (circles at many heights, and the
//! pieces' bottom discs), from the radius of the assembly written here in closed
//! form, tested against the part written as a closed-form solid (the block below
//! z = 40, the pocket x in (25, 35), y in (10, 50) cut down to z = 0;
//! `parts/README.md`).

use swarf_geom::Point3;
use swarf_tool::Cutter;
use swarf_tool::drop::MeshDropper;
use swarf_tool::holder::vertical::{HolderReport, StickOut, check_vertical};
use swarf_tool::holder::{Assembly, PieceKind, StackSegment};

/// The test tool: ball d = 6 with 12 mm of flutes; shank a cone 5 -> 6 over 8, then
/// d = 6 (tool 60 long); holder a nose cone 8 -> 32 over 30, then d = 63 over 30.
fn assembly(stick_out: f64, shank_top: f64) -> Assembly {
    Assembly {
        cutter: Cutter::ball(6.0, Some(12.0)).unwrap(),
        shank: vec![
            StackSegment::Cone {
                d0: 5.0,
                d1: 6.0,
                length: 8.0,
            },
            StackSegment::Cylinder {
                d: 6.0,
                length: shank_top,
            },
        ],
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
        stick_out,
    }
}

/// Closed form: the nose cone's radius reaches the pocket's half width 5 at 2.5 mm
/// above its bottom (radius 4 + 0.4 t), so its bottom may dip to z = 37.5.
const NOSE_FLOOR: f64 = 37.5;

/// Radius of the shank and holder at height `h` above the tip (oracle, closed form);
/// `None` below the shank or above the holder.
fn radius(h: f64, stick_out: f64) -> Option<f64> {
    if h < 12.0 {
        None
    } else if h < 20.0 && h < stick_out {
        Some(2.5 + (h - 12.0) / 16.0)
    } else if h < stick_out {
        Some(3.0)
    } else if h < stick_out + 30.0 {
        Some(4.0 + 0.4 * (h - stick_out))
    } else if h <= stick_out + 60.0 {
        Some(31.5)
    } else {
        None
    }
}

/// The part as a closed-form solid: strictly inside the material, by more than
/// 1e-9 mm.
fn in_material(p: &Point3) -> bool {
    let e = 1e-9;
    let in_block = p.x > e && p.x < 60.0 - e && p.y > e && p.y < 60.0 - e;
    let in_pocket = p.x > 25.0 - e && p.x < 35.0 + e && p.y > 10.0 - e && p.y < 50.0 + e;
    in_block && p.z < 40.0 - e && !(in_pocket && p.z >= -e)
}

/// Brute force: does any sampled point of the shank or holder lie in the part?
fn oracle_collides(cl: &Point3, stick_out: f64) -> bool {
    const ANGLES: usize = 720;
    let dirs: Vec<(f64, f64)> = (0..ANGLES)
        .map(|i| (std::f64::consts::TAU * i as f64 / ANGLES as f64).sin_cos())
        .collect();
    let at = |rho: f64, h: f64, (s, c): (f64, f64)| {
        Point3::new(cl.x + rho * c, cl.y + rho * s, cl.z + h)
    };
    // Side surfaces: circles every 0.002 mm of height.
    let steps = ((stick_out + 60.0 - 12.0) / 0.002) as usize;
    for k in 0..=steps {
        let h = 12.0 + 0.002 * k as f64;
        let Some(r) = radius(h, stick_out) else {
            continue;
        };
        if dirs.iter().any(|&d| in_material(&at(r, h, d))) {
            return true;
        }
    }
    // Bottom discs of the shank (h = 12) and of the holder (h = stick-out), and the
    // step under the holder's cylinder.
    for (h, r0, r1) in [
        (12.0, 0.0, 2.5),
        (stick_out, 0.0, 4.0),
        (stick_out + 30.0, 16.0, 31.5),
    ] {
        let n = ((r1 - r0) / 0.01) as usize;
        for k in 0..=n {
            let rho = r0 + (r1 - r0) * k as f64 / n as f64;
            if dirs.iter().any(|&d| in_material(&at(rho, h, d))) {
                return true;
            }
        }
    }
    false
}

/// The path: the pocket's centre line y = 15 ..= 45 at tip heights 40 (entering), 30,
/// 20, 10 and 0 (floor), then back out over the top at x = 10.
fn path() -> Vec<Point3> {
    let mut cls = Vec::new();
    for z in [40.0, 30.0, 20.0, 10.0, 0.0] {
        for i in 0..=30 {
            cls.push(Point3::new(30.0, 15.0 + f64::from(i), z));
        }
    }
    for i in 0..=10 {
        cls.push(Point3::new(10.0, 5.0 + 5.0 * f64::from(i), 40.0));
    }
    cls
}

fn report(a: &Assembly, cls: &[Point3]) -> HolderReport {
    let mesh = swarf_io::builtin_mesh("deep-pocket").unwrap();
    let dropper = MeshDropper::new(&mesh, &a.cutter);
    check_vertical(a, &dropper, cls).unwrap()
}

#[test]
fn collisions_at_the_default_stick_out_are_the_deep_poses() {
    let cls = path();
    let r = report(&assembly(25.0, 40.0), &cls);
    // Closed form: the nose's bottom at z + 25 must stay at or above 37.5: the poses
    // at z = 10 (2.5 mm in) and z = 0 (12.5 mm in) collide, nothing else.
    assert_eq!(r.collisions.len(), 62);
    for c in &r.collisions {
        assert!(c.cl.z <= 10.0 && c.cl.x == 30.0, "{c:?}");
        assert!(
            (c.depth - (NOSE_FLOOR - 25.0 - c.cl.z)).abs() < 1e-9,
            "{c:?}"
        );
        assert_eq!(c.piece, PieceKind::Holder(0));
        // Lowered onto the part, the nose touches the rim of the pocket.
        assert!((c.contact.z - 40.0).abs() < 1e-9, "{c:?}");
        let on = |v: f64, w: f64| (v - w).abs() < 1e-9;
        let p = c.contact;
        assert!(
            on(p.x, 25.0) || on(p.x, 35.0) || on(p.y, 10.0) || on(p.y, 50.0),
            "{c:?}"
        );
    }
    let worst = r.min_clearance.unwrap();
    assert!((worst.1 + 12.5).abs() < 1e-9, "{worst:?}");
    // The oracle agrees on every pose of two rows and on the top.
    for (i, cl) in cls.iter().enumerate().filter(|(i, _)| i % 31 == 3) {
        let hit = r.collisions.iter().any(|c| c.pose == i);
        assert_eq!(oracle_collides(cl, 25.0), hit, "pose {i} at {cl:?}");
    }
    let e = r.require_clear().unwrap_err().to_string();
    assert!(
        e.contains("collides at 62 of 166 poses at stick-out 25 mm")
            && e.contains("holder[0] 2.500 mm into the part")
            && e.contains("a stick-out of at least 37.500 mm clears every pose"),
        "{e}"
    );
}

#[test]
fn the_reported_stick_out_clears_and_a_hundredth_less_does_not() {
    let cls = path();
    let r = report(&assembly(25.0, 40.0), &cls);
    let StickOut::Clears {
        stick_out,
        pose: Some(pose),
    } = r.shortest
    else {
        panic!("{:?}", r.shortest);
    };
    println!("shortest stick-out {stick_out} (closed form {NOSE_FLOOR}) set by pose {pose}");
    assert!((stick_out - NOSE_FLOOR).abs() < 1e-9);
    assert_eq!(cls[pose].z, 0.0);
    // The check itself at that stick-out and 0.01 less.
    assert!(
        report(&assembly(stick_out, 40.0), &cls)
            .collisions
            .is_empty()
    );
    let short = report(&assembly(stick_out - 0.01, 40.0), &cls);
    assert_eq!(short.collisions.len(), 31);
    // The brute-force oracle at the floor poses.
    for cl in cls.iter().filter(|p| p.z == 0.0).step_by(10) {
        assert!(!oracle_collides(cl, stick_out), "{cl:?} at {stick_out}");
        assert!(oracle_collides(cl, stick_out - 0.01), "{cl:?}");
    }
}

#[test]
fn a_shank_against_the_wall_means_no_stick_out_clears() {
    // Off centre at x = 27: the shank's cone (radius 2.5 at 12 above the tip) reaches
    // x = 24.5, into the wall, whatever the stick-out.
    let cls = [Point3::new(27.0, 30.0, 5.0)];
    let r = report(&assembly(25.0, 40.0), &cls);
    let StickOut::ShankCollides { collision, .. } = r.shortest else {
        panic!("{:?}", r.shortest);
    };
    assert_eq!(collision.piece, PieceKind::Shank(0));
    assert!((collision.depth - 23.0).abs() < 1e-9, "{collision:?}");
    let e = r.require_clear().unwrap_err().to_string();
    assert!(e.contains("no stick-out clears"), "{e}");
    assert!(oracle_collides(&cls[0], 60.0));
}

#[test]
fn a_holder_colliding_everywhere_names_the_stick_out_needed() {
    // Every pose on the floor, and a tool only 32 long: 37.5 is needed.
    let cls: Vec<Point3> = (0..5)
        .map(|i| Point3::new(30.0, 20.0 + 5.0 * f64::from(i), 0.0))
        .collect();
    let r = report(&assembly(25.0, 12.0), &cls);
    assert_eq!(r.collisions.len(), 5);
    assert_eq!(
        r.shortest,
        StickOut::TooLong {
            stick_out: NOSE_FLOOR,
            tool_length: 32.0
        }
    );
    let e = r.require_clear().unwrap_err().to_string();
    assert!(e.contains("collides at 5 of 5 poses"), "{e}");
    assert!(
        e.contains("clearing needs a stick-out of 37.500 mm but the tool is only 32.000 mm long"),
        "{e}"
    );
}
