//! Pictures a machinist reads at a glance: the deviation heat map over the part
//! (top view, diverging colours centred at zero: red below the design, blue above,
//! white on it; a legend in mm with the tolerance marked; gouge regions ringed and
//! labelled with their program lines), and the tool path drawn over the part (feed
//! moves solid, rapids dashed in another colour).
//!
//! When a pixel covers several cells it shows the most extreme deviation among them,
//! so that a gouge one cell wide still shows at any picture size.
//!
//! Each picture is laid out before it is drawn ([`crate::page`] places every line
//! of text as a box: the title and footer wrap, margins grow to fit their labels), so
//! no text overlaps other text, the map or the legend, or runs off the canvas.

use crate::canvas::{Canvas, Rgb};
use crate::error::ReportError;
use crate::page::map::Map;
use crate::page::text::SCALE;
use crate::page::{Bar, Cells, Legend, Page};
use swarf_sim::Grid;
use swarf_sim::report::count;
use swarf_sim::verify::Verification;
use swarf_toolpath::{Motion, MotionKind};

const BLACK: Rgb = [0, 0, 0];
const WHITE: Rgb = [255, 255, 255];
const OFF_PART: Rgb = [225, 225, 225];
const NO_MATERIAL: Rgb = [120, 120, 120];
/// Labelled gouge rings.
const LABELLED: usize = 8;
/// Radius of a gouge ring, px (drawn 2 px wide).
const RING: f64 = 9.0;

/// Diverging colour for `t` in `[-1, 1]`: red (below the design) - white - blue
/// (above), the ColorBrewer RdBu ramp.
pub fn diverging(t: f64) -> Rgb {
    const NEG: [Rgb; 4] = [
        [247, 247, 247],
        [244, 165, 130],
        [214, 96, 77],
        [103, 0, 31],
    ];
    const POS: [Rgb; 4] = [
        [247, 247, 247],
        [146, 197, 222],
        [67, 147, 195],
        [5, 48, 97],
    ];
    let ramp = if t < 0.0 { &NEG } else { &POS };
    let x = t.abs().min(1.0) * 3.0;
    let k = (x.floor() as usize).min(2);
    let f = x - k as f64;
    let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    [0, 1, 2].map(|c| mix(ramp[k][c], ramp[k + 1][c]))
}

/// The colour of a cell (or a pixel over several) whose picked deviation is `pick`
/// (NaN: none measured): the diverging ramp scaled by `below` (red side) and
/// `above` (blue side), else grey where the design has no stock measured
/// (`any_design`), light grey off the part. One scale for the PNG heat map and the
/// glTF stock ([`crate::gltf`]).
pub fn deviation_colour(pick: f64, any_design: bool, below: f64, above: f64) -> Rgb {
    if pick.is_finite() {
        diverging(if pick < 0.0 {
            pick / below
        } else {
            pick / above
        })
    } else if any_design {
        NO_MATERIAL
    } else {
        OFF_PART
    }
}

/// The colour scale's limits: `(below, above)`, both > 0, mm.
pub fn limits(v: &Verification) -> (f64, f64) {
    let s = &v.deviation.summary;
    let floor = 2.0 * s.tol;
    let above = s
        .scallop
        .max
        .unwrap_or(0.0)
        .max(s.allowed_excess + 2.0 * s.tol);
    let above = above.max(s.max.unwrap_or(0.0).min(4.0 * above)).max(floor);
    let below = (-s.min.unwrap_or(0.0)).max(floor);
    (below, above)
}

