//! The machined surface of the die experiment (thesis 000 ch. 6 and 8) by generating
//! curves against the dexel (Z-map) verifier of swarf-sim, on section lines `x = c`:
//! `cargo run --release -p swarf-fiveaxis --example die_dexel -- [alpha] [cell] [sample_tol] [meridians] [x...]`.
//! Prints, per section, the largest difference of the two machined heights and both
//! times.

use std::time::Instant;
use swarf_fiveaxis::design::DesignSurface;
use swarf_fiveaxis::drive::{DrivePlanes, drive_plane_passes};
use swarf_fiveaxis::swept::SweptSurface;
use swarf_fiveaxis::{CurveOptions, incline_pass};
use swarf_nc::read::{Motion, MotionKind};
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimTool, StockInit, simulate};
use swarf_tool::{Cutter, Pose};

fn arg(k: usize, default: f64) -> f64 {
    std::env::args()
        .nth(k)
        .and_then(|a| a.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let alpha = arg(1, 3.0);
    let cell = arg(2, 0.05);
    let sample_tol = arg(3, 0.002);
    let meridians = arg(4, 181.0) as usize;
    let mut sections: Vec<f64> = std::env::args()
        .skip(5)
        .filter_map(|a| a.parse().ok())
        .collect();
    if sections.is_empty() {
        sections = vec![-20.0, -50.0, -80.0];
    }
    let part = swarf_io::builtin_part("die").expect("built-in die");
    let design = DesignSurface::new(&part);
    let dp = DrivePlanes {
        angle: 60f64.to_radians(),
        cross_feed: 3.5,
        step: 1.0,
        zigzag: true,
    };
    let cc = drive_plane_passes(&design, &part.control_box(), &dp).expect("passes");
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().expect("tool");
    let passes: Vec<Vec<Pose>> = cc
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let p = incline_pass(&cutter, c, &[alpha.to_radians()], 0.0, k).expect("pose");
            p.points.iter().map(|q| q.pose).collect()
        })
        .collect();
    let t = Instant::now();
    let opts = CurveOptions {
        meridians,
        wall_cards: 24,
        ..CurveOptions::default()
    };
    let swept = SweptSurface::new(&cutter.profile(), &passes, &opts).expect("swept");
    let t_gc = t.elapsed().as_secs_f64();
    let motions: Vec<Motion> = passes
        .iter()
        .flat_map(|p| p.windows(2))
        .enumerate()
        .map(|(i, w)| Motion {
            kind: MotionKind::Linear,
            start: w[0],
            end: w[1],
            feed: 150.0,
            line: i + 1,
        })
        .collect();
    let tool = SimTool::new(&cutter).expect("sim tool");
    let b = part.control_box();
    println!(
        "alpha {alpha} deg: {} poses; generating curves ({meridians} meridians): {:.2} s",
        passes.iter().map(Vec::len).sum::<usize>(),
        t_gc
    );
    for x in sections {
        let grid = Grid::covering(
            [x - 0.5 * cell, b.min.y],
            [x + 0.5 * cell, b.max.y],
            cell,
            1 << 30,
        )
        .expect("grid");
        let mut dexel = Dexel::new(grid, StockInit::Box { top: b.max.z + 5.0 }).expect("stock");
        let t = Instant::now();
        let so = SimOptions {
            sample_tol,
            known_start: true,
        };
        simulate(&mut dexel, &tool, &motions, &so, &Quiet);
        let t_dx = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let (mut worst, mut at, mut n, mut gouge) = (0.0f64, 0.0, 0, 0.0f64);
        for j in 0..grid.ny {
            let [cx, cy] = grid.centre(0, j);
            let (Some(h), Some((d, _))) = (swept.height(cx, cy), design.height(cx, cy)) else {
                continue;
            };
            let z = dexel.height(0, j);
            if z > b.max.z {
                continue;
            }
            n += 1;
            gouge = gouge.max(d - z);
            if (h - z).abs() > worst.abs() {
                worst = h - z;
                at = cy;
            }
        }
        let t_q = t.elapsed().as_secs_f64();
        println!(
            "x = {x}: {n} cells; largest difference (curves - dexel) {:.4} mm at y = {at:.2}; \
             dexel deepest below design {:.4} mm; dexel {:.2} s, section of the curves' surface {:.3} s",
            worst, gouge, t_dx, t_q
        );
    }
}
