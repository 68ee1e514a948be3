//! `swarf verify --machine` on five-axis G-code: the same inclined tool path on the die
//! (thesis 000 ch. 8 cutter, lead 6 degrees), posted for the A/C trunnion as G-code and
//! written as APT CL, verifies to the same gouge and excess figures; bad input (a
//! missing machine file, rotary words without `--machine`) fails with the file and line
//! named, a non-zero exit and no panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::positioning::{Positioning, position};
use swarf_fiveaxis::post::{PostOptions, write_gcode_5x};
use swarf_nc::{Units, write_cl};
use swarf_testkit::die_cc;
use swarf_testkit::machines::machine_path;
use swarf_testkit::parts::die;
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, Linking, Toolpath};

const CUTTER: &str = "bull:d=38.1,r=6.35";

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-5x-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn trunnion_file() -> PathBuf {
    machine_path("xyzac-trunnion.toml")
}

/// Two neighbouring passes across the middle of the die (iso-planar, 60 degrees off
/// X, cross feed 3.5 mm as in thesis 000 ch. 8) at a lead of 6 degrees.
fn toolpath() -> Toolpath {
    let part = die();
    let all = die_cc(&part, CUTTER, 60.0, 3.5, 0.005);
    let n = all.len();
    let cc = vec![all[n / 2].clone(), all[n / 2 + 1].clone()];
    let cutter: Cutter = CUTTER.parse().unwrap();
    let inclined = Positioning::Inclined {
        alpha: 6.0,
        tilt: 0.0,
        sections: 1.0,
    };
    let (passes, _) = position(&cutter, &part, &cc, &inclined, 0.01).unwrap();
    Toolpath {
        passes,
        feeds: Feeds::default(),
        linking: Linking {
            clearance: 70.0,
            approach: 2.0,
            ..Linking::default()
        },
    }
}

