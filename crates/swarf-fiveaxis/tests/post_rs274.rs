//! Five-axis G-code for the three example machines, read back by LinuxCNC's `rs274 -g`
//! (when installed; required when `SWARF_REQUIRE_REFERENCES=1`): the interpreter accepts
//! every program, and its canonical moves, turned back into part-frame poses by our
//! forward kinematics, are the tool path's poses to the printed precision, with the
//! blocks the post inserts between them on the chords (within `path_tol`).

use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::kinematics::Joints;
use swarf_fiveaxis::post::{FeedMode, PostOptions, write_gcode_5x};
use swarf_fiveaxis::{FiveAxisError, incline_pass};
use swarf_geom::{Point3, Vec3};

use swarf_testkit::machines::MACHINES;
use swarf_testkit::parts::die;
use swarf_testkit::{die_cc, rs274::run_rs274};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Feeds, Linking, Move, Toolpath};

/// Three inclined passes over the die (lead 10 degrees, tilt 5), iso-planar at a 19 mm cross feed.
fn toolpath() -> Toolpath {
    let part = die();
    let cutter: Cutter = "bull:d=20,r=4".parse().unwrap();
    let cc = die_cc(&part, "bull:d=20,r=4", 60.0, 19.0, 0.05);
    let passes = cc
        .iter()
        .take(3)
        .enumerate()
        .map(|(k, c)| {
            incline_pass(&cutter, c, &[10f64.to_radians()], 5f64.to_radians(), k).unwrap()
        })
        .collect();
    Toolpath {
        passes,
        feeds: Feeds::default(),
        linking: Linking {
            clearance: 70.0,
            approach: 2.0,
            ..Linking::default()
        },
    }
}

/// The machine positions of `STRAIGHT_TRAVERSE` / `STRAIGHT_FEED` lines and the feed
/// rate in force at each.
fn canonical(text: &str, names: [char; 2]) -> Vec<(Joints, f64, bool)> {
    let mut out = Vec::new();
    let mut rate = 0.0;
    for line in text.lines() {
        if let Some(r) = line.split("SET_FEED_RATE(").nth(1) {
            rate = r.trim_end_matches(')').parse().unwrap();
        }
        let (feed, args) = if let Some(a) = line.split("STRAIGHT_FEED(").nth(1) {
            (true, a)
        } else if let Some(a) = line.split("STRAIGHT_TRAVERSE(").nth(1) {
            (false, a)
        } else {
            continue;
        };
        let v: Vec<f64> = args
            .trim_end_matches(')')
            .split(',')
            .map(|s| s.trim().parse().unwrap())
            .collect();
        let word = |c: char| v[3 + (c as usize - 'A' as usize)];
        let rotary = [word(names[0]).to_radians(), word(names[1]).to_radians()];
        out.push((
            Joints {
                linear: Vec3::new(v[0], v[1], v[2]),
                rotary,
            },
            rate,
            feed,
        ));
    }
    out
}

/// `rs274 -g` on `program`: its canonical output, checked clean; `None` when rs274
/// is not installed.
fn rs274(program: &str, name: &str) -> Option<String> {
    run_rs274(program, &format!("5x-{name}")).map(|out| out.clean(name))
}

#[test]
fn rs274_reads_back_the_poses_on_every_machine() {
    let tp = toolpath();
    let moves = tp.moves();
    let tool_length = 80.0;
    for (name, text) in MACHINES {
        let m = Machine::parse(text, name).unwrap();
        for mode in [FeedMode::InverseTime, FeedMode::UnitsPerMinute] {
            let opts = PostOptions {
                feed_mode: mode,
                tool_length,
                comments: vec![format!("test {name}")],
                ..PostOptions::default()
            };
            let program = write_gcode_5x(&m, &tp, &opts).unwrap();
            let Some(out) = rs274(&program, name) else {
                return;
            };
            let motions = canonical(&out, m.rotary_names());
            assert!(motions.len() > 20, "{name}: {} motions", motions.len());
            let inserted = check_motions(name, &m, &moves, &motions, &opts);
            assert!(inserted > 0, "{name}: no block inserted");
        }
    }
}

