//! The paper's claim (issue 13): the snug drop-and-spin pass leaves less material at
//! the common edge than the vertical three-axis tool touching both faces there, and
//! never less than an insert can (the ball bound `r (sec b - 1)`, the insert's ball
//! wedged between faces sloping at `b`). Both programs are written as APT CL, read
//! back and cut on our dexel stock; the material left is measured at the edge.

use swarf_app::drop_spin::plan_drop_spin;
use swarf_fiveaxis::dsm::Dsm;
use swarf_geom::Vec3;
use swarf_nc::Units;
use swarf_nc::read::parse_cl;
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimTool, StockInit, simulate};
use swarf_tool::Cutter;
use swarf_toolpath::{Pass, PathPoint, Toolpath};

const CELL: f64 = 0.05;

/// Height of the stock after `tp` at `(x, 0)` (a strip of stock along the edge,
/// cells of `CELL`), mm.
fn cut_at_edge(tp: &Toolpath, tool: &Cutter, x: f64) -> f64 {
    let text = swarf_nc::write_cl(&tp.moves(), &tp.feeds, tool, "edge", Units::Mm).unwrap();
    let program = parse_cl(&text, "edge.cl").unwrap();
    let grid = Grid::covering([x - 1.0, -1.0], [x + 1.0, 1.0], CELL, 1 << 20).unwrap();
    let mut stock = Dexel::new(grid, StockInit::Box { top: 40.0 }).unwrap();
    let opts = SimOptions {
        sample_tol: 0.0025,
        known_start: false,
    };
    simulate(
        &mut stock,
        &SimTool::new(tool).unwrap(),
        &program.motions,
        &opts,
        &Quiet,
    );
    let i = ((x - grid.x(0)) / CELL).round() as usize;
    let j = ((0.0 - grid.y(0)) / CELL).round() as usize;
    stock.height(i, j)
}

#[test]
fn the_snug_pass_leaves_less_at_the_edge_than_three_axes() {
    let text = include_str!("../../../jobs/edge-concave-drop-spin.toml")
        .replace("zone = \"full\"", "zone = \"snug\"");
    let job = swarf_app::Job::parse(&text, "snug.toml").unwrap();
    let part = swarf_io::builtin_part("edge-concave").unwrap();
    let tool = job.tool;
    let snug = plan_drop_spin(&job, &part).unwrap().plan.toolpath;
    // The vertical tool touching both faces along the edge (T1 = 0 by symmetry).
    let dsm = Dsm::new(&part, [0, 1], &tool, Vec3::x()).unwrap();
    let points: Vec<PathPoint> = (0..=36)
        .map(|k| {
            let st = dsm.station(6.0 + 2.4 * f64::from(k)).unwrap();
            PathPoint::new(dsm.drop_on(0, dsm.footprint(&st, 0, 0.0)).unwrap().pose)
        })
        .collect();
    let three = Toolpath {
        passes: vec![Pass {
            points,
            ..Pass::default()
        }],
        ..snug.clone()
    };
    let r = 2.0;
    for x in [30.0, 50.0, 70.0] {
        let st = dsm.station(x).unwrap();
        let (d, t) = (
            cut_at_edge(&snug, &tool, x) - st.edge.z,
            cut_at_edge(&three, &tool, x) - st.edge.z,
        );
        // The faces' slope across the edge there: face 0's normal at the edge.
        let drop = dsm.drop_on(0, dsm.footprint(&st, 0, 0.0)).unwrap();
        let b = drop.normal.y.abs().atan2(drop.normal.z);
        let bound = r * (1.0 / b.cos() - 1.0);
        eprintln!(
            "x = {x}: left at the edge: drop-spin snug {d:.4}, three-axis {t:.4}, ball bound {bound:.4}"
        );
        assert!(d < t, "snug {d} not below three-axis {t}");
        assert!(
            d >= bound - 2.0 * CELL * b.tan(),
            "snug {d} below the ball bound {bound}"
        );
    }
}
