//! Five-axis G-code read back through the machine's forward kinematics: for each of
//! the three example machines, an inclined tool path on the die (thesis 000 ch. 8
//! cutter, lead 6 degrees) written by `post_5x` with G93 and with G94 and read by the
//! G-code reader with `MachineKinematics`. Every pose of the tool path comes back (tip
//! to the printed precision, axis to 1e-4 rad), in order, with the blocks the post
//! inserted between them; every point of the machine's joint-linear motion as read
//! back lies within `path_tol` (plus print rounding) of the chord between the two
//! poses it joins, and the axis within `path_angle_tol` of the great circle; the G93
//! feeds read back are the programmed feeds wherever the feed, not a rotary speed
//! limit, set the time. Written one block per pose (`path_tol = inf`), the same check
//! finds the tip well off the chord: the check can fail.

use std::ops::Range;
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::kinematics::Joints;
use swarf_fiveaxis::machine::reader::MachineKinematics;
use swarf_fiveaxis::positioning::{Positioning, position};
use swarf_fiveaxis::post::subdivide::MAX_BLOCKS;
use swarf_fiveaxis::post::{FeedMode, PostOptions, post_5x};
use swarf_geom::{Point3, Vec3};
use swarf_nc::read::{GcodeReadOptions, Program, parse_gcode};
use swarf_testkit::die_cc;
use swarf_testkit::machines::MACHINES;
use swarf_testkit::parts::die;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Feeds, Linking, Move, MoveKind, Toolpath};

/// Tool length (gauge line to tip) for the machines with head axes, mm.
const TOOL_LENGTH: f64 = 80.0;

/// Tip tolerance: 1e-3 mm printed `X Y Z`, plus 5e-5 degrees of rotary rounding at up
/// to a few hundred mm from the rotary axes.
const TIP_TOL: f64 = 2e-3;

/// Axis tolerance, rad (rotary words printed to 1e-4 degree: 1.7e-6 rad).
const AXIS_TOL: f64 = 1e-4;

/// The reader's chordal tolerance on joint-linear motion, mm.
const READ_TOL: f64 = 1e-3;

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
            ..Linking::default()
        },
    }
}

/// One block of the program as read: its line, the motions it reads as (the
/// reader's subdivision of the joint-linear motion), where it ends, its tip feed.
struct Block {
    line: usize,
    ends: Vec<Pose>,
    end: Pose,
    feed: f64,
}

fn blocks(p: &Program) -> Vec<Block> {
    let mut out: Vec<Block> = Vec::new();
    for m in &p.motions {
        match out.last_mut() {
            Some(b) if b.line == m.line => {
                b.end = m.end;
                b.ends.push(m.end);
            }
            _ => out.push(Block {
                line: m.line,
                ends: vec![m.end],
                end: m.end,
                feed: m.feed,
            }),
        }
    }
    out
}

fn close(a: &Pose, b: &Pose) -> bool {
    (a.cl - b.cl).norm() <= TIP_TOL && (a.axis - b.axis).norm() <= AXIS_TOL
}

/// The blocks each move was written as, in order: the blocks the post inserted
/// before the one that ends at the move's pose, and that one; none when the post
/// left the move out (no word changed: it ends where the block before it did).
fn spans(name: &str, moves: &[Move], blocks: &[Block]) -> Vec<Range<usize>> {
    let mut k = 0;
    let mut out = Vec::with_capacity(moves.len());
    for (i, mv) in moves.iter().enumerate() {
        let here = blocks.get(k).is_some_and(|b| close(&mv.to, &b.end));
        if !here && k > 0 && close(&mv.to, &blocks[k - 1].end) {
            out.push(k..k);
            continue;
        }
        let end =
            (k..blocks.len().min(k + MAX_BLOCKS + 1)).find(|&b| close(&mv.to, &blocks[b].end));
        let Some(end) = end else {
            panic!(
                "{name}: move {i} {:?} is not read back (next block ends at {:?})",
                mv.to,
                blocks.get(k).map(|b| b.end)
            );
        };
        out.push(k..end + 1);
        k = end + 1;
    }
    assert_eq!(
        k,
        blocks.len(),
        "{name}: blocks the tool path does not have"
    );
    out
}

/// Distance from `p` to the segment `a b`.
fn off_chord(p: &Point3, a: &Point3, b: &Point3) -> f64 {
    let d = b - a;
    let t = ((p - a).dot(&d) / d.norm_squared().max(1e-300)).clamp(0.0, 1.0);
    (p - (a + d * t)).norm()
}

