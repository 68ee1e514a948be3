//! Thesis 000 ch. 8 on die.toml (its eq. 6.1): the inclined tool at alpha = 3 and 6
//! degrees and the automatic gouge-free lead, with a toroidal cutter R = 12.7, r = 6.35
//! (`bull:d=38.1,r=6.35`), feed 60 degrees off X, cross feed 3.5 mm. To keep the test
//! fast it runs five iso-planar passes across the part (cross feed 7 mm, steps of
//! about 2 mm); `examples/die_ch8.rs` runs the full experiment. Gouges found by
//! sectioning are confirmed by a dense independent check (the tool's signed distance
//! to design points), and the automatic method's result is checked gouge-free by the
//! same independent check.

use swarf_fiveaxis::lead_bound::lead_bound;
use swarf_fiveaxis::positioning::{Positioning, position};
use swarf_geom::{Part, Point3, Vec3};
use swarf_testkit::die_cc;
use swarf_testkit::parts::die;
use swarf_tool::Cutter;
use swarf_toolpath::{Contact, Pass};

fn cc(part: &Part) -> Vec<Vec<Contact>> {
    let all = die_cc(part, "bull:d=38.1,r=6.35", 60.0, 7.0, 0.005);
    // Five passes across the part, the last one along the corner at (-4.9, -103.2).
    let n = all.len();
    [1, n / 4, n / 2, 3 * n / 4, n - 2]
        .iter()
        .map(|&k| all[k].clone())
        .collect()
}

/// Deepest penetration of the tool into the design along the normal (minus the
/// signed distance of design points on a dense grid), over the given poses.
fn penetration(part: &Part, cutter: &Cutter, passes: &[Pass], every: usize) -> f64 {
    let profile = cutter.profile();
    let patch = &part.patches[0];
    let pts: Vec<Point3> = (0..=300)
        .flat_map(|i| (0..=300).map(move |j| (i, j)))
        .map(|(i, j)| patch.eval(i as f64 / 300.0, j as f64 / 300.0))
        .collect();
    let mut worst = f64::NEG_INFINITY;
    for pass in passes {
        for p in pass.points.iter().step_by(every) {
            let r = cutter.radius() + 1.0;
            for q in &pts {
                if (q - p.pose.cl).norm() < r + 20.0 {
                    worst = worst.max(-profile.signed_distance(&p.pose, q));
                }
            }
        }
    }
    worst
}

#[test]
fn fixed_leads_gouge_and_the_automatic_lead_does_not() {
    let part = die();
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
    let cc = cc(&part);
    let tol = 0.01;
    let fixed = |alpha: f64| {
        let p = Positioning::Inclined {
            alpha,
            tilt: 0.0,
            sections: 1.0,
        };
        position(&cutter, &part, &cc, &p, tol).unwrap()
    };
    let (p3, r3) = fixed(3.0);
    assert!(
        r3.gouging_poses > r3.poses / 2,
        "{} of {}",
        r3.gouging_poses,
        r3.poses
    );
    assert!(r3.worst_depth > 1.0, "{}", r3.worst_depth);
    assert!(penetration(&part, &cutter, &p3, 5) > 1.0);
    let (_, r6) = fixed(6.0);
    assert!(r6.gouging_poses < r3.gouging_poses && r6.worst_depth < r3.worst_depth);
    let auto = Positioning::GougeFree {
        max_alpha: 25.0,
        sections: 1.0,
        tilt: 0.0,
        max_rate: 0.5,
        tolerance: None,
    };
    let (pa, ra) = position(&cutter, &part, &cc, &auto, tol).unwrap();
    assert_eq!(ra.gouging_poses, 0);
    // The least lead from the curvature along the feed: the same for every method on
    // these passes, above both fixed leads (which gouge), and below the automatic
    // lead's largest, less what the tolerance lets the back insert sink: 2 R cos(alpha)
    // d_alpha <= tol, d_alpha <= 0.01 / (25.4 * 0.97) rad = 0.023 degrees.
    let bound = r3.local_lead_bound_deg.expect("a bound for the bull");
    assert_eq!(r6.local_lead_bound_deg, Some(bound));
    assert_eq!(ra.local_lead_bound_deg, Some(bound));
    assert!(bound > 6.0 && bound < 13.0, "{bound}");
    assert_eq!(ra.local_lead_unfit, 0);
    assert!(
        ra.alpha_range_deg[1] >= bound - 0.025,
        "automatic {} < bound {bound}",
        ra.alpha_range_deg[1]
    );
    assert!(ra.worst_depth <= tol);
    assert!(ra.alpha_range_deg[1] > 6.0 && ra.alpha_range_deg[1] < 25.0);
    // Normal penetration is at most the vertical depth: within the tolerance, plus
    // what 1 mm sections can miss between two planes (depth falling off as the square
    // of the offset, at most 0.5 mm, times half the design's curvature, 0.007 / mm:
    // under 2 micrometres).
    let pen = penetration(&part, &cutter, &pa, 1);
    assert!(pen <= tol + 0.002, "independent check: {pen} mm");
}
/// Thesis 000 eq. 6.1 in closed form.
fn die_closed_form(u: f64, v: f64) -> Vec3 {
    Vec3::new(
        -99.4 + 88.9 * v + 5.6 * v * v,
        -131.3 * u + 28.1 * u * u,
        5.9 * (u * u * v * v + u * u * v) - 3.9 * v * v * u + 76.2 * u * u + 6.7 * v * v
            - 27.3 * u * v
            - 50.8 * u
            + 25.0 * v
            + 12.1,
    )
}

