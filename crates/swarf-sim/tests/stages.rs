//! Several programs in sequence on one stock (issue 11, item 6): a coarse ball
//! raster, then a finer one with a smaller ball, against a brute-force oracle at the
//! cell centres; the motion numbering across programs; the reports naming programs;
//! determinism; one stage against the plain simulation.

use swarf_geom::{Part, Patch, Point3};
use swarf_sim::dexel::NO_MOTION;
use swarf_sim::report::{ReportContext, flagged_csv, json_report, text_summary};
use swarf_sim::{
    Design, Dexel, Quiet, SimOptions, SimTool, Stage, StockInit, StockSpec, Verification,
    VerifyOptions, simulate, verify, verify_stages,
};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Motion, MotionKind, Program};

/// Stock allowance over the plane, mm.
const ALLOWANCE: f64 = 0.5;

fn mv(kind: MotionKind, a: [f64; 3], b: [f64; 3], line: usize) -> Motion {
    Motion {
        kind,
        start: Pose::vertical(Point3::from(a)),
        end: Pose::vertical(Point3::from(b)),
        feed: 600.0,
        line,
    }
}

/// The plane z = 0 over [0, 40] x [0, 20].
fn plane() -> Part {
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    Part {
        name: "plane".into(),
        faces: Vec::new(),
        patches: vec![
            Patch::bezier(
                [1, 1],
                vec![p(0.0, 0.0), p(0.0, 20.0), p(40.0, 0.0), p(40.0, 20.0)],
            )
            .unwrap(),
        ],
    }
}

/// A raster along x over the plane, passes at `ys` with the tip at `z(pass)`; each
/// pass plunges and retracts at x = -10 and x = 50, off the grid for any tool up to
/// 10 mm across. One motion per line, lines from 1.
fn raster(source: &str, ys: &[f64], z: impl Fn(usize) -> f64) -> Program {
    let mut p = Program::new(source);
    let safe = [-10.0, ys[0], 10.0];
    let mut at = safe;
    let mut push = |p: &mut Program, kind, to: [f64; 3]| {
        let line = p.motions.len() + 1;
        p.motions.push(mv(kind, at, to, line));
        at = to;
    };
    push(&mut p, MotionKind::Rapid, safe);
    for (k, &y) in ys.iter().enumerate() {
        push(&mut p, MotionKind::Rapid, [-10.0, y, 10.0]);
        push(&mut p, MotionKind::Linear, [-10.0, y, z(k)]);
        push(&mut p, MotionKind::Linear, [50.0, y, z(k)]);
        push(&mut p, MotionKind::Rapid, [50.0, y, 10.0]);
    }
    p
}

/// Pass heights `0, step, 2 step, ... 20`.
fn passes(step: f64) -> Vec<f64> {
    let n = (20.0 / step).round() as usize;
    (0..=n).map(|k| k as f64 * step).collect()
}

fn options() -> VerifyOptions {
    VerifyOptions {
        cell: Some(0.125),
        stock: StockSpec::Offset {
            allowance: ALLOWANCE,
        },
        ..VerifyOptions::default()
    }
}

/// The finishing program (ball d=10, 4 mm stepover: 0.417 mm scallops) and the
/// cleanup program (ball d=4, 0.25 mm stepover: 0.004 mm scallops).
fn finish_and_cleanup() -> (Program, Cutter, Program, Cutter) {
    let finish = raster("finish.ngc", &passes(4.0), |_| 0.0);
    let cleanup = raster("cleanup.ngc", &passes(0.25), |_| 0.0);
    let (big, small) = ("ball:d=10".parse().unwrap(), "ball:d=4".parse().unwrap());
    (finish, big, cleanup, small)
}

/// Lowest point of a ball of radius `r`, tip at height `z` on a line along x at `y0`,
/// over a cell at `y` (the line spans the grid in x).
fn ball_over(r: f64, y0: f64, z: f64, y: f64) -> f64 {
    let d = (y - y0).abs();
    if d <= r {
        z + r - (r * r - d * d).sqrt()
    } else {
        f64::INFINITY
    }
}

