//! Where everything sits on a report picture: the map (a world rectangle drawn at one
//! scale), its axes, the legend column right of it, the title above and the footer
//! below. Every piece of text is laid out as a rectangle before anything is drawn, so
//! a test can check that no two of them overlap, that none covers the map, the colour
//! bar or a legend key, and that all of them lie on the canvas.
//!
//! The title and the footer wrap to the canvas width (`text::wrap`); axis ticks are
//! spaced so that their labels clear one another (`text::ticks`); the left margin fits
//! the widest y label, and the legend column starts right of the map and of the x
//! labels; the top margin follows the title's lines and the footer starts below the
//! lowest label or legend key. Gouge labels go right, left, above or
//! below their ring, the first place inside the map clear of the labels before them
//! (worst first), or nowhere. All positions are integers computed from the inputs
//! alone, so a picture is byte-identical from run to run.

pub(crate) mod map;
pub(crate) mod text;

use crate::canvas::{Canvas, Rgb};
pub use map::Cells;
use map::Map;
use text::{GLYPH, LEAD, Label, Rect, SIZE, TICK_GAP, overlap, ticks, tw, within, wrap};

/// Margin kept at the canvas edges and between blocks, px.
const PAD: i64 = 8;
/// Least left margin, px (room for the y labels).
const MIN_LEFT: i64 = 100;
/// Least right margin, px (room for the legend column).
const MIN_RIGHT: i64 = 230;
/// Least canvas width, px, so that titles of narrow maps wrap into usable lines.
const MIN_WIDTH: i64 = 640;
/// Least height of the map's row (the colour bar's length), px.
const MIN_ROW: i64 = 320;
/// Colour bar width, px.
pub(crate) const BAR_W: i64 = 28;
const BLACK: Rgb = [0, 0, 0];

/// What the legend column shows.
pub(crate) enum Legend<'a> {
    /// A colour bar from `-below` to `+above` (mm) with `tol` marked, then swatches.
    Bar {
        /// Deviation at the bar's foot is `-below`, mm (> 0).
        below: f64,
        /// Deviation at the bar's head is `above`, mm (> 0).
        above: f64,
        /// Tolerance, mm.
        tol: f64,
        /// Names of the colour swatches below the bar.
        keys: &'a [&'a str],
    },
    /// A line sample per name, from the top.
    Lines(&'a [&'a str]),
}

/// The colour bar: its pixels and the rows of its marks.
pub(crate) struct Bar {
    /// The bar's pixels (its frame lies one pixel outside).
    pub rect: Rect,
    /// Rows of the value ticks, right of the bar.
    pub ticks: Vec<i64>,
    /// Rows of the tolerance marks, across the bar.
    pub tols: Vec<i64>,
}

/// Labels, colour bar and key samples of a legend column at `x`, from `top`, beside a
/// map row `row` px tall.
fn legend_column(
    legend: &Legend,
    x: i64,
    top: i64,
    row: i64,
) -> (Vec<Label>, Option<Bar>, Vec<Rect>) {
    match *legend {
        Legend::Bar {
            below,
            above,
            tol,
            keys,
        } => {
            let (mid, half) = (top + row / 2, (row / 2) as f64);
            let at = |v: f64| {
                let f = if v >= 0.0 { v / above } else { v / below };
                mid - (f.clamp(-1.0, 1.0) * half).round() as i64
            };
            let mut labels = vec![Label::new(x - 8, top - 28, "dev, mm")];
            let values = [above, 0.5 * above, 0.0, -0.5 * below, -below];
            for v in values {
                let text = if v == 0.0 {
                    "0".into()
                } else {
                    format!("{v:+.3}")
                };
                labels.push(Label::new(x + BAR_W + 12, at(v) - 7, text));
            }
            let y = top + row + 14;
            labels.push(Label::new(x - 2, y, format!("tol {tol}")));
            let mut swatches = Vec::new();
            for (k, name) in keys.iter().enumerate() {
                let ky = y + 26 + 24 * k as i64;
                swatches.push([x, ky, x + 17, ky + 17]);
                labels.push(Label::new(x + 24, ky, *name));
            }
            let bar = Bar {
                rect: [x, top, x + BAR_W, top + row],
                ticks: values.map(at).to_vec(),
                tols: [tol, -tol].map(at).to_vec(),
            };
            (labels, Some(bar), swatches)
        }
        Legend::Lines(names) => {
            let at = |k: usize| top + 24 * k as i64;
            let labels = names
                .iter()
                .enumerate()
                .map(|(k, name)| Label::new(x + 32, at(k), *name))
                .collect();
            let samples = (0..names.len())
                .map(|k| [x, at(k), x + 24, at(k) + GLYPH])
                .collect();
            (labels, None, samples)
        }
    }
}

