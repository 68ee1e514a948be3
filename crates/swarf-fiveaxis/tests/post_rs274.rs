//! Five-axis G-code for the three example machines, read back by LinuxCNC's `rs274 -g`
//! (when installed; required when `SWARF_REQUIRE_REFERENCES=1`): the interpreter accepts
//! every program, and its canonical moves, turned back into part-frame poses by our
//! forward kinematics, are the tool path's poses to the printed precision.

use std::path::Path;
use std::process::Command;
use swarf_fiveaxis::job::planned_cc_paths;
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::kinematics::Joints;
use swarf_fiveaxis::post::{FeedMode, PostOptions, write_gcode_5x};
use swarf_fiveaxis::{FiveAxisError, incline_pass};
use swarf_geom::{Part, Vec3};
use swarf_path::{Contact, Feeds, Job, Linking, Toolpath};
use swarf_tool::{Cutter, Pose};

const MACHINES: [(&str, &str); 3] = [
    (
        "trunnion",
        include_str!("../../../machines/xyzac-trunnion.toml"),
    ),
    ("head", include_str!("../../../machines/xyzbc-head.toml")),
    (
        "table-head",
        include_str!("../../../machines/xyzbc-table-head.toml"),
    ),
];

fn die() -> Part {
    swarf_io::builtin_part("die").expect("the built-in die part loads")
}

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

fn rs274(program: &str, name: &str) -> Option<String> {
    if !Path::new("/usr/bin/rs274").exists() {
        assert!(
            std::env::var("SWARF_REQUIRE_REFERENCES").as_deref() != Ok("1"),
            "rs274 is required but not installed"
        );
        return None;
    }
    let dir = std::env::temp_dir().join(format!("swarf-5x-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("prog.ngc");
    std::fs::write(&file, program).unwrap();
    let out = Command::new("/usr/bin/rs274")
        .arg("-g")
        .arg(&file)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(out.status.success(), "{name}: rs274 failed:\n{text}");
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let t = line.trim_start();
        let ok = t
            .split(' ')
            .next()
            .is_some_and(|n| n.parse::<u32>().is_ok())
            && t.contains("N..... ");
        assert!(ok, "{name}: rs274 complained: {line}");
    }
    std::fs::remove_dir_all(&dir).ok();
    Some(text)
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
            // Each canonical position is the next move's pose (moves that change no word
            // are not written); positions printed to 1e-4 mm and 1e-4 degrees.
            let mut k = 0;
            let mut prev: Option<(Pose, Joints)> = None;
            for (j, rate, feed) in &motions {
                let p = m.forward(j, tool_length);
                while k < moves.len() && (moves[k].to.cl - p.cl).norm() > 2e-3 {
                    k += 1;
                }
                assert!(k < moves.len(), "{name}: a canonical move matches no pose");
                assert!((moves[k].to.axis - p.axis).norm() < 1e-5, "{name}: axis");
                if *feed
                    && mode == FeedMode::InverseTime
                    && let Some((q, qj)) = prev
                {
                    // rs274 turns F (1/min) into F times the X Y Z length of the block;
                    // we wrote F = feed / length of the tip's path over the part.
                    let part = (p.cl - q.cl).norm();
                    let machine = (j.linear - qj.linear).norm();
                    if part > 0.5 && machine > 0.5 {
                        let expected = moves[k].feed * machine / part;
                        assert!(
                            (rate - expected).abs() < 1e-3 * expected,
                            "{name}: feed rate {rate} vs {expected}"
                        );
                    }
                }
                prev = Some((p, *j));
            }
            assert_eq!(k, moves.len() - 1, "{name}: the last move");
        }
    }
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
