//! Waterline loops against OpenCAMLib 2023.1.11's `Waterline` and
//! `AdaptiveWaterline`, recorded by `tools/ocl/record_waterline.py` at 0.1 mm
//! sampling on the small tessellations of the shared parts (the drop-cutter
//! references' meshes). For each case:
//!
//! - every swarf loop point lies on the true contour: OpenCAMLib's own drop height
//!   there (run live, `tools/ocl/drop_at.py`) equals the level within 1e-6 mm, or,
//!   where the drop height jumps (the cutter leaving the mesh's edge), it is at least
//!   the level 1e-6 mm inside the loop and at most the level (or no contact) 1e-6 mm
//!   outside;
//! - the two contours are within OpenCAMLib's sampling of each other (Hausdorff
//!   distance, both ways, point to polyline);
//! - swarf finds no fewer loops.

use std::path::{Path, PathBuf};
use swarf_path::Finish;
use swarf_path::strategy::waterline::{Milling, Waterline, WaterlineParams};
use swarf_testkit::ocl::ocl_drop;

struct Reference {
    name: String,
    mesh: String,
    spec: String,
    z: f64,
    sampling: f64,
    loops: Vec<Vec<[f64; 2]>>,
}

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ocl")
}

fn mesh_path(mesh: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../swarf-tool/tests/data/ocl")
        .join(format!("{mesh}.stl"))
}

fn read(path: &Path) -> Reference {
    let text = std::fs::read_to_string(path).unwrap();
    let name = path.file_stem().unwrap().to_string_lossy().to_string();
    let header = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(&format!("# {key}: ")))
            .unwrap_or_else(|| panic!("{name}: no {key}"))
            .trim()
            .to_string()
    };
    let mut loops: Vec<Vec<[f64; 2]>> = Vec::new();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("loop"))
    {
        let f: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let k = f[0] as usize;
        if loops.len() <= k {
            loops.resize(k + 1, Vec::new());
        }
        loops[k].push([f[1], f[2]]);
    }
    Reference {
        mesh: name.split("__").nth(1).unwrap().to_string(),
        spec: header("spec"),
        z: header("z").parse().unwrap(),
        sampling: header("sampling").parse().unwrap(),
        loops,
        name,
    }
}

/// Distance from `p` to the closed polylines `loops`.
fn distance(p: [f64; 2], loops: &[Vec<[f64; 2]>]) -> f64 {
    let mut best = f64::INFINITY;
    for lp in loops {
        for k in 0..lp.len() {
            let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let l2 = d[0] * d[0] + d[1] * d[1];
            let t = if l2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            best = best.min((p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1]));
        }
    }
    best
}

#[test]
fn loops_match_opencamlib_waterline() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(data())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    files.sort();
    assert!(files.len() >= 14, "references missing: {files:?}");
    for path in files {
        let r = read(&path);
        let mesh = swarf_io::stl::read_stl(&mesh_path(&r.mesh)).unwrap();
        let params = WaterlineParams {
            finish: Finish {
                tolerance: 0.01,
                ..Finish::default()
            },
            ..WaterlineParams::new(0.05)
        };
        let wl = Waterline::new(&mesh, &r.spec.parse().unwrap(), &params).unwrap();
        let level = wl.level(r.z, Milling::Climb);
        let ours: Vec<Vec<[f64; 2]>> = level
            .loops
            .iter()
            .map(|lp| lp.iter().map(|p| [p.pose.cl.x, p.pose.cl.y]).collect())
            .collect();
        assert!(
            ours.len() >= r.loops.len(),
            "{}: {} loops, OpenCAMLib {}",
            r.name,
            ours.len(),
            r.loops.len()
        );
        let theirs_to_ours = r.loops.iter().flatten().map(|&p| distance(p, &ours));
        let ours_to_theirs = ours.iter().flatten().map(|&p| distance(p, &r.loops));
        let h = theirs_to_ours.chain(ours_to_theirs).fold(0.0, f64::max);
        assert!(h <= r.sampling, "{}: Hausdorff distance {h}", r.name);
        // Each point, and the points 1e-6 mm to either side across the loop (the
        // inside is on the right of travel).
        let mut probes: Vec<[f64; 2]> = Vec::new();
        for lp in &ours {
            let n = lp.len();
            for k in 0..n {
                let (a, b) = (lp[(k + n - 1) % n], lp[(k + 1) % n]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let l = dx.hypot(dy).max(1e-300);
                let right = [dy / l * 1e-6, -dx / l * 1e-6];
                let p = lp[k];
                probes.push(p);
                probes.push([p[0] + right[0], p[1] + right[1]]);
                probes.push([p[0] - right[0], p[1] - right[1]]);
            }
        }
        let Some(heights) = ocl_drop(&mesh_path(&r.mesh), &r.spec, &probes) else {
            continue;
        };
        let mut exact = 0;
        let mut worst = 0.0f64;
        for (k, h) in heights.chunks(3).enumerate() {
            let at = h[0].map_or(f64::INFINITY, |z| (z - r.z).abs());
            if at <= 1e-6 {
                exact += 1;
                continue;
            }
            // A jump of the drop height (a cliff, the mesh's edge): the contour lies
            // between the inside and outside neighbours.
            let inside = h[1].is_some_and(|z| z >= r.z - 1e-6);
            let outside = h[2].is_none_or(|z| z <= r.z + 1e-6);
            assert!(
                inside && outside,
                "{}: point {k} is not on the contour (OpenCAMLib heights {h:?}, level {})",
                r.name,
                r.z
            );
            worst = worst.max(at);
        }
        eprintln!(
            "{}: {} loops (OpenCAMLib {}), Hausdorff {h:.4} mm, {exact} of {} points at \
             the level within 1e-6 mm, the others at a jump of the drop height",
            r.name,
            ours.len(),
            r.loops.len(),
            heights.len() / 3
        );
    }
}
