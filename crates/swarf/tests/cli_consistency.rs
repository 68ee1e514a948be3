//! The command line agrees with itself and with the code: every command that writes
//! takes `-o/--out`, the help texts list the built-in parts and the formats the code
//! reads, each command's help carries only its own notes, and `--version` names the
//! commit.

use std::path::Path;
use std::process::{Command, Output};
use swarf_io::ModelFormat;

/// Runs `swarf ARGS`.
fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

/// The `--help` text of `command`, its whitespace collapsed to single spaces.
fn help(command: &str) -> String {
    let out = swarf(&[command, "--help"]);
    assert!(out.status.success(), "swarf {command} --help failed");
    let text = String::from_utf8(out.stdout).unwrap();
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The names a help text lists as built-in parts: `built-in part (a, b, c; ...)`.
fn listed_builtins(text: &str) -> Vec<String> {
    let start = text
        .find("built-in part (")
        .unwrap_or_else(|| panic!("no built-in part list in: {text}"))
        + "built-in part (".len();
    let rest = &text[start..];
    let end = rest.find([';', ')']).unwrap();
    rest[..end].split(", ").map(str::to_string).collect()
}

/// The commands that write files.
const WRITERS: [&str; 10] = [
    "plan",
    "verify",
    "view",
    "rest",
    "classify",
    "compare",
    "drop",
    "tessellate",
    "demo",
    "batch",
];

#[test]
fn every_command_that_writes_takes_dash_o_and_dash_dash_out() {
    for command in WRITERS {
        let text = help(command);
        assert!(
            text.contains("-o, --out <"),
            "swarf {command} --help: no -o, --out: {text}"
        );
    }
    // The older long form still reads.
    for command in ["drop", "tessellate"] {
        assert!(help(command).contains("[alias: --output]"), "{command}");
    }
}

#[test]
fn plan_writes_a_shipped_job_into_the_folder_dash_o_names() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let job = root.join("jobs/wave-iso-planar.toml");
    let out = std::env::temp_dir().join(format!("swarf-cli-plan-o-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = swarf(&["plan", job.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(
        run.status.success(),
        "swarf plan -o failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    for file in ["wave-iso-planar.ngc", "wave-iso-planar.json"] {
        assert!(out.join(file).is_file(), "{file} not written in {out:?}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn help_texts_list_the_built_in_parts_of_the_code() {
    let all: Vec<String> = swarf_app::model::builtin_names()
        .into_iter()
        .map(str::to_string)
        .collect();
    let patches: Vec<String> = swarf_app::model::builtin_part_names()
        .into_iter()
        .map(str::to_string)
        .collect();
    assert_eq!(all.len(), 12, "the built-in parts: {all:?}");
    for command in ["inspect", "verify", "view", "rest", "classify"] {
        assert_eq!(
            listed_builtins(&help(command)),
            all,
            "swarf {command} --help"
        );
    }
    for command in ["eval", "tessellate", "dsm"] {
        assert_eq!(
            listed_builtins(&help(command)),
            patches,
            "swarf {command} --help"
        );
    }
}

#[test]
fn part_arguments_name_every_format_the_code_reads() {
    for command in ["inspect", "verify", "view"] {
        let text = help(command);
        for format in ModelFormat::ALL {
            let exts: Vec<String> = format
                .extensions()
                .iter()
                .map(|e| format!(".{e}"))
                .collect();
            let named = format!("{} ({})", format.name(), exts.join(", "));
            assert!(
                text.contains(&named),
                "swarf {command} --help lacks {named}"
            );
        }
    }
    assert!(!help("eval").contains("STL (.stl)"), "eval reads no mesh");
}

#[test]
fn each_command_carries_only_its_own_notes() {
    for command in ["verify", "view", "compare"] {
        let text = help(command);
        for other in ["verify", "compare", "view"] {
            for note in [format!("({other}:"), format!("; {other}:")] {
                assert!(!text.contains(&note), "swarf {command} --help says {note}");
            }
        }
    }
    let view = help("view");
    assert!(
        !view.contains("--partial"),
        "view refuses --partial: {view}"
    );
    assert!(view.contains("the job's tolerance with --job"));
    assert!(help("compare").contains("(default: each job's tolerance)"));
    let plan = swarf(&["--help"]);
    let top = String::from_utf8(plan.stdout).unwrap();
    assert!(top.contains("Plan a job (finishing, roughing"), "{top}");
}

#[test]
fn version_names_the_commit_or_says_unknown() {
    let out = swarf(&["--version"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let commit = text
        .trim()
        .strip_prefix(&format!("swarf {} (commit ", env!("CARGO_PKG_VERSION")))
        .and_then(|r| r.strip_suffix(')'))
        .unwrap_or_else(|| panic!("unexpected --version: {text}"));
    assert!(
        commit == "unknown" || (commit.len() >= 7 && commit.chars().all(|c| c.is_ascii_hexdigit())),
        "{commit}"
    );
}