/// Angle from the unit `v` to the great circle through `a` and `b` (to `a` when they
/// are parallel).
fn off_circle(v: &Vec3, a: &Vec3, b: &Vec3) -> f64 {
    let n = a.cross(b);
    if n.norm() < 1e-9 {
        return v.angle(a);
    }
    v.dot(&n.normalize()).abs().asin()
}

/// Largest distance of the read-back tip from the chord of the move each block
/// belongs to, and largest angle of the axis from its great circle: over the cutting
/// moves (`cutting`) or the links.
fn deviations(
    moves: &[Move],
    blocks: &[Block],
    spans: &[Range<usize>],
    cutting: bool,
) -> (f64, f64) {
    let (mut tip, mut angle) = (0.0f64, 0.0f64);
    for i in (1..moves.len()).filter(|&i| moves[i].pass.is_some() == cutting) {
        let (a, b) = (&moves[i - 1].to, &moves[i].to);
        for p in spans[i].clone().flat_map(|k| &blocks[k].ends) {
            tip = tip.max(off_chord(&p.cl, &a.cl, &b.cl));
            angle = angle.max(off_circle(&p.axis, &a.axis, &b.axis));
        }
    }
    (tip, angle)
}

/// The machine axes after each line of `program` (the modal `X Y Z` and rotary words
/// as printed), by line number (1-based), and the line's `F` word.
fn words(program: &str, names: [char; 2]) -> Vec<(Joints, Option<f64>)> {
    let mut j = Joints {
        linear: Vec3::zeros(),
        rotary: [0.0; 2],
    };
    let mut out = vec![(j, None)];
    for line in program.lines() {
        let mut f = None;
        if !line.starts_with('(') {
            for w in line.split_whitespace() {
                let (c, v) = w.split_at(1);
                let Ok(v) = v.parse::<f64>() else { continue };
                match c.chars().next() {
                    Some('X') => j.linear.x = v,
                    Some('Y') => j.linear.y = v,
                    Some('Z') => j.linear.z = v,
                    Some('F') => f = Some(v),
                    Some(c) if c == names[0] => j.rotary[0] = v.to_radians(),
                    Some(c) if c == names[1] => j.rotary[1] = v.to_radians(),
                    _ => {}
                }
            }
        }
        out.push((j, f));
    }
    out
}

