//! OpenCAMLib (`pip install opencamlib`, 2023.1.11) as a live reference, through the
//! scripts in `tools/ocl`: drop heights at arbitrary points.

use crate::references::skip_reference;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn script(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tools/ocl")
        .join(name)
}

/// OpenCAMLib's `BatchDropCutter` tip heights of `spec` (a swarf tool spec) over the
/// STL at `stl`, one per point (`None`: no contact); `None` when OpenCAMLib cannot
/// be run (then the check is skipped, or fails under `SWARF_REQUIRE_REFERENCES=1`).
///
/// # Panics
/// When the script runs but fails or prints something else than one height per
/// point.
pub fn ocl_drop(stl: &Path, spec: &str, points: &[[f64; 2]]) -> Option<Vec<Option<f64>>> {
    let child = Command::new("python3")
        .arg(script("drop_at.py"))
        .args(["--stl".as_ref(), stl.as_os_str()])
        .args(["--spec", spec])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn();
    let mut child = match child {
        Ok(c) => c,
        Err(e) => {
            skip_reference("OpenCAMLib (python3)", &e.to_string());
            return None;
        }
    };
    let input: String = points
        .iter()
        .map(|p| format!("{:.17},{:.17}\n", p[0], p[1]))
        .collect();
    if let Some(mut stdin) = child.stdin.take() {
        stdin
            .write_all(input.as_bytes())
            .expect("write points to drop_at.py");
    }
    let out = child.wait_with_output().expect("run drop_at.py");
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        if stderr.contains("No module named 'opencamlib'") {
            skip_reference("OpenCAMLib", "python3 cannot import opencamlib");
            return None;
        }
        panic!("drop_at.py failed: {stderr}");
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let heights: Vec<Option<f64>> = text
        .lines()
        .map(|l| (!l.trim().is_empty()).then(|| l.trim().parse().expect("a height")))
        .collect();
    assert_eq!(
        heights.len(),
        points.len(),
        "drop_at.py: one height per point"
    );
    Some(heights)
}
