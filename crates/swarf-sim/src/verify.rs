//! The whole verification: grid over the design, design heights, stock, simulation of
//! the program (or of several programs in sequence, [`crate::stage`]), deviation, and
//! the program's own figures (time, lengths, passes).
//!
//! Machining time follows the program: each cutting motion at its own feed, rapids at
//! the machine's rapid rate (a parameter: programs do not state it). A cutting motion
//! without a feed (APT CL without `FEDRAT`) adds its length to
//! [`ProgramStats::unknown_feed_length_mm`] and nothing to the time.

use crate::design::{Design, DesignField, DesignSurface};
use crate::deviation::{Deviation, DeviationOptions, analyse, vertical_deviation};
use crate::dexel::{Dexel, StockInit};
use crate::error::SimError;
use crate::floor::FloorCheck;
use crate::grid::{DEFAULT_MAX_BYTES, Grid};
use crate::mow::normal_deviation;
use crate::progress::Progress;
use crate::simulate::{SimOptions, SimReport};
use crate::stage::{Stage, StageSummary, run_stages, stage_of};
use crate::sweep::SimTool;
use serde::Serialize;
use std::time::Instant;
use swarf_geom::TriMesh;
use swarf_tool::Cutter;
use swarf_toolpath::{MotionKind, Program};

/// Default cell size as a multiple of the tolerance.
pub const CELL_PER_TOL: f64 = 5.0;

/// Where the stock comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum StockSpec {
    /// A block over the design's XY box; top at `top` (default: the design's top).
    Box {
        /// Top height, mm.
        top: Option<f64>,
    },
    /// The design raised by an allowance, mm.
    Offset {
        /// Allowance, mm.
        allowance: f64,
    },
    /// The upper envelope of a mesh (no material where the mesh is absent).
    Mesh(TriMesh),
}

impl StockSpec {
    /// A bound of the stock's height over a design whose highest point is
    /// `design_top`, mm.
    pub fn top(&self, design_top: f64) -> f64 {
        match self {
            StockSpec::Box { top } => top.unwrap_or(design_top),
            StockSpec::Offset { allowance } => design_top + allowance,
            StockSpec::Mesh(m) => m.aabb().max.z,
        }
    }

    /// Short description for reports.
    pub fn describe(&self) -> String {
        match self {
            StockSpec::Box { top: Some(t) } => format!("box, top {t} mm"),
            StockSpec::Box { top: None } => "box (the design's bounding box)".into(),
            StockSpec::Offset { allowance } => format!("design + {allowance} mm"),
            StockSpec::Mesh(m) => format!("mesh ({} triangles)", m.len()),
        }
    }
}

/// Verification options.
#[derive(Debug, Clone, PartialEq)]
pub struct VerifyOptions {
    /// Cell size, mm (default [`CELL_PER_TOL`] times the tolerance).
    pub cell: Option<f64>,
    /// Gouge / excess tolerance, mm.
    pub tol: f64,
    /// Material allowed above the design (scallop limit), mm.
    pub allowed_excess: f64,
    /// The stock.
    pub stock: StockSpec,
    /// Memory limit for the grid, bytes.
    pub max_bytes: u64,
    /// Sampling bound for arcs and five-axis motions, mm (default:
    /// [`default_sample_tol`] of the tolerance).
    pub sample_tol: Option<f64>,
    /// Machine rapid rate for the time estimate, mm/min.
    pub rapid_rate: f64,
    /// Regions of each kind to list.
    pub max_regions: usize,
    /// Measure along the design normals ("mow the grass", [`crate::mow`]) instead
    /// of vertically.
    pub along_normals: bool,
    /// Verify only inside this XY rectangle `[min, max]`, mm, clipped to the design's
    /// box (default: the whole design).
    pub window: Option<[[f64; 2]; 2]>,
    /// Sample five-axis motions by the first-order bound alone: the slow reference
    /// sweep ([`crate::sweep_bound`]).
    pub first_order: bool,
    /// Stop the simulation at the first rapid that removes material
    /// ([`SimOptions::stop_at_rapid_cut`]): the deviation is then of the stock as
    /// that rapid left it.
    pub stop_at_rapid_cut: bool,
    /// The lowest height the tool may reach, mm: every motion is checked against it
    /// ([`crate::floor`]); `None`: no floor check.
    pub floor: Option<f64>,
}