/// Tick positions (x along the bottom, y along the left side) and their labels, and
/// the axis names.
fn axes(map: &Map, xt: &[(f64, String)], yt: &[(f64, String)]) -> ([Vec<i64>; 2], Vec<Label>) {
    let (mut pos, mut labels) = ([Vec::new(), Vec::new()], Vec::new());
    let foot = map.top + map.h;
    for (t, s) in xt {
        let x = map.px(*t, map.rect[1])[0] as i64;
        pos[0].push(x);
        labels.push(Label::new(x - tw(s) / 2, foot + 10, s.as_str()));
    }
    for (t, s) in yt {
        let y = map.px(map.rect[0], *t)[1] as i64;
        pos[1].push(y);
        labels.push(Label::new(map.left - 10 - tw(s), y - 8, s.as_str()));
    }
    let name = "x, mm";
    let x = (map.left + map.w / 2 - tw(name) / 2).max(PAD);
    labels.push(Label::new(x, foot + 34, name));
    labels.push(Label::new(PAD, map.top - 28, "y, mm"));
    (pos, labels)
}

/// A whole picture's layout.
pub(crate) struct Page {
    /// The map.
    pub map: Map,
    /// Canvas width and height, px.
    pub size: [i64; 2],
    /// Tick positions: columns along the map's foot, rows along its left side.
    pub ticks: [Vec<i64>; 2],
    /// Every line of text but the gouge labels.
    pub labels: Vec<Label>,
    /// The colour bar, if the legend has one.
    pub bar: Option<Bar>,
    /// Legend key samples (swatches or line samples), in legend order.
    pub keys: Vec<Rect>,
}

impl Page {
    /// The layout of a map of `rect` (mm) over `grid`, titled `title` (wrapped),
    /// with `legend` and the `footer` lines (each wrapped) below.
    pub(crate) fn new(
        grid: &Cells,
        rect: [f64; 4],
        title: &str,
        footer: &[String],
        legend: &Legend,
    ) -> Page {
        let mut map = Map::new(grid, rect);
        let xt = ticks(rect[0], rect[2], map.ppmm, tw);
        let yt = ticks(rect[1], rect[3], map.ppmm, |_| GLYPH);
        let widest = |t: &[(f64, String)]| t.iter().map(|(_, s)| tw(s)).max().unwrap_or(0);
        map.left = MIN_LEFT
            .max(PAD + widest(&yt) + 10)
            .max(PAD + widest(&xt) / 2 + 1);
        let row = map.h.max(MIN_ROW);
        let x_labels = axes(&map, &xt, &yt).1;
        let legend_x = x_labels
            .iter()
            .filter(|l| l.at[1] > map.top + map.h)
            .map(|l| l.rect()[2] + TICK_GAP)
            .fold(map.left + map.w + 40, i64::max);
        let legend_right = legend_column(legend, legend_x, 0, row)
            .0
            .iter()
            .map(|l| l.rect()[2])
            .fold(legend_x + BAR_W, i64::max);
        let width = (map.left + map.w + MIN_RIGHT)
            .max(legend_right + PAD)
            .max(MIN_WIDTH);
        let room = (width - map.left - PAD).max(1);
        let title = wrap(title, room);
        map.top = LEAD * title.len().max(1) as i64 + 38;
        let mut labels: Vec<Label> = (0..)
            .zip(title)
            .map(|(k, s)| Label::new(map.left, 14 + LEAD * k, s))
            .collect();
        let (ticks, axis) = axes(&map, &xt, &yt);
        let (legend, bar, keys) = legend_column(legend, legend_x, map.top, row);
        labels.extend(axis.into_iter().chain(legend));
        let y0 = labels
            .iter()
            .map(|l| l.rect()[3])
            .chain(keys.iter().map(|r| r[3]))
            .fold(map.top + row + 1, i64::max)
            + 12;
        let lines = footer.iter().flat_map(|f| wrap(f, room));
        labels.extend(
            (0..)
                .zip(lines)
                .map(|(k, s)| Label::new(map.left, y0 + LEAD * k, s)),
        );
        let bottom = labels.iter().map(|l| l.rect()[3]).fold(y0, i64::max);
        Page {
            map,
            size: [width, bottom + 12],
            ticks,
            labels,
            bar,
            keys,
        }
    }

