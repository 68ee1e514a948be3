//! Bar charts for figures that have no map: one group of bars per category (a station
//! along an edge, an operation of a sequence), one bar per series, its value printed
//! above it, and a reference mark per category (a bound, a limit) drawn across the
//! group. The y axis starts at zero and ends at a nice step ([`crate::page`]'s tick
//! rule) above the largest value or mark.

use crate::canvas::{Canvas, Rgb};
use crate::error::ReportError;
use crate::page::text::{GLYPH, LEAD, SIZE, nice_step, trim, tw, wrap};

const WHITE: Rgb = [255, 255, 255];
const BLACK: Rgb = [0, 0, 0];
const GRID: Rgb = [225, 225, 230];
/// Bar colours by series (ColorBrewer Set2, darkened for text contrast).
const SERIES: [Rgb; 5] = [
    [27, 158, 119],
    [217, 95, 2],
    [117, 112, 179],
    [231, 41, 138],
    [102, 166, 30],
];
/// Canvas width, px.
const WIDTH: i64 = 960;
/// Plot height, px.
const PLOT_H: i64 = 300;
/// Margins: left (y labels), right (legend), px.
const MARGIN: [i64; 2] = [90, 250];

/// One series of bars.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend name.
    pub name: String,
    /// Value per category (NaN: no bar).
    pub values: Vec<f64>,
}

/// A bar chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// Title (wrapped).
    pub title: String,
    /// Name of the values, for the y axis (e.g. `mm left`).
    pub unit: String,
    /// Category labels, left to right.
    pub categories: Vec<String>,
    /// The series.
    pub series: Vec<Series>,
    /// The reference mark of each category (NaN: none) and its legend name.
    pub marks: Option<(String, Vec<f64>)>,
    /// Lines under the chart (each wrapped).
    pub footer: Vec<String>,
}

/// The chart as PNG bytes.
///
/// # Errors
/// [`ReportError::Write`] when PNG encoding fails.
pub fn chart_png(chart: &Chart) -> Result<Vec<u8>, ReportError> {
    let room = WIDTH - 2 * 16;
    let title = wrap(&chart.title, room);
    let top = 20 + LEAD * title.len() as i64 + 30;
    let (left, right) = (MARGIN[0], WIDTH - MARGIN[1]);
    let foot = top + PLOT_H;
    let footer: Vec<String> = chart.footer.iter().flat_map(|f| wrap(f, room)).collect();
    let height = foot + 2 * LEAD + 20 + LEAD * footer.len() as i64 + 16;
    let mut c = Canvas::new(WIDTH as usize, height as usize, WHITE);
    for (k, line) in title.iter().enumerate() {
        c.text(16, 16 + LEAD * k as i64, line, SIZE, BLACK);
    }
    let marks = chart.marks.as_ref();
    let highest = chart
        .series
        .iter()
        .flat_map(|s| s.values.iter())
        .chain(marks.into_iter().flat_map(|m| m.1.iter()))
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let step = nice_step((highest / 5.0).max(1e-9));
    let ymax = step * ((highest / step).floor() + 1.0);
    let y = |v: f64| foot - (v.max(0.0) / ymax * PLOT_H as f64).round() as i64;
    let mut t = 0.0;
    while t <= ymax + 1e-9 * ymax {
        let row = y(t);
        c.fill(left, row, right, row + 1, GRID);
        let label = trim(t);
        c.text(left - 10 - tw(&label), row - GLYPH / 2, &label, SIZE, BLACK);
        t += step;
    }
    c.text(16, top - 28, &chart.unit, SIZE, BLACK);
    let n = chart.categories.len().max(1) as i64;
    let group = (right - left) / n;
    let bars = chart.series.len().max(1) as i64;
    let bar = ((group * 3 / 4) / bars).max(2);
    for (k, cat) in chart.categories.iter().enumerate() {
        let x0 = left + group * k as i64 + (group - bar * bars) / 2;
        for (s, (series, colour)) in chart.series.iter().zip(SERIES.iter().cycle()).enumerate() {
            let v = series.values.get(k).copied().unwrap_or(f64::NAN);
            if !v.is_finite() {
                continue;
            }
            let bx = x0 + bar * s as i64;
            c.fill(bx + 1, y(v), bx + bar - 1, foot, *colour);
            let label = format!("{v:.3}");
            let lx = bx + bar / 2 - tw(&label) / 2;
            c.text(lx, y(v) - GLYPH - 2, &label, SIZE * 0.8, BLACK);
        }
        if let Some(m) = marks.and_then(|m| m.1.get(k)).filter(|m| m.is_finite()) {
            let row = y(*m);
            let (a, b) = (x0 - 6, x0 + bar * bars + 6);
            c.line(
                [a as f64, row as f64],
                [b as f64, row as f64],
                2.5,
                BLACK,
                Some((6.0, 4.0)),
            );
        }
        let cx = left + group * k as i64 + group / 2;
        let lines = wrap(cat, group - 8);
        for (j, line) in lines.iter().take(2).enumerate() {
            c.text(
                cx - tw(line) / 2,
                foot + 8 + LEAD * j as i64,
                line,
                SIZE,
                BLACK,
            );
        }
    }
    c.fill(left, top, left + 1, foot + 1, BLACK);
    c.fill(left, foot, right, foot + 1, BLACK);
    legend(&mut c, chart, right + 24, top);
    let y0 = foot + 2 * LEAD + 20;
    for (k, line) in footer.iter().enumerate() {
        c.text(16, y0 + LEAD * k as i64, line, SIZE, BLACK);
    }
    c.to_png()
}

