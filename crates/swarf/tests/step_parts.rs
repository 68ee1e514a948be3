//! STEP parts end to end, against OpenCASCADE (`cadquery-ocp`) and OpenCAMLib:
//! the reference parts of `swarf-io/tests/occ/make_step.py` read by swarf have OCC's
//! face areas to 1e-6 (relative), tessellate without open edges, and a raster job on
//! a multi-face part neither gouges nor leaves excess against OpenCAMLib's drop
//! cutter on OCC's own mesh of the part; an iso-scallop job on one trimmed face stays
//! on it. Skipped with a note when a reference is missing, unless
//! `SWARF_REQUIRE_REFERENCES=1`.

use std::path::{Path, PathBuf};
use std::process::Command;
use swarf_testkit::ocl::ocl_drop;
use swarf_testkit::references::skip_reference;

fn here() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// OCC's reference parts in a fresh folder, or `None` when OCP is missing.
fn occ_parts(name: &str) -> Option<PathBuf> {
    let dir = std::env::temp_dir().join(format!("swarf-step-parts-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = Command::new("python3")
        .arg(here().join("../swarf-io/tests/occ/make_step.py"))
        .arg(&dir)
        .arg(here().join("../../parts/wave.toml"))
        .output();
    match out {
        Ok(o) if o.status.success() => Some(dir),
        Ok(o) => {
            skip_reference(
                "OpenCASCADE (cadquery-ocp)",
                &String::from_utf8_lossy(&o.stderr),
            );
            None
        }
        Err(e) => {
            skip_reference("python3", &e.to_string());
            None
        }
    }
}

/// OCC's face areas of `step` (exact trimmed faces) and its mesh at `deflection`,
/// written to `stl`.
fn occ_read(step: &Path, stl: &Path, deflection: f64) -> Vec<f64> {
    let out = Command::new("python3")
        .arg(here().join("../../tools/occ/read_step.py"))
        .arg(step)
        .arg(stl)
        .arg(deflection.to_string())
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.strip_prefix("area,"))
        .map(|a| a.parse().unwrap())
        .collect()
}

fn read(step: &Path, trim_chord: f64) -> swarf_geom::Part {
    let opts = swarf_io::CadOptions {
        trim_chord,
        ..swarf_io::CadOptions::default()
    };
    let cad = swarf_io::read_step(step, &opts).unwrap();
    assert!(cad.warnings.is_empty(), "{:?}", cad.warnings);
    cad.part
}

/// Edges used by one triangle only, after welding vertices closer than `weld` mm.
fn open_edges(mesh: &swarf_geom::TriMesh, weld: f64) -> usize {
    let key = |p: &swarf_geom::Point3| [p.x, p.y, p.z].map(|c| (c / weld).round() as i64);
    let mut ids = std::collections::HashMap::new();
    let id: Vec<usize> = mesh
        .vertices
        .iter()
        .map(|p| {
            let n = ids.len();
            *ids.entry(key(p)).or_insert(n)
        })
        .collect();
    let mut edges = std::collections::HashMap::new();
    for t in &mesh.triangles {
        let v = t.map(|i| id[i as usize]);
        for (a, b) in [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])] {
            if a != b {
                *edges.entry((a.min(b), a.max(b))).or_insert(0usize) += 1;
            }
        }
    }
    edges.values().filter(|&&c| c == 1).count()
}

#[test]
fn faces_have_occs_areas_and_meshes_close() {
    let Some(dir) = occ_parts("areas") else {
        return;
    };
    for name in ["plate_hole", "fillet", "cylinder", "torus"] {
        let step = dir.join(format!("{name}.step"));
        let mut want = occ_read(&step, &dir.join(format!("{name}.occ.stl")), 0.01);
        let part = read(&step, 1e-6);
        let mut got: Vec<f64> = (0..part.patches.len())
            .map(|k| part.patches[k].area(part.trim(k)))
            .collect();
        assert_eq!(got.len(), want.len(), "{name}: face count");
        got.sort_by(f64::total_cmp);
        want.sort_by(f64::total_cmp);
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-6 * w, "{name}: area {g} vs OCC {w}");
        }
        // Closed solids: every edge of the mesh is shared by two faces' triangles.
        let mesh = read(&step, 1e-4).tessellate(0.01).unwrap();
        assert_eq!(open_edges(&mesh, 1e-6), 0, "{name}: open edges");
    }
}

