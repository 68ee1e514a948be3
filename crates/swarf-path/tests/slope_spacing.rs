//! Prove it (issue 12, "Spacing"): the closed-form scallop on inclined planes for a
//! ball, a flat end and a bull against the dexel figure.
//!
//! A plane `z = y tan(theta)` rises across raster passes along X. Each case plans
//! the raster with a spacing (fixed, or from [`swarf_path::stepping::slope_step`] for a
//! scallop `h`), cuts it on a Z-map stock covering the passes between the second
//! and the last but one contact, and takes the largest deviation from the plane
//! along its normal (the vertical deviation times `cos(theta)`, exact on a plane).
//! On this plane each raster pass runs along the strike at constant height, so it
//! is also a Z-level pass with `dz = s tan(theta)`: the Z-level cases plan the
//! spacing of [`swarf_path::stepping::slope_step::zlevel_spacing`] that way.
//!
//! The closed forms are written here from the geometry of the section, without the
//! crate's helpers: two circles for a ball while the cusp stays on the sphere (past
//! its equator, on steep walls, the shank cuts it lower), the right-angled V of a
//! flat end's rim, a bull's corner arcs, sides and floor. Tolerance: the stock samples the machined surface at cell
//! centres `c` apart in Y, `du = c / cos(theta)` apart along the plane; the cusp's
//! gentler flank rises at most 45 degrees from the plane in every case here, so
//! the sampled crest lies within `du` below the true one, and never above it.

use std::f64::consts::FRAC_PI_2;
use swarf_geom::{Point3, TriMesh};
use swarf_nc::read::{Motion, MotionKind};
use swarf_path::Cutting;
use swarf_path::stepping::slope_step::{raster_spacing, zlevel_spacing};
use swarf_path::strategy::raster::RasterParams;
use swarf_sim::{Dexel, Grid, Quiet, SimOptions, SimTool, StockInit, simulate};
use swarf_tool::Cutter;

/// Cells of the stock per XY spacing across the passes.
const CELLS_PER_STEP: f64 = 1000.0;
/// Passes per case; the stock covers the contacts of passes 1 to `PASSES - 1`.
const PASSES: usize = 6;
/// Float slack of the simulation and the drops, mm.
const EPS: f64 = 1e-6;

/// How a case spaces its passes.
#[derive(Debug, Clone, Copy)]
enum Spacing {
    /// This XY spacing, mm.
    Fixed(f64),
    /// The slope-aware raster spacing for this scallop (mm) up to the plane's slope.
    Raster(f64),
    /// The Z-level spacing for this scallop (mm) from the plane's slope up.
    ZLevel(f64),
}

/// A ball, a flat end and a bull of the same diameter, as the test takes them.
#[derive(Debug, Clone, Copy)]
enum Shape {
    Ball { r: f64 },
    Flat { r: f64 },
    Bull { a: f64, r: f64 },
}

impl Shape {
    fn cutter(self) -> Cutter {
        match self {
            Shape::Ball { r } => Cutter::ball(2.0 * r, None),
            Shape::Flat { r } => Cutter::flat(2.0 * r, None),
            Shape::Bull { a, r } => Cutter::bull(2.0 * (a + r), r, None),
        }
        .unwrap()
    }

    /// Where the tool touches a plane of slope `t`, from its axis across the passes.
    fn contact(self, t: f64) -> f64 {
        match self {
            _ if t == 0.0 => 0.0,
            Shape::Ball { r } => r * t.sin(),
            Shape::Flat { r } => r,
            Shape::Bull { a, r } => a + r * t.sin(),
        }
    }

    /// The scallop (normal to the plane) of two passes `w` apart along a plane of
    /// slope `t`, from the section: two outlines touching the line `w` apart.
    fn scallop(self, w: f64, t: f64) -> f64 {
        match self {
            // Two circles, the cusp midway while it stays on the sphere.
            Shape::Ball { r } if 0.5 * w <= r * t.cos() => r - (r * r - 0.25 * w * w).sqrt(),
            Shape::Ball { r } => cusp(r, t, w, false),
            // The triangle under the first tool's side (at 90 - t to the plane)
            // and the second tool's bottom (at t): a right angle at its apex.
            Shape::Flat { .. } => w * t.sin() * t.cos(),
            Shape::Bull { a, r } if t == 0.0 => {
                let e = (0.5 * w - a).max(0.0);
                r - (r * r - e * e).sqrt()
            }
            Shape::Bull { r, .. } => cusp(r, t, w, true),
        }
    }
}

/// The cusp of two outlines with a corner (or ball) of radius `r` touching a line
/// of slope `t` at `0` and `w`: the first rises from its contact along its arc for
/// `90 - t` degrees, then along its side (the shank); the second along its arc for
/// `t` degrees, then along its flat bottom (`floor`, a bull) or on along the
/// circle (a ball). The heights meet where they cross.
fn cusp(r: f64, t: f64, w: f64, floor: bool) -> f64 {
    let (s, c) = t.sin_cos();
    let arc = |d: f64| r - (r * r - d * d).sqrt();
    let up = |u: f64| {
        if u <= r * c {
            arc(u)
        } else {
            r - r * s + (u - r * c) * c / s
        }
    };
    let down = |v: f64| {
        if v <= r * s || !floor {
            arc(v)
        } else {
            r - r * c + (v - r * s) * s / c
        }
    };
    let (mut lo, mut hi) = (0.0, w);
    for _ in 0..100 {
        let m = 0.5 * (lo + hi);
        if up(m) < down(w - m) {
            lo = m;
        } else {
            hi = m;
        }
    }
    up(lo)
}

