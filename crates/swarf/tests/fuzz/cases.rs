//! Cases for each input file type: which seed, which edits, and the command that
//! reads the mutated file (several commands read each type).

use crate::exec::Case;
use crate::mesh;
use crate::mutate::{Mutation, apply_all, mutations};
use crate::seeds::{self, Seed};
use proptest::prelude::*;

/// A seed index, the edits to make to it, and a command index (each taken modulo
/// what there is).
pub type Edit = (usize, Vec<Mutation>, usize);

/// Any [`Edit`].
pub fn edit() -> impl Strategy<Value = Edit> {
    (0usize..1000, mutations(), 0usize..1000)
}

/// Files named by `name` and content.
pub type Files = Vec<(String, Vec<u8>)>;

pub fn file(name: &str, text: &str) -> (String, Vec<u8>) {
    (name.to_string(), text.as_bytes().to_vec())
}

/// A case of `command` with `args`; `places` may name the error.
pub fn case(
    command: &'static str,
    args: &[&str],
    files: Files,
    places: &[&str],
    about: String,
) -> Case {
    Case {
        command,
        args: args.iter().map(|a| (*a).to_string()).collect(),
        files,
        places: places.iter().map(|p| (*p).to_string()).collect(),
        about,
    }
}

/// The seed `k` (modulo) and its mutated bytes.
fn mutated<'a>(seeds: &'a [Seed], k: usize, ms: &[Mutation]) -> (&'a Seed, Vec<u8>, String) {
    let seed = &seeds[k % seeds.len()];
    let about = format!("seed {}; edits {ms:?}", seed.origin);
    (seed, apply_all(&seed.bytes, ms), about)
}

/// A part file, read by every command that takes a part.
pub fn part(seeds: &[Seed], (k, ms, cmd): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let p = seed.name.as_str();
    let mut files = vec![(p.to_string(), bytes)];
    match cmd % 8 {
        0 => case("inspect", &["inspect", p], files, &[p], about),
        1 => case("inspect", &["inspect", p, "--json"], files, &[p], about),
        2 => {
            let args = ["eval", p, "--patch=0", "--uv=0.5,0.5"];
            case("eval", &args, files, &[p, "--patch", "--uv"], about)
        }
        3 => {
            let args = ["tessellate", p, "--tol=0.1", "-o", "out.stl"];
            case("tessellate", &args, files, &[p], about)
        }
        4 => case(
            "classify",
            &["classify", p, "--cell=2", "-o", "out"],
            files,
            &[p],
            about,
        ),
        5 => {
            files.push(file("pass.ngc", seeds::PLATE_PROGRAM));
            let args = [
                "verify",
                "--part",
                p,
                "--program",
                "pass.ngc",
                "--tool=ball:d=6",
                "--cell=1",
                "--max-memory=1024",
                "-o",
                "out",
            ];
            case("verify", &args, files, &[p], about)
        }
        6 => {
            let args = [
                "dsm",
                p,
                "--tool=bull:d=12,r=2",
                "--station=50",
                "--offset=1",
            ];
            let places = [p, "--faces", "--station", "--offset"];
            case("dsm", &args, files, &places, about)
        }
        _ => {
            let args = ["rest", "--part", p, "--reference=ball:d=12", "-o", "out"];
            case("rest", &args, files, &[p], about)
        }
    }
}

/// A job file, planned (and sometimes compared or used as a rest parent).
pub fn job(seeds: &[Seed], (k, ms, cmd): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let j = seed.name.as_str();
    let mut files = seeds::parents(seed, seeds);
    files.insert(0, (j.to_string(), bytes));
    match cmd % 6 {
        0..=3 => case("plan", &["plan", j, "--out", "out"], files, &[j], about),
        4 => case(
            "rest",
            &["rest", "--job", j, "-o", "out"],
            files,
            &[j],
            about,
        ),
        _ => {
            let args = ["compare", j, "--cell=1", "--max-memory=1024", "-o", "out"];
            case("compare", &args, files, &[j], about)
        }
    }
}

/// A tool spec text: a seed spec with text edits, as one command-line word.
pub fn tool_spec(seeds: &[&str], k: usize, ms: &[Mutation]) -> String {
    let seed = seeds[k % seeds.len()];
    let text = String::from_utf8_lossy(&apply_all(seed.as_bytes(), ms)).replace('\0', "");
    // One argument may hold at most 128 KiB on Linux: cut by bytes, not characters
    // (a replacement character takes three).
    crate::check::head(&text, 100_000)
}

/// `s` as a TOML basic string.
pub fn toml_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out += "\\\"",
            '\\' => out += "\\\\",
            c if c.is_control() => out += &format!("\\u{:04X}", c as u32),
            c => out.push(c),
        }
    }
    out + "\""
}

