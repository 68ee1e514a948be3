//! Hostile input (issue 15): a structure-aware fuzz suite that runs on stable Rust.
//!
//! Every input swarf reads has a proptest strategy that mutates real seeds: part
//! files (TOML, STEP and IGES), job files, tool specs, G-code (swarf's own three- and five-axis programs,
//! hand-written RS274 with parameters, O-words and canned cycles, Fanuc macro B, and
//! the LinuxCNC reference corpus), APT CL, pose CSV, binary and ASCII STL, OBJ,
//! machine files, drop points CSV, LinuxCNC tool tables and parameter files, and
//! the command-line option values. Mutations put extreme numbers in place of real
//! ones (1e308, -1e308, 5e-324, -0, 1e-200, 1e30, 400 digits, nan, inf ...),
//! delete, duplicate and swap lines and tokens, cut the file short, insert binary
//! garbage and 100 KB tokens, or empty it; binary STL gets NaN and infinite floats,
//! lying triangle counts and collapsed triangles ([`mutate`], [`mesh`], [`options`]).
//!
//! Each case runs the built `swarf` binary, exactly as a user would, in a fresh
//! folder, under a memory cap (`ulimit -v`, 3000 MB) and a wall-clock limit (60 s: a
//! hang, not a slow case, with room for a loaded CI machine that runs the debug
//! build's slowest seed, about 5 s on an idle two-core one, four times slower), and
//! must: finish in time; not die by a signal (abort, allocation failure, stack
//! overflow); not panic (exit status 101); write only finite numbers to standard
//! output and its files (no `inf` or `NaN` words, no JSON `null` where a number
//! belongs, finite floats in STL); and, when it fails, name the place in its error:
//! the mutated file or the option ([`check`]). One case runs at a time. Commands
//! that simulate are given `--max-memory=1024` (unless that option is the one
//! fuzzed), so that their own grid limit lies under the cap.
//!
//! A failing case prints its reproducer: the command line to run in the case folder
//! (kept, with the inputs and a `cmd.sh`), the mutated input when it is short text,
//! and the `SWARF_FUZZ_SEED` / `SWARF_FUZZ_CASE` pair that regenerates it. Each kind
//! of failure is shrunk (a few runs) to a smaller input; failures are grouped by
//! command, input type and symptom, and each test ends with its table of distinct
//! failures (also written to `$SWARF_FUZZ_DIR/INPUT.txt`).
//!
//! # Running
//!
//! Every input type runs in the workspace tests (and so in CI) with the default
//! count and seed 1, a fixed set of cases that must all pass:
//!
//! ```sh
//! cargo test -p swarf --test fuzz -- --nocapture          # every input type
//! cargo test -p swarf --test fuzz -- --nocapture fuzz_gcode
//! ```
//!
//! Settings (environment):
//!
//! - `SWARF_FUZZ_CASES` cases per input type (default 32: the 13 input types and
//!   the unmutated seeds take about two and a half minutes in the test profile on
//!   two cores);
//! - `SWARF_FUZZ_SEED` the seed (default 1); `SWARF_FUZZ_CASE=N` runs only case N,
//!   to reproduce it;
//! - `SWARF_FUZZ_TIMEOUT` seconds per run (60), `SWARF_FUZZ_MEMORY_MB` (3000);
//! - `SWARF_FUZZ_SHRINK` runs spent shrinking each new failure (8; 0 for none);
//! - `SWARF_FUZZ_DIR` where case folders go (default `$TMPDIR/swarf-fuzz-SEED`).
//!
//! For a long local run (about an hour on two cores: cases take 0.1 to 2 s each),
//! raise the count and pick a fresh seed, in the release profile for more cases per
//! hour:
//!
//! ```sh
//! SWARF_FUZZ_CASES=300 SWARF_FUZZ_SEED=$RANDOM \
//!   cargo test --release -p swarf --test fuzz -- --nocapture --test-threads 1
//! ```

mod cases;
mod check;
mod exec;
mod mesh;
mod mutate;
mod options;
mod runner;
mod seeds;

use runner::fuzz;

#[test]
fn fuzz_part() {
    let seeds = seeds::parts();
    fuzz("part", cases::edit(), |v| cases::part(&seeds, v));
}

#[test]
fn fuzz_job() {
    let seeds = seeds::jobs();
    fuzz("job", cases::edit(), |v| cases::job(&seeds, v));
}

#[test]
fn fuzz_tool() {
    fuzz("tool", cases::edit(), cases::tool);
}

