//! Five-axis RS274/NGC G-code: a tool path's moves as machine axis positions `X Y Z`
//! and two rotary words (`A C`, `B C`, ...), through a [`Machine`]'s inverse
//! kinematics.
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
//! Layout otherwise as the 3-axis post of swarf-nc: `%`, comments, modal line, tool
//! change, spindle, moves with only changed words, `M5`, `M30`, `%`.

pub mod subdivide;

use crate::error::FiveAxisError;
use crate::machine::joints::solve_pass;
use crate::machine::kinematics::Joints;
use crate::machine::{Machine, MachineKind};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use subdivide::{PathTol, subdivide};
pub use subdivide::{PostReport, Stray};
use swarf_nc::number::{Units, format_decimal};
use swarf_nc::{Dialect, NcError};
use swarf_tool::Pose;
use swarf_toolpath::{Move, MoveKind, Toolpath};

/// Decimal places of rotary words, degrees.
const ANGLE_DECIMALS: usize = 4;

/// How feeds are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FeedMode {
    /// G93: `F` is the inverse of each move's time.
    #[default]
    InverseTime,
    /// G94: `F` in length units per minute.
    UnitsPerMinute,
}

/// What the five-axis post writes besides the moves.
#[derive(Debug, Clone, PartialEq)]
pub struct PostOptions {
    /// Control family.
    pub dialect: Dialect,
    /// Output units.
    pub units: Units,
    /// Tool number for `T` (and `H`).
    pub tool_number: u32,
    /// Fanuc program number (`O`), 1..=9999.
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
            dialect: Dialect::Linuxcnc,
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
/// [`FiveAxisError::Nc`] for non-finite values or a bad program number;
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
    let mut out = String::with_capacity(blocks.len() * 48 + 512);
    header(&mut out, m, toolpath, opts);
    let names = m.rotary_names();
    let letters = ['X', 'Y', 'Z', names[0], names[1]];
    let mut modal: [Option<String>; 5] = Default::default();
    let mut motion = None;
    let mut feed_word: Option<String> = None;
    let mut prev: Option<&Joints> = None;
    for (index, b) in blocks.iter().enumerate() {
        let j = &b.joints;
        let values = [
            opts.units.from_mm(j.linear.x),
            opts.units.from_mm(j.linear.y),
            opts.units.from_mm(j.linear.z),
            j.rotary[0].to_degrees(),
            j.rotary[1].to_degrees(),
        ];
        if !values.iter().all(|v| v.is_finite()) {
            return Err(NcError::NonFinite {
                index,
                what: "machine position",
            }
            .into());
        }
        let mut words = String::new();
        for k in 0..5 {
            let decimals = if k < 3 {
                opts.units.decimals()
            } else {
                ANGLE_DECIMALS
            };
            let w = format_decimal(values[k], decimals);
            if modal[k].as_deref() != Some(w.as_str()) {
                push_word(&mut words, letters[k], &w);
                modal[k] = Some(w);
            }
        }
        if words.is_empty() {
            prev = Some(j);
            continue;
        }
        if motion != Some(b.kind) {
            out.push_str(if b.kind == MoveKind::Rapid {
                "G0 "
            } else {
                "G1 "
            });
            motion = Some(b.kind);
        }
        out.push_str(&words);
        if b.kind == MoveKind::Feed {
            let f = feed(b, prev, opts, index)?;
            if opts.feed_mode == FeedMode::InverseTime || feed_word.as_deref() != Some(f.as_str()) {
                push_word(&mut out, 'F', &f);
                feed_word = Some(f);
            }
        }
        out.push('\n');
        prev = Some(j);
    }
    out.push_str("M5\nM30\n%\n");
    Ok(Post5x { gcode: out, report })
}

/// One block to write: a move, or a piece of one.
struct Written {
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
    for (mv, j) in moves.iter().zip(joints) {
        if let Some(k) = mv.pass {
            point = if k == pass { point + 1 } else { 1 };
            pass = k;
        }
        let written = |joints: Joints, length: f64| Written {
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
) -> Result<String, FiveAxisError> {
    if !(b.feed.is_finite() && b.feed > 0.0) {
        return Err(NcError::NonFinite {
            index,
            what: "feed",
        }
        .into());
    }
    match opts.feed_mode {
        FeedMode::UnitsPerMinute => Ok(format_decimal(
            opts.units.from_mm(b.feed),
            opts.units.decimals().min(3),
        )),
        FeedMode::InverseTime => {
            let turn = prev.map_or(0.0, |p| {
                (0..2)
                    .map(|k| (b.joints.rotary[k] - p.rotary[k]).abs().to_degrees())
                    .fold(0.0, f64::max)
            });
            let minutes = (b.length / b.feed).max(turn / opts.rotary_feed).max(1e-7);
            Ok(format_decimal((1.0 / minutes).max(1e-4), 4))
        }
    }
}

fn push_word(block: &mut String, letter: char, value: &str) {
    if !block.is_empty() {
        block.push(' ');
    }
    block.push(letter);
    block.push_str(value);
}

fn check_options(o: &PostOptions) -> Result<(), FiveAxisError> {
    if o.dialect == Dialect::Fanuc && !(1..=9999).contains(&o.program_number) {
        return Err(NcError::InvalidOption {
            field: "program_number",
            message: format!("expected 1..=9999, found {}", o.program_number),
        }
        .into());
    }
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

/// A comment safe for both dialects.
fn comment(text: &str, dialect: Dialect) -> String {
    let clean: String = text
        .chars()
        .map(|c| match c {
            '(' | ')' => ' ',
            c if c.is_ascii_graphic() || c == ' ' => c,
            _ => '?',
        })
        .collect();
    match dialect {
        Dialect::Linuxcnc => format!("({clean})"),
        Dialect::Fanuc => format!("({})", clean.to_ascii_uppercase()),
    }
}

fn header(out: &mut String, m: &Machine, toolpath: &Toolpath, opts: &PostOptions) {
    out.push_str("%\n");
    if opts.dialect == Dialect::Fanuc {
        let _ = writeln!(out, "O{:04}", opts.program_number);
    }
    for c in &opts.comments {
        let _ = writeln!(out, "{}", comment(c, opts.dialect));
    }
    let _ = writeln!(
        out,
        "{}",
        comment(&format!("machine {}", m.name), opts.dialect)
    );
    let units = match opts.units {
        Units::Mm => "G21",
        Units::Inch => "G20",
    };
    let feed = match opts.feed_mode {
        FeedMode::InverseTime => "G93",
        FeedMode::UnitsPerMinute => "G94",
    };
    let _ = writeln!(out, "G17 {units} G40 G49 G80 G90 {feed}");
    let t = opts.tool_number;
    let six = if opts.dialect == Dialect::Fanuc {
        "M06"
    } else {
        "M6"
    };
    let _ = writeln!(out, "T{t} {six}");
    if m.kind == MachineKind::TableTable {
        let _ = writeln!(out, "G43 H{t}");
    } else {
        let note = format!("tool length {} mm in the kinematics", opts.tool_length);
        let _ = writeln!(out, "{}", comment(&note, opts.dialect));
    }
    let _ = writeln!(out, "S{} M3", toolpath.feeds.spindle.round() as u64);
}
