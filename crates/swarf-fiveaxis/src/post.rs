//! Five-axis programs: a tool path's moves as machine axis positions `X Y Z` and two
//! rotary words (`A C`, `B C`, ...), through a [`Machine`]'s inverse kinematics, for
//! any post description with rotary axes ([`swarf_nc::Post`]: LinuxCNC, Fanuc,
//! Mach3, Heidenhain; grbl has none and is refused, and so is inverse time on a post
//! without it).
//!
//! The program holds joint positions, as a control without tool-centre-point
//! management (LinuxCNC with trivkins, which `rs274` emulates) moves them: each block
//! moves all axes linearly. Passes are solved with [`solve_pass`] (continuity from the
//! previous pass's last position, limits); link moves take the rotary angles of the pass
//! they leave or enter (retracts keep the orientation of the pass end, the approach
//! already has that of the next pass start), so the rotary axes turn only on the rapid
//! at the clearance plane.
//!
//! **Between poses.** Moving its axes linearly, such a control would run the tool tip
//! over the part on a curve, not along the chord between two poses that the tool path
//! (and its APT CL) states: on the die's 2 mm steps, where C turns 7 degrees a step,
//! up to 0.15 mm off. Every move that turns a rotary axis (cutting moves, and the
//! links that turn the axes at the clearance plane) is therefore written as as many
//! blocks as keep the tip within [`PostOptions::path_tol`] of the chord and the axis
//! within [`PostOptions::path_angle_tol`] of the great circle ([`subdivide()`]): the
//! motion a tool-centre-point control would make. [`post_5x`] reports how many
//! blocks that added and the deviations before and after.
//!
//! Feeds: with [`FeedMode::InverseTime`] (G93) every `G1` carries `F = 1 / t`, `t` the
//! block's time in minutes: the length of the tool tip's path over the part in that
//! block over the feed rate, or the largest rotary step over `rotary_feed` when that
//! is longer (a turn on the spot), so that the tip moves over the part at the
//! programmed feed whatever the machine axes do. With [`FeedMode::UnitsPerMinute`] (G94) `F` is the feed rate, which
//! LinuxCNC applies to the `X Y Z` motion of the machine, not to the tip over the part.
//!
//! Table-table machines program the tool tip (`G43 H` tool length compensation);
//! machines with head axes program the head's reference point, the tool length being
//! part of the kinematics (`tool_length`), so no length compensation is active (`G49`).
//! Layout otherwise as the 3-axis post of swarf-nc, through the same block writer
//! ([`swarf_nc::BlockWriter`]): the post's header, comments, modal line, tool change,
//! spindle, moves with only changed words, the post's end and footer.

pub mod subdivide;

use crate::error::FiveAxisError;
use crate::machine::joints::solve_pass;
use crate::machine::kinematics::Joints;
use crate::machine::{Machine, MachineKind};
use subdivide::{PathTol, subdivide};
pub use subdivide::{PostReport, Stray};
pub use swarf_nc::block::FeedMode;
use swarf_nc::block::{BlockWriter, Feed, MotionCode, WordKind};
use swarf_nc::number::Units;
use swarf_nc::{NcError, Post};
use swarf_tool::Pose;
use swarf_toolpath::{Move, MoveKind, Toolpath};

/// What the five-axis post writes besides the moves.
#[derive(Debug, Clone, PartialEq)]
pub struct PostOptions {
    /// The post: how the control wants its program written.
    pub post: Post,
    /// Output units.
    pub units: Units,
    /// Tool number for the tool change (and the length offset).
    pub tool_number: u32,
    /// Program number (Fanuc `O`, Heidenhain program name), within the post's range.
    pub program_number: u32,
    /// Comment lines for the header.
    pub comments: Vec<String>,
    /// G93 or G94.
    pub feed_mode: FeedMode,
    /// Spindle gauge line to tool tip, mm (machines with head axes).
    pub tool_length: f64,
    /// Rotary speed for moves that only turn, degrees per minute.
    pub rotary_feed: f64,
    /// Largest distance of the tool tip from the planned chord between two poses while
    /// the machine moves its axes linearly, mm (module doc); `f64::INFINITY` writes one
    /// block per move.
    pub path_tol: f64,
    /// Largest angle of the tool axis from the planned great circle between two poses,
    /// radians; `f64::INFINITY` for any.
    pub path_angle_tol: f64,
}