/// Each canonical position is the next move's pose (moves that change no word are not
/// written), or a block the post inserted before it: on the chord from the previous
/// move's pose within `path_tol`, the axis on the great circle within
/// `path_angle_tol`; positions printed to 1e-4 mm and 1e-4 degrees. In G93, rs274's
/// feed rate is F times the block's `X Y Z` length, and F the tip's path length over
/// the part over the feed. Returns the number of inserted blocks.
fn check_motions(
    name: &str,
    m: &Machine,
    moves: &[Move],
    motions: &[(Joints, f64, bool)],
    opts: &PostOptions,
) -> usize {
    let close =
        |p: &Pose, q: &Pose| (p.cl - q.cl).norm() <= 2e-3 && (p.axis - q.axis).norm() < 1e-5;
    let mut k: Option<usize> = None;
    let mut inserted = 0;
    let mut prev: Option<Joints> = None;
    for (j, rate, feed) in motions {
        let p = m.forward(j, opts.tool_length);
        // Moves the post left out end where the one before them did.
        while let Some(i) =
            k.filter(|&i| i + 1 < moves.len() && close(&moves[i + 1].to, &moves[i].to))
        {
            k = Some(i + 1);
        }
        let next = k.map_or(0, |i| i + 1);
        assert!(
            next < moves.len(),
            "{name}: a canonical move after the last pose"
        );
        if close(&p, &moves[next].to) {
            k = Some(next);
        } else {
            let Some(i) = k else {
                panic!("{name}: the first canonical move is not the first pose");
            };
            let (a, b) = (&moves[i].to, &moves[next].to);
            let off = off_chord(&p.cl, &a.cl, &b.cl);
            assert!(
                off <= opts.path_tol + 2e-3,
                "{name}: {off} mm off the chord"
            );
            let n = a.axis.cross(&b.axis).normalize();
            let angle = p.axis.dot(&n).abs().asin();
            assert!(
                angle <= opts.path_angle_tol + 1e-5,
                "{name}: axis {angle} rad off"
            );
            inserted += 1;
        }
        if *feed
            && opts.feed_mode == FeedMode::InverseTime
            && let Some(q) = prev
        {
            let path = path_length(m, &q, j, opts.tool_length);
            let machine = (j.linear - q.linear).norm();
            if path > 0.5 && machine > 0.5 {
                let expected = moves[next].feed * machine / path;
                assert!(
                    (rate - expected).abs() < 1e-3 * expected,
                    "{name}: feed rate {rate} vs {expected}"
                );
            }
        }
        prev = Some(*j);
    }
    assert_eq!(k, Some(moves.len() - 1), "{name}: the last move");
    inserted
}

/// Distance from `p` to the segment `a b`.
fn off_chord(p: &Point3, a: &Point3, b: &Point3) -> f64 {
    let d = b - a;
    let t = ((p - a).dot(&d) / d.norm_squared().max(1e-300)).clamp(0.0, 1.0);
    (p - (a + d * t)).norm()
}

/// Length of the tip's path over the part while the machine moves its axes linearly
/// from `a` to `b` (a fine polyline of the forward kinematics).
fn path_length(m: &Machine, a: &Joints, b: &Joints, tool_length: f64) -> f64 {
    let n = 200;
    let at = |k: usize| {
        let t = k as f64 / n as f64;
        let j = Joints {
            linear: a.linear + (b.linear - a.linear) * t,
            rotary: [
                a.rotary[0] + (b.rotary[0] - a.rotary[0]) * t,
                a.rotary[1] + (b.rotary[1] - a.rotary[1]) * t,
            ],
        };
        m.forward(&j, tool_length).cl
    };
    (1..=n).map(|k| (at(k) - at(k - 1)).norm()).sum()
}

#[test]
fn unreachable_poses_name_the_pass_point_and_axis() {
    let tp = toolpath();
    let tight = MACHINES[0]
        .1
        .replace("limits = [-30, 120]", "limits = [-5, 5]");
    let m = Machine::parse(&tight, "tight").unwrap();
    let e = write_gcode_5x(&m, &tp, &PostOptions::default()).unwrap_err();
    assert!(
        matches!(e, FiveAxisError::Unreachable { pass: 0, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("axis A"), "{e}");
    let small = MACHINES[0].1.replace("x = [-508, 508]", "x = [-10, 10]");
    let m = Machine::parse(&small, "small").unwrap();
    let e = write_gcode_5x(&m, &tp, &PostOptions::default()).unwrap_err();
    assert!(e.to_string().contains("axis X"), "{e}");
}
