//! The cases listed in issue 15.

use crate::support::*;
use std::path::Path;
use std::process::Command;

#[test]
fn aborts_are_refusals() {
    let dir = scratch("aborts");
    let part = plate(&dir);
    std::fs::write(
        dir.join("arc.ngc"),
        "G21 G90 G17\nG0 X0 Y0 Z1\nG2 X0 Y0 I1e30 F100\nM2\n",
    )
    .unwrap();
    let (ok, text, _) = swarf_in(&dir, &verify_cmd(&part, "arc.ngc", "ball:d=6", &[]));
    assert!(!ok && text.contains("arc.ngc:3"), "{text}");
    refused(
        &dir,
        &verify_cmd(&part, "arc.ngc", "ball:d=6", &["--sample-tol", "1e-9"]),
        &[
            "--sample-tol",
            "expected a sampling distance",
            "found 1e-9",
            "nearest that fits: 0.0001",
        ],
    );
    refused(
        &dir,
        &verify_cmd(
            "wave",
            "arc.ngc",
            "ball:d=6",
            &["--cell", "0.0001", "--max-memory", "100000000"],
        ),
        &["--cell", "expected a cell size"],
    );
    refused(
        &dir,
        &verify_cmd(
            "wave",
            "arc.ngc",
            "ball:d=6",
            &["--max-memory", "100000000"],
        ),
        &["--max-memory", "1048576 MiB"],
    );
}

#[test]
fn job_hangs_are_refusals() {
    let dir = scratch("job-hangs");
    let scallop = "kind = \"iso-scallop\"\nscallop = 0.15\ntolerance = 0.01";
    for (tool, strategy, needles) in [
        (
            "ball:d=1e308",
            scallop,
            vec!["tool", "d", "expected a tool diameter"],
        ),
        (
            "ball:d=8",
            "kind = \"iso-scallop\"\nscallop = 0.000001\ntolerance = 0.01",
            vec!["strategy.scallop", "found 1e-6"],
        ),
        (
            "ball:d=8",
            "kind = \"iso-scallop\"\nscallop = 0.15\ntolerance = 5e-324",
            vec!["strategy.tolerance", "5e-324"],
        ),
        (
            "ball:d=1e308",
            "kind = \"iso-parametric\"\nstepover = 1\ntolerance = 0.01",
            vec!["expected a tool diameter"],
        ),
    ] {
        let job = wave_job(&dir, "job.toml", tool, strategy);
        refused(&dir, &["plan", &job], &needles);
    }
    let inclined = dir.join("inclined.toml");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs/die-inclined-3.toml"),
    )
    .unwrap();
    assert!(
        text.contains("sections = 1.0"),
        "the shipped inclined job has sections"
    );
    std::fs::write(&inclined, text.replace("sections = 1.0", "sections = 1e-9")).unwrap();
    // A plate 0.9 km square (inside the coordinate domain) rastered at 0.01 mm.
    let mut stl = String::from("solid big\n");
    for t in [[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]] {
        stl += "facet normal 0 0 1\nouter loop\n";
        for [x, y] in t {
            stl += &format!("vertex {} {} 0\n", x * 900_000, y * 900_000);
        }
        stl += "endloop\nendfacet\n";
    }
    std::fs::write(dir.join("big.stl"), stl + "endsolid big\n").unwrap();
    std::fs::write(
        dir.join("big.toml"),
        "part = \"big.stl\"\ntool = \"ball:d=6\"\n[strategy]\nkind = \"raster\"\n\
         stepover = 0.01\ntolerance = 0.01\n[output]\ngcode = \"big.ngc\"\n",
    )
    .unwrap();
    refused(
        &dir,
        &["plan", "big.toml"],
        &[
            "big.toml",
            "strategy.stepover",
            "more than the limit of 5e7",
        ],
    );
    refused(
        &dir,
        &["plan", inclined.to_str().unwrap()],
        &["sections", "1e-9"],
    );
}

