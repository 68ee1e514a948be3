//! `swarf inspect` on hostile input (issue 15): degenerate parts and meshes are refused
//! with an error that names the file (and the patch), and whatever is accepted is
//! reported with finite numbers only.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-hostile-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `swarf inspect FILE` (text and JSON) fails, and its message holds every one of `wants`.
fn refused(file: &Path, wants: &[&str]) {
    for json in [false, true] {
        let mut args = vec!["inspect", file.to_str().unwrap()];
        if json {
            args.push("--json");
        }
        let o = swarf(&args);
        let out = String::from_utf8_lossy(&o.stdout);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} should fail, printed:\n{out}");
        for want in wants {
            assert!(err.contains(want), "{args:?}: {want:?} not in {err}");
        }
    }
}

/// A part file with a good bilinear patch and then `second` as the points of a
/// second bilinear patch.
fn two_patches(second: &str) -> String {
    format!(
        "name = \"t\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
         points = [[0,0,0],[0,1,0],[1,0,0],[1,1,1]]\n\
         [[patch]]\ndegree = [1, 1]\npoints = {second}\n"
    )
}

#[test]
fn an_obj_without_faces_is_refused() {
    let dir = temp_dir("noface");
    let obj = dir.join("vertices-only.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    refused(&obj, &["vertices-only.obj", "no triangle"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_patch_below_the_smallest_size_is_refused() {
    let dir = temp_dir("tiny");
    let part = dir.join("tiny.toml");
    std::fs::write(
        &part,
        two_patches("[[0,0,0],[1e-200,0,0],[0,1e-200,0],[1e-200,1e-200,0]]"),
    )
    .unwrap();
    refused(
        &part,
        &["tiny.toml", "line 8", "patch[1].points", "1e-6 mm"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_patch_with_no_tangent_plane_is_refused() {
    let dir = temp_dir("line");
    let part = dir.join("line.toml");
    std::fs::write(&part, two_patches("[[0,0,0],[1,0,0],[2,0,0],[3,0,0]]")).unwrap();
    refused(&part, &["line.toml", "patch 1", "normal"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every number in `text`: no `inf` or `NaN` spelled out (text) and every JSON
/// number finite (a non-finite f64 becomes JSON `null`).
fn all_finite(text: &str) -> bool {
    let lower = text.to_ascii_lowercase();
    !lower.contains("inf") && !lower.contains("nan") && !lower.contains("null")
}

#[test]
fn accepted_input_is_reported_with_finite_numbers() {
    let dir = temp_dir("finite");
    let stl = dir.join("half.stl");
    let facet = |v: [&str; 3]| {
        format!(
            "facet normal 0 0 1\nouter loop\nvertex {}\nvertex {}\nvertex {}\n\
             endloop\nendfacet\n",
            v[0], v[1], v[2]
        )
    };
    let good = facet(["0 0 0", "1 0 0", "0 1 0"]);
    let bad = facet(["inf 0 0", "1 0 0", "0 1 0"]);
    std::fs::write(&stl, format!("solid h\n{bad}{good}endsolid h\n")).unwrap();
    // No triangle has a finite corner: nothing to bound.
    let all_bad = dir.join("all-bad.stl");
    let bad = facet(["nan 0 0", "0 inf 0", "0 0 -inf"]);
    std::fs::write(&all_bad, format!("solid h\n{bad}{bad}endsolid h\n")).unwrap();
    let part = dir.join("small.toml");
    std::fs::write(
        &part,
        two_patches("[[0,0,0],[1e-6,0,0],[0,1e-6,0],[1e-6,1e-6,1e-6]]"),
    )
    .unwrap();
    for file in [&stl, &part] {
        for json in [false, true] {
            let mut args = vec!["inspect", file.to_str().unwrap()];
            if json {
                args.push("--json");
            }
            let o = swarf(&args);
            let out = String::from_utf8_lossy(&o.stdout);
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(o.status.success(), "{args:?}: {err}");
            assert!(all_finite(&out), "{args:?}:\n{out}");
        }
    }
    refused(&all_bad, &["all-bad.stl", "finite"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
