//! The 3-axis post: a tool path's moves as a program for any post description
//! ([`crate::post::Post`]: LinuxCNC, checked with its standalone interpreter
//! `rs274 -g`; Fanuc; Mach3; grbl; Heidenhain conversational; a user's file).
//!
//! Layout: the post's header and begin lines (`%`, Fanuc's `O` number, Heidenhain's
//! `BEGIN PGM`), comment lines naming part, tool and strategy, the safe modal line
//! (`G17 G21|G20 G40 G49 G80 G90 G94`), tool change and length offset (`T1 M6`,
//! `G43 H1`) for each tool, spindle on, the moves (only changed words, `F` when
//! it changes), the post's end blocks and footer. A move that changes no written
//! coordinate is dropped. The blocks are written by the one block writer of every
//! post, [`crate::block::BlockWriter`].
//!
//! With `arc_tolerance` set and a post that writes arcs, runs of feed moves at one
//! feed that lie on an arc or helix ([`crate::arc_fit`]) become arc blocks; rapids
//! never do.

use crate::arc_fit::{FittedArc, fit_arcs};
use crate::block::{ArcBlock, BlockWriter, Feed, FeedMode, MotionCode, WordKind};
use crate::error::NcError;
use crate::number::Units;
use crate::post::Post;
use swarf_toolpath::{Feeds, Move, MoveKind};

/// What the G-code post writes besides the moves.
#[derive(Debug, Clone, PartialEq)]
pub struct GcodeOptions {
    /// The post: how the control wants its program written.
    pub post: Post,
    /// Output units.
    pub units: Units,
    /// Tool number for the tool change (and the length offset).
    pub tool_number: u32,
    /// Program number (Fanuc `O`, Heidenhain program name), within the post's range.
    pub program_number: u32,
    /// Comment lines for the header (part, tool, strategy, ...).
    pub comments: Vec<String>,
    /// Arcs: fit them within this distance of the moves (mm, from
    /// [`MIN_ARC_TOLERANCE_MM`] to [`MAX_ARC_TOLERANCE_MM`]) where the post writes
    /// arcs; `None` writes straight moves only.
    pub arc_tolerance: Option<f64>,
}

/// Smallest arc tolerance, mm.
pub const MIN_ARC_TOLERANCE_MM: f64 = 1e-5;
/// Largest arc tolerance, mm.
pub const MAX_ARC_TOLERANCE_MM: f64 = 1.0;
/// The arc tolerance of jobs that ask for arcs without giving one, mm: above the
/// chord error of the arcs swarf's strategies sample (leads at 5 degrees a step,
/// round joins at 0.05 rad), since an arc can only be fitted to a polyline within
/// the polyline's own sagitta.
pub const DEFAULT_ARC_TOLERANCE_MM: f64 = 0.01;

impl Default for GcodeOptions {
    fn default() -> Self {
        GcodeOptions {
            post: Post::linuxcnc(),
            units: Units::Mm,
            tool_number: 1,
            program_number: 1000,
            comments: Vec::new(),
            arc_tolerance: None,
        }
    }
}

/// One tool's share of a program with several tools: its moves, feeds, T number
/// and the comments that open it.
#[derive(Debug, Clone, Copy)]
pub struct ToolSection<'a> {
    /// The moves, from the clearance plane back to it.
    pub moves: &'a [Move],
    /// Feeds and spindle speed.
    pub feeds: &'a Feeds,
    /// T number.
    pub tool_number: u32,
    /// Comment lines before its tool change.
    pub comments: &'a [String],
}

/// Writes `moves` as a 3-axis G-code program with one tool, `opts.tool_number`.
///
/// # Units
/// Moves and feeds in mm and mm/min; converted to `opts.units` on output.
///
/// # Errors
/// [`NcError::NotThreeAxis`] when a pose's axis is not +Z, [`NcError::NonFinite`] for
/// NaN or infinite values, [`NcError::InvalidOption`] for a program number outside
/// the post's range or an arc tolerance outside its domain.
pub fn write_gcode(moves: &[Move], feeds: &Feeds, opts: &GcodeOptions) -> Result<String, NcError> {
    let section = ToolSection {
        moves,
        feeds,
        tool_number: opts.tool_number,
        comments: &[],
    };
    write_gcode_sections(&[section], opts)
}

