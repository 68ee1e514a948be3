//! The fillet pocket from a box in one sequence job (jobs/fillet-pocket-sequence.toml):
//! adaptive roughing, raster finishing and cleanup on one in-process stock. No
//! operation gouges; the roughing's engagement, measured on the stock, holds; the
//! ball d=4 cleanup reaches every fillet (radius 3) and corner (radius 5), so no rest
//! is left; with a ball d=8 instead, rest is left only where that ball cannot reach
//! (the fillets and corners, by the pocket's closed form).

use std::path::{Path, PathBuf};
use swarf_app::sequence::{Sequence, SequenceReport, plan_sequence};

fn jobs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

fn run(text: &str, tag: &str) -> SequenceReport {
    run_program(text, tag).0
}

/// The report and the whole program's text.
fn run_program(text: &str, tag: &str) -> (SequenceReport, String) {
    let seq = Sequence::parse(text, "fillet-pocket-sequence.toml", &jobs()).unwrap();
    let dir = std::env::temp_dir().join(format!("swarf-sequence-test-{tag}"));
    let mut out = swarf_app::Outputs::new(&dir);
    let report = plan_sequence(&seq, &jobs(), &mut out).unwrap();
    let program = out
        .read_text(&out.path("fillet-pocket-sequence.ngc"))
        .unwrap();
    (report, program)
}

fn shipped() -> String {
    std::fs::read_to_string(jobs().join("fillet-pocket-sequence.toml")).unwrap()
}

#[test]
fn fillet_pocket_from_a_box_in_one_job() {
    let text = shipped();
    assert!(Sequence::is_sequence(&text));
    let (report, program) = run_program(&text, "d4");
    // The shipped job writes arcs (read back and simulated as arcs).
    let arcs = program
        .lines()
        .filter(|l| l.starts_with("G2 ") || l.starts_with("G3 "))
        .count();
    eprintln!("{} blocks, {arcs} opening an arc", program.lines().count());
    assert!(arcs > 0);
    each_tool_change_sets_its_length(&program);
    for op in &report.operations {
        eprintln!(
            "T{} {}: {} motions, {:.0} s; gouge cells {}, rest cells {} over {:.3} mm, max {:.3} mm",
            op.number,
            op.name,
            op.motions,
            op.time_s,
            op.gouge_cells,
            op.rest_cells,
            op.rest_limit_mm,
            op.max_rest_mm
        );
        assert_eq!(op.gouge_cells, 0, "{} gouges", op.name);
        assert!(
            op.below_floor_lines.is_empty(),
            "{}: {:?}",
            op.name,
            op.below_floor_lines
        );
    }
    assert!(
        program.contains("0 rapids in material, 0 gouge cells beyond")
            && program.contains("mm, 0 motions below the floor at "),
        "the gate's verdict in the header"
    );
    // Both roughings (the second is rest roughing with a smaller tool) hold the
    // stated engagement on every clearing motion, to the measurement's 1 degree.
    for op in &report.operations[..2] {
        let e = op.engagement.as_ref().unwrap();
        eprintln!("{} engagement: {e:?}", op.name);
        assert!(e.max_deg <= e.limit_deg + 1.0, "{}: {e:?}", op.name);
    }
    // Rest roughing cuts where the first tool left material, little in the air.
    let rest = report.operations[1].engagement.as_ref().unwrap();
    assert!(rest.air < 0.5, "{rest:?}");
    let last = report.operations.last().unwrap();
    assert_eq!(
        last.rest_cells, 0,
        "the ball d=4 reaches every fillet and corner"
    );
}

/// rs274 with a tool table of four different lengths (inches, its machine units)
/// puts each tool's length in force after its change (skipped without rs274).
fn each_tool_change_sets_its_length(program: &str) {
    let dir = std::env::temp_dir().join(format!("swarf-sequence-tlo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let lengths = [2.0, 3.25, 4.5, 5.75];
    let table: String = (1..=4)
        .zip(lengths)
        .map(|(t, l)| format!("T{t} P{t} Z{l}\n"))
        .collect();
    std::fs::write(dir.join("tool.tbl"), table).unwrap();
    std::fs::write(dir.join("seq.ngc"), program).unwrap();
    let out = swarf_testkit::rs274::run_rs274_precise(&dir, "seq.ngc", "tool.tbl");
    std::fs::remove_dir_all(&dir).ok();
    let Some(out) = out else { return };
    assert!(out.contains("--- exit 0"), "rs274 failed:\n{out}");
    let got = swarf_testkit::rs274::length_after_changes(&out);
    let want: Vec<(u32, Option<f64>)> = (1..=4)
        .zip(lengths)
        .map(|(t, l)| (t, Some(l * 25.4)))
        .collect();
    assert_eq!(got.len(), 4, "{got:?}");
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g.0, w.0, "{got:?}");
        let z = g.1.unwrap_or(f64::NAN);
        assert!((z - w.1.unwrap()).abs() < 1e-6, "T{}: {z}", g.0);
    }
}

/// Distance from the pocket's core rectangle [25, 75] x [25, 55] (parts/README.md).
fn core_distance(x: f64, y: f64) -> f64 {
    let dx = (25.0 - x).max(x - 75.0).max(0.0);
    let dy = (25.0 - y).max(y - 55.0).max(0.0);
    dx.hypot(dy)
}

