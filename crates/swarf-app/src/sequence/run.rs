//! A sequence run: each operation planned on the in-process stock, posted, read
//! back, simulated on the stock and reported (module doc of [`super`]).

use super::report::{
    EngagementSummary, OperationReport, SequenceReport, deviation, op_report, rest_cells,
};
use super::{Operation, Sequence};
use crate::cleanup::part_mesh;
use crate::error::{AppError, Result};
use crate::gate::Gate;
use crate::holder::{HolderSummary, POSE_SPACING, check_program};
use crate::model::{Model, load_model_with};
use crate::outputs::Outputs;
use crate::plan::{PlanInput, plan};
use crate::plan_job::part_arg;
use crate::stock::{Stock, StockKind};
use crate::strategy::Strategy;
use std::path::Path;
use swarf_geom::TriMesh;
use swarf_nc::read::{GcodeReadOptions, Motion, Program, parse_gcode};
use swarf_path::strategy::roughing::{
    RoughingReport, RoughingStock, entry_moves, plan as plan_roughing,
};
use swarf_path::{Plan, PlanReport};
use swarf_rest::{Source, detect, plan_cleanup};
use swarf_sim::engagement::measure_engagement;
use swarf_sim::grid::DEFAULT_MAX_BYTES;
use swarf_sim::simulate_from;
use swarf_sim::verify::program_stats;
use swarf_sim::{Design, DesignSurface, Dexel, Grid, Quiet, SimOptions, SimTool, StockInit};
use swarf_tool::library::LibraryTool;
use swarf_toolpath::{Move, motion_stats};

/// Checks the shank and holder of `tool` at every pose of `program` (every motion's
/// end and every [`POSE_SPACING`] mm along it).
///
/// # Errors
/// A collision: its line, place and depth, and the shortest stick-out that clears.
fn holder_check(mesh: &TriMesh, program: &Program, tool: &LibraryTool) -> Result<HolderSummary> {
    check_program(mesh, program, tool, POSE_SPACING)?.cleared()
}

/// What every operation of a sequence shares: the part, its mesh, the design's
/// height per stock cell, the post and how its programs are read.
struct Shop<'a> {
    seq: &'a Sequence,
    model: Model,
    mesh: TriMesh,
    design: Vec<f64>,
    /// The lowest height of the tool's lowest point ([`crate::stock::Stock::floor`]).
    floor: f64,
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
    let verdict = gate_verdict(seq, shop.floor, &report.operations)?;
    report.program = whole_program(&shop, &all_moves, motions_before, verdict)?;
    if let Some(file) = &seq.output.gcode {
        out.write(file, report.program.as_bytes())?;
        let mut record = sequence_record(seq);
        record.programs = vec![file.clone()];
        out.write_json(crate::plan_record::record_name(file), &record)?;
    }
    if let Some(limit) = report.operations.last().map(|o| o.rest_limit_mm) {
        report.rest = rest_cells(&dexel, &shop.design, limit);
    }
    if let Some(file) = &seq.output.summary {
        out.write_json(file, &report)?;
    }
    Ok(report)
}

/// The plan record of the sequence's program (`crate::plan_record`): every
/// operation's tool and what it was planned for.
fn sequence_record(seq: &Sequence) -> crate::plan_record::PlanRecord {
    use crate::plan_record::{OperationRecord, PlanRecord, ToolRecord};
    let tools = seq
        .operations
        .iter()
        .map(|op| ToolRecord {
            number: op.number,
            cutter: op.job.tool.to_string(),
            name: op.job.library_tool.as_ref().map(|t| t.name.clone()),
        })
        .collect();
    let operations = seq
        .operations
        .iter()
        .map(|op| OperationRecord {
            name: op.name.clone(),
            strategy: op.job.strategy.kind().into(),
            tool: op.number,
            scallop: op.job.strategy.scallop(),
            tolerance: op.job.tolerance(),
        })
        .collect();
    PlanRecord::new(
        &seq.part,
        seq.output.units,
        tools,
        operations,
        seq.output.post.as_deref().unwrap_or("linuxcnc"),
    )
}

