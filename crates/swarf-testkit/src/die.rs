//! The CC paths of the die experiment (thesis 000 ch. 8), planned as the jobs do.

use swarf_app::Job;
use swarf_geom::Part;
use swarf_toolpath::Contact;

/// CC paths on the die: iso-planar at `angle` degrees off X, a fixed cross feed of
/// `stepover` mm and the chordal tolerance `tol` mm, for `tool`.
///
/// # Panics
/// When the job does not plan (a broken fixture fails the test).
pub fn die_cc(part: &Part, tool: &str, angle: f64, stepover: f64, tol: f64) -> Vec<Vec<Contact>> {
    let text = format!(
        "part = \"builtin:die\"\ntool = \"{tool}\"\n[strategy]\nkind = \"iso-planar\"\n\
         stepover = {stepover}\ntolerance = {tol}\nangle = {angle}\n"
    );
    let job = Job::parse(&text, "die job").expect("job");
    swarf_app::five_axis::planned_cc_paths(&job, part).expect("CC paths")
}
