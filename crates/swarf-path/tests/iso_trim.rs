//! Iso strategies on a trimmed face (issue 18): a bicubic B-spline bump 60 x 60 mm
//! whose face has a corner cut off and a circular hole of radius 0.2 in uv (about
//! 12 mm). Checked with the same independent oracles as the untrimmed parts
//! (iso_support): every CC point lies on the face and none in the hole, passes that
//! meet the hole are split at it, the true scallop left by the swept balls stays
//! within h on a dense grid of face points (the trim boundary included: boundary
//! passes run along the trimming loops), and no CL pose enters the face by more than
//! the tolerance.

mod iso_support;

use iso_support::swept::{Swept, residuals};
use iso_support::{
    IsoJob, dense_face_frames, dense_points, iso_job, max_penetration, max_residual,
};
use swarf_geom::part::Face;
use swarf_geom::trim::Trim;
use swarf_geom::{Part, Patch, Point3};

const H: f64 = 0.15;
const TOL: f64 = 0.01;
/// The oracle's allowance over h, as in iso_wave.rs.
const SLACK: f64 = 1.02;
const HOLE: [f64; 2] = [0.45, 0.5];
const HOLE_R: f64 = 0.2;
/// Points on the hole's polygon.
const HOLE_N: usize = 96;

/// A 5 x 5 bicubic B-spline over 60 x 60 mm with a bump of 10 mm in the middle.
fn bump() -> Patch {
    let mut pts = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            let (x, y) = (15.0 * i as f64, 15.0 * j as f64);
            let d2 = (x - 30.0).powi(2) + (y - 30.0).powi(2);
            pts.push(Point3::new(x, y, 10.0 * (-d2 / 400.0).exp()));
        }
    }
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    Patch::new([3, 3], pts, [Some(knots.clone()), Some(knots)], None).unwrap()
}

fn trimmed() -> Part {
    let m = 0.02;
    let outer = vec![
        [m, m],
        [1.0 - m, m],
        [1.0 - m, 0.7],
        [0.7, 1.0 - m],
        [m, 1.0 - m],
    ];
    let n = HOLE_N;
    let hole = (0..n)
        .map(|k| {
            let a = -std::f64::consts::TAU * k as f64 / n as f64;
            [HOLE[0] + HOLE_R * a.cos(), HOLE[1] + HOLE_R * a.sin()]
        })
        .collect();
    let mut part = Part::new("trimmed bump", vec![bump()]);
    part.faces = vec![Face {
        name: Some("bump".into()),
        surface: None,
        trim: Some(Trim::new(vec![outer, hole]).unwrap()),
    }];
    part
}

fn job(kind: &str, tool: &str) -> IsoJob {
    iso_job(kind, tool, &format!("scallop = {H}\ntolerance = {TOL}\n"))
}

/// Distance in uv from `uv` to the nearest trimming loop.
fn loop_distance(part: &Part, uv: [f64; 2]) -> f64 {
    let mut d = f64::INFINITY;
    for l in part.trim(0).unwrap().loops() {
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            let ab = [b[0] - a[0], b[1] - a[1]];
            let t = (((uv[0] - a[0]) * ab[0] + (uv[1] - a[1]) * ab[1])
                / (ab[0] * ab[0] + ab[1] * ab[1]))
                .clamp(0.0, 1.0);
            d = d.min((uv[0] - a[0] - t * ab[0]).hypot(uv[1] - a[1] - t * ab[1]));
        }
    }
    d
}

fn hole_distance(uv: [f64; 2]) -> f64 {
    (uv[0] - HOLE[0]).hypot(uv[1] - HOLE[1])
}

