//! A small RGB raster for report pictures: rectangles, lines (solid or dashed, any
//! width), rings, and text in the public-domain 8x8 bitmap font (`font8x8`, from
//! Daniel Hepper's font8x8_basic), encoded as PNG with the `png` crate. No TrueType
//! stack, no colour management: the pictures are diagrams.

use crate::error::ReportError;

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

    /// Text with its top-left corner at `(x, y)`, each font pixel `scale` pixels.
    /// Characters outside ASCII print as `?`.
    pub fn text(&mut self, x: i64, y: i64, s: &str, scale: i64, c: Rgb) {
        for (n, ch) in s.chars().enumerate() {
            let code = if ch.is_ascii() {
                ch as usize
            } else {
                '?' as usize
            };
            let glyph = font8x8::legacy::BASIC_LEGACY[code];
            let gx = x + n as i64 * 8 * scale;
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    if bits >> col & 1 == 1 {
                        let (px, py) = (gx + col * scale, y + row as i64 * scale);
                        self.fill(px, py, px + scale, py + scale, c);
                    }
                }
            }
        }
    }

    /// Width of `s` in pixels at `scale`.
    pub fn text_width(s: &str, scale: i64) -> i64 {
        s.chars().count() as i64 * 8 * scale
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
        c.text(10, 0, "A", 1, [0, 0, 255]);
        let blue = (0..8).flat_map(|y| (10..18).map(move |x| (x, y)));
        assert!(
            blue.filter(|&(x, y)| c.get(x, y) == Some([0, 0, 255]))
                .count()
                > 10
        );
        let png = c.to_png().unwrap();
        assert_eq!(&png[1..4], b"PNG");
        assert!(Canvas::new(0, 0, [0; 3]).to_png().is_err());
        assert_eq!(Canvas::text_width("abc", 2), 48);
    }
}
