//! Engagement measurement keeps what the simulation finds: a rapid that dips 2 mm
//! into a box stock is reported with its line and depth (the box's top less the
//! tool's tip, in closed form), one above the box is not.

use swarf_geom::Point3;
use swarf_sim::engagement::measure_engagement;
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimTool, StockInit};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::program::{Motion, MotionKind};

fn motion(kind: MotionKind, a: [f64; 3], b: [f64; 3], line: usize) -> Motion {
    let p = |c: [f64; 3]| Pose::vertical(Point3::new(c[0], c[1], c[2]));
    Motion {
        kind,
        start: p(a),
        end: p(b),
        feed: if kind == MotionKind::Rapid {
            0.0
        } else {
            300.0
        },
        line,
    }
}

#[test]
fn a_rapid_into_the_stock_is_reported_with_its_line_and_depth() {
    let grid = Grid::covering([0.0, 0.0], [20.0, 20.0], 0.25, 1 << 28).unwrap();
    let mut dexel = Dexel::new(grid, StockInit::Box { top: 10.0 }).unwrap();
    let tool = SimTool::new(&Cutter::flat(4.0, None).unwrap()).unwrap();
    let r = MotionKind::Rapid;
    let motions = [
        motion(r, [5.0, 5.0, 12.0], [15.0, 5.0, 12.0], 1),
        motion(r, [15.0, 5.0, 12.0], [15.0, 15.0, 8.0], 2),
        motion(r, [15.0, 15.0, 8.0], [15.0, 15.0, 12.0], 3),
    ];
    let opts = SimOptions {
        known_start: true,
        ..SimOptions::default()
    };
    let eng = measure_engagement(&mut dexel, &tool, &motions, 0, &opts, &Quiet);
    assert_eq!(eng.rapid_cuts.len(), 1, "{:?}", eng.rapid_cuts);
    let cut = eng.rapid_cuts[0];
    assert_eq!((cut.motion, cut.line), (1, 2));
    assert!((cut.amount - 2.0).abs() < 1e-9, "{}", cut.amount);
    assert_eq!(eng.without(&[true, true, true]).rapid_cuts, eng.rapid_cuts);
}