/// Default [`PostOptions::path_tol`]: the default chordal tolerance of jobs, mm.
pub const DEFAULT_PATH_TOL: f64 = 0.01;

/// Default [`PostOptions::path_angle_tol`], 0.05 degrees, radians: at the edge of a
/// cutter of radius 12 mm the axis error moves the cutting point by 0.01 mm.
pub const DEFAULT_PATH_ANGLE_TOL: f64 = 0.05 * std::f64::consts::PI / 180.0;

impl Default for PostOptions {
    fn default() -> Self {
        PostOptions {
            post: Post::linuxcnc(),
            units: Units::Mm,
            tool_number: 1,
            program_number: 1000,
            comments: Vec::new(),
            feed_mode: FeedMode::InverseTime,
            tool_length: 0.0,
            rotary_feed: 3600.0,
            path_tol: DEFAULT_PATH_TOL,
            path_angle_tol: DEFAULT_PATH_ANGLE_TOL,
        }
    }
}

/// A five-axis program and what its subdivision did.
#[derive(Debug, Clone, PartialEq)]
pub struct Post5x {
    /// The G-code.
    pub gcode: String,
    /// The subdivision between poses.
    pub report: PostReport,
    /// The range `[least, greatest]` each rotary axis (in the machine's order) takes
    /// over the program, radians; `None` for a program without moves.
    pub rotary_ranges: Option<[[f64; 2]; 2]>,
    /// For each move of `toolpath.moves()`, the line of the G-code (from 1) where
    /// it ends: its last block, or the block before it where it changes no word.
    pub move_lines: Vec<usize>,
}

/// The machine axis positions at the end of every move of `moves =
/// toolpath.moves()`: per pass, the approach moves up to the feed onto its first pose
/// take that pose's angles, the cutting moves the solved poses, the retract the last
/// pose's angles.
///
/// # Errors
/// As [`solve_pass`], with the pass and point of the tool path; a link position out of
/// the linear travel names the pass and the move.
pub fn solve_moves(
    m: &Machine,
    toolpath: &Toolpath,
    moves: &[Move],
    tool_length: f64,
) -> Result<Vec<Joints>, FiveAxisError> {
    let mut out = Vec::with_capacity(moves.len());
    let mut last: Option<Joints> = None;
    let mut i = 0;
    for (k, pass) in toolpath.passes.iter().enumerate() {
        let poses: Vec<_> = pass.points.iter().map(|p| p.pose).collect();
        let js = solve_pass(m, &poses, last.as_ref(), tool_length, k)?;
        let (Some(first), Some(end)) = (js.first().copied(), js.last().copied()) else {
            continue;
        };
        let at = |mv: &Move, rotary: [f64; 2]| -> Result<Joints, FiveAxisError> {
            let j = Joints {
                linear: m.linear_for(&mv.to.cl, &rotary, tool_length),
                rotary,
            };
            check_travel(m, &j, k)?;
            Ok(j)
        };
        while let Some(mv) = moves.get(i) {
            i += 1;
            if mv.kind == MoveKind::Feed && mv.pass.is_none() {
                out.push(first);
                break;
            }
            out.push(at(mv, first.rotary)?);
        }
        for j in &js[1..] {
            out.push(*j);
            i += 1;
        }
        if let Some(mv) = moves.get(i) {
            out.push(at(mv, end.rotary)?);
            i += 1;
        }
        last = Some(end);
    }
    if out.len() != moves.len() {
        return Err(FiveAxisError::parameter(
            "moves",
            format!(
                "expected the {} moves of the tool path's own linking, found {}",
                out.len(),
                moves.len()
            ),
        ));
    }
    Ok(out)
}

