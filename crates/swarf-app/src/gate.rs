//! The verification gate of `swarf plan`: every program a job writes is simulated
//! on the job's stock ([`crate::stock`]), rapids included, by the one verifier
//! ([`swarf_sim::verify_stages`], deviation along the design normals), before it is
//! written. A program with a rapid that removes material (a crash on the machine),
//! a gouge beyond the job's tolerance or a motion whose tool goes below the job's
//! floor ([`swarf_sim::floor`]; `stock.floor`, default the part's lowest point) is
//! refused, naming its G-code lines (of a
//! five-axis program: the line where the move ends; the tool path's move numbers
//! where no G-code is written), unless the job
//! is planned with [`Gate::AllowUnsafe`]: then it is written, and its header
//! comment and summary say what it does. [`Gate::Skip`] (`--no-verify`) writes
//! without verifying, and the header says that too.
//!
//! The gate's grid is coarser than `swarf verify`'s default where the part is
//! large ([`GATE_CELLS`] cells at most, never finer than the verifier's default
//! cell): the dexel is exact at its cell centres, so every gouge and rapid cut the
//! gate reports is there; features between cell centres are left to `swarf
//! verify`.
//!
//! Five-axis programs are simulated from their poses (part frame, the axis turned
//! by the one slerp, as their APT CL reads), on cells of at least
//! [`FIVE_AXIS_CELL`] mm: the tilted sweep visits every cell of a motion's
//! footprint at each of its samples. A five-axis finishing job's default stock is
//! the design raised by an allowance ([`crate::stock::Stock::near_net`]): a
//! tilted finishing tool in a block is buried to its holder, and the gate says so.

use crate::compare::FIVE_AXIS_CELL;
use crate::error::{AppError, Result};
use crate::job::Job;
use crate::model::Model;
use crate::stock::StockKind;
use crate::verify::design_of;
use serde::Serialize;
use std::path::Path;
use swarf_nc::read::{GcodeReadOptions, parse_gcode};
use swarf_sim::verify::CELL_PER_TOL;
use swarf_sim::{Quiet, Stage, StockSpec, VerifyOptions, verify_stages};
use swarf_toolpath::Move;
use swarf_toolpath::program::{Motion, Program};

/// Most cells of the gate's grid.
pub const GATE_CELLS: f64 = 500_000.0;

/// Findings of each kind named in a refusal.
const MAX_NAMED: usize = 10;

/// What the gate does with a job's program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Gate {
    /// Verify; refuse an unsafe program.
    #[default]
    Verify,
    /// Verify; write an unsafe program, labelled (`--allow-unsafe`).
    AllowUnsafe,
    /// Do not verify (`--no-verify`).
    Skip,
}

/// A motion the gate found unsafe.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Finding {
    /// Index of the motion in the program simulated.
    pub motion: usize,
    /// Its line in the program written (the move's number, `k + 1`, where no
    /// G-code is written).
    pub line: Option<usize>,
    /// How deep it cut, mm (a rapid: the material it removed; a gouge: below the
    /// design).
    pub depth: f64,
}

/// What the gate found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GateReport {
    /// The stock simulated.
    pub stock: String,
    /// Cell of the gate's grid, mm.
    pub cell: f64,
    /// Gouge tolerance, mm.
    pub tol: f64,
    /// Rapids that removed material.
    pub rapid_cuts: Vec<Finding>,
    /// The floor, mm (`None`: the job is not on its stock).
    pub floor: Option<f64>,
    /// Motions whose tool goes deeper than the tolerance below the floor, with
    /// that depth.
    pub below_floor: Vec<Finding>,
    /// Cells gouged beyond the tolerance.
    pub gouge_cells: usize,
    /// Deepest gouge, mm (0 without one).
    pub worst_gouge_mm: f64,
    /// The gouge regions, deepest first (at most 10).
    pub gouges: Vec<Finding>,
    /// Cells with more material left than the planned scallop and the tolerance.
    pub excess_cells: usize,
    /// Whether the program is written although unsafe ([`Gate::AllowUnsafe`]).
    pub written_unsafe: bool,
    /// Motions simulated when the gate stopped at the first rapid in material (it
    /// refuses the program; [`Gate::Verify`] only); `None`: every motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_after: Option<usize>,
    /// Time the gate took, s (not part of deterministic outputs).
    #[serde(skip)]
    pub seconds: f64,
}

impl GateReport {
    /// Whether the program is safe to run: no rapid in material, no gouge, no
    /// motion below the floor.
    pub fn safe(&self) -> bool {
        self.rapid_cuts.is_empty() && self.gouge_cells == 0 && self.below_floor.is_empty()
    }