#[test]
fn fuzz_gcode() {
    let seeds = seeds::gcode();
    fuzz("gcode", cases::edit(), |v| cases::gcode(&seeds, v));
}

#[test]
fn fuzz_cl() {
    let seeds: Vec<_> = ["wave-raster.cl", "die-inclined.cl"]
        .iter()
        .map(|n| seeds::file_seed(&format!("{}/{n}", seeds::OWN)))
        .collect();
    fuzz("cl", cases::edit(), |v| cases::cl(&seeds, v));
}

#[test]
fn fuzz_pose_csv() {
    let seeds: Vec<_> = ["wave-raster.csv", "tilted.csv"]
        .iter()
        .map(|n| seeds::file_seed(&format!("{}/{n}", seeds::OWN)))
        .collect();
    fuzz("pose-csv", cases::edit(), |v| cases::pose_csv(&seeds, v));
}

#[test]
fn fuzz_stl_binary() {
    fuzz("stl-binary", mesh::stl_edit(), mesh::binary_stl_case);
}

#[test]
fn fuzz_stl_ascii() {
    let seed = mesh::ascii_stl(&mesh::height_field(8));
    fuzz("stl-ascii", cases::edit(), |v| {
        mesh::text_mesh("mesh.stl", &seed, v)
    });
}

#[test]
fn fuzz_obj() {
    let seed = mesh::obj(8);
    fuzz("obj", cases::edit(), |v| {
        mesh::text_mesh("mesh.obj", &seed, v)
    });
}

#[test]
fn fuzz_machine() {
    let seeds = seeds::dir_seeds("machines", ".toml");
    let jobs = seeds::jobs();
    fuzz("machine", cases::edit(), |v| {
        cases::machine(&seeds, &jobs, v)
    });
}

#[test]
fn fuzz_points() {
    let seeds = seeds::points();
    fuzz("points", cases::edit(), |v| cases::points(&seeds, v));
}

#[test]
fn fuzz_nc_setup() {
    fuzz("nc-setup", cases::edit(), cases::nc_setup);
}

#[test]
fn fuzz_options() {
    fuzz("options", options::option_edit(), options::option_case);
}

/// The unmutated seeds pass every check (else the suite would report swarf's
/// handling of good input, not of its mutations): each seed, with no edit, through
/// every command of its input type.
#[test]
fn seeds_pass_unmutated() {
    let mut all = Vec::new();
    let mut each = |n: usize, commands: &[usize], make: &dyn Fn(&cases::Edit) -> exec::Case| {
        for k in 0..n {
            for &c in commands {
                all.push(make(&(k, Vec::new(), c)));
            }
        }
    };
    let parts = seeds::parts();
    each(parts.len(), &[0, 1, 2, 3, 4, 5, 6, 7], &|v| {
        cases::part(&parts, v)
    });
    let jobs = seeds::jobs();
    each(jobs.len(), &[0, 4, 5], &|v| cases::job(&jobs, v));
    each(seeds::TOOLS.len(), &[0, 1, 2, 3, 4], &cases::tool);
    let gcode = seeds::gcode();
    each(gcode.len(), &[0], &|v| cases::gcode(&gcode, v));
    let machines = seeds::dir_seeds("machines", ".toml");
    each(machines.len(), &[0, 1], &|v| {
        cases::machine(&machines, &jobs, v)
    });
    let points = seeds::points();
    each(points.len(), &[0, 1, 2], &|v| cases::points(&points, v));
    each(2, &[0, 1, 2, 3, 4, 5, 6], &cases::nc_setup);
    let ascii = mesh::ascii_stl(&mesh::height_field(8));
    let obj = mesh::obj(8);
    let stl = mesh::binary_stl(&mesh::height_field(8));
    for c in 0..6 {
        all.push(mesh::text_mesh("mesh.stl", &ascii, &(0, Vec::new(), c)));
        all.push(mesh::text_mesh("mesh.obj", &obj, &(0, Vec::new(), c)));
        all.push(mesh::mesh_case(
            "mesh.stl",
            stl.clone(),
            c,
            "binary STL seed".into(),
        ));
    }
    for name in [
        "wave-raster.cl",
        "die-inclined.cl",
        "wave-raster.csv",
        "tilted.csv",
    ] {
        let s = vec![seeds::file_seed(&format!("{}/{name}", seeds::OWN))];
        let v = (0, Vec::new(), 0);
        all.push(if name.ends_with(".cl") {
            cases::cl(&s, &v)
        } else {
            cases::pose_csv(&s, &v)
        });
    }
    all.extend(options::good_cases());
    runner::run_cases("seeds", all);
}
