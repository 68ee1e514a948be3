//! A sequence run: each operation planned on the in-process stock, posted, read
//! back, simulated on the stock and reported (module doc of [`super`]).

use super::{Operation, Sequence, Stock, StockKind};
use crate::cleanup::part_mesh;
use crate::error::{AppError, Result};
use crate::holder::{POSE_SPACING, check_program};
use crate::model::{Model, load_model_with};
use crate::outputs::Outputs;
use crate::plan::{PlanInput, plan};
use crate::plan_job::part_arg;
use serde::Serialize;
use std::path::Path;
use swarf_geom::TriMesh;
use swarf_nc::read::{GcodeReadOptions, Motion, MotionKind, Program, parse_gcode};
use swarf_path::roughing::{RoughingReport, RoughingStock, entry_moves, plan as plan_roughing};
use swarf_path::{Plan, PlanReport, StrategyKind};
use swarf_rest::{CleanupParams, Source, detect, plan_cleanup};
use swarf_sim::engagement::measure_engagement;
use swarf_sim::grid::DEFAULT_MAX_BYTES;
use swarf_sim::simulate_from;
use swarf_sim::verify::program_stats;
use swarf_sim::{Design, DesignSurface, Dexel, Grid, Quiet, SimOptions, SimTool, StockInit};
use swarf_tool::holder::vertical::StickOut;
use swarf_tool::library::LibraryTool;
use swarf_toolpath::{Move, MoveKind, motion_stats};

/// Engagement of a roughing operation, measured on the stock.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EngagementSummary {
    /// The stated largest engagement, degrees.
    pub limit_deg: f64,
    /// The largest measured on a clearing motion, degrees.
    pub max_deg: f64,
    /// Share of the cutting motions above the limit plus 5 degrees.
    pub over_limit: f64,
    /// Cutting motions by engagement in 10 degree bins from 0.
    pub histogram_10deg: Vec<usize>,
    /// Entries (ramps into a level and their round at it), left out of the figures.
    pub entries: usize,
}

/// The holder check of an operation that cleared.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HolderSummary {
    /// The library's stick-out, mm.
    pub stick_out: f64,
    /// Poses checked.
    pub poses: usize,
    /// The least clearance of shank or holder over the part, mm.
    pub min_clearance: Option<f64>,
    /// The shortest stick-out that clears (vertical poses).
    pub shortest: StickOut,
}

/// Checks the shank and holder of `tool` at every pose of `program` (every motion's
/// end and every [`POSE_SPACING`] mm along it).
///
/// # Errors
/// A collision: its line, place and depth, and the shortest stick-out that clears.
fn holder_check(mesh: &TriMesh, program: &Program, tool: &LibraryTool) -> Result<HolderSummary> {
    let check = check_program(mesh, program, tool, POSE_SPACING)?;
    if !check.collisions.is_empty() {
        return Err(AppError::Message(check.summary()));
    }
    Ok(HolderSummary {
        stick_out: check.vertical.stick_out,
        poses: check.poses,
        min_clearance: check.vertical.min_clearance.map(|(_, c)| c),
        shortest: check.vertical.shortest,
    })
}

/// What one operation did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OperationReport {
    /// Name.
    pub name: String,
    /// T number.
    pub number: u32,
    /// Cutter spec.
    pub tool: String,
    /// Strategy.
    pub strategy: String,
    /// Motions of its program.
    pub motions: usize,
    /// Cutting length, mm.
    pub cutting_length_mm: f64,
    /// Estimated machining time, s.
    pub time_s: f64,
    /// Roughing: engagement measured on the stock.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub engagement: Option<EngagementSummary>,
    /// Cells below the design by more than the tolerance after it.
    pub gouge_cells: usize,
    /// Deepest of them, mm (0 for none).
    pub worst_gouge_mm: f64,
    /// Cells more than `rest_limit_mm` above the design after it.
    pub rest_cells: usize,
    /// The material the operation was to leave plus the tolerance, mm.
    pub rest_limit_mm: f64,
    /// Highest material above the design, mm.
    pub max_rest_mm: f64,
    /// The library tool's shank and holder against the part at every pose.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub holder: Option<HolderSummary>,
    /// Planning time, s (not part of deterministic outputs).
    #[serde(skip)]
    pub plan_s: f64,
    /// Posting, reading back, simulating and measuring time, s (not part of
    /// deterministic outputs).
    #[serde(skip)]
    pub verify_s: f64,
}

