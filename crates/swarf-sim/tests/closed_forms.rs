//! The simulation against closed forms at cell centres (issue 5, "Prove it").

use swarf_geom::{Part, Patch, Point3};
use swarf_sim::sweep::SimTool;
use swarf_sim::{
    Design, Dexel, Grid, Quiet, SimOptions, StockInit, StockSpec, VerifyOptions, simulate, verify,
};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Motion, MotionKind, Program};

fn mv(kind: MotionKind, a: [f64; 3], b: [f64; 3], line: usize) -> Motion {
    Motion {
        kind,
        start: Pose::vertical(Point3::from(a)),
        end: Pose::vertical(Point3::from(b)),
        feed: 300.0,
        line,
    }
}

fn feed(a: [f64; 3], b: [f64; 3], line: usize) -> Motion {
    mv(MotionKind::Linear, a, b, line)
}

/// A grid whose cell centres sit on multiples of 1/8 mm.
fn grid(half_x: f64, half_y: f64) -> Grid {
    let c = 0.125;
    Grid::covering(
        [-half_x - c / 2.0, -half_y - c / 2.0],
        [half_x + c / 2.0, half_y + c / 2.0],
        c,
        1 << 30,
    )
    .unwrap()
}

fn run(cutter: &str, top: f64, g: Grid, moves: &[Motion]) -> Dexel {
    let tool = SimTool::new(&cutter.parse::<Cutter>().unwrap()).unwrap();
    let mut d = Dexel::new(g, StockInit::Box { top }).unwrap();
    simulate(&mut d, &tool, moves, &SimOptions::default(), &Quiet);
    d
}

#[test]
fn two_ball_passes_leave_the_scallop() {
    let (r, s) = (4.0, 2.0);
    let g = grid(10.0, 6.0);
    let moves = [
        feed([-12.0, -s / 2.0, 0.0], [12.0, -s / 2.0, 0.0], 1),
        feed([12.0, s / 2.0, 0.0], [-12.0, s / 2.0, 0.0], 2),
    ];
    let d = run("ball:d=8", 5.0, g, &moves);
    let h = |rho: f64| {
        if rho <= r {
            r - (r * r - rho * rho).sqrt()
        } else {
            f64::INFINITY
        }
    };
    for j in 0..g.ny {
        for i in 0..g.nx {
            let y = g.y(j);
            let want = h((y - s / 2.0).abs()).min(h((y + s / 2.0).abs())).min(5.0);
            assert!((d.height(i, j) - want).abs() < 1e-9, "y {y}");
        }
    }
    let (_, mid) = g.cell_of(0.0, 0.0).unwrap();
    let scallop = r - (r * r - s * s / 4.0).sqrt();
    assert!((d.height(g.nx / 2, mid) - scallop).abs() < 1e-9);
}

#[test]
fn flat_plunge_leaves_a_disc() {
    let g = grid(6.0, 6.0);
    let moves = [feed([0.5, 0.25, 5.0], [0.5, 0.25, -1.0], 1)];
    let d = run("flat:d=6", 0.0, g, &moves);
    for j in 0..g.ny {
        for i in 0..g.nx {
            let [x, y] = g.centre(i, j);
            let inside = (x - 0.5).hypot(y - 0.25) <= 3.0;
            assert_eq!(d.height(i, j), if inside { -1.0 } else { 0.0 }, "{x} {y}");
        }
    }
}

#[test]
fn bull_nose_pass_leaves_its_profile() {
    let g = grid(10.0, 7.0);
    let moves = [feed([-15.0, 0.0, -1.0], [15.0, 0.0, -1.0], 1)];
    let d = run("bull:d=10,r=2", 0.0, g, &moves);
    let h = |rho: f64| {
        if rho <= 3.0 {
            0.0
        } else if rho <= 5.0 {
            2.0 - (4.0 - (rho - 3.0) * (rho - 3.0)).sqrt()
        } else {
            f64::INFINITY
        }
    };
    for j in 0..g.ny {
        let want = (-1.0 + h(g.y(j).abs())).min(0.0);
        for i in 0..g.nx {
            assert!((d.height(i, j) - want).abs() < 1e-9, "y {}", g.y(j));
        }
    }
}

