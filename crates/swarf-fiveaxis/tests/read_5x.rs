//! Five-axis G-code read back through the machine's forward kinematics: for each of
//! the three example machines, an inclined tool path on the die (thesis 000 ch. 8
//! cutter, lead 6 degrees) written by `write_gcode_5x` with G93 and with G94 and read
//! by the G-code reader with `MachineKinematics`. Every pose of the tool path comes
//! back (tip to the printed precision, axis to 1e-4 rad), and the G93 feeds read back
//! are the programmed feeds wherever the feed, not a rotary speed limit, set the time.

use swarf_fiveaxis::job::planned_cc_paths;
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::kinematics::Joints;
use swarf_fiveaxis::machine::reader::MachineKinematics;
use swarf_fiveaxis::positioning::{Positioning, position};
use swarf_fiveaxis::post::{FeedMode, PostOptions, solve_moves, write_gcode_5x};
use swarf_geom::Part;
use swarf_nc::read::{GcodeReadOptions, Program, parse_gcode};
use swarf_path::{Contact, Feeds, Job, Linking, Move, MoveKind, Toolpath};
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

/// Tool length (gauge line to tip) for the machines with head axes, mm.
const TOOL_LENGTH: f64 = 80.0;

/// Tip tolerance: 1e-3 mm printed `X Y Z`, plus 5e-5 degrees of rotary rounding at up
/// to a few hundred mm from the rotary axes.
const TIP_TOL: f64 = 2e-3;

/// Axis tolerance, rad (rotary words printed to 1e-4 degree: 1.7e-6 rad).
const AXIS_TOL: f64 = 1e-4;

fn die() -> Part {
    swarf_io::builtin_part("die").expect("the built-in die part loads")
}

/// Three passes across the die at a fixed lead of 6 degrees (thesis 000 §8.2 cutter).
fn toolpath() -> Toolpath {
    let part = die();
    let all = die_cc(&part, "bull:d=38.1,r=6.35", 60.0, 7.0, 0.005);
    let n = all.len();
    let cc: Vec<_> = [n / 4, n / 2, 3 * n / 4]
        .iter()
        .map(|&k| all[k].clone())
        .collect();
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
    let inclined = Positioning::Inclined {
        alpha: 6.0,
        tilt: 0.0,
        sections: 1.0,
    };
    let (passes, _) = position(&cutter, &part, &cc, &inclined, 0.01).unwrap();
    Toolpath {
        passes,
        feeds: Feeds {
            feed: 800.0,
            ..Feeds::default()
        },
        linking: Linking {
            clearance: 70.0,
            approach: 2.0,
        },
    }
}

/// One block of the program as read: its line, where it ends and its tip feed.
struct Block {
    end: Pose,
    feed: f64,
}

fn blocks(p: &Program) -> Vec<Block> {
    let mut out: Vec<Block> = Vec::new();
    let mut line = 0;
    for m in &p.motions {
        if m.line == line {
            if let Some(b) = out.last_mut() {
                b.end = m.end;
            }
        } else {
            line = m.line;
            out.push(Block {
                end: m.end,
                feed: m.feed,
            });
        }
    }
    out
}

fn close(a: &Pose, b: &Pose) -> bool {
    (a.cl - b.cl).norm() <= TIP_TOL && (a.axis - b.axis).norm() <= AXIS_TOL
}

/// The block each move ends, in order: a move the post left out (no word changed)
/// ends where the block before it did.
fn match_moves(name: &str, moves: &[Move], blocks: &[Block]) -> Vec<usize> {
    let mut k = 0;
    let mut out = Vec::with_capacity(moves.len());
    for (i, mv) in moves.iter().enumerate() {
        if k < blocks.len() && close(&mv.to, &blocks[k].end) {
            k += 1;
        } else {
            let prev = k.checked_sub(1).map(|k| &blocks[k].end);
            assert!(
                prev.is_some_and(|p| close(&mv.to, p)),
                "{name}: move {i} {:?} is not read back (next block ends at {:?})",
                mv.to,
                blocks.get(k).map(|b| b.end)
            );
        }
        out.push(k - 1);
    }
    assert_eq!(
        k,
        blocks.len(),
        "{name}: blocks the tool path does not have"
    );
    out
}