/// What a sequence did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SequenceReport {
    /// Name.
    pub name: Option<String>,
    /// The stock's grid: cells across, along, cell size (mm).
    pub grid: (usize, usize, f64),
    /// Each operation.
    pub operations: Vec<OperationReport>,
    /// Machining time of the whole program, s.
    pub time_s: f64,
    /// The operations' programs (G-code), in order.
    #[serde(skip)]
    pub programs: Vec<String>,
    /// The whole program, a tool change per operation.
    #[serde(skip)]
    pub program: String,
    /// Cells left more than the last operation's limit above the design: centre x,
    /// y and the material above the design, mm.
    #[serde(skip)]
    pub rest: Vec<[f64; 3]>,
}

impl SequenceReport {
    /// One line per operation, then the whole program's time.
    pub fn lines(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .operations
            .iter()
            .map(|op| {
                let eng = op.engagement.as_ref().map_or(String::new(), |e| {
                    format!(
                        ", engagement max {:.0} deg, {:.1} % over {:.0} deg",
                        e.max_deg,
                        100.0 * e.over_limit,
                        e.limit_deg + 5.0
                    )
                });
                let holder = op.holder.as_ref().map_or(String::new(), |h| {
                    format!(
                        "; holder clears by {:.2} mm at stick-out {} mm",
                        h.min_clearance.unwrap_or(f64::INFINITY),
                        h.stick_out
                    )
                });
                format!(
                    "T{} {} ({}, {}): {} motions, {:.0} mm, {:.0} s{eng}{holder}; after it: {} \
                     gouge cells, {} cells more than {:.3} mm above the part",
                    op.number,
                    op.name,
                    op.strategy,
                    op.tool,
                    op.motions,
                    op.cutting_length_mm,
                    op.time_s,
                    op.gouge_cells,
                    op.rest_cells,
                    op.rest_limit_mm
                )
            })
            .collect();
        out.push(format!("whole program: {:.0} s", self.time_s));
        out
    }
}

/// What every operation of a sequence shares: the part, its mesh, the design's
/// height per stock cell, the post and how its programs are read.
struct Shop<'a> {
    seq: &'a Sequence,
    model: Model,
    mesh: TriMesh,
    design: Vec<f64>,
    post: swarf_nc::Post,
    read: GcodeReadOptions<'static>,
}

/// Plans, posts and simulates every operation of `seq` in order on one stock
/// (module doc of [`super`]).
///
/// # Errors
/// The part or stock cannot be read; an operation cannot be planned (the error
/// names it); an operation's program does not read back.
pub fn plan_sequence(seq: &Sequence, job_dir: &Path, out: &mut Outputs) -> Result<SequenceReport> {
    let (shop, mut dexel) = open_shop(seq, job_dir)?;
    let grid = *dexel.grid();
    let mut report = SequenceReport {
        name: seq.name.clone(),
        grid: (grid.nx, grid.ny, grid.cell),
        operations: Vec::new(),
        time_s: 0.0,
        programs: Vec::new(),
        program: String::new(),
        rest: Vec::new(),
    };
    let mut motions_before = 0;
    let mut all_moves = Vec::with_capacity(seq.operations.len());
    for k in 0..seq.operations.len() {
        let (r, text, moves) = run_operation(&shop, k, &mut dexel, motions_before)?;
        motions_before += r.motions;
        report.time_s += r.time_s;
        report.operations.push(r);
        report.programs.push(text);
        all_moves.push(moves);
    }
    report.program = whole_program(&shop, &all_moves, motions_before)?;
    if let Some(file) = &seq.output.gcode {
        out.write(file, report.program.as_bytes())?;
    }
    if let Some(limit) = report.operations.last().map(|o| o.rest_limit_mm) {
        report.rest = rest_cells(&dexel, &shop.design, limit);
    }
    if let Some(file) = &seq.output.summary {
        out.write_json(file, &report)?;
    }
    Ok(report)
}

