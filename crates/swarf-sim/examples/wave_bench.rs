//! Verifies a finishing program on wave.toml at 0.05 mm cells (about 8 million) and
//! prints the stage times, cell updates per second and the peak memory.
//!
//! `cargo run --release -p swarf-sim --example wave_bench [PROGRAM [normal]]`
//! (`normal`: deviation along the design normals). Without a
//! program, a ball (r = 4) iso-parametric zigzag over wave with a 2.17 mm side step
//! (the step for a 0.15 mm scallop on a plane) is generated: CL = CC + r N - r z.

use std::time::Instant;
use swarf_geom::{Point3, Vec3};
use swarf_nc::read::{Motion, MotionKind, Program, read_program};
use swarf_sim::{Design, Quiet, StockSpec, VerifyOptions, verify};
use swarf_tool::{Cutter, Pose};

fn generated(part: &swarf_geom::Part, r: f64) -> Program {
    let patch = &part.patches[0];
    let mut program = Program::new("generated iso-parametric zigzag");
    let passes = 47;
    let samples = 400;
    let mut at = Point3::new(0.0, 0.0, 60.0);
    let push = |at: &mut Point3, to: Point3, kind: MotionKind, program: &mut Program| {
        let line = program.motions.len() + 1;
        program.motions.push(Motion {
            kind,
            start: Pose::vertical(*at),
            end: Pose::vertical(to),
            feed: if kind == MotionKind::Rapid {
                0.0
            } else {
                300.0
            },
            line,
        });
        *at = to;
    };
    for k in 0..=passes {
        let v = k as f64 / passes as f64;
        let cl = |i: usize| {
            let u = if k % 2 == 0 { i } else { samples - i } as f64 / samples as f64;
            let d = patch.derivs(u, v);
            let mut n = d.du.cross(&d.dv).normalize();
            if n.z < 0.0 {
                n = -n;
            }
            d.point + n * r - Vec3::z() * r
        };
        let first = cl(0);
        push(
            &mut at,
            Point3::new(first.x, first.y, 60.0),
            MotionKind::Rapid,
            &mut program,
        );
        push(&mut at, first, MotionKind::Linear, &mut program);
        for i in 1..=samples {
            push(&mut at, cl(i), MotionKind::Linear, &mut program);
        }
        let up = Point3::new(at.x, at.y, 60.0);
        push(&mut at, up, MotionKind::Rapid, &mut program);
    }
    program
}

/// CPU time of this process (user + system), s: with other work on the machine the
/// wall clock overstates the cost, CPU time does not.
fn cpu_s() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = after.split_whitespace().collect();
    let tick = |k: usize| f.get(k).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (tick(11) + tick(12)) / 100.0
}

fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn main() {
    let part = swarf_io::builtin_part("wave").expect("wave is built in");
    let cutter: Cutter = "ball:d=8".parse().expect("ball spec");
    let program = match std::env::args().nth(1) {
        Some(path) => read_program(std::path::Path::new(&path)).expect("program reads"),
        None => generated(&part, 4.0),
    };
    let opts = VerifyOptions {
        cell: Some(0.05),
        tol: 0.01,
        allowed_excess: 0.15,
        stock: StockSpec::Offset { allowance: 0.5 },
        along_normals: std::env::args().nth(2).is_some_and(|a| a == "normal"),
        ..VerifyOptions::default()
    };
    let (t, c) = (Instant::now(), cpu_s());
    let v = verify(Design::Part(&part), &program, &cutter, &opts, &Quiet).expect("verifies");
    let (total, cpu) = (t.elapsed().as_secs_f64(), cpu_s() - c);
    let s = &v.deviation.summary;
    println!(
        "program: {} ({} motions)",
        program.source,
        program.motions.len()
    );
    println!(
        "grid: {} x {} = {} cells of {} mm",
        v.grid.nx,
        v.grid.ny,
        v.grid.len(),
        v.grid.cell
    );
    println!(
        "design {:.2} s, simulate {:.2} s, deviation {:.2} s, total {:.2} s (threads: {})",
        v.timings.design_s,
        v.timings.simulate_s,
        v.timings.deviation_s,
        total,
        rayon::current_num_threads()
    );
    println!(
        "cells visited {} ({:.0} M/s), lowered {}",
        v.sim.cells_visited,
        v.sim.cells_visited as f64 / v.timings.simulate_s / 1e6,
        v.sim.cells_lowered
    );
    println!(
        "gouge cells {}, excess cells {}, scallop p5-p95 {:?}-{:?} max {:?}",
        s.gouge.cells, s.excess.cells, s.scallop.p05, s.scallop.p95, s.scallop.max
    );
    println!(
        "CPU time {cpu:.2} s over {total:.2} s wall ({:.2} CPUs busy; 2 idle cores would take about {:.2} s)",
        cpu / total,
        cpu / 2.0
    );
    if let Some(mib) = peak_rss_mib() {
        println!("peak memory {mib:.0} MiB");
    }
}
