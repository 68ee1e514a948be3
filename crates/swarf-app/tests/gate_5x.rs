//! The verification gate on five-axis programs: every shipped five-axis job is
//! planned on its default stock (the design raised by 1 mm: a five-axis finish
//! cuts what roughing left near net) and simulated from its poses, rapids
//! included. The automatic gouge-free lead and drop-and-spin pass (no rapid in
//! material, no gouge beyond the tolerance); the fixed leads of thesis 000 ch. 8
//! gouge the die and are refused naming the G-code line, or written labelled under
//! `AllowUnsafe`. The jobs are planned with a coarser step (as the fuzz suite
//! plans them): the inputs keep their shape.

use std::path::{Path, PathBuf};
use swarf_app::Job;
use swarf_app::gate::Gate;
use swarf_app::model::load_model_with;
use swarf_app::plan_job::{Planned, part_arg, plan_model_toolpath};
use swarf_app::stock::{Stock, StockKind};
use swarf_sim::Quiet;

fn jobs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

/// A plan and its G-code.
type Written = (Planned, Option<String>);

/// The shipped job `name`, its step coarsened by `edit`, planned under `gate`.
fn planned(name: &str, edit: (&str, &str), gate: Gate) -> swarf_app::Result<Written> {
    planned_on(name, edit, gate, None)
}

/// [`planned`], on `stock` where given (else the near-net default).
fn planned_on(
    name: &str,
    edit: (&str, &str),
    gate: Gate,
    stock: Option<Stock>,
) -> swarf_app::Result<Written> {
    let text = std::fs::read_to_string(jobs().join(name)).unwrap();
    assert!(text.contains(edit.0), "{name}: {edit:?}");
    let text = text.replace(edit.0, edit.1);
    let mut job = Job::parse_in(&text, name, &jobs()).unwrap();
    let near_net = job.stock.kind == StockKind::Offset;
    assert!(near_net, "{name}: near-net by default");
    if let Some(stock) = stock {
        job.stock = stock;
    }
    job.gate = gate;
    let model = load_model_with(&part_arg(&job, &jobs()), &job.load_options()).unwrap();
    let dir = std::env::temp_dir().join(format!("swarf-gate-5x-{name}"));
    let mut out = swarf_app::Outputs::new(&dir);
    let planned = plan_model_toolpath(&job, &model, &jobs(), &mut out, &Quiet);
    let gcode = job.output.gcode.as_ref().map(|rel| out.path(rel));
    planned.map(|p| (p, gcode.map(|g| out.read_text(&g).unwrap())))
}

#[test]
fn shipped_five_axis_jobs_that_do_not_gouge_pass_the_gate_from_their_poses() {
    let cases = [
        ("die-gouge-free.toml", ("stepover = 3.5", "stepover = 15")),
        ("edge-concave-drop-spin.toml", ("step = 5 ", "step = 30 ")),
    ];
    for (name, edit) in cases {
        let (p, _) = planned(name, edit, Gate::Verify).unwrap();
        assert!(
            p.toolpath.moves().iter().any(|m| !m.to.is_vertical()),
            "{name}: five-axis"
        );
        let v = &p.summary["verification"];
        assert_eq!(v["stock"], "design + 1 mm", "{name}: {v}");
        assert!(v["cell"].as_f64().unwrap() >= 0.5, "{name}: {v}");
        assert_eq!(v["rapid_cuts"].as_array().unwrap().len(), 0, "{name}: {v}");
        assert_eq!(v["gouge_cells"], 0, "{name}: {v}");
        // The tool's lowest point, tilted, stays on or above the floor.
        assert!(v["floor"].is_number(), "{name}: {v}");
        assert_eq!(v["below_floor"].as_array().unwrap().len(), 0, "{name}: {v}");
        assert_eq!(v["written_unsafe"], false, "{name}: {v}");
    }
}

#[test]
fn a_fixed_lead_that_gouges_the_die_is_refused_by_line_or_written_labelled() {
    let edit = ("stepover = 3.5", "stepover = 15");
    let Err(refused) = planned("die-inclined-3.toml", edit, Gate::Verify) else {
        panic!("the fixed lead of 3 degrees gouges the die");
    };
    let refused = refused.to_string();
    assert!(
        refused.contains("cells gouged beyond 0.01 mm") && refused.contains("cut at line "),
        "{refused}"
    );
    assert!(refused.contains("nothing written"), "{refused}");
    let (written, gcode) = planned("die-inclined-3.toml", edit, Gate::AllowUnsafe).unwrap();
    let v = &written.summary["verification"];
    assert_eq!(v["written_unsafe"], true, "{v}");
    // The refusal's line is the five-axis block that ends the gouging move: a feed
    // of the trunnion's G-code, after the header.
    let line = v["gouges"][0]["line"].as_u64().unwrap() as usize;
    assert!(
        refused.contains(&format!("cut at line {line} ")),
        "{refused}"
    );
    let gcode = gcode.unwrap();
    let block = gcode.lines().nth(line - 1).unwrap();
    let header = gcode
        .lines()
        .take_while(|l| l.starts_with('(') || *l == "%")
        .count();
    assert!(line > header, "line {line} in the header of {header} lines");
    assert!(
        block.contains(['X', 'Y', 'Z', 'A', 'C']),
        "line {line}: {block}"
    );
    assert!(!block.starts_with("G0"), "line {line} is a rapid: {block}");
    // The sectioning check of positioning finds millimetres; so does the gate.
    assert!(v["worst_gouge_mm"].as_f64().unwrap() < -1.0, "{v}");
    assert_eq!(v["rapid_cuts"].as_array().unwrap().len(), 0, "{v}");
}

/// A tilted finishing tool in a block is buried to its holder: its first retract
/// along the axis cuts the block above its 25.4 mm body. The gate refuses at that
/// rapid without simulating the rest (the first-order sweep of a buried tool is the
/// slow one).
#[test]
fn a_five_axis_finish_in_a_block_is_refused_at_its_first_rapid_in_material() {
    let edit = ("stepover = 3.5", "stepover = 15");
    let block = Stock {
        kind: StockKind::Box,
        ..Stock::default()
    };
    let Err(refused) = planned_on("die-gouge-free.toml", edit, Gate::Verify, Some(block)) else {
        panic!("a buried tool's retract cuts the block");
    };
    let refused = refused.to_string();
    assert!(
        refused.contains("1 rapid cuts material: line "),
        "{refused}"
    );
    assert!(
        refused.contains("the simulation stopped there"),
        "{refused}"
    );
}