/// The normal curvature of eq. 6.1 at `(u, v)` along the tangent whose XY projection
/// is at `angle` from X (the direction of an iso-planar pass's drive plane), positive
/// when concave seen from above: derivatives by central differences of the closed form
/// (exact up to rounding for a biquadratic), `II / I` of that tangent.
fn closed_form_curvature(u: f64, v: f64, angle: f64) -> f64 {
    let h = 1e-3;
    let s = die_closed_form;
    let su = (s(u + h, v) - s(u - h, v)) / (2.0 * h);
    let sv = (s(u, v + h) - s(u, v - h)) / (2.0 * h);
    let suu = (s(u + h, v) - 2.0 * s(u, v) + s(u - h, v)) / (h * h);
    let svv = (s(u, v + h) - 2.0 * s(u, v) + s(u, v - h)) / (h * h);
    let suv =
        (s(u + h, v + h) - s(u + h, v - h) - s(u - h, v + h) + s(u - h, v - h)) / (4.0 * h * h);
    let mut n = su.cross(&sv).normalize();
    if n.z < 0.0 {
        n = -n;
    }
    let (sa, ca) = angle.sin_cos();
    let det = su.x * sv.y - su.y * sv.x;
    let a = (ca * sv.y - sa * sv.x) / det;
    let b = (su.x * sa - su.y * ca) / det;
    let t = a * su + b * sv;
    (a * a * suu.dot(&n) + 2.0 * a * b * suv.dot(&n) + b * b * svv.dot(&n)) / t.norm_squared()
}

/// The least lead of the demo's die job (bull R = 12.7, r = 6.35, 60 degrees off X,
/// cross feed 3.5 mm, tolerance 0.01 mm) from the design's curvature along the feed:
/// [`lead_bound`] on its CC paths agrees with the same bound recomputed from the closed
/// form at every CC point, and with the maximum over the whole surface (12.97 degrees
/// at u = 0.68, v = 1, on the edge x = -4.9, where the die is concave along the feed
/// with radius 62.9 mm).
#[test]
fn least_lead_on_the_demo_die_job_matches_the_closed_form() {
    let part = die();
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
    let cc = die_cc(&part, "bull:d=38.1,r=6.35", 60.0, 3.5, 0.01);
    let b = lead_bound(&cutter, &part, &cc).expect("a bound");
    let least = |k: f64| (12.7 / (1.0 / k - 6.35)).asin().to_degrees();
    let angle = 60f64.to_radians();
    let mut worst = (f64::NEG_INFINITY, [0, 0]);
    for (k, pass) in cc.iter().enumerate() {
        for (i, c) in pass.iter().enumerate() {
            let curv = closed_form_curvature(c.uv[0], c.uv[1], angle);
            if curv > worst.0 {
                worst = (curv, [k, i]);
            }
        }
    }
    let ours = b.lead.to_degrees();
    assert_eq!(b.at_index, worst.1);
    assert!(
        (ours - least(worst.0)).abs() < 0.01,
        "{ours} vs {}",
        least(worst.0)
    );
    assert_eq!((b.unfit, b.points), (0, 1498));
    let mut top = (f64::NEG_INFINITY, Vec3::zeros());
    for i in 0..=1000 {
        for j in 0..=100 {
            let (u, v) = (i as f64 / 1000.0, j as f64 / 100.0);
            let curv = closed_form_curvature(u, v, angle);
            if curv > top.0 {
                top = (curv, die_closed_form(u, v));
            }
        }
    }
    let surface = least(top.0);
    assert!((surface - 12.97).abs() < 0.05, "{surface}");
    assert!((1.0 / top.0 - 62.9).abs() < 0.1, "{}", 1.0 / top.0);
    assert!((top.1.xy() - Vec3::new(-4.9, -76.3, 0.0).xy()).norm() < 0.5);
    assert!(ours <= surface + 1e-3 && ours > surface - 0.05, "{ours}");
    assert!((b.at.coords.xy() - top.1.xy()).norm() < 3.6, "{}", b.at);
}
