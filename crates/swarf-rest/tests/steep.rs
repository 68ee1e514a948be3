//! Steep rest and its Z-level cleanup (issue 12): the angle against closed forms,
//! the rest against the boss's analytic wall areas, and the raster with its cleanup
//! cut on our dexel stock.

use swarf_nc::read::{GcodeReadOptions, parse_gcode};
use swarf_path::strategy::raster::RasterParams;
use swarf_path::strategy::waterline::WaterlineParams;
use swarf_path::{Cutting, Finish};
use swarf_rest::steep::steep_rest_angle;
use swarf_rest::{RasterParent, SteepParams, plan_steep};
use swarf_sim::{Design, Quiet, Stage, VerifyOptions, verify_stages};
use swarf_testkit::boss::reach;
use swarf_tool::Cutter;
use swarf_toolpath::Toolpath;

const TOL: f64 = 0.005;

fn cutter(s: &str) -> Cutter {
    s.parse().unwrap()
}

fn finish() -> Finish {
    Finish {
        tolerance: TOL,
        ..Finish::default()
    }
}

/// The boss's raster along x with ball d = 10 at the flat-model step for 0.01 mm
/// (parts/README.md).
fn boss_parent(feed_angle: f64) -> RasterParent {
    RasterParent {
        tool: cutter("ball:d=10"),
        spacing: 0.632,
        feed_angle,
    }
}

/// The steep cleanup's tool.
fn ball10() -> Cutting {
    Cutting::new(cutter("ball:d=10"))
}

fn steep(threshold: f64, h: f64) -> SteepParams {
    SteepParams {
        waterline: WaterlineParams {
            finish: finish(),
            ..WaterlineParams::new(h)
        },
        threshold,
        overlap: 1.0,
    }
}

#[test]
fn the_rest_angle_is_the_closed_form() {
    // Ball: the passes s / cos a apart along the slope leave R - sqrt(R² - w²/4).
    for (r, s, t) in [(5.0, 0.632, 0.015), (5.0, 0.632, 0.06), (3.0, 0.3, 0.01)] {
        let parent = RasterParent {
            tool: cutter(&format!("ball:d={}", 2.0 * r)),
            spacing: s,
            feed_angle: 0.0,
        };
        let a: f64 = steep_rest_angle(&parent, t).unwrap();
        let exact = (s / (2.0 * (2.0 * r * t - t * t).sqrt())).acos();
        assert!((a - exact).abs() < 1e-7, "ball {r} {s} {t}: {a} vs {exact}");
    }
    // Flat end: the rim's V leaves w sin a cos a = s sin a.
    let parent = RasterParent {
        tool: cutter("flat:d=10"),
        spacing: 1.0,
        feed_angle: 0.0,
    };
    let a = steep_rest_angle(&parent, 0.25).unwrap();
    assert!((a - 0.25f64.asin()).abs() < 1e-7, "flat: {a}");
    // A threshold below what the parent leaves on a level floor is refused.
    let e = steep_rest_angle(&boss_parent(0.0), 0.005)
        .unwrap_err()
        .to_string();
    assert!(e.contains("threshold") && e.contains("level floor"), "{e}");
}

#[test]
fn the_boss_rest_is_the_walls_above_the_angle() {
    let mesh = swarf_io::builtin_mesh("boss").unwrap();
    // 0.06 mm: the 65-degree walls keep 0.056 (parts/README.md), the 80 and 90 go.
    // 0.015: all four walls.
    for (t, walls) in [
        (0.06, &[80.0, 90.0][..]),
        (0.015, &[45.0, 65.0, 80.0, 90.0]),
    ] {
        let (rest, passes) =
            plan_steep(&mesh, &boss_parent(0.0), &ball10(), &steep(t, 0.01)).unwrap();
        let surface: f64 = walls
            .iter()
            .map(|a: &f64| 1600.0 / a.to_radians().sin())
            .sum();
        let xy: f64 = walls
            .iter()
            .map(|a: &f64| 1600.0 / a.to_radians().tan())
            .sum();
        eprintln!(
            "threshold {t}: angle {:.3} deg, surface {:.3} (exact {surface:.3}), xy {:.3} (exact {xy:.3}), {} passes",
            rest.angle.to_degrees(),
            rest.region.surface_area,
            rest.region.xy_area,
            passes.len()
        );
        assert!((rest.region.surface_area - surface).abs() < 1e-6 * surface);
        // The XY region is the walls' projection plus the cells the vertical walls
        // meet, which are steep whole (two sides, 80 long, cells of a quarter radius).
        assert!(rest.region.xy_area >= xy - 1e-3);
        assert!(rest.region.xy_area <= xy + 2.0 * 80.0 * 1.25 + 1e-3);
        assert!(!passes.is_empty());
        // Every level stays on the steep walls and the overlap past them.
        for p in passes.iter().flat_map(|p| &p.points) {
            let c = p.contact.unwrap().point;
            assert!(c.z > -1e-6 && c.z < 10.0 + 1e-6);
        }
    }
}