#[test]
fn one_long_move_equals_a_thousand_small_ones() {
    for cutter in [
        "ball:d=6",
        "bull:d=8,r=1.5",
        "flat:d=4",
        "cone:d=6,angle=90",
    ] {
        let g = grid(12.0, 8.0);
        // End points off the cell lattice: no centre at exactly the radius from them,
        // where rounding alone decides whether a tool touches.
        let (a, b) = ([-9.01, -5.03, -0.8], [9.02, 5.47, 0.6]);
        let long = run(cutter, 1.0, g, &[feed(a, b, 1)]);
        let pieces: Vec<Motion> = (0..1000)
            .map(|k| {
                let at = |t: f64| [0, 1, 2].map(|c| a[c] + (b[c] - a[c]) * t);
                feed(at(k as f64 / 1000.0), at((k + 1) as f64 / 1000.0), k + 1)
            })
            .collect();
        let split = run(cutter, 1.0, g, &pieces);
        let worst = long
            .heights()
            .iter()
            .zip(split.heights())
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "{cutter}: {worst}");
        // A Z-map that only places the tool at the end points (no sweep) is far off.
        let ends = run(cutter, 1.0, g, &[feed(a, a, 1), feed(b, b, 2)]);
        let gap = long
            .heights()
            .iter()
            .zip(ends.heights())
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        assert!(gap > 0.5, "{cutter}: {gap}");
    }
}

/// A flat design z = 0 over [0, 40] x [0, 20], a ball raster on it, and the same with
/// one CL point pushed 0.05 mm down.
fn raster(plant: bool) -> (Program, usize) {
    let mut program = Program::new("raster");
    let mut planted_line = 0;
    let mut at = [0.0625, 0.0625, 5.0];
    let mut go = |to: [f64; 3], kind: MotionKind, program: &mut Program| {
        let line = program.motions.len() + 1;
        program.motions.push(mv(kind, at, to, line));
        at = to;
        line
    };
    for k in 0..14 {
        let y = 0.0625 + 1.5 * k as f64;
        go([-4.0, y, 5.0], MotionKind::Rapid, &mut program);
        go([-4.0, y, 0.0], MotionKind::Linear, &mut program);
        for s in 0..=22 {
            let planted = plant && k == 6 && s == 12;
            let x = if planted {
                20.0625
            } else {
                -4.0 + 2.0 * s as f64
            };
            let z = if planted { -0.05 } else { 0.0 };
            let l = go([x, y, z], MotionKind::Linear, &mut program);
            if planted {
                planted_line = l;
            }
        }
        go([40.0, y, 5.0], MotionKind::Rapid, &mut program);
    }
    (program, planted_line)
}

fn flat_part() -> Part {
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    Part {
        name: "plane".into(),
        faces: Vec::new(),
        patches: vec![
            Patch::bezier(
                [1, 1],
                vec![p(0.0, 0.0), p(0.0, 20.0), p(40.0, 0.0), p(40.0, 20.0)],
            )
            .unwrap(),
        ],
    }
}

/// The flat part, a ball d = 6 and cells of 0.125 mm over a 0.5 mm offset stock.
fn planted_setup() -> (Part, Cutter, VerifyOptions) {
    let opts = VerifyOptions {
        cell: Some(0.125),
        stock: StockSpec::Offset { allowance: 0.5 },
        ..VerifyOptions::default()
    };
    (flat_part(), "ball:d=6".parse().unwrap(), opts)
}

#[test]
fn a_planted_gouge_is_found_where_and_as_deep_as_planted() {
    let (part, cutter, opts) = planted_setup();
    let (clean, _) = raster(false);
    let v = verify(Design::Part(&part), &clean, &cutter, &opts, &Quiet).unwrap();
    let s = &v.deviation.summary;
    assert_eq!(s.gouge.cells, 0, "{:?}", s.gouges.first());
    assert!(s.min.unwrap() > -1e-9);

    let (dirty, line) = raster(true);
    let v = verify(Design::Part(&part), &dirty, &cutter, &opts, &Quiet).unwrap();
    let s = &v.deviation.summary;
    assert_eq!(s.gouge.regions, 1);
    let g = &s.gouges[0];
    assert!((g.worst + 0.05).abs() < 1e-9, "{g:?}");
    assert_eq!(g.at[0..2], [20.0625, 9.0625]);
    assert_eq!(g.line, Some(line));
    // The moves in and out of the planted point cut a tapered groove: depth
    // D(t) = D0 (1 - t / L) along each (L their lengths), gouging where the ball's
    // section D - y^2 / (2 r) is below -tol, so its area is about
    // sum over both moves of 2 sqrt(2 r D0) L (2/3) (1 - tol / D0)^1.5.
    let (r, d0, tol) = (3.0, 0.05, 0.01);
    let lengths = 2.0625f64.hypot(d0) + 1.9375f64.hypot(d0);
    let area = 2.0 * (2.0 * r * d0).sqrt() * lengths * (2.0 / 3.0) * (1.0 - tol / d0).powf(1.5);
    assert!(
        (g.area_mm2 - area).abs() < 0.1 * area,
        "{} vs {area}",
        g.area_mm2
    );
}

