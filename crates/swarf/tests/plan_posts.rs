//! `swarf plan` with `[output] post`: the wave's iso-planar job written for every
//! built-in post, and `swarf verify` reading each program back (Heidenhain as a `.h`
//! file, Fanuc with `--dialect fanuc`) without a gouge; the older key `dialect` still
//! chooses the post; an unknown post and a five-axis job on grbl fail naming the post
//! and the field.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn text(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

fn jobs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

/// The wave's iso-planar job with its outputs replaced by `output` lines.
fn job(dir: &Path, name: &str, output: &str) -> PathBuf {
    let text = std::fs::read_to_string(jobs().join("wave-iso-planar.toml")).unwrap();
    let head = &text[..text.find("[output]").unwrap()];
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, format!("{head}[output]\n{output}\n")).unwrap();
    path
}

#[test]
fn every_post_plans_and_verifies() {
    let dir = std::env::temp_dir().join(format!("swarf-plan-posts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "linuxcnc",
            "post = \"linuxcnc\"",
            "ngc",
            "linuxcnc",
            "G17 G21",
        ),
        ("fanuc", "dialect = \"fanuc\"", "nc", "fanuc", "O1000"),
        ("mach3", "post = \"mach3\"", "tap", "linuxcnc", "G43 H1"),
        ("grbl", "post = \"grbl\"", "gcode", "linuxcnc", "G94\nS"),
        (
            "heidenhain",
            "post = \"heidenhain\"",
            "h",
            "linuxcnc",
            "BEGIN PGM",
        ),
    ];
    for (name, key, ext, dialect, mark) in cases {
        let program = format!("wave-{name}.{ext}");
        let path = job(&dir, name, &format!("{key}\ngcode = \"{program}\""));
        let o = swarf(&["plan", path.to_str().unwrap()]);
        assert!(o.status.success(), "{name}: {}", text(&o));
        let written = std::fs::read_to_string(dir.join(&program)).unwrap();
        assert!(written.contains(mark), "{name}: {mark} not in the program");
        let to = dir.join(format!("v-{name}"));
        let o = swarf(&[
            "verify",
            "--part",
            "builtin:wave",
            "--program",
            dir.join(&program).to_str().unwrap(),
            "--tool",
            "ball:d=8",
            "--dialect",
            dialect,
            "-o",
            to.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{name}: {}", text(&o));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(to.join("report.json")).unwrap())
                .unwrap();
        assert_eq!(report["deviation"]["gouge"]["cells"], 0, "{name}");
    }
    let path = job(&dir, "unknown", "post = \"sinumerik\"\ngcode = \"w.ngc\"");
    let o = swarf(&["plan", path.to_str().unwrap()]);
    assert!(!o.status.success());
    let e = text(&o);
    assert!(
        e.contains("output.post = \"sinumerik\"") && e.contains("no built-in post"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_five_axis_job_on_grbl_is_refused_by_name() {
    let dir = std::env::temp_dir().join(format!("swarf-plan-grbl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let output = "post = \"grbl\"\nmachine = \"builtin:xyzac-trunnion\"\ngcode = \"w.ngc\"";
    let path = job(&dir, "grbl5", output);
    let o = swarf(&["plan", path.to_str().unwrap()]);
    assert!(!o.status.success());
    let e = text(&o);
    assert!(
        e.contains("post grbl: rotary_axes: five-axis program"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