#[test]
fn passes_running_down_the_walls_leave_no_steep_rest() {
    let mesh = swarf_io::builtin_mesh("boss").unwrap();
    let parent = boss_parent(90f64.to_radians());
    let (rest, passes) = plan_steep(&mesh, &parent, &ball10(), &steep(0.015, 0.01)).unwrap();
    assert_eq!((rest.region.cells, passes.len()), (0, 0));
    assert!(rest.level_step.is_none());
}

fn program(tp: &Toolpath, name: &str) -> swarf_nc::read::Program {
    let text = swarf_nc::write_gcode(&tp.moves(), &tp.feeds, &Default::default()).unwrap();
    parse_gcode(&text, name, &GcodeReadOptions::default()).unwrap()
}

/// The flat-model raster leaves 0.020 to 0.343 mm on the boss's walls and misses the
/// vertical ones; with its steep cleanup every cell a ball reaches is within
/// `h + tol`, and nothing is gouged.
#[test]
fn the_cleanup_brings_the_walls_within_the_scallop() {
    let mesh = swarf_io::builtin_mesh("boss").unwrap();
    let tool = cutter("ball:d=10");
    let h = 0.01;
    let raster = RasterParams {
        finish: finish(),
        scallop: Some(h),
        ..RasterParams::default()
    };
    let rows = swarf_path::strategy::raster::plan(&mesh, &Cutting::new(tool), &raster).unwrap();
    let spacing = rows.report.side_step_range.unwrap()[0];
    let parent = RasterParent {
        spacing,
        ..boss_parent(0.0)
    };
    let (rest, passes) = plan_steep(&mesh, &parent, &ball10(), &steep(0.015, h)).unwrap();
    assert!(rest.region.cells > 0);
    let cleanup = Toolpath {
        linking: rows.toolpath.linking,
        feeds: rows.toolpath.feeds,
        passes,
    };
    let opts = VerifyOptions {
        cell: Some(0.05),
        tol: 2.0 * TOL,
        allowed_excess: h,
        along_normals: true,
        ..VerifyOptions::default()
    };
    let measure = |stages: &[Stage<'_>]| {
        let v = verify_stages(Design::Mesh(&mesh), stages, &opts, &Quiet).unwrap();
        let g = &v.grid;
        reach(&v.deviation.values, |k| [g.x(k % g.nx), g.y(k / g.nx)], 5.0)
    };
    let (p_rows, p_clean) = (
        program(&rows.toolpath, "raster"),
        program(&cleanup, "steep"),
    );
    let before = measure(&[Stage {
        program: &p_rows,
        cutter: &tool,
    }]);
    let after = measure(&[
        Stage {
            program: &p_rows,
            cutter: &tool,
        },
        Stage {
            program: &p_clean,
            cutter: &tool,
        },
    ]);
    eprintln!("boss raster: {before:?}\nwith steep cleanup: {after:?}");
    // A Z-map sees the scallops on the 80-degree walls only in part (0.087 of 0.343
    // at 0.05 mm cells) and the vertical walls not at all: still far above h + tol.
    assert!(before.worst.0 > 0.05, "{before:?}");
    assert!(after.counted > 3_000_000);
    assert!(after.deepest >= -2.0 * TOL, "gouge {}", after.deepest);
    assert!(after.worst.0 <= h + 2.0 * TOL, "{:?}", after.worst);
}
