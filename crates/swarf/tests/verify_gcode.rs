//! `swarf verify` on G-code that needs what a machine has besides the program: a tool
//! table (cutter compensation, tool length), subroutine files on a search path, the
//! Fanuc dialect; and the errors that say which flag is missing.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn swarf(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("swarf runs");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// A plate z = 0 over [0, 20] x [0, 10], a tool table (T1: d = 2 mm, length 30), a
/// subroutine file in `subs/` (a rectangle from (#1, #2) to (#3, #4) at depth #5) and
/// a program calling it with compensation to the right (outside of the rectangle,
/// counter-clockwise: convex corners).
fn setup(dir: &Path) -> (PathBuf, PathBuf) {
    std::fs::create_dir_all(dir.join("subs")).unwrap();
    std::fs::create_dir_all(dir.join("prog")).unwrap();
    std::fs::write(
        dir.join("plate.toml"),
        "name = \"plate\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
         points = [[0, 0, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]]\n",
    )
    .unwrap();
    std::fs::write(dir.join("tool.tbl"), "T1 P1 D2 Z30 ;2 mm end mill\n").unwrap();
    std::fs::write(
        dir.join("subs/rectangle.ngc"),
        "o<rectangle> sub\n  G0 X[#1 - 4] Y[#2 - 4]\n  G1 Z#5 F300\n  G42 D1\n  G1 X#1 Y#2\n  \
         G1 X#3\n  G1 Y#4\n  G1 X#1\n  G1 Y#2\n  G40\n  G0 Z5\no<rectangle> endsub\nM2\n",
    )
    .unwrap();
    let program = dir.join("prog/profile.ngc");
    std::fs::write(
        &program,
        "(a profile round a rectangle, from a subroutine file)\nG21 G90 G17 G94\n\
         T1 M6 G43 H1\nG0 X0 Y0 Z5\no<rectangle> call [5] [3] [15] [7] [0]\nM2\n",
    )
    .unwrap();
    (dir.join("plate.toml"), program)
}

#[test]
fn tool_table_and_subroutine_files_are_taken_from_their_flags() {
    let dir = std::env::temp_dir().join(format!("swarf-verify-gcode-{}", std::process::id()));
    let (part, program) = setup(&dir);
    let (part, program) = (part.to_str().unwrap(), program.to_str().unwrap());
    let table = dir.join("tool.tbl");
    let subs = dir.join("subs");
    let out = dir.join("out");
    let base = [
        "verify",
        "--part",
        part,
        "--program",
        program,
        "--tool",
        "flat:d=2",
        "--cell",
        "0.05",
    ];
    let with = |extra: &[&str]| {
        let mut a: Vec<&str> = base.to_vec();
        a.extend_from_slice(extra);
        swarf(&a)
    };
    let (table, subs, out) = (
        table.to_str().unwrap(),
        subs.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    let (ok, text) = with(&["--sub-path", subs, "-o", out]);
    assert!(!ok);
    assert!(
        text.contains("tool number 1 not found") && text.contains("--tool-table"),
        "{text}"
    );
    let (ok, text) = with(&["--tool-table", table, "-o", out]);
    assert!(!ok);
    assert!(
        text.contains("o<rectangle> not found") && text.contains("--sub-path"),
        "{text}"
    );
    let (ok, text) = with(&["--tool-table", table, "--sub-path", subs, "-o", out]);
    assert!(ok, "{text}");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/report.json")).unwrap())
            .unwrap();
    assert_eq!(report["complete"], Value::Bool(true), "{report}");
    assert_eq!(
        report["deviation"]["gouge"]["cells"].as_u64(),
        Some(0),
        "{}",
        report["deviation"]
    );
    // The three convex corners the path turns (the fourth is where it ends), each
    // turned round on an arc of the tool's radius; the motions of the subroutine file
    // carry the line of its call.
    assert_eq!(
        report["program_stats"]["arcs"].as_u64(),
        Some(3),
        "{report}"
    );
    assert_eq!(
        report["simulation"]["rapid_cuts"][0]["line"].as_u64(),
        Some(5),
        "{report}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_fanuc_dialect_is_chosen_by_flag() {
    let dir = std::env::temp_dir().join(format!("swarf-verify-fanuc-{}", std::process::id()));
    let (part, _) = setup(&dir);
    let program = dir.join("prog/O1000.nc");
    std::fs::write(
        &program,
        "%\nO1000 (PASSES)\nG21 G90 G17 G94\nG0 X-2. Y1. Z5.\n#1 = 1.\nWHILE [#1 LE 9.] DO1\n\
         G0 X-2. Y#1\nG1 Z0 F300.\nG1 X22.\nG0 Z5.\n#1 = #1 + 2.\nEND1\nM30\n%\n",
    )
    .unwrap();
    let (part, program) = (part.to_str().unwrap(), program.to_str().unwrap());
    let out = dir.join("out");
    let out = out.to_str().unwrap();
    let args = [
        "verify",
        "--part",
        part,
        "--program",
        program,
        "--tool",
        "ball:d=2",
        "-o",
        out,
    ];
    let (ok, text) = swarf(&args);
    assert!(!ok);
    assert!(
        text.contains("O1000.nc:6:"),
        "the LinuxCNC dialect stops at WHILE: {text}"
    );
    let mut fanuc = args.to_vec();
    fanuc.extend_from_slice(&["--dialect", "fanuc"]);
    let (ok, text) = swarf(&fanuc);
    assert!(ok, "{text}");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/report.json")).unwrap())
            .unwrap();
    assert_eq!(report["complete"], Value::Bool(true), "{report}");
    let _ = std::fs::remove_dir_all(&dir);
}
