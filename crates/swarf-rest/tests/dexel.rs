//! Rest detection and cleanup against our own dexel simulation and closed forms
//! (issue 11, "Prove it"): finishing programs and their cleanup are written as
//! G-code, read back, and cut on one Z-map stock.

use geo::{Contains, Point};
use swarf_geom::TriMesh;
use swarf_nc::read::{GcodeReadOptions, parse_gcode};
use swarf_path::Cutting;
use swarf_path::strategy::raster::RasterParams;
use swarf_rest::{CleanupParams, Pattern, RegionParams, RestRegion, Source, detect, plan_cleanup};
use swarf_sim::deviation::vertical_deviation;
use swarf_sim::mow::normal_deviation;
use swarf_sim::{
    Design, DesignSurface, Dexel, Grid, Quiet, SimOptions, SimTool, StockInit, simulate,
};
use swarf_tool::Cutter;
use swarf_toolpath::Toolpath;

const TOL: f64 = 0.01;

fn cutter(s: &str) -> Cutter {
    s.parse().unwrap()
}

/// Raster finishing along X with `tool` at scallop `h`, refined to half the
/// tolerance (the raster's midpoint test lets a chord over a convex edge dip up to a
/// quarter more than it measures: at the full tolerance the grooves' top edges show
/// 0.0125 mm gouges).
fn finish(mesh: &TriMesh, tool: &Cutter, h: f64) -> swarf_path::Plan {
    let mut p = RasterParams {
        scallop: Some(h),
        ..RasterParams::default()
    };
    p.finish.tolerance = 0.5 * TOL;
    swarf_path::strategy::raster::plan(mesh, &Cutting::new(*tool), &p).unwrap()
}

/// A cut stock: heights after the programs, the design heights, normals and the
/// vertical and normal deviations per cell.
struct Cut {
    grid: Grid,
    design: Vec<f64>,
    normals: Vec<[f32; 3]>,
    vertical: Vec<f64>,
    normal: Vec<f64>,
}

/// Cuts `stages` (tool paths with their tools) in order on a block over `grid`.
fn cut(mesh: &TriMesh, grid: Grid, top: f64, stages: &[(&Toolpath, &Cutter)]) -> Cut {
    let mut stock = Dexel::new(grid, StockInit::Box { top }).unwrap();
    for (tp, tool) in stages {
        let text = swarf_nc::write_gcode(&tp.moves(), &tp.feeds, &Default::default()).unwrap();
        let program = parse_gcode(&text, "stage", &GcodeReadOptions::default()).unwrap();
        let opts = SimOptions {
            sample_tol: 0.25 * TOL,
            known_start: false,
            ..SimOptions::default()
        };
        simulate(
            &mut stock,
            &SimTool::new(tool).unwrap(),
            &program.motions,
            &opts,
            &Quiet,
        );
    }
    let field = DesignSurface::new(Design::Mesh(mesh))
        .unwrap()
        .heights(&grid, true, &Quiet);
    let vertical = vertical_deviation(stock.heights(), &field.heights);
    let normals = field.normals.unwrap();
    let normal = normal_deviation(&grid, stock.heights(), &field.heights, &normals, &vertical).0;
    Cut {
        grid,
        design: field.heights,
        normals,
        vertical,
        normal,
    }
}

fn grid(x: [f64; 2], y: [f64; 2], cell: f64) -> Grid {
    Grid::covering([x[0], y[0]], [x[1], y[1]], cell, 1 << 30).unwrap()
}

/// Cells whose centre lies inside one of the polygons `inside` picks from each
/// region.
fn mask(g: &Grid, regions: &[RestRegion], raw: bool) -> Vec<bool> {
    (0..g.len())
        .map(|k| {
            let [x, y] = g.centre(k % g.nx, k / g.nx);
            let p = Point::new(x, y);
            regions.iter().any(|r| {
                if raw {
                    r.raw.contains(&p)
                } else {
                    r.boundary.contains(&p)
                }
            })
        })
        .collect()
}

/// Intersection over union of `a` and `b`, and the fraction of `b` inside `a`.
fn iou_recall(a: &[bool], b: &[bool]) -> (f64, f64) {
    let both = a.iter().zip(b).filter(|(x, y)| **x && **y).count() as f64;
    let either = a.iter().zip(b).filter(|(x, y)| **x || **y).count() as f64;
    let nb = b.iter().filter(|y| **y).count() as f64;
    (both / either, both / nb)
}