/// A tool spec, given to every command that takes one.
pub fn tool((k, ms, cmd): &Edit) -> Case {
    let spec = tool_spec(seeds::TOOLS, *k, ms);
    let about = format!(
        "seed {:?}; edits {ms:?}",
        seeds::TOOLS[k % seeds::TOOLS.len()]
    );
    let tool = format!("--tool={spec}");
    match cmd % 5 {
        0 => {
            let files = vec![
                ("mesh.stl".into(), mesh::binary_stl(&mesh::height_field(8))),
                file("points.csv", "x,y\n10,10\n20,25\n-30,5\n"),
            ];
            let args = [
                "drop",
                "--mesh",
                "mesh.stl",
                "--points",
                "points.csv",
                &tool,
            ];
            case("drop", &args, files, &["--tool"], about)
        }
        1 => {
            let files = vec![
                file("plate.toml", seeds::PLATE),
                file("pass.ngc", seeds::PLATE_PROGRAM),
            ];
            let args = [
                "verify",
                "--part",
                "plate.toml",
                "--program",
                "pass.ngc",
                &tool,
                "--cell=0.5",
                "--max-memory=1024",
                "-o",
                "out",
            ];
            case("verify", &args, files, &["--tool"], about)
        }
        2 => {
            let reference = format!("--reference={spec}");
            let args = ["rest", "--part", "v-grooves", &reference, "-o", "out"];
            case("rest", &args, Vec::new(), &["--reference"], about)
        }
        3 => {
            let args = ["dsm", "wedge-30-45", &tool, "--station=50", "--offset=1"];
            case("dsm", &args, Vec::new(), &["--tool"], about)
        }
        _ => {
            let job = seeds::TOOL_JOB.replace("TOOL", &toml_string(&spec));
            let files = vec![file("tool.toml", &job)];
            let args = ["plan", "tool.toml", "--out", "out"];
            case("plan", &args, files, &["tool.toml"], about)
        }
    }
}

/// A G-code program, verified with the setup its seed needs.
pub fn gcode(seeds: &[Seed], (k, ms, _): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let p = seed.name.as_str();
    let mut files = vec![(p.to_string(), bytes)];
    let mut args = vec!["verify", "--program", p, "--max-memory=1024", "-o", "out"];
    match p {
        "wave-raster.ngc" => args.extend(["--part=wave", "--tool=ball:d=8", "--cell=1"]),
        "die-trunnion.ngc" => args.extend([
            "--part=die",
            "--machine=builtin:xyzac-trunnion",
            "--tool=bull:d=38.1,r=6.35",
            "--cell=2",
        ]),
        _ => {
            files.push(file("floor.toml", seeds::FLOOR));
            args.extend(["--part=floor.toml", "--tool=ball:d=6", "--cell=1"]);
        }
    }
    if p == "fanuc.nc" {
        args.push("--dialect=fanuc");
    }
    let mut places = vec![p.to_string()];
    if seed.origin.starts_with(seeds::CORPUS) {
        for name in ["tool.tbl", "rs274ngc.var"] {
            let s = seeds::file_seed(&format!("{}/{name}", seeds::CORPUS));
            files.push((name.into(), s.bytes));
        }
        let subs = seeds::corpus_subs();
        places.extend(subs.iter().map(|(n, _)| n.clone()));
        files.extend(subs);
        args.extend([
            "--tool-table=tool.tbl",
            "--params=rs274ngc.var",
            "--sub-path=subs",
            "--machine-units=inch",
        ]);
    }
    let places: Vec<&str> = places.iter().map(String::as_str).collect();
    case("verify", &args, files, &places, about)
}

/// An APT CL program (its CUTTER record names the tool).
pub fn cl(seeds: &[Seed], (k, ms, _): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let p = seed.name.as_str();
    let part = if p.starts_with("die") {
        "--part=die"
    } else {
        "--part=wave"
    };
    let cell = if p.starts_with("die") {
        "--cell=2"
    } else {
        "--cell=1"
    };
    let args = [
        "verify",
        part,
        "--program",
        p,
        cell,
        "--max-memory=1024",
        "-o",
        "out",
    ];
    case("verify", &args, vec![(p.to_string(), bytes)], &[p], about)
}

/// A pose CSV program.
pub fn pose_csv(seeds: &[Seed], (k, ms, _): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let p = seed.name.as_str();
    let mut files = vec![(p.to_string(), bytes)];
    let mut args = vec![
        "verify",
        "--program",
        p,
        "--cell=1",
        "--max-memory=1024",
        "-o",
        "out",
    ];
    if p.starts_with("wave") {
        args.extend(["--part=wave", "--tool=ball:d=8"]);
    } else {
        files.push(file("floor.toml", seeds::FLOOR));
        args.extend(["--part=floor.toml", "--tool=ball:d=6"]);
    }
    case("verify", &args, files, &[p], about)
}

