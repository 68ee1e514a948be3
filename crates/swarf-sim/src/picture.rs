//! Pictures a machinist reads at a glance: the deviation heat map over the part
//! (top view, diverging colours centred at zero: red below the design, blue above,
//! white on it; a legend in mm with the tolerance marked; gouge regions ringed and
//! labelled with their program lines), and the tool path drawn over the part (feed
//! moves solid, rapids dashed in another colour).
//!
//! When a pixel covers several cells it shows the most extreme deviation among them,
//! so that a gouge one cell wide still shows at any picture size.

use crate::canvas::{Canvas, Rgb};
use crate::error::SimError;
use crate::grid::Grid;
use crate::verify::Verification;
use swarf_nc::read::{Motion, MotionKind};

/// Largest map size, pixels.
const MAP_MAX: [f64; 2] = [1000.0, 700.0];
/// Margins: left, top, right (legend), bottom.
const MARGIN: [i64; 4] = [100, 60, 230, 110];
const BLACK: Rgb = [0, 0, 0];
const WHITE: Rgb = [255, 255, 255];
const OFF_PART: Rgb = [225, 225, 225];
const NO_MATERIAL: Rgb = [120, 120, 120];
/// Labelled gouge rings.
const LABELLED: usize = 8;

/// Where the map sits in the picture: the world rectangle `rect` (mm) drawn at
/// `ppmm` pixels per mm from `(left, top)`.
struct Layout {
    grid: Grid,
    rect: [f64; 4],
    left: i64,
    top: i64,
    ppmm: f64,
    w: i64,
    h: i64,
}

impl Layout {
    /// The layout showing `rect` (`[xmin, ymin, xmax, ymax]`, mm).
    fn new(grid: &Grid, rect: [f64; 4]) -> Layout {
        let (sx, sy) = ((rect[2] - rect[0]).max(1e-9), (rect[3] - rect[1]).max(1e-9));
        let ppmm = (MAP_MAX[0] / sx).min(MAP_MAX[1] / sy);
        Layout {
            grid: *grid,
            rect,
            left: MARGIN[0],
            top: MARGIN[1],
            ppmm,
            w: (sx * ppmm).round().max(1.0) as i64,
            h: (sy * ppmm).round().max(1.0) as i64,
        }
    }

    /// The layout showing the grid.
    fn of_grid(grid: &Grid) -> Layout {
        let max = grid.max();
        Layout::new(grid, [grid.origin[0], grid.origin[1], max[0], max[1]])
    }

    fn canvas(&self) -> Canvas {
        let w = self.left + self.w + MARGIN[2];
        let h = self.top + self.h.max(320) + MARGIN[3];
        Canvas::new(w as usize, h as usize, WHITE)
    }

    /// Picture coordinates of a point of the XY plane.
    fn px(&self, x: f64, y: f64) -> [f64; 2] {
        [
            self.left as f64 + (x - self.rect[0]) * self.ppmm,
            (self.top + self.h) as f64 - (y - self.rect[1]) * self.ppmm,
        ]
    }

    /// Cells under map pixel `(u, v)` (from the map's top-left): column and row
    /// ranges, `None` off the grid.
    fn cells(&self, u: i64, v: i64) -> Option<([usize; 2], [usize; 2])> {
        let g = &self.grid;
        let span = |a0: f64, a1: f64, origin: f64, n: usize| {
            let lo = ((a0 - origin) / g.cell).floor();
            let hi = ((a1 - origin) / g.cell).ceil();
            if hi <= 0.0 || lo >= n as f64 {
                return None;
            }
            let lo = lo.max(0.0) as usize;
            Some([lo, (hi as usize).clamp(lo + 1, n)])
        };
        let x0 = self.rect[0] + u as f64 / self.ppmm;
        let y0 = self.rect[1] + (self.h - 1 - v) as f64 / self.ppmm;
        let i = span(x0, x0 + 1.0 / self.ppmm, g.origin[0], g.nx)?;
        let j = span(y0, y0 + 1.0 / self.ppmm, g.origin[1], g.ny)?;
        Some((i, j))
    }

