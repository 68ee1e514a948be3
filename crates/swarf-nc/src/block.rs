//! The one block writer of every post: the 3-axis post ([`crate::gcode_writer`]) and
//! the five-axis post of swarf-fiveaxis both emit their programs through it, for any
//! post description ([`crate::post::Post`]: LinuxCNC, Fanuc, Mach3, grbl, Heidenhain,
//! or a user's file).
//!
//! What it owns: the program frame (the post's header, begin, end and footer lines),
//! comments (parentheses and non-ASCII replaced, so one comment style fits every
//! control), block numbers, the safe modal line, tool change and spindle blocks, and
//! motion blocks with modal suppression. A motion block writes the motion word when
//! the motion changes (on every block for posts whose motion word is not modal, as
//! Heidenhain's `L`), each axis word only when its written text changes (so two
//! positions that round to the same word count as unchanged), and no block at all when
//! no axis word changed. Lengths are converted from mm to the output units and angles
//! from radians to degrees here, with the post's decimals and signs
//! ([`crate::number::format_decimal`]). Every value is checked before it is written:
//! lengths within the coordinate domain, feeds within the rate domain, angles finite
//! ([`crate::number::writable_length`]), so no program holds `inf` or a 300-digit word.
//! Arc blocks, in the post's `[arc]` convention, are written by [`arc`].

use crate::error::NcError;
use crate::number::{Units, format_decimal, writable_length, writable_rate, writable_spindle};
use crate::post::{Post, render};
use serde::{Deserialize, Serialize};

pub mod arc;
pub use arc::ArcBlock;

/// How feeds are written.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum FeedMode {
    /// G93: `F` is the inverse of each move's time.
    #[default]
    InverseTime,
    /// G94: `F` in length units per minute.
    UnitsPerMinute,
}

/// What an axis word holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WordKind {
    /// A length, given in mm, written in the output units.
    Length,
    /// An angle, given in radians, written in degrees.
    Angle,
}

/// The motion word of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionCode {
    /// Rapid (`G0`, Heidenhain `L ... FMAX`).
    Rapid,
    /// Straight feed (`G1`, Heidenhain `L ... F`).
    Linear,
    /// Clockwise arc (`G2`, Heidenhain `C ... DR-`), written by [`BlockWriter::arc`].
    ArcCw,
    /// Counter-clockwise arc (`G3`, Heidenhain `C ... DR+`).
    ArcCcw,
}

/// The `F` word of a motion block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// A feed rate in mm/min, written in the output units per minute when it changes.
    PerMinute(f64),
    /// An inverse time in 1/min (G93), written on every block.
    InverseTime(f64),
}

/// Writes a program block by block for a post (module doc).
#[derive(Debug, Clone)]
pub struct BlockWriter<'p> {
    post: &'p Post,
    units: Units,
    /// Axis letters, what they hold, and the text last written for each.
    axes: Vec<(char, WordKind, Option<String>)>,
    motion: Option<MotionCode>,
    feed: Option<String>,
    /// The next block number, when the post numbers blocks.
    block_number: Option<u64>,
    /// The program number given to [`BlockWriter::start`].
    program_number: u32,
    out: String,
    /// Lines written so far.
    lines: usize,
}

impl<'p> BlockWriter<'p> {
    /// A writer for `post` in `units`, for axes `axes` (letter and kind, in block
    /// order), with room for about `blocks` blocks.
    pub fn new(post: &'p Post, units: Units, axes: &[(char, WordKind)], blocks: usize) -> Self {
        BlockWriter {
            post,
            units,
            axes: axes.iter().map(|&(c, k)| (c, k, None)).collect(),
            motion: None,
            feed: None,
            block_number: post.numbers.as_ref().map(|n| n.start),
            program_number: 0,
            out: String::with_capacity(blocks * (12 * axes.len() + 12) + 512),
            lines: 0,
        }
    }

    /// Lines written so far: the number of the last one (from 1).
    pub fn lines(&self) -> usize {
        self.lines
    }

    /// A line without a block number (`%`, `O1000`).
    fn line(&mut self, text: &str) {
        self.out.push_str(text);
        self.out.push('\n');
        self.lines += 1 + text.matches('\n').count();
    }

    /// A block: the line with its block number when the post numbers blocks.
    fn block(&mut self, text: &str) {
        if let (Some(n), Some(numbers)) = (self.block_number, &self.post.numbers) {
            self.out.push_str(&numbers.prefix);
            self.out.push_str(&n.to_string());
            self.out.push(' ');
            self.block_number = Some(n.saturating_add(numbers.step));
        }
        self.line(text);
    }

