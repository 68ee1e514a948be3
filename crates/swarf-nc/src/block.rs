//! The one block writer of every G-code post: the 3-axis post ([`crate::gcode_writer`])
//! and the five-axis post of swarf-fiveaxis both emit their programs through it.
//!
//! What it owns: the program frame (`%`, the Fanuc `O` number, `M5 M30 %`), comments
//! safe for both dialects, the safe modal line `G17 G21|G20 G40 G49 G80 G90 G93|G94`,
//! tool change and spindle words, and motion blocks with modal suppression. A motion
//! block writes `G0`/`G1` only when the motion changes, each axis word only when its
//! written text changes (so two positions that round to the same word count as
//! unchanged), and no block at all when no axis word changed. Lengths are converted
//! from mm to the output units and angles from radians to degrees here; every value
//! carries a decimal point ([`crate::number::format_decimal`]). Every value is checked
//! before it is written: lengths within the coordinate domain, feeds within the rate
//! domain, angles finite ([`crate::number::writable_length`]), so no program holds
//! `inf` or a 300-digit word.

use crate::error::NcError;
use crate::number::{Units, format_decimal, writable_length, writable_rate, writable_spindle};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// Decimal places of rotary words, degrees.
pub const ANGLE_DECIMALS: usize = 4;

/// Decimal places of inverse-time feed words (`F` in 1/min under G93).
pub const INVERSE_TIME_DECIMALS: usize = 4;

/// Most decimal places of a feed rate word (mm/min or in/min).
const FEED_DECIMALS: usize = 3;

/// Control family the program is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// LinuxCNC (RS274/NGC as its interpreter reads it).
    #[default]
    Linuxcnc,
    /// Fanuc-style: `O` program number, upper-case comments, `M06`.
    Fanuc,
}

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
    /// `G0`.
    Rapid,
    /// `G1`.
    Linear,
}

/// The `F` word of a motion block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// A feed rate in mm/min, written in the output units per minute when it changes.
    PerMinute(f64),
    /// An inverse time in 1/min (G93), written on every block.
    InverseTime(f64),
}

/// Writes a G-code program block by block (module doc).
#[derive(Debug, Clone)]
pub struct BlockWriter {
    dialect: Dialect,
    units: Units,
    /// Axis letters, what they hold, and the text last written for each.
    axes: Vec<(char, WordKind, Option<String>)>,
    motion: Option<MotionCode>,
    feed: Option<String>,
    out: String,
}

impl BlockWriter {
    /// A writer for axes `axes` (letter and kind, in block order), with room for
    /// about `blocks` blocks.
    pub fn new(dialect: Dialect, units: Units, axes: &[(char, WordKind)], blocks: usize) -> Self {
        BlockWriter {
            dialect,
            units,
            axes: axes.iter().map(|&(c, k)| (c, k, None)).collect(),
            motion: None,
            feed: None,
            out: String::with_capacity(blocks * (12 * axes.len() + 12) + 512),
        }
    }

    /// Checks a Fanuc program number (1..=9999; any number for LinuxCNC, which writes
    /// none).
    ///
    /// # Errors
    /// [`NcError::InvalidOption`] for a Fanuc program number out of range.
    pub fn check_program_number(dialect: Dialect, number: u32) -> Result<(), NcError> {
        if dialect == Dialect::Fanuc && !(1..=9999).contains(&number) {
            return Err(NcError::InvalidOption {
                field: "program_number",
                message: format!("expected 1..=9999, found {number}"),
            });
        }
        Ok(())
    }

    /// Opens the program: `%`, and on Fanuc the `O` program number.
    pub fn start(&mut self, program_number: u32) {
        self.out.push_str("%\n");
        if self.dialect == Dialect::Fanuc {
            let _ = writeln!(self.out, "O{program_number:04}");
        }
    }

    /// A comment line safe for both dialects: no parentheses, printable ASCII; upper
    /// case on Fanuc.
    pub fn comment(&mut self, text: &str) {
        let clean: String = text
            .chars()
            .map(|c| match c {
                '(' | ')' => ' ',
                c if c.is_ascii_graphic() || c == ' ' => c,
                _ => '?',
            })
            .collect();
        match self.dialect {
            Dialect::Linuxcnc => {
                let _ = writeln!(self.out, "({clean})");
            }
            Dialect::Fanuc => {
                let _ = writeln!(self.out, "({})", clean.to_ascii_uppercase());
            }
        }
    }