/// The part, the design over the stock's grid, the post, and the stock.
fn open_shop<'a>(seq: &'a Sequence, job_dir: &Path) -> Result<(Shop<'a>, Dexel)> {
    let first = &seq.operations[0].job;
    let model = load_model_with(&part_arg(first, job_dir), &first.load_options())?;
    let mesh = part_mesh(&model, seq.stock.tol.min(first.strategy.tolerance))?.into_owned();
    let b = mesh.aabb();
    let m = seq.stock.margin;
    let grid = Grid::covering(
        [b.min.x - m, b.min.y - m],
        [b.max.x + m, b.max.y + m],
        seq.stock.cell,
        DEFAULT_MAX_BYTES,
    )?;
    let design = DesignSurface::new(Design::Mesh(&mesh))?
        .heights(&grid, false, &Quiet)
        .heights;
    if seq.stock.kind == StockKind::Box
        && let Some(top) = seq.stock.top
        && top < b.max.z
    {
        return Err(AppError::Message(format!(
            "stock.top: {top} mm is below the part's top ({:.3} mm): expected a box that holds the part",
            b.max.z
        )));
    }
    let dexel = initial_stock(&seq.stock, grid, &design, b.max.z, job_dir)?;
    let spec = seq.output.post.as_deref().unwrap_or("linuxcnc");
    let post = swarf_nc::Post::load(spec, job_dir)
        .map_err(|e| AppError::Message(format!("output.post = {spec:?}: {e}")))?;
    let read = GcodeReadOptions {
        language: post.reader(),
        ..GcodeReadOptions::default()
    };
    let shop = Shop {
        seq,
        model,
        mesh,
        design,
        post,
        read,
    };
    Ok((shop, dexel))
}

/// Operation `k`: planned on the stock, posted, read back, its holder checked,
/// simulated on the stock (motions numbered from `first`) and reported; with its
/// program and moves.
fn run_operation(
    shop: &Shop<'_>,
    k: usize,
    dexel: &mut Dexel,
    first: usize,
) -> Result<(OperationReport, String, Vec<Move>)> {
    let seq = shop.seq;
    let op = &seq.operations[k];
    let named = |e: AppError| AppError::Message(format!("operation[{k}] ({}): {e}", op.name));
    let reference = k.checked_sub(1).map(|p| seq.operations[p].job.tool);
    let start = std::time::Instant::now();
    let (planned, roughing) = plan_operation(op, shop, dexel, reference).map_err(named)?;
    let plan_s = start.elapsed().as_secs_f64();
    let start = std::time::Instant::now();
    let moves = planned.toolpath.moves();
    let text = swarf_nc::write_gcode(&moves, &op.job.feeds, &gcode_options(op, &shop.post, seq))
        .map_err(|e| named(e.into()))?;
    let program = parse_gcode(&text, &op.name, &shop.read).map_err(|e| named(e.into()))?;
    let holder = match &op.library_tool {
        Some(tool) => Some(holder_check(&shop.mesh, &program, tool).map_err(named)?),
        None => None,
    };
    let mut r = match &roughing {
        Some(rough) => measure_roughing(op, dexel, &moves, rough, first)?,
        None => simulate_operation(op, dexel, &program, first)?,
    };
    r.motions = program.motions.len();
    r.holder = holder;
    r.plan_s = plan_s;
    deviation(dexel, &shop.design, op, seq.stock.tol, &mut r);
    r.verify_s = start.elapsed().as_secs_f64();
    Ok((r, text, moves))
}

/// The stock before the first operation.
fn initial_stock(
    stock: &Stock,
    grid: Grid,
    design: &[f64],
    part_top: f64,
    job_dir: &Path,
) -> Result<Dexel> {
    Ok(match stock.kind {
        StockKind::Box => Dexel::new(
            grid,
            StockInit::Box {
                top: stock.top.unwrap_or(part_top + 1.0),
            },
        )?,
        StockKind::Offset => Dexel::new(
            grid,
            StockInit::Offset {
                design,
                allowance: stock.allowance,
            },
        )?,
        StockKind::Mesh => {
            let file = stock.file.as_deref().unwrap_or_default();
            let path = job_dir.join(file);
            let mesh = swarf_io::read_mesh(&path)
                .map_err(|e| AppError::Message(format!("stock.file: {e}")))?;
            let heights = DesignSurface::new(Design::Mesh(&mesh))?
                .heights(&grid, false, &Quiet)
                .heights;
            Dexel::new(grid, StockInit::Heights(&heights))?
        }
    })
}

