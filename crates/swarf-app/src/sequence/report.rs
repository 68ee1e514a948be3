//! What a sequence reports: per operation and for the whole, and the stock's
//! gouge and rest after each operation.

use super::Operation;
use crate::holder::HolderSummary;
use crate::strategy::Strategy;
use serde::Serialize;
use swarf_sim::Dexel;

/// Engagement of a roughing operation, measured on the stock.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EngagementSummary {
    /// The stated largest engagement, degrees.
    pub limit_deg: f64,
    /// The largest measured on a clearing motion, degrees.
    pub max_deg: f64,
    /// Share of the cutting motions above the limit plus the measurement's rim step
    /// (1 degree).
    pub over_limit: f64,
    /// Share of the clearing motions that met no material.
    pub air: f64,
    /// Cutting motions by engagement in 10 degree bins from 0.
    pub histogram_10deg: Vec<usize>,
    /// Entries (ramps into a level and their round at it), left out of the figures.
    pub entries: usize,
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
    /// Rapids of its program that removed material from the in-process stock (a
    /// crash on the machine): their lines in the operation's own program (a
    /// roughing's: the numbers of its planned moves, which it is simulated from).
    pub rapid_cut_lines: Vec<usize>,
    /// Motions of its program whose tool goes below the floor by more than the
    /// stock's tolerance ([`swarf_sim::floor`]): their lines in its program.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub below_floor_lines: Vec<usize>,
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
                        ", engagement max {:.0} deg (stated {:.0}), {:.1} % over, {:.0} % of \
                         clearing motions in air",
                        e.max_deg,
                        e.limit_deg,
                        100.0 * e.over_limit,
                        100.0 * e.air
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
                    "T{} {} ({}, {}): {} motions, {:.0} mm, {:.0} s{eng}{holder}; {} rapids in \
                     material; after it: {} gouge cells, {} cells more than {:.3} mm above the \
                     part",
                    op.number,
                    op.name,
                    op.strategy,
                    op.tool,
                    op.motions,
                    op.cutting_length_mm,
                    op.time_s,
                    op.rapid_cut_lines.len(),
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

/// The report of an operation of `(cutting length mm, time s)`, before the stock
/// is looked at.
pub(super) fn op_report(
    op: &Operation,
    (cutting_length_mm, time_s): (f64, f64),
    engagement: Option<EngagementSummary>,
) -> OperationReport {
    let job = &op.job;
    OperationReport {
        name: op.name.clone(),
        number: op.number,
        tool: job.tool.to_string(),
        strategy: job.strategy.name().to_lowercase(),
        motions: 0,
        cutting_length_mm,
        time_s,
        engagement,
        rapid_cut_lines: Vec::new(),
        below_floor_lines: Vec::new(),
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
pub(super) fn deviation(
    dexel: &Dexel,
    design: &[f64],
    op: &Operation,
    tol: f64,
    r: &mut OperationReport,
) {
    let s = &op.job.strategy;
    let leave = match s {
        Strategy::Roughing(r) => r.allowance,
        _ => s.scallop().unwrap_or(0.0),
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
pub(super) fn rest_cells(dexel: &Dexel, design: &[f64], limit: f64) -> Vec<[f64; 3]> {
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