#[test]
fn command_hangs_are_refusals() {
    let dir = scratch("hangs");
    let part = plate(&dir);
    line_ngc(&dir);
    refused(
        &dir,
        &verify_cmd(&part, "line.ngc", "cone:d=1e9,angle=90", &[]),
        &["--tool cone:d=1e9,angle=90", "expected a tool diameter"],
    );
    refused(
        &dir,
        &["tessellate", "wave", "--tol", "5e-324", "-o", "w.stl"],
        &["--tol", "5e-324"],
    );
    std::fs::write(dir.join("p.csv"), "x,y\n1,2\n").unwrap();
    let stl = dir.join("w.stl");
    let (ok, text, _) = swarf_in(&dir, &["tessellate", "wave", "--tol", "0.1", "-o", "w.stl"]);
    assert!(ok && stl.exists(), "{text}");
    refused(
        &dir,
        &[
            "drop",
            "--mesh",
            "w.stl",
            "--tool",
            "ball:d=4",
            "--points",
            "p.csv",
            "--threads",
            "100000",
        ],
        &[
            "--threads",
            "expected a thread count from 1 to 1024",
            "found 100000",
        ],
    );
    let fifo = dir.join("part.toml");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    if made {
        refused(
            &dir,
            &["inspect", "part.toml"],
            &["part.toml", "not a regular file"],
        );
    }
}

#[test]
fn unbounded_reads_are_refused() {
    let dir = scratch("reads");
    let part = plate(&dir);
    line_ngc(&dir);
    wave_stl(&dir);
    for args in [
        vec!["inspect", "/dev/zero"],
        vec![
            "drop",
            "--mesh",
            "w.stl",
            "--tool",
            "ball:d=4",
            "--points",
            "/dev/zero",
        ],
        vec!["plan", "/dev/zero"],
        vec![
            "verify",
            "--part",
            &part,
            "--program",
            "line.ngc",
            "--tool",
            "ball:d=4",
            "--machine",
            "/dev/zero",
            "-o",
            "v",
        ],
    ] {
        refused(&dir, &args, &["/dev/zero", "not a regular file"]);
    }
    // A 10 MB token is quoted shortened.
    let token = "x".repeat(10 << 20);
    std::fs::write(
        dir.join("big.toml"),
        format!("name = \"b\"\nunits = {token}\n"),
    )
    .unwrap();
    refused(&dir, &["inspect", "big.toml"], &["big.toml"]);
    let arg = format!("ball:d={}", &token[..100_000]);
    refused(
        &dir,
        &[
            "drop", "--mesh", "w.stl", "--tool", &arg, "--points", "line.ngc",
        ],
        &["--tool"],
    );
}

#[test]
fn non_finite_numbers_are_errors() {
    let dir = scratch("finite");
    let part = plate(&dir);
    let digits = "9".repeat(400);
    std::fs::write(
        dir.join("long.ngc"),
        format!("G21 G90\nG0 X0 Y0 Z5\nG1 X{digits} F100\nM2\n"),
    )
    .unwrap();
    std::fs::write(dir.join("far.cl"), "GOTO/0,0,5\nGOTO/1e308,0,0\n").unwrap();
    std::fs::write(
        dir.join("far.csv"),
        "x,y,z,i,j,k\n0,0,5,0,0,1\n-1e300,0.6,0.8,0,0,1\n",
    )
    .unwrap();
    for (program, line) in [
        ("long.ngc", "long.ngc:3"),
        ("far.cl", "far.cl:2"),
        ("far.csv", "far.csv:3"),
    ] {
        let (ok, text, _) = swarf_in(&dir, &verify_cmd(&part, program, "ball:d=4", &[]));
        assert!(
            !ok && text.contains(line) && !text.contains("inf"),
            "{program}: {text}"
        );
        assert!(
            !dir.join("v/report.json").exists(),
            "{program}: a report was written"
        );
    }
    std::fs::write(dir.join("p.csv"), "x,y\n100,100\n").unwrap();
    wave_stl(&dir);
    refused(
        &dir,
        &[
            "drop",
            "--mesh",
            "w.stl",
            "--tool",
            "ball:d=1e308",
            "--points",
            "p.csv",
        ],
        &["ball:d=1e308", "expected a tool diameter"],
    );
}

#[test]
fn flags_beyond_their_domains_are_refused() {
    let dir = scratch("flags");
    let part = plate(&dir);
    line_ngc(&dir);
    for (flag, value, what) in [
        ("--tol", "1e308", "a tolerance"),
        ("--tol", "5e-324", "a tolerance"),
        ("--scallop", "1e308", "a scallop height"),
        ("--rapid", "1e308", "a rate"),
        ("--cell", "5e-324", "a cell size"),
    ] {
        refused(
            &dir,
            &verify_cmd(&part, "line.ngc", "ball:d=4", &[flag, value]),
            &[flag, what, value],
        );
    }
}