/// The deviation heat map as PNG bytes.
///
/// # Errors
/// [`ReportError::Write`] when PNG encoding fails.
pub fn deviation_png(v: &Verification, title: &str) -> Result<Vec<u8>, ReportError> {
    let (below, above) = limits(v);
    let s = &v.deviation.summary;
    let legend = Legend::Bar {
        below,
        above,
        tol: s.tol,
        keys: &["off part", "no stock"],
    };
    let max = v.grid.max();
    let rect = [v.grid.origin[0], v.grid.origin[1], max[0], max[1]];
    let page = Page::new(&cells(&v.grid), rect, title, &footer(v), &legend);
    let mut c = page.canvas(WHITE);
    heat_map(&mut c, &page.map, v, below, above);
    page.draw(&mut c);
    if let Some(bar) = &page.bar {
        colour_bar(&mut c, bar);
    }
    for (r, col) in page.keys.iter().zip([OFF_PART, NO_MATERIAL]) {
        c.fill(r[0], r[1], r[2] - 1, r[3] - 1, col);
        c.frame(r[0], r[1], r[2] - 1, r[3] - 1, BLACK);
    }
    let rings: Vec<[f64; 2]> = (s.gouges.iter())
        .map(|g| page.map.px(g.at[0], g.at[1]))
        .collect();
    for &p in &rings {
        c.ring(p, RING, 2.0, BLACK);
    }
    let marks: Vec<([f64; 2], String)> = (s.gouges.iter().zip(&rings))
        .take(LABELLED)
        .filter_map(|(g, &p)| g.line.map(|line| (p, format!("L{line}"))))
        .collect();
    for l in page.marks(&marks, &rings, RING + 1.0) {
        c.text(l.at[0], l.at[1], &l.text, SCALE, BLACK);
    }
    c.to_png()
}

/// Each map pixel in the colour of the most extreme deviation of the cells under it,
/// grey where the design has no stock measured, light grey off the part.
fn heat_map(c: &mut Canvas, map: &Map, v: &Verification, below: f64, above: f64) {
    let nx = v.grid.nx;
    let (dev, design) = (&v.deviation.values, &v.design.heights);
    for vpx in 0..map.h {
        for upx in 0..map.w {
            let Some(([i0, i1], [j0, j1])) = map.cells(upx, vpx) else {
                continue;
            };
            let (mut pick, mut any_design) = (f64::NAN, false);
            for j in j0..j1 {
                for i in i0..i1 {
                    let d = dev[j * nx + i];
                    any_design |= design[j * nx + i].is_finite();
                    if d.is_finite() && (pick.is_nan() || d.abs() > pick.abs()) {
                        pick = d;
                    }
                }
            }
            let col = deviation_colour(pick, any_design, below, above);
            c.set(map.left + upx, map.top + vpx, col);
        }
    }
}

/// The colour bar's ramp, frame, value ticks and tolerance marks.
fn colour_bar(c: &mut Canvas, bar: &Bar) {
    let [x0, top, x1, foot] = bar.rect;
    let (mid, half) = ((top + foot) / 2, ((foot - top) / 2).max(1));
    for y in top..foot {
        c.fill(x0, y, x1, y + 1, diverging((mid - y) as f64 / half as f64));
    }
    c.frame(x0 - 1, top - 1, x1, foot, BLACK);
    for &y in &bar.ticks {
        c.fill(x1, y, x1 + 8, y + 1, BLACK);
    }
    for &y in &bar.tols {
        c.fill(x0 - 6, y, x1 + 6, y + 1, BLACK);
    }
}

/// The figures under the heat map: gouge, then excess and scallop.
fn footer(v: &Verification) -> Vec<String> {
    let s = &v.deviation.summary;
    let gouge = match s.gouges.first() {
        Some(g) => format!(
            "gouge: {} in {}, deepest {:.4} mm{}",
            count(s.gouge.cells, "cell"),
            count(s.gouge.regions, "region"),
            g.worst,
            g.line.map_or(String::new(), |l| format!(" at line {l}"))
        ),
        None => format!("gouge: none below -{} mm", s.tol),
    };
    let scallop = match (s.scallop.p05, s.scallop.p95) {
        (Some(a), Some(b)) => format!("scallop {a:.3}-{b:.3} mm"),
        _ => "no scallop crests".into(),
    };
    let excess = format!(
        "excess > {:.3} mm: {}, {}",
        s.allowed_excess + s.tol,
        count(s.excess.cells, "cell"),
        scallop
    );
    vec![gouge, excess]
}

/// Straight pieces of a motion, in XY, for drawing.
fn polyline(m: &Motion) -> Vec<[f64; 2]> {
    let n = match m.kind {
        MotionKind::Arc { .. } => 32,
        _ => 1,
    };
    (0..=n)
        .map(|k| {
            let p = m.point_at(k as f64 / n as f64).cl;
            [p.x, p.y]
        })
        .collect()
}