#[test]
fn v_grooves_dexel_and_detection_agree_with_the_closed_form() {
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let ball = cutter("ball:d=12");
    let plan = finish(&mesh, &ball, TOL);
    let h = plan.report.predicted_max_scallop.unwrap();
    let g = grid([0.0, 140.0], [20.0, 40.0], 0.1);
    let c = cut(&mesh, g, 10.5, &[(&plan.toolpath, &ball)]);
    let det = detect(
        &mesh,
        &ball,
        Source::Contacts(&plan.double_contacts),
        TOL,
        &RegionParams::default(),
    )
    .unwrap();
    assert_eq!(det.regions.len(), 3);
    for (x, deg) in [(20.0, 60.0f64), (55.0, 90.0), (105.0, 120.0)] {
        let exact = 6.0 / (deg.to_radians() / 2.0).sin() - 6.0;
        // The dexel's deepest rest near the groove's bottom line, within one cell
        // (the flank rises cot(a/2) per mm across the cell).
        let worst = (0..c.grid.len())
            .filter(|k| (c.grid.centre(k % c.grid.nx, 0)[0] - x).abs() < 1.0)
            .map(|k| c.vertical[k])
            .fold(f64::NEG_INFINITY, f64::max);
        let slack = c.grid.cell / (deg.to_radians() / 2.0).tan() + TOL;
        assert!(
            (worst - exact).abs() <= slack,
            "{deg}: dexel {worst} vs {exact}"
        );
        let r = det
            .regions
            .iter()
            .find(|r| (r.deepest.x - x).abs() < 1.0)
            .unwrap();
        assert!(
            (r.depth - exact).abs() < 1e-6,
            "{deg}: detected {} vs {exact}",
            r.depth
        );
    }
    // Detected regions against the dexel's excess mask above scallop + tolerance.
    let rest: Vec<bool> = c.vertical.iter().map(|v| *v > h + TOL).collect();
    let (iou, _) = iou_recall(&mask(&c.grid, &det.regions, true), &rest);
    let (_, recall) = iou_recall(&mask(&c.grid, &det.regions, false), &rest);
    eprintln!("v-grooves: IoU {iou:.3} (raw regions), recall {recall:.4} (with overlap)");
    assert!(iou >= 0.8, "IoU {iou}");
    assert!(recall >= 0.99, "recall {recall}");
}