/// Issue 14's three-line program: a positioning move to the assumed start (the
/// origin), then two feeds at Z0 through a box stock 70 mm high. Both feeds cut down
/// to the plane (a flat d = 6 at Z0 leaves 0 under its path); before the fix the
/// first feed was taken for the program's unknown first move and cut nothing.
#[test]
fn the_first_feed_after_a_move_to_the_start_cuts() {
    let text = "G0 X0 Y0 Z0\nG1 X20 Y20 F100\nG1 X40 Y20\n";
    let program = swarf_nc::read::parse_gcode(
        text,
        "first.ngc",
        &swarf_nc::read::GcodeReadOptions::default(),
    )
    .unwrap();
    assert_eq!(program.motions.len(), 3);
    let (part, _, opts) = planted_setup();
    let cutter: Cutter = "flat:d=6".parse().unwrap();
    let opts = VerifyOptions {
        stock: StockSpec::Box { top: Some(70.0) },
        ..opts
    };
    let v = verify(Design::Part(&part), &program, &cutter, &opts, &Quiet).unwrap();
    for (x, y) in [(5.0, 5.0), (10.0, 10.0), (15.0, 15.0), (30.0, 19.0)] {
        let (i, j) = v.grid.cell_of(x, y).unwrap();
        assert!(
            v.stock.height(i, j).abs() < 1e-9,
            "({x}, {y}): {}",
            v.stock.height(i, j)
        );
    }
    let (i, j) = v.grid.cell_of(30.0, 10.0).unwrap();
    assert_eq!(v.stock.height(i, j), 70.0);
}

/// A window verifies the cells it covers as the whole design does, finds the planted
/// gouge inside it, and nothing from outside it; a window off the design is refused.
#[test]
fn a_window_verifies_its_cells_as_the_whole_design_does() {
    let (part, cutter, opts) = planted_setup();
    let (dirty, _) = raster(true);
    let whole = verify(Design::Part(&part), &dirty, &cutter, &opts, &Quiet).unwrap();
    let inside = |lo: [f64; 2], hi: [f64; 2]| VerifyOptions {
        window: Some([lo, hi]),
        ..opts.clone()
    };
    let w = verify(
        Design::Part(&part),
        &dirty,
        &cutter,
        &inside([15.0, 5.0], [25.0, 12.0]),
        &Quiet,
    )
    .unwrap();
    assert_eq!((w.grid.nx, w.grid.ny), (80, 56));
    for j in 0..w.grid.ny {
        for i in 0..w.grid.nx {
            let (x, y) = (w.grid.x(i), w.grid.y(j));
            let (a, b) = whole.grid.cell_of(x, y).unwrap();
            assert!((whole.grid.x(a) - x).abs() < 1e-9 && (whole.grid.y(b) - y).abs() < 1e-9);
            assert_eq!(
                w.stock.height(i, j),
                whole.stock.height(a, b),
                "cell ({x}, {y})"
            );
        }
    }
    assert_eq!(w.deviation.summary.gouge.regions, 1);
    let away = verify(
        Design::Part(&part),
        &dirty,
        &cutter,
        &inside([30.0, 0.0], [60.0, 5.0]),
        &Quiet,
    )
    .unwrap();
    assert_eq!(away.deviation.summary.gouge.cells, 0);
    assert!(away.grid.x(away.grid.nx - 1) < 40.0);
    let e = verify(
        Design::Part(&part),
        &dirty,
        &cutter,
        &inside([50.0, 0.0], [60.0, 5.0]),
        &Quiet,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("window") && e.contains("overlaps the design"),
        "{e}"
    );
}