/// The XY rectangle holding the grid and every motion, padded by 2 % of its longer
/// side.
fn path_rect(grid: &Grid, motions: &[Motion]) -> [f64; 4] {
    let max = grid.max();
    let mut rect = [grid.origin[0], grid.origin[1], max[0], max[1]];
    for m in motions {
        for p in polyline(m) {
            rect = [
                rect[0].min(p[0]),
                rect[1].min(p[1]),
                rect[2].max(p[0]),
                rect[3].max(p[1]),
            ];
        }
    }
    let pad = 0.02 * (rect[2] - rect[0]).max(rect[3] - rect[1]);
    [rect[0] - pad, rect[1] - pad, rect[2] + pad, rect[3] + pad]
}

/// The design (heights per cell of `grid`) in grey, lighter higher up, white off
/// the part.
pub(crate) fn relief(c: &mut Canvas, map: &Map, grid: &Grid, design: &[f64]) {
    let (lo, hi) = design
        .iter()
        .filter(|z| z.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    let span = (hi - lo).max(1e-9);
    for vpx in 0..map.h {
        for upx in 0..map.w {
            let z = map
                .cells(upx, vpx)
                .map_or(f64::NAN, |([i0, _], [j0, _])| design[j0 * grid.nx + i0]);
            let col = if z.is_finite() {
                let g = (175.0 + 70.0 * (z - lo) / span).round() as u8;
                [g, g, g]
            } else {
                WHITE
            };
            c.set(map.left + upx, map.top + vpx, col);
        }
    }
}

/// The tool path over the part (top view) as PNG bytes.
///
/// # Errors
/// [`ReportError::Write`] when PNG encoding fails.
pub fn toolpath_png(
    v: &Verification,
    motions: &[Motion],
    title: &str,
) -> Result<Vec<u8>, ReportError> {
    const FEED: Rgb = [20, 60, 170];
    const RAPID: Rgb = [235, 120, 0];
    const START: Rgb = [0, 160, 0];
    const END: Rgb = [200, 0, 0];
    let p = &v.program;
    let footer = format!(
        "{} motions, {} passes, cutting {:.0} mm, rapid {:.0} mm, time {}",
        p.motions,
        p.passes,
        p.cutting_length_mm,
        p.rapid_length_mm,
        swarf_sim::report::clock(p.time_s)
    );
    let legend = Legend::Lines(&["feed", "rapid", "start", "end"]);
    let rect = path_rect(&v.grid, motions);
    let page = Page::new(&cells(&v.grid), rect, title, &[footer], &legend);
    let mut c = page.canvas(WHITE);
    relief(&mut c, &page.map, &v.grid, &v.design.heights);
    for m in motions {
        let rapid = matches!(m.kind, MotionKind::Rapid);
        let pts: Vec<[f64; 2]> = polyline(m)
            .iter()
            .map(|p| page.map.px(p[0], p[1]))
            .collect();
        for w in pts.windows(2) {
            if rapid {
                c.line(w[0], w[1], 1.0, RAPID, Some((6.0, 4.0)));
            } else {
                c.line(w[0], w[1], 1.0, FEED, None);
            }
        }
    }
    if let (Some(first), Some(last)) = (motions.first(), motions.last()) {
        let ring = |m: &Motion| page.map.px(m.end.cl.x, m.end.cl.y);
        c.ring(ring(first), 6.0, 3.0, START);
        c.ring(ring(last), 6.0, 3.0, END);
    }
    page.draw(&mut c);
    for (r, col) in page.keys.iter().zip([FEED, RAPID, START, END]) {
        let y = ((r[1] + r[3]) / 2) as f64;
        c.line([r[0] as f64, y], [r[2] as f64, y], 3.0, col, None);
    }
    c.to_png()
}

/// The cells of the dexel grid, as a map shows them.
pub fn cells(grid: &Grid) -> Cells {
    Cells {
        origin: grid.origin,
        cell: grid.cell,
        nx: grid.nx,
        ny: grid.ny,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_ramp() {
        assert_eq!(diverging(0.0), [247, 247, 247]);
        assert_eq!(diverging(-1.0), [103, 0, 31]);
        assert_eq!(diverging(1.0), [5, 48, 97]);
        assert_eq!(diverging(7.0), [5, 48, 97]);
    }
}
