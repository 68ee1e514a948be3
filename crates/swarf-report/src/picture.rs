//! Pictures a machinist reads at a glance: the deviation heat map over the part
//! (top view, diverging colours: red below the design, blue above; a legend in mm
//! with the tolerance marked; gouge regions ringed and labelled with their program
//! lines), and the tool path drawn over the part (feed moves solid, rapids dashed in
//! another colour).
//!
//! The colour scale ([`Scale`]) is set by robust percentiles: its ends are the 1st
//! and 99th percentiles of the measured deviations (at least twice the tolerance
//! either side, and above at least the allowed excess plus the tolerance, so that
//! the scallop crests a job allows are on the ramp), so one spot far off (a 0.73 mm
//! gouge, a false 19.8 mm excess on a STEP part's seam) does not wash the rest of the
//! map out to white; the cells past either end are drawn in colours of their own
//! (magenta below, cyan above) and counted in the footer. Cells within the tolerance, `|dev| <= tol`, are drawn
//! neutral grey: they are on the design as far as the check can tell, and a ramp
//! shade there would read as a small gouge or a thin skin. The ramp starts just past
//! the tolerance at a light tint, so "just out of tolerance" is never white.
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
use crate::page::text::SIZE;
use crate::page::{Bar, Cells, Legend, Page};
use swarf_sim::Grid;
use swarf_sim::report::count;
use swarf_sim::verify::Verification;
use swarf_toolpath::{Motion, MotionKind};

const BLACK: Rgb = [0, 0, 0];
const WHITE: Rgb = [255, 255, 255];
/// Cells off the part.
pub const OFF_PART: Rgb = [240, 240, 240];
/// Cells of the design where no stock was measured.
pub const NO_MATERIAL: Rgb = [110, 110, 110];
/// Cells within the tolerance, `|dev| <= tol` (module doc).
pub const NEUTRAL: Rgb = [185, 185, 185];
/// Cells deeper below the design than the scale's lower end.
pub const BEYOND_BELOW: Rgb = [235, 0, 190];
/// Cells higher above the design than the scale's upper end.
pub const BEYOND_ABOVE: Rgb = [0, 215, 230];
/// Where the ramp starts just past the tolerance (a light tint, not white).
const RAMP_START: f64 = 0.15;
/// Percentiles of the deviation at the scale's ends.
const PERCENTILES: [f64; 2] = [0.01, 0.99];
/// Least half-range of the scale, mm (a tolerance of zero).
const MIN_RANGE: f64 = 1e-6;
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

/// The deviation colour scale of a map (module doc), mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    /// The darkest red is at `-below` (> 0).
    pub below: f64,
    /// The darkest blue is at `above` (> 0).
    pub above: f64,
    /// Cells with `|dev| <= tol` are neutral.
    pub tol: f64,
}

impl Scale {
    /// The scale of `values` (NaN: not measured): the 1st and 99th percentiles of the
    /// finite ones, at least `2 tol` either side of zero and at least `allowed + tol`
    /// above it (`allowed`: the excess the job allows, its scallop limit; 0 for none).
    ///
    /// # Units
    /// mm.
    ///
    /// # Example
    /// ```
    /// use swarf_report::picture::Scale;
    /// let mut dev: Vec<f64> = (0..1000).map(|k| 0.05 * f64::from(k) / 1000.0).collect();
    /// dev[500] = 0.73;
    /// let s = Scale::of_values(&dev, 0.01, 0.0);
    /// assert!(s.above < 0.051 && s.below == 0.02);
    /// assert!((Scale::of_values(&dev, 0.01, 0.15).above - 0.16).abs() < 1e-12);
    /// ```
    pub fn of_values(values: &[f64], tol: f64, allowed: f64) -> Scale {
        let mut v: Vec<f64> = values.iter().copied().filter(|d| d.is_finite()).collect();
        let floor = (2.0 * tol).max(MIN_RANGE);
        let [lo, hi] = PERCENTILES.map(|p| {
            if v.is_empty() {
                return 0.0;
            }
            let k = ((p * (v.len() - 1) as f64).round() as usize).min(v.len() - 1);
            *v.select_nth_unstable_by(k, f64::total_cmp).1
        });
        Scale {
            below: (-lo).max(floor),
            above: hi.max(floor).max(allowed.max(0.0) + tol),
            tol: tol.max(0.0),
        }
    }