/// The plane `z = y tan(t)` over `[x0, x1] x [y0, y1]`.
fn plane(t: f64, x: [f64; 2], y: [f64; 2]) -> TriMesh {
    let p = |x: f64, y: f64| Point3::new(x, y, y * t.tan());
    let (a, b) = (p(x[0], y[0]), p(x[1], y[0]));
    let (c, d) = (p(x[1], y[1]), p(x[0], y[1]));
    TriMesh::from_triangles(&[[a, b, c], [a, c, d]])
}

/// One measured case.
struct Figure {
    spacing: f64,
    closed: f64,
    dexel: f64,
    du: f64,
    predicted: Option<f64>,
}

/// Plans, cuts and measures one case.
fn measure(shape: Shape, deg: f64, spacing: Spacing) -> Figure {
    let (tool, t) = (shape.cutter(), deg.to_radians());
    let cut = Cutting::new(tool);
    let mut params = RasterParams::new(1.0);
    let s = match spacing {
        Spacing::Fixed(s) => s,
        Spacing::Raster(h) => {
            (params.stepover, params.scallop, params.max_slope) = (None, Some(h), Some(t));
            raster_spacing(&tool, h, t).unwrap()
        }
        Spacing::ZLevel(h) => zlevel_spacing(&tool, h, t).unwrap() / t.tan(),
    };
    if !matches!(spacing, Spacing::Raster(_)) {
        params.stepover = Some(s);
    }
    // A boundary a hair under PASSES steps: the raster divides it into exactly
    // PASSES steps.
    let width = PASSES as f64 * s * (1.0 - 1e-9);
    params.boundary = Some([0.0, 0.0, 4.0, width]);
    let mesh = plane(t, [-30.0, 34.0], [-30.0, width + 30.0]);
    let plan = swarf_path::strategy::raster::plan(&mesh, &cut, &params).unwrap();
    let step = plan.report.side_step_range.unwrap()[0];
    assert!((step - s).abs() < 1e-6 * s, "{step} vs {s}");
    let motions: Vec<Motion> = plan
        .toolpath
        .passes
        .iter()
        .flat_map(|p| p.points.windows(2))
        .map(|w| Motion {
            kind: MotionKind::Linear,
            start: w[0].pose,
            end: w[1].pose,
            feed: 1000.0,
            line: 0,
        })
        .collect();
    let cell = step / CELLS_PER_STEP;
    let y = [step, (PASSES - 1) as f64 * step].map(|y| y + shape.contact(t));
    let grid = Grid::covering([2.0, y[0]], [2.0 + 3.0 * cell, y[1]], cell, 1 << 30).unwrap();
    let top = y[1] * t.tan() + 1.0;
    let mut stock = Dexel::new(grid, StockInit::Box { top }).unwrap();
    let sim = SimTool::new(&tool).unwrap();
    simulate(&mut stock, &sim, &motions, &SimOptions::default(), &Quiet);
    let normal: Vec<f64> = (0..grid.len())
        .map(|k| {
            let [_, yc] = grid.centre(k % grid.nx, k / grid.nx);
            (stock.heights()[k] - yc * t.tan()) * t.cos()
        })
        .collect();
    let least = normal.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(least >= -EPS, "{shape:?} {deg}: gouge {least}");
    Figure {
        spacing: step,
        closed: shape.scallop(step / t.cos(), t),
        dexel: normal.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        du: cell / t.cos(),
        predicted: plan.report.predicted_max_scallop,
    }
}

fn check(shape: Shape, cases: &[(f64, Spacing)]) {
    for &(deg, spacing) in cases {
        let f = measure(shape, deg, spacing);
        println!(
            "{shape:?} {deg:>2} deg {spacing:?}: s = {:.5} mm, closed {:.5}, dexel {:.5} (du {:.5})",
            f.spacing, f.closed, f.dexel, f.du
        );
        let within = f.dexel <= f.closed + EPS && f.dexel >= f.closed - f.du - EPS;
        assert!(
            within,
            "{shape:?} {deg} {spacing:?}: {} vs {}",
            f.dexel, f.closed
        );
        if let Spacing::Raster(h) | Spacing::ZLevel(h) = spacing {
            assert!(f.closed <= h + 1e-9, "{shape:?} {deg}: {} > {h}", f.closed);
        }
        if let Spacing::Raster(_) = spacing {
            let p = f.predicted.unwrap();
            assert!(
                (p - f.closed).abs() < 1e-6,
                "{shape:?} {deg}: predicted {p}"
            );
        }
    }
}