    fn frame_values(&self, number: u32) -> [(&'static str, String); 2] {
        let digits = self.post.program.number_digits;
        [
            ("{number}", format!("{number:0digits$}")),
            ("{units}", self.post.units_word(self.units).to_string()),
        ]
    }

    fn frame_lines(&mut self, lines: &[String], number: u32, numbered: bool) {
        let values = self.frame_values(number);
        let values: Vec<_> = values.iter().map(|(k, v)| (*k, v.as_str())).collect();
        for l in lines {
            let text = render(l, &values);
            if numbered {
                self.block(&text);
            } else {
                self.line(&text);
            }
        }
    }

    /// Opens the program: the post's header lines (`%`, `O0012`) and begin blocks
    /// (`BEGIN PGM 12 MM`), with `program_number` for `{number}`.
    pub fn start(&mut self, program_number: u32) {
        let post = self.post;
        self.frame_lines(&post.program.header, program_number, false);
        self.frame_lines(&post.program.begin, program_number, true);
        self.program_number = program_number;
    }

    /// A comment block in the post's style: parentheses replaced by spaces and
    /// anything but printable ASCII by `?`; upper case where the post says so.
    pub fn comment(&mut self, text: &str) {
        let clean: String = text
            .chars()
            .map(|c| match c {
                '(' | ')' => ' ',
                c if c.is_ascii_graphic() || c == ' ' => c,
                _ => '?',
            })
            .collect();
        let c = &self.post.comment;
        let clean = if c.upper_case {
            clean.to_ascii_uppercase()
        } else {
            clean
        };
        let block = format!("{}{clean}{}", c.open, c.close);
        self.block(&block);
    }

    /// The post's safe modal line (none when the post has none), with the units and
    /// the feed mode.
    pub fn safe_modal(&mut self, feed_mode: FeedMode) {
        let modal = &self.post.modal;
        if modal.line.is_empty() {
            return;
        }
        let feed = match feed_mode {
            FeedMode::InverseTime => &modal.inverse_time,
            FeedMode::UnitsPerMinute => &modal.per_minute,
        };
        let text = render(
            &modal.line,
            &[
                ("{units}", self.post.units_word(self.units)),
                ("{feed_mode}", feed),
            ],
        );
        self.block(&text);
    }

    fn tool_blocks(&mut self, lines: &[String], tool: u32, rpm: f64) -> Result<(), NcError> {
        let speed = (writable_spindle(rpm)?.round() as u64).to_string();
        let tool = tool.to_string();
        for l in lines {
            let text = render(l, &[("{tool}", &tool), ("{speed}", &speed)]);
            self.block(&text);
        }
        Ok(())
    }

    /// The post's tool change blocks for tool `tool` at `rpm` (`T1 M6`, `TOOL CALL 1
    /// Z S5000`).
    ///
    /// # Errors
    /// [`NcError::InvalidOption`] when `rpm` is not a finite speed from 0 to 1e6 rpm.
    pub fn tool_change(&mut self, tool: u32, rpm: f64) -> Result<(), NcError> {
        let post = self.post;
        self.tool_blocks(&post.tool.change, tool, rpm)
    }

    /// Forgets the words last written, so the next motion block states the motion
    /// word, every axis and the feed (after a tool change, where the control may
    /// have moved).
    pub fn forget_position(&mut self) {
        for axis in &mut self.axes {
            axis.2 = None;
        }
        self.motion = None;
        self.feed = None;
    }

    /// The post's tool length offset blocks (`G43 H t`; none on controls without).
    pub fn length_offset(&mut self, tool: u32) {
        let post = self.post;
        let _ = self.tool_blocks(&post.tool.length_offset, tool, 0.0);
    }

    /// The post's spindle-on blocks, clockwise at `rpm` rounded to a whole number.
    ///
    /// # Errors
    /// [`NcError::InvalidOption`] when `rpm` is not a finite speed from 0 to 1e6 rpm.
    pub fn spindle_on(&mut self, rpm: f64) -> Result<(), NcError> {
        let post = self.post;
        self.tool_blocks(&post.tool.spindle_on, 0, rpm)
    }

    /// `value` with `decimals` in the post's number style (sign, decimal point).
    fn number(&self, value: f64, decimals: usize) -> String {
        let mut s = format_decimal(value, decimals);
        let w = &self.post.words;
        if !w.trailing_point && s.ends_with('.') {
            s.pop();
        }
        if w.plus_sign && !s.starts_with('-') {
            s.insert(0, '+');
        }
        s
    }

    /// The word of axis `k` at `value` (mm or radians) as written.
    fn word(&self, k: usize, value: f64) -> String {
        match self.axes[k].1 {
            WordKind::Length => self.number(
                self.units.from_mm(value),
                self.post.length_decimals(self.units),
            ),
            WordKind::Angle => self.number(value.to_degrees(), self.post.words.angle_decimals),
        }
    }

    fn check_position(
        index: usize,
        position: &[f64],
        axes: &[(char, WordKind, Option<String>)],
    ) -> Result<(), NcError> {
        for (&v, a) in position.iter().zip(axes) {
            match a.1 {
                WordKind::Length => {
                    writable_length(index, "machine position", v)?;
                }
                WordKind::Angle if !v.to_degrees().is_finite() => {
                    return Err(NcError::NonFinite {
                        index,
                        what: "machine angle",
                    });
                }
                WordKind::Angle => {}
            }
        }
        Ok(())
    }

    /// The `F` word of `feed`, if one is written.
    fn feed_word(&mut self, index: usize, feed: Option<Feed>) -> Result<Option<String>, NcError> {
        match feed {
            Some(Feed::PerMinute(mm_per_min)) => {
                writable_rate(index, "feed", mm_per_min)?;
                let decimals = self
                    .post
                    .length_decimals(self.units)
                    .min(self.post.words.feed_decimals);
                let f = self.unsigned(self.units.from_mm(mm_per_min), decimals);
                if self.feed.as_deref() == Some(f.as_str()) {
                    return Ok(None);
                }
                self.feed = Some(f.clone());
                Ok(Some(f))
            }
            Some(Feed::InverseTime(per_min)) => {
                if !(per_min.is_finite() && per_min > 0.0) {
                    return Err(NcError::NonFinite {
                        index,
                        what: "inverse-time feed",
                    });
                }
                let f = self.unsigned(per_min, self.post.words.inverse_time_decimals);
                self.feed = Some(f.clone());
                Ok(Some(f))
            }
            None => Ok(None),
        }
    }

    /// A positive value (a feed) in the post's style, without a plus sign.
    fn unsigned(&self, value: f64, decimals: usize) -> String {
        let s = self.number(value, decimals);
        s.strip_prefix('+').map_or(s.clone(), str::to_string)
    }

    /// A motion block to `position` (one value per axis, mm or radians): the motion
    /// word when it changed (or always, for posts whose motion word is not modal),
    /// the axis words that changed, the rapid suffix, and the feed word that `feed`
    /// gives (asked only when the block is written). Returns whether a block was
    /// written: none is when no axis word changed.
    ///
    /// # Errors
    /// [`NcError::NonFinite`] (move `index`) when a converted position is not finite;
    /// the error of `feed`.
    pub fn motion(
        &mut self,
        index: usize,
        code: MotionCode,
        position: &[f64],
        feed: impl FnOnce() -> Result<Option<Feed>, NcError>,
    ) -> Result<bool, NcError> {
        Self::check_position(index, position, &self.axes)?;
        let mut words = String::new();
        for (k, &value) in position.iter().enumerate().take(self.axes.len()) {
            let w = self.word(k, value);
            if self.axes[k].2.as_deref() != Some(w.as_str()) {
                push_word(&mut words, self.axes[k].0, &w);
                self.axes[k].2 = Some(w);
            }
        }
        if words.is_empty() {
            return Ok(false);
        }
        let mut block = self.motion_word(code);
        block.push_str(&words);
        let m = &self.post.motion;
        if code == MotionCode::Rapid && !m.rapid_suffix.is_empty() {
            block.push(' ');
            block.push_str(&m.rapid_suffix);
        }
        if let Some(f) = self.feed_word(index, feed()?)? {
            push_word(&mut block, 'F', &f);
        }
        self.block(&block);
        Ok(true)
    }

    /// The motion word of `code` and a space, when it is written: when the motion
    /// changed, or always for posts whose motion word is not modal.
    fn motion_word(&mut self, code: MotionCode) -> String {
        let m = &self.post.motion;
        if self.motion == Some(code) && m.modal {
            return String::new();
        }
        self.motion = Some(code);
        let arc = self.post.arc.as_ref();
        let word = match code {
            MotionCode::Rapid => &m.rapid,
            MotionCode::Linear => &m.linear,
            MotionCode::ArcCw => arc.map_or("", |a| &a.cw),
            MotionCode::ArcCcw => arc.map_or("", |a| &a.ccw),
        };
        format!("{word} ")
    }

    /// Closes the program (the post's end blocks and footer lines) and returns its
    /// text.
    pub fn finish(mut self) -> String {
        let post = self.post;
        let number = self.program_number;
        self.frame_lines(&post.program.end, number, true);
        self.frame_lines(&post.program.footer, number, false);
        self.out
    }
}

/// Appends word `letter value` to a block, after a space unless the block is empty.
fn push_word(block: &mut String, letter: char, value: &str) {
    if !block.is_empty() {
        block.push(' ');
    }
    block.push(letter);
    block.push_str(value);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xyz() -> [(char, WordKind); 3] {
        [
            ('X', WordKind::Length),
            ('Y', WordKind::Length),
            ('Z', WordKind::Length),
        ]
    }

    #[test]
    fn unchanged_words_and_blocks_are_suppressed() {
        let linuxcnc = Post::builtin("linuxcnc").unwrap();
        let mut w = BlockWriter::new(&linuxcnc, Units::Mm, &xyz(), 4);
        let none = || Ok(None);
        let feed = || Ok(Some(Feed::PerMinute(300.0)));
        assert!(
            w.motion(0, MotionCode::Rapid, &[1.0, 2.0, 3.0], none)
                .unwrap()
        );
        assert!(
            w.motion(1, MotionCode::Linear, &[1.0, 2.0, 0.5], feed)
                .unwrap()
        );
        assert!(
            w.motion(2, MotionCode::Linear, &[4.0, 2.0, 0.5], feed)
                .unwrap()
        );
        // Rounds to the same words: no block.
        assert!(
            !w.motion(3, MotionCode::Linear, &[4.00001, 2.0, 0.5], feed)
                .unwrap()
        );
        assert_eq!(
            w.finish(),
            "G0 X1. Y2. Z3.\nG1 Z0.5 F300.\nX4.\nM5\nM30\n%\n"
        );
    }

    #[test]
    fn inch_angles_and_inverse_time() {
        let fanuc = Post::builtin("fanuc").unwrap();
        let axes = [('X', WordKind::Length), ('A', WordKind::Angle)];
        let mut w = BlockWriter::new(&fanuc, Units::Inch, &axes, 2);
        w.start(12);
        w.comment("part (wave) é");
        let it = || Ok(Some(Feed::InverseTime(2.5)));
        assert!(w.motion(0, MotionCode::Linear, &[25.4, 0.5], it).unwrap());
        assert!(w.motion(1, MotionCode::Linear, &[50.8, 0.5], it).unwrap());
        let text = w.finish();
        assert_eq!(
            text,
            "%\nO0012\n(PART  WAVE  ?)\nG1 X1. A28.6479 F2.5\nX2. F2.5\nM5\nM30\n%\n"
        );
    }

    #[test]
    fn heidenhain_numbers_blocks_and_signs_words() {
        let post = Post::builtin("heidenhain").unwrap();
        let mut w = BlockWriter::new(&post, Units::Mm, &xyz(), 4);
        w.start(7);
        w.comment("a (b)");
        w.safe_modal(FeedMode::UnitsPerMinute);
        w.tool_change(3, 5000.0).unwrap();
        w.spindle_on(5000.0).unwrap();
        let none = || Ok(None);
        let feed = || Ok(Some(Feed::PerMinute(300.0)));
        w.motion(0, MotionCode::Rapid, &[1.0, -2.0, 0.0], none)
            .unwrap();
        w.motion(1, MotionCode::Linear, &[1.0, -2.0, -0.25], feed)
            .unwrap();
        w.motion(2, MotionCode::Linear, &[4.0, -2.0, -0.25], feed)
            .unwrap();
        assert_eq!(
            w.finish(),
            "0 BEGIN PGM 7 MM\n1 ; a  b \n2 TOOL CALL 3 Z S5000\n3 M3\n\
             4 L X+1 Y-2 Z+0 FMAX\n5 L Z-0.25 F300\n6 L X+4\n7 M5\n8 END PGM 7 MM\n"
        );
    }

    #[test]
    fn non_finite_positions_and_program_numbers_are_errors() {
        let linuxcnc = Post::builtin("linuxcnc").unwrap();
        let fanuc = Post::builtin("fanuc").unwrap();
        let mut w = BlockWriter::new(&linuxcnc, Units::Mm, &xyz(), 1);
        let e = w.motion(7, MotionCode::Rapid, &[f64::NAN, 0.0, 0.0], || Ok(None));
        assert!(matches!(e, Err(NcError::NonFinite { index: 7, .. })));
        let e = w.motion(8, MotionCode::Rapid, &[1e300, 0.0, 0.0], || Ok(None));
        assert!(matches!(e, Err(NcError::OutOfDomain { index: 8, .. })));
        let feed = || Ok(Some(Feed::PerMinute(f64::INFINITY)));
        let e = w.motion(9, MotionCode::Linear, &[1.0, 0.0, 0.0], feed);
        assert!(matches!(e, Err(NcError::NonFinite { index: 9, .. })));
        assert!(w.spindle_on(f64::NAN).is_err());
        let op = "test";
        let per_minute = FeedMode::UnitsPerMinute;
        assert!(fanuc.check(op, 0, per_minute, false).is_err());
        assert!(linuxcnc.check(op, 0, per_minute, false).is_ok());
    }
}