    /// The safe modal line: XY plane, units, no compensation, no length offset, no
    /// canned cycle, absolute, and the feed mode.
    pub fn safe_modal(&mut self, feed_mode: FeedMode) {
        let units = match self.units {
            Units::Mm => "G21",
            Units::Inch => "G20",
        };
        let feed = match feed_mode {
            FeedMode::InverseTime => "G93",
            FeedMode::UnitsPerMinute => "G94",
        };
        let _ = writeln!(self.out, "G17 {units} G40 G49 G80 G90 {feed}");
    }

    /// Tool change: `T t M6` (Fanuc `M06`).
    pub fn tool_change(&mut self, tool: u32) {
        let six = match self.dialect {
            Dialect::Linuxcnc => "M6",
            Dialect::Fanuc => "M06",
        };
        let _ = writeln!(self.out, "T{tool} {six}");
    }

    /// Tool length compensation from the tool table: `G43 H t`.
    pub fn length_offset(&mut self, tool: u32) {
        let _ = writeln!(self.out, "G43 H{tool}");
    }

    /// Spindle on, clockwise, at `rpm` rounded to a whole number.
    ///
    /// # Errors
    /// [`NcError::InvalidOption`] when `rpm` is not a finite speed from 0 to 1e6 rpm.
    pub fn spindle_on(&mut self, rpm: f64) -> Result<(), NcError> {
        let _ = writeln!(self.out, "S{} M3", writable_spindle(rpm)?.round() as u64);
        Ok(())
    }

    /// The words of `position` (one value per axis, mm or radians) as written.
    fn word(&self, k: usize, value: f64) -> String {
        match self.axes[k].1 {
            WordKind::Length => format_decimal(self.units.from_mm(value), self.units.decimals()),
            WordKind::Angle => format_decimal(value.to_degrees(), ANGLE_DECIMALS),
        }
    }

    /// A motion block to `position` (one value per axis, mm or radians): the motion
    /// word when it changed, the axis words that changed, and the feed word that
    /// `feed` gives (asked only when the block is written). Returns whether a block was
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
        for (&v, a) in position.iter().zip(&self.axes) {
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
        if self.motion != Some(code) {
            self.out.push_str(match code {
                MotionCode::Rapid => "G0 ",
                MotionCode::Linear => "G1 ",
            });
            self.motion = Some(code);
        }
        self.out.push_str(&words);
        match feed()? {
            Some(Feed::PerMinute(mm_per_min)) => {
                writable_rate(index, "feed", mm_per_min)?;
                let decimals = self.units.decimals().min(FEED_DECIMALS);
                let f = format_decimal(self.units.from_mm(mm_per_min), decimals);
                if self.feed.as_deref() != Some(f.as_str()) {
                    push_word(&mut self.out, 'F', &f);
                    self.feed = Some(f);
                }
            }
            Some(Feed::InverseTime(per_min)) => {
                if !(per_min.is_finite() && per_min > 0.0) {
                    return Err(NcError::NonFinite {
                        index,
                        what: "inverse-time feed",
                    });
                }
                let f = format_decimal(per_min, INVERSE_TIME_DECIMALS);
                push_word(&mut self.out, 'F', &f);
                self.feed = Some(f);
            }
            None => {}
        }
        self.out.push('\n');
        Ok(true)
    }

    /// Closes the program (spindle off, `M30`, `%`) and returns its text.
    pub fn finish(mut self) -> String {
        self.out.push_str("M5\nM30\n%\n");
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
        let mut w = BlockWriter::new(Dialect::Linuxcnc, Units::Mm, &xyz(), 4);
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
        let axes = [('X', WordKind::Length), ('A', WordKind::Angle)];
        let mut w = BlockWriter::new(Dialect::Fanuc, Units::Inch, &axes, 2);
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
    fn non_finite_positions_and_program_numbers_are_errors() {
        let mut w = BlockWriter::new(Dialect::Linuxcnc, Units::Mm, &xyz(), 1);
        let e = w.motion(7, MotionCode::Rapid, &[f64::NAN, 0.0, 0.0], || Ok(None));
        assert!(matches!(e, Err(NcError::NonFinite { index: 7, .. })));
        let e = w.motion(8, MotionCode::Rapid, &[1e300, 0.0, 0.0], || Ok(None));
        assert!(matches!(e, Err(NcError::OutOfDomain { index: 8, .. })));
        let feed = || Ok(Some(Feed::PerMinute(f64::INFINITY)));
        let e = w.motion(9, MotionCode::Linear, &[1.0, 0.0, 0.0], feed);
        assert!(matches!(e, Err(NcError::NonFinite { index: 9, .. })));
        assert!(w.spindle_on(f64::NAN).is_err());
        assert!(BlockWriter::check_program_number(Dialect::Fanuc, 0).is_err());
        assert!(BlockWriter::check_program_number(Dialect::Linuxcnc, 0).is_ok());
    }
}
