//! Timing of rest detection, cleanup planning and the dexel re-verification, on the
//! built-in fillet pocket (21k triangles) and on the same pocket with every triangle
//! split into 64 (1.34M triangles, the same surface: the figures must agree).
//!
//! `cargo run --release -p swarf-rest --example rest_bench`

use std::time::Instant;
use swarf_geom::{Point3, TriMesh};
use swarf_path::Cutting;
use swarf_path::strategy::raster::RasterParams;
use swarf_rest::{CleanupParams, Pattern, RegionParams, Source, detect, plan_cleanup};
use swarf_sim::{Design, StockSpec, VerifyOptions};
use swarf_tool::Cutter;

/// Every triangle split into four at its edge midpoints, `levels` times.
fn split(mesh: &TriMesh, levels: usize) -> TriMesh {
    let mut tris: Vec<[Point3; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|k| mesh.vertices[k as usize]))
        .collect();
    for _ in 0..levels {
        tris = tris
            .iter()
            .flat_map(|[a, b, c]| {
                let m = |p: &Point3, q: &Point3| Point3::from((p.coords + q.coords) * 0.5);
                let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
                [[*a, ab, ca], [ab, *b, bc], [ca, bc, *c], [ab, bc, ca]]
            })
            .collect();
    }
    TriMesh::from_triangles(&tris)
}

fn run(name: &str, mesh: &TriMesh) {
    let (ball, small): (Cutter, Cutter) =
        ("ball:d=12".parse().unwrap(), "ball:d=4".parse().unwrap());
    let t = Instant::now();
    let det = detect(
        mesh,
        &ball,
        Source::Reference,
        0.01,
        &RegionParams::default(),
    )
    .unwrap();
    let detect_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let cut = Cutting::new(small);
    let params = CleanupParams {
        pattern: Pattern::FollowPocket,
        passes: 0,
        ..CleanupParams::new(0.01)
    };
    let clean = plan_cleanup(mesh, &det.regions, &ball, &cut, &params).unwrap();
    let clean_s = t.elapsed().as_secs_f64();
    let fp = RasterParams {
        scallop: Some(0.01),
        ..RasterParams::default()
    };
    let t = Instant::now();
    let finish = swarf_path::strategy::raster::plan(mesh, &Cutting::new(ball), &fp).unwrap();
    let finish_s = t.elapsed().as_secs_f64();
    let program = |tp: &swarf_toolpath::Toolpath, n: &str| {
        let text = swarf_nc::write_gcode(&tp.moves(), &tp.feeds, &Default::default()).unwrap();
        swarf_nc::read::parse_gcode(&text, n, &Default::default()).unwrap()
    };
    let (pf, pc) = (
        program(&finish.toolpath, "finish"),
        program(&clean, "cleanup"),
    );
    let stages = [
        swarf_sim::Stage {
            program: &pf,
            cutter: &ball,
        },
        swarf_sim::Stage {
            program: &pc,
            cutter: &small,
        },
    ];
    let opts = VerifyOptions {
        cell: Some(0.1),
        stock: StockSpec::Box { top: None },
        along_normals: true,
        ..VerifyOptions::default()
    };
    let t = Instant::now();
    let v = swarf_sim::verify::verify_stages(Design::Mesh(mesh), &stages, &opts, &swarf_sim::Quiet)
        .unwrap();
    let verify_s = t.elapsed().as_secs_f64();
    println!(
        "{name}: {} triangles | detect {detect_s:.2} s ({} regions, {} samples) | cleanup {clean_s:.2} s ({} passes, {} poses) | finish raster {finish_s:.2} s | verify both {verify_s:.2} s ({} cells, excess {} cells, worst {:.4} mm, gouge {} cells)",
        mesh.len(),
        det.regions.len(),
        det.samples,
        clean.passes.len(),
        clean.pose_count(),
        v.grid.len(),
        v.deviation.summary.excess.cells,
        v.deviation.summary.excess.worst,
        v.deviation.summary.gouge.cells,
    );
}

fn main() {
    let pocket = swarf_io::builtin_mesh("fillet-pocket").unwrap();
    run("fillet pocket", &pocket);
    run("fillet pocket split 64x", &split(&pocket, 3));
}