fn check_travel(m: &Machine, j: &Joints, pass: usize) -> Result<(), FiveAxisError> {
    for (k, name) in ['X', 'Y', 'Z'].into_iter().enumerate() {
        let [lo, hi] = m.linear[k];
        if !(j.linear[k] >= lo && j.linear[k] <= hi) {
            return Err(FiveAxisError::Unreachable {
                pass,
                index: 0,
                axis: name.to_string(),
                message: format!(
                    "the link move to {:.4} mm is outside the travel [{lo}, {hi}]",
                    j.linear[k]
                ),
            });
        }
    }
    Ok(())
}

/// Writes `toolpath` as a five-axis G-code program for machine `m` (module doc).
///
/// # Units
/// Moves and feeds in mm and mm/min; converted to `opts.units`; angles in degrees.
///
/// # Errors
/// As [`post_5x`].
pub fn write_gcode_5x(
    m: &Machine,
    toolpath: &Toolpath,
    opts: &PostOptions,
) -> Result<String, FiveAxisError> {
    post_5x(m, toolpath, opts).map(|p| p.gcode)
}

/// Writes `toolpath` as a five-axis G-code program for machine `m` (module doc), with
/// the report of the blocks inserted between poses.
///
/// # Units
/// Moves and feeds in mm and mm/min; converted to `opts.units`; angles in degrees.
///
/// # Errors
/// [`FiveAxisError::Unreachable`] for poses the machine cannot reach (those of the
/// tool path, or between two of them);
/// [`FiveAxisError::Nc`] for non-finite values, a bad program number, or a post that
/// cannot express the program ([`NcError::Unsupported`]: no rotary axes, no inverse
/// time);
/// [`FiveAxisError::InvalidParameter`] for a non-positive rotary feed or path
/// tolerance, or a tool length that is not finite.
pub fn post_5x(
    m: &Machine,
    toolpath: &Toolpath,
    opts: &PostOptions,
) -> Result<Post5x, FiveAxisError> {
    check_options(opts)?;
    let moves = toolpath.moves();
    let joints = solve_moves(m, toolpath, &moves, opts.tool_length)?;
    let (blocks, report) = blocks(m, &moves, &joints, opts)?;
    let names = m.rotary_names();
    let axes = [
        ('X', WordKind::Length),
        ('Y', WordKind::Length),
        ('Z', WordKind::Length),
        (names[0], WordKind::Angle),
        (names[1], WordKind::Angle),
    ];
    let mut w = BlockWriter::new(&opts.post, opts.units, &axes, blocks.len());
    header(&mut w, m, toolpath, opts)?;
    let mut prev: Option<&Joints> = None;
    let mut move_lines = vec![0; moves.len()];
    for (index, b) in blocks.iter().enumerate() {
        let j = &b.joints;
        let position = [j.linear.x, j.linear.y, j.linear.z, j.rotary[0], j.rotary[1]];
        let code = match b.kind {
            MoveKind::Rapid => MotionCode::Rapid,
            MoveKind::Feed => MotionCode::Linear,
        };
        let feed = || match b.kind {
            MoveKind::Feed => feed(b, prev, opts, index).map(Some),
            MoveKind::Rapid => Ok(None),
        };
        w.motion(index, code, &position, feed)?;
        if let Some(line) = move_lines.get_mut(b.step) {
            *line = w.lines();
        }
        prev = Some(j);
    }
    let rotary_ranges = (!blocks.is_empty()).then(|| {
        std::array::from_fn(|k| {
            blocks
                .iter()
                .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], b| {
                    [lo.min(b.joints.rotary[k]), hi.max(b.joints.rotary[k])]
                })
        })
    });
    Ok(Post5x {
        gcode: w.finish(),
        report,
        rotary_ranges,
        move_lines,
    })
}

/// One block to write: a move, or a piece of one.
struct Written {
    /// Index of its move.
    step: usize,
    kind: MoveKind,
    /// The move's feed, mm/min.
    feed: f64,
    joints: Joints,
    /// Length of the tip's path over the part from the previous block's end, mm.
    length: f64,
}

