//! The CC paths of the die experiment (thesis 000 ch. 8), planned by the iso-planar
//! kernel with a job's defaults.

use swarf_geom::Part;
use swarf_path::strategy::iso::planar::{self, IsoPlanarParams};
use swarf_path::{Cutting, Finish};
use swarf_toolpath::Contact;

/// CC paths on the die: iso-planar at `angle` degrees off X, a fixed cross feed of
/// `stepover` mm and the chordal tolerance `tol` mm, for `tool` (a cutter spec).
///
/// # Panics
/// When the cutter spec does not parse or the plan fails (a broken fixture fails the
/// test).
pub fn die_cc(part: &Part, tool: &str, angle: f64, stepover: f64, tol: f64) -> Vec<Vec<Contact>> {
    let tool = tool.parse().expect("cutter spec");
    let params = IsoPlanarParams {
        finish: Finish {
            tolerance: tol,
            ..Finish::default()
        },
        stepover: Some(stepover),
        angle: angle.to_radians(),
        ..IsoPlanarParams::default()
    };
    let plan = planar::plan(part, &Cutting::new(tool), &params).expect("CC paths");
    swarf_fiveaxis::cc_paths::cc_paths(&plan.toolpath)
}
