//! The second-order sampling of tilted motions (`swarf_sim::sweep_bound`) against the
//! first-order reference sweep at a much finer sample tolerance: random tilted
//! motions of ball and bull cutters, axes up to 50 degrees from vertical turning up to
//! 60 degrees within a motion. Both stocks lie within their bounds (3D) of the true
//! swept solid, so where the cut surface's slope is `s` (at most 2 here) their heights
//! differ by at most `(bound + reference bound) sqrt(1 + s^2)`, the vertical image of
//! a 3D gap on a plane of that slope (the tools' radii are hundreds of times the
//! bounds, so their curvature adds nothing that matters).

use swarf_geom::{Point3, Vec3};
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimReport, SimTool, StockInit, simulate};
use swarf_testkit::heights::worst_height_ratio;
use swarf_tool::Pose;
use swarf_toolpath::{Motion, MotionKind};

/// A deterministic generator of numbers in `[0, 1)` (64-bit LCG, top bits).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// An axis `tilt` from vertical towards azimuth `az`.
fn axis(tilt: f64, az: f64) -> Vec3 {
    Vec3::new(tilt.sin() * az.cos(), tilt.sin() * az.sin(), tilt.cos())
}

/// Random tilted cutting motions over the square `[-6, 6]^2`, tips between
/// `z = -2.5` and `z = -0.5` under a stock at 0, each axis turning up to 60 degrees.
fn motions(seed: u64, count: usize) -> Vec<Motion> {
    let mut rng = Lcg(seed);
    (0..count)
        .map(|k| {
            let tilt = rng.range(0.0, 50f64.to_radians());
            let az = rng.range(0.0, std::f64::consts::TAU);
            let a = axis(tilt, az);
            let b = axis(
                (tilt + rng.range(-0.5, 0.5)).clamp(0.0, 50f64.to_radians()),
                az + rng.range(-0.6, 0.6),
            );
            let p = |rng: &mut Lcg| {
                Point3::new(
                    rng.range(-6.0, 6.0),
                    rng.range(-6.0, 6.0),
                    rng.range(-2.5, -0.5),
                )
            };
            let (s, e) = (p(&mut rng), p(&mut rng));
            Motion {
                kind: MotionKind::Linear,
                start: Pose::new(s, a).expect("axis"),
                end: Pose::new(e, b).expect("axis"),
                feed: 500.0,
                line: k + 1,
            }
        })
        .collect()
}

fn run(spec: &str, moves: &[Motion], tol: f64, first_order: bool) -> (Dexel, SimReport) {
    let tool = SimTool::new(&spec.parse().expect("cutter")).expect("tool");
    let g = Grid::covering([-12.0, -12.0], [12.0, 12.0], 0.25, 1 << 30).expect("grid");
    let mut d = Dexel::new(g, StockInit::Box { top: 0.0 }).expect("stock");
    let opts = SimOptions {
        sample_tol: tol,
        first_order,
        ..SimOptions::default()
    };
    let r = simulate(&mut d, &tool, moves, &opts, &Quiet);
    (d, r)
}

/// [`worst_height_ratio`] of the two stocks over cut cells (below the stock's top).
fn worst_ratio(fast: &Dexel, slow: &Dexel, allowed: f64) -> (f64, usize) {
    let g = *slow.grid();
    let h = slow.heights();
    worst_height_ratio((h, fast.heights()), (g.nx, g.ny, g.cell), allowed, |k| {
        h[k] < 0.0
    })
}

#[test]
fn second_order_sampling_agrees_with_the_fine_reference() {
    for (spec, seed) in [("ball:d=8,length=12", 7), ("bull:d=10,r=2,length=12", 11)] {
        let moves = motions(seed, 5);
        let (fast, rf) = run(spec, &moves, 0.01, false);
        let (slow, rs) = run(spec, &moves, 0.002, true);
        // (a motion whose sharp top may come within its first-order margin of the
        // stock keeps the first order)
        assert!(rf.second_order_motions >= 3, "{spec}: {rf:?}");
        assert_eq!(rs.second_order_motions, 0, "{spec}");
        assert!(rf.max_sample_bound <= 0.01 && rs.max_sample_bound <= 0.002);
        assert!(
            rf.primitives * 10 < rs.primitives,
            "{spec}: {} vs {} samples",
            rf.primitives,
            rs.primitives
        );
        let allowed = rf.max_sample_bound + rs.max_sample_bound + 1e-9;
        let (worst, checked) = worst_ratio(&fast, &slow, allowed);
        assert!(checked > 1000, "{spec}: {checked} cells checked");
        assert!(
            worst <= 1.0,
            "{spec}: worst {worst} of the allowed {allowed} mm"
        );
    }
}

#[test]
fn a_stock_over_the_sharp_top_keeps_the_first_order() {
    // Tips 0.5 to 2.5 mm deep in a stock whose top is 40 mm up: the flat top of a
    // 12 mm flute is inside it, so every motion is sampled by the first-order bound
    // and the two paths cut the same.
    let moves = motions(3, 3);
    let tool = SimTool::new(&"ball:d=8,length=12".parse().expect("cutter")).expect("tool");
    let g = Grid::covering([-12.0, -12.0], [12.0, 12.0], 0.4, 1 << 30).expect("grid");
    let sim = |first_order: bool| {
        let mut d = Dexel::new(g, StockInit::Box { top: 40.0 }).expect("stock");
        let opts = SimOptions {
            sample_tol: 0.01,
            first_order,
            ..SimOptions::default()
        };
        let r = simulate(&mut d, &tool, &moves, &opts, &Quiet);
        (d.heights().to_vec(), r.second_order_motions, r.primitives)
    };
    let (a, b) = (sim(false), sim(true));
    assert_eq!(a.1, 0);
    assert_eq!(a, b);
}
