//! Each named cutter equals its APT form, and both match the textbook closed forms.

mod common;

use common::{NAMED, cutter, spherical};
use swarf_geom::Point3;
use swarf_tool::{Apt, Cutter, Pose};

const TOL: f64 = 1e-12;

fn close(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(x), Some(y)) => (x - y).abs() <= TOL,
        (None, None) => true,
        _ => false,
    }
}

#[test]
fn named_profiles_equal_their_apt_profiles() {
    for spec in NAMED {
        let named = cutter(spec);
        let apt = named.to_apt();
        let general = Cutter::Apt(apt);
        // The APT construction derives e and f from d alone; they match the table.
        let derived = Apt::from_corner(apt.d, apt.r, apt.alpha, apt.beta, apt.h).unwrap();
        assert!(
            (derived.e - apt.e).abs() < TOL && (derived.f - apt.f).abs() < TOL,
            "{spec}"
        );
        assert!((named.radius() - general.radius()).abs() < TOL, "{spec}");
        assert_eq!(named.length(), general.length(), "{spec}");
        let (p, q) = (named.profile(), general.profile());
        let r = named.radius();
        for k in 0..=2000 {
            let rho = r * 1.02 * k as f64 / 2000.0;
            let (a, b) = (p.height_at_radius(rho), q.height_at_radius(rho));
            assert!(
                close(a, b),
                "{spec}: height_at_radius({rho}) {a:?} vs {b:?}"
            );
        }
        let h = named.length();
        for k in 0..=2000 {
            let z = -0.5 + (h + 1.0) * k as f64 / 2000.0;
            let (a, b) = (p.radius_at_height(z), q.radius_at_height(z));
            assert!(close(a, b), "{spec}: radius_at_height({z}) {a:?} vs {b:?}");
        }
        let pose = Pose::new(Point3::new(1.0, -2.0, 3.0), spherical(0.7, 2.0)).unwrap();
        for k in 0..3000 {
            // A deterministic spread of points around the tool.
            let t = k as f64;
            let p3 = pose.cl
                + (1.3 * r + 1.0)
                    * spherical(1.0 + (t * 0.7).sin() * 2.0, t * 2.399)
                    * (0.05 + (t * 0.37).sin().abs())
                + (h * (t * 0.113).sin().abs()) * pose.axis;
            let (a, b) = (p.signed_distance(&pose, &p3), q.signed_distance(&pose, &p3));
            assert!(
                (a - b).abs() <= TOL,
                "{spec}: signed_distance at {p3}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn heights_match_textbook_closed_forms() {
    let ball = cutter("ball:d=8");
    for k in 0..=400 {
        let rho = 4.0 * k as f64 / 400.0;
        let expected = 4.0 - (16.0 - rho * rho).sqrt();
        assert!((ball.height_at_radius(rho).unwrap() - expected).abs() < TOL);
    }
    let (big_r, c) = (5.0, 2.0);
    let bull = cutter("bull:d=10,r=2");
    for k in 0..=400 {
        let rho = big_r * k as f64 / 400.0;
        let expected = if rho <= big_r - c {
            0.0
        } else {
            c - (c * c - (rho - (big_r - c)).powi(2)).sqrt()
        };
        assert!((bull.height_at_radius(rho).unwrap() - expected).abs() < TOL);
        // The inverse on the corner: radius at that height.
        if rho > big_r - c && expected < c {
            assert!((bull.radius_at_height(expected).unwrap() - rho).abs() < 1e-9);
        }
    }
    let half = 20f64.to_radians();
    let cone = cutter("cone:d=10,angle=40");
    for k in 0..=400 {
        let rho = 5.0 * k as f64 / 400.0;
        assert!((cone.height_at_radius(rho).unwrap() - rho / half.tan()).abs() < 1e-11);
        let z = 5.0 / half.tan() * k as f64 / 400.0;
        assert!((cone.radius_at_height(z).unwrap() - z * half.tan()).abs() < 1e-11);
    }
    let flat = cutter("flat:d=6");
    assert_eq!(flat.height_at_radius(3.0), Some(0.0));
    assert_eq!(flat.height_at_radius(3.0 + 1e-12), None);
    assert_eq!(flat.radius_at_height(0.0), Some(3.0));
    let (t, b) = (1.0, 10f64.to_radians());
    let taper = cutter("taperball:d=6,angle=10,tip=1");
    for k in 0..=400 {
        let rho = taper.radius() * k as f64 / 400.0;
        let expected = if rho <= t * b.cos() {
            t - (t * t - rho * rho).sqrt()
        } else {
            t * (1.0 - b.sin()) + (rho - t * b.cos()) / b.tan()
        };
        assert!((taper.height_at_radius(rho).unwrap() - expected).abs() < 1e-11);
    }
}

#[test]
fn undercut_apt_has_its_widest_point_on_the_corner() {
    let c = cutter("apt:d=10,r=1,alpha=5,beta=-10,h=8");
    let a = c.to_apt();
    assert!((c.radius() - (a.e + a.r)).abs() < TOL);
    // Lowest height at the widest radius is the corner's equator, not the side line.
    assert!((c.height_at_radius(a.e + a.r).unwrap() - a.f).abs() < 1e-9);
    // Above the corner the cross-section narrows along the side line.
    let t2 = a.side_start();
    let z = 0.5 * (t2.z + a.h);
    let expected = t2.rho - (z - t2.z) * 10f64.to_radians().tan();
    assert!((c.radius_at_height(z).unwrap() - expected).abs() < 1e-12);
}
