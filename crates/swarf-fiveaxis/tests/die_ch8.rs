//! Thesis 000 ch. 8 on die.toml (its eq. 6.1): the inclined tool at alpha = 3 and 6
//! degrees and the automatic gouge-free lead, with a toroidal cutter R = 12.7, r = 6.35
//! (`bull:d=38.1,r=6.35`), feed 60 degrees off X, cross feed 3.5 mm. To keep the test
//! fast it runs five iso-planar passes across the part (cross feed 7 mm, steps of
//! about 2 mm); `examples/die_ch8.rs` runs the full experiment. Gouges found by
//! sectioning are confirmed by a dense independent check (the tool's signed distance
//! to design points), and the automatic method's result is checked gouge-free by the
//! same independent check.

use swarf_fiveaxis::job::planned_cc_paths;
use swarf_fiveaxis::positioning::{Positioning, position};
use swarf_geom::{Part, Point3};
use swarf_path::{Contact, Job, Pass};
use swarf_tool::Cutter;

fn die() -> Part {
    swarf_io::builtin_part("die").expect("the built-in die part loads")
}

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
    assert!(ra.worst_depth <= tol);
    assert!(ra.alpha_range_deg[1] > 6.0 && ra.alpha_range_deg[1] < 25.0);
    // Normal penetration is at most the vertical depth: within the tolerance, plus
    // what 1 mm sections can miss between two planes (depth falling off as the square
    // of the offset, at most 0.5 mm, times half the design's curvature, 0.007 / mm:
    // under 2 micrometres).
    let pen = penetration(&part, &cutter, &pa, 1);
    assert!(pen <= tol + 0.002, "independent check: {pen} mm");
}

/// CC paths on the die: iso-planar at `angle` degrees off X, a fixed cross feed of
/// `stepover` mm and the chordal tolerance `tol` mm, for `tool`.
fn die_cc(part: &Part, tool: &str, angle: f64, stepover: f64, tol: f64) -> Vec<Vec<Contact>> {
    let text = format!(
        "part = \"builtin:die\"\ntool = \"{tool}\"\n[strategy]\nkind = \"iso-planar\"\n\
         stepover = {stepover}\ntolerance = {tol}\nangle = {angle}\n"
    );
    let job = Job::parse(&text, "die job").expect("job");
    planned_cc_paths(&job, part).expect("CC paths")
}
