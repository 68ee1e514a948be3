//! The steep, horizontal and other areas over the part (top view, thesis 002 §6.1):
//! the design's relief in grey, each class's region tinted over it (steep red,
//! horizontal green, other dark grey) and outlined in a darker shade of its colour.
//!
//! Regions are filled by scanlines through the pixel centres with the even-odd rule
//! over all their rings, so holes stay clear; the classes' regions are disjoint, so
//! the tints never mix.

use crate::canvas::{Canvas, Rgb};
use crate::error::ReportError;
use crate::page::map::Map;
use crate::page::{Legend, Page};
use crate::picture::{cells, relief};
use swarf_sim::Grid;

const WHITE: Rgb = [255, 255, 255];
/// Fill and outline colour of each class, steep, horizontal, other.
const COLOURS: [(Rgb, Rgb); 3] = [
    ([220, 40, 40], [140, 0, 0]),
    ([40, 170, 70], [0, 100, 30]),
    ([100, 100, 110], [50, 50, 60]),
];
/// Weight of the class colour over the relief.
const TINT: f64 = 0.5;

/// One class's region as drawn: its rings in XY (outer and holes alike), mm.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ClassRings {
    /// Legend name of the class.
    pub name: String,
    /// The region's rings, each closed or not.
    pub rings: Vec<Vec<[f64; 2]>>,
}

/// The classes (steep, horizontal, other, in that order: the colours go by
/// position) over the design heights `design` (per cell of `grid`, NaN off the part)
/// as PNG bytes, titled `title`, with `footer` lines below.
///
/// # Errors
/// [`ReportError::Write`] when PNG encoding fails.
pub fn classify_png(
    grid: &Grid,
    design: &[f64],
    classes: &[ClassRings; 3],
    title: &str,
    footer: &[String],
) -> Result<Vec<u8>, ReportError> {
    let max = grid.max();
    let rect = [grid.origin[0], grid.origin[1], max[0], max[1]];
    let names: Vec<&str> = classes.iter().map(|c| c.name.as_str()).collect();
    let legend = Legend::Lines(&names);
    let page = Page::new(&cells(grid), rect, title, footer, &legend);
    let mut c = page.canvas(WHITE);
    relief(&mut c, &page.map, grid, design);
    for (class, (fill, _)) in classes.iter().zip(COLOURS) {
        tint(&mut c, &page.map, &class.rings, fill);
    }
    let px = |p: &[f64; 2]| page.map.px(p[0], p[1]);
    for (class, (_, line)) in classes.iter().zip(COLOURS) {
        for ring in &class.rings {
            let closing = ring.last().zip(ring.first());
            for (a, b) in ring.windows(2).map(|w| (&w[0], &w[1])).chain(closing) {
                c.line(px(a), px(b), 1.5, line, None);
            }
        }
    }
    page.draw(&mut c);
    for (r, (fill, line)) in page.keys.iter().zip(COLOURS) {
        c.fill(r[0], r[1] + 2, r[2], r[3] - 2, fill);
        c.frame(r[0], r[1] + 2, r[2], r[3] - 2, line);
    }
    c.to_png()
}

/// Blends `colour` into the map pixels whose centres lie inside `rings` (even-odd).
fn tint(c: &mut Canvas, map: &Map, rings: &[Vec<[f64; 2]>], colour: Rgb) {
    let mut xs = Vec::new();
    for v in 0..map.h {
        let y = map.rect[1] + ((map.h - 1 - v) as f64 + 0.5) / map.ppmm;
        xs.clear();
        for ring in rings {
            let n = ring.len();
            for k in 0..n {
                let (p, q) = (ring[k], ring[(k + 1) % n]);
                if (p[1] <= y) != (q[1] <= y) {
                    xs.push(p[0] + (y - p[1]) / (q[1] - p[1]) * (q[0] - p[0]));
                }
            }
        }
        xs.sort_by(f64::total_cmp);
        for span in xs.chunks_exact(2) {
            let u = |x: f64| ((x - map.rect[0]) * map.ppmm - 0.5).ceil() as i64;
            for upx in u(span[0]).max(0)..u(span[1]).min(map.w) {
                let (x, y) = (map.left + upx, map.top + v);
                if let Some(old) = c.get(x as usize, y as usize) {
                    let mix = |k: usize| {
                        (f64::from(old[k]) * (1.0 - TINT) + f64::from(colour[k]) * TINT).round()
                            as u8
                    };
                    c.set(x, y, [mix(0), mix(1), mix(2)]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_are_tinted_over_the_relief() {
        let grid = Grid {
            origin: [0.0, 0.0],
            cell: 1.0,
            nx: 40,
            ny: 20,
        };
        let design = vec![0.0; 800];
        let square = |x: f64| vec![[x, 5.0], [x + 8.0, 5.0], [x + 8.0, 15.0], [x, 15.0]];
        let hole = vec![[22.0, 8.0], [22.0, 12.0], [26.0, 12.0], [26.0, 8.0]];
        let classes = [
            ClassRings {
                name: "steep".into(),
                rings: vec![square(2.0)],
            },
            ClassRings {
                name: "horizontal".into(),
                rings: vec![square(20.0), hole],
            },
            ClassRings::default(),
        ];
        let png = classify_png(&grid, &design, &classes, "classes", &["footer".into()]).unwrap();
        let buf = crate::canvas::decoded(&png);
        let px = &buf[..];
        let count = |f: &dyn Fn([i32; 3]) -> bool| {
            px.chunks(3)
                .filter(|p| f([0, 1, 2].map(|k| i32::from(p[k]))))
                .count()
        };
        let red = count(&|p| p[0] > p[1] + 60 && p[0] > p[2] + 60);
        let green = count(&|p| p[1] > p[0] + 40 && p[1] > p[2] + 40);
        // The horizontal square has a hole of a fifth of its area.
        let ratio = green as f64 / red as f64;
        assert!(red > 1000 && (ratio - 0.8).abs() < 0.1, "{red} {green}");
    }
}