/// The ideal cleanup of a groove part (extruded along y): the cleanup tool dropped
/// everywhere along a line across the grooves, sampled every 0.005 mm, and the
/// lowest its lower surface reaches above each x (an oracle independent of the
/// planner and the simulator).
fn ideal_across(mesh: &TriMesh, tool: &Cutter, y: f64, xs: &[f64]) -> Vec<f64> {
    let dropper = swarf_tool::drop::MeshDropper::new(mesh, tool);
    let mut s = swarf_tool::drop::DropScratch::default();
    let r = tool.radius();
    let profile = tool.profile();
    let cls: Vec<(f64, f64)> = (0..=28_000)
        .map(|i| f64::from(i) * 0.005)
        .filter_map(|x| dropper.drop(x, y, &mut s).map(|d| (x, d.z)))
        .collect();
    xs.iter()
        .map(|&x| {
            cls.iter()
                .filter(|(c, _)| (c - x).abs() <= r)
                .map(|(c, z)| {
                    z + profile
                        .height_at_radius((c - x).abs())
                        .unwrap_or(f64::INFINITY)
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

#[test]
fn flow_cut_leaves_no_more_than_the_ideal_cleanup() {
    // Enough parallel passes to cover the widest groove's rest (5.2 mm each side of
    // the bottom; 0.4 mm apart along a 60 degree flank is 0.2 mm in XY).
    cleanup_leaves_no_more_than_the_ideal(Pattern::FlowCut, 30);
}

#[test]
fn follow_pocket_leaves_no_more_than_the_ideal_cleanup() {
    cleanup_leaves_no_more_than_the_ideal(Pattern::FollowPocket, 0);
}

fn cleanup_leaves_no_more_than_the_ideal(pattern: Pattern, passes: usize) {
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let (ball, small) = (cutter("ball:d=12"), cutter("ball:d=4"));
    let plan = finish(&mesh, &ball, TOL);
    let det = detect(
        &mesh,
        &ball,
        Source::Reference,
        TOL,
        &RegionParams::default(),
    )
    .unwrap();
    let cutting = Cutting::new(small);
    let params = CleanupParams {
        pattern,
        passes,
        ..CleanupParams::new(TOL)
    };
    let clean = plan_cleanup(&mesh, &det.regions, &ball, &cutting, &params).unwrap();
    let g = grid([0.0, 140.0], [28.0, 32.0], 0.1);
    let c = cut(&mesh, g, 10.5, &[(&plan.toolpath, &ball), (&clean, &small)]);
    let xs: Vec<f64> = (0..c.grid.nx).map(|i| c.grid.x(i)).collect();
    let ideal = ideal_across(&mesh, &small, 30.0, &xs);
    let h = plan.report.predicted_max_scallop.unwrap();
    let gouges: Vec<[f64; 3]> = (0..c.grid.len())
        .filter(|&k| c.vertical[k] < -TOL)
        .map(|k| {
            let [x, y] = c.grid.centre(k % c.grid.nx, k / c.grid.nx);
            [x, y, c.vertical[k]]
        })
        .collect();
    assert!(
        gouges.is_empty(),
        "{} gouges: {:?}",
        gouges.len(),
        &gouges[..gouges.len().min(12)]
    );
    let mut worst = f64::NEG_INFINITY;
    for k in 0..c.grid.len() {
        let i = k % c.grid.nx;
        let ideal_rest = ideal[i] - c.design[k];
        // Scallops (normal to the flank) stand h / n_z tall: the finishing path's
        // where the cleanup does not reach, the cleanup's own on top of the ideal.
        let nz = f64::from(c.normals[k][2]);
        let excess = c.vertical[k] - (ideal_rest + TOL / nz).max(h / nz);
        worst = worst.max(excess);
        assert!(
            excess <= TOL,
            "cell {k} x {}: rest {} ideal {ideal_rest}",
            xs[i],
            c.vertical[k]
        );
        assert!(
            c.vertical[k] >= -TOL,
            "gouge at x {}: {}",
            xs[i],
            c.vertical[k]
        );
    }
    assert!(worst.is_finite());
}

#[test]
fn fillet_pocket_rest_and_its_follow_pocket_cleanup() {
    let mesh = swarf_io::builtin_mesh("fillet-pocket").unwrap();
    let (ball, small) = (cutter("ball:d=12"), cutter("ball:d=4"));
    let det = detect(
        &mesh,
        &ball,
        Source::Reference,
        TOL,
        &RegionParams::default(),
    )
    .unwrap();
    // Along the straight walls (away from the corners) the rest on the fillet's
    // bisector is (R - rho)(sqrt 2 - 1).
    let exact = 3.0 * (2f64.sqrt() - 1.0);
    let along_walls: Vec<f64> = det
        .regions
        .iter()
        .flat_map(|r| &r.pairs)
        .filter(|p| (p.cl.x - 50.0).abs() < 20.0 && (p.cl.y - 26.0).abs() < 1.0)
        .map(|p| p.depth)
        .collect();
    assert!(!along_walls.is_empty());
    for d in &along_walls {
        assert!(
            (d - exact).abs() < 2.0 * swarf_io::MESH_PART_CHORD,
            "{d} vs {exact}"
        );
    }
    let plan = finish(&mesh, &ball, TOL);
    let cutting = Cutting::new(small);
    let params = CleanupParams {
        pattern: Pattern::FollowPocket,
        passes: 0,
        ..CleanupParams::new(TOL)
    };
    let clean = plan_cleanup(&mesh, &det.regions, &ball, &cutting, &params).unwrap();
    // A window across the floor, the fillet and the wall x = 20, which the raster
    // passes (along X) cross: there the finishing ball reaches its bitangent
    // position (passes along a wall stop up to a stepover short of it).
    let g = grid([18.0, 32.0], [32.0, 48.0], 0.1);
    let before = cut(&mesh, g, 20.5, &[(&plan.toolpath, &ball)]);
    // Cells whose design normal is within 5 degrees of the fillet's bisector.
    let on_bisector = |k: usize| {
        let nz = f64::from(before.normals[k][2]);
        (nz - std::f64::consts::FRAC_1_SQRT_2).abs() < 0.06
    };
    let bisector = (0..before.grid.len())
        .filter(|&k| on_bisector(k))
        .map(|k| before.normal[k])
        .filter(|v| v.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        (bisector - exact).abs() <= before.grid.cell,
        "dexel {bisector} vs {exact}"
    );
    let after = cut(&mesh, g, 20.5, &[(&plan.toolpath, &ball), (&clean, &small)]);
    let worst = after
        .normal
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    let least = after
        .normal
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    let at = (0..after.grid.len())
        .find(|&k| after.normal[k] == worst)
        .unwrap();
    let [x, y] = after.grid.centre(at % after.grid.nx, at / after.grid.nx);
    assert!(
        worst <= TOL + TOL,
        "rest after cleanup {worst} at {x} {y} design {} n {:?} v {}",
        after.design[at],
        after.normals[at],
        after.vertical[at]
    );
    assert!(least >= -TOL, "gouge {least}");
}
