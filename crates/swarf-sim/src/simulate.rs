//! Running a program's motions over a dexel stock, in parallel and deterministically.
//!
//! Every motion becomes primitives ([`crate::sweep::sweep_motion`]). The stock is cut
//! into bands of rows; each band, on its own thread, applies every primitive whose XY
//! box meets it, in program order. A cell is only ever written by its band's thread,
//! in program order, so the heights and the "last motion that lowered the cell" are
//! the same whatever the thread count. Per-band findings (rapids that cut material)
//! are merged in band order. A program read from a file does not say where the
//! machine stood before its first motion; with [`SimOptions::known_start`] false
//! that motion only places the tool at its end. Motions are taken in chunks of at most
//! [`CHUNK_PRIMITIVES`] primitives so that a densely sampled five-axis program does
//! not hold all its tool positions at once. Programs run one after the other on the
//! same stock ([`crate::stage`]) number their motions on from those before them
//! ([`simulate_from`]), so that a cell's last motion says which program left it.

use crate::dexel::{Dexel, NO_MOTION};
use crate::grid::Grid;
use crate::progress::Progress;
use crate::sweep::{Primitive, RowJob, Sampling, SimTool, sweep_motion};
use crate::sweep_bound::StockCeiling;
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use swarf_toolpath::{Motion, MotionKind};

/// Most primitives held at once.
pub const CHUNK_PRIMITIVES: usize = 1 << 18;
/// A cutting motion whose swept box lies further than this many tool radii from
/// the grid is reported as outside the stock (closer ones are approaches).
pub const OUTSIDE_MARGIN: f64 = 2.0;
/// A rapid that lowers material by more than this is reported, mm: a nanometre,
/// above the rounding of a tilted tool retracting along its own axis from where
/// it cut (a few 1e-9 mm).
pub const RAPID_CUT_EPS: f64 = 1e-6;

/// Simulation options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimOptions {
    /// Distance bound for sampled motions (arcs, five-axis), mm.
    pub sample_tol: f64,
    /// The first motion's start is where the tool really was. When false (a program
    /// read from a file does not say where the machine stands before it), the first
    /// motion only places the tool at its end.
    pub known_start: bool,
    /// Sample every tilted motion by the first-order bound, as the reference sweep
    /// the second-order sampling ([`crate::sweep_bound`]) is checked against.
    pub first_order: bool,
    /// Stop at the first rapid that removes material (each rapid is then applied
    /// as it comes): a check that refuses the program on it needs no more.
    pub stop_at_rapid_cut: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            sample_tol: 0.001,
            known_start: true,
            first_order: false,
            stop_at_rapid_cut: false,
        }
    }
}

/// A motion worth a warning.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MotionNote {
    /// Index of the motion in the program.
    pub motion: usize,
    /// Its source line.
    pub line: usize,
    /// For a rapid that cut: the deepest cut, mm. For a move outside the stock: how
    /// far its swept box lies from the grid, mm.
    pub amount: f64,
}

/// What a simulation did.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SimReport {
    /// Motions simulated.
    pub motions: usize,
    /// Primitives (exact sweeps, chords, sampled tool positions) applied.
    pub primitives: usize,
    /// Motions that were sampled (arcs, five-axis).
    pub sampled_motions: usize,
    /// Five-axis motions sampled by the second-order bound (rounded tools whose sharp
    /// top stays above the stock, [`crate::sweep_bound`]); the others by the first.
    pub second_order_motions: usize,
    /// Largest sampling bound of any motion, mm (0: all exact); five-axis rapids are
    /// sampled at least as coarsely as [`crate::sweep::RAPID_SAMPLE`].
    pub max_sample_bound: f64,
    /// Cell evaluations (cells within reach of a primitive).
    pub cells_visited: u64,
    /// Cells lowered.
    pub cells_lowered: u64,
    /// Rapid motions that removed material (a crash on a machine).
    pub rapid_cuts: Vec<MotionNote>,
    /// Cutting motions whose swept box misses the stock grid entirely (clipped away).
    pub outside: Vec<MotionNote>,
    /// Motions simulated when the run stopped at a rapid that cut
    /// ([`SimOptions::stop_at_rapid_cut`]); `None` (not written): every motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_after: Option<usize>,
}

/// One band's findings.
#[derive(Default)]
struct BandStats {
    visited: u64,
    lowered: u64,
    rapid: BTreeMap<u32, f64>,
}

