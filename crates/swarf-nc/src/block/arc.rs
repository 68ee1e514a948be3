//! Arc blocks in the post's `[arc]` convention ([`crate::post`]): `G2|G3 X Y [Z] I J`
//! (centre offsets from the start as the control knows it: the words last written,
//! so rounding moves the centre by at most one output unit), `G2|G3 X Y [Z] R`, or
//! Heidenhain's centre block `CC X Y` then `C X Y DR-|DR+`. Axis words follow the
//! same modal suppression as straight moves; the feed word as on a straight move.
//! An arc whose start is not known (no block since [`BlockWriter::forget_position`])
//! or whose written chord is shorter than ten output units is not written: the
//! caller writes its segments instead.

use super::{BlockWriter, Feed, MotionCode, WordKind, push_word};
use crate::error::NcError;
use crate::number::writable_length;
use crate::post::CenterForm;

/// An arc in the XY plane to write: its end and centre, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcBlock {
    /// End point (X, Y, Z), mm.
    pub end: [f64; 3],
    /// Centre (X, Y), mm.
    pub center: [f64; 2],
    /// Counter-clockwise seen from +Z (G3).
    pub ccw: bool,
}

/// Shortest written chord of an arc, in output units of the last decimal.
const MIN_CHORD_UNITS: f64 = 10.0;

impl BlockWriter<'_> {
    /// Whether the post writes arcs (it has an `[arc]` table) on X Y Z axes.
    pub fn writes_arcs(&self) -> bool {
        let xyz = self.axes.len() >= 3
            && self.axes[..3]
                .iter()
                .zip(['X', 'Y', 'Z'])
                .all(|(a, c)| a.0 == c && a.1 == WordKind::Length);
        self.post.arc.is_some() && xyz
    }

    /// The post's arc setup blocks (`G91.1`), for programs with arcs.
    pub fn arc_setup(&mut self) {
        let post = self.post;
        if let Some(a) = &post.arc {
            for l in &a.setup {
                self.block(l);
            }
        }
    }

    /// The written value of axis `k`, in output units, if known.
    fn written(&self, k: usize) -> Option<f64> {
        let text = self.axes[k].2.as_deref()?;
        text.strip_prefix('+').unwrap_or(text).parse().ok()
    }

    /// An arc block (module doc) from the last written position to `arc.end`, with
    /// the feed word `feed` gives. Returns whether it was written; when not, nothing
    /// was (the caller writes the segments).
    ///
    /// # Errors
    /// [`NcError::NonFinite`] or [`NcError::OutOfDomain`] (move `index`) for an end
    /// or centre that cannot be written; the error of `feed`.
    pub fn arc(
        &mut self,
        index: usize,
        arc: &ArcBlock,
        feed: impl FnOnce() -> Result<Option<Feed>, NcError>,
    ) -> Result<bool, NcError> {
        let post = self.post;
        let Some(words) = post.arc.as_ref().filter(|_| self.writes_arcs()) else {
            return Ok(false);
        };
        Self::check_position(index, &arc.end, &self.axes[..3])?;
        for c in arc.center {
            writable_length(index, "arc centre", c)?;
        }
        let (Some(sx), Some(sy), Some(_)) = (self.written(0), self.written(1), self.written(2))
        else {
            return Ok(false);
        };
        let end: Vec<String> = (0..3).map(|k| self.word(k, arc.end[k])).collect();
        let parse = |t: &str| t.strip_prefix('+').unwrap_or(t).parse::<f64>().ok();
        let (Some(ex), Some(ey)) = (parse(&end[0]), parse(&end[1])) else {
            return Ok(false);
        };
        let decimals = post.length_decimals(self.units);
        let unit = 10f64.powi(-(decimals as i32));
        if (ex - sx).hypot(ey - sy) < MIN_CHORD_UNITS * unit {
            return Ok(false);
        }
        let [cx, cy] = arc.center.map(|c| self.units.from_mm(c));
        let code = if arc.ccw {
            MotionCode::ArcCcw
        } else {
            MotionCode::ArcCw
        };
        if words.center == CenterForm::Cc {
            let mut block = words.center_block.clone();
            push_word(&mut block, 'X', &self.number(cx, decimals));
            push_word(&mut block, 'Y', &self.number(cy, decimals));
            self.block(&block);
        }
        let mut block = self.motion_word(code);
        let mut axes = String::new();
        for (k, w) in end.into_iter().enumerate() {
            if self.axes[k].2.as_deref() != Some(w.as_str()) {
                push_word(&mut axes, self.axes[k].0, &w);
                self.axes[k].2 = Some(w);
            }
        }
        block.push_str(&axes);
        match words.center {
            CenterForm::Ij => {
                push_word(&mut block, 'I', &self.number(cx - sx, decimals));
                push_word(&mut block, 'J', &self.number(cy - sy, decimals));
            }
            CenterForm::R => {
                let r = f64::midpoint((cx - sx).hypot(cy - sy), (cx - ex).hypot(cy - ey));
                push_word(&mut block, 'R', &self.unsigned(r, decimals));
            }
            CenterForm::Cc => {}
        }
        let suffix = if arc.ccw {
            &words.ccw_suffix
        } else {
            &words.cw_suffix
        };
        if !suffix.is_empty() {
            block.push(' ');
            block.push_str(suffix);
        }
        if let Some(f) = self.feed_word(index, feed()?)? {
            push_word(&mut block, 'F', &f);
        }
        self.block(&block);
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::Units;
    use crate::post::Post;

    fn write(post: &str, units: Units) -> String {
        let post = Post::builtin(post).unwrap();
        let axes = ['X', 'Y', 'Z'].map(|c| (c, WordKind::Length));
        let mut w = BlockWriter::new(&post, units, &axes, 4);
        let feed = || Ok(Some(Feed::PerMinute(254.0)));
        let none = || Ok(None);
        let quarter = ArcBlock {
            end: [0.0, 25.4, -2.54],
            center: [0.0, 0.0],
            ccw: true,
        };
        assert!(!w.arc(0, &quarter, feed).unwrap(), "start unknown");
        w.motion(0, MotionCode::Rapid, &[25.4, 0.0, -2.54], none)
            .unwrap();
        assert!(w.arc(1, &quarter, feed).unwrap());
        let back = ArcBlock {
            end: [25.4, 0.0, -2.54],
            ccw: false,
            ..quarter
        };
        assert!(w.arc(2, &back, feed).unwrap());
        w.finish()
    }

    #[test]
    fn each_center_form_is_written() {
        let t = write("linuxcnc", Units::Inch);
        assert!(
            t.starts_with("G0 X1. Y0. Z-0.1\nG3 X0. Y1. I-1. J0. F10.\nG2 X1. Y0. I0. J-1.\n"),
            "{t}"
        );
        let t = write("fanuc", Units::Mm);
        assert!(
            t.contains("G3 X0. Y25.4 R25.4 F254.\nG2 X25.4 Y0. R25.4\n"),
            "{t}"
        );
        let t = write("heidenhain", Units::Mm);
        assert!(
            t.starts_with(
                "0 L X+25.4 Y+0 Z-2.54 FMAX\n1 CC X+0 Y+0\n2 C X+0 Y+25.4 DR+ F254\n\
                 3 CC X+0 Y+0\n4 C X+25.4 Y+0 DR-\n"
            ),
            "{t}"
        );
    }
}
