//! The machined surface of the die experiment (thesis 000 ch. 6 and 8) by generating
//! curves against the dexel (Z-map) verifier of swarf-sim, on section lines `x = c`:
//! `cargo run --release -p swarf-fiveaxis --example die_dexel -- [alpha|auto] [cell] [sample_tol] [meridians] [x...]`.
//! Prints, per section, the largest difference of the two machined heights and both
//! times; the deepest gouge the dexel finds; and whether every cell the dexel finds
//! gouged lies under a pose that the sectioning check flagged.

use std::time::Instant;
use swarf_fiveaxis::CurveOptions;
use swarf_fiveaxis::design::DesignSurface;
use swarf_fiveaxis::gouge::{GougeOptions, check_pass};
use swarf_fiveaxis::positioning::{Positioning, position};
use swarf_fiveaxis::sections::Sections;
use swarf_fiveaxis::swept::SweptSurface;
use swarf_geom::Point3;
use swarf_nc::read::{Motion, MotionKind};
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimTool, StockInit, simulate};
use swarf_testkit::die_cc;
use swarf_tool::ProfileTable;
use swarf_tool::{Cutter, Pose};

/// Gouge tolerance, mm.
const TOL: f64 = 0.01;

/// Tip positions of the poses the sectioning check (whole tool) flags.
fn flagged_poses(design: &DesignSurface, cutter: &Cutter, passes: &[Vec<Pose>]) -> Vec<Point3> {
    let profile = cutter.profile();
    let table = ProfileTable::new(&profile);
    let g = GougeOptions {
        sections: Sections::along(60f64.to_radians(), 1.0).expect("sections"),
        tolerance: TOL,
        curve: CurveOptions::default(),
        cap_meridians: 96,
        whole_tool: true,
    };
    let mut out = Vec::new();
    for poses in passes {
        for (p, pg) in poses.iter().zip(check_pass(design, &table, poses, &g)) {
            if pg.gouges(TOL) {
                out.push(p.cl);
            }
        }
    }
    out
}

fn arg(k: usize, default: f64) -> f64 {
    std::env::args()
        .nth(k)
        .and_then(|a| a.parse().ok())
        .unwrap_or(default)
}

/// What a section compares.
struct Run<'a> {
    design: &'a DesignSurface,
    swept: &'a SweptSurface,
    motions: &'a [Motion],
    flagged: &'a [Point3],
    cutter: &'a Cutter,
    part: &'a swarf_geom::Part,
    cell: f64,
    sample_tol: f64,
}

fn main() {
    let auto = std::env::args().nth(1).as_deref() == Some("auto");
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
    let design = DesignSurface::new(&part).expect("design");
    let cutter: Cutter = "bull:d=38.1,r=6.35".parse().expect("tool");
    let passes = plan(&part, &cutter, auto, alpha);
    let flagged = flagged_poses(&design, &cutter, &passes);
    println!("sectioning flags {} poses", flagged.len());
    let t = Instant::now();
    let opts = CurveOptions {
        meridians,
        wall_cards: 24,
        ..CurveOptions::default()
    };
    let swept = SweptSurface::new(&cutter.profile(), &passes, &opts).expect("swept");
    println!(
        "{} poses; generating curves ({meridians} meridians): {:.2} s",
        passes.iter().map(Vec::len).sum::<usize>(),
        t.elapsed().as_secs_f64()
    );
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
    let run = Run {
        design: &design,
        swept: &swept,
        motions: &motions,
        flagged: &flagged,
        cutter: &cutter,
        part: &part,
        cell,
        sample_tol,
    };
    for x in sections {
        compare(&run, x);
    }
}

/// The die's passes with the fixed lead `alpha` or the automatic one.
fn plan(part: &swarf_geom::Part, cutter: &Cutter, auto: bool, alpha: f64) -> Vec<Vec<Pose>> {
    let cc = die_cc(part, "bull:d=38.1,r=6.35", 60.0, 3.5, 0.002);
    let p = if auto {
        Positioning::GougeFree {
            max_alpha: 25.0,
            sections: 1.0,
            tilt: 0.0,
            max_rate: 0.5,
            tolerance: None,
        }
    } else {
        Positioning::Inclined {
            alpha,
            tilt: 0.0,
            sections: 1.0,
        }
    };
    let (planned, report) = position(cutter, part, &cc, &p, TOL).expect("positioning");
    println!(
        "{}: lead {:.2}..{:.2} deg",
        if auto { "automatic" } else { "fixed" },
        report.alpha_range_deg[0],
        report.alpha_range_deg[1],
    );
    planned
        .iter()
        .map(|p| p.points.iter().map(|q| q.pose).collect())
        .collect()
}

/// The dexel of the strip `x` against the curves' surface and the design.
fn compare(r: &Run<'_>, x: f64) {
    let b = r.part.control_box();
    let grid = Grid::covering(
        [x - 0.5 * r.cell, b.min.y],
        [x + 0.5 * r.cell, b.max.y],
        r.cell,
        1 << 30,
    )
    .expect("grid");
    let mut dexel = Dexel::new(grid, StockInit::Box { top: b.max.z + 5.0 }).expect("stock");
    let t = Instant::now();
    let so = SimOptions {
        sample_tol: r.sample_tol,
        known_start: true,
        ..SimOptions::default()
    };
    let tool = SimTool::new(r.cutter).expect("sim tool");
    simulate(&mut dexel, &tool, r.motions, &so, &Quiet);
    let t_dx = t.elapsed().as_secs_f64();
    let (mut worst, mut at, mut n, mut gouge) = (0.0f64, 0.0, 0, 0.0f64);
    let (mut gouged, mut unflagged) = (0, 0);
    let reach = r.cutter.radius() + 1.0;
    for j in 0..grid.ny {
        let [cx, cy] = grid.centre(0, j);
        let (Some(h), Some((d, _))) = (r.swept.height(cx, cy), r.design.height(cx, cy)) else {
            continue;
        };
        let z = dexel.height(0, j);
        if z > b.max.z {
            continue;
        }
        n += 1;
        gouge = gouge.max(d - z);
        if d - z > TOL {
            gouged += 1;
            if !r.flagged.iter().any(|q| (q.x - cx).hypot(q.y - cy) < reach) {
                unflagged += 1;
            }
        }
        if (h - z).abs() > worst.abs() {
            worst = h - z;
            at = cy;
        }
    }
    println!(
        "x = {x}: {n} cells; largest difference (curves - dexel) {worst:.4} mm at y = {at:.2}; \
         dexel deepest below design {gouge:.4} mm, {gouged} cells gouged, {unflagged} of them \
         under no flagged pose; dexel {t_dx:.2} s"
    );
}