    /// Axes with ticks in mm, and the frame.
    fn axes(&self, c: &mut Canvas) {
        let r = self.rect;
        c.frame(
            self.left - 1,
            self.top - 1,
            self.left + self.w,
            self.top + self.h,
            BLACK,
        );
        for (axis, lo, hi) in [(0, r[0], r[2]), (1, r[1], r[3])] {
            let step = nice_step((hi - lo) / 6.0);
            let mut t = (lo / step).ceil() * step;
            while t <= hi + 1e-9 {
                let label = trim(t);
                if axis == 0 {
                    let [x, y] = self.px(t, r[1]);
                    c.fill(x as i64, y as i64, x as i64 + 1, y as i64 + 6, BLACK);
                    let tw = Canvas::text_width(&label, 2);
                    c.text(x as i64 - tw / 2, y as i64 + 10, &label, 2, BLACK);
                } else {
                    let [x, y] = self.px(r[0], t);
                    c.fill(x as i64 - 6, y as i64, x as i64, y as i64 + 1, BLACK);
                    let tw = Canvas::text_width(&label, 2);
                    c.text(x as i64 - 10 - tw, y as i64 - 8, &label, 2, BLACK);
                }
                t += step;
            }
        }
        c.text(
            self.left + self.w / 2 - 32,
            self.top + self.h + 34,
            "x, mm",
            2,
            BLACK,
        );
        c.text(8, self.top - 28, "y, mm", 2, BLACK);
    }
}

/// 1, 2 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let p = 10f64.powf(raw.max(1e-12).log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * p)
}