#[test]
fn a_cleanup_tool_too_large_for_the_fillets_leaves_rest_only_there() {
    let text = shipped().replace("tool = \"ball:d=4\"", "tool = \"ball:d=8\"");
    let report = run(&text, "d8");
    let cells = &report.rest;
    let last = report.operations.last().unwrap();
    assert!(
        last.rest_cells > 0,
        "a ball of radius 4 leaves rest in radius 3 fillets"
    );
    // A ball of radius 4 touching wall (d = 5) and floor leaves rest only where the
    // fillet curves, d in (2, 5) from the core along the sides; in the corners, where
    // the fillet is a torus curved both ways, the ball stands further off and its
    // rest reaches into the floor a little (d < 2 there).
    let stray: Vec<_> = cells
        .iter()
        .filter(|c| {
            let (x, y) = (c[0], c[1]);
            let d = core_distance(x, y);
            let corner = !(25.0..=75.0).contains(&x) && !(25.0..=55.0).contains(&y);
            let band = d < 5.0 + 0.5 && (d > 2.0 - 0.5 || corner);
            !band
        })
        .collect();
    eprintln!(
        "{} rest cells, {} outside the fillet band",
        cells.len(),
        stray.len()
    );
    assert!(
        stray.is_empty(),
        "rest outside the fillets: {:?}",
        &stray[..stray.len().min(5)]
    );
}

#[test]
fn bad_sequences_are_refused_naming_the_operation_and_field() {
    let base = shipped();
    let cases: Vec<(String, &str)> = vec![
        (
            base.replace("tool = \"flat:d=6\"", "tool = \"flat:d=-6\""),
            "operation[1]",
        ),
        (
            base.replace("name = \"finish\"", "name = \"finish\"\nspeed = 3"),
            "operation[2]: unknown field `speed`",
        ),
        (base.replace("cell = 0.25", "cell = 0"), "stock.cell"),
        (
            base.replace(
                "scallop = 0.01, tolerance = 0.01, angle = 0",
                "scallop = -1, angle = 0",
            ),
            "operation[2]: strategy.scallop",
        ),
        (
            base.replace(
                "[[operation]]\nname = \"rough\"",
                "[[operation]]\nname = \"rough\"\npart = \"x.stl\"",
            ),
            "operation[0]: part: not an operation's key",
        ),
        (
            base.replace("gcode = \"fillet-pocket-sequence.ngc\"", "gcode = \"\""),
            "output.gcode",
        ),
        (
            base.replace(
                "arcs = true",
                "arcs = true
arc_tolerance = 2",
            ),
            "output.arc_tolerance: expected",
        ),
    ];
    for (text, want) in cases {
        let err = Sequence::parse(&text, "seq.toml", &jobs())
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(want) && err.contains("seq.toml"),
            "{want}: {err}"
        );
    }
    // A cleanup first has nothing to clean up after; a box below the part is refused.
    let first_cleanup = base.replacen("kind = \"roughing\", allowance = 0.5, step_down = 4, max_engagement = 60, ramp_angle = 3, tolerance = 0.01", "kind = \"cleanup\", scallop = 0.01", 1);
    let err = Sequence::parse(&first_cleanup, "seq.toml", &jobs())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("operation[0]: strategy.kind") && err.contains("first operation"),
        "{err}"
    );
    let mut out = swarf_app::Outputs::new(&std::env::temp_dir().join("swarf-sequence-bad"));
    let low = Sequence::parse(&base.replace("top = 21", "top = 15"), "seq.toml", &jobs()).unwrap();
    let err = plan_sequence(&low, &jobs(), &mut out)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("stock.top: the stock's top 15 mm is below the part's top"),
        "{err}"
    );
    // grbl has no tool change: four tools are refused before anything is planned.
    let grbl = base.replace("[output]", "[output]\npost = \"grbl\"");
    let grbl = Sequence::parse(&grbl, "seq.toml", &jobs()).unwrap();
    let err = plan_sequence(&grbl, &jobs(), &mut out)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains(
            "output.post = \"grbl\": post grbl: tool.change: sequence with 4 tools (T1, T2, T3, T4)"
        ),
        "{err}"
    );
}

/// A sequence on the deep pocket (60 x 60 block, a 10 x 40 pocket 40 deep) finished
/// by the library's `ball6-long` (T3: stick-out 30 mm, holder nose 20 mm across).
fn deep_pocket(tool: &str) -> String {
    format!(
        "name = \"deep pocket\"\npart = \"builtin:deep-pocket\"\ntools = \"../tooling/library.toml\"\n\
         [stock]\nkind = \"offset\"\nallowance = 0.5\ncell = 0.5\n\
         [[operation]]\nname = \"finish\"\ntool = {tool}\n\
         strategy = {{ kind = \"raster\", scallop = 0.5, tolerance = 0.01 }}\n"
    )
}

#[test]
fn library_tools_are_named_and_their_holders_checked() {
    // By name: the holder collides at stick-out 30; the job stops, naming the
    // operation, the place and the stick-out that clears.
    let seq = Sequence::parse(&deep_pocket("\"ball6-long\""), "deep.toml", &jobs()).unwrap();
    assert_eq!(seq.operations[0].number, 3);
    assert_eq!(
        seq.operations[0].job.feeds.feed, 1200.0,
        "the library's feed"
    );
    let mut out = swarf_app::Outputs::new(&std::env::temp_dir().join("swarf-sequence-holder"));
    let err = plan_sequence(&seq, &jobs(), &mut out)
        .unwrap_err()
        .to_string();
    eprintln!("{err}");
    assert!(
        err.contains("operation[0] (finish)") && err.contains("collide"),
        "{err}"
    );
    assert!(err.contains("shortest stick-out that clears"), "{err}");
    // By a number the library lacks: the error lists the library's tools.
    let err = Sequence::parse(&deep_pocket("7"), "deep.toml", &jobs())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("operation[0]: tool") && err.contains("ball6-long"),
        "{err}"
    );
    // A library tool without a library.
    let text = deep_pocket("3").replace("tools = \"../tooling/library.toml\"\n", "");
    let err = Sequence::parse(&text, "deep.toml", &jobs())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(err.contains("no `tools` library"), "{err}");
}