/// The operation's plan on the stock as it stands (and a roughing's report).
fn plan_operation(
    op: &Operation,
    shop: &Shop<'_>,
    dexel: &Dexel,
    reference: Option<swarf_tool::Cutter>,
) -> Result<(Plan, Option<RoughingReport>)> {
    let (model, mesh, design, tol) = (&shop.model, &shop.mesh, &shop.design, shop.seq.stock.tol);
    let job = &op.job;
    let plan = match job.strategy.kind {
        StrategyKind::Roughing => {
            let grid = *dexel.grid();
            let material = |x: f64, y: f64| {
                grid.cell_of(x, y)
                    .map_or(f64::NEG_INFINITY, |(i, j)| dexel.height(i, j))
            };
            let top = dexel
                .heights()
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max);
            let stock = RoughingStock {
                min: grid.origin,
                max: grid.max(),
                top,
                material: &material,
            };
            let (plan, report) = plan_roughing(mesh, &stock, &job.roughing_params())?;
            return Ok((plan, Some(report)));
        }
        StrategyKind::Cleanup => {
            let reference = reference.ok_or_else(|| {
                AppError::Message(
                    "a cleanup cannot be the first operation: it cleans up after the one before"
                        .into(),
                )
            })?;
            let excess: Vec<f64> = dexel
                .heights()
                .iter()
                .zip(design)
                .map(|(h, d)| if d.is_finite() { h - d } else { f64::NAN })
                .collect();
            let source = Source::Stock {
                grid: dexel.grid(),
                excess: &excess,
                design,
            };
            // Every region the stock shows is rest of the stock kind: all are cleaned.
            let detection = detect(mesh, &reference, source, tol, &job.region_params())?;
            let params = CleanupParams {
                finish: job.finish(),
                pattern: job.strategy.pattern,
                passes: job.strategy.passes,
                scallop: job.strategy.scallop.unwrap_or(job.strategy.tolerance),
            };
            let toolpath = plan_cleanup(mesh, &detection.regions, &reference, &params)?;
            Plan {
                toolpath,
                report: PlanReport::default(),
                double_contacts: Vec::new(),
            }
        }
        _ => match model {
            Model::Patches(part) if !matches!(job.strategy.kind, StrategyKind::Raster) => {
                plan(job, PlanInput::Part(part))?
            }
            _ => plan(job, PlanInput::Mesh(mesh))?,
        },
    };
    Ok((plan, None))
}

/// The operation's G-code options: the post, its T number and a comment naming it.
fn gcode_options(op: &Operation, post: &swarf_nc::Post, seq: &Sequence) -> swarf_nc::GcodeOptions {
    swarf_nc::GcodeOptions {
        post: post.clone(),
        units: seq.output.units,
        tool_number: op.number,
        comments: vec![section_comment(op)],
        ..swarf_nc::GcodeOptions::default()
    }
}

fn section_comment(op: &Operation) -> String {
    format!(
        "operation {}: {:?} with {}",
        op.name, op.job.strategy.kind, op.job.tool
    )
}

/// The whole program: every operation's moves after its tool change; checked to
/// read back whole, as `motions` motions.
///
/// # Errors
/// A program the post refuses, or one that does not read back.
fn whole_program(shop: &Shop<'_>, moves: &[Vec<Move>], motions: usize) -> Result<String> {
    let seq = shop.seq;
    let comments: Vec<Vec<String>> = seq
        .operations
        .iter()
        .map(|op| vec![section_comment(op)])
        .collect();
    let sections: Vec<swarf_nc::ToolSection<'_>> = seq
        .operations
        .iter()
        .zip(moves)
        .zip(&comments)
        .map(|((op, moves), comments)| swarf_nc::ToolSection {
            moves,
            feeds: &op.job.feeds,
            tool_number: op.number,
            comments,
        })
        .collect();
    let header = vec![
        format!(
            "swarf sequence: {}",
            seq.name.as_deref().unwrap_or(&seq.part)
        ),
        format!("part: {}", seq.part),
    ];
    let opts = swarf_nc::GcodeOptions {
        post: shop.post.clone(),
        units: seq.output.units,
        comments: header,
        ..swarf_nc::GcodeOptions::default()
    };
    let program = swarf_nc::write_gcode_sections(&sections, &opts)?;
    let back = parse_gcode(&program, "the whole program", &shop.read)?;
    if let Some(stop) = &back.stopped {
        return Err(AppError::Message(format!(
            "the whole program does not read back: {stop}"
        )));
    }
    if back.motions.len() != motions {
        return Err(AppError::Message(format!(
            "the whole program reads back as {} motions, its operations as {motions}",
            back.motions.len()
        )));
    }
    Ok(program)
}

/// Simulates the operation's program on the stock, its motions numbered from
/// `first`.
fn simulate_operation(
    op: &Operation,
    dexel: &mut Dexel,
    program: &Program,
    first: usize,
) -> Result<OperationReport> {
    let job = &op.job;
    let tool = SimTool::new(&job.tool)?;
    simulate_from(
        dexel,
        &tool,
        &program.motions,
        first,
        &sim_options(op),
        &Quiet,
    );
    let stats = program_stats(program, job.feeds.rapid);
    Ok(op_report(op, (stats.cutting_length_mm, stats.time_s), None))
}