    /// The colour of a cell (or a pixel over several) whose picked deviation is
    /// `pick` (NaN: none measured): neutral within the tolerance, the diverging ramp
    /// from just past it to the scale's ends, the beyond colours past them; else
    /// dark grey where the design has no stock measured (`any_design`), light grey
    /// off the part. One scale for the PNG heat map and the glTF stock
    /// ([`crate::gltf`]).
    pub fn colour(&self, pick: f64, any_design: bool) -> Rgb {
        if !pick.is_finite() {
            return if any_design { NO_MATERIAL } else { OFF_PART };
        }
        let end = if pick < 0.0 { self.below } else { self.above };
        let a = pick.abs();
        if a <= self.tol {
            NEUTRAL
        } else if a > end {
            if pick < 0.0 {
                BEYOND_BELOW
            } else {
                BEYOND_ABOVE
            }
        } else {
            let f = (a - self.tol) / (end - self.tol).max(MIN_RANGE);
            diverging(pick.signum() * (RAMP_START + (1.0 - RAMP_START) * f))
        }
    }

    /// Cells of `values` past the scale's lower and upper ends.
    pub fn beyond(&self, values: &[f64]) -> [usize; 2] {
        let below = values.iter().filter(|&&d| d < -self.below).count();
        let above = values.iter().filter(|&&d| d > self.above).count();
        [below, above]
    }
}

/// The colour scale of the verification `v` ([`Scale::of_values`] over its
/// deviations, at its tolerance and allowed excess).
pub fn limits(v: &Verification) -> Scale {
    let s = &v.deviation.summary;
    Scale::of_values(&v.deviation.values, s.tol, s.allowed_excess)
}

/// The deviation heat map as PNG bytes.
///
/// # Errors
/// [`ReportError::Write`] when PNG encoding fails.
pub fn deviation_png(v: &Verification, title: &str) -> Result<Vec<u8>, ReportError> {
    let scale = limits(v);
    let s = &v.deviation.summary;
    let keys = [
        "|dev| \u{2264} tol".to_string(),
        format!("below \u{2212}{:.3}", scale.below),
        format!("above +{:.3}", scale.above),
        "off part".to_string(),
        "no stock".to_string(),
    ];
    let keys: Vec<&str> = keys.iter().map(String::as_str).collect();
    let legend = Legend::Bar {
        below: scale.below,
        above: scale.above,
        tol: s.tol,
        keys: &keys,
    };
    let max = v.grid.max();
    let rect = [v.grid.origin[0], v.grid.origin[1], max[0], max[1]];
    let page = Page::new(&cells(&v.grid), rect, title, &footer(v, &scale), &legend);
    let mut c = page.canvas(WHITE);
    heat_map(&mut c, &page.map, v, &scale);
    page.draw(&mut c);
    if let Some(bar) = &page.bar {
        colour_bar(&mut c, bar, &scale);
    }
    let swatches = [NEUTRAL, BEYOND_BELOW, BEYOND_ABOVE, OFF_PART, NO_MATERIAL];
    for (r, col) in page.keys.iter().zip(swatches) {
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
        c.text(l.at[0], l.at[1], &l.text, SIZE, BLACK);
    }
    c.to_png()
}

/// Each map pixel in the colour of the most extreme deviation of the cells under it,
/// grey where the design has no stock measured, light grey off the part.
fn heat_map(c: &mut Canvas, map: &Map, v: &Verification, scale: &Scale) {
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
            let col = scale.colour(pick, any_design);
            c.set(map.left + upx, map.top + vpx, col);
        }
    }
}