impl SimReport {
    /// Adds the findings of a later run on the same stock (counts summed, notes
    /// appended, the largest sampling bound kept).
    pub fn absorb(&mut self, later: SimReport) {
        self.motions += later.motions;
        self.primitives += later.primitives;
        self.sampled_motions += later.sampled_motions;
        self.second_order_motions += later.second_order_motions;
        self.max_sample_bound = self.max_sample_bound.max(later.max_sample_bound);
        self.cells_visited += later.cells_visited;
        self.cells_lowered += later.cells_lowered;
        self.rapid_cuts.extend(later.rapid_cuts);
        self.outside.extend(later.outside);
        if self.stopped_after.is_none() {
            self.stopped_after = later
                .stopped_after
                .map(|n| n + self.motions - later.motions);
        }
    }
}

/// Runs `motions` over `dexel` with `tool`; motion `k` is recorded as `k` in the
/// stock's last-motion record and in the notes ([`simulate_from`] numbers them from
/// another index).
pub fn simulate(
    dexel: &mut Dexel,
    tool: &SimTool,
    motions: &[Motion],
    opts: &SimOptions,
    progress: &dyn Progress,
) -> SimReport {
    simulate_from(dexel, tool, motions, 0, opts, progress)
}

/// Runs `motions` over `dexel` with `tool`, recording motion `k` as `first + k` in
/// the stock's last-motion record and in the notes: the motions of a later program
/// on the same stock are numbered after those of the programs before it.
pub fn simulate_from(
    dexel: &mut Dexel,
    tool: &SimTool,
    motions: &[Motion],
    first: usize,
    opts: &SimOptions,
    progress: &dyn Progress,
) -> SimReport {
    let grid = *dexel.grid();
    let mut report = SimReport {
        motions: motions.len(),
        ..SimReport::default()
    };
    let ceiling = StockCeiling::of(&grid, dexel.heights());
    let sampling = Sampling {
        tol: opts.sample_tol,
        ceiling: &ceiling,
        first_order: opts.first_order,
    };
    progress.begin("simulating", motions.len() as u64);
    let mut chunk: Vec<(Primitive, u32)> = Vec::new();
    let mut rapid = BTreeMap::new();
    let mut pending = 0u64;
    for (k, m) in motions.iter().enumerate() {
        let sw = if k == 0 && !opts.known_start {
            // Where the machine stands before the program is unknown: the first
            // motion places the tool at its end.
            let mut first = *m;
            first.start = m.end;
            first.kind = MotionKind::Linear;
            let mut sw = sweep_motion(tool, &first, &sampling);
            sw.bound = 0.0;
            sw
        } else {
            sweep_motion(tool, m, &sampling)
        };
        if sw.bound > 0.0 {
            report.sampled_motions += 1;
            report.max_sample_bound = report.max_sample_bound.max(sw.bound);
            report.second_order_motions += usize::from(sw.second_order);
        }
        if !matches!(m.kind, MotionKind::Rapid)
            && let Some(gap) = outside_gap(&grid, &sw.primitives)
            && gap > OUTSIDE_MARGIN * tool.radius()
        {
            report.outside.push(MotionNote {
                motion: first + k,
                line: m.line,
                amount: gap,
            });
        }
        let index = u32::try_from(k).unwrap_or(u32::MAX - 1);
        chunk.extend(sw.primitives.into_iter().map(|p| (p, index)));
        pending += 1;
        let check_now = opts.stop_at_rapid_cut && matches!(m.kind, MotionKind::Rapid);
        if chunk.len() >= CHUNK_PRIMITIVES || k + 1 == motions.len() || check_now {
            let numbering = Numbering { motions, first };
            run_chunk(dexel, tool, numbering, &chunk, &mut report, &mut rapid);
            report.primitives += chunk.len();
            chunk.clear();
            progress.advance(pending);
            pending = 0;
            if opts.stop_at_rapid_cut && !rapid.is_empty() {
                report.stopped_after = Some(k + 1);
                break;
            }
        }
    }
    progress.end();
    report.rapid_cuts = rapid
        .into_iter()
        .map(|(k, depth)| MotionNote {
            motion: first + k as usize,
            line: motions.get(k as usize).map_or(0, |m| m.line),
            amount: depth,
        })
        .collect();
    report
}

/// The motions of a run and the index its first one is recorded as.
#[derive(Clone, Copy)]
struct Numbering<'a> {
    motions: &'a [Motion],
    first: usize,
}

