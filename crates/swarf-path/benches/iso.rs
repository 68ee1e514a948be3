//! Planning time of the three iso strategies on wave.toml (ball d = 8), gouge checks
//! included: paper 004's experiment (h = 0.15 mm, tolerance 0.01 mm) and a fine one
//! (h = 0.01 mm, tolerance 0.001 mm; target under 3 s each on a 2-core machine).
//!
//! The pass bound of wave (`swarf_path::strategy::iso::pass_bound`, computed by every iso plan) is
//! timed on its own.
//!
//! `cargo bench -p swarf-path --bench iso` (criterion; 10 samples each).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use swarf_geom::Part;
use swarf_path::params::ParamDir;
use swarf_path::stepping::side_step::SideStep;
use swarf_path::strategy::iso::pass_bound::{Feed, pass_bound};
use swarf_path::strategy::iso::planar::IsoPlanarParams;
use swarf_path::strategy::iso::{IsoParams, parametric, planar, scallop};
use swarf_path::{Cutting, Finish, Plan};

/// Plans the iso strategy `kind` on `part` with a ball d = 8 at scallop `h` and
/// tolerance `tol`.
fn plan(kind: &str, part: &Part, h: f64, tol: f64) -> Plan {
    let cut = Cutting::new("ball:d=8".parse().expect("valid tool"));
    let finish = Finish {
        tolerance: tol,
        ..Finish::default()
    };
    let iso = IsoParams {
        finish,
        ..IsoParams::new(h)
    };
    match kind {
        "iso-parametric" => parametric::plan(part, &cut, &iso),
        "iso-scallop" => scallop::plan(part, &cut, &iso),
        _ => planar::plan(
            part,
            &cut,
            &IsoPlanarParams {
                finish,
                ..IsoPlanarParams::new(h)
            },
        ),
    }
    .expect("plans")
}

fn bench(c: &mut Criterion) {
    let part = swarf_io::builtin_part("wave").expect("built-in wave");
    let mut group = c.benchmark_group("wave");
    group.sample_size(10).warm_up_time(Duration::from_secs(1));
    for (h, tol) in [(0.15, 0.01), (0.01, 0.001)] {
        for kind in ["iso-parametric", "iso-planar", "iso-scallop"] {
            group.bench_function(format!("{kind} h={h} tol={tol}"), |b| {
                b.iter(|| black_box(plan(kind, &part, h, tol).toolpath.pose_count()))
            });
        }
    }
    for tool in ["ball:d=8", "bull:d=10,r=2"] {
        let cutter = tool.parse().expect("valid tool");
        let side = SideStep::new(&cutter, 0.15).expect("valid scallop");
        group.bench_function(format!("pass bound {tool} h=0.15"), |b| {
            b.iter(|| black_box(pass_bound(&part, &side, Feed::Param(ParamDir::U))))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