/// The moves as blocks, subdivided between poses (module doc). Errors between two
/// poses name the pass and point of the move's end (for links, the last pass point
/// before them).
fn blocks(
    m: &Machine,
    moves: &[Move],
    joints: &[Joints],
    opts: &PostOptions,
) -> Result<(Vec<Written>, PostReport), FiveAxisError> {
    let tol = PathTol {
        tip: opts.path_tol,
        angle: opts.path_angle_tol,
    };
    let mut report = PostReport::default();
    let mut out = Vec::with_capacity(moves.len());
    let (mut pass, mut point) = (0, 0);
    let mut from: Option<(&Pose, &Joints)> = None;
    for (step, (mv, j)) in moves.iter().zip(joints).enumerate() {
        if let Some(k) = mv.pass {
            point = if k == pass { point + 1 } else { 1 };
            pass = k;
        }
        let written = |joints: Joints, length: f64| Written {
            step,
            kind: mv.kind,
            feed: mv.feed,
            joints,
            length,
        };
        let Some(start) = from.replace((&mv.to, j)) else {
            out.push(written(*j, 0.0));
            continue;
        };
        let s = subdivide(m, start, (&mv.to, j), opts.tool_length, &tol, pass, point)?;
        match mv.pass {
            Some(_) => report.cutting.add(&s),
            None => report.links.add(&s),
        }
        for b in &s.blocks {
            out.push(written(b.joints, b.deviation.length));
        }
    }
    Ok((out, report))
}

/// The `F` word of a feed block (module doc).
fn feed(
    b: &Written,
    prev: Option<&Joints>,
    opts: &PostOptions,
    index: usize,
) -> Result<Feed, NcError> {
    if !(b.feed.is_finite() && b.feed > 0.0) {
        return Err(NcError::NonFinite {
            index,
            what: "feed",
        });
    }
    match opts.feed_mode {
        FeedMode::UnitsPerMinute => Ok(Feed::PerMinute(b.feed)),
        FeedMode::InverseTime => {
            let turn = prev.map_or(0.0, |p| {
                (0..2)
                    .map(|k| (b.joints.rotary[k] - p.rotary[k]).abs().to_degrees())
                    .fold(0.0, f64::max)
            });
            let minutes = (b.length / b.feed).max(turn / opts.rotary_feed).max(1e-7);
            Ok(Feed::InverseTime((1.0 / minutes).max(1e-4)))
        }
    }
}

fn check_options(o: &PostOptions) -> Result<(), FiveAxisError> {
    o.post
        .check("five-axis program", o.program_number, o.feed_mode, true)?;
    if !(o.rotary_feed.is_finite() && o.rotary_feed > 0.0) {
        return Err(FiveAxisError::parameter(
            "rotary_feed",
            format!(
                "expected a rotary speed > 0 degrees/min, found {}",
                o.rotary_feed
            ),
        ));
    }
    for (field, v) in [
        ("path_tol", o.path_tol),
        ("path_angle_tol", o.path_angle_tol),
    ] {
        if v.is_nan() || v <= 0.0 {
            return Err(FiveAxisError::parameter(
                field,
                format!("expected a tolerance > 0 (or infinity for none), found {v}"),
            ));
        }
    }
    if !o.tool_length.is_finite() {
        return Err(FiveAxisError::parameter(
            "tool_length",
            "expected a finite length in mm",
        ));
    }
    Ok(())
}

fn header(
    w: &mut BlockWriter,
    m: &Machine,
    toolpath: &Toolpath,
    opts: &PostOptions,
) -> Result<(), FiveAxisError> {
    w.start(opts.program_number);
    for c in &opts.comments {
        w.comment(c);
    }
    w.comment(&format!("machine {}", m.name));
    w.safe_modal(opts.feed_mode);
    w.tool_change(opts.tool_number, toolpath.feeds.spindle)?;
    if m.kind == MachineKind::TableTable {
        w.length_offset(opts.tool_number);
    } else {
        w.comment(&format!(
            "tool length {} mm in the kinematics",
            opts.tool_length
        ));
    }
    Ok(w.spindle_on(toolpath.feeds.spindle)?)
}