/// Whether machine file `name` turns the head (its kinematics need a tool length).
fn turns_head(name: &str) -> bool {
    name.contains("head")
}

/// A machine file: posted to by a five-axis job, and read to verify five-axis G-code.
pub fn machine(seeds: &[Seed], jobs: &[Seed], (k, ms, cmd): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let m = seed.name.as_str();
    let mut files = vec![(m.to_string(), bytes)];
    if cmd % 2 == 0 {
        let base = jobs
            .iter()
            .find(|j| j.name == "die-inclined-3.toml")
            .unwrap();
        let mut text = String::from_utf8_lossy(&base.bytes)
            .replace("\"builtin:xyzac-trunnion\"", &toml_string(m));
        if turns_head(m) {
            text = text.replace("feed_mode =", "tool_length = 150\nfeed_mode =");
        }
        files.push(file("die-5x.toml", &text));
        let args = ["plan", "die-5x.toml", "--out", "out"];
        case("plan", &args, files, &[m, "die-5x.toml"], about)
    } else {
        // The program swarf posted for this machine (die-inclined-3, tool length 150).
        let program = match m {
            "xyzbc-head.toml" => "die-xyzbc-head.ngc",
            "xyzbc-table-head.toml" => "die-xyzbc-table-head.ngc",
            _ => "die-trunnion.ngc",
        };
        let bytes = seeds::file_seed(&format!("{}/{program}", seeds::OWN)).bytes;
        files.push((program.into(), bytes));
        let machine = format!("--machine={m}");
        let mut args = vec![
            "verify",
            "--part=die",
            "--program",
            program,
            &machine,
            "--tool=bull:d=38.1,r=6.35",
            "--cell=2",
            "--max-memory=1024",
            "-o",
            "out",
        ];
        if turns_head(m) {
            args.push("--tool-length=150");
        }
        case("verify", &args, files, &[m, program], about)
    }
}

/// A drop points CSV.
pub fn points(seeds: &[Seed], (k, ms, cmd): &Edit) -> Case {
    let (seed, bytes, about) = mutated(seeds, *k, ms);
    let p = seed.name.as_str();
    let files = vec![
        (p.to_string(), bytes),
        ("mesh.stl".into(), mesh::binary_stl(&mesh::height_field(8))),
    ];
    let mut args = vec![
        "drop",
        "--mesh",
        "mesh.stl",
        "--tool=ball:d=4",
        "--points",
        p,
    ];
    match cmd % 3 {
        0 => {}
        1 => args.extend(["--contact", "-o", "out.csv"]),
        _ => args.push("--threads=1"),
    }
    case("drop", &args, files, &[p], about)
}

/// Corpus programs that read the tool table or the parameter file.
const SETUP_PROGRAMS: &[&str] = &[
    "05-params-tool-position.ngc",
    "07-params-var-file.ngc",
    "32-comp-line-entry.ngc",
    "36-comp-closed-pocket.ngc",
    "46-offsets-g28-g30.ngc",
    "47-tool-length.ngc",
    "55-real-pocket-comp-sub.ngc",
];

/// A LinuxCNC tool table or parameter file, read with a corpus program that uses it.
pub fn nc_setup((k, ms, cmd): &Edit) -> Case {
    let names = ["tool.tbl", "rs274ngc.var"];
    let subject = names[k % 2];
    let program = SETUP_PROGRAMS[cmd % SETUP_PROGRAMS.len()];
    let mut files = Vec::new();
    for name in names {
        let s = seeds::file_seed(&format!("{}/{name}", seeds::CORPUS));
        let bytes = if name == subject {
            apply_all(&s.bytes, ms)
        } else {
            s.bytes
        };
        files.push((name.to_string(), bytes));
    }
    let p = seeds::file_seed(&format!("{}/{program}", seeds::CORPUS));
    files.push((program.to_string(), p.bytes));
    files.push(file("floor.toml", seeds::FLOOR));
    files.extend(seeds::corpus_subs());
    let args = [
        "verify",
        "--part=floor.toml",
        "--program",
        program,
        "--tool=ball:d=6",
        "--cell=1",
        "--tool-table=tool.tbl",
        "--params=rs274ngc.var",
        "--sub-path=subs",
        "--machine-units=inch",
        "--max-memory=1024",
        "-o",
        "out",
    ];
    let about = format!(
        "seed {}/{subject} with {program}; edits {ms:?}",
        seeds::CORPUS
    );
    // An error at the program line that asks for the missing tool is placed too.
    case("verify", &args, files, &[subject, program], about)
}
