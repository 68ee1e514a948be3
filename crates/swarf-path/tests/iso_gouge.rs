//! No CL point of any iso strategy enters the part by more than the tolerance, checked
//! by brute force (`Cutter::signed_distance` of every CL pose against a dense grid of
//! exact surface points of every patch), on wave.toml and on the two-patch valley of
//! edge-convex.toml, where the gouge check has work to do (the crease is tighter than
//! the ball).

mod iso_support;

use iso_support::{IsoJob, dense_points, iso_job, max_penetration, wave, wave_job};

const TOL: f64 = 0.01;

fn job(kind: &str, tool: &str, extra: &str) -> IsoJob {
    iso_job(
        kind,
        tool,
        &format!("scallop = 0.3\ntolerance = {TOL}\n{extra}\n"),
    )
}

#[test]
fn wave_paths_do_not_gouge() {
    let part = wave();
    let points = dense_points(&part, 0.3);
    for kind in ["iso-parametric", "iso-planar", "iso-scallop"] {
        let job = wave_job(kind, 0.15, TOL);
        let plan = job.plan(&part).unwrap();
        let depth = max_penetration(&plan, &job.tool, &points);
        assert!(depth <= TOL, "{kind}: enters wave by {depth} mm");
    }
}

#[test]
fn valley_of_two_patches_is_lifted_out_of() {
    let part = swarf_io::builtin_part("edge-convex").unwrap();
    let points = dense_points(&part, 0.3);
    for (kind, extra) in [
        ("iso-planar", "angle = 90"),
        ("iso-planar", "angle = 30"),
        ("iso-parametric", "direction = \"v\""),
        ("iso-scallop", ""),
    ] {
        for tool in ["ball:d=8", "bull:d=10,r=2"] {
            let job = job(kind, tool, extra);
            let plan = job.plan(&part).unwrap();
            let depth = max_penetration(&plan, &job.tool, &points);
            assert!(depth <= TOL, "{kind} {extra} {tool}: enters by {depth} mm");
            assert!(
                plan.report.lifted_points > 0,
                "{kind} {extra} {tool}: crease not lifted"
            );
            assert_eq!(plan.report.lifted_points, plan.toolpath.lifted_count());
            // The oracle sees a gouge: put the most lifted point back where it was planned.
            let mut undone = plan.clone();
            let p = undone
                .toolpath
                .passes
                .iter_mut()
                .flat_map(|p| &mut p.points)
                .max_by(|a, b| a.lifted.total_cmp(&b.lifted))
                .unwrap();
            p.pose.cl.z -= p.lifted;
            let depth = max_penetration(&undone, &job.tool, &points);
            assert!(depth > TOL, "{kind} {extra} {tool}: oracle blind ({depth})");
        }
    }
}