fn report(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("report.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Writes the tool path as G-code for the trunnion and as APT CL into `dir`.
fn write_programs(dir: &Path) {
    let tp = toolpath();
    let m = Machine::parse(&std::fs::read_to_string(trunnion_file()).unwrap(), "m").unwrap();
    let gcode = write_gcode_5x(&m, &tp, &PostOptions::default()).unwrap();
    std::fs::write(dir.join("die.ngc"), gcode).unwrap();
    let cutter: Cutter = CUTTER.parse().unwrap();
    let cl = write_cl(&tp.moves(), &tp.feeds, &cutter, "die", Units::Mm).unwrap();
    std::fs::write(dir.join("die.cl"), cl).unwrap();
}

/// `swarf verify` on `dir/program` into `dir/out` (1 mm cells, motions sampled within
/// 0.01 mm: a few seconds in the dev profile), with `extra` arguments.
fn verify(dir: &Path, program: &str, out: &str, extra: &[&str]) -> Output {
    let program = dir.join(program).display().to_string();
    let out = dir.join(out).display().to_string();
    let mut args = vec![
        "verify",
        "--part",
        "die",
        "--program",
        &program,
        "--tool",
        CUTTER,
        "--cell",
        "1",
        "--tol",
        "0.01",
        "--sample-tol",
        "0.01",
        "-o",
        &out,
    ];
    args.extend_from_slice(extra);
    swarf(&args)
}

/// `a` and `b` within `rel` of each other (relative to the larger).
fn near(a: &serde_json::Value, b: &serde_json::Value, rel: f64) -> bool {
    let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

#[test]
fn gcode_through_the_machine_verifies_like_the_cl_data() {
    let dir = temp_dir("same");
    write_programs(&dir);
    let machine = trunnion_file().display().to_string();
    let o = verify(&dir, "die.ngc", "gcode", &["--machine", &machine]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = verify(&dir, "die.cl", "cl", &["--machine", &machine]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("ignored"), "{}", stderr(&o));
    let (g, c) = (report(&dir.join("gcode")), report(&dir.join("cl")));
    // The lead of 6 degrees gouges the die's corner near (-77, -92) by 2.8 mm along
    // the design normal, 3.4 mm vertically (thesis
    // 000 ch. 8: alpha = 6 is not gouge-free there); the rest of the stock is uncut
    // (0.5 mm excess). Both programs find the same: the G-code's axes, interpolated
    // linearly, bend the tip off the CL chords by a few hundredths of a millimetre
    // where C turns fast, which moves boundary cells only.
    for what in ["gouge", "excess"] {
        let (a, b) = (&g["deviation"][what], &c["deviation"][what]);
        eprintln!("{what}: G-code {a}\n{what}: CL     {b}");
        assert_eq!(a["regions"], b["regions"], "{what}: {a} vs {b}");
        assert!(near(&a["cells"], &b["cells"], 0.01), "{what}: {a} vs {b}");
        assert!(
            near(&a["volume_mm3"], &b["volume_mm3"], 0.01),
            "{what}: {a} vs {b}"
        );
        let worst = a["worst"].as_f64().unwrap() - b["worst"].as_f64().unwrap();
        assert!(worst.abs() < 0.01, "{what}: {a} vs {b}");
    }
    let gouge = &g["deviation"]["gouge"];
    assert!(gouge["worst"].as_f64().unwrap() < -2.5, "{gouge}");
    // Machining times agree too: G93 feeds read back as the tip's feed over the part.
    let time = |r: &serde_json::Value| r["program_stats"]["time_s"].as_f64().unwrap();
    let cutting = |r: &serde_json::Value| r["program_stats"]["cutting_length_mm"].as_f64().unwrap();
    assert!((cutting(&g) - cutting(&c)).abs() < 0.01 * cutting(&c));
    assert!(time(&g) > 0.0 && (time(&g) - time(&c)).abs() < 0.05 * time(&c));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_machine_input_names_the_file_and_line() {
    let dir = temp_dir("bad");
    write_programs(&dir);
    let no_panic = |o: &Output| {
        assert!(!o.status.success());
        assert!(!stderr(o).contains("panicked"), "{}", stderr(o));
        stderr(o)
    };
    // A machine file that is not there.
    let missing = dir.join("nope.toml").display().to_string();
    let e = no_panic(&verify(&dir, "die.ngc", "a", &["--machine", &missing]));
    assert!(e.contains(&missing) && e.contains("cannot read"), "{e}");
    // A machine file with a bad line.
    let bad = dir.join("bad.toml");
    let text = std::fs::read_to_string(trunnion_file()).unwrap();
    std::fs::write(
        &bad,
        text.replace("kind = \"table-table\"", "kind = \"spider\""),
    )
    .unwrap();
    let bad = bad.display().to_string();
    let e = no_panic(&verify(&dir, "die.ngc", "b", &["--machine", &bad]));
    assert!(e.contains(&bad) && e.contains("line"), "{e}");
    // Rotary words without a machine: the reader stops at the first, naming file,
    // line and column, and points to --machine.
    let gcode = std::fs::read_to_string(dir.join("die.ngc")).unwrap();
    let line = 1 + gcode
        .lines()
        .position(|l| !l.starts_with('(') && l.contains(" A"))
        .unwrap();
    let e = no_panic(&verify(&dir, "die.ngc", "c", &[]));
    assert!(e.contains(&format!("die.ngc:{line}:")), "{e}");
    assert!(
        e.contains("rotary axis word") && e.contains("--machine"),
        "{e}"
    );
    // A machine with head axes needs the tool length.
    let e = no_panic(&verify(
        &dir,
        "die.ngc",
        "d",
        &["--machine", "builtin:xyzbc-head"],
    ));
    assert!(e.contains("--tool-length"), "{e}");
    // and --tool-length alone means nothing.
    let e = no_panic(&verify(&dir, "die.ngc", "e", &["--tool-length", "80"]));
    assert!(e.contains("--machine"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