#[test]
fn far_coordinates_fail_fast_naming_the_file_and_patch() {
    let dir = scratch("far");
    for (name, x) in [("huge.toml", "1e308"), ("far.toml", "1e150")] {
        std::fs::write(
            dir.join(name),
            format!(
                "name = \"far\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
                 points = [[0, 0, 0], [0, 10, 0], [{x}, 0, 0], [20, 10, 0]]\n"
            ),
        )
        .unwrap();
        let (ok, text, secs) =
            swarf_in(&dir, &["tessellate", name, "--tol", "0.01", "-o", "x.stl"]);
        assert!(!ok && secs < 5.0, "{secs} s: {text}");
        for n in [
            name,
            "line 5",
            "patch[0].points[2]",
            "expected a coordinate",
        ] {
            assert!(text.contains(n), "no {n:?} in {text}");
        }
        assert!(!text.contains("tol = 0.001"), "{text}");
    }
    std::fs::write(dir.join("empty.obj"), "v 0 0 0\nv 1 0 0\n").unwrap();
    line_ngc(&dir);
    refused(
        &dir,
        &verify_cmd("empty.obj", "line.ngc", "ball:d=4", &[]),
        &["empty.obj", "no triangle"],
    );
}

#[test]
fn output_sets_are_whole() {
    let dir = scratch("sets");
    // A plan whose second output cannot be put in place: neither is replaced.
    let job = wave_job(
        &dir,
        "job.toml",
        "ball:d=8",
        "kind = \"iso-planar\"\nstepover = 2\ntolerance = 0.05",
    );
    let text = std::fs::read_to_string(&job).unwrap() + "cl = \"out.cl\"\n";
    std::fs::write(&job, text).unwrap();
    let (ok, out, _) = swarf_in(&dir, &["plan", &job]);
    assert!(ok, "{out}");
    let before = std::fs::read(dir.join("out.ngc")).unwrap();
    let text = std::fs::read_to_string(&job).unwrap();
    std::fs::write(
        &job,
        text.replace("stepover = 2", "stepover = 3")
            .replace("out.cl", "blocked"),
    )
    .unwrap();
    std::fs::create_dir_all(dir.join("blocked")).unwrap();
    let (ok, out, _) = swarf_in(&dir, &["plan", &job]);
    assert!(
        !ok && out.contains("blocked: cannot replace: it is a directory"),
        "{out}"
    );
    assert_eq!(
        std::fs::read(dir.join("out.ngc")).unwrap(),
        before,
        "a new G-code beside an old CL"
    );
    // Temporary files of a killed run are removed by the next run.
    let stale = dir.join(".out.ngc.4194304.0.tmp");
    std::fs::write(&stale, "half").unwrap();
    std::fs::write(&job, text.replace("blocked", "out.cl")).unwrap();
    let (ok, out, _) = swarf_in(&dir, &["plan", &job]);
    assert!(ok && !stale.exists(), "{out}");
    let temps: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(temps.is_empty(), "{temps:?}");
    // An output that is an input.
    let (ok, out, _) = swarf_in(&dir, &["tessellate", "wave", "--tol", "0.1", "-o", "w.stl"]);
    assert!(ok, "{out}");
    std::fs::write(dir.join("p.csv"), "x,y\n1,2\n").unwrap();
    refused(
        &dir,
        &[
            "drop", "--mesh", "w.stl", "--tool", "ball:d=4", "--points", "p.csv", "-o", "p.csv",
        ],
        &["p.csv: cannot replace: it is an input of this command"],
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("p.csv")).unwrap(),
        "x,y\n1,2\n"
    );
    // A directory named like a built-in part does not hide it; a file does, and says so.
    std::fs::create_dir_all(dir.join("die")).unwrap();
    let (ok, out, _) = swarf_in(&dir, &["inspect", "die"]);
    assert!(ok, "{out}");
    let (ok, out, _) = swarf_in(&dir, &["inspect", "builtin:die"]);
    assert!(ok, "{out}");
    std::fs::write(dir.join("wave"), "not a part").unwrap();
    let (ok, out, _) = swarf_in(&dir, &["inspect", "wave"]);
    assert!(
        !ok && out.contains("write builtin:wave for the built-in part"),
        "{out}"
    );
}