    /// Every finding, of every kind.
    fn findings_mut(&mut self) -> impl Iterator<Item = &mut Finding> {
        self.rapid_cuts
            .iter_mut()
            .chain(self.gouges.iter_mut())
            .chain(self.below_floor.iter_mut())
    }

    /// The header comment of the program.
    pub fn comment(&self) -> String {
        let mut found = format!(
            "{} rapids in material, {} gouge cells beyond {} mm",
            self.rapid_cuts.len(),
            self.gouge_cells,
            self.tol
        );
        if let Some(floor) = self.floor {
            found += &format!(
                ", {} motions below the floor at {floor:.3} mm",
                self.below_floor.len()
            );
        }
        if self.safe() {
            format!(
                "verified on {}, {} mm cells: {found}",
                self.stock, self.cell
            )
        } else {
            format!(
                "UNSAFE, written with --allow-unsafe: on {}, {} mm cells, {found}",
                self.stock, self.cell
            )
        }
    }

    /// The refusal message: what was found, and where.
    pub fn refusal(&self) -> String {
        let named = |list: &[Finding], what: &dyn Fn(&Finding) -> String| {
            let at = |f: &Finding| match f.line {
                Some(l) => format!("line {l}"),
                None => format!("move {}", f.motion + 1),
            };
            let each: Vec<String> = list
                .iter()
                .take(MAX_NAMED)
                .map(|f| format!("{} ({})", at(f), what(f)))
                .collect();
            each.join(", ")
        };
        let mut parts = Vec::new();
        if !self.rapid_cuts.is_empty() {
            let n = self.rapid_cuts.len();
            let what = if n == 1 { "rapid cuts" } else { "rapids cut" };
            let deep = named(&self.rapid_cuts, &|f| format!("{:.3} mm deep", f.depth));
            parts.push(format!("{n} {what} material: {deep}"));
        }
        if self.gouge_cells > 0 {
            parts.push(format!(
                "{} cells gouged beyond {} mm, worst {:.4} mm, cut at {}",
                self.gouge_cells,
                self.tol,
                -self.worst_gouge_mm,
                named(&self.gouges, &|f| format!("{:.4} mm", -f.depth))
            ));
        }
        if !self.below_floor.is_empty() {
            let n = self.below_floor.len();
            let what = if n == 1 { "motion goes" } else { "motions go" };
            parts.push(format!(
                "{n} {what} below the floor at {:.3} mm (stock.floor): {}",
                self.floor.unwrap_or_default(),
                named(&self.below_floor, &|f| format!("{:.3} mm below", f.depth))
            ));
        }
        if let Some(n) = self.stopped_after {
            parts.push(format!(
                "the simulation stopped there, after {n} motions (--allow-unsafe simulates \
                 them all)"
            ));
        }
        format!(
            "the program fails its verification on {} ({} mm cells): {}; nothing written \
             (--allow-unsafe writes it, labelled; --no-verify skips the check)",
            self.stock,
            self.cell,
            parts.join("; ")
        )
    }
}

/// The stock of `job` as the verifier takes it (files relative to `dir`).
///
/// # Errors
/// A mesh stock that cannot be read.
pub fn stock_spec(job: &Job, dir: &Path) -> Result<StockSpec> {
    Ok(match job.stock.kind {
        StockKind::Box => StockSpec::Box {
            top: job.material_top,
        },
        StockKind::Offset => StockSpec::Offset {
            allowance: job.stock.allowance,
        },
        StockKind::Mesh => match job.stock.mesh(dir)? {
            Some(mesh) => StockSpec::Mesh(mesh),
            None => StockSpec::Box {
                top: job.material_top,
            },
        },
    })
}

/// The program the gate simulates: the three-axis G-code `text` as it reads back
/// (arcs and the post's rounding included; read as `read` says), else the tool
/// path's `moves` themselves (move `k` as line `k + 1`).
///
/// # Errors
/// G-code that does not read back whole.
pub fn program(moves: &[Move], text: Option<&str>, read: &GcodeReadOptions<'_>) -> Result<Program> {
    let Some(text) = text else {
        let mut p = Program::new("the job's moves");
        if let Some(first) = moves.first() {
            p.motions = Motion::of_moves(moves, first.to);
        }
        return Ok(p);
    };
    let p = parse_gcode(text, "the job's program", read)?;
    if let Some(stop) = &p.stopped {
        return Err(AppError::Message(format!(
            "the job's program does not read back: {stop}"
        )));
    }
    Ok(p)
}