/// Simulates a roughing's planned moves on the stock, measuring the engagement of
/// every clearing move (its entries, slots by design, left out) before it cuts.
/// The moves are the program's before rounding to its words (1e-4 mm).
fn measure_roughing(
    op: &Operation,
    dexel: &mut Dexel,
    moves: &[Move],
    rough: &RoughingReport,
    first: usize,
) -> Result<OperationReport> {
    let job = &op.job;
    let tool = SimTool::new(&job.tool)?;
    let mut at = moves.first().map_or_else(
        || swarf_tool::Pose::vertical(swarf_geom::Point3::origin()),
        |m| m.to,
    );
    let motions: Vec<Motion> = moves
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let motion = Motion {
                kind: match m.kind {
                    MoveKind::Rapid => MotionKind::Rapid,
                    MoveKind::Feed => MotionKind::Linear,
                },
                start: at,
                end: m.to,
                feed: m.feed,
                line: k + 1,
            };
            at = m.to;
            motion
        })
        .collect();
    let eng = measure_engagement(dexel, &tool, &motions, first, &sim_options(op), &Quiet)
        .without(&entry_moves(moves, rough));
    let limit = job.roughing_params().max_engagement.to_degrees();
    let cutting = eng.cutting();
    let over = cutting
        .iter()
        .filter(|a| a.to_degrees() > limit + 5.0)
        .count();
    let summary = EngagementSummary {
        limit_deg: limit,
        max_deg: eng.max().to_degrees(),
        over_limit: over as f64 / cutting.len().max(1) as f64,
        histogram_10deg: eng.histogram(10.0),
        entries: rough.entries.len(),
    };
    let stats = motion_stats(moves, job.feeds.rapid);
    Ok(op_report(
        op,
        (stats.cutting_length, stats.time_s),
        Some(summary),
    ))
}

fn sim_options(op: &Operation) -> SimOptions {
    SimOptions {
        sample_tol: 0.25 * op.job.strategy.tolerance,
        known_start: false,
    }
}

/// The report of an operation of `(cutting length mm, time s)`, before the stock
/// is looked at.
fn op_report(
    op: &Operation,
    (cutting_length_mm, time_s): (f64, f64),
    engagement: Option<EngagementSummary>,
) -> OperationReport {
    let job = &op.job;
    OperationReport {
        name: op.name.clone(),
        number: op.number,
        tool: job.tool.to_string(),
        strategy: format!("{:?}", job.strategy.kind).to_lowercase(),
        motions: 0,
        cutting_length_mm,
        time_s,
        engagement,
        gouge_cells: 0,
        worst_gouge_mm: 0.0,
        rest_cells: 0,
        rest_limit_mm: 0.0,
        max_rest_mm: 0.0,
        holder: None,
        plan_s: 0.0,
        verify_s: 0.0,
    }
}

/// Gouge and rest on the stock after an operation.
fn deviation(dexel: &Dexel, design: &[f64], op: &Operation, tol: f64, r: &mut OperationReport) {
    let s = &op.job.strategy;
    let leave = match s.kind {
        StrategyKind::Roughing => op.job.roughing_params().allowance,
        _ => s.scallop.unwrap_or(0.0),
    };
    r.rest_limit_mm = leave + tol;
    for (h, d) in dexel.heights().iter().zip(design) {
        if !d.is_finite() || !h.is_finite() {
            continue;
        }
        let e = h - d;
        if e < -tol {
            r.gouge_cells += 1;
            r.worst_gouge_mm = r.worst_gouge_mm.max(-e);
        }
        if e > r.rest_limit_mm {
            r.rest_cells += 1;
        }
        r.max_rest_mm = r.max_rest_mm.max(e);
    }
}

/// The cells more than `limit` above the design: centre and excess.
fn rest_cells(dexel: &Dexel, design: &[f64], limit: f64) -> Vec<[f64; 3]> {
    let grid = dexel.grid();
    let mut out = Vec::new();
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let d = design[j * grid.nx + i];
            let e = dexel.height(i, j) - d;
            if d.is_finite() && e.is_finite() && e > limit {
                let [x, y] = grid.centre(i, j);
                out.push([x, y, e]);
            }
        }
    }
    out
}