    /// A blank canvas of the page's size.
    pub(crate) fn canvas(&self, background: Rgb) -> Canvas {
        Canvas::new(self.size[0] as usize, self.size[1] as usize, background)
    }

    /// Labels `(point, text)` beside marks at picture points, worst first: each
    /// right, left, above or below its mark, at the first place inside the map clear
    /// of the labels placed before it and of every ring of radius `ring` px about
    /// `rings`, else at the first place clear of those labels only; a label with no
    /// such place is left out.
    pub(crate) fn marks(
        &self,
        marks: &[([f64; 2], String)],
        rings: &[[f64; 2]],
        ring: f64,
    ) -> Vec<Label> {
        let inside = self.map.inside();
        let r = ring.ceil() as i64;
        let gap = r + 2;
        let circles: Vec<Rect> = rings
            .iter()
            .map(|p| {
                let [x, y] = p.map(|v| v.round() as i64);
                [x - r, y - r, x + r + 1, y + r + 1]
            })
            .collect();
        let mut placed: Vec<Label> = Vec::new();
        for (p, text) in marks {
            let ([x, y], w) = (p.map(|v| v.round() as i64), tw(text));
            let places: Vec<Label> = [
                (x + gap, y - GLYPH / 2),
                (x - gap - w, y - GLYPH / 2),
                (x - w / 2, y - gap - GLYPH),
                (x - w / 2, y + gap),
            ]
            .into_iter()
            .map(|(x, y)| Label::new(x, y, text.as_str()))
            .filter(|l| {
                within(&l.rect(), &inside) && placed.iter().all(|q| !overlap(&q.rect(), &l.rect()))
            })
            .collect();
            let clear = |l: &&Label| circles.iter().all(|c| !overlap(c, &l.rect()));
            let best = places.iter().find(clear).or(places.first()).cloned();
            placed.extend(best);
        }
        placed
    }