/// Checks the tip feed `read` back for block `b` (from the axes `a` to `b` of the
/// program's words) of a feed move at `want` mm/min; true when the feed, not the
/// rotary speed limit, set the G93 time, so that the read feed is known exactly.
///
/// G93: the post timed the block by the tip's path over the part (within `path_tol`
/// of the block's chord): the feed read back is the programmed feed, within the
/// rounding of the printed words (5e-4 mm each, at both ends, over the block's
/// length). G94: LinuxCNC applies F to the machine's `X Y Z`, so the tip runs at the
/// programmed feed times path / (X Y Z travel).
fn check_feed(
    name: &str,
    mode: FeedMode,
    m: &Machine,
    a: &Joints,
    b: &Joints,
    want: f64,
    read: f64,
) -> bool {
    let path = path_length(m, a, b);
    let turn = (0..2)
        .map(|k| (b.rotary[k] - a.rotary[k]).abs().to_degrees())
        .fold(0.0, f64::max);
    let travel = (b.linear - a.linear).norm();
    let rotary_feed = PostOptions::default().rotary_feed;
    let rounding = 1.5e-3 / path;
    match mode {
        FeedMode::InverseTime if path / want > turn / rotary_feed * (1.0 + rounding) => {
            assert!(
                (read - want).abs() < want * rounding,
                "{name}: {read} vs {want} over {path} mm"
            );
            true
        }
        FeedMode::InverseTime => {
            assert!(read < want * (1.0 + rounding), "{name}: {read} vs {want}");
            false
        }
        // G94 on a block that turns nothing: the programmed feed exactly.
        FeedMode::UnitsPerMinute if a.rotary == b.rotary => {
            assert_eq!(read, want, "{name}");
            false
        }
        FeedMode::UnitsPerMinute => {
            let ratio = path / travel;
            let rounding = want * ratio * 1e-3 / travel.min(path);
            assert!(
                (read - want * ratio).abs() < rounding,
                "{name}: {read} vs {want} x {ratio}"
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
        kinematics_tol: READ_TOL,
        ..GcodeReadOptions::default()
    };
    let p = parse_gcode(program, name, &opts).unwrap();
    assert!(p.stopped.is_none(), "{name}: {:?}", p.stopped);
    p
}

/// Checks every block's feed; returns how many G93 feeds were known exactly.
fn check_feeds(
    name: &str,
    mode: FeedMode,
    m: &Machine,
    program: &str,
    moves: &[Move],
    blocks: &[Block],
    spans: &[Range<usize>],
) -> usize {
    let words = words(program, m.rotary_names());
    let mut checked = 0;
    for (mv, span) in moves.iter().zip(spans) {
        if mv.kind != MoveKind::Feed {
            continue;
        }
        for k in span.clone().filter(|&k| k > 0) {
            let (a, b) = (&words[blocks[k - 1].line].0, &words[blocks[k].line].0);
            if mode == FeedMode::InverseTime {
                assert!(
                    words[blocks[k].line].1.is_some(),
                    "{name}: G93 block without F"
                );
            }
            checked += usize::from(check_feed(name, mode, m, a, b, mv.feed, blocks[k].feed));
        }
    }
    checked
}

#[test]
fn every_pose_and_inverse_time_feed_reads_back_on_every_machine() {
    let tp = toolpath();
    let moves = tp.moves();
    assert!(moves.len() > 100, "{} moves", moves.len());
    for (name, text) in MACHINES {
        let m = Machine::parse(text, name).unwrap();
        let k = MachineKinematics::new(m.clone(), TOOL_LENGTH).unwrap();
        let mut ends = Vec::new();
        for mode in [FeedMode::InverseTime, FeedMode::UnitsPerMinute] {
            let opts = PostOptions {
                feed_mode: mode,
                tool_length: TOOL_LENGTH,
                ..PostOptions::default()
            };
            let post = post_5x(&m, &tp, &opts).unwrap();
            let p = read(&post.gcode, &k, name);
            let blocks = blocks(&p);
            let spans = spans(name, &moves, &blocks);
            let r = post.report;
            for (kind, stray, cutting) in [("cutting", r.cutting, true), ("links", r.links, false)]
            {
                let (tip, angle) = deviations(&moves, &blocks, &spans, cutting);
                println!(
                    "{name} {mode:?} {kind}: {} moves, {} blocks inserted; tip off the chord \
                     {tip:.5} mm read back ({:.5} by the post, {:.5} in one block per move), \
                     axis {:.5} deg ({:.5})",
                    stray.moves,
                    stray.inserted,
                    stray.tip,
                    stray.unsplit_tip,
                    angle.to_degrees(),
                    stray.unsplit_angle.to_degrees()
                );
                assert!(
                    stray.inserted > 0 && stray.at_bound == 0,
                    "{name}: {stray:?}"
                );
                assert!(
                    tip <= opts.path_tol + TIP_TOL,
                    "{name}: {tip} mm off the chord"
                );
                assert!(
                    angle <= opts.path_angle_tol + AXIS_TOL,
                    "{name}: {angle} rad"
                );
                assert!(stray.tip <= opts.path_tol && stray.angle <= opts.path_angle_tol);
            }
            let checked = check_feeds(name, mode, &m, &post.gcode, &moves, &blocks, &spans);
            if mode == FeedMode::InverseTime {
                assert!(checked > moves.len() / 2, "{name}: {checked} feeds checked");
            }
            ends.push(blocks.iter().map(|b| b.end).collect::<Vec<_>>());
        }
        // Both programs put the tool in the same places.
        assert_eq!(ends[0].len(), ends[1].len());
        for (a, b) in ends[0].iter().zip(&ends[1]) {
            assert!((a.cl - b.cl).norm() < 1e-9 && (a.axis - b.axis).norm() < 1e-12);
        }
    }
}

#[test]
fn one_block_per_pose_strays_off_the_chord() {
    let tp = toolpath();
    let moves = tp.moves();
    let (name, text) = MACHINES[0];
    let m = Machine::parse(text, name).unwrap();
    let opts = PostOptions {
        tool_length: TOOL_LENGTH,
        path_tol: f64::INFINITY,
        path_angle_tol: f64::INFINITY,
        ..PostOptions::default()
    };
    let post = post_5x(&m, &tp, &opts).unwrap();
    assert_eq!(post.report.cutting.inserted + post.report.links.inserted, 0);
    let k = MachineKinematics::new(m.clone(), TOOL_LENGTH).unwrap();
    let p = read(&post.gcode, &k, name);
    let blocks = blocks(&p);
    let spans = spans(name, &moves, &blocks);
    assert!(spans.iter().all(|s| s.len() <= 1));
    // The tip bows off the chord while cutting, and the post's own measure of the bow
    // agrees with the reader's.
    let (tip, _) = deviations(&moves, &blocks, &spans, true);
    let unsplit = post.report.cutting.unsplit_tip;
    println!("{name}: one block per pose, tip {tip:.4} mm off the chord (post: {unsplit:.4})");
    assert!(tip > 0.05, "{tip}");
    assert!(
        (tip - unsplit).abs() < READ_TOL + TIP_TOL,
        "{tip} vs {unsplit}"
    );
}