#[test]
fn iso_paths_stay_on_the_trimmed_face_and_meet_h_without_gouging() {
    let part = trimmed();
    let points = dense_points(&part, 0.3);
    let inscribed = HOLE_R * (std::f64::consts::PI / HOLE_N as f64).cos();
    for kind in ["iso-parametric", "iso-planar", "iso-scallop"] {
        let job = job(kind, "ball:d=8");
        let plan = job.plan(&part).unwrap();
        let mut near_hole = 0;
        for pass in &plan.toolpath.passes {
            let cc: Vec<[f64; 2]> = pass
                .points
                .iter()
                .filter_map(|p| p.contact)
                .map(|c| c.uv)
                .collect();
            for uv in &cc {
                // On the face, or on a trimming loop (boundary passes run along them).
                assert!(
                    part.face_contains(0, uv[0], uv[1]) || loop_distance(&part, *uv) < 1e-9,
                    "{kind}: CC {uv:?} off the face"
                );
                assert!(
                    hole_distance(*uv) >= inscribed - 1e-9,
                    "{kind}: CC {uv:?} in the hole"
                );
                if hole_distance(*uv) < HOLE_R + 0.005 {
                    near_hole += 1;
                }
            }
            // No step of a pass crosses the hole: passes meeting it are split.
            // (Bridging links between pieces carry no contact and are not steps.)
            for w in pass.points.windows(2) {
                let (Some(a), Some(b)) = (w[0].contact, w[1].contact) else {
                    continue;
                };
                let w = [a.uv, b.uv];
                let mid = [0.5 * (w[0][0] + w[1][0]), 0.5 * (w[0][1] + w[1][1])];
                assert!(
                    hole_distance(mid) > HOLE_R - 0.01,
                    "{kind}: step {w:?} over the hole"
                );
            }
        }
        assert!(
            near_hole > 10,
            "{kind}: only {near_hole} CC points at the hole's edge"
        );
        let (left, at) = max_residual(&plan, &part, 4.0, 0.5);
        let depth = max_penetration(&plan, &job.tool, &points);
        println!(
            "{kind}: {} passes, max scallop {left:.4} mm (h {H}), max gouge {depth:.5} mm",
            plan.toolpath.passes.len()
        );
        assert!(left <= SLACK * H, "{kind}: {left} left at {at:?}");
        assert!(depth <= TOL, "{kind}: enters by {depth} mm");
    }
}

/// Iso-scallop with a bull end mill: the true scallop of the swept tools
/// (`iso_support::swept`) on the face's points, and no gouge.
#[test]
fn iso_scallop_with_a_bull_meets_h_on_the_trimmed_face() {
    let part = trimmed();
    let job = job("iso-scallop", "bull:d=10,r=2");
    let plan = job.plan(&part).unwrap();
    let swept = Swept::new(&plan, &job.tool);
    let frames = dense_face_frames(&part, 0.6);
    let left = residuals(&swept, &frames).into_iter().fold(0.0, f64::max);
    let points = dense_points(&part, 0.3);
    let depth = max_penetration(&plan, &job.tool, &points);
    println!(
        "iso-scallop bull d=10 r=2: max scallop {left:.4} mm (h {H}), max gouge {depth:.5} mm"
    );
    assert!(left <= SLACK * H, "bull: {left} left");
    assert!(depth <= TOL, "bull: enters by {depth} mm");
    for c in plan
        .toolpath
        .passes
        .iter()
        .flat_map(|p| &p.points)
        .filter_map(|p| p.contact)
    {
        let uv = c.uv;
        assert!(
            hole_distance(uv) > HOLE_R - 1e-3,
            "bull: CC {uv:?} in the hole"
        );
    }
}

/// The oracle sees what the trim takes away: the same plans on the whole patch leave
/// far more than h in the trimmed-off corner and the hole.
#[test]
fn the_scallop_oracle_sees_the_trimmed_off_region() {
    let part = trimmed();
    let whole = Part::new("bump", vec![bump()]);
    let job = job("iso-parametric", "ball:d=8");
    let plan = job.plan(&part).unwrap();
    let (left, _) = max_residual(&plan, &whole, 4.0, 1.0);
    assert!(left > 10.0 * H, "{left}");
}
