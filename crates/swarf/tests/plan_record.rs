//! The plan record (`part.record.json` beside a program swarf writes): `swarf
//! verify` takes the scallop allowance, the tolerance and the tool from it, for
//! G-code, APT CL and pose CSV alike, and a hand-edited G-code header no longer
//! changes the allowance while the record is there.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

const JOB: &str = r#"
name = "record"
part = "builtin:wave"
tool = "ball:d=8"
[strategy]
kind = "raster"
scallop = 0.12
tolerance = 0.02
boundary = [60, 20, 80, 40]
[output]
gcode = "record.ngc"
cl = "record.cl"
csv = "record.csv"
"#;

/// Verifies `program` without a tool or an allowance; the report and the output.
fn verify(dir: &Path, program: &Path, name: &str, extra: &[&str]) -> (serde_json::Value, String) {
    let to = dir.join(name);
    let mut args = extra.to_vec();
    args.extend([
        "verify",
        "--part",
        "builtin:wave",
        "--program",
        program.to_str().unwrap(),
        "--cell",
        "0.25",
        "-o",
        to.to_str().unwrap(),
    ]);
    args.rotate_left(extra.len());
    let o = swarf(&args);
    let text =
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{name}: {text}");
    let report = std::fs::read_to_string(to.join("report.json")).unwrap();
    (serde_json::from_str(&report).unwrap(), text)
}

fn planned(dir: &Path) -> PathBuf {
    let job = dir.join("record.toml");
    std::fs::write(&job, JOB).unwrap();
    let o = swarf(&[
        "plan",
        job.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    dir.join("record.record.json")
}

#[test]
fn cl_and_csv_get_the_allowance_of_their_g_code_from_the_record() {
    let dir = std::env::temp_dir().join(format!("swarf-plan-record-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let record = planned(&dir);
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&record).unwrap()).unwrap();
    assert_eq!(r["version"], 1);
    assert_eq!(
        r["programs"],
        serde_json::json!(["record.ngc", "record.cl", "record.csv"])
    );
    assert_eq!(r["operations"][0]["scallop"], 0.12);
    assert_eq!(r["tools"][0]["cutter"], "ball:d=8");
    let figures = |rep: &serde_json::Value| {
        let d = &rep["deviation"];
        (d["allowed_excess"].as_f64(), d["tol"].as_f64())
    };
    let mut seen = Vec::new();
    for program in ["record.ngc", "record.cl", "record.csv"] {
        let (rep, text) = verify(&dir, &dir.join(program), &format!("v-{program}"), &[]);
        assert!(text.contains("plan record"), "{program}: {text}");
        assert_eq!(figures(&rep), (Some(0.12), Some(0.02)), "{program}");
        seen.push(rep["deviation"]["excess"]["cells"].clone());
    }
    // The CL carries the G-code's moves; the pose CSV its passes, so its cells may
    // differ by what the links cut.
    assert_eq!(seen[0], seen[1], "{seen:?}");
    // A header edited by hand: the record still rules.
    let ngc = dir.join("record.ngc");
    let text = std::fs::read_to_string(&ngc).unwrap();
    assert!(text.contains("(scallop limit 0.12 mm)"), "{text}");
    std::fs::write(
        &ngc,
        text.replace("(scallop limit 0.12 mm)", "(scallop limit 3 mm)"),
    )
    .unwrap();
    let (rep, _) = verify(&dir, &ngc, "v-edited", &[]);
    assert_eq!(figures(&rep), (Some(0.12), Some(0.02)));
    // Without the record the header is read again (and the default tolerance).
    std::fs::remove_file(&record).unwrap();
    let (rep, text) = verify(&dir, &ngc, "v-header", &["--tool", "ball:d=8"]);
    assert!(text.contains("its header"), "{text}");
    assert_eq!(figures(&rep), (Some(3.0), Some(0.01)));
    let _ = std::fs::remove_dir_all(&dir);
}