/// The legend column at `(x, top)`: a swatch per series, then the mark's sample.
fn legend(c: &mut Canvas, chart: &Chart, x: i64, top: i64) {
    let mut row = top;
    for (series, colour) in chart.series.iter().zip(SERIES.iter().cycle()) {
        c.fill(x, row, x + 18, row + GLYPH, *colour);
        for line in wrap(&series.name, WIDTH - x - 40) {
            c.text(x + 26, row, &line, SIZE, BLACK);
            row += LEAD;
        }
        row += 6;
    }
    if let Some((name, _)) = &chart.marks {
        let mid = (row + GLYPH / 2) as f64;
        c.line(
            [x as f64, mid],
            [(x + 18) as f64, mid],
            2.5,
            BLACK,
            Some((6.0, 4.0)),
        );
        for line in wrap(name, WIDTH - x - 40) {
            c.text(x + 26, row, &line, SIZE, BLACK);
            row += LEAD;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_marks_and_labels_are_drawn() {
        let chart = Chart {
            title: "material left at the edge".into(),
            unit: "mm".into(),
            categories: vec!["25 mm".into(), "50 mm".into(), "75 mm".into()],
            series: vec![
                Series {
                    name: "drop and spin".into(),
                    values: vec![0.1, 0.12, f64::NAN],
                },
                Series {
                    name: "three-axis".into(),
                    values: vec![1.5, 1.4, 1.45],
                },
            ],
            marks: Some(("ball bound".into(), vec![0.05, 0.05, f64::NAN])),
            footer: vec!["tool bull d=12 r=2".into()],
        };
        let png = chart_png(&chart).unwrap();
        let buf = crate::canvas::decoded(&png);
        let px = &buf[..];
        let count = |c: Rgb| px.chunks(3).filter(|p| *p == c).count();
        assert!(
            count(SERIES[1]) > 5 * count(SERIES[0]),
            "taller bars, more pixels"
        );
        assert!(count(SERIES[0]) > 200);
        let dark = px
            .chunks(3)
            .filter(|p| p[0] < 60 && p[1] < 60 && p[2] < 60)
            .count();
        assert!(dark > 500, "{dark} text and axis pixels");
        let empty = Chart {
            categories: Vec::new(),
            series: Vec::new(),
            marks: None,
            ..chart
        };
        assert!(chart_png(&empty).is_ok());
    }
}