/// Applies one chunk of primitives (each with its motion's index in the run) to
/// every band in parallel.
fn run_chunk(
    dexel: &mut Dexel,
    tool: &SimTool,
    numbering: Numbering<'_>,
    chunk: &[(Primitive, u32)],
    report: &mut SimReport,
    rapid: &mut BTreeMap<u32, f64>,
) {
    let grid = *dexel.grid();
    let rows = band_rows(&grid);
    let boxes: Vec<[f64; 4]> = chunk.iter().map(|(p, _)| p.bounds()).collect();
    let stats: Vec<BandStats> = dexel
        .bands_mut(rows)
        .map(|(b, (heights, last))| {
            let j0 = b * rows;
            let j1 = (j0 + rows).min(grid.ny) - 1;
            let (y0, y1) = (grid.y(j0) - 0.5 * grid.cell, grid.y(j1) + 0.5 * grid.cell);
            let mut st = BandStats::default();
            for ((prim, motion), bx) in chunk.iter().zip(&boxes) {
                if bx[3] < y0 || bx[1] > y1 {
                    continue;
                }
                let Some((r0, r1)) = grid.rows(bx[1].max(y0), bx[3].min(y1)) else {
                    continue;
                };
                let is_rapid = numbering
                    .motions
                    .get(*motion as usize)
                    .is_some_and(|m| matches!(m.kind, MotionKind::Rapid));
                let recorded = recorded_index(numbering.first, *motion);
                for j in r0.max(j0)..=r1.min(j1) {
                    let off = (j - j0) * grid.nx;
                    let job = RowJob {
                        tool,
                        grid: &grid,
                        row: j,
                        motion: recorded,
                    };
                    let cut = prim.cut_row(
                        &job,
                        &mut heights[off..off + grid.nx],
                        &mut last[off..off + grid.nx],
                    );
                    st.visited += cut.visited;
                    st.lowered += cut.lowered;
                    if is_rapid && cut.depth > RAPID_CUT_EPS {
                        let e = st.rapid.entry(*motion).or_insert(0.0);
                        *e = e.max(cut.depth);
                    }
                }
            }
            st
        })
        .collect();
    for st in stats {
        report.cells_visited += st.visited;
        report.cells_lowered += st.lowered;
        for (k, d) in st.rapid {
            let e = rapid.entry(k).or_insert(0.0);
            *e = e.max(d);
        }
    }
}

/// The last-motion value of run motion `k` in a run numbered from `first`
/// (saturating below [`NO_MOTION`], which means "no motion").
fn recorded_index(first: usize, k: u32) -> u32 {
    u32::try_from(first.saturating_add(k as usize))
        .unwrap_or(NO_MOTION - 1)
        .min(NO_MOTION - 1)
}

/// Rows per band: enough bands for load balance, few enough to keep the per-band
/// scan of primitive boxes cheap.
fn band_rows(grid: &Grid) -> usize {
    (grid.ny / 128).clamp(2, 64)
}

