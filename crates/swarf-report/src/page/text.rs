//! Text on report pictures: label boxes, line wrapping, and axis tick labels.
//!
//! Text is the embedded font ([`crate::canvas`]) 16 px tall, 22 px a line. A label is
//! one line of text and the rectangle its line box covers (the font's advance widths
//! across, ascent to descent down), so a layout can be checked for overlaps before
//! anything is drawn. Long text wraps after spaces and commas, and inside a word only
//! where the word alone is wider than a line.
//! Axis ticks step by 1, 2 or 5 times a power of ten (the usual "nice numbers"), the
//! least such step from a sixth of the range up whose labels clear one another by
//! [`TICK_GAP`] at the map's scale.

use crate::canvas::Canvas;

/// Height of a line of text (ascent to descent), px.
pub(crate) const GLYPH: i64 = 16;
/// [`GLYPH`] as the canvas takes it.
pub(crate) const SIZE: f64 = GLYPH as f64;
/// Line pitch of wrapped text, px.
pub(crate) const LEAD: i64 = 22;
/// Least clear gap between neighbouring tick labels, px.
pub(crate) const TICK_GAP: i64 = 16;
/// Most ticks on one axis (a guard against degenerate ranges).
const MAX_TICKS: i64 = 100;

/// A rectangle of pixels, `[x0, y0, x1, y1)`.
pub(crate) type Rect = [i64; 4];

/// Whether two rectangles share a pixel.
pub(crate) fn overlap(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Whether `a` lies within `b`.
pub(crate) fn within(a: &Rect, b: &Rect) -> bool {
    a[0] >= b[0] && a[1] >= b[1] && a[2] <= b[2] && a[3] <= b[3]
}

/// Width of `s` in pixels.
pub(crate) fn tw(s: &str) -> i64 {
    Canvas::text_width(s, SIZE)
}

/// One line of text: its top-left corner and its characters.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Label {
    /// Top-left corner, px.
    pub at: [i64; 2],
    /// The characters.
    pub text: String,
}

impl Label {
    pub(crate) fn new(x: i64, y: i64, text: impl Into<String>) -> Label {
        Label {
            at: [x, y],
            text: text.into(),
        }
    }

    /// The pixels its character cells cover.
    pub(crate) fn rect(&self) -> Rect {
        let [x, y] = self.at;
        [x, y, x + tw(&self.text), y + GLYPH]
    }
}

/// 1, 2 or 5 times a power of ten, at least `raw`.
pub(crate) fn nice_step(raw: f64) -> f64 {
    let p = 10f64.powf(raw.max(1e-12).log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * p)
}

/// A number without trailing zeros.
pub(crate) fn trim(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// The multiples of `step` in `[lo, hi]`, labelled.
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<(f64, String)> {
    let first = (lo / step).ceil();
    let count = ((hi + 1e-9) / step).floor() - first + 1.0;
    if !(1.0..=MAX_TICKS as f64).contains(&count) {
        return Vec::new();
    }
    (0..count as i64)
        .map(|k| {
            let t = (first + k as f64) * step;
            (t, trim(t))
        })
        .collect()
}

/// Ticks over `[lo, hi]` at the least nice step (from a sixth of the range up) at
/// which labels `extent(label)` px long along the axis clear one another by
/// [`TICK_GAP`] at `ppmm`.
pub(crate) fn ticks(
    lo: f64,
    hi: f64,
    ppmm: f64,
    extent: impl Fn(&str) -> i64,
) -> Vec<(f64, String)> {
    let mut step = nice_step((hi - lo) / 6.0);
    for _ in 0..64 {
        let t = multiples(lo, hi, step);
        let widest = t.iter().map(|(_, s)| extent(s)).max().unwrap_or(0);
        if step * ppmm >= (widest + TICK_GAP) as f64 {
            return t;
        }
        step = nice_step(1.5 * step);
    }
    Vec::new()
}

/// `text` in lines at most `max` px wide: broken after spaces and commas, and inside
/// a word only where the word alone is wider than a line (a line holds at least one
/// character); spaces at either end of a line are dropped, and so are empty lines.
pub(crate) fn wrap(text: &str, max: i64) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    let mut push = |line: &str| {
        let l = line.trim();
        if !l.is_empty() {
            lines.push(l.to_string());
        }
    };
    for piece in text.split_inclusive([' ', ',']) {
        let joined = format!("{line}{piece}");
        if tw(joined.trim()) <= max {
            line = joined;
            continue;
        }
        push(&line);
        let mut rest: Vec<char> = piece.trim().chars().collect();
        while tw(&rest.iter().collect::<String>()) > max && rest.len() > 1 {
            let fits = (1..rest.len())
                .rev()
                .find(|&n| tw(&rest[..n].iter().collect::<String>()) <= max)
                .unwrap_or(1);
            push(&rest[..fits].iter().collect::<String>());
            rest.drain(..fits);
        }
        line = rest.into_iter().collect::<String>() + &piece[piece.trim_end().len()..];
    }
    push(&line);
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn ticks_widen_until_their_labels_clear() {
        let t: Vec<f64> = ticks(0.0, 100.0, 1.0, tw).iter().map(|t| t.0).collect();
        assert_eq!(t, [0.0, 50.0, 100.0]);
        let t: Vec<String> = ticks(-100.0, -4.0, 7.0, tw)
            .into_iter()
            .map(|t| t.1)
            .collect();
        assert_eq!(t, ["-100", "-80", "-60", "-40", "-20"]);
        assert!(ticks(1e6, 1e6, 1.0, tw).len() <= 1);
    }

    #[test]
    fn wrap_breaks_after_spaces_and_commas_and_inside_long_words() {
        assert_eq!(
            wrap("gouge: 37707 cells in 1 region", tw("gouge: 37707")),
            ["gouge: 37707", "cells in 1", "region"]
        );
        assert_eq!(
            wrap("apt:d=38.1,r=6.35,e=12.7", tw("apt:d=38.1,")),
            ["apt:d=38.1,", "r=6.35,", "e=12.7"]
        );
        assert_eq!(wrap("0000000000", tw("0000")), ["0000", "0000", "00"]);
        assert_eq!(wrap("00 0000000", tw("0000")), ["00", "0000", "000"]);
        assert!(wrap("   ", 30).is_empty());
        assert_eq!(wrap("short", 0), ["s", "h", "o", "r", "t"]);
    }

    #[test]
    fn scale_helpers() {
        assert_eq!(nice_step(33.0), 50.0);
        assert_eq!(nice_step(0.7), 1.0);
        assert_eq!(nice_step(15.0), 20.0);
        assert_eq!(trim(12.5), "12.5");
        assert_eq!(trim(-0.0), "0");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn wrapped_lines_fit_and_keep_every_character(
            text in "[a-z ,=.]{0,200}",
            max in 1i64..600,
        ) {
            let lines = wrap(&text, max);
            for l in &lines {
                prop_assert!(!l.is_empty() && (tw(l) <= max || l.chars().count() == 1), "{l:?}");
                prop_assert_eq!(l.trim(), l.as_str());
            }
            let squeeze = |s: &str| s.chars().filter(|c| *c != ' ').collect::<String>();
            prop_assert_eq!(squeeze(&lines.concat()), squeeze(&text));
        }
    }
}
