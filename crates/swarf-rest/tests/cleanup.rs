//! Cleanup paths: no gouge by brute force, determinism across thread counts, region
//! merging on the short grooves, bad input.

use swarf_geom::{Point3, TriMesh, Vec3};
use swarf_path::Cutting;
use swarf_rest::{CleanupParams, Pattern, RegionParams, RestError, Source, detect, plan_cleanup};
use swarf_tool::Cutter;
use swarf_toolpath::Toolpath;

const TOL: f64 = 0.01;

fn cutter(s: &str) -> Cutter {
    s.parse().unwrap()
}

fn cleanup(mesh: &TriMesh, reference: &str, tool: &str, pattern: Pattern) -> Toolpath {
    let reference = cutter(reference);
    let det = detect(
        mesh,
        &reference,
        Source::Reference,
        TOL,
        &RegionParams::default(),
    )
    .unwrap();
    let cut = Cutting::new(cutter(tool));
    let params = CleanupParams {
        pattern,
        passes: 3,
        ..CleanupParams::new(TOL)
    };
    plan_cleanup(mesh, &det.regions, &reference, &cut, &params).unwrap()
}

/// The point of triangle `t` closest to `p` (Ericson, Real-Time Collision
/// Detection §5.1.5), written here independently of the kernel.
fn closest_on_triangle(p: &Point3, t: &[Point3; 3]) -> Point3 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// The least distance from the centre of a ball of radius `r` with its tip at each
/// CL point (every `every`-th) to every triangle, minus `r`: negative is a gouge.
fn ball_clearance(mesh: &TriMesh, tp: &Toolpath, r: f64, every: usize) -> f64 {
    let tris: Vec<[Point3; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|k| mesh.vertices[k as usize]))
        .collect();
    tp.passes
        .iter()
        .flat_map(|p| &p.points)
        .step_by(every)
        .map(|q| {
            let centre = q.pose.cl + Vec3::new(0.0, 0.0, r);
            tris.iter()
                .map(|t| (closest_on_triangle(&centre, t) - centre).norm() - r)
                .fold(f64::INFINITY, f64::min)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn no_cleanup_cl_point_gouges_any_triangle() {
    let grooves = swarf_io::builtin_mesh("v-grooves").unwrap();
    let short = swarf_io::builtin_mesh("short-grooves").unwrap();
    let pocket = swarf_io::builtin_mesh("fillet-pocket").unwrap();
    for (mesh, reference, every) in [
        (&grooves, "ball:d=12", 1),
        (&short, "ball:d=6", 1),
        (&pocket, "ball:d=12", 97),
    ] {
        for pattern in [Pattern::FlowCut, Pattern::FollowPocket] {
            let tp = cleanup(mesh, reference, "ball:d=4", pattern);
            assert!(!tp.passes.is_empty());
            let c = ball_clearance(mesh, &tp, 2.0, every);
            assert!(
                c >= -1e-9,
                "{reference} {pattern:?}: a CL point {c} mm into the part"
            );
        }
    }
}

#[test]
fn the_same_path_on_one_and_two_threads() {
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let run = |threads: usize| {
        swarf_testkit::threads::on_threads(threads, || {
            [Pattern::FlowCut, Pattern::FollowPocket]
                .map(|p| cleanup(&mesh, "ball:d=12", "ball:d=4", p))
        })
    };
    let (one, two) = (run(1), run(2));
    for (a, b) in one.iter().zip(&two) {
        let text = |t: &Toolpath| {
            swarf_nc::write_gcode(&t.moves(), &t.feeds, &Default::default()).unwrap()
        };
        assert_eq!(text(a), text(b));
        // (Contacts on a mesh carry NaN surface parameters: compare the poses.)
        let poses = |t: &Toolpath| -> Vec<_> {
            t.passes
                .iter()
                .flat_map(|p| &p.points)
                .map(|q| q.pose)
                .collect()
        };
        assert_eq!(poses(a), poses(b));
    }
}

#[test]
fn grooves_1_5_mm_apart_merge_at_2_mm_and_5_mm_apart_do_not() {
    let mesh = swarf_io::builtin_mesh("short-grooves").unwrap();
    let ball = cutter("ball:d=6");
    let count = |merge: f64| {
        let params = RegionParams {
            merge,
            ..RegionParams::default()
        };
        detect(&mesh, &ball, Source::Reference, TOL, &params)
            .unwrap()
            .regions
            .len()
    };
    assert_eq!(count(1.0), 4);
    assert_eq!(count(2.0), 3);
    assert_eq!(count(6.0), 2);
}

#[test]
fn bad_input_is_an_error_or_an_empty_path() {
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let ball = cutter("ball:d=6");
    // A cleanup tool larger than the reference.
    let det = detect(
        &mesh,
        &ball,
        Source::Reference,
        TOL,
        &RegionParams::default(),
    )
    .unwrap();
    let cut = Cutting::new(cutter("ball:d=8"));
    let params = CleanupParams {
        pattern: Pattern::FlowCut,
        passes: 0,
        ..CleanupParams::new(TOL)
    };
    let e = plan_cleanup(&mesh, &det.regions, &ball, &cut, &params).unwrap_err();
    assert!(matches!(e, RestError::ToolNotSmaller { .. }), "{e}");
    // Zero or negative merge, overlap, min_area; a NaN threshold.
    for (field, p) in [
        (
            "merge",
            RegionParams {
                merge: 0.0,
                ..RegionParams::default()
            },
        ),
        (
            "overlap",
            RegionParams {
                overlap: -1.0,
                ..RegionParams::default()
            },
        ),
        (
            "min_area",
            RegionParams {
                min_area: 0.0,
                ..RegionParams::default()
            },
        ),
        (
            "threshold",
            RegionParams {
                threshold: f64::NAN,
                ..RegionParams::default()
            },
        ),
    ] {
        let e = detect(&mesh, &ball, Source::Reference, TOL, &p).unwrap_err();
        assert!(e.to_string().starts_with(&format!("{field} = ")), "{e}");
    }
    // No regions: an empty path, not an error.
    let flat = TriMesh::from_triangles(&[[
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(10.0, 0.0, 0.0),
        Point3::new(0.0, 10.0, 0.0),
    ]]);
    let det = detect(
        &flat,
        &ball,
        Source::Reference,
        TOL,
        &RegionParams::default(),
    )
    .unwrap();
    assert!(det.regions.is_empty());
    let cut = Cutting::new(cutter("ball:d=4"));
    assert!(
        plan_cleanup(&flat, &det.regions, &ball, &cut, &params)
            .unwrap()
            .passes
            .is_empty()
    );
}
