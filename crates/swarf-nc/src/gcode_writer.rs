//! RS274/NGC G-code post for 3-axis programs, in two dialects: LinuxCNC (checked
//! with its standalone interpreter `rs274 -g`) and Fanuc-style controls.
//!
//! Layout: `%`, (Fanuc: an `O` program number), comment lines naming part, tool and
//! strategy, a safe modal line `G17 G21|G20 G40 G49 G80 G90 G94`, tool change,
//! spindle on, the moves (`G0`/`G1`, only changed words, `F` when it changes), spindle
//! off, `M30`, `%`. A move that changes no written coordinate is dropped. Every value carries a decimal point (see [`crate::number`]).

use crate::error::NcError;
use crate::number::{Units, format_decimal};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use swarf_toolpath::{Feeds, Move, MoveKind};

/// Control family the program is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// LinuxCNC (RS274/NGC as its interpreter reads it).
    #[default]
    Linuxcnc,
    /// Fanuc-style: `O` program number, upper-case comments, `G43 H` length offset.
    Fanuc,
}

/// What the G-code post writes besides the moves.
#[derive(Debug, Clone, PartialEq)]
pub struct GcodeOptions {
    /// Control family.
    pub dialect: Dialect,
    /// Output units.
    pub units: Units,
    /// Tool number for `T` (and `H` on Fanuc).
    pub tool_number: u32,
    /// Fanuc program number (`O`), 1..=9999.
    pub program_number: u32,
    /// Comment lines for the header (part, tool, strategy, ...).
    pub comments: Vec<String>,
}

impl Default for GcodeOptions {
    fn default() -> Self {
        GcodeOptions {
            dialect: Dialect::Linuxcnc,
            units: Units::Mm,
            tool_number: 1,
            program_number: 1000,
            comments: Vec::new(),
        }
    }
}

/// Axis words tracked between blocks so that only changed values are written.
#[derive(Default)]
struct Modal {
    words: [Option<String>; 3],
    motion: Option<MoveKind>,
    feed: Option<String>,
}

/// Writes `moves` as a 3-axis G-code program.
///
/// # Units
/// Moves and feeds in mm and mm/min; converted to `opts.units` on output.
///
/// # Errors
/// [`NcError::NotThreeAxis`] when a pose's axis is not +Z, [`NcError::NonFinite`] for
/// NaN or infinite values, [`NcError::InvalidOption`] for a bad program number.
pub fn write_gcode(moves: &[Move], feeds: &Feeds, opts: &GcodeOptions) -> Result<String, NcError> {
    if opts.dialect == Dialect::Fanuc && !(1..=9999).contains(&opts.program_number) {
        return Err(NcError::InvalidOption {
            field: "program_number",
            message: format!("expected 1..=9999, found {}", opts.program_number),
        });
    }
    let mut out = String::with_capacity(moves.len() * 32 + 512);
    write_header(&mut out, feeds, opts);
    let mut modal = Modal::default();
    let decimals = opts.units.decimals();
    for (index, m) in moves.iter().enumerate() {
        check_move(index, m)?;
        let cl = m.to.cl;
        let mut words = String::new();
        let mut changed = [None, None, None];
        for (k, letter) in ['X', 'Y', 'Z'].into_iter().enumerate() {
            let w = format_decimal(opts.units.from_mm(cl[k]), decimals);
            if modal.words[k].as_deref() != Some(w.as_str()) {
                push_word(&mut words, letter, &w);
                changed[k] = Some(w);
            }
        }
        if words.is_empty() {
            continue;
        }
        for (k, w) in changed.into_iter().enumerate() {
            if w.is_some() {
                modal.words[k] = w;
            }
        }
        if modal.motion != Some(m.kind) {
            out.push_str(if m.kind == MoveKind::Rapid {
                "G0 "
            } else {
                "G1 "
            });
            modal.motion = Some(m.kind);
        }
        out.push_str(&words);
        if m.kind == MoveKind::Feed {
            let f = format_decimal(opts.units.from_mm(m.feed), decimals.min(3));
            if modal.feed.as_deref() != Some(f.as_str()) {
                push_word(&mut out, 'F', &f);
                modal.feed = Some(f);
            }
        }
        out.push('\n');
    }
    write_footer(&mut out);
    Ok(out)
}

fn push_word(block: &mut String, letter: char, value: &str) {
    if !block.is_empty() {
        block.push(' ');
    }
    block.push(letter);
    block.push_str(value);
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

/// A comment safe for both dialects: no parentheses, printable ASCII; upper case on Fanuc.
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

fn write_header(out: &mut String, feeds: &Feeds, opts: &GcodeOptions) {
    out.push_str("%\n");
    if opts.dialect == Dialect::Fanuc {
        let _ = writeln!(out, "O{:04}", opts.program_number);
    }
    for c in &opts.comments {
        out.push_str(&comment(c, opts.dialect));
        out.push('\n');
    }
    let units = match opts.units {
        Units::Mm => "G21",
        Units::Inch => "G20",
    };
    let _ = writeln!(out, "G17 {units} G40 G49 G80 G90 G94");
    let t = opts.tool_number;
    match opts.dialect {
        Dialect::Linuxcnc => {
            let _ = writeln!(out, "T{t} M6");
        }
        Dialect::Fanuc => {
            let _ = writeln!(out, "T{t} M06");
            let _ = writeln!(out, "G43 H{t}");
        }
    }
    let _ = writeln!(out, "S{} M3", feeds.spindle.round() as u64);
}

fn write_footer(out: &mut String) {
    out.push_str("M5\n");
    out.push_str("M30\n");
    out.push_str("%\n");
}