#[test]
fn tilted_ball_passes_leave_the_same_scallop_within_the_sampling_bound() {
    // A ball tilted 20 degrees about y is still a sphere at its tip: two five-axis
    // passes s apart leave r - sqrt(r^2 - s^2 / 4), up to the stated sampling bound.
    // (passes off the cell lattice, so that no centre is exactly tangent to the tool,
    // where a distance threshold decides)
    let (r, s, tilt) = (2.0, 2.06, 20f64.to_radians());
    let axis = swarf_geom::Vec3::new(tilt.sin(), 0.0, tilt.cos());
    let pose = |x: f64, y: f64| Pose::new(Point3::new(x, y, r) - axis * r, axis).unwrap();
    let tilted = |a: Pose, b: Pose, line: usize| Motion {
        kind: MotionKind::Linear,
        start: a,
        end: b,
        feed: 300.0,
        line,
    };
    let moves = [
        tilted(pose(-7.0, -s / 2.0), pose(7.0, -s / 2.0), 1),
        tilted(pose(7.0, s / 2.0), pose(-7.0, s / 2.0), 2),
    ];
    let g = grid(4.0, 3.0);
    let tool = SimTool::new(&"ball:d=4".parse::<Cutter>().unwrap()).unwrap();
    let mut d = Dexel::new(g, StockInit::Box { top: 3.0 }).unwrap();
    let opts = SimOptions {
        sample_tol: 0.01,
        ..SimOptions::default()
    };
    let report = simulate(&mut d, &tool, &moves, &opts, &Quiet);
    assert!(report.max_sample_bound <= 0.01 && report.sampled_motions == 2);
    let h = |rho: f64| {
        if rho <= r {
            r - (r * r - rho * rho).sqrt()
        } else {
            3.0
        }
    };
    for j in 0..g.ny {
        let y = g.y(j);
        let want = h((y - s / 2.0).abs()).min(h((y + s / 2.0).abs())).min(3.0);
        // Between two of the n + 1 tool positions of a pass, l = 14 / n apart, the
        // column halfway sees the ball at l / 2 along the pass: a tube of radius
        // sqrt(r^2 - l^2 / 4). The true surface's point there is sqrt(r^2 + l^2 / 4)
        // from both balls' centres: the 3D gap the stated bound must cover.
        let l = 14.0 / (report.primitives / 2 - 1) as f64;
        let shrunk = (r * r - 0.25 * l * l).sqrt();
        assert!((r * r + 0.25 * l * l).sqrt() - r <= report.max_sample_bound);
        let hi = |rho: f64| {
            if rho < shrunk {
                r - (shrunk * shrunk - rho * rho).sqrt()
            } else {
                3.0
            }
        };
        let most = hi((y - s / 2.0).abs())
            .min(hi((y + s / 2.0).abs()))
            .min(3.0);
        for i in 0..g.nx {
            let got = d.height(i, j);
            // The march stops within 1e-9 mm (3D) of the tool: vertically 1e-9 over
            // the cosine of the slope, which on the ball's flank is 1e-7 at most here.
            assert!(
                got >= want - 1e-7 && got <= most + 1e-9,
                "y {y}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn a_mesh_design_and_a_mesh_stock_give_the_patch_results() {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let plane = swarf_geom::TriMesh::from_triangles(&[
        [p(0.0, 0.0, 0.0), p(40.0, 0.0, 0.0), p(40.0, 20.0, 0.0)],
        [p(0.0, 0.0, 0.0), p(40.0, 20.0, 0.0), p(0.0, 20.0, 0.0)],
    ]);
    let lid = swarf_geom::TriMesh::from_triangles(&[
        [p(-5.0, -5.0, 0.5), p(45.0, -5.0, 0.5), p(45.0, 25.0, 0.5)],
        [p(-5.0, -5.0, 0.5), p(45.0, 25.0, 0.5), p(-5.0, 25.0, 0.5)],
    ]);
    let cutter: Cutter = "ball:d=6".parse().unwrap();
    let (dirty, line) = raster(true);
    let opts = VerifyOptions {
        cell: Some(0.125),
        stock: StockSpec::Mesh(lid),
        ..VerifyOptions::default()
    };
    let v = verify(Design::Mesh(&plane), &dirty, &cutter, &opts, &Quiet).unwrap();
    let s = &v.deviation.summary;
    assert_eq!((s.gouge.regions, s.gouges[0].line), (1, Some(line)));
    assert!((s.gouges[0].worst + 0.05).abs() < 1e-9);
    let part = flat_part();
    let w = verify(Design::Part(&part), &dirty, &cutter, &opts, &Quiet).unwrap();
    assert_eq!(v.stock.heights(), w.stock.heights());
    assert_eq!(v.deviation.summary, w.deviation.summary);
    // Program figures: feed moves at their feeds, rapids at the machine's rate.
    let p = &v.program;
    let want = 60.0 * (p.cutting_length_mm / 300.0) + 60.0 * p.rapid_length_mm / 5000.0;
    assert!(p.time_s > 0.0 && (p.time_s - want).abs() < 1e-9 * want);
    assert_eq!((p.passes, p.rapids), (14, 28));
}
