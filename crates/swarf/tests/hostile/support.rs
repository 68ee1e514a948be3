//! Running the swarf binary as a user would, under a time and memory limit, and the
//! small inputs the hostile tests share.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Seconds any of these commands may take (a debug build on a loaded CI machine).
pub const LIMIT_S: u64 = 60;

/// Virtual memory limit of each command, KiB (4 GiB: a 16 TB grid or a 120 GB
/// sample buffer would abort or be killed instead of being refused).
pub const MEMORY_KIB: u64 = 4 << 20;

/// Runs swarf with `args` in `dir` under the memory limit; kills it after
/// [`LIMIT_S`]. Returns (success, stdout + stderr, seconds).
pub fn swarf_in(dir: &Path, args: &[&str]) -> (bool, String, f64) {
    let mut cmd = Command::new("sh");
    cmd.arg("-c")
        .arg(format!("ulimit -v {MEMORY_KIB}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let start = Instant::now();
    let mut child = cmd.spawn().expect("swarf runs");
    let (mut out, mut err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out.read_to_string(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > Duration::from_secs(LIMIT_S) {
            let _ = child.kill();
            panic!("swarf {args:?} ran past {LIMIT_S} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let secs = start.elapsed().as_secs_f64();
    let text = reader.join().unwrap() + &err_reader.join().unwrap();
    assert!(
        status.code().is_some(),
        "swarf {args:?} was killed by a signal (abort?): {text}"
    );
    assert!(
        !text.contains("panicked"),
        "swarf {args:?} panicked: {text}"
    );
    (status.success(), text, secs)
}

/// A fresh directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-hostile-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `args` fail, and the message holds every one of `needles`.
pub fn refused(dir: &Path, args: &[&str], needles: &[&str]) {
    let (ok, text, _) = swarf_in(dir, args);
    assert!(!ok, "swarf {args:?} succeeded: {text}");
    for n in needles {
        assert!(text.contains(n), "swarf {args:?}: no {n:?} in: {text}");
    }
    assert!(text.len() < 4000, "a message of {} bytes", text.len());
}

/// `swarf verify --part PART --program PROGRAM --tool TOOL -o v EXTRA...`.
pub fn verify_cmd<'a>(
    part: &'a str,
    program: &'a str,
    tool: &'a str,
    extra: &[&'a str],
) -> Vec<&'a str> {
    let mut args = vec![
        "verify",
        "--part",
        part,
        "--program",
        program,
        "--tool",
        tool,
        "-o",
        "v",
    ];
    args.extend_from_slice(extra);
    args
}

/// A line cut, `line.ngc`.
pub fn line_ngc(dir: &Path) {
    std::fs::write(
        dir.join("line.ngc"),
        "G21 G90\nG0 X0 Y0 Z5\nG1 X10 F100\nM2\n",
    )
    .unwrap();
}

/// The built-in wave tessellated within 0.1 mm, `w.stl`.
pub fn wave_stl(dir: &Path) {
    let (ok, text, _) = swarf_in(dir, &["tessellate", "wave", "--tol", "0.1", "-o", "w.stl"]);
    assert!(ok && dir.join("w.stl").exists(), "{text}");
}

/// A flat 20 x 10 mm plate at z = 0.
pub fn plate(dir: &Path) -> String {
    let path = dir.join("plate.toml");
    std::fs::write(
        &path,
        "name = \"plate\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
         points = [[0, 0, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]]\n",
    )
    .unwrap();
    path.display().to_string()
}

/// A job on the built-in wave part, `strategy` holding the strategy's lines.
pub fn wave_job(dir: &Path, name: &str, tool: &str, strategy: &str) -> String {
    let path = dir.join(name);
    std::fs::write(
        &path,
        format!(
            "part = \"builtin:wave\"\ntool = \"{tool}\"\n[strategy]\n{strategy}\n\
             [feeds]\nfeed = 300\nspindle = 1500\n[output]\ngcode = \"out.ngc\"\n"
        ),
    )
    .unwrap();
    path.display().to_string()
}
