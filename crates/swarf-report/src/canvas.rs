//! A small RGB raster for report pictures: rectangles, lines (solid or dashed, any
//! width), rings, and anti-aliased text, encoded as PNG with the `png` crate. No
//! colour management: the pictures are diagrams.
//!
//! Text is DejaVu Sans, embedded (`fonts/`: a subset of under 10 KB holding ASCII and
//! the few signs the pictures print, with its licence), outlined and rasterised by
//! `ab_glyph`: each glyph's coverage of a pixel blends the text colour over what is
//! there, so labels read at small sizes and over the heat map, which a bitmap font
//! scaled up in whole pixels does not. A character the subset lacks prints as `?`.
//! Glyphs sit on the pen position rounded to whole pixels only at the start of a
//! label, so the advance widths add up as the font defines them.

use crate::error::ReportError;
use ab_glyph::{Font, FontRef, GlyphId, PxScale, ScaleFont, point};
use std::sync::OnceLock;

/// The embedded font (module doc).
const FONT: &[u8] = include_bytes!("../fonts/DejaVuSans-subset.ttf");

/// The parsed embedded font (`None` would draw no text; a test checks it parses).
fn font() -> Option<&'static FontRef<'static>> {
    static PARSED: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    PARSED
        .get_or_init(|| FontRef::try_from_slice(FONT).ok())
        .as_ref()
}

/// The glyph of `ch`, `?` where the font has none.
fn glyph_id(f: &FontRef<'static>, ch: char) -> GlyphId {
    match f.glyph_id(ch) {
        GlyphId(0) => f.glyph_id('?'),
        id => id,
    }
}

/// An RGB colour.
pub type Rgb = [u8; 3];

/// An RGB image, row-major from the top-left corner.
#[derive(Debug, Clone, PartialEq)]
pub struct Canvas {
    width: usize,
    height: usize,
    pixels: Vec<u8>,
}

impl Canvas {
    /// A `width x height` canvas filled with `background`.
    pub fn new(width: usize, height: usize, background: Rgb) -> Canvas {
        Canvas {
            width,
            height,
            pixels: background.repeat(width * height),
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The colour at `(x, y)`, if on the canvas.
    pub fn get(&self, x: usize, y: usize) -> Option<Rgb> {
        (x < self.width && y < self.height).then(|| {
            let k = 3 * (y * self.width + x);
            [self.pixels[k], self.pixels[k + 1], self.pixels[k + 2]]
        })
    }

    /// Sets `(x, y)` (ignored off the canvas).
    pub fn set(&mut self, x: i64, y: i64, c: Rgb) {
        if x >= 0 && y >= 0 && (x as usize) < self.width && (y as usize) < self.height {
            let k = 3 * (y as usize * self.width + x as usize);
            self.pixels[k..k + 3].copy_from_slice(&c);
        }
    }

    /// Fills the rectangle `[x0, x1) x [y0, y1)`.
    pub fn fill(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: Rgb) {
        for y in y0.max(0)..y1.min(self.height as i64) {
            for x in x0.max(0)..x1.min(self.width as i64) {
                self.set(x, y, c);
            }
        }
    }

    /// The outline of the rectangle `[x0, x1] x [y0, y1]`.
    pub fn frame(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: Rgb) {
        self.fill(x0, y0, x1 + 1, y0 + 1, c);
        self.fill(x0, y1, x1 + 1, y1 + 1, c);
        self.fill(x0, y0, x0 + 1, y1 + 1, c);
        self.fill(x1, y0, x1 + 1, y1 + 1, c);
    }

    /// A line from `a` to `b`, `width` pixels wide; with `dash = Some((on, off))`
    /// dashed in runs of pixels.
    pub fn line(&mut self, a: [f64; 2], b: [f64; 2], width: f64, c: Rgb, dash: Option<(f64, f64)>) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if !len.is_finite() {
            return;
        }
        let n = len.ceil().max(1.0) as usize;
        let r = (0.5 * width).max(0.5);
        let ri = r.ceil() as i64;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            if let Some((on, off)) = dash
                && (t * len) % (on + off) > on
            {
                continue;
            }
            let (x, y) = (a[0] + t * dx, a[1] + t * dy);
            for oy in -ri..=ri {
                for ox in -ri..=ri {
                    if ((ox * ox + oy * oy) as f64) <= r * r {
                        self.set(x.round() as i64 + ox, y.round() as i64 + oy, c);
                    }
                }
            }
        }
    }

    /// A ring of `radius` about `centre`, `width` pixels wide.
    pub fn ring(&mut self, centre: [f64; 2], radius: f64, width: f64, c: Rgb) {
        let n = (radius * 8.0).ceil().max(16.0) as usize;
        for k in 0..n {
            let a0 = std::f64::consts::TAU * k as f64 / n as f64;
            let a1 = std::f64::consts::TAU * (k + 1) as f64 / n as f64;
            let p = |a: f64| [centre[0] + radius * a.cos(), centre[1] + radius * a.sin()];
            self.line(p(a0), p(a1), width, c, None);
        }
    }