/// A number without trailing zeros.
fn trim(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

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

/// The colour scale's limits: `(below, above)`, both > 0, mm.
fn limits(v: &Verification) -> (f64, f64) {
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
/// [`SimError::Write`] when PNG encoding fails.
pub fn deviation_png(v: &Verification, title: &str) -> Result<Vec<u8>, SimError> {
    let lay = Layout::of_grid(&v.grid);
    let mut c = lay.canvas();
    let (below, above) = limits(v);
    let nx = v.grid.nx;
    let (dev, design) = (&v.deviation.values, &v.design.heights);
    for vpx in 0..lay.h {
        for upx in 0..lay.w {
            let Some(([i0, i1], [j0, j1])) = lay.cells(upx, vpx) else {
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
            let col = if pick.is_finite() {
                diverging(if pick < 0.0 {
                    pick / below
                } else {
                    pick / above
                })
            } else if any_design {
                NO_MATERIAL
            } else {
                OFF_PART
            };
            c.set(lay.left + upx, lay.top + vpx, col);
        }
    }
    lay.axes(&mut c);
    legend(&mut c, &lay, below, above, v.deviation.summary.tol);
    for (n, g) in v.deviation.summary.gouges.iter().enumerate() {
        let p = lay.px(g.at[0], g.at[1]);
        c.ring(p, 9.0, 2.0, BLACK);
        if let (true, Some(line)) = (n < LABELLED, g.line) {
            c.text(
                p[0] as i64 + 12,
                p[1] as i64 - 8,
                &format!("L{line}"),
                2,
                BLACK,
            );
        }
    }
    c.text(MARGIN[0], 14, title, 2, BLACK);
    footer(&mut c, &lay, v);
    c.to_png()
}

/// The vertical colour bar with ticks in mm and the tolerance marked.
fn legend(c: &mut Canvas, lay: &Layout, below: f64, above: f64, tol: f64) {
    let x = lay.left + lay.w + 40;
    let (top, h) = (lay.top, lay.h.max(320));
    let mid = top + h / 2;
    for y in top..top + h {
        let t = (mid - y) as f64 / (h / 2) as f64;
        c.fill(x, y, x + 28, y + 1, diverging(t));
    }
    c.frame(x - 1, top - 1, x + 28, top + h, BLACK);
    c.text(x - 8, top - 28, "dev, mm", 2, BLACK);
    let at = |value: f64| {
        if value >= 0.0 {
            mid - (value / above * (h / 2) as f64).round() as i64
        } else {
            mid + (-value / below * (h / 2) as f64).round() as i64
        }
    };
    for value in [above, 0.5 * above, 0.0, -0.5 * below, -below] {
        let label = if value == 0.0 {
            "0".to_string()
        } else {
            format!("{value:+.3}")
        };
        let y = at(value);
        c.fill(x + 28, y, x + 36, y + 1, BLACK);
        c.text(x + 40, y - 7, &label, 2, BLACK);
    }
    for value in [tol, -tol] {
        let y = at(value);
        c.fill(x - 6, y, x + 34, y + 1, BLACK);
    }
    c.text(x - 2, top + h + 8, &format!("tol {tol}"), 2, BLACK);
    let keys = [(OFF_PART, "off part"), (NO_MATERIAL, "no stock")];
    for (k, (col, label)) in keys.iter().enumerate() {
        let y = top + h + 34 + 24 * k as i64;
        c.fill(x, y, x + 16, y + 16, *col);
        c.frame(x, y, x + 16, y + 16, BLACK);
        c.text(x + 24, y, label, 2, BLACK);
    }
}

/// Two lines of figures under the map.
fn footer(c: &mut Canvas, lay: &Layout, v: &Verification) {
    let s = &v.deviation.summary;
    let gouge = match s.gouges.first() {
        Some(g) => format!(
            "gouge: {} cells in {} regions, deepest {:.4} mm{}",
            s.gouge.cells,
            s.gouge.regions,
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
        "excess > {:.3} mm: {} cells, {}",
        s.allowed_excess + s.tol,
        s.excess.cells,
        scallop
    );
    let y = lay.top + lay.h.max(320) + 60;
    c.text(MARGIN[0], y, &gouge, 2, BLACK);
    c.text(MARGIN[0], y + 22, &excess, 2, BLACK);
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

/// The tool path over the part (top view) as PNG bytes.
///
/// # Errors
/// [`SimError::Write`] when PNG encoding fails.
pub fn toolpath_png(
    v: &Verification,
    motions: &[Motion],
    title: &str,
) -> Result<Vec<u8>, SimError> {
    let max = v.grid.max();
    let mut rect = [v.grid.origin[0], v.grid.origin[1], max[0], max[1]];
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
    let rect = [rect[0] - pad, rect[1] - pad, rect[2] + pad, rect[3] + pad];
    let lay = Layout::new(&v.grid, rect);
    let mut c = lay.canvas();
    let design = &v.design.heights;
    let (lo, hi) = design
        .iter()
        .filter(|z| z.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &z| {
            (a.min(z), b.max(z))
        });
    let span = (hi - lo).max(1e-9);
    for vpx in 0..lay.h {
        for upx in 0..lay.w {
            let z = lay
                .cells(upx, vpx)
                .map_or(f64::NAN, |([i0, _], [j0, _])| design[j0 * v.grid.nx + i0]);
            let col = if z.is_finite() {
                let g = (175.0 + 70.0 * (z - lo) / span).round() as u8;
                [g, g, g]
            } else {
                WHITE
            };
            c.set(lay.left + upx, lay.top + vpx, col);
        }
    }
    const FEED: Rgb = [20, 60, 170];
    const RAPID: Rgb = [235, 120, 0];
    for m in motions {
        let rapid = matches!(m.kind, MotionKind::Rapid);
        let pts: Vec<[f64; 2]> = polyline(m).iter().map(|p| lay.px(p[0], p[1])).collect();
        for w in pts.windows(2) {
            if rapid {
                c.line(w[0], w[1], 1.0, RAPID, Some((6.0, 4.0)));
            } else {
                c.line(w[0], w[1], 1.0, FEED, None);
            }
        }
    }
    if let (Some(first), Some(last)) = (motions.first(), motions.last()) {
        c.ring(
            lay.px(first.end.cl.x, first.end.cl.y),
            6.0,
            3.0,
            [0, 160, 0],
        );
        c.ring(lay.px(last.end.cl.x, last.end.cl.y), 6.0, 3.0, [200, 0, 0]);
    }
    lay.axes(&mut c);
    let x = lay.left + lay.w + 40;
    let keys: [(Rgb, &str); 4] = [
        (FEED, "feed"),
        (RAPID, "rapid"),
        ([0, 160, 0], "start"),
        ([200, 0, 0], "end"),
    ];
    for (k, (col, label)) in keys.iter().enumerate() {
        let y = lay.top + 24 * k as i64;
        c.line(
            [x as f64, (y + 8) as f64],
            [(x + 24) as f64, (y + 8) as f64],
            3.0,
            *col,
            None,
        );
        c.text(x + 32, y, label, 2, BLACK);
    }
    c.text(MARGIN[0], 14, title, 2, BLACK);
    let p = &v.program;
    let text = format!(
        "{} motions, {} passes, cutting {:.0} mm, rapid {:.0} mm, time {}",
        p.motions,
        p.passes,
        p.cutting_length_mm,
        p.rapid_length_mm,
        crate::report::clock(p.time_s)
    );
    c.text(MARGIN[0], lay.top + lay.h.max(320) + 60, &text, 2, BLACK);
    c.to_png()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_helpers() {
        assert_eq!(nice_step(33.0), 50.0);
        assert_eq!(nice_step(0.7), 1.0);
        assert_eq!(nice_step(15.0), 20.0);
        assert_eq!(trim(12.5), "12.5");
        assert_eq!(trim(-0.0), "0");
        assert_eq!(diverging(0.0), [247, 247, 247]);
        assert_eq!(diverging(-1.0), [103, 0, 31]);
        assert_eq!(diverging(1.0), [5, 48, 97]);
        assert_eq!(diverging(7.0), [5, 48, 97]);
    }
}