/// Simulates `program` of `job` (cut with `job.tool`) on `stock` over `model`;
/// `scallop` is the material the plan leaves by design, mm.
///
/// # Errors
/// A verification the verifier refuses (a grid over its memory limit).
pub fn check(
    job: &Job,
    model: &Model,
    program: &Program,
    stock: StockSpec,
    scallop: f64,
) -> Result<GateReport> {
    let start = std::time::Instant::now();
    let tol = job.tolerance();
    let b = model.bounds();
    let area = (b.max.x - b.min.x) * (b.max.y - b.min.y);
    let tilted = program
        .motions
        .iter()
        .any(|m| !m.start.is_vertical() || !m.end.is_vertical());
    let least = if tilted { FIVE_AXIS_CELL } else { 0.0 };
    let cell = (CELL_PER_TOL * tol)
        .max((area / GATE_CELLS).sqrt())
        .max(least);
    let cell = (cell * 1e4).ceil() / 1e4;
    let opts = VerifyOptions {
        cell: Some(cell),
        tol,
        allowed_excess: scallop,
        stock,
        max_regions: MAX_NAMED,
        along_normals: true,
        // A rapid in material refuses the program: the rest is not needed for that.
        stop_at_rapid_cut: job.gate == Gate::Verify,
        floor: job.reach.map(|r| r.floor),
        ..VerifyOptions::default()
    };
    let stock_name = opts.stock.describe();
    let stage = Stage {
        program,
        cutter: &job.tool,
    };
    let v = verify_stages(design_of(model), &[stage], &opts, &Quiet)
        .map_err(|e| AppError::Message(format!("the verification gate: {e}")))?;
    let s = &v.deviation.summary;
    Ok(GateReport {
        stock: stock_name,
        cell,
        tol,
        rapid_cuts: v
            .sim
            .rapid_cuts
            .iter()
            .map(|n| Finding {
                motion: n.motion,
                line: None,
                depth: n.amount,
            })
            .collect(),
        floor: v.floor.as_ref().map(|f| f.floor),
        below_floor: v.floor.as_ref().map_or_else(Vec::new, |f| {
            f.below
                .iter()
                .map(|n| Finding {
                    motion: n.motion,
                    line: None,
                    depth: n.amount,
                })
                .collect()
        }),
        gouge_cells: s.gouge.cells,
        worst_gouge_mm: s.gouge.worst,
        gouges: s
            .gouges
            .iter()
            .filter_map(|r| {
                r.motion.map(|m| Finding {
                    motion: m,
                    line: None,
                    depth: r.worst,
                })
            })
            .collect(),
        excess_cells: s.excess.cells,
        written_unsafe: false,
        stopped_after: v.sim.stopped_after,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Sets each finding's line: the line of its motion in `program` (the program as
/// written, which may differ from the one simulated by header lines only).
pub fn locate(report: &mut GateReport, program: &Program) {
    for f in report.findings_mut() {
        f.line = program.motions.get(f.motion).map(|m| m.line);
    }
}

/// What a job's program is simulated from: its moves, the three-axis G-code as
/// written without the gate's header line (`None`: none written, or five-axis), and
/// how that G-code reads.
pub type Simulated<'a> = (&'a [Move], Option<&'a str>, &'a GcodeReadOptions<'a>);

/// The gate on a job's program ([`check`] of [`program`]), on `stock` (`None`:
/// skipped).
///
/// # Errors
/// As [`program`] and [`check`].
pub fn run(
    job: &Job,
    model: &Model,
    (moves, text, read): Simulated<'_>,
    stock: Option<&StockSpec>,
    scallop: f64,
) -> Result<Option<GateReport>> {
    let Some(stock) = stock else {
        return Ok(None);
    };
    let simulated = program(moves, text, read)?;
    check(job, model, &simulated, stock.clone(), scallop).map(Some)
}

/// The program's header line about the gate: its verdict, or that it was skipped.
pub fn comment(gate: Option<&GateReport>) -> String {
    gate.map_or_else(|| "not verified: --no-verify".into(), GateReport::comment)
}

/// After the program is written (`text`: its three-axis G-code, with the gate's
/// line; `move_lines`: a five-axis program's line where each move ends, empty
/// without one): refuses an unsafe one under [`Gate::Verify`], naming its lines, and
/// marks it written otherwise.
///
/// # Errors
/// The refusal ([`GateReport::refusal`]); written G-code that does not read back.
pub fn conclude(
    job: &Job,
    gate: Option<&mut GateReport>,
    (moves, text, read): Simulated<'_>,
    move_lines: &[usize],
) -> Result<()> {
    let Some(g) = gate.filter(|g| !g.safe()) else {
        return Ok(());
    };
    if text.is_some() {
        locate(g, &program(moves, text, read)?);
    } else if !move_lines.is_empty() {
        // The gate simulated the moves themselves: motion k is move k.
        for f in g.findings_mut() {
            f.line = move_lines.get(f.motion).copied();
        }
    }
    if job.gate == Gate::Verify {
        return Err(AppError::Message(g.refusal()));
    }
    g.written_unsafe = true;
    Ok(())
}
