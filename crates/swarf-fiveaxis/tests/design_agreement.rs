//! Sectioning (five-axis `DesignSurface`) and dexel verification (the simulator's
//! design field) read the same height-field query, so they agree at the patch edges
//! of the two-patch part edge-convex: along and across the common edge (the patches
//! cross at y = 0 and run past it to y = +-10 under each other), on the outer edges
//! and just outside them.

use swarf_fiveaxis::design::DesignSurface;
use swarf_sim::{Design, Grid, Quiet};

/// Compares both callers at every cell centre of `grid`; returns how many centres
/// each patch of the part tops.
fn compare(part: &swarf_geom::Part, grid: &Grid) -> [usize; 2] {
    let sectioning = DesignSurface::new(part).unwrap();
    let field = swarf_sim::DesignSurface::new(Design::Part(part))
        .unwrap()
        .heights(grid, false, &Quiet);
    assert_eq!(field.approximate, 0);
    let mut tops = [0; 2];
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let [x, y] = grid.centre(i, j);
            let sim = field.heights[j * grid.nx + i];
            match sectioning.height(x, y) {
                None => assert!(sim.is_nan(), "({x}, {y}): sim {sim}, sectioning off"),
                Some((z, k)) => {
                    assert!((z - sim).abs() <= 1e-9, "({x}, {y}): {z} vs sim {sim}");
                    tops[k] += 1;
                }
            }
        }
    }
    tops
}

#[test]
fn sectioning_and_verification_agree_at_the_edges_of_edge_convex() {
    let part = swarf_io::builtin_part("edge-convex").unwrap();
    // Centres on every multiple of 1/8 mm from -1 to 101 in x and -51 to 51 in y:
    // on the common edge y = 0, on x = 0 and x = 100, on y = +-10 (where each patch
    // ends under the other) and on y = +-50, and a millimetre outside all round.
    let h = 0.0625;
    let exact = Grid::covering(
        [-1.0 - h, -51.0 - h],
        [101.0 + h, 51.0 + h],
        2.0 * h,
        1 << 30,
    )
    .unwrap();
    assert_eq!(exact.centre(8, 408), [0.0, 0.0]);
    let tops = compare(&part, &exact);
    assert!(tops[0] > 300_000 && tops[1] > 300_000, "{tops:?}");
    // The same lattice moved by 1e-7 mm: just inside x = 0 and y = -50, just outside
    // x = 100 and y = 50, and a hair off the common edge.
    let e = 1e-7;
    let shifted = Grid::covering(
        [-1.0 - h + e, -51.0 - h + e],
        [101.0 + h, 51.0 + h],
        2.0 * h,
        1 << 30,
    )
    .unwrap();
    compare(&part, &shifted);
    // Across the common edge, finely: 1 um apart over +-0.2 mm at x = 37.3.
    let across = Grid::covering([37.3, -0.2], [37.301, 0.2], 0.001, 1 << 30).unwrap();
    let tops = compare(&part, &across);
    assert!(tops[0] > 150 && tops[1] > 150, "{tops:?}");
}
