//! Running one case: the built `swarf` binary as a subprocess in a fresh folder, as a
//! user would run it, under a memory cap (`ulimit -v`, through `sh`) and a wall-clock
//! limit (the child is killed when it runs past it).

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// One run of swarf: its command line, the input files it reads and what may name
/// the place of an error.
#[derive(Debug, Clone)]
pub struct Case {
    /// The subcommand, for grouping failures.
    pub command: &'static str,
    /// The arguments after `swarf`; files are named relative to the case folder.
    pub args: Vec<String>,
    /// Files written into the case folder before the run: relative path, content.
    pub files: Vec<(String, Vec<u8>)>,
    /// Words one of which a failing run's stderr must contain: the mutated file's
    /// name, the option's name.
    pub places: Vec<String>,
    /// The seed and the edits that made this case.
    pub about: String,
}

impl Case {
    /// The total size of the input files and arguments, bytes (smaller reproduces
    /// better).
    pub fn size(&self) -> usize {
        self.files.iter().map(|(_, b)| b.len()).sum::<usize>()
            + self.args.iter().map(String::len).sum::<usize>()
    }
}

/// How long and how much memory a run may take.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Wall-clock limit.
    pub timeout: Duration,
    /// Address-space limit (`ulimit -v`), KiB.
    pub memory_kib: u64,
}

/// What a run did.
#[derive(Debug)]
pub struct Outcome {
    /// The exit status; `None` when the run was killed at the time limit.
    pub status: Option<ExitStatus>,
    /// Wall-clock time of the run.
    pub elapsed: Duration,
    /// Standard output (its first [`CAPTURE`] bytes).
    pub stdout: Vec<u8>,
    /// Standard error (its first [`CAPTURE`] bytes).
    pub stderr: Vec<u8>,
    /// Files the run wrote into the case folder: relative path, content (the first
    /// [`CAPTURE`] bytes).
    pub outputs: Vec<(String, Vec<u8>)>,
}

/// Most bytes kept of any stream or output file.
pub const CAPTURE: usize = 64 << 20;

/// The shell line that applies the limits and runs `swarf` with `"$@"`.
fn limit_script(limits: &Limits) -> String {
    format!(
        "ulimit -v {}; ulimit -c 0; exec \"$0\" \"$@\"",
        limits.memory_kib
    )
}

/// The command line that reproduces `case` from a shell in its folder.
pub fn reproducer(case: &Case, dir: &Path, limits: &Limits) -> String {
    let mut line = format!(
        "cd {} && (ulimit -v {} && timeout {} {}",
        quote(&dir.display().to_string()),
        limits.memory_kib,
        limits.timeout.as_secs(),
        quote(env!("CARGO_BIN_EXE_swarf"))
    );
    for a in &case.args {
        line.push(' ');
        if a.len() > 300 {
            line += &format!(
                "{}...[{} bytes: the full line is in cmd.sh]",
                quote(&a.chars().take(120).collect::<String>()),
                a.len()
            );
        } else {
            line += &quote(a);
        }
    }
    line + ")"
}

/// `s` quoted for a POSIX shell when it needs it.
pub fn quote(s: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "-_./:=,+@%".contains(c);
    if !s.is_empty() && s.chars().all(plain) {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// Writes the case's files into `dir` (made afresh), runs swarf there under the
/// limits and collects what it wrote.
pub fn run(case: &Case, dir: &Path, limits: &Limits) -> Outcome {
    if dir.exists() {
        std::fs::remove_dir_all(dir).expect("the old case folder can be removed");
    }
    std::fs::create_dir_all(dir).expect("the case folder can be made");
    for (name, bytes) in &case.files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, bytes).expect("an input file can be written");
    }
    let script = format!("#!/bin/sh\n{}\n", reproducer_full(case, dir, limits));
    std::fs::write(dir.join("cmd.sh"), script).unwrap();
    let start = Instant::now();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(limit_script(limits))
        .arg(env!("CARGO_BIN_EXE_swarf"))
        .args(&case.args)
        .current_dir(dir)
        .env("MALLOC_ARENA_MAX", "2")
        .env("RUST_BACKTRACE", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sh runs");
    let out = capture(child.stdout.take().unwrap());
    let err = capture(child.stderr.take().unwrap());
    let status = loop {
        if let Some(s) = child.try_wait().expect("the child can be waited for") {
            break Some(s);
        }
        if start.elapsed() > limits.timeout {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let elapsed = start.elapsed();
    let inputs: Vec<&str> = case.files.iter().map(|(n, _)| n.as_str()).collect();
    let mut outputs = Vec::new();
    collect(dir, dir, &inputs, &mut outputs);
    Outcome {
        status,
        elapsed,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
        outputs,
    }
}

/// The full command line, long arguments included (for `cmd.sh`).
fn reproducer_full(case: &Case, dir: &Path, limits: &Limits) -> String {
    let mut line = format!(
        "cd {} && ulimit -v {} && exec timeout {} {}",
        quote(&dir.display().to_string()),
        limits.memory_kib,
        limits.timeout.as_secs(),
        quote(env!("CARGO_BIN_EXE_swarf"))
    );
    for a in &case.args {
        line.push(' ');
        line += &quote(a);
    }
    line
}

/// Reads a stream to its end on a thread, keeping its first [`CAPTURE`] bytes.
fn capture(mut r: impl Read + Send + 'static) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut kept = Vec::new();
        let mut buf = vec![0u8; 1 << 16];
        while let Ok(n) = r.read(&mut buf) {
            if n == 0 {
                break;
            }
            let room = CAPTURE.saturating_sub(kept.len()).min(n);
            kept.extend_from_slice(&buf[..room]);
        }
        kept
    })
}

/// Every file under `dir` that is not an input or `cmd.sh`, relative to `root`.
fn collect(root: &Path, dir: &Path, inputs: &[&str], out: &mut Vec<(String, Vec<u8>)>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for path in paths {
        let rel = path
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .into_owned();
        if path.is_dir() {
            collect(root, &path, inputs, out);
        } else if rel != "cmd.sh" && !inputs.contains(&rel.as_str()) {
            let mut bytes = Vec::new();
            if let Ok(f) = std::fs::File::open(&path) {
                let _ = f.take(CAPTURE as u64).read_to_end(&mut bytes);
            }
            out.push((rel, bytes));
        }
    }
}
