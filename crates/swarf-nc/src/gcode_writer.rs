//! The 3-axis post: a tool path's moves as a program for any post description
//! ([`crate::post::Post`]: LinuxCNC, checked with its standalone interpreter
//! `rs274 -g`; Fanuc; Mach3; grbl; Heidenhain conversational; a user's file).
//!
//! Layout: the post's header and begin lines (`%`, Fanuc's `O` number, Heidenhain's
//! `BEGIN PGM`), comment lines naming part, tool and strategy, the safe modal line
//! (`G17 G21|G20 G40 G49 G80 G90 G94`), tool change (and length offset where the post
//! writes it in 3-axis programs), spindle on, the moves (only changed words, `F` when
//! it changes), the post's end blocks and footer. A move that changes no written
//! coordinate is dropped. The blocks are written by the one block writer of every
//! post, [`crate::block::BlockWriter`].

use crate::block::{BlockWriter, Feed, FeedMode, MotionCode, WordKind};
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
}

impl Default for GcodeOptions {
    fn default() -> Self {
        GcodeOptions {
            post: Post::linuxcnc(),
            units: Units::Mm,
            tool_number: 1,
            program_number: 1000,
            comments: Vec::new(),
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
/// the post's range.
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
    let axes = ['X', 'Y', 'Z'].map(|c| (c, WordKind::Length));
    let blocks = sections.iter().map(|s| s.moves.len()).sum();
    let mut w = BlockWriter::new(post, opts.units, &axes, blocks);
    w.start(opts.program_number);
    for c in &opts.comments {
        w.comment(c);
    }
    w.safe_modal(per_minute);
    let mut index = 0;
    for s in sections {
        for c in s.comments {
            w.comment(c);
        }
        w.tool_change(s.tool_number, s.feeds.spindle)?;
        if w.length_offset_3_axis() {
            w.length_offset(s.tool_number);
        }
        w.spindle_on(s.feeds.spindle)?;
        w.forget_position();
        for m in s.moves {
            check_move(index, m)?;
            let code = match m.kind {
                MoveKind::Rapid => MotionCode::Rapid,
                MoveKind::Feed => MotionCode::Linear,
            };
            let feed = (m.kind == MoveKind::Feed).then_some(Feed::PerMinute(m.feed));
            w.motion(index, code, m.to.cl.coords.as_slice(), || Ok(feed))?;
            index += 1;
        }
    }
    Ok(w.finish())
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