/// The sampling bound of arcs and five-axis motions for a verification tolerance
/// `tol`, mm, when none is given: a quarter of it.
pub fn default_sample_tol(tol: f64) -> f64 {
    0.25 * tol
}

impl VerifyOptions {
    /// The sampling bound: given, else [`default_sample_tol`] of the tolerance, mm.
    pub fn sample_tol(&self) -> f64 {
        self.sample_tol.unwrap_or(default_sample_tol(self.tol))
    }
}

impl Default for VerifyOptions {
    fn default() -> Self {
        VerifyOptions {
            cell: None,
            tol: 0.01,
            allowed_excess: 0.0,
            stock: StockSpec::Offset { allowance: 0.5 },
            max_bytes: DEFAULT_MAX_BYTES,
            sample_tol: None,
            rapid_rate: 5000.0,
            max_regions: 20,
            along_normals: false,
            window: None,
            first_order: false,
            stop_at_rapid_cut: false,
            floor: None,
        }
    }
}

/// The program's own figures.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ProgramStats {
    /// Motions read.
    pub motions: usize,
    /// Rapid motions.
    pub rapids: usize,
    /// Arc motions.
    pub arcs: usize,
    /// Passes: runs of cutting motions between rapids.
    pub passes: usize,
    /// Length of cutting motions, mm.
    pub cutting_length_mm: f64,
    /// Length of rapid motions, mm.
    pub rapid_length_mm: f64,
    /// Cutting length without a feed rate, mm (not in the time).
    pub unknown_feed_length_mm: f64,
    /// Machining time estimate, s.
    pub time_s: f64,
}

impl ProgramStats {
    /// Adds the figures of another program run on the same stock.
    pub fn add(&mut self, other: &ProgramStats) {
        self.motions += other.motions;
        self.rapids += other.rapids;
        self.arcs += other.arcs;
        self.passes += other.passes;
        self.cutting_length_mm += other.cutting_length_mm;
        self.rapid_length_mm += other.rapid_length_mm;
        self.unknown_feed_length_mm += other.unknown_feed_length_mm;
        self.time_s += other.time_s;
    }
}

/// Wall times of the computation's steps, s.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Timings {
    /// Design heights.
    pub design_s: f64,
    /// Material removal.
    pub simulate_s: f64,
    /// Deviation analysis.
    pub deviation_s: f64,
}

/// Everything a verification found.
#[derive(Debug, Clone)]
pub struct Verification {
    /// The grid.
    pub grid: Grid,
    /// The machined stock.
    pub stock: Dexel,
    /// Design heights (and normals).
    pub design: DesignField,
    /// Deviation per cell and its figures.
    pub deviation: Deviation,
    /// What the simulation did.
    pub sim: SimReport,
    /// The program's figures (summed over the stages).
    pub program: ProgramStats,
    /// Source line of each motion (of the stages' motions in order: see
    /// [`Verification::stages`]).
    pub lines: Vec<usize>,
    /// Each program run, in order, with the index of its first motion (one for a
    /// single program).
    pub stages: Vec<StageSummary>,
    /// Sampling bound used, mm.
    pub sample_tol: f64,
    /// Along the design normals (true) or vertical (false).
    pub along_normals: bool,
    /// Cells whose normal deviation kept its first-order value (see [`crate::mow`]).
    pub normal_fallback: usize,
    /// Motions below the floor, when one was given ([`VerifyOptions::floor`]).
    pub floor: Option<FloorCheck>,
    /// Stage times.
    pub timings: Timings,
}

impl Verification {
    /// The stage (program) that motion `motion` (an index into [`Verification::lines`],
    /// the stock's last-motion record, regions and notes) came from.
    pub fn stage_of(&self, motion: usize) -> Option<&StageSummary> {
        stage_of(&self.stages, motion).map(|s| &self.stages[s])
    }
}