/// Checks the tip feed `read` back for the feed move `i` against the programmed feed
/// and the machine's motion; true when the G93 time was the feed's (not the rotary
/// speed limit's), so that the read feed is known exactly.
///
/// The post timed the chord between the poses (`post.rs`: `max(chord / feed, turn /
/// rotary_feed)` in G93); the machine, moving its axes linearly, runs the tip along a
/// longer bow (up to 1.6 % longer here, where C turns 7 degrees in a 2 mm step). So
/// the G93 feed read back is the programmed feed times path / chord; in G94 it is the
/// programmed feed times path / (X Y Z travel), as LinuxCNC applies F to X Y Z. Both
/// within the rounding of the printed words (5e-4 mm each, at both ends).
fn check_feed(
    name: &str,
    mode: FeedMode,
    m: &Machine,
    moves: &[Move],
    joints: &[Joints],
    i: usize,
    read: f64,
) -> bool {
    let want = moves[i].feed;
    let (a, b) = (&joints[i - 1], &joints[i]);
    let path = path_length(m, a, b);
    let chord = (moves[i].to.cl - moves[i - 1].to.cl).norm();
    let turn = (0..2)
        .map(|k| (b.rotary[k] - a.rotary[k]).abs().to_degrees())
        .fold(0.0, f64::max);
    let travel = (b.linear - a.linear).norm();
    let rotary_feed = PostOptions::default().rotary_feed;
    match mode {
        FeedMode::InverseTime if chord / want > turn / rotary_feed => {
            let ratio = path / chord;
            let rounding = want * 1e-3 / chord;
            assert!(
                (read - want * ratio).abs() < rounding,
                "{name} move {i}: {read} vs {want} x {ratio}"
            );
            true
        }
        FeedMode::InverseTime => {
            assert!(read < want * path / chord, "{name} move {i}: {read}");
            false
        }
        // G94 on a block that turns nothing: the programmed feed exactly.
        FeedMode::UnitsPerMinute if a.rotary == b.rotary => {
            assert_eq!(read, want, "{name} move {i}");
            false
        }
        FeedMode::UnitsPerMinute => {
            let ratio = path / travel;
            let rounding = want * ratio * 1e-3 / travel.min(chord);
            assert!(
                (read - want * ratio).abs() < rounding,
                "{name} move {i}: {read} vs {want} x {ratio}"
            );
            false
        }
    }
}

/// Length of the tip's path over the part while the machine moves its axes linearly
/// from `a` to `b` (a fine polyline of the forward kinematics).
fn path_length(m: &Machine, a: &Joints, b: &Joints) -> f64 {
    let n = 400;
    let at = |k: usize| {
        let t = k as f64 / n as f64;
        let j = Joints {
            linear: a.linear + (b.linear - a.linear) * t,
            rotary: [
                a.rotary[0] + (b.rotary[0] - a.rotary[0]) * t,
                a.rotary[1] + (b.rotary[1] - a.rotary[1]) * t,
            ],
        };
        m.forward(&j, TOOL_LENGTH).cl
    };
    (1..=n).map(|k| (at(k) - at(k - 1)).norm()).sum()
}

fn read(program: &str, k: &MachineKinematics, name: &str) -> Program {
    let opts = GcodeReadOptions {
        kinematics: Some(k),
        kinematics_tol: 1e-3,
        ..GcodeReadOptions::default()
    };
    let p = parse_gcode(program, name, &opts).unwrap();
    assert!(p.stopped.is_none(), "{name}: {:?}", p.stopped);
    p
}

#[test]
fn every_pose_and_inverse_time_feed_reads_back_on_every_machine() {
    let tp = toolpath();
    let moves = tp.moves();
    assert!(moves.len() > 100, "{} moves", moves.len());
    for (name, text) in MACHINES {
        let m = Machine::parse(text, name).unwrap();
        let joints = solve_moves(&m, &tp, &moves, TOOL_LENGTH).unwrap();
        let k = MachineKinematics::new(m.clone(), TOOL_LENGTH).unwrap();
        let mut ends = Vec::new();
        for mode in [FeedMode::InverseTime, FeedMode::UnitsPerMinute] {
            let opts = PostOptions {
                feed_mode: mode,
                tool_length: TOOL_LENGTH,
                ..PostOptions::default()
            };
            let program = write_gcode_5x(&m, &tp, &opts).unwrap();
            let p = read(&program, &k, name);
            let blocks = blocks(&p);
            let at = match_moves(name, &moves, &blocks);
            ends.push(blocks.iter().map(|b| b.end).collect::<Vec<_>>());
            let mut checked = 0;
            for i in 1..moves.len() {
                let fresh = at[i] != at[i - 1];
                if !(fresh && moves[i].kind == MoveKind::Feed) {
                    continue;
                }
                let read = blocks[at[i]].feed;
                checked += usize::from(check_feed(name, mode, &m, &moves, &joints, i, read));
            }
            if mode == FeedMode::InverseTime {
                assert!(checked > moves.len() / 2, "{name}: {checked} feeds checked");
            }
        }
        // Both programs put the tool in the same places.
        assert_eq!(ends[0].len(), ends[1].len());
        for (a, b) in ends[0].iter().zip(&ends[1]) {
            assert!((a.cl - b.cl).norm() < 1e-9 && (a.axis - b.axis).norm() < 1e-12);
        }
    }
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