/// The colour bar's ramp (with the neutral band), frame, value ticks and tolerance
/// marks.
fn colour_bar(c: &mut Canvas, bar: &Bar, scale: &Scale) {
    let [x0, top, x1, foot] = bar.rect;
    let (mid, half) = ((top + foot) / 2, ((foot - top) / 2).max(1));
    for y in top..foot {
        let t = ((mid - y) as f64 / half as f64).clamp(-1.0, 1.0);
        let v = if t < 0.0 {
            t * scale.below
        } else {
            t * scale.above
        };
        c.fill(x0, y, x1, y + 1, scale.colour(v, true));
    }
    c.frame(x0 - 1, top - 1, x1, foot, BLACK);
    for &y in &bar.ticks {
        c.fill(x1, y, x1 + 8, y + 1, BLACK);
    }
    for &y in &bar.tols {
        c.fill(x0 - 6, y, x1 + 6, y + 1, BLACK);
    }
}

/// The figures under the heat map: gouge, then excess and scallop, then the scale.
fn footer(v: &Verification, scale: &Scale) -> Vec<String> {
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
    let [lo, hi] = scale.beyond(&v.deviation.values);
    let range = format!(
        "colour scale \u{2212}{:.3} to +{:.3} mm (the 1st and 99th percentiles, widened to \
         twice the tolerance and to the allowed excess): {} below it (magenta), {} \
         above it (cyan); grey within \u{00b1}{} mm",
        scale.below,
        scale.above,
        count(lo, "cell"),
        count(hi, "cell"),
        s.tol
    );
    vec![gouge, excess, range]
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

    /// Scallops up to 0.05 mm over 10 000 cells, and one spot of 25 cells at 0.73 mm.
    fn scalloped() -> Vec<f64> {
        let mut dev: Vec<f64> = (0..10_000)
            .map(|k| 0.05 * f64::from(k % 100) / 99.0)
            .collect();
        dev[..25].fill(0.73);
        dev[100] = -0.4;
        dev.push(f64::NAN);
        dev
    }

    #[test]
    fn one_outlier_does_not_stretch_the_scale() {
        let dev = scalloped();
        let s = Scale::of_values(&dev, 0.01, 0.0);
        assert!((0.045..=0.05).contains(&s.above), "{s:?}");
        assert_eq!(s.below, 0.02);
        assert_eq!(s.beyond(&dev), [1, 25]);
        assert_eq!(s.colour(0.73, true), BEYOND_ABOVE);
        assert_eq!(s.colour(-0.4, true), BEYOND_BELOW);
        // A 0.04 mm scallop is well into the blue, not near white.
        let c = s.colour(0.04, true);
        assert!(c[0] < 120 && c[2] > 150, "{c:?}");
        // All-NaN and zero tolerance still give a usable scale.
        let s = Scale::of_values(&[f64::NAN], 0.0, 0.0);
        assert!(s.below > 0.0 && s.above > 0.0);
        assert_eq!(s.colour(f64::NAN, false), OFF_PART);
        assert_eq!(s.colour(f64::NAN, true), NO_MATERIAL);
    }

    #[test]
    fn the_tolerance_band_is_neutral_grey_and_just_past_it_is_tinted() {
        let s = Scale {
            below: 0.1,
            above: 0.2,
            tol: 0.01,
        };
        for d in [-0.01, -0.004, 0.0, 0.009, 0.01] {
            assert_eq!(s.colour(d, true), NEUTRAL, "{d}");
        }
        let grey = |c: Rgb| c[0] == c[1] && c[1] == c[2];
        for d in [-0.0101, 0.0101] {
            let c = s.colour(d, true);
            assert!(!grey(c) && c != WHITE && c != [247; 3], "{d}: {c:?}");
        }
        assert_eq!(s.colour(-0.1, true), diverging(-1.0));
        assert_eq!(s.colour(0.2, true), diverging(1.0));
    }
}