/// Verifies `program`, cut with `cutter`, against `design`: [`verify_stages`] with
/// one stage.
///
/// # Units
/// mm, mm/min, s.
///
/// # Errors
/// Invalid options (tolerance, cell size), a grid that does not fit in
/// `opts.max_bytes`, an empty design, an unusable cutter.
pub fn verify(
    design: Design<'_>,
    program: &Program,
    cutter: &Cutter,
    opts: &VerifyOptions,
    progress: &dyn Progress,
) -> Result<Verification, SimError> {
    verify_stages(design, &[Stage { program, cutter }], opts, progress)
}

/// The validated settings of one verification.
struct Checked {
    tol: f64,
    cell: f64,
    sample_tol: f64,
    tools: Vec<SimTool>,
}

/// Checks the options and cutters and that sampling the stages' motions stays within
/// budget, before anything is allocated.
fn check_settings(
    design: &Design<'_>,
    stages: &[Stage<'_>],
    opts: &VerifyOptions,
) -> Result<Checked, SimError> {
    if stages.is_empty() {
        return Err(SimError::Empty(
            "nothing to verify: no program was given".into(),
        ));
    }
    let tol = SimError::check_positive("tolerance", opts.tol)?;
    SimError::check_non_negative("allowed excess", opts.allowed_excess)?;
    SimError::check_positive("rapid rate", opts.rapid_rate)?;
    if let Some(floor) = opts.floor
        && !floor.is_finite()
    {
        return Err(SimError::InvalidParameter {
            name: "floor".into(),
            value: floor,
            expected: "a finite height, mm".into(),
        });
    }
    let cell = SimError::check_positive("cell size", opts.cell.unwrap_or(CELL_PER_TOL * tol))?;
    let sample_tol = SimError::check_positive("sample tolerance", opts.sample_tol())?;
    let tools = stages
        .iter()
        .map(|s| SimTool::new(s.cutter))
        .collect::<Result<Vec<_>, _>>()?;
    let (design_low, design_top) = match design {
        Design::Part(p) => (p.control_box().min.z, p.control_box().max.z),
        Design::Mesh(m) => (m.aabb().min.z, m.aabb().max.z),
    };
    let stock_top = opts.stock.top(design_top);
    for (stage, tool) in stages.iter().zip(&tools) {
        let p = stage.program;
        let (motions, file) = (&p.motions, &p.source);
        crate::sweep_budget::check_sampling(
            tool, motions, sample_tol, file, design_low, stock_top,
        )?;
    }
    Ok(Checked {
        tol,
        cell,
        sample_tol,
        tools,
    })
}

/// Verifies `stages` (programs run one after the other on one stock, each with its
/// own cutter; [`crate::stage`]) against `design`. Motion indices of the result
/// index the concatenated list of the stages' motions ([`Verification::stages`]).
/// Scallop crests look for cut valleys within the smallest tool radius.
///
/// # Units
/// mm, mm/min, s.
///
/// # Errors
/// No stage; invalid options (tolerance, cell size), a grid that does not fit in
/// `opts.max_bytes`, an empty design, an unusable cutter.
pub fn verify_stages(
    design: Design<'_>,
    stages: &[Stage<'_>],
    opts: &VerifyOptions,
    progress: &dyn Progress,
) -> Result<Verification, SimError> {
    let Checked {
        tol,
        cell,
        sample_tol,
        tools,
    } = check_settings(&design, stages, opts)?;
    let t0 = Instant::now();
    let surface = DesignSurface::new(design)?;
    let b = surface.bounds();
    let grid = window_grid(&b, opts.window, cell, opts.max_bytes)?;
    let field = surface.heights(&grid, opts.along_normals, progress);
    let mut stock = initial_stock(grid, &opts.stock, &field, b.max.z, progress)?;
    let t1 = Instant::now();
    let run = run_stages(
        &mut stock,
        stages,
        &tools,
        SimOptions {
            sample_tol,
            first_order: opts.first_order,
            stop_at_rapid_cut: opts.stop_at_rapid_cut,
            ..SimOptions::default()
        },
        opts.rapid_rate,
        progress,
    );
    let t2 = Instant::now();
    let mut values = vertical_deviation(stock.heights(), &field.heights);
    let mut normal_fallback = 0;
    if let (true, Some(normals)) = (opts.along_normals, &field.normals) {
        let (v, n) = normal_deviation(&grid, stock.heights(), &field.heights, normals, &values);
        (values, normal_fallback) = (v, n);
    }
    let dopts = DeviationOptions {
        tol,
        allowed_excess: opts.allowed_excess,
        valley_reach: tools
            .iter()
            .map(SimTool::radius)
            .fold(f64::INFINITY, f64::min),
        max_regions: opts.max_regions,
    };
    let deviation = analyse(
        &grid,
        values,
        &field.heights,
        stock.last_motion(),
        &run.lines,
        &dopts,
    );
    let t3 = Instant::now();
    Ok(Verification {
        grid,
        stock,
        design: field,
        deviation,
        sim: run.sim,
        program: run
            .stages
            .iter()
            .fold(ProgramStats::default(), |mut sum, s| {
                sum.add(&s.stats);
                sum
            }),
        lines: run.lines,
        stages: run.stages,
        sample_tol,
        along_normals: opts.along_normals,
        normal_fallback,
        floor: opts.floor.map(|f| crate::floor::check(stages, f, tol)),
        timings: Timings {
            design_s: (t1 - t0).as_secs_f64(),
            simulate_s: (t2 - t1).as_secs_f64(),
            deviation_s: (t3 - t2).as_secs_f64(),
        },
    })
}

/// The grid over `window` clipped to the design box `b` (all of it without one).
fn window_grid(
    b: &swarf_geom::Aabb,
    window: Option<[[f64; 2]; 2]>,
    cell: f64,
    max_bytes: u64,
) -> Result<Grid, SimError> {
    let [lo, hi] = window.unwrap_or([[b.min.x, b.min.y], [b.max.x, b.max.y]]);
    let (lo, hi) = (
        [lo[0].max(b.min.x), lo[1].max(b.min.y)],
        [hi[0].min(b.max.x), hi[1].min(b.max.y)],
    );
    if !(lo[0] < hi[0] && lo[1] < hi[1]) {
        return Err(SimError::InvalidParameter {
            name: "window".into(),
            value: hi[0] - lo[0],
            expected: "a rectangle that overlaps the design".into(),
        });
    }
    Grid::covering(lo, hi, cell, max_bytes)
}

/// The stock before any cut, over `grid`: `spec` with the design `field` (and its
/// top `design_top`, mm, for a box without a top).
fn initial_stock(
    grid: Grid,
    spec: &StockSpec,
    field: &DesignField,
    design_top: f64,
    progress: &dyn Progress,
) -> Result<Dexel, SimError> {
    let stock_heights;
    let init = match spec {
        StockSpec::Box { .. } => StockInit::Box {
            top: spec.top(design_top),
        },
        StockSpec::Offset { allowance } => StockInit::Offset {
            design: &field.heights,
            allowance: *allowance,
        },
        StockSpec::Mesh(mesh) => {
            let s = DesignSurface::new(Design::Mesh(mesh))?;
            stock_heights = s.heights(&grid, false, progress).heights;
            StockInit::Heights(&stock_heights)
        }
    };
    Dexel::new(grid, init)
}

/// Time, lengths and passes of a program (see the module doc).
pub fn program_stats(program: &Program, rapid_rate: f64) -> ProgramStats {
    let mut s = ProgramStats {
        motions: program.motions.len(),
        ..ProgramStats::default()
    };
    let mut in_pass = false;
    for m in &program.motions {
        let len = m.length();
        match m.kind {
            MotionKind::Rapid => {
                s.rapids += 1;
                s.rapid_length_mm += len;
                s.time_s += 60.0 * len / rapid_rate;
                in_pass = false;
            }
            kind => {
                if matches!(kind, MotionKind::Arc { .. }) {
                    s.arcs += 1;
                }
                if !in_pass {
                    s.passes += 1;
                    in_pass = true;
                }
                s.cutting_length_mm += len;
                if m.feed > 0.0 {
                    s.time_s += 60.0 * len / m.feed;
                } else {
                    s.unknown_feed_length_mm += len;
                }
            }
        }
    }
    s
}