fn verify_both(threads: usize) -> Verification {
    let (finish, big, cleanup, small) = finish_and_cleanup();
    let stages = [
        Stage {
            program: &finish,
            cutter: &big,
        },
        Stage {
            program: &cleanup,
            cutter: &small,
        },
    ];
    let part = plane();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| verify_stages(Design::Part(&part), &stages, &options(), &Quiet).unwrap())
}

#[test]
fn two_programs_leave_the_lower_envelope_of_both_tools() {
    let v = verify_both(2);
    let g = &v.grid;
    let mut crests_recut = 0;
    for j in 0..g.ny {
        let y = g.y(j);
        let coarse = passes(4.0)
            .iter()
            .map(|&y0| ball_over(5.0, y0, 0.0, y))
            .fold(f64::INFINITY, f64::min);
        let fine = passes(0.25)
            .iter()
            .map(|&y0| ball_over(2.0, y0, 0.0, y))
            .fold(f64::INFINITY, f64::min);
        let want = coarse.min(fine).min(ALLOWANCE);
        for i in 0..g.nx {
            let k = j * g.nx + i;
            if v.design.heights[k].is_nan() {
                continue;
            }
            let got = v.stock.heights()[k];
            assert!(
                (got - want).abs() < 1e-9,
                "({}, {y}): {got} vs {want}",
                g.x(i)
            );
            // Where the cleanup went deeper than the finish, it left the cell: its
            // motion is numbered after the finishing program's and says so.
            if fine < coarse - 1e-6 {
                let m = v.stock.last_motion()[k] as usize;
                let stage = v.stage_of(m).unwrap();
                assert_eq!(stage.source, "cleanup.ngc");
                assert_eq!(v.lines[m], m - stage.first_motion + 1);
                crests_recut += 1;
            }
        }
    }
    assert!(crests_recut > 1000, "{crests_recut}");
    let s = &v.deviation.summary;
    assert_eq!((s.excess.cells, s.gouge.cells), (0, 0));
    assert!(s.max.unwrap() < 0.005, "{:?}", s.max);
}

#[test]
fn the_finish_alone_leaves_scallops_the_cleanup_removes() {
    let (finish, big, _, _) = finish_and_cleanup();
    let v = verify(Design::Part(&plane()), &finish, &big, &options(), &Quiet).unwrap();
    let s = &v.deviation.summary;
    assert!(s.excess.cells > 1000, "{:?}", s.excess);
    // The crest midway between passes, 4 mm apart, sampled by cells 1/8 mm wide.
    let crest = 5.0 - 21.0f64.sqrt();
    let max = s.max.unwrap();
    assert!(
        max <= crest + 1e-9 && max > crest - 0.05,
        "{max} vs {crest}"
    );
}

#[test]
fn figures_and_numbering_span_both_programs() {
    let (finish, _, cleanup, _) = finish_and_cleanup();
    let v = verify_both(1);
    let (n1, n2) = (finish.motions.len(), cleanup.motions.len());
    assert_eq!(v.stages.len(), 2);
    assert_eq!(
        (v.stages[0].first_motion, v.stages[1].first_motion),
        (0, n1)
    );
    assert_eq!(
        (v.stages[0].tool.as_str(), v.stages[1].tool.as_str()),
        ("ball:d=10", "ball:d=4")
    );
    assert_eq!(v.lines.len(), n1 + n2);
    assert_eq!((v.lines[n1 - 1], v.lines[n1]), (n1, 1));
    assert_eq!(v.sim.motions, n1 + n2);
    let p = &v.program;
    assert_eq!(p.motions, n1 + n2);
    assert_eq!(p.passes, passes(4.0).len() + passes(0.25).len());
    let sum = v.stages[0].stats.time_s + v.stages[1].stats.time_s;
    assert!(sum > 0.0 && (p.time_s - sum).abs() < 1e-9 * sum);
    assert!(v.stage_of(n1 + n2).is_none());
}