/// Writes a 3-axis G-code program of several tools: the header (`opts.comments`,
/// the safe modal line), then for each section its comments, the tool change, the
/// length offset (when the post writes it), the spindle and its moves, the first of
/// them stating the whole position. `opts.tool_number` is not used.
///
/// # Units
/// Moves and feeds in mm and mm/min; converted to `opts.units` on output.
///
/// # Errors
/// As [`write_gcode`]; a move's index counts over all sections.
pub fn write_gcode_sections(
    sections: &[ToolSection<'_>],
    opts: &GcodeOptions,
) -> Result<String, NcError> {
    let per_minute = FeedMode::UnitsPerMinute;
    let post = &opts.post;
    post.check("3-axis program", opts.program_number, per_minute, false)?;
    post.check_tools("3-axis program", sections.iter().map(|s| s.tool_number))?;
    let axes = ['X', 'Y', 'Z'].map(|c| (c, WordKind::Length));
    let blocks = sections.iter().map(|s| s.moves.len()).sum();
    let fit = match opts.arc_tolerance {
        Some(t) if (MIN_ARC_TOLERANCE_MM..=MAX_ARC_TOLERANCE_MM).contains(&t) => post.arc_fit(t),
        Some(t) => {
            return Err(NcError::InvalidOption {
                field: "arc_tolerance",
                message: format!(
                    "expected {MIN_ARC_TOLERANCE_MM} to {MAX_ARC_TOLERANCE_MM} mm, found {t}"
                ),
            });
        }
        None => None,
    };
    let mut w = BlockWriter::new(post, opts.units, &axes, blocks);
    w.start(opts.program_number);
    for c in &opts.comments {
        w.comment(c);
    }
    w.safe_modal(per_minute);
    if fit.is_some() {
        w.arc_setup();
    }
    let mut index = 0;
    for s in sections {
        for c in s.comments {
            w.comment(c);
        }
        w.tool_change(s.tool_number, s.feeds.spindle)?;
        w.length_offset(s.tool_number);
        w.spindle_on(s.feeds.spindle)?;
        w.forget_position();
        for (k, m) in s.moves.iter().enumerate() {
            check_move(index + k, m)?;
        }
        let arcs = fit.map_or_else(Vec::new, |f| section_arcs(s.moves, &f));
        let mut arcs = arcs.iter().peekable();
        let mut k = 0;
        while k < s.moves.len() {
            if let Some(&&(_, last, arc)) = arcs.peek().filter(|a| a.0 == k) {
                arcs.next();
                let m = &s.moves[last];
                let block = ArcBlock {
                    end: [m.to.cl.x, m.to.cl.y, m.to.cl.z],
                    center: arc.center,
                    ccw: arc.ccw,
                };
                let feed = Some(Feed::PerMinute(m.feed));
                if w.arc(index + last, &block, || Ok(feed))? {
                    k = last + 1;
                    continue;
                }
            }
            line(&mut w, index + k, &s.moves[k])?;
            k += 1;
        }
        index += s.moves.len();
    }
    Ok(w.finish())
}

/// A straight move's block.
fn line(w: &mut BlockWriter<'_>, index: usize, m: &Move) -> Result<bool, NcError> {
    let code = match m.kind {
        MoveKind::Rapid => MotionCode::Rapid,
        MoveKind::Feed => MotionCode::Linear,
    };
    let feed = (m.kind == MoveKind::Feed).then_some(Feed::PerMinute(m.feed));
    w.motion(index, code, m.to.cl.coords.as_slice(), || Ok(feed))
}

/// The arcs of a section's moves, as (first move, last move, arc), in order: fitted
/// on each run of feed moves at one feed, from the point before the run.
fn section_arcs(
    moves: &[Move],
    fit: &crate::arc_fit::ArcFitOptions,
) -> Vec<(usize, usize, FittedArc)> {
    let mut out = Vec::new();
    let mut i = 1;
    while i < moves.len() {
        let feed = moves[i].feed;
        let same = |m: &Move| m.kind == MoveKind::Feed && m.feed.to_bits() == feed.to_bits();
        if !same(&moves[i]) {
            i += 1;
            continue;
        }
        let mut j = i;
        while j + 1 < moves.len() && same(&moves[j + 1]) {
            j += 1;
        }
        let points: Vec<_> = moves[i - 1..=j].iter().map(|m| m.to.cl).collect();
        for a in fit_arcs(&points, fit) {
            out.push((i + a.start, i - 1 + a.end, a));
        }
        i = j + 1;
    }
    out
}

fn check_move(index: usize, m: &Move) -> Result<(), NcError> {
    if !m.to.cl.coords.iter().all(|c| c.is_finite()) {
        return Err(NcError::NonFinite {
            index,
            what: "CL point",
        });
    }
    if m.kind == MoveKind::Feed && !(m.feed.is_finite() && m.feed > 0.0) {
        return Err(NcError::NonFinite {
            index,
            what: "feed",
        });
    }
    let a = m.to.axis;
    if (a.x.abs() > 1e-9) || (a.y.abs() > 1e-9) || (a.z - 1.0).abs() > 1e-9 {
        return Err(NcError::NotThreeAxis {
            index,
            axis: [a.x, a.y, a.z],
        });
    }
    Ok(())
}
