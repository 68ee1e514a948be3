//! Cell updates per second of the exact sweep: a zigzag raster of straight moves over
//! a 40 x 40 mm stock at 0.05 mm cells (640 000 cells), for a ball and a bull-nose
//! cutter (the bull's torus takes the bracketed Newton path). Throughput is counted in
//! cell evaluations (cells within reach of a move).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use swarf_geom::Point3;
use swarf_sim::sweep::SimTool;
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, StockInit, simulate};
use swarf_tool::Pose;
use swarf_toolpath::{Motion, MotionKind};

fn raster() -> Vec<Motion> {
    let mut out = Vec::new();
    let mut at = Point3::new(-2.0, -2.0, 0.0);
    for k in 0..20 {
        let y = -2.0 + 2.2 * k as f64;
        for s in 0..=50 {
            let x = if k % 2 == 0 {
                -2.0 + 0.88 * s as f64
            } else {
                42.0 - 0.88 * s as f64
            };
            let z = -0.5 + 0.3 * (0.2 * x).sin() * (0.15 * y).cos();
            let to = Point3::new(x, y, z);
            out.push(Motion {
                kind: MotionKind::Linear,
                start: Pose::vertical(at),
                end: Pose::vertical(to),
                feed: 300.0,
                line: out.len() + 1,
            });
            at = to;
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let grid = Grid::covering([0.0, 0.0], [40.0, 40.0], 0.05, 1 << 30).expect("grid");
    let moves = raster();
    let mut group = c.benchmark_group("sweep");
    group.sample_size(10);
    for spec in ["ball:d=8", "bull:d=8,r=1"] {
        let tool = SimTool::new(&spec.parse().expect("tool")).expect("tool");
        let run = || {
            let mut d = Dexel::new(grid, StockInit::Box { top: 1.0 }).expect("stock");
            simulate(&mut d, &tool, &moves, &SimOptions::default(), &Quiet)
        };
        let visited = run().cells_visited;
        group.throughput(Throughput::Elements(visited));
        group.bench_function(spec, |b| b.iter(|| black_box(run())));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
