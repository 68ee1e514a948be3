//! The rest regions over the part (top view): the design's relief in grey, what
//! detection found (the raw rest) outlined thin, each region's final boundary
//! (smoothed, merged, with its overlap) thick, numbered as in the reports.

use crate::canvas::Rgb;
use crate::error::ReportError;
use crate::page::{Legend, Page};
use crate::picture::{cells, relief};
use swarf_sim::Grid;

const WHITE: Rgb = [255, 255, 255];
const BOUNDARY: Rgb = [200, 20, 20];
const RAW: Rgb = [235, 130, 0];
const LABEL: Rgb = [120, 0, 0];

/// A rest region as drawn: rings in XY, mm.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RegionOutline {
    /// The final boundary's rings (outer first, then holes).
    pub boundary: Vec<Vec<[f64; 2]>>,
    /// The raw rest's rings.
    pub raw: Vec<Vec<[f64; 2]>>,
    /// The label drawn beside the boundary (the region's number).
    pub label: String,
}

/// The rest regions over the design heights `design` (per cell of `grid`, NaN off
/// the part) as PNG bytes, titled `title`, with `footer` lines below.
///
/// # Errors
/// [`ReportError::Write`] when PNG encoding fails.
pub fn rest_png(
    grid: &Grid,
    design: &[f64],
    regions: &[RegionOutline],
    title: &str,
    footer: &[String],
) -> Result<Vec<u8>, ReportError> {
    let max = grid.max();
    let mut rect = [grid.origin[0], grid.origin[1], max[0], max[1]];
    for p in regions.iter().flat_map(|r| r.boundary.iter().flatten()) {
        rect = [
            rect[0].min(p[0]),
            rect[1].min(p[1]),
            rect[2].max(p[0]),
            rect[3].max(p[1]),
        ];
    }
    let legend = Legend::Lines(&["region boundary", "detected rest"]);
    let page = Page::new(&cells(grid), rect, title, footer, &legend);
    let mut c = page.canvas(WHITE);
    relief(&mut c, &page.map, grid, design);
    let px = |p: &[f64; 2]| page.map.px(p[0], p[1]);
    for r in regions {
        for (rings, width, col) in [(&r.raw, 1.0, RAW), (&r.boundary, 2.5, BOUNDARY)] {
            for ring in rings {
                for w in ring.windows(2) {
                    c.line(px(&w[0]), px(&w[1]), width, col, None);
                }
            }
        }
        let top = r
            .boundary
            .iter()
            .flatten()
            .map(&px)
            .min_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
        if let Some([x, y]) = top {
            c.text(x as i64 + 4, y as i64 - 14, &r.label, 12.0, LABEL);
        }
    }
    page.draw(&mut c);
    for (r, col) in page.keys.iter().zip([BOUNDARY, RAW]) {
        let y = ((r[1] + r[3]) / 2) as f64;
        c.line([r[0] as f64, y], [r[2] as f64, y], 3.0, col, None);
    }
    c.to_png()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_are_drawn_over_the_relief() {
        let grid = Grid {
            origin: [0.0, 0.0],
            cell: 1.0,
            nx: 40,
            ny: 20,
        };
        let design: Vec<f64> = (0..800).map(|k| f64::from(k % 40)).collect();
        let square = |x: f64| {
            vec![
                [x, 5.0],
                [x + 5.0, 5.0],
                [x + 5.0, 10.0],
                [x, 10.0],
                [x, 5.0],
            ]
        };
        let regions = [RegionOutline {
            boundary: vec![square(10.0)],
            raw: vec![square(11.0)],
            label: "1".into(),
        }];
        let png = rest_png(&grid, &design, &regions, "rest", &["one region".into()]).unwrap();
        let buf = crate::canvas::decoded(&png);
        let px = &buf[..];
        let count = |c: Rgb| px.chunks(3).filter(|p| *p == c).count();
        assert!(
            count(BOUNDARY) > 100 && count(RAW) > 50,
            "{} {}",
            count(BOUNDARY),
            count(RAW)
        );
    }
}
