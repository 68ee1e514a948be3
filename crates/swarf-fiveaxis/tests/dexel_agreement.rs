//! The machined surface by generating curves against swarf-sim's dexel (Z-map)
//! verifier, on a section line across three passes of the die experiment (thesis 000
//! ch. 6: "both methods are in agreement within 3 um"); the full comparison at x = -20,
//! -50, -80 mm is `examples/die_dexel.rs`.

use swarf_fiveaxis::swept::SweptSurface;
use swarf_fiveaxis::{CurveOptions, incline_pass};
use swarf_nc::read::{Motion, MotionKind};
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimTool, StockInit, simulate};
use swarf_testkit::die_cc;
use swarf_tool::{Cutter, Pose};

#[test]
fn generating_curves_agree_with_the_dexel_within_3_micrometres() {
    let part = swarf_io::builtin_part("die").unwrap();
    let cc = die_cc(&part, "bull:d=38.1,r=6.35", 60.0, 3.5, 0.002);
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
    // Three neighbouring passes through the middle, 24 poses each around x = -50.
    let mid = cc.len() / 2;
    let passes: Vec<Vec<Pose>> = cc[mid - 1..=mid + 1]
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let p = incline_pass(&cutter, c, &[6f64.to_radians()], 0.0, k).unwrap();
            let poses: Vec<Pose> = p.points.iter().map(|q| q.pose).collect();
            let i = poses
                .iter()
                .position(|q| (q.cl.x + 50.0).abs() < 1.0)
                .unwrap();
            poses[i.saturating_sub(12)..(i + 12).min(poses.len())].to_vec()
        })
        .collect();
    let opts = CurveOptions {
        meridians: 121,
        wall_cards: 24,
        ..CurveOptions::default()
    };
    let swept = SweptSurface::new(&cutter.profile(), &passes, &opts).unwrap();
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
    let cell = 0.25;
    let (x, y0, y1) = (-50.0, -80.0, -40.0);
    let grid = Grid::covering([x - 0.5 * cell, y0], [x + 0.5 * cell, y1], cell, 1 << 26).unwrap();
    let mut dexel = Dexel::new(grid, StockInit::Box { top: 100.0 }).unwrap();
    let tool = SimTool::new(&cutter).unwrap();
    // (sampled within 1 um: second order, a few dozen positions per motion)
    let so = SimOptions {
        sample_tol: 0.001,
        known_start: true,
        ..SimOptions::default()
    };
    simulate(&mut dexel, &tool, &motions, &so, &Quiet);
    let mut compared = 0;
    for j in 0..grid.ny {
        let [cx, cy] = grid.centre(0, j);
        let z = dexel.height(0, j);
        if let (Some(h), true) = (swept.height(cx, cy), z < 99.0) {
            assert!((h - z).abs() < 0.003, "y = {cy}: curves {h}, dexel {z}");
            compared += 1;
        }
    }
    assert!(compared > 50, "{compared} cells compared");
}
