//! Drop-and-spin on two planes (issue 13, "Two planes, closed form"): the shipped
//! wedges against the closed forms of the spin zone and the spin angle, derived from
//! the insert circle's distance to each plane (module doc of `swarf_fiveaxis::dsm`),
//! to 1e-9.

use swarf_fiveaxis::dsm::{Dsm, SpinSide};
use swarf_geom::Vec3;
use swarf_tool::Cutter;

const TOL: f64 = 1e-9;

fn dsm(part: &str, tool: &str) -> Dsm {
    let part = swarf_io::builtin_part(part).unwrap();
    let tool: Cutter = tool.parse().unwrap();
    Dsm::new(&part, [0, 1], &tool, Vec3::x()).unwrap()
}

/// `T1` and the ball limit `T2` for S1 falling at `b`, S2 rising at `g` (degrees),
/// insert-centre radius `big`, insert radius `r`.
fn zone_closed_form(b: f64, g: f64, big: f64, r: f64) -> (f64, f64) {
    let (b, g) = (b.to_radians(), g.to_radians());
    let sec = |x: f64| 1.0 / x.cos();
    let t1 = (big * (b.tan() - g.tan()) + r * (sec(b) - sec(g))) / (b.tan() + g.tan());
    let t2 = big + r * (g.cos() - b.cos()) / (b + g).sin();
    (t1, t2)
}

#[test]
fn the_edge_of_the_wedges_is_the_x_axis() {
    for part in ["wedge-symmetric", "wedge-30-45"] {
        let d = dsm(part, "bull:d=20,r=3,length=40");
        for s in [10.0, 50.0, 90.0] {
            let st = d.station(s).unwrap();
            assert!(
                (st.edge - swarf_geom::Point3::new(s, 0.0, 0.0)).norm() < TOL,
                "{st:?}"
            );
            assert!((st.across - Vec3::y()).norm() < 1e-12);
            assert!((st.tangent - Vec3::x()).norm() < 1e-6);
        }
    }
}

#[test]
fn the_zone_is_the_closed_form() {
    for (part, b, g) in [("wedge-symmetric", 30.0, 30.0), ("wedge-30-45", 30.0, 45.0)] {
        for (tool, big, r) in [
            ("bull:d=20,r=3,length=40", 7.0, 3.0),
            ("bull:d=16,r=5,length=40", 3.0, 5.0),
        ] {
            let d = dsm(part, tool);
            let st = d.station(50.0).unwrap();
            let z = d.zone(&st, 0).unwrap();
            let (t1, t2) = zone_closed_form(b, g, big, r);
            eprintln!(
                "{part} {tool}: T1 {} ({t1}), T2 ball {} ({t2}), T2 {} {:?}",
                z.t1, z.t2_ball, z.t2, z.binding
            );
            assert!((z.t1 - t1).abs() < TOL, "T1 {} vs {t1}", z.t1);
            assert!((z.t2_ball - t2).abs() < TOL, "T2 {} vs {t2}", z.t2_ball);
            assert!(z.t2 <= z.t2_ball + TOL);
        }
    }
}

/// The symmetric case: at `w = t R` the spin angle `a` solves
/// `2 sin b (1 - t) - sin b cos a + (1 - cos a) sin b cos 2b - sqrt(1 - c²) = 0`,
/// `c = cos b [cos a + (1 - cos a) cos 2b]`; both spins mirror each other.
#[test]
fn the_spin_angle_is_the_closed_form() {
    let d = dsm("wedge-symmetric", "bull:d=20,r=3,length=40");
    let st = d.station(50.0).unwrap();
    let (b, big) = (30f64.to_radians(), 7.0);
    let f = |t: f64, a: f64| {
        let c = b.cos() * (a.cos() + (1.0 - a.cos()) * (2.0 * b).cos());
        2.0 * b.sin() * (1.0 - t) - b.sin() * a.cos() + (1.0 - a.cos()) * b.sin() * (2.0 * b).cos()
            - (1.0 - c * c).sqrt()
    };
    for t in [0.1, 0.3, 0.5, 0.8] {
        // First root in (0, pi): scan, then bisect (independent of the solver).
        let mut lo = 0.0;
        let mut hi = 1e-3;
        while f(t, hi) < 0.0 {
            lo = hi;
            hi += 1e-3;
        }
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if f(t, m) < 0.0 { lo = m } else { hi = m }
        }
        let drop = d.drop_on(0, d.footprint(&st, 0, t * big)).unwrap();
        let plus = d.spin(&drop, SpinSide::Plus).unwrap();
        let minus = d.spin(&drop, SpinSide::Minus).unwrap();
        eprintln!(
            "t {t}: closed form {lo}, spins {} {}",
            plus.angle, minus.angle
        );
        assert!((plus.angle - lo).abs() < TOL, "{} vs {lo}", plus.angle);
        assert!((minus.angle + lo).abs() < TOL, "{} vs -{lo}", minus.angle);
        for s in [plus, minus] {
            assert!(s.clearance.abs() < 1e-9 && s.own_clearance > -1e-9, "{s:?}");
        }
    }
}
