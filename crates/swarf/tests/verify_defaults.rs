//! `swarf verify` with its defaults on programs swarf planned (issue 14): deviation
//! along the design normals and the scallop allowance the program states it was
//! planned for, so the demo's clean programs report no gouge at all (measured
//! vertically, the wave's slopes showed about 3,000 gouge cells 0.0126 mm deep on a
//! clean iso-scallop program), and a program without a stated scallop is told what
//! counts as excess. The flagged-cell CSV is capped, and the report and the console
//! say so where it is cut (the raster leaves 704,662 excess cells on the wave's
//! walls).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn jobs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

#[test]
fn the_demos_clean_programs_verify_without_gouges() {
    let dir = std::env::temp_dir().join(format!("swarf-verify-defaults-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let cases = [
        ("wave-iso-parametric", "builtin:wave", "ball:d=8"),
        ("wave-iso-planar", "builtin:wave", "ball:d=8"),
        ("wave-iso-scallop", "builtin:wave", "ball:d=8"),
        ("wave-raster", "builtin:wave", "ball:d=8"),
        ("wave-steep-shallow", "builtin:wave", "ball:d=8"),
        ("fillet-pocket-finish", "builtin:fillet-pocket", "ball:d=12"),
    ];
    for (job, part, tool) in cases {
        let o = swarf(&[
            "plan",
            jobs().join(format!("{job}.toml")).to_str().unwrap(),
            "--out",
            out,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let program = dir.join(format!("{job}.ngc"));
        let to = dir.join(format!("v-{job}"));
        let o = swarf(&[
            "verify",
            "--part",
            part,
            "--program",
            program.to_str().unwrap(),
            "--tool",
            tool,
            "-o",
            to.to_str().unwrap(),
        ]);
        let text =
            String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{job}: {text}");
        assert!(
            text.contains("as the program states it was planned"),
            "{job}: {text}"
        );
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(to.join("report.json")).unwrap())
                .unwrap();
        assert_eq!(report["deviation_mode"], "normal", "{job}");
        assert_eq!(
            report["deviation"]["gouge"]["cells"], 0,
            "{job}: {}",
            report["deviation"]["gouge"]
        );
        eprintln!(
            "{job}: gouge cells 0, excess cells {}",
            report["deviation"]["excess"]["cells"]
        );
        // The flagged-cell CSV holds at most its cap, and both outputs say so.
        let f = &report["flagged_csv"];
        let n = |k: &str| f[k].as_u64().unwrap();
        let (flagged, rows, cap) = (n("flagged_cells"), n("rows"), n("cap_rows"));
        let csv = std::fs::read_to_string(to.join("flagged.csv")).unwrap();
        assert_eq!(csv.lines().count() as u64, rows + 1, "{job}");
        assert_eq!(rows, flagged.min(cap), "{job}");
        let said = text.contains(&format!("holds the first {rows} of {flagged}"));
        assert_eq!(flagged > cap, said, "{job}: {text}");
    }
    // A program that states no scallop: the note says what counts as excess.
    let bare = dir.join("bare.ngc");
    std::fs::write(&bare, "G21 G90\nG0 X10 Y10 Z30\nG1 X20 F100\n").unwrap();
    let o = swarf(&[
        "verify",
        "--part",
        "builtin:wave",
        "--program",
        bare.to_str().unwrap(),
        "--tool",
        "ball:d=8",
        "-o",
        dir.join("v-bare").to_str().unwrap(),
    ]);
    let text =
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(
        text.contains("no --scallop and no planned scallop"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