/// The part, the design over the stock's grid, the post, and the stock.
fn open_shop<'a>(seq: &'a Sequence, job_dir: &Path) -> Result<(Shop<'a>, Dexel)> {
    let first = &seq.operations[0].job;
    let model = load_model_with(&part_arg(first, job_dir), &first.load_options())?;
    let mesh = part_mesh(&model, seq.stock.tol.min(first.tolerance()))?.into_owned();
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
    let floor = seq.stock.floor(b.min.z, b.max.z)?;
    let dexel = initial_stock(&seq.stock, grid, &design, b.max.z, job_dir)?;
    let spec = seq.output.post.as_deref().unwrap_or("linuxcnc");
    let post_error =
        |e: swarf_nc::NcError| AppError::Message(format!("output.post = {spec:?}: {e}"));
    let post = swarf_nc::Post::load(spec, job_dir).map_err(post_error)?;
    post.check_tools("sequence", seq.operations.iter().map(|o| o.number))
        .map_err(post_error)?;
    let read = GcodeReadOptions {
        language: post.reader(),
        ..GcodeReadOptions::default()
    };
    let shop = Shop {
        seq,
        model,
        mesh,
        design,
        floor,
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
    let holder = match &op.job.library_tool {
        Some(tool) => Some(holder_check(&shop.mesh, &program, tool).map_err(named)?),
        None => None,
    };
    let mut r = match &roughing {
        Some(rough) => measure_roughing(op, dexel, &moves, rough, first)?,
        None => simulate_operation(op, dexel, &program, first)?,
    };
    r.motions = program.motions.len();
    let stage = swarf_sim::Stage {
        program: &program,
        cutter: &op.job.tool,
    };
    r.below_floor_lines = swarf_sim::floor::check(&[stage], shop.floor, seq.stock.tol)
        .below
        .iter()
        .map(|n| n.line)
        .collect();
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
    let mesh = stock.mesh(job_dir)?;
    let top = stock.top(part_top, mesh.as_ref())?;
    Ok(match (stock.kind, mesh) {
        (StockKind::Offset, _) => Dexel::new(
            grid,
            StockInit::Offset {
                design,
                allowance: stock.allowance,
            },
        )?,
        (_, Some(mesh)) => {
            let heights = DesignSurface::new(Design::Mesh(&mesh))?
                .heights(&grid, false, &Quiet)
                .heights;
            Dexel::new(grid, StockInit::Heights(&heights))?
        }
        (_, None) => Dexel::new(grid, StockInit::Box { top })?,
    })
}

/// The operation's job on the stock as it stands: the in-process stock is the
/// material its links stay above, and its XY box with the floor where its tool
/// may go.
fn on_stock(op: &Operation, shop: &Shop<'_>, dexel: &Dexel) -> crate::job::Job {
    let top = dexel
        .heights()
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = (dexel.grid().origin, dexel.grid().max());
    crate::job::Job {
        material_top: Some(top),
        reach: Some(swarf_toolpath::reach::Reach::around(
            shop.floor,
            [lo[0], lo[1], hi[0], hi[1]],
            op.job.tool.radius(),
        )),
        ..op.job.clone()
    }
}

/// The operation's plan on the stock as it stands (and a roughing's report).
fn plan_operation(
    op: &Operation,
    shop: &Shop<'_>,
    dexel: &Dexel,
    reference: Option<swarf_tool::Cutter>,
) -> Result<(Plan, Option<RoughingReport>)> {
    let (model, mesh, design, tol) = (&shop.model, &shop.mesh, &shop.design, shop.seq.stock.tol);
    let job = &on_stock(op, shop, dexel);
    let top = job.material_top.unwrap_or_default();
    let plan = match &job.strategy {
        Strategy::Roughing(r) => {
            let grid = *dexel.grid();
            // Material to rough: stock above the design plus the allowance (the part
            // itself, and what an earlier roughing left of the allowance, are not).
            let leave = r.allowance + tol;
            let material = |x: f64, y: f64| {
                grid.cell_of(x, y).map_or(f64::NEG_INFINITY, |(i, j)| {
                    let h = dexel.height(i, j);
                    let d = design[j * grid.nx + i];
                    if d.is_finite() && h <= d + leave {
                        f64::NEG_INFINITY
                    } else {
                        h
                    }
                })
            };
            let stock = RoughingStock {
                min: grid.origin,
                max: grid.max(),
                top,
                material: &material,
            };
            let (mut plan, report) = plan_roughing(mesh, &stock, &job.cutting(), r)
                .map_err(|e| crate::plan::in_table("strategy", e))?;
            crate::plan::clip_to_reach(job, &mut plan)?;
            return Ok((plan, Some(report)));
        }
        Strategy::Cleanup(c) => {
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
            let detection = detect(mesh, &reference, source, tol, &c.regions())?;
            let toolpath = plan_cleanup(mesh, &detection.regions, &reference, &job.cutting(), c)?;
            let mut plan = Plan {
                toolpath,
                report: PlanReport::default(),
                double_contacts: Vec::new(),
            };
            crate::plan::clip_to_reach(job, &mut plan)?;
            plan
        }
        _ => match model {
            Model::Patches(part) if !matches!(job.strategy, Strategy::Raster(_)) => {
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
        arc_tolerance: seq.output.arc_tolerance_mm(),
        ..swarf_nc::GcodeOptions::default()
    }
}

fn section_comment(op: &Operation) -> String {
    format!(
        "operation {}: {} with {}",
        op.name,
        op.job.strategy.name(),
        op.job.tool
    )
}

/// The gate on a sequence ([`crate::gate`]): every operation is simulated on the
/// in-process stock as it is planned; a rapid in material, a gouge beyond the
/// stock's tolerance or a motion below the `floor` refuses the program (naming the
/// operations), unless the sequence allows it. Returns the program's header line.
///
/// # Errors
/// An unsafe program under [`Gate::Verify`].
fn gate_verdict(seq: &Sequence, floor: f64, ops: &[OperationReport]) -> Result<String> {
    let mut gouged = 0;
    let mut found = Vec::new();
    for op in ops {
        if !op.rapid_cut_lines.is_empty() {
            found.push(format!(
                "operation {}: {} rapids cut material (its program's lines {:?})",
                op.name,
                op.rapid_cut_lines.len(),
                op.rapid_cut_lines
            ));
        }
        if !op.below_floor_lines.is_empty() {
            found.push(format!(
                "operation {}: {} motions go below the floor at {:.3} mm (its program's lines \
                 {:?})",
                op.name,
                op.below_floor_lines.len(),
                floor,
                op.below_floor_lines
            ));
        }
        if op.gouge_cells > gouged {
            found.push(format!(
                "operation {}: gouges {} more cells beyond {} mm (worst {:.4} mm)",
                op.name,
                op.gouge_cells - gouged,
                seq.stock.tol,
                -op.worst_gouge_mm
            ));
            gouged = op.gouge_cells;
        }
    }
    match (found.is_empty(), seq.gate) {
        (true, _) => Ok(format!(
            "verified on the in-process stock: 0 rapids in material, 0 gouge cells beyond {} \
             mm, 0 motions below the floor at {floor:.3} mm",
            seq.stock.tol
        )),
        (false, Gate::Verify) => Err(AppError::Message(format!(
            "the program fails its verification on the in-process stock: {}; nothing written \
             (--allow-unsafe writes it, labelled)",
            found.join("; ")
        ))),
        (false, gate) => Ok(format!(
            "UNSAFE, written with {}: {}",
            if gate == Gate::Skip {
                "--no-verify"
            } else {
                "--allow-unsafe"
            },
            found.join("; ")
        )),
    }
}

/// The whole program: every operation's moves after its tool change; checked to
/// read back whole, as `motions` motions.
///
/// # Errors
/// A program the post refuses, or one that does not read back.
fn whole_program(
    shop: &Shop<'_>,
    moves: &[Vec<Move>],
    motions: usize,
    verdict: String,
) -> Result<String> {
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
        verdict,
    ];
    let opts = swarf_nc::GcodeOptions {
        post: shop.post.clone(),
        units: seq.output.units,
        comments: header,
        arc_tolerance: seq.output.arc_tolerance_mm(),
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
    let sim = simulate_from(
        dexel,
        &tool,
        &program.motions,
        first,
        &sim_options(op),
        &Quiet,
    );
    let stats = program_stats(program, job.feeds.rapid);
    let mut r = op_report(op, (stats.cutting_length_mm, stats.time_s), None);
    r.rapid_cut_lines = sim.rapid_cuts.iter().map(|n| n.line).collect();
    Ok(r)
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
    let start = moves.first().map_or_else(
        || swarf_tool::Pose::vertical(swarf_geom::Point3::origin()),
        |m| m.to,
    );
    let motions = Motion::of_moves(moves, start);
    let eng = measure_engagement(dexel, &tool, &motions, first, &sim_options(op), &Quiet)
        .without(&entry_moves(moves, rough));
    let Strategy::Roughing(r) = &job.strategy else {
        return Err(AppError::Message(format!(
            "operation {}: only roughing has its engagement measured",
            op.name
        )));
    };
    let limit = r.max_engagement.to_degrees();
    let cutting = eng.cutting();
    let over = cutting
        .iter()
        .filter(|a| a.to_degrees() > limit + swarf_sim::engagement::RIM_STEP_DEG)
        .count();
    let measured = eng.per_motion.iter().flatten().count();
    let summary = EngagementSummary {
        limit_deg: limit,
        max_deg: eng.max().to_degrees(),
        over_limit: over as f64 / cutting.len().max(1) as f64,
        air: (measured - cutting.len()) as f64 / measured.max(1) as f64,
        histogram_10deg: eng.histogram(10.0),
        entries: rough.entries.len(),
    };
    let stats = motion_stats(moves, job.feeds.rapid);
    let mut r = op_report(op, (stats.cutting_length, stats.time_s), Some(summary));
    r.rapid_cut_lines = eng.rapid_cuts.iter().map(|n| n.line).collect();
    Ok(r)
}

fn sim_options(op: &Operation) -> SimOptions {
    SimOptions {
        sample_tol: swarf_sim::verify::default_sample_tol(op.job.tolerance()),
        known_start: false,
        ..SimOptions::default()
    }
}
