//! The IGES reader against OpenCASCADE: `occ/make_iges.py` builds a rational
//! B-spline face, a plane plate with a circular hole (written as 108 with model-space
//! trimming curves) and the same plate converted to NURBS (128 with parameter-space
//! curves) and a rational surface periodic in u (unclamped knots, which swarf clamps), writes them as IGES 144/142 faces, and records OCC's own sample points
//! inside each face and the face areas. Each sample must lie on the swarf face
//! (projection within 1e-9 mm) and inside its trim; where swarf keeps OCC's
//! parametrisation (the 128 faces) `S(u, v)` must equal OCC's point; the trimmed
//! area (midpoint rule over the face's `(u, v)` box, `|S_u x S_v|` where the face
//! contains the cell centre) must match OCC's within 0.5 %; the hole's trimming
//! loops must stay within `trim_chord` of the exact circle.
//! The same for `solid.igs`, the faces of a box less a cylinder fused with a sphere,
//! converted to NURBS and written in inches (seam edges, poles, unit conversion).
//!
//! Skipped with a note when Python's OCP module is missing, unless
//! `SWARF_REQUIRE_REFERENCES=1`.

use std::path::PathBuf;
use std::process::Command;
use swarf_io::{CadOptions, read_iges};

/// Faces whose IGES surface is OCC's surface (128), so `(u, v)` agree.
const SAME_PARAMETRISATION: [usize; 3] = [0, 2, 3];
/// Deviation allowed for the inch file, mm (OCC prints 10 significant digits).
const INCH_TOL: f64 = 1e-6;
/// Cells per direction of the area's midpoint rule.
const AREA_GRID: usize = 200;

fn occ_available() -> bool {
    let ok = Command::new("python3")
        .args(["-c", "import OCP"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var("SWARF_REQUIRE_REFERENCES").as_deref() != Ok("1"),
            "SWARF_REQUIRE_REFERENCES=1 but python3 cannot import OCP (pip install cadquery-ocp)"
        );
        eprintln!("note: skipping the OpenCASCADE IGES test: python3 cannot import OCP");
    }
    ok
}

/// Rows `(face, u, v, [x, y, z], area)` of the CSV.
fn samples(text: &str) -> Vec<(usize, f64, f64, [f64; 3], f64)> {
    text.lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.parse().expect("number")).collect();
            (f[0] as usize, f[1], f[2], [f[3], f[4], f[5]], f[6])
        })
        .collect()
}

fn area(part: &swarf_geom::Part, k: usize) -> f64 {
    let p = &part.patches[k];
    let [du, dv] = part.trim(k).map_or_else(|| p.domain(), |t| t.uv_box());
    let (hu, hv) = (
        (du[1] - du[0]) / AREA_GRID as f64,
        (dv[1] - dv[0]) / AREA_GRID as f64,
    );
    let mut sum = 0.0;
    for a in 0..AREA_GRID {
        for b in 0..AREA_GRID {
            let (u, v) = (du[0] + (a as f64 + 0.5) * hu, dv[0] + (b as f64 + 0.5) * hv);
            if part.face_contains(k, u, v) {
                let d = p.derivs(u, v);
                sum += d.du.cross(&d.dv).norm() * hu * hv;
            }
        }
    }
    sum
}

/// Largest distance from the hole's circle (centre (125, 18, 5), radius 9) of the
/// surface points at the hole loops' vertices and edge midpoints, faces 1 and 2.
fn hole_deviation(part: &swarf_geom::Part) -> f64 {
    let c = swarf_geom::Point3::new(125.0, 18.0, 5.0);
    let mut worst = 0.0f64;
    for k in [1, 2] {
        let hole = &part.trim(k).expect("trimmed").loops()[1];
        for (a, b) in hole.iter().zip(hole.iter().cycle().skip(1)) {
            for t in [0.0, 0.5] {
                let (u, v) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
                let p = part.patches[k].eval(u, v);
                worst = worst.max(((p - c).norm() - 9.0).abs());
            }
        }
    }
    worst
}

/// Largest projection and evaluation deviations, mm, after checking every sample
/// of `csv` against `part` within `tol` mm and every face area within 0.5 %.
fn check(part: &swarf_geom::Part, csv: &str, same: &dyn Fn(usize) -> bool, tol: f64) -> (f64, f64) {
    let rows = samples(csv);
    let faces = rows.last().expect("samples").0 + 1;
    assert_eq!(part.patches.len(), faces);
    let (mut max_proj, mut max_eval) = (0.0f64, 0.0f64);
    for &(k, u, v, x, _) in &rows {
        let q = swarf_geom::Point3::new(x[0], x[1], x[2]);
        let pr = part.patches[k].project(&q);
        max_proj = max_proj.max(pr.distance);
        assert!(
            pr.distance < tol,
            "face {k}: OCC point {q:?} is {:e} mm off",
            pr.distance
        );
        let (cu, cv) = if same(k) { (u, v) } else { (pr.u, pr.v) };
        assert!(
            part.face_contains(k, cu, cv),
            "face {k}: OCC point {q:?} outside the trim"
        );
        if same(k) {
            let d = (part.patches[k].eval(u, v) - q).norm();
            max_eval = max_eval.max(d);
            assert!(
                d < tol,
                "face {k}: S({u}, {v}) is {d:e} mm from OCC's point"
            );
        }
    }
    for k in 0..faces {
        let occ = rows
            .iter()
            .find(|r| r.0 == k)
            .expect("samples on every face")
            .4;
        let ours = area(part, k);
        eprintln!("face {k}: area {ours:.4} mm^2, OCC {occ:.4} mm^2");
        assert!(
            (ours - occ).abs() < 5e-3 * occ,
            "face {k}: area {ours} vs OCC {occ}"
        );
    }
    eprintln!(
        "{} points: max projection {max_proj:.1e} mm, max eval {max_eval:.1e} mm",
        rows.len()
    );
    (max_proj, max_eval)
}

#[test]
fn occ_faces_match() {
    if !occ_available() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("swarf-iges-occ-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/occ/make_iges.py");
    let out = Command::new("python3")
        .arg(&script)
        .arg(&dir)
        .output()
        .expect("run python3");
    assert!(
        out.status.success(),
        "make_iges.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |name: &str| {
        let cad = read_iges(&dir.join(format!("{name}.igs")), &CadOptions::default())
            .expect("read OCC's IGES");
        let csv = std::fs::read_to_string(dir.join(format!("{name}.csv"))).expect("csv");
        assert!(cad.warnings.is_empty(), "{:?}", cad.warnings);
        (cad, csv)
    };
    let (faces, faces_csv) = read("occ");
    let (solid, solid_csv) = read("solid");
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(faces.unit, "mm");
    assert_eq!(solid.unit, "inch");
    assert_eq!(
        faces.part.faces[1].surface.as_deref(),
        Some("DE 7 type 108 (plane)")
    );
    check(
        &faces.part,
        &faces_csv,
        &|k| SAME_PARAMETRISATION.contains(&k),
        1e-9,
    );
    let dev = hole_deviation(&faces.part);
    assert!(
        dev <= CadOptions::default().trim_chord * (1.0 + 1e-6),
        "hole deviation {dev:e} mm"
    );
    eprintln!("hole loops within {dev:.1e} mm of the circle");
    // inch coordinates printed to 10 digits: about 1e-8 mm of rounding; OCC's writer
    // reparametrises some of these faces, so (u, v) are not compared
    check(&solid.part, &solid_csv, &|_| false, INCH_TOL);
}