#[test]
fn ball_scallop_on_inclined_planes_matches_the_dexel() {
    use Spacing::*;
    check(
        Shape::Ball { r: 5.0 },
        &[
            (0.0, Fixed(2.0)),
            (0.0, Fixed(4.0)),
            (30.0, Raster(0.1)),
            (30.0, Fixed(3.0)),
            (60.0, Raster(0.1)),
            (60.0, Fixed(1.5)),
            (85.0, Raster(0.1)),
            (85.0, Fixed(0.3)),
            (30.0, ZLevel(0.1)),
            (60.0, ZLevel(0.1)),
            (85.0, ZLevel(0.1)),
        ],
    );
}

#[test]
fn flat_scallop_on_inclined_planes_matches_the_dexel() {
    use Spacing::*;
    check(
        Shape::Flat { r: 5.0 },
        &[
            (0.0, Fixed(4.0)),
            (30.0, Raster(0.1)),
            (30.0, Fixed(1.0)),
            (60.0, Raster(0.1)),
            (60.0, Fixed(1.0)),
            (85.0, Raster(0.1)),
            (85.0, Fixed(0.5)),
            (30.0, ZLevel(0.1)),
            (60.0, ZLevel(0.1)),
            (85.0, ZLevel(0.1)),
        ],
    );
}

#[test]
fn bull_scallop_on_inclined_planes_matches_the_dexel() {
    use Spacing::*;
    check(
        Shape::Bull { a: 3.0, r: 2.0 },
        &[
            (0.0, Fixed(7.0)),
            (0.0, Fixed(8.0)),
            (30.0, Raster(0.1)),
            (30.0, Fixed(2.0)),
            (60.0, Raster(0.1)),
            (60.0, Fixed(1.0)),
            (85.0, Raster(0.1)),
            (85.0, Fixed(0.2)),
            (30.0, ZLevel(0.1)),
            (60.0, ZLevel(0.1)),
            (85.0, ZLevel(0.1)),
        ],
    );
}

#[test]
fn slope_limits_are_checked() {
    let mesh = plane(0.3, [0.0, 10.0], [0.0, 10.0]);
    for bad in [0.0, -0.2, FRAC_PI_2, f64::NAN] {
        let cut = Cutting::new("ball:d=6".parse().unwrap());
        let mut params = RasterParams::new(1.0);
        (params.stepover, params.scallop, params.max_slope) = (None, Some(0.1), Some(bad));
        let e = swarf_path::strategy::raster::plan(&mesh, &cut, &params).unwrap_err();
        assert!(e.to_string().starts_with("max_slope"), "{e}");
        params.stepover = Some(1.0);
        assert!(swarf_path::strategy::raster::plan(&mesh, &cut, &params).is_err());
    }
}

/// The spacings against the exact forward model of every shape (the 2D section of
/// [`swarf_path::stepping::side_step::plane_scallop`]), sampled finer than the spacings' own
/// slope grid: the scallop stays within `h` on every slope of the range, and comes
/// close to it where the cusp stays on the ball or the corner arcs at the limit.
#[test]
fn spacings_hold_on_every_slope_of_their_range() {
    use swarf_path::stepping::slope_step::{raster_max_scallop, raster_scallop, zlevel_scallop};
    let specs = [
        "ball:d=10",
        "flat:d=10",
        "bull:d=10,r=2",
        "bull:d=10,r=0.5",
        "cone:d=10,angle=90",
        "taperball:d=6,angle=10,tip=1",
    ];
    for spec in specs {
        let c: Cutter = spec.parse().unwrap();
        // The side-step table (half a degree) holds to about 1e-5 relative; the
        // ball's and the flat end's forms are exact.
        let closed = spec.starts_with("ball") || spec.starts_with("flat");
        let slack = if closed { 1e-9 } else { 1e-4 };
        for (h, limit) in [(0.05, 30.0f64), (0.2, 60.0), (0.1, 85.0)] {
            let limit = limit.to_radians();
            let s = raster_spacing(&c, h, limit).unwrap();
            let dz = zlevel_spacing(&c, h, limit).unwrap();
            let mut worst = [0.0f64; 2];
            for k in 0..=300 {
                let f = k as f64 / 300.0;
                let up = raster_scallop(&c, s, limit * f).unwrap();
                let t = limit + (89.9f64.to_radians() - limit) * f;
                let down = zlevel_scallop(&c, dz, t).unwrap();
                worst = [worst[0].max(up), worst[1].max(down)];
            }
            assert!(
                worst[0] <= h * (1.0 + slack),
                "{spec} raster: {worst:?} {h}"
            );
            assert!(worst[1] <= h * (1.0 + slack), "{spec} z: {worst:?} {h}");
            assert!(
                limit > 1.1 || worst[0] >= 0.9 * h && worst[1] >= 0.5 * h,
                "{spec} {worst:?}"
            );
            let max = raster_max_scallop(&c, s, limit).unwrap();
            assert!(max <= worst[0] + 1e-12 && max >= 0.9 * worst[0], "{spec}");
        }
    }
}
