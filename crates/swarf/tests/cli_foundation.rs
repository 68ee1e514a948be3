//! Golden CLI tests of the foundation commands: outputs, exit codes and error
//! messages that name the file and field.

use std::path::PathBuf;
use std::process::{Command, Output};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn help_lists_every_subcommand() {
    let o = swarf(&["--help"]);
    assert!(o.status.success());
    let text = stdout(&o);
    for sub in [
        "inspect",
        "eval",
        "tessellate",
        "plan",
        "drop",
        "verify",
        "compare",
        "demo",
        "rest",
        "classify",
        "dsm",
    ] {
        assert!(
            text.contains(&format!("  {sub}")),
            "{sub} missing from:\n{text}"
        );
    }
}

#[test]
fn eval_matches_the_die_closed_form() {
    let o = swarf(&["eval", "die", "--patch", "0", "--uv", "0.3,0.7"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let (u, w) = (0.3_f64, 0.7_f64);
    let want = [
        -99.4 + 88.9 * w + 5.6 * w * w,
        -131.3 * u + 28.1 * u * u,
        5.9 * (u * u * w * w + u * u * w) - 3.9 * w * w * u + 76.2 * u * u + 6.7 * w * w
            - 27.3 * u * w
            - 50.8 * u
            + 25.0 * w
            + 12.1,
    ];
    for (k, want) in want.iter().enumerate() {
        let got = v["point"][k].as_f64().unwrap();
        assert!((got - want).abs() < 1e-9, "point[{k}] {got} vs {want}");
    }
    let want_du = [0.0, -131.3 + 56.2 * u];
    for (k, want) in want_du.iter().enumerate() {
        assert!((v["du"][k].as_f64().unwrap() - want).abs() < 1e-9);
    }
    let k1 = v["k1"].as_f64().unwrap();
    let k2 = v["k2"].as_f64().unwrap();
    assert!(k1 >= k2);
    let n: Vec<f64> = (0..3).map(|k| v["normal"][k].as_f64().unwrap()).collect();
    assert!((n.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
}

#[test]
fn inspect_reports_the_wave_box() {
    let o = swarf(&["inspect", "wave", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let p = &v["patches"][0];
    assert_eq!(p["degree"], serde_json::json!([3, 3]));
    for (k, want) in [0.0, 0.0].iter().enumerate() {
        assert!((p["bbox_min"][k].as_f64().unwrap() - want).abs() < 1e-6);
    }
    for (k, want) in [200.0, 100.0].iter().enumerate() {
        assert!((p["bbox_max"][k].as_f64().unwrap() - want).abs() < 1e-6);
    }
}

#[test]
fn tessellate_writes_a_readable_stl() {
    let dir = temp_dir("tess");
    let stl = dir.join("die.stl");
    let o = swarf(&[
        "tessellate",
        "die",
        "--tol",
        "0.1",
        "-o",
        stl.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mesh = swarf_io::read_stl(&stl).unwrap();
    assert!(mesh.triangles.len() > 100);
    let o = swarf(&["inspect", stl.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("no degenerate"), "{}", stdout(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_names_the_file_and_field() {
    let dir = temp_dir("bad");
    let part = dir.join("bad.toml");
    std::fs::write(
        &part,
        "name = \"bad\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\npoints = [[0,0,0],[1,0,0],[0,1,0]]\n",
    )
    .unwrap();
    let p = part.to_str().unwrap();
    let stl = dir.join("out.stl");
    let cases: [(Vec<&str>, &[&str]); 6] = [
        (vec!["inspect", p], &["bad.toml", "points", "expected 4"]),
        (vec!["eval", "die", "--uv", "0.5"], &["--uv", "two numbers"]),
        (vec!["eval", "die", "--uv", "1.5,0"], &["--uv", "outside"]),
        (
            vec!["eval", "die", "--patch", "3", "--uv", "0,0"],
            &["--patch"],
        ),
        (
            vec!["inspect", "no-such-part"],
            &["no-such-part", "built-in parts"],
        ),
        (
            vec![
                "tessellate",
                "wave",
                "--tol",
                "0",
                "-o",
                stl.to_str().unwrap(),
            ],
            &["--tol"],
        ),
    ];
    for (args, wants) in cases {
        let o = swarf(&args);
        assert!(!o.status.success(), "{args:?} should fail");
        let e = stderr(&o);
        for want in wants {
            assert!(e.contains(want), "{args:?}: {want:?} not in {e}");
        }
        assert!(!e.contains("panicked"), "{args:?}: {e}");
    }
    assert!(!stl.exists(), "a failed run must not write its output");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `swarf classify` on the built-in boss: the steep surface is the walls' closed
/// form (two sides of 80 x 10 / sin a for a = 45, 65, 80, 90 degrees), the regions
/// tile the 80 x 140 plate; bad angles and parts name what is wrong.
#[test]
fn classify_the_boss() {
    let dir = temp_dir("classify");
    let out = dir.to_str().unwrap();
    let o = swarf(&["classify", "boss", "-o", out]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("steep: "), "{}", stdout(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("classify.json")).unwrap()).unwrap();
    let walls: f64 = [45.0_f64, 65.0, 80.0, 90.0]
        .iter()
        .map(|a| 1600.0 / a.to_radians().sin())
        .sum();
    let area = |class: &str, what: &str| v["classes"][class][what].as_f64().unwrap();
    assert!(
        (area("steep", "surface_area_mm2") - walls).abs() < 1e-6,
        "{v}"
    );
    let xy: f64 = ["steep", "horizontal", "other"]
        .iter()
        .map(|c| area(c, "xy_area_mm2"))
        .sum();
    assert!((xy - 11200.0).abs() < 1e-3, "{xy}");
    assert_eq!(v["parameters"]["steep_angle_deg"], 40.0);
    assert_eq!(v["triangles"], 34);
    assert!(
        std::fs::read(dir.join("classify.png"))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
    // Only the 80 and 90 degree walls are steeper than 70 degrees.
    let o = swarf(&["classify", "boss", "--steep-angle", "70", "-o", out]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("classify.json")).unwrap()).unwrap();
    assert_eq!(v["classes"]["steep"]["triangles"], 8);
    let o = swarf(&["classify", "boss", "--steep-angle", "5", "-o", out]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains("--steep-angle 5: expected more than --flat-angle 10 degrees"),
        "{e}"
    );
    let o = swarf(&["classify", "boss", "--cell", "0", "-o", out]);
    assert!(!o.status.success() && stderr(&o).contains("--cell: expected a cell size"));
    let o = swarf(&["classify", "no-such-part", "-o", out]);
    assert!(!o.status.success() && stderr(&o).contains("no-such-part"));
    std::fs::remove_dir_all(&dir).ok();
}
