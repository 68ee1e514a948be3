//! Several programs in sequence on one stock: a finishing program, then the cleanup
//! program that takes out what its larger tool could not reach, each with its own
//! cutter.
//!
//! The stages run in order on the same [`Dexel`], each with its own [`SimTool`]. Each
//! program was read from its own file, so where the machine stands before its first
//! motion is unknown: every stage starts with [`SimOptions::known_start`] false. The
//! motions of all stages form one list, in stage order: stage `s` owns the indices
//! `first_motion .. first_motion + stats.motions` of its [`StageSummary`]. The stock's
//! last-motion record, [`crate::Verification::lines`], the regions of the deviation
//! and the notes of the simulation all index that list; [`stage_of`] tells which
//! stage (program) a motion came from, and `lines` its source line in that program.
//! With one stage the list is the program's own and nothing changes.

use crate::dexel::Dexel;
use crate::progress::Progress;
use crate::simulate::{SimOptions, SimReport, simulate_from};
use crate::sweep::SimTool;
use crate::verify::{ProgramStats, program_stats};
use serde::Serialize;
use swarf_tool::Cutter;
use swarf_toolpath::Program;

/// One program and the cutter it runs with.
#[derive(Debug, Clone, Copy)]
pub struct Stage<'a> {
    /// The program (its motions in the part frame).
    pub program: &'a Program,
    /// The cutter.
    pub cutter: &'a Cutter,
}

/// What one stage of a verification was.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageSummary {
    /// The program's file name ([`Program::source`]).
    pub source: String,
    /// The cutter as a spec string.
    pub tool: String,
    /// Index of the stage's first motion in the list of all stages' motions.
    pub first_motion: usize,
    /// The program's own figures (`stats.motions` motions).
    pub stats: ProgramStats,
}

/// All stages run: what the simulation did, the source line of every motion, and
/// each stage.
pub(crate) struct StagesRun {
    /// Simulation findings over all stages (motion indices in the concatenated list).
    pub sim: SimReport,
    /// Source line of each motion of the concatenated list.
    pub lines: Vec<usize>,
    /// Each stage, in order.
    pub stages: Vec<StageSummary>,
}

/// Runs `stages` in order over `dexel`, stage `s` with `tools[s]` (see the module
/// doc), simulated by `opts` (each stage's first motion only places the tool);
/// machining time at `rapid_rate` mm/min for rapids. A stop at a rapid that cut
/// ([`SimOptions::stop_at_rapid_cut`]) ends the run.
pub(crate) fn run_stages(
    dexel: &mut Dexel,
    stages: &[Stage<'_>],
    tools: &[SimTool],
    opts: SimOptions,
    rapid_rate: f64,
    progress: &dyn Progress,
) -> StagesRun {
    let opts = SimOptions {
        known_start: false,
        ..opts
    };
    let mut run = StagesRun {
        sim: SimReport::default(),
        lines: Vec::new(),
        stages: Vec::with_capacity(stages.len()),
    };
    for (stage, tool) in stages.iter().zip(tools) {
        let motions = &stage.program.motions;
        let first = run.lines.len();
        let sim = simulate_from(dexel, tool, motions, first, &opts, progress);
        run.sim.absorb(sim);
        run.lines.extend(motions.iter().map(|m| m.line));
        run.stages.push(StageSummary {
            source: stage.program.source.clone(),
            tool: stage.cutter.to_string(),
            first_motion: first,
            stats: program_stats(stage.program, rapid_rate),
        });
        if run.sim.stopped_after.is_some() {
            break;
        }
    }
    run
}

/// The stage whose motions hold index `motion` of the concatenated list (`None` past
/// the last motion).
///
/// # Example
/// ```
/// use swarf_sim::stage::{StageSummary, stage_of};
/// use swarf_sim::ProgramStats;
/// let stage = |first: usize, motions: usize| StageSummary {
///     source: String::new(),
///     tool: String::new(),
///     first_motion: first,
///     stats: ProgramStats { motions, ..ProgramStats::default() },
/// };
/// let stages = [stage(0, 3), stage(3, 0), stage(3, 2)];
/// assert_eq!(stage_of(&stages, 2), Some(0));
/// assert_eq!(stage_of(&stages, 3), Some(2));
/// assert_eq!(stage_of(&stages, 5), None);
/// ```
pub fn stage_of(stages: &[StageSummary], motion: usize) -> Option<usize> {
    let k = stages.partition_point(|s| s.first_motion <= motion);
    let s = stages.get(k.checked_sub(1)?)?;
    (motion < s.first_motion + s.stats.motions).then_some(k - 1)
}
