//! Deviation of the machined stock from the design, and what it means for the part.
//!
//! At every cell centre where the design is defined, `deviation = machined - design`
//! (vertical; [`crate::mow`] measures along the design normals instead, thesis 000
//! §2.5 "mow the grass"). With the tolerance `tol` and an allowed excess `a` (the
//! scallop limit a finishing strategy was planned for; 0 when none):
//!
//! - **gouge**: `deviation < -tol`, the tool cut into the part;
//! - **excess** (remaining material): `deviation > a + tol`;
//! - **scallop crest**: a cell that is a local maximum of the deviation along one of
//!   the four grid directions (both neighbours on the design and not higher, one
//!   strictly lower), stands above `tol`, and sees a cut valley (`deviation <= tol`)
//!   within the tool radius on both sides along that direction: the ridge between two
//!   passes (paper 004, "scallop height"). The valley condition rejects the slope of
//!   uncut stock at the part's rim and bumps of stock no pass reached.
//!
//! Gouge and excess cells are grouped into regions (8-connected); a gouge region
//! reports its deepest cell and the program line of the motion that last lowered it
//! (the cut that left the cell where it is). Areas are cell counts times the cell
//! area, volumes the sums of `|deviation|` times the cell area.

use crate::dexel::NO_MOTION;
use crate::grid::Grid;
use rayon::prelude::*;
use serde::Serialize;

/// Deviation thresholds and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeviationOptions {
    /// Tolerance, mm (> 0).
    pub tol: f64,
    /// Material allowed above the design before it counts as excess (a scallop
    /// limit), mm.
    pub allowed_excess: f64,
    /// How far a scallop crest may be from the cut valleys on its sides, mm (the
    /// tool radius).
    pub valley_reach: f64,
    /// How many regions of each kind to list, worst first.
    pub max_regions: usize,
}

impl Default for DeviationOptions {
    fn default() -> Self {
        DeviationOptions {
            tol: 0.01,
            allowed_excess: 0.0,
            valley_reach: 5.0,
            max_regions: 20,
        }
    }
}

/// Counts and sizes of one class of cells.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ClassSummary {
    /// Cells in the class.
    pub cells: usize,
    /// Their area, mm^2.
    pub area_mm2: f64,
    /// Material volume (gouged or left), mm^3.
    pub volume_mm3: f64,
    /// Worst deviation, mm (most negative for gouges, largest for excess; 0 if none).
    pub worst: f64,
    /// Connected regions.
    pub regions: usize,
}

/// A connected region of gouge or excess cells.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Region {
    /// Cells in it.
    pub cells: usize,
    /// Area, mm^2.
    pub area_mm2: f64,
    /// Volume, mm^3.
    pub volume_mm3: f64,
    /// Worst deviation, mm.
    pub worst: f64,
    /// Where: the worst cell's centre and design height, mm.
    pub at: [f64; 3],
    /// The motion that last lowered the worst cell (index in the program).
    pub motion: Option<usize>,
    /// Its program line.
    pub line: Option<usize>,
}

/// Scallop crest heights (deviation at the crests), mm.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ScallopSummary {
    /// Crest cells.
    pub crests: usize,
    /// Lowest crest.
    pub min: Option<f64>,
    /// 5th percentile.
    pub p05: Option<f64>,
    /// Median.
    pub p50: Option<f64>,
    /// 95th percentile.
    pub p95: Option<f64>,
    /// Highest crest.
    pub max: Option<f64>,
}