#[test]
fn a_raster_on_a_multi_face_part_matches_opencamlib_on_occs_mesh() {
    let Some(dir) = occ_parts("raster") else {
        return;
    };
    let occ_stl = dir.join("fillet.occ.stl");
    occ_read(&dir.join("fillet.step"), &occ_stl, 1e-4);
    let job = dir.join("raster.toml");
    std::fs::write(
        &job,
        "part = \"fillet.step\"\ntool = \"ball:d=6\"\n[strategy]\nkind = \"raster\"\nstepover = 1.5\n\
         tolerance = 0.005\n[linking]\nclearance = 30\n[output]\ncsv = \"raster.csv\"\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_swarf"))
        .arg("plan")
        .arg(&job)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let poses: Vec<[f64; 3]> = std::fs::read_to_string(dir.join("raster.csv"))
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('x'))
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert!(poses.len() > 200, "{} poses", poses.len());
    // Each pose and four neighbours 0.01 mm away: OpenCAMLib's CL surface slope
    // there gives the contact normal's vertical component n_z (a ball's CL surface
    // is normal to its contact normal), which turns a distance along the normal
    // into a height: a mesh within e of the part moves the CL by up to e / n_z.
    const H: f64 = 0.01;
    let xy: Vec<[f64; 2]> = poses
        .iter()
        .flat_map(|p| {
            [[0.0, 0.0], [H, 0.0], [-H, 0.0], [0.0, H], [0.0, -H]]
                .map(|d| [p[0] + d[0], p[1] + d[1]])
        })
        .collect();
    let Some(ocl) = ocl_drop(&occ_stl, "ball:d=6", &xy) else {
        return;
    };
    let (mut compared, mut worst) = (0, 0.0f64);
    for (p, o) in poses.iter().zip(ocl.chunks(5)) {
        let [Some(z), Some(xp), Some(xm), Some(yp), Some(ym)] = [o[0], o[1], o[2], o[3], o[4]]
        else {
            continue;
        };
        let (gx, gy) = ((xp - xm) / (2.0 * H), (yp - ym) / (2.0 * H));
        let nz = 1.0 / (1.0 + gx * gx + gy * gy).sqrt();
        if nz < 0.1 {
            continue; // contact within 6 degrees of the ball's equator: heights say little
        }
        // OCC's mesh is within 1e-4 mm of the part, swarf's mesh within 5e-4 and its
        // CL profile within the 0.005 mm tolerance: no gouge below, no excess above.
        let d = p[2] - z;
        assert!(
            d > -(5e-4 + 1e-4) / nz - 1e-6 && d < (0.005 + 1e-4) / nz,
            "at {p:?}: swarf {} vs OpenCAMLib {z} (contact normal n_z {nz:.3})",
            p[2]
        );
        worst = worst.max(d.abs() * nz);
        compared += 1;
    }
    assert!(compared > 200, "{compared} poses compared");
    eprintln!(
        "raster on OCC's fillet: {compared} poses, largest |swarf - OpenCAMLib| along the normal {worst:.2e} mm"
    );
}

#[test]
fn an_iso_scallop_on_a_trimmed_face_stays_on_it() {
    let Some(dir) = occ_parts("iso") else { return };
    let step = dir.join("plate_hole.step");
    let part = read(&step, 1e-4);
    // The drilled top face: the one with a hole.
    let top = (0..part.patches.len())
        .find(|&k| part.trim(k).is_some_and(|t| t.loops().len() == 2))
        .expect("a face with a hole");
    let text = format!(
        "part = {:?}\nfaces = [{top}]\ntool = \"ball:d=4\"\n[strategy]\n\
         kind = \"iso-scallop\"\nscallop = 0.05\ntolerance = 0.005\n[linking]\nclearance = 30\n",
        step.display().to_string()
    );
    let job = swarf_app::Job::parse(&text, "iso.toml").unwrap();
    let model = swarf_app::load_model_with(&job.part, &job.load_options()).unwrap();
    let swarf_app::Model::Patches(face) = &model else {
        panic!("a part")
    };
    let plan = swarf_app::plan(&job, swarf_app::PlanInput::Part(face)).unwrap();
    let trim = face.trim(0).unwrap();
    let mut n = 0;
    for p in plan.toolpath.passes.iter().flat_map(|p| &p.points) {
        // Points without a contact are links between pieces of a pass.
        let Some(c) = p.contact else { continue };
        let uv = c.uv;
        // Inside, or on a loop (where boundary passes and clipped ends run).
        let on_loop = trim
            .loops()
            .iter()
            .any(|l| (0..l.len()).any(|k| segment_distance(uv, l[k], l[(k + 1) % l.len()]) < 1e-6));
        assert!(
            trim.contains(uv[0], uv[1]) || on_loop,
            "CC {:?} outside the face",
            c.point
        );
        // The hole (radius 6 about (15, 14)) is not on the face.
        let r = ((c.point.x - 15.0).powi(2) + (c.point.y - 14.0).powi(2)).sqrt();
        assert!(r > 6.0 - 1e-4, "CC {:?} over the hole", c.point);
        n += 1;
    }
    assert!(n > 100, "{n} contacts");
}

/// Distance from `p` to the segment `a`-`b` in the plane.
fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((p[0] - a[0] - t * d[0]).powi(2) + (p[1] - a[1] - t * d[1]).powi(2)).sqrt()
}
