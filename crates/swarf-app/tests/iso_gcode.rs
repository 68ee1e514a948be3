//! The shipped example jobs (`jobs/wave-iso-*.toml`, paper 004's experiment): their
//! G-code is accepted by LinuxCNC's interpreter `rs274 -g` without error, and the moves
//! it executes pass through every pose of the CSV output, in order, to the printed
//! precision (4 decimals in the G-code, 6 in the CSV). Without `rs274` the check is
//! skipped, unless `SWARF_REQUIRE_REFERENCES=1`.

use std::path::{Path, PathBuf};
use swarf_app::{Job, PlanInput};
use swarf_nc::{GcodeOptions, Units};
use swarf_testkit::rs274::run_rs274;

fn job_path(kind: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../jobs/wave-{kind}.toml"))
}

/// `rs274 -g` on a program: exit status and everything it printed; `None` when it is
/// not installed.
fn rs274(program: &str, name: &str) -> Option<(bool, String)> {
    run_rs274(program, name).map(|out| (out.success, out.text("\n")))
}

/// End points of the interpreter's straight moves, with `true` for cutting feeds
/// (feed moves at `feed`).
fn canon_moves(text: &str, feed: f64) -> Vec<([f64; 3], bool)> {
    let mut rate = 0.0;
    let mut out = Vec::new();
    for line in text.lines() {
        let Some(call) = line.split("N..... ").nth(1) else {
            continue;
        };
        let args = || -> Vec<f64> {
            let inner = &call[call.find('(').unwrap() + 1..call.rfind(')').unwrap()];
            inner
                .split(',')
                .map(|a| a.trim().parse().unwrap())
                .collect()
        };
        if call.starts_with("SET_FEED_RATE") {
            rate = args()[0];
        } else if call.starts_with("STRAIGHT_TRAVERSE") {
            let a = args();
            out.push(([a[0], a[1], a[2]], false));
        } else if call.starts_with("STRAIGHT_FEED") {
            let a = args();
            out.push(([a[0], a[1], a[2]], rate == feed));
        } else if call.starts_with("ARC_FEED") {
            panic!("the iso strategies write straight moves only: {call}");
        }
    }
    out
}

/// Poses of the CSV output (comment lines `# ...` skipped).
fn csv_poses(text: &str) -> Vec<[f64; 3]> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,i,j,k"));
    lines
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(&v[3..], &[0.0, 0.0, 1.0]);
            [v[0], v[1], v[2]]
        })
        .collect()
}

#[test]
fn example_jobs_run_in_rs274_and_reproduce_the_csv() {
    for kind in ["iso-parametric", "iso-planar", "iso-scallop"] {
        let path = job_path(kind);
        let text = std::fs::read_to_string(&path).unwrap();
        let job = Job::parse(&text, &path.display().to_string()).unwrap();
        assert_eq!(job.part, "builtin:wave");
        assert_eq!(job.tool.to_string(), "ball:d=8");
        assert_eq!(job.strategy.scallop(), Some(0.15));
        assert_eq!(job.tolerance(), 0.01);
        assert_eq!((job.feeds.feed, job.feeds.spindle), (300.0, 1500.0));
        let part = swarf_io::builtin_part("wave").unwrap();
        let plan = swarf_app::plan(&job, PlanInput::Part(&part)).unwrap();
        let opts = GcodeOptions {
            comments: vec![
                "part wave".into(),
                "tool ball:d=8".into(),
                format!("strategy {kind}"),
            ],
            ..GcodeOptions::default()
        };
        let gcode = swarf_nc::write_gcode(&plan.toolpath.moves(), &job.feeds, &opts).unwrap();
        let csv = csv_poses(&swarf_nc::write_pose_csv(&plan.toolpath, Units::Mm).unwrap());
        assert_eq!(csv.len(), plan.toolpath.pose_count());
        let Some((ok, out)) = rs274(&gcode, kind) else {
            return;
        };
        assert!(ok, "{kind}: rs274 failed:\n{out}");
        let errors: Vec<&str> = out
            .lines()
            .filter(|l| !l.contains("N.....") && !l.trim().is_empty() && l.trim() != "executing")
            .collect();
        assert!(errors.is_empty(), "{kind}: rs274 says {errors:?}");
        assert!(out.contains("PROGRAM_END"), "{kind}: no program end");
        check_moves(kind, &canon_moves(&out, job.feeds.feed), &csv);
    }
}

/// Every CSV pose, in order, is an end point of the interpreter's moves (consecutive
/// poses that round to the same G-code point collapse into one move), and every
/// cutting move ends on a CSV pose.
fn check_moves(kind: &str, moves: &[([f64; 3], bool)], csv: &[[f64; 3]]) {
    let close =
        |a: &[f64; 3], b: &[f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() <= 0.5e-4 + 0.5e-6 + 1e-9);
    let mut k = 0;
    for (n, pose) in csv.iter().enumerate() {
        if k > 0 && close(&moves[k - 1].0, pose) {
            continue;
        }
        while k < moves.len() && !close(&moves[k].0, pose) {
            assert!(
                !moves[k].1,
                "{kind}: cutting move {:?} is not the CSV pose {n} {pose:?}",
                moves[k].0
            );
            k += 1;
        }
        assert!(
            k < moves.len(),
            "{kind}: CSV pose {n} {pose:?} is never reached"
        );
        k += 1;
    }
    assert!(
        moves[k..].iter().all(|m| !m.1),
        "{kind}: cutting moves after the last pose"
    );
}