/// All figures of a deviation analysis.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct DeviationSummary {
    /// Tolerance used, mm.
    pub tol: f64,
    /// Allowed excess used, mm.
    pub allowed_excess: f64,
    /// Cells where both the design and material exist.
    pub measured_cells: usize,
    /// Design cells with no material left at all (e.g. outside a mesh stock).
    pub no_material_cells: usize,
    /// Smallest deviation, mm.
    pub min: Option<f64>,
    /// Largest deviation, mm.
    pub max: Option<f64>,
    /// Mean deviation, mm.
    pub mean: Option<f64>,
    /// Cells within `[-tol, allowed + tol]`.
    pub within_cells: usize,
    /// Gouges.
    pub gouge: ClassSummary,
    /// Excess (remaining material).
    pub excess: ClassSummary,
    /// Scallop crests.
    pub scallop: ScallopSummary,
    /// Gouge regions, deepest first (at most `max_regions`).
    pub gouges: Vec<Region>,
    /// Excess regions, highest first (at most `max_regions`).
    pub excesses: Vec<Region>,
}

/// Per-cell deviation and its summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Deviation {
    /// `machined - design` per cell, mm; NaN where not measured.
    pub values: Vec<f64>,
    /// The figures.
    pub summary: DeviationSummary,
}