/// How far the union of the primitives' boxes lies from the grid (`None` when it
/// meets the grid or there is nothing).
fn outside_gap(grid: &Grid, prims: &[Primitive]) -> Option<f64> {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in prims {
        let q = p.bounds();
        b = [
            b[0].min(q[0]),
            b[1].min(q[1]),
            b[2].max(q[2]),
            b[3].max(q[3]),
        ];
    }
    let max = grid.max();
    let dx = (grid.origin[0] - b[2]).max(b[0] - max[0]).max(0.0);
    let dy = (grid.origin[1] - b[3]).max(b[1] - max[1]).max(0.0);
    let gap = dx.hypot(dy);
    (gap > 0.0 && gap.is_finite()).then_some(gap)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dexel::{NO_MOTION, StockInit};
    use crate::progress::Quiet;
    use swarf_geom::Point3;
    use swarf_tool::Pose;

    pub(crate) fn line(kind: MotionKind, a: [f64; 3], b: [f64; 3], line: usize) -> Motion {
        Motion {
            kind,
            start: Pose::vertical(Point3::from(a)),
            end: Pose::vertical(Point3::from(b)),
            feed: 300.0,
            line,
        }
    }

    fn stock(top: f64) -> Dexel {
        let g = Grid::covering([-10.0, -10.0], [10.0, 10.0], 0.1, 1 << 30).unwrap();
        Dexel::new(g, StockInit::Box { top }).unwrap()
    }

    #[test]
    fn records_lines_rapid_cuts_and_outside_moves() {
        let tool = SimTool::new(&"ball:d=4".parse().unwrap()).unwrap();
        let mut d = stock(0.0);
        let moves = [
            line(MotionKind::Rapid, [0.0, 0.0, 10.0], [-5.0, 0.0, 10.0], 1),
            line(MotionKind::Linear, [-5.0, 0.0, 10.0], [-5.0, 0.0, -1.0], 2),
            line(MotionKind::Linear, [-5.0, 0.0, -1.0], [5.0, 0.0, -1.0], 3),
            line(MotionKind::Rapid, [5.0, 0.0, -1.0], [5.0, 5.0, -0.5], 4),
            line(MotionKind::Linear, [50.0, 0.0, -1.0], [60.0, 0.0, -1.0], 5),
            line(MotionKind::Linear, [60.0, 0.0, -1.0], [13.0, 0.0, -1.0], 6),
        ];
        let opts = SimOptions {
            known_start: false,
            ..SimOptions::default()
        };
        let r = simulate(&mut d, &tool, &moves, &opts, &Quiet);
        assert_eq!(r.motions, 6);
        assert_eq!(r.rapid_cuts.len(), 1);
        assert_eq!((r.rapid_cuts[0].motion, r.rapid_cuts[0].line), (3, 4));
        // It climbs out of the slot the feed move cut: new material only beside it.
        let depth = r.rapid_cuts[0].amount;
        assert!(depth > 0.5 && depth < 1.0, "{:?}", r.rapid_cuts);
        assert_eq!(r.outside.len(), 1);
        assert_eq!(r.outside[0].line, 5);
        assert!((r.outside[0].amount - 38.0).abs() < 1e-9);
        let g = *d.grid();
        let (i, j) = g.cell_of(0.05, 0.05).unwrap();
        let k = j * g.nx + i;
        assert_eq!(d.last_motion()[k], 2);
        assert!((d.heights()[k] - (-1.0 + 2.0 - (4.0f64 - 0.0025).sqrt())).abs() < 1e-12);
        let (i, j) = g.cell_of(-9.95, 9.95).unwrap();
        assert_eq!(d.last_motion()[j * g.nx + i], NO_MOTION);
    }

    /// Stopping at the first rapid that cuts: the feeds before it are applied, the
    /// moves after it are not (the second rapid cut, the last feed).
    #[test]
    fn a_run_can_stop_at_the_first_rapid_that_cuts() {
        let tool = SimTool::new(&"ball:d=4".parse().unwrap()).unwrap();
        let moves = [
            line(MotionKind::Linear, [-5.0, 0.0, 10.0], [-5.0, 0.0, -1.0], 1),
            line(MotionKind::Linear, [-5.0, 0.0, -1.0], [5.0, 0.0, -1.0], 2),
            line(MotionKind::Rapid, [5.0, 0.0, -1.0], [5.0, 5.0, -0.5], 3),
            line(MotionKind::Rapid, [5.0, 5.0, -0.5], [-5.0, 5.0, -0.5], 4),
            line(MotionKind::Linear, [-5.0, 5.0, -0.5], [-5.0, -5.0, -2.0], 5),
        ];
        let run = |stop: bool| {
            let mut d = stock(0.0);
            let opts = SimOptions {
                known_start: false,
                stop_at_rapid_cut: stop,
                ..SimOptions::default()
            };
            (simulate(&mut d, &tool, &moves, &opts, &Quiet), d)
        };
        let (all, _) = run(false);
        assert_eq!(all.rapid_cuts.len(), 2);
        assert_eq!(all.stopped_after, None);
        let (stopped, d) = run(true);
        assert_eq!(stopped.stopped_after, Some(3));
        assert_eq!(stopped.rapid_cuts.len(), 1);
        assert_eq!(stopped.rapid_cuts[0].line, 3);
        assert_eq!(stopped.rapid_cuts[0].amount, all.rapid_cuts[0].amount);
        let g = *d.grid();
        let (i, j) = g.cell_of(-5.05, -4.95).unwrap();
        assert_eq!(
            d.heights()[j * g.nx + i],
            0.0,
            "the last feed is not applied"
        );
        let (i, j) = g.cell_of(0.05, 0.05).unwrap();
        assert_eq!(d.last_motion()[j * g.nx + i], 1);
    }

    #[test]
    fn deterministic_whatever_the_threads() {
        let tool = SimTool::new(&"bull:d=6,r=1".parse().unwrap()).unwrap();
        let moves: Vec<Motion> = (0..40)
            .map(|k| {
                let a = k as f64 * 0.37 - 7.0;
                line(MotionKind::Linear, [a, -8.0, -0.3], [-a, 8.0, -1.2], k + 1)
            })
            .collect();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut d = stock(0.0);
                simulate(&mut d, &tool, &moves, &SimOptions::default(), &Quiet);
                (d.heights().to_vec(), d.last_motion().to_vec())
            })
        };
        assert!(run(1) == run(3));
    }
}