#[test]
fn the_same_whatever_the_threads() {
    let (a, b) = (verify_both(1), verify_both(2));
    assert!(a.stock.heights() == b.stock.heights());
    assert!(a.stock.last_motion() == b.stock.last_motion());
    assert_eq!(a.sim, b.sim);
    assert_eq!(a.deviation.summary, b.deviation.summary);
    assert_eq!(flagged_csv(&a), flagged_csv(&b));
}

#[test]
fn no_program_is_an_error() {
    let e = verify_stages(Design::Part(&plane()), &[], &options(), &Quiet).unwrap_err();
    assert!(e.to_string().contains("no program"), "{e}");
}

/// The cleanup program with pass `k` planted 0.05 mm deep: its gouge is reported
/// with the cleanup's line and name, in the JSON, the CSV and the summary.
#[test]
fn reports_name_the_program_of_each_motion() {
    let (finish, big, _, small) = finish_and_cleanup();
    let (k, depth) = (40, -0.05);
    let cleanup = raster("cleanup.ngc", &passes(0.25), |p| {
        if p == k { depth } else { 0.0 }
    });
    let stages = [
        Stage {
            program: &finish,
            cutter: &big,
        },
        Stage {
            program: &cleanup,
            cutter: &small,
        },
    ];
    let v = verify_stages(Design::Part(&plane()), &stages, &options(), &Quiet).unwrap();
    let cut_line = 4 * k + 4;
    let ctx = ReportContext {
        program: "finish.ngc + cleanup.ngc".into(),
        ..ReportContext::default()
    };
    let json = json_report(&v, &ctx);
    let worst = &json["deviation"]["gouges"][0];
    assert_eq!(worst["program"], "cleanup.ngc", "{worst}");
    assert_eq!(worst["line"].as_u64(), Some(cut_line as u64), "{worst}");
    assert_eq!(json["programs"][1]["source"], "cleanup.ngc");
    assert_eq!(json["programs"][1]["first_motion"], finish.motions.len());
    let csv = flagged_csv(&v);
    let mut rows = csv.lines();
    assert_eq!(
        rows.next(),
        Some("x,y,design_z,machined_z,deviation,kind,motion,line,program")
    );
    let gouge = rows.next().unwrap();
    assert!(
        gouge.ends_with(&format!(
            ",gouge,{},{cut_line},cleanup.ngc",
            v.stages[1].first_motion + cut_line - 1
        )),
        "{gouge}"
    );
    let text = text_summary(&v, &ctx);
    assert!(
        text.contains(&format!("(line {cut_line} of cleanup.ngc)")),
        "{text}"
    );
    assert!(text.contains("cleanup.ngc with ball:d=4"), "{text}");
}

/// One stage is the plain simulation of its program from an unknown start, and its
/// reports carry no program names.
#[test]
fn one_stage_is_the_program_simulated_alone() {
    let (finish, big, _, _) = finish_and_cleanup();
    let v = verify(Design::Part(&plane()), &finish, &big, &options(), &Quiet).unwrap();
    let mut d = Dexel::new(
        v.grid,
        StockInit::Offset {
            design: &v.design.heights,
            allowance: ALLOWANCE,
        },
    )
    .unwrap();
    let opts = SimOptions {
        sample_tol: v.sample_tol,
        known_start: false,
        ..SimOptions::default()
    };
    let sim = simulate(
        &mut d,
        &SimTool::new(&big).unwrap(),
        &finish.motions,
        &opts,
        &Quiet,
    );
    assert!(d.heights() == v.stock.heights());
    assert!(d.last_motion() == v.stock.last_motion());
    assert!(d.last_motion().iter().any(|&m| m != NO_MOTION));
    assert_eq!(sim, v.sim);
    assert_eq!(v.stages.len(), 1);
    let lines: Vec<usize> = finish.motions.iter().map(|m| m.line).collect();
    assert_eq!(v.lines, lines);
    let csv = flagged_csv(&v);
    assert!(csv.starts_with("x,y,design_z,machined_z,deviation,kind,motion,line\n"));
    assert!(!csv.contains("finish.ngc"));
    let json = json_report(&v, &ReportContext::default());
    assert!(json.get("programs").is_none());
    assert!(json["deviation"]["excesses"][0].get("program").is_none());
}
