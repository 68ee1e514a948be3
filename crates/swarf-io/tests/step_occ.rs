//! STEP files written by an independent kernel (OpenCASCADE through the
//! `cadquery-ocp` wheel, `tests/occ/make_step.py`) read by swarf: every point OCC
//! evaluates on a face lies on a swarf face, inside its trim, within 1e-9 mm; B-spline
//! faces evaluate identically at OCC's own (u, v); a plate written in inches (AP203)
//! and a fillet written as AP242 read as the mm AP214 ones; the shared `wave` part written as
//! STEP by OCC reads back as the TOML part.
//!
//! Skipped with a note when OCP is missing, unless `SWARF_REQUIRE_REFERENCES=1`.

use std::path::{Path, PathBuf};
use std::process::Command;
use swarf_geom::Point3;
use swarf_io::{CadOptions, CadPart, read_step};

const TOL: f64 = 1e-9;

/// A scratch directory removed when dropped (also when a check fails).
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn occ_dir() -> Option<Scratch> {
    let have = Command::new("python3")
        .args(["-c", "import OCP"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !have {
        assert!(
            std::env::var("SWARF_REQUIRE_REFERENCES").as_deref() != Ok("1"),
            "OCP (cadquery-ocp) is missing and SWARF_REQUIRE_REFERENCES=1; run .ci/install-references"
        );
        eprintln!("note: python3 cannot import OCP (cadquery-ocp); STEP reference tests skipped");
        return None;
    }
    let dir = std::env::temp_dir().join(format!("swarf-step-occ-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scratch = Scratch(dir.clone());
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let wave = here.join("../../parts/wave.toml");
    let out = Command::new("python3")
        .arg(here.join("tests/occ/make_step.py"))
        .arg(&dir)
        .arg(&wave)
        .output()
        .expect("run python3");
    assert!(
        out.status.success(),
        "make_step.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(scratch)
}

struct Sample {
    kind: String,
    u: f64,
    v: f64,
    p: Point3,
}

fn samples(path: &Path) -> Vec<Sample> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let n = |i: usize| f[i].parse::<f64>().unwrap();
            Sample {
                kind: f[1].to_string(),
                u: n(2),
                v: n(3),
                p: Point3::new(n(4), n(5), n(6)),
            }
        })
        .collect()
}

/// Largest distance from an OCC point to the nearest swarf face containing its
/// projection, and for B-spline samples the largest |S(u, v) - P| over swarf's patches
/// with OCC's domain.
fn deviations(cad: &CadPart, s: &[Sample]) -> (f64, Option<f64>) {
    let part = &cad.part;
    let mut worst: f64 = 0.0;
    let mut eval: Option<f64> = None;
    for q in s {
        let best = (0..part.patches.len())
            .map(|k| {
                // Patch::project's starts can miss near a pole or apex (where the
                // rational patch degenerates): also descend from a grid of starts.
                let patch = &part.patches[k];
                let [du, dv] = patch.domain();
                let grid = (0..=4).flat_map(|i| {
                    (0..=4).map(move |j| {
                        let u = du[0] + (du[1] - du[0]) * f64::from(i) / 4.0;
                        let v = dv[0] + (dv[1] - dv[0]) * f64::from(j) / 4.0;
                        patch.project_from(&q.p, u, v)
                    })
                });
                std::iter::once(patch.project(&q.p))
                    .chain(grid)
                    .filter(|pr| part.face_contains(k, pr.u, pr.v))
                    .map(|pr| pr.distance)
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(f64::INFINITY, f64::min);
        if best > TOL {
            eprintln!(
                "  {} at OCC ({}, {}) {:?}: {best:e} mm",
                q.kind, q.u, q.v, q.p
            );
        }
        worst = worst.max(best);
        if q.kind == "bspline" {
            let e = part
                .patches
                .iter()
                .flat_map(|p| {
                    let [du, _] = p.domain();
                    [p.eval(q.u, q.v), p.eval(du[0] + du[1] - q.u, q.v)]
                })
                .map(|x| (x - q.p).norm())
                .fold(f64::INFINITY, f64::min);
            eval = Some(eval.unwrap_or(0.0).max(e));
        }
    }
    (worst, eval)
}

#[test]
fn occ_faces_read_back_within_1e_9_mm() {
    let Some(scratch) = occ_dir() else { return };
    let dir = scratch.0.clone();
    let opts = CadOptions::default();
    for name in [
        "bspline",
        "rational",
        "periodic",
        "extrusion",
        "plate_hole",
        "fillet",
        "cylinder",
        "cone",
        "sphere",
        "torus",
        "wave",
        "plate_inch",
        "fillet_ap242",
    ] {
        let cad = read_step(&dir.join(format!("{name}.step")), &opts)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(cad.warnings.is_empty(), "{name}: {:?}", cad.warnings);
        let unit = if name == "plate_inch" { "inch" } else { "mm" };
        assert_eq!(cad.unit, unit, "{name}");
        let s = samples(&dir.join(format!("{name}.csv")));
        assert!(s.len() > 50, "{name}: {} samples", s.len());
        let (worst, eval) = deviations(&cad, &s);
        eprintln!(
            "{name}: {} faces, {} OCC points, max distance to a swarf face {worst:.2e} mm, \
             B-spline eval at OCC (u, v) {eval:?} mm",
            cad.part.patches.len(),
            s.len()
        );
        assert!(
            worst <= TOL,
            "{name}: an OCC point lies {worst:e} mm from every swarf face"
        );
        if let Some(e) = eval {
            assert!(e <= TOL, "{name}: B-spline eval differs by {e:e} mm");
        }
    }
    watertight_trims(&dir, &opts);
    plate_hole_is_open(&dir, &opts);
    wave_round_trip(&dir, &opts);
}

/// Shared edges are shared samples: every trimming-loop point of a closed solid,
/// evaluated on its patch, meets a loop point of a neighbour (watertight trims).
fn watertight_trims(dir: &Path, opts: &CadOptions) {
    for name in ["plate_hole", "fillet"] {
        let cad = read_step(&dir.join(format!("{name}.step")), opts).unwrap();
        let mut pts = Vec::new();
        for (k, p) in cad.part.patches.iter().enumerate() {
            for (l, lp) in cad
                .part
                .trim(k)
                .map_or(&[][..], |t| t.loops())
                .iter()
                .enumerate()
            {
                pts.extend(
                    lp.iter()
                        .enumerate()
                        .map(|(i, q)| ((k, l, i), p.eval(q[0], q[1]))),
                );
            }
        }
        let mut gap: f64 = 0.0;
        for (id, a) in &pts {
            let d = pts
                .iter()
                .filter(|(jd, _)| jd.0 != id.0)
                .map(|(_, b)| (a - b).norm())
                .fold(f64::INFINITY, f64::min);
            gap = gap.max(d);
        }
        eprintln!(
            "{name}: {} loop points, largest gap to a neighbour face {gap:.2e} mm",
            pts.len()
        );
        assert!(
            gap <= TOL,
            "{name}: trimming loops of neighbour faces part by {gap:e} mm"
        );
    }
}

/// The hole of the plate is not part of any face.
fn plate_hole_is_open(dir: &Path, opts: &CadOptions) {
    let cad = read_step(&dir.join("plate_hole.step"), opts).unwrap();
    for z in [0.0, 5.0] {
        let c = Point3::new(15.0, 14.0, z);
        let inside = (0..cad.part.patches.len()).any(|k| {
            let pr = cad.part.patches[k].project(&c);
            pr.distance < 1e-6 && cad.part.face_contains(k, pr.u, pr.v)
        });
        assert!(!inside, "the hole's centre at z = {z} lies on a face");
    }
}

/// The shared wave part written by OCC reads back as the TOML part.
fn wave_round_trip(dir: &Path, opts: &CadOptions) {
    let cad = read_step(&dir.join("wave.step"), opts).unwrap();
    let wave = swarf_io::builtin_part("wave").unwrap();
    let (a, b) = (&cad.part.patches[0], &wave.patches[0]);
    assert_eq!(a.domain(), b.domain());
    let [du, dv] = b.domain();
    let mut worst: f64 = 0.0;
    for i in 0..=20 {
        for j in 0..=20 {
            let u = du[0] + (du[1] - du[0]) * f64::from(i) / 20.0;
            let v = dv[0] + (dv[1] - dv[0]) * f64::from(j) / 20.0;
            worst = worst.max((a.eval(u, v) - b.eval(u, v)).norm());
        }
    }
    eprintln!("wave round trip: max |S_step - S_toml| = {worst:.2e} mm");
    assert!(worst <= TOL);
}