/// Vertical deviation of `machined` from `design` (both row-major over `grid`).
pub fn vertical_deviation(machined: &[f64], design: &[f64]) -> Vec<f64> {
    machined
        .par_iter()
        .zip(design)
        .map(|(&m, &d)| {
            if d.is_finite() && m.is_finite() {
                m - d
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// Analyses per-cell `values` (from [`vertical_deviation`] or [`crate::mow`]).
/// `last` holds the motion that last lowered each cell, `lines` each motion's line.
pub fn analyse(
    grid: &Grid,
    values: Vec<f64>,
    design: &[f64],
    last: &[u32],
    lines: &[usize],
    opts: &DeviationOptions,
) -> Deviation {
    let (tol, allowed) = (opts.tol, opts.allowed_excess);
    let mut s = DeviationSummary {
        tol,
        allowed_excess: allowed,
        ..DeviationSummary::default()
    };
    let area = grid.cell * grid.cell;
    let (mut sum, mut lo, mut hi) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
    for (&v, &d) in values.iter().zip(design) {
        if v.is_nan() {
            if d.is_finite() {
                s.no_material_cells += 1;
            }
            continue;
        }
        s.measured_cells += 1;
        sum += v;
        lo = lo.min(v);
        hi = hi.max(v);
        if v < -tol {
            let worse = v < s.gouge.worst;
            add(&mut s.gouge, v, area, worse);
        } else if v > allowed + tol {
            let worse = v > s.excess.worst;
            add(&mut s.excess, v, area, worse);
        } else {
            s.within_cells += 1;
        }
    }
    if s.measured_cells > 0 {
        (s.min, s.max, s.mean) = (Some(lo), Some(hi), Some(sum / s.measured_cells as f64));
    }
    let at = |k: usize| {
        RegionCtx {
            grid,
            design,
            last,
            lines,
        }
        .locate(k)
    };
    let gouges = regions(grid, &values, |v| v < -tol);
    s.gouge.regions = gouges.len();
    s.gouges = worst_regions(gouges, &values, area, opts.max_regions, true, &at);
    let excesses = regions(grid, &values, |v| v > allowed + tol);
    s.excess.regions = excesses.len();
    s.excesses = worst_regions(excesses, &values, area, opts.max_regions, false, &at);
    s.scallop = scallops(grid, &values, tol, opts.valley_reach);
    Deviation { values, summary: s }
}

fn add(c: &mut ClassSummary, v: f64, area: f64, worse: bool) {
    c.cells += 1;
    c.area_mm2 += area;
    c.volume_mm3 += v.abs() * area;
    if worse {
        c.worst = v;
    }
}

/// Where a cell is, and which motion and line left it.
struct RegionCtx<'a> {
    grid: &'a Grid,
    design: &'a [f64],
    last: &'a [u32],
    lines: &'a [usize],
}

impl RegionCtx<'_> {
    fn locate(&self, k: usize) -> ([f64; 3], Option<usize>, Option<usize>) {
        let [x, y] = self.grid.centre(k % self.grid.nx, k / self.grid.nx);
        let motion = self
            .last
            .get(k)
            .filter(|&&m| m != NO_MOTION)
            .map(|&m| m as usize);
        let line = motion.and_then(|m| self.lines.get(m).copied());
        ([x, y, self.design[k]], motion, line)
    }
}

/// 8-connected regions of the cells (row-major over `grid`) whose value passes
/// `flag`, each as its cell list, in the order of their first cell.
pub fn regions(grid: &Grid, values: &[f64], flag: impl Fn(f64) -> bool) -> Vec<Vec<usize>> {
    let (nx, ny) = (grid.nx as isize, grid.ny as isize);
    let mut seen = vec![false; values.len()];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..values.len() {
        if seen[start] || !flag(values[start]) {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut cells = Vec::new();
        while let Some(k) = stack.pop() {
            cells.push(k);
            let (i, j) = ((k % grid.nx) as isize, (k / grid.nx) as isize);
            for (di, dj) in [
                (-1, -1),
                (0, -1),
                (1, -1),
                (-1, 0),
                (1, 0),
                (-1, 1),
                (0, 1),
                (1, 1),
            ] {
                let (a, b) = (i + di, j + dj);
                if a < 0 || b < 0 || a >= nx || b >= ny {
                    continue;
                }
                let q = (b * nx + a) as usize;
                if !seen[q] && flag(values[q]) {
                    seen[q] = true;
                    stack.push(q);
                }
            }
        }
        out.push(cells);
    }
    out
}

/// The `keep` worst regions as reports, worst first (`low`: most negative is worst).
fn worst_regions(
    regions: Vec<Vec<usize>>,
    values: &[f64],
    area: f64,
    keep: usize,
    low: bool,
    at: &dyn Fn(usize) -> ([f64; 3], Option<usize>, Option<usize>),
) -> Vec<Region> {
    let mut out: Vec<Region> = regions
        .iter()
        .map(|cells| {
            let worst_cell = cells.iter().copied().fold(cells[0], |w, k| {
                let better = if low {
                    values[k] < values[w]
                } else {
                    values[k] > values[w]
                };
                if better { k } else { w }
            });
            let (pos, motion, line) = at(worst_cell);
            Region {
                cells: cells.len(),
                area_mm2: cells.len() as f64 * area,
                volume_mm3: cells.iter().map(|&k| values[k].abs()).sum::<f64>() * area,
                worst: values[worst_cell],
                at: pos,
                motion,
                line,
            }
        })
        .collect();
    out.sort_by(|a, b| {
        let o = a.worst.total_cmp(&b.worst);
        if low { o } else { o.reverse() }
    });
    out.truncate(keep);
    out
}

/// Scallop crests (see the module doc) and their height statistics.
fn scallops(grid: &Grid, values: &[f64], tol: f64, reach: f64) -> ScallopSummary {
    let steps = (reach / grid.cell).ceil().max(1.0) as isize;
    let (nx, ny) = (grid.nx as isize, grid.ny as isize);
    let at = |i: isize, j: isize| -> f64 {
        if i < 0 || j < 0 || i >= nx || j >= ny {
            f64::NAN
        } else {
            values[(j * nx + i) as usize]
        }
    };
    let crest = |k: usize| -> Option<f64> {
        let v = values[k];
        if v.is_nan() || v <= tol {
            return None;
        }
        let (i, j) = ((k % grid.nx) as isize, (k / grid.nx) as isize);
        for (di, dj) in [(1, 0), (0, 1), (1, 1), (1, -1)] {
            let (a, b) = (at(i - di, j - dj), at(i + di, j + dj));
            if !(a <= v && b <= v && (a < v || b < v)) {
                continue;
            }
            let valley =
                |sign: isize| (1..=steps).any(|t| at(i + sign * t * di, j + sign * t * dj) <= tol);
            if valley(-1) && valley(1) {
                return Some(v);
            }
        }
        None
    };
    let mut h: Vec<f64> = (0..values.len())
        .into_par_iter()
        .filter_map(crest)
        .collect();
    h.sort_by(f64::total_cmp);
    let q = |p: f64| h.get(((h.len() - 1) as f64 * p).round() as usize).copied();
    if h.is_empty() {
        return ScallopSummary::default();
    }
    ScallopSummary {
        crests: h.len(),
        min: h.first().copied(),
        p05: q(0.05),
        p50: q(0.5),
        p95: q(0.95),
        max: h.last().copied(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Grid {
        Grid::covering([0.0, 0.0], [10.0, 5.0], 0.5, 1 << 20).unwrap()
    }

    #[test]
    fn classes_regions_and_lines() {
        let g = grid();
        let design = vec![1.0; g.len()];
        let mut machined = vec![1.0; g.len()];
        let mut last = vec![NO_MOTION; g.len()];
        // a gouge of two cells, 0.05 and 0.03 deep, cut by motions 4 and 5
        machined[3 * g.nx + 4] = 0.95;
        last[3 * g.nx + 4] = 4;
        machined[3 * g.nx + 5] = 0.97;
        last[3 * g.nx + 5] = 5;
        // a separate, shallower gouge
        machined[0] = 0.98;
        // excess
        machined[g.len() - 1] = 1.5;
        let values = vertical_deviation(&machined, &design);
        let lines = vec![10, 11, 12, 13, 14, 15];
        let opts = DeviationOptions {
            tol: 0.01,
            ..DeviationOptions::default()
        };
        let d = analyse(&g, values, &design, &last, &lines, &opts);
        let s = &d.summary;
        assert_eq!((s.gouge.cells, s.gouge.regions, s.excess.cells), (3, 2, 1));
        assert!((s.gouge.worst + 0.05).abs() < 1e-12);
        assert!((s.gouge.area_mm2 - 0.75).abs() < 1e-12);
        assert!((s.gouge.volume_mm3 - 0.25 * 0.1).abs() < 1e-12);
        let deepest = &s.gouges[0];
        assert_eq!(
            (deepest.cells, deepest.motion, deepest.line),
            (2, Some(4), Some(14))
        );
        assert_eq!(deepest.at[0..2], [2.25, 1.75]);
        assert_eq!(s.gouges[1].line, None);
        assert_eq!(s.within_cells, g.len() - 4);
        assert_eq!(s.scallop.crests, 0);
    }

    #[test]
    fn scallop_crests_between_valleys_only() {
        // Centres at multiples of 1/8 mm, so each crest (odd x) is a centre.
        let g = Grid::covering([-0.0625, 0.0], [20.0625, 4.0], 0.125, 1 << 20).unwrap();
        // passes every 2 mm along y, ridges of 0.15 mm half-way between
        let design = vec![0.0; g.len()];
        let mut machined = vec![0.0; g.len()];
        for j in 0..g.ny {
            for i in 0..g.nx {
                let x = g.x(i);
                let t = (x % 2.0) / 2.0; // 0 at passes, 0.5 midway
                let ridge =
                    0.15 * (1.0 - (2.0 * t - 1.0).abs().powi(2)) * if x > 18.0 { 0.0 } else { 1.0 };
                machined[j * g.nx + i] = ridge + if x > 19.0 { 1.0 } else { 0.0 };
            }
        }
        let values = vertical_deviation(&machined, &design);
        let opts = DeviationOptions {
            tol: 0.01,
            valley_reach: 2.0,
            ..DeviationOptions::default()
        };
        let d = analyse(&g, values, &design, &vec![NO_MOTION; g.len()], &[], &opts);
        let sc = d.summary.scallop;
        // nine crests (x = 1, 3, ..., 17) per row; the uncut strip beyond x = 19 is not
        // a scallop (no valley beyond it).
        assert_eq!(sc.crests, 9 * g.ny);
        assert!((sc.max.unwrap() - 0.15).abs() < 1e-3, "{sc:?}");
        assert!(sc.min.unwrap() > 0.14);
    }
}