    /// The map's frame, the axis ticks, and every label.
    pub(crate) fn draw(&self, c: &mut Canvas) {
        let m = &self.map;
        c.frame(m.left - 1, m.top - 1, m.left + m.w, m.top + m.h, BLACK);
        let foot = m.top + m.h;
        for &x in &self.ticks[0] {
            c.fill(x, foot, x + 1, foot + 6, BLACK);
        }
        for &y in &self.ticks[1] {
            c.fill(m.left - 6, y, m.left, y + 1, BLACK);
        }
        for l in &self.labels {
            c.text(l.at[0], l.at[1], &l.text, SIZE, BLACK);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const DIE_TITLE: &str = "normal deviation: die-inclined-6.cl, \
        apt:d=38.1,r=6.35,e=12.700000000000001,f=0,alpha=0,beta=0,h=25.4, tol 0.01 mm";

    fn die_footer() -> Vec<String> {
        vec![
            "gouge: 37707 cells in 1 region, deepest -3.4370 mm at line 113".into(),
            "excess > 0.010 mm: 398 cells, scallop 0.010-0.019 mm".into(),
        ]
    }

    fn grid(rect: [f64; 4], cell: f64) -> Cells {
        let g = swarf_sim::Grid::covering([rect[0], rect[1]], [rect[2], rect[3]], cell, 1 << 40);
        crate::picture::cells(&g.unwrap())
    }

    const BAR: Legend = Legend::Bar {
        below: 3.437,
        above: 0.031,
        tol: 0.01,
        keys: &["off part", "no stock"],
    };
    const LINES: Legend = Legend::Lines(&["feed", "rapid", "start", "end"]);

    /// What is drawn that text must stay off: the map's frame and ticks, the colour
    /// bar's frame, ticks and tolerance marks, the legend keys.
    fn graphics(page: &Page) -> Vec<Rect> {
        let m = &page.map;
        let foot = m.top + m.h;
        let mut g = vec![[m.left - 1, m.top - 1, m.left + m.w + 1, foot + 1]];
        g.extend(page.ticks[0].iter().map(|&x| [x, foot, x + 1, foot + 6]));
        g.extend(
            page.ticks[1]
                .iter()
                .map(|&y| [m.left - 6, y, m.left, y + 1]),
        );
        if let Some(b) = &page.bar {
            let [x0, y0, x1, y1] = b.rect;
            g.push([x0 - 1, y0 - 1, x1 + 1, y1 + 1]);
            g.extend(b.ticks.iter().map(|&y| [x1, y, x1 + 8, y + 1]));
            g.extend(b.tols.iter().map(|&y| [x0 - 6, y, x1 + 6, y + 1]));
        }
        g.extend(page.keys.iter().copied());
        g
    }

    /// Every label on the canvas, no two sharing a pixel, none on a drawn mark; the
    /// gouge labels `marks` inside the map.
    fn assert_clear(page: &Page, marks: &[Label]) {
        let canvas = [0, 0, page.size[0], page.size[1]];
        let all: Vec<&Label> = page.labels.iter().chain(marks).collect();
        for (k, a) in all.iter().enumerate() {
            assert!(within(&a.rect(), &canvas), "{a:?} off {canvas:?}");
            for b in &all[..k] {
                assert!(!overlap(&a.rect(), &b.rect()), "{a:?} on {b:?}");
            }
        }
        for l in &page.labels {
            for g in graphics(page) {
                assert!(!overlap(&l.rect(), &g), "{l:?} on {g:?}");
            }
        }
        for l in marks {
            assert!(within(&l.rect(), &page.map.inside()), "{l:?}");
        }
    }

    #[test]
    fn the_die_picture_wraps_its_title_and_keeps_the_footer_off_the_legend() {
        let rect = [-99.75, -103.2, -4.25, 0.3];
        let title = format!("{DIE_TITLE}, {DIE_TITLE}");
        let page = Page::new(&grid(rect, 0.5), rect, &title, &die_footer(), &BAR);
        assert_clear(&page, &[]);
        let titles = page.labels.iter().filter(|l| l.at[1] < page.map.top - 28);
        assert!(titles.count() >= 2);
        let text: Vec<&str> = page.labels.iter().map(|l| l.text.as_str()).collect();
        for want in [
            "off part", "no stock", "tol 0.01", "dev, mm", "-3.437", "+0.031",
        ] {
            assert!(text.contains(&want), "{want}: {text:?}");
        }
        let joined: String = text.concat();
        assert!(joined.contains("1 region,"), "{joined}");
        let path = Page::new(&grid(rect, 0.5), rect, DIE_TITLE, &die_footer(), &LINES);
        assert_clear(&path, &[]);
    }

    #[test]
    fn odd_shapes_long_words_and_far_coordinates_stay_clear() {
        let word = "x".repeat(300);
        let cases: [([f64; 4], &str); 6] = [
            ([0.0, 0.0, 2.0, 500.0], DIE_TITLE),
            ([0.0, 0.0, 500.0, 2.0], DIE_TITLE),
            ([-12345.678, -20010.5, -12000.0, -20000.0], &word),
            ([0.1, 0.1, 0.4, 0.3], ""),
            ([-3.0, 7.0, 1.0e4, 7.5e3], "a , , b"),
            ([0.0, 0.0, 1.0, 1.0], " "),
        ];
        for (rect, title) in cases {
            for legend in [&BAR, &LINES] {
                let g = grid(rect, (rect[2] - rect[0]).min(rect[3] - rect[1]) / 8.0);
                let page = Page::new(&g, rect, title, &die_footer(), legend);
                assert_clear(&page, &[]);
                let page = Page::new(&g, rect, title, &[], legend);
                assert_clear(&page, &[]);
            }
        }
    }

    #[test]
    fn crowded_marks_are_placed_around_or_left_out() {
        let rect = [0.0, 0.0, 100.0, 70.0];
        let page = Page::new(&grid(rect, 1.0), rect, "t", &[], &BAR);
        let centre = page.map.px(50.0, 35.0);
        let edge = page.map.px(99.9, 35.0);
        let mut marks: Vec<_> = (0..8).map(|k| (centre, format!("L{k}"))).collect();
        marks.push((edge, "L12345".into()));
        let placed = page.marks(&marks, &[], 10.0);
        assert_clear(&page, &placed);
        assert_eq!(placed.len(), 5, "{placed:?}");
        let last = &placed[4];
        assert!(last.rect()[2] < edge[0] as i64, "{last:?}");
    }

    #[test]
    fn mark_labels_keep_off_other_rings_while_they_can() {
        let rect = [0.0, 0.0, 100.0, 70.0];
        let page = Page::new(&grid(rect, 1.0), rect, "t", &[], &BAR);
        let [x, y] = page.map.px(50.0, 35.0);
        let right = [x + 20.0, y];
        let marks = [([x, y], "L1".to_string())];
        let placed = page.marks(&marks, &[[x, y], right], 10.0);
        assert_eq!(placed[0].at, [x as i64 - 12 - tw("L1"), y as i64 - 8]);
        let boxed = [[x, y], right, [x - 30.0, y], [x, y - 30.0], [x, y + 30.0]];
        let placed = page.marks(&marks, &boxed, 10.0);
        assert_eq!(placed[0].at, [x as i64 + 12, y as i64 - 8]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn no_text_overlaps_or_leaves_the_canvas(
            x0 in -1.0e4..1.0e4f64,
            y0 in -1.0e4..1.0e4f64,
            sx in 0.1..3000.0f64,
            sy in 0.1..3000.0f64,
            title in "[a-z0-9 ,:=.]{0,160}",
            footer in proptest::collection::vec("[a-z0-9 ,:=.-]{0,140}", 0..3),
            bar in any::<bool>(),
            marks in proptest::collection::vec((0.0..1.0f64, 0.0..1.0f64, 0u32..100_000), 0..12),
        ) {
            let rect = [x0, y0, x0 + sx, y0 + sy];
            let legend = if bar { &BAR } else { &LINES };
            let page = Page::new(&grid(rect, sx.min(sy) / 4.0), rect, &title, &footer, legend);
            let marks: Vec<_> = marks
                .iter()
                .map(|&(u, v, line)| {
                    let p = page.map.px(x0 + u * sx, y0 + v * sy);
                    (p, format!("L{line}"))
                })
                .collect();
            let rings: Vec<[f64; 2]> = marks.iter().map(|m| m.0).collect();
            let placed = page.marks(&marks, &rings, 10.0);
            assert_clear(&page, &placed);
        }
    }
}
