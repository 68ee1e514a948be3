//! Raster finishing on the tessellated wave (the shipped example's settings, on part
//! of the part to stay fast): every CL point is gouge-free against every triangle
//! (brute force, no index), and LinuxCNC's interpreter `rs274 -g` reads the G-code
//! to the end with every feed move. Without `rs274` the second check is skipped,
//! unless `SWARF_REQUIRE_REFERENCES=1`.

use swarf_path::strategy::raster::{RasterParams, plan};
use swarf_path::{Cutting, Plan};
use swarf_tool::drop::{DropCutter, triangle_drop};
use swarf_toolpath::MoveKind;

fn wave_plan() -> (swarf_geom::TriMesh, Cutting, Plan) {
    let part = swarf_io::builtin_part("wave").unwrap();
    let mesh = part.tessellate(0.01).unwrap();
    let params = RasterParams {
        scallop: Some(0.15),
        boundary: Some([70.0, 20.0, 110.0, 55.0]),
        ..RasterParams::default()
    };
    let job = Cutting::new("ball:d=8".parse().unwrap());
    let p = plan(&mesh, &job, &params).unwrap();
    (mesh, job, p)
}

#[test]
fn wave_raster_is_gouge_free_and_rs274_reads_it() {
    let (mesh, job, p) = wave_plan();
    let tool = DropCutter::new(&job.tool);
    let r = tool.radius();
    let mut points = 0;
    for q in p.toolpath.passes.iter().flat_map(|p| &p.points) {
        points += 1;
        let cl = q.pose.cl;
        for t in 0..mesh.len() {
            let tri = mesh.triangle(t);
            let far = tri
                .iter()
                .all(|v| (v.x - cl.x).abs() > r + 2.0 || (v.y - cl.y).abs() > r + 2.0);
            if far {
                continue;
            }
            if let Some(c) = triangle_drop(&tool, [cl.x, cl.y], &tri) {
                assert!(
                    c.z <= cl.z + 1e-9,
                    "{cl:?} gouges triangle {t} by {}",
                    c.z - cl.z
                );
            }
        }
    }
    assert!(points > 500, "{points}");
    let moves = p.toolpath.moves();
    let gcode =
        swarf_nc::write_gcode(&moves, &job.feeds, &swarf_nc::GcodeOptions::default()).unwrap();
    let Some(canon) = run_rs274(&gcode) else {
        return;
    };
    let feeds = canon
        .lines()
        .filter(|l| l.contains("STRAIGHT_FEED"))
        .count();
    let feed_moves = moves.iter().filter(|m| m.kind == MoveKind::Feed).count();
    assert_eq!(
        feeds, feed_moves,
        "rs274 read {feeds} feeds of {feed_moves}"
    );
}

/// `rs274 -g` on the program: its canonical output, `None` when rs274 is not
/// installed (a failure instead with `SWARF_REQUIRE_REFERENCES=1`).
fn run_rs274(gcode: &str) -> Option<String> {
    let out = swarf_testkit::rs274::run_rs274(gcode, "wave-raster")?;
    assert!(
        out.success,
        "rs274 refused the program: {}\n{}",
        out.stderr, out.stdout
    );
    assert!(out.stdout.contains("PROGRAM_END"), "{}", out.stdout);
    Some(out.stdout)
}
