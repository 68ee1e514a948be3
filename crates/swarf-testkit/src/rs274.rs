//! LinuxCNC's standalone interpreter `rs274 -g`, found on `PATH`, as an independent
//! reference for G-code: it prints the canonical machining calls a program makes
//! (`STRAIGHT_TRAVERSE`, `STRAIGHT_FEED`, `ARC_FEED`, ...), one numbered line each.

use crate::references::skip_reference;
use std::process::Command;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Concurrent runs interfere (rs274 keeps state outside the process): one at a time.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());
/// Distinguishes the program files of one test process.
static RUNS: AtomicUsize = AtomicUsize::new(0);

/// What `rs274 -g` made of a program.
#[derive(Debug, Clone)]
pub struct Rs274 {
    /// True when it exited with success.
    pub success: bool,
    /// Its standard output: the canonical calls.
    pub stdout: String,
    /// Its standard error: complaints.
    pub stderr: String,
}

impl Rs274 {
    /// Standard output and error, joined by `separator`.
    pub fn text(&self, separator: &str) -> String {
        format!("{}{separator}{}", self.stdout, self.stderr)
    }

    /// The canonical output of a program it accepted without complaint.
    ///
    /// # Panics
    /// When it failed, or any non-empty line of its output is not a numbered canonical
    /// call (`<n> N..... CALL(...)`): the test fails, naming `name`.
    pub fn clean(self, name: &str) -> String {
        assert!(self.success, "{name}: rs274 failed:\n{}", self.stdout);
        for line in self.stdout.lines().filter(|l| !l.trim().is_empty()) {
            let t = line.trim_start();
            let numbered = t
                .split(' ')
                .next()
                .is_some_and(|n| n.parse::<u32>().is_ok());
            assert!(
                numbered && t.contains("N..... "),
                "{name}: rs274 complained: {line}"
            );
        }
        self.stdout
    }
}

/// Runs `rs274 -g` on `program` (written to a temporary file named after `name`);
/// `None`, after [`skip_reference`], when rs274 cannot be run.
pub fn run_rs274(program: &str, name: &str) -> Option<Rs274> {
    let _guard = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // A folder of this process's own, its HOME too: rs274 keeps its parameter file
    // there, and test processes run side by side.
    let dir = std::env::temp_dir().join(format!("swarf-rs274-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("the temporary folder is created");
    let run = RUNS.fetch_add(1, Ordering::Relaxed);
    let path = dir.join(format!("swarf-{name}-{}-{run}.ngc", std::process::id()));
    std::fs::write(&path, program).expect("the temporary program is written");
    let out = Command::new("rs274")
        .arg("-g")
        .arg(&path)
        .current_dir(&dir)
        .env("HOME", &dir)
        .output();
    let _ = std::fs::remove_file(&path);
    match out {
        Ok(out) => Some(Rs274 {
            success: out.status.success(),
            stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        }),
        Err(e) => {
            skip_reference("rs274", &e.to_string());
            None
        }
    }
}

/// The precise shim (`rs274/precise.c`, 10 decimals instead of 4), built once per
/// test process with `gcc`; `None` when it cannot be built.
fn precise_shim() -> Option<std::path::PathBuf> {
    static SHIM: std::sync::OnceLock<Option<std::path::PathBuf>> = std::sync::OnceLock::new();
    SHIM.get_or_init(|| {
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("rs274/precise.c");
        let out = std::env::temp_dir().join(format!("swarf-precise-{}.so", std::process::id()));
        let ok = Command::new("gcc")
            .args(["-shared", "-fPIC", "-O2", "-o"])
            .arg(&out)
            .arg(&src)
            .status()
            .is_ok_and(|s| s.success());
        ok.then_some(out)
    })
    .clone()
}

/// Runs `rs274 -g -t TOOL_TABLE PROGRAM` with full precision (the shim) in `dir`,
/// which is also its `HOME` (rs274 keeps its tool table there) and where it finds
/// subroutine files; returns its output as a corpus recording (stdout, `--- stderr`
/// and stderr, `--- exit N`). `None`, after [`skip_reference`], when rs274 or the
/// shim cannot be used.
pub fn run_rs274_precise(dir: &std::path::Path, program: &str, tool_table: &str) -> Option<String> {
    let Some(shim) = precise_shim() else {
        skip_reference("rs274", "the precise shim could not be built with gcc");
        return None;
    };
    let _guard = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let out = Command::new("timeout")
        .args(["30", "rs274", "-g", "-t", tool_table, program])
        .current_dir(dir)
        .env("HOME", dir)
        .env("LC_ALL", "C")
        .env("LD_PRELOAD", &shim)
        .env_remove("INI_FILE_NAME")
        .stdin(std::process::Stdio::null())
        .output();
    match out {
        Ok(out) if out.status.code() == Some(127) => {
            skip_reference("rs274", "not on PATH");
            None
        }
        Ok(out) => Some(format!(
            "{}\n--- stderr\n{}\n--- exit {}\n",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
            out.status.code().unwrap_or(-1)
        )),
        Err(e) => {
            skip_reference("rs274", &e.to_string());
            None
        }
    }
}

/// The tool length offset in force after each tool change of an `rs274` output (the
/// tool of the last `SELECT_TOOL(n)` at each `CHANGE_TOOL`, which names a table slot,
/// then the Z of the next `USE_TOOL_LENGTH_OFFSET(x y z, ...)`), in order: `(n, None)`
/// for a change that is followed by another change, or by the end, before any offset.
pub fn length_after_changes(output: &str) -> Vec<(u32, Option<f64>)> {
    let args = |line: &str, call: &str| -> Option<String> {
        let (_, rest) = line.split_once(call)?;
        Some(rest.split(')').next().unwrap_or("").to_string())
    };
    let mut selected = u32::MAX;
    let mut out: Vec<(u32, Option<f64>)> = Vec::new();
    for line in output.lines() {
        if let Some(a) = args(line, "SELECT_TOOL(") {
            selected = a.trim().parse().unwrap_or(u32::MAX);
        } else if args(line, "CHANGE_TOOL(").is_some() {
            out.push((selected, None));
        } else if let Some(a) = args(line, "USE_TOOL_LENGTH_OFFSET(")
            && let Some((_, z)) = out.last_mut().filter(|(_, z)| z.is_none())
        {
            *z = a
                .split([' ', ','])
                .filter(|w| !w.is_empty())
                .nth(2)
                .and_then(|w| w.parse().ok());
        }
    }
    out
}