    /// Text `size` px tall (ascent to descent) with the top-left corner of its line
    /// box at `(x, y)`, anti-aliased over what is drawn (module doc).
    pub fn text(&mut self, x: i64, y: i64, s: &str, size: f64, c: Rgb) {
        let Some(f) = font() else { return };
        let scale = PxScale::from(size as f32);
        let scaled = f.as_scaled(scale);
        let baseline = y as f32 + scaled.ascent();
        let mut caret = x as f32;
        for ch in s.chars() {
            let id = glyph_id(f, ch);
            let glyph = id.with_scale_and_position(scale, point(caret, baseline));
            caret += scaled.h_advance(id);
            let Some(outline) = f.outline_glyph(glyph) else {
                continue;
            };
            let b = outline.px_bounds();
            let (x0, y0) = (b.min.x as i64, b.min.y as i64);
            outline.draw(|gx, gy, cover| {
                self.blend(x0 + i64::from(gx), y0 + i64::from(gy), c, f64::from(cover));
            });
        }
    }

    /// Mixes `c` into `(x, y)` with weight `alpha` in `[0, 1]` (ignored off the canvas).
    fn blend(&mut self, x: i64, y: i64, c: Rgb, alpha: f64) {
        let Some(old) = (x >= 0 && y >= 0)
            .then(|| self.get(x as usize, y as usize))
            .flatten()
        else {
            return;
        };
        let a = alpha.clamp(0.0, 1.0);
        let mix = |k: usize| {
            (f64::from(old[k]) + (f64::from(c[k]) - f64::from(old[k])) * a).round() as u8
        };
        self.set(x, y, [mix(0), mix(1), mix(2)]);
    }

    /// Width of `s` in whole pixels at `size` (as [`Canvas::text`] draws it).
    pub fn text_width(s: &str, size: f64) -> i64 {
        let Some(f) = font() else { return 0 };
        let scaled = f.as_scaled(PxScale::from(size as f32));
        let w: f32 = s.chars().map(|ch| scaled.h_advance(glyph_id(f, ch))).sum();
        w.ceil() as i64
    }

    /// The PNG file bytes.
    ///
    /// # Errors
    /// [`ReportError::Write`] when encoding fails (a zero-sized canvas).
    pub fn to_png(&self) -> Result<Vec<u8>, ReportError> {
        let err = |e: png::EncodingError| ReportError::Write {
            path: "<png>".into(),
            message: e.to_string(),
        };
        let mut out = Vec::new();
        {
            let w = u32::try_from(self.width).unwrap_or(0);
            let h = u32::try_from(self.height).unwrap_or(0);
            let mut enc = png::Encoder::new(&mut out, w, h);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            let mut writer = enc.write_header().map_err(err)?;
            writer.write_image_data(&self.pixels).map_err(err)?;
            writer.finish().map_err(err)?;
        }
        Ok(out)
    }
}

/// The pixels of a PNG as written (tests of the pictures read their colours back).
#[cfg(test)]
pub(crate) fn decoded(png: &[u8]) -> Vec<u8> {
    let mut reader = png::Decoder::new(std::io::Cursor::new(png))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_and_encodes() {
        let mut c = Canvas::new(40, 20, [255; 3]);
        c.fill(0, 0, 2, 2, [0, 0, 0]);
        assert_eq!(c.get(1, 1), Some([0, 0, 0]));
        assert_eq!(c.get(2, 2), Some([255; 3]));
        c.line(
            [0.0, 10.0],
            [39.0, 10.0],
            1.0,
            [255, 0, 0],
            Some((4.0, 4.0)),
        );
        assert_eq!(c.get(2, 10), Some([255, 0, 0]));
        assert_eq!(c.get(6, 10), Some([255; 3]));
        let png = c.to_png().unwrap();
        assert_eq!(&png[1..4], b"PNG");
        assert!(Canvas::new(0, 0, [0; 3]).to_png().is_err());
    }

    #[test]
    fn text_is_anti_aliased() {
        assert!(font().is_some(), "the embedded font parses");
        let mut c = Canvas::new(120, 24, [255; 3]);
        c.text(2, 2, "Ag 0.05 mm", 16.0, [0, 0, 0]);
        let greys: Vec<u8> = (0..24)
            .flat_map(|y| (0..120).map(move |x| (x, y)))
            .filter_map(|(x, y)| c.get(x, y).map(|p| p[0]))
            .collect();
        let full = greys.iter().filter(|&&g| g < 40).count();
        let partial = greys.iter().filter(|&&g| (40..215).contains(&g)).count();
        assert!(full > 20, "{full} dark pixels");
        assert!(partial > 20, "{partial} intermediate pixels");
        for row in [0, 1] {
            assert!(
                (0..120).all(|x| c.get(x, row) == Some([255; 3])),
                "row {row}"
            );
        }
        let w = Canvas::text_width("Ag 0.05 mm", 16.0);
        assert!((60..110).contains(&w), "{w}");
        assert!(Canvas::text_width("WWW", 16.0) > Canvas::text_width("iii", 16.0));
        assert_eq!(
            Canvas::text_width("\u{4e00}", 16.0),
            Canvas::text_width("?", 16.0)
        );
    }
}
