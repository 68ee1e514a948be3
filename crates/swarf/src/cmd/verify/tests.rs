//! Tests of `swarf verify`: reports, gouges and floors on a plane part, stopped
//! programs, two programs on one stock, a tool library.

use super::*;

/// The plane z = 0 over [0, 20] x [0, 10], as a part file in `dir`.
fn plane_part(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let part = dir.join("plane.toml");
    std::fs::write(
        &part,
        "name = \"plane\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
         points = [[0, 0, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]]\n",
    )
    .unwrap();
    part
}

/// The command's defaults, with 0.05 mm cells.
fn sim_args() -> SimArgs {
    SimArgs {
        stock: "offset:0.5".into(),
        cell: Some(0.05),
        tol: None,
        scallop: None,
        rapid: None,
        sample_tol: None,
        max_memory: 4096,
        deviation: None,
        first_order_sweep: false,
        floor: None,
    }
}

fn read_report(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A ball raster over a plane with one CL point 0.05 mm too deep, then the same
/// program cut off by a bad word: the gouge is reported with its line; the
/// stopped program fails and leaves the previous reports whole, or with
/// `--partial` writes the report of the motions before the stop.
#[test]
fn verify_finds_the_gouge_and_fails_on_a_stopped_program() {
    let (dir, program, g, gouge_line) = gouging_raster("test");
    let args = |program: &Path, out: &str| plane_args(&dir, &[program], &["ball:d=6"], out);
    run(&args(&program, "ok")).unwrap();
    let report = read_report(&dir.join("ok/report.json"));
    let worst = &report["deviation"]["gouges"][0];
    assert_eq!(worst["line"].as_u64(), Some(gouge_line as u64), "{worst}");
    assert!(
        (worst["worst"].as_f64().unwrap() + 0.05).abs() < 2e-3,
        "{worst}"
    );
    for f in ["flagged.csv", "deviation.png", "toolpath.png"] {
        assert!(dir.join("ok").join(f).exists(), "{f}");
    }
    let stopped = dir.join("stopped.ngc");
    let cut: String = g.lines().take(30).map(|l| format!("{l}\n")).collect();
    std::fs::write(&stopped, cut + "G1 X4 Y\n").unwrap();
    // Without --partial the previous set stays whole.
    let before: Vec<Vec<u8>> = ["report.json", "flagged.csv", "deviation.png"]
        .iter()
        .map(|f| std::fs::read(dir.join("ok").join(f)).unwrap())
        .collect();
    let err = run(&args(&stopped, "ok")).unwrap_err().to_string();
    assert!(
        err.contains("stopped.ngc:31") && err.contains("no report was written"),
        "{err}"
    );
    let after: Vec<Vec<u8>> = ["report.json", "flagged.csv", "deviation.png"]
        .iter()
        .map(|f| std::fs::read(dir.join("ok").join(f)).unwrap())
        .collect();
    assert!(before == after, "the previous reports were replaced");
    let mut partial = args(&stopped, "stop");
    partial.partial = true;
    let err = run(&partial).unwrap_err().to_string();
    assert!(
        err.contains("the report covers the motions before it"),
        "{err}"
    );
    let report = read_report(&dir.join("stop/report.json"));
    assert_eq!(report["complete"], serde_json::Value::Bool(false));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A ball d=6 raster on the plane part in a temporary folder named by `name`, its
/// tip 0.05 mm below the plane at one point: the folder, the program's file and
/// text, and the line of that move.
fn gouging_raster(name: &str) -> (PathBuf, PathBuf, String, usize) {
    let dir = std::env::temp_dir().join(format!("swarf-verify-{name}-{}", std::process::id()));
    plane_part(&dir);
    let mut g = String::from("G21 G90 G17\nG0 Z5\n");
    let mut gouge_line = 0;
    for k in 0..8 {
        let y = 0.625 + 1.25 * k as f64;
        g += &format!("G0 X-3 Y{y}\nG1 Z0 F100\n");
        for s in 0..=13 {
            let x = -3.0 + 2.0 * s as f64;
            let z = if k == 4 && s == 6 { -0.05 } else { 0.0 };
            g += &format!("G1 X{x} Y{y} Z{z} F300\n");
            if z < 0.0 {
                gouge_line = g.lines().count();
            }
        }
        g += "G0 Z5\n";
    }
    let program = dir.join("raster.ngc");
    std::fs::write(&program, &g).unwrap();
    (dir, program, g, gouge_line)
}

/// `swarf verify` of `programs` cut with `tools` on the plane part in `dir`, its
/// reports in `dir/out`.
fn plane_args(dir: &Path, programs: &[&Path], tools: &[&str], out: &str) -> Args {
    Args {
        part: dir.join("plane.toml").display().to_string(),
        program: programs.iter().map(|p| p.to_path_buf()).collect(),
        tool: tools.iter().map(|t| (*t).to_string()).collect(),
        tool_library: None,
        machine: None,
        tool_length: None,
        gcode: GcodeArgs::default(),
        sim: sim_args(),
        partial: false,
        out: dir.join(out),
    }
}

/// Without `--floor` no floor check; with `--floor 0` the move down to the
/// gouge and the one out of it are named by line, 0.05 mm below.
#[test]
fn verify_names_the_motions_below_the_floor() {
    let (dir, program, _, gouge_line) = gouging_raster("floor");
    run(&plane_args(&dir, &[&program], &["ball:d=6"], "none")).unwrap();
    let report = read_report(&dir.join("none/report.json"));
    assert!(report.get("floor").is_none(), "{}", report["floor"]);
    let mut floored = plane_args(&dir, &[&program], &["ball:d=6"], "floor");
    floored.sim.floor = Some(0.0);
    run(&floored).unwrap();
    let floor = &read_report(&dir.join("floor/report.json"))["floor"];
    let below: Vec<(u64, f64)> = floor["below"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| (n["line"].as_u64().unwrap(), n["amount"].as_f64().unwrap()))
        .collect();
    let at = gouge_line as u64;
    assert_eq!(
        below.iter().map(|b| b.0).collect::<Vec<_>>(),
        [at, at + 1],
        "{floor}"
    );
    assert!(below.iter().all(|b| (b.1 - 0.05).abs() < 1e-9), "{floor}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A ball raster along x over the plane with tool radius `r`: passes `step` apart
/// from y = 0 to y = 10, the tip on the plane, plunging and retracting off the part.
fn raster(step: f64, r: f64) -> String {
    let (x0, x1) = (-(r + 1.0), 20.0 + r + 1.0);
    let mut g = String::from("G21 G90 G17\nG0 Z5\n");
    let n = (10.0 / step).round() as usize;
    for k in 0..=n {
        let y = k as f64 * step;
        g += &format!("G0 X{x0} Y{y:.4}\nG1 Z0 F300\nG1 X{x1} F600\nG0 Z5\n");
    }
    g
}

/// A finish (ball d=6, 2.5 mm stepover: 0.27 mm scallops), then its cleanup (ball
/// d=2, 0.2 mm stepover: 0.005 mm scallops) on the same stock: the cleanup takes
/// out what the finish left, and the report names both programs and tools.
#[test]
fn verify_runs_a_finish_then_its_cleanup_on_one_stock() {
    let dir = std::env::temp_dir().join(format!("swarf-verify-two-{}", std::process::id()));
    plane_part(&dir);
    let (finish, cleanup) = (dir.join("finish.ngc"), dir.join("cleanup.ngc"));
    std::fs::write(&finish, raster(2.5, 3.0)).unwrap();
    std::fs::write(&cleanup, raster(0.2, 1.0)).unwrap();
    let args = |programs: &[&PathBuf], tools: &[&str], out: &str| {
        let programs: Vec<&Path> = programs.iter().map(|p| p.as_path()).collect();
        plane_args(&dir, &programs, tools, out)
    };
    run(&args(&[&finish], &["ball:d=6"], "finish")).unwrap();
    let alone = read_report(&dir.join("finish/report.json"));
    let left = alone["deviation"]["excess"]["cells"].as_u64().unwrap();
    assert!(left > 10_000, "{}", alone["deviation"]);
    assert!(alone.get("programs").is_none());

    let both = [&finish, &cleanup];
    run(&args(&both, &["ball:d=6", "ball:d=2"], "both")).unwrap();
    let report = read_report(&dir.join("both/report.json"));
    let d = &report["deviation"];
    assert_eq!(d["excess"]["cells"].as_u64(), Some(0), "{d}");
    assert_eq!(d["gouge"]["cells"].as_u64(), Some(0), "{d}");
    assert!(d["max"].as_f64().unwrap() < 0.01, "{d}");
    let names = format!("{} + {}", finish.display(), cleanup.display());
    assert_eq!(report["program"].as_str(), Some(names.as_str()));
    assert_eq!(report["tool"], "ball:d=6 + ball:d=2");
    let programs = report["programs"].as_array().unwrap();
    assert_eq!(programs.len(), 2);
    assert_eq!(programs[1]["source"].as_str(), cleanup.to_str());
    assert_eq!(programs[1]["tool"], "ball:d=2");
    let motions = |r: &serde_json::Value| r["program_stats"]["motions"].as_u64().unwrap();
    assert_eq!(
        motions(&report),
        motions(&alone) + programs[1]["stats"]["motions"].as_u64().unwrap()
    );
    let csv = std::fs::read_to_string(dir.join("both/flagged.csv")).unwrap();
    assert!(csv.starts_with("x,y,design_z,machined_z,deviation,kind,motion,line,program\n"));

    let err = run(&args(&both, &["ball:d=6", "ball:q=2"], "bad"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("--tool ball:q=2 (tool 2 of 2)"), "{err}");
    let missing = dir.join("missing.ngc");
    let err = run(&args(&[&finish, &missing], &["ball:d=6"], "bad"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("missing.ngc"), "{err}");
    // A finish that stops mid-way: the cleanup after it is not simulated.
    let stopped = dir.join("stopped.ngc");
    let cut: String = raster(2.5, 3.0)
        .lines()
        .take(10)
        .map(|l| l.to_string() + "\n")
        .collect();
    std::fs::write(&stopped, cut + "G1 X4 Y\n").unwrap();
    let two = [&stopped, &cleanup];
    let mut partial = args(&two, &["ball:d=6", "ball:d=2"], "stop");
    partial.partial = true;
    let err = run(&partial).unwrap_err().to_string();
    assert!(err.contains("stopped.ngc:11"), "{err}");
    let report = read_report(&dir.join("stop/report.json"));
    assert_eq!(report["complete"], serde_json::Value::Bool(false));
    assert!(report.get("programs").is_none(), "{}", report["programs"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--tool-library` with the shipped library: tool 3 (ball d=6, holder nose
/// d=20 at stick-out 30) plunged to the floor of the 40 mm deep pocket: the
/// holder hits the top from the tip at z < 10, and the holder face must sit on
/// the top at the floor: stick-out 40.
#[test]
fn verify_with_a_tool_library_reports_the_holder() {
    let dir = std::env::temp_dir().join(format!("swarf-verify-holder-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("pocket.ngc");
    std::fs::write(
        &program,
        "G21 G90 G17\nG0 X30 Y20 Z50\nG1 Z0 F100\nG1 Y40 F300\nG0 Z50\n",
    )
    .unwrap();
    let library = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tooling/library.toml"
    ));
    let args = |tool: &str| Args {
        part: "deep-pocket".into(),
        program: vec![program.clone()],
        tool: vec![tool.into()],
        tool_library: Some(library.clone()),
        machine: None,
        tool_length: None,
        gcode: GcodeArgs::default(),
        sim: sim_args(),
        partial: false,
        out: dir.join("out"),
    };
    run(&args("ball6-long")).unwrap();
    let checks = read_report(&dir.join("out/holder.json"));
    let c = &checks[0];
    assert_eq!(c["number"], 3);
    let first = &c["collisions"][0];
    assert_eq!(first["line"], 3, "{first}");
    assert_eq!(first["piece"]["Holder"], 0, "{first}");
    let deepest = c["collisions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["depth"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert!((deepest - 10.0).abs() < 1e-9, "{deepest}");
    let s = c["vertical"]["shortest"]["Clears"]["stick_out"]
        .as_f64()
        .unwrap();
    assert!((s - 40.0).abs() < 1e-9, "{s}");
    let err = run(&args("T7")).unwrap_err().to_string();
    assert!(
        err.contains("no tool `T7`") && err.contains("3 \"ball6-long\""),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--program` and `--tool` repeat, in order; at least one program.
#[test]
fn programs_and_tools_repeat_in_order() {
    use clap::Parser;
    #[derive(clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: Args,
    }
    let cli = Cli::try_parse_from([
        "verify",
        "--part",
        "p",
        "--program",
        "a.ngc",
        "--tool",
        "ball:d=6",
        "--program",
        "b.cl",
        "--tool",
        "ball:d=2",
        "-o",
        "out",
    ])
    .unwrap();
    let programs: Vec<&str> = cli
        .args
        .program
        .iter()
        .map(|p| p.to_str().unwrap())
        .collect();
    assert_eq!(programs, ["a.ngc", "b.cl"]);
    assert_eq!(cli.args.tool, ["ball:d=6", "ball:d=2"]);
    assert!(Cli::try_parse_from(["verify", "--part", "p", "-o", "out"]).is_err());
}
