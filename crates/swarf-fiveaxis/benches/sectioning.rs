//! The sectioning gouge check per pose on the die experiment (thesis 000 ch. 8: bull
//! R 12.7, r 6.35, lead 6 degrees, 60 degrees off X, 1 mm sections), with the generating
//! curves alone and with the whole tool and the design's edges; and one gouge-free
//! search for a pose. `cargo bench -p swarf-fiveaxis --bench sectioning`.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use swarf_fiveaxis::autotilt::{TiltOptions, gouge_free_tilt};
use swarf_fiveaxis::design::DesignSurface;
use swarf_fiveaxis::gouge::{GougeOptions, pose_gouge};
use swarf_fiveaxis::sections::Sections;
use swarf_fiveaxis::{CurveOptions, incline_pass};
use swarf_testkit::die_cc;
use swarf_tool::ProfileTable;
use swarf_tool::{Cutter, Pose};

fn bench(c: &mut Criterion) {
    let part = swarf_io::builtin_part("die").expect("die");
    let design = DesignSurface::new(&part).expect("design");
    let angle = 60f64.to_radians();
    let cc = die_cc(&part, "bull:d=38.1,r=6.35", 60.0, 3.5, 0.002);
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().expect("tool");
    let profile = cutter.profile();
    let table = ProfileTable::new(&profile);
    let mid = &cc[cc.len() / 2];
    let pass = incline_pass(&cutter, mid, &[6f64.to_radians()], 0.0, 0).expect("pass");
    let poses: Vec<Pose> = pass.points.iter().map(|p| p.pose).collect();
    let mut g = GougeOptions {
        sections: Sections::along(angle, 1.0).expect("sections"),
        tolerance: 0.01,
        curve: CurveOptions::default(),
        cap_meridians: 96,
        whole_tool: false,
    };
    let i = poses.len() / 2;
    c.bench_function("pose check, generating curves", |b| {
        b.iter(|| black_box(pose_gouge(&design, &table, &poses, black_box(i), &g)))
    });
    g.whole_tool = true;
    c.bench_function("pose check, whole tool and edges", |b| {
        b.iter(|| black_box(pose_gouge(&design, &table, &poses, black_box(i), &g)))
    });
    g.whole_tool = false;
    let opts = TiltOptions {
        max_alpha: 25f64.to_radians(),
        tilt: 0.0,
        resolution: 0.01f64.to_radians(),
        max_rate: 0.5f64.to_radians(),
        gouge: g,
        max_rounds: 50,
    };
    let one = vec![mid[..5].to_vec()];
    c.bench_function("gouge-free tilt of 5 poses", |b| {
        b.iter(|| black_box(gouge_free_tilt(&cutter, &design, &one, &opts).expect("tilt")))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
