//! The sweep interface: what one motion removes, as a list of primitives that each
//! know their XY box and how to lower a row of cells (CAMotics' `Sweep` per tool
//! shape, `src/camotics/sim/Sweep.h`, in the same spirit).
//!
//! # Which motions are exact and which are sampled
//!
//! - A straight move of a vertical tool is one [`LinearSweep`]: exact (the swept
//!   minimum of [`crate::swept_min`]).
//! - An arc or helix of a vertical tool is cut into `n` chords at equal parameter
//!   steps, each swept exactly. With `phi = t Theta` the arc's angle, the tip's XY
//!   position `P(phi) = r(phi) (cos, sin)(phi)` (radius linear in `phi` for the slight
//!   spirals a G-code tolerance admits) and its height linear in `phi` (so the chords
//!   carry it exactly). Linear interpolation of a vector function between two samples
//!   `dphi` apart errs by at most `dphi^2 / 8 * max |P''|` (the Green's-function form
//!   of the interpolation error, valid for vectors), and
//!   `|P''| <= r_max + 2 |r'| = r_max + 2 |r2 - r1| / Theta = M`. Every chord position
//!   is a translate of the true position at the same parameter by at most
//!   `eps = M Theta^2 / (8 n^2)`, so the simulated and true swept solids lie within
//!   `eps` of each other (Hausdorff distance). `n` is the least count with
//!   `eps <= sample_tol`.
//! - A motion whose tool axis is not vertical (five-axis CL data) is sampled as
//!   [`ToolInstance`]s at `t = k / n`, which lie inside the true swept solid. Between
//!   samples the tip moves at most `S / n` (S the tip path's length bound: the chord,
//!   or `Theta r_max + |r2 - r1| + |h|` on an arc) and the axis turns by at most
//!   `alpha / n` (alpha the angle between the end axes, slerp turning uniformly),
//!   which moves any tool point by at most `(S + B alpha) / n`, `B = sqrt(R^2 + H^2)`
//!   the tool's reach from its tip: every point of the true swept solid lies within
//!   `delta_1 = (S + B alpha) / (2 n)` of the samples (first order). Ball and bull
//!   cutters whose sharp top stays clear of the stock are bounded to second order,
//!   `delta_2 = (A + V^2 / rho) / (8 n^2)` ([`crate::sweep_bound`]), so `n` grows as
//!   `1 / sqrt(sample_tol)`. Either way the simulated surface may stand up to the
//!   bound (a 3D distance, i.e. along the surface normal) above the true one, never
//!   below. `n` is the least count with the bound `<= sample_tol`; rapids use the
//!   coarser [`RAPID_SAMPLE`] (a rapid that touches material is reported anyway).

use crate::error::SimError;
use crate::grid::Grid;
use crate::sweep_bound::{Kinematics, Rounding, StockCeiling, rolling_radius};
use crate::sweep_linear::{LinearSweep, RowCut};
use crate::sweep_tilted::ToolInstance;
use crate::tool_solid::ToolSolid;
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Point3, Vec3};
use swarf_tool::Cutter;
use swarf_tool::drop::Envelope;
use swarf_toolpath::{Motion, MotionKind};

/// Sampling tolerance for five-axis rapids, mm (at least this coarse).
pub const RAPID_SAMPLE: f64 = 0.1;

/// A cutter prepared for simulation.
#[derive(Debug, Clone, Copy)]
pub struct SimTool {
    /// The cutter.
    pub cutter: Cutter,
    solid: ToolSolid,
    envelope: Envelope,
    radius: f64,
    length: f64,
    convex: bool,
    rounding: Rounding,
}

impl SimTool {
    /// Prepares `cutter`.
    ///
    /// # Errors
    /// [`SimError::Unsupported`] when the cutter is invalid or has no lower profile.
    pub fn new(cutter: &Cutter) -> Result<SimTool, SimError> {
        cutter
            .validate()
            .map_err(|e| SimError::Unsupported(format!("tool {cutter}: {e}")))?;
        let profile = cutter.profile();
        let envelope = Envelope::new(&profile);
        if envelope.pieces().is_empty() {
            return Err(SimError::Unsupported(format!(
                "tool {cutter}: the profile has no lower surface to cut with"
            )));
        }
        let radius = envelope.radius().max(profile.radius());
        let length = profile.length();
        Ok(SimTool {
            cutter: *cutter,
            solid: ToolSolid::of(cutter, &profile),
            envelope,
            radius,
            length,
            convex: profile.is_convex(),
            rounding: Rounding {
                radius,
                length,
                rho: rolling_radius(cutter, length),
            },
        })
    }

    /// The lower envelope.
    pub fn envelope(&self) -> &Envelope {
        &self.envelope
    }

    /// Largest cutting radius, mm.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Reach of any tool point from the tip, `sqrt(R^2 + H^2)`, mm.
    pub fn reach(&self) -> f64 {
        self.radius.hypot(self.length)
    }
}

/// What a shape-specific sweep must provide.
pub trait Sweep {
    /// XY box of the cells it may lower: `[xmin, ymin, xmax, ymax]`, mm.
    fn bounds(&self) -> [f64; 4];
    /// Lowers the cells of row `j` (`heights`, `last`: that row) to the tool,
    /// recording `motion` for each cell lowered.
    fn cut_row(&self, cut: &RowJob<'_>, heights: &mut [f64], last: &mut [u32]) -> RowCut;
}

/// The context of one row update.
#[derive(Debug, Clone, Copy)]
pub struct RowJob<'a> {
    /// The prepared tool.
    pub tool: &'a SimTool,
    /// The grid.
    pub grid: &'a Grid,
    /// Row index.
    pub row: usize,
    /// Motion index to record.
    pub motion: u32,
}

impl Sweep for LinearSweep {
    fn bounds(&self) -> [f64; 4] {
        LinearSweep::bounds(self)
    }

    fn cut_row(&self, job: &RowJob<'_>, heights: &mut [f64], last: &mut [u32]) -> RowCut {
        LinearSweep::cut_row(
            self,
            &job.tool.envelope,
            job.grid,
            job.row,
            heights,
            last,
            job.motion,
        )
    }
}

impl Sweep for ToolInstance {
    fn bounds(&self) -> [f64; 4] {
        ToolInstance::bounds(self)
    }

    fn cut_row(&self, job: &RowJob<'_>, heights: &mut [f64], last: &mut [u32]) -> RowCut {
        let b = self.bounds();
        let Some((i0, i1)) = job.grid.columns(b[0], b[2]) else {
            return RowCut::default();
        };
        let y = job.grid.y(job.row);
        let mut out = RowCut {
            visited: (i1 - i0 + 1) as u64,
            ..RowCut::default()
        };
        for i in i0..=i1 {
            let h = heights[i];
            if h <= self.zlo() {
                continue;
            }
            let x = job.grid.x(i);
            let floor = self.floor(x, y);
            if floor >= h {
                continue;
            }
            let z = self.lowest(&job.tool.solid, job.tool.convex, (x, y), h, floor);
            if z < h {
                heights[i] = z;
                last[i] = job.motion;
                out.lowered += 1;
                out.depth = out.depth.max(h - z);
            }
        }
        out
    }
}

/// One piece of a motion's removal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Primitive {
    /// A straight move of a vertical tool, swept exactly.
    Linear(LinearSweep),
    /// One sampled position of a tilted tool.
    Instance(ToolInstance),
}

impl Primitive {
    /// XY box, mm.
    pub fn bounds(&self) -> [f64; 4] {
        match self {
            Primitive::Linear(s) => Sweep::bounds(s),
            Primitive::Instance(s) => Sweep::bounds(s),
        }
    }

    /// See [`Sweep::cut_row`].
    #[inline]
    pub fn cut_row(&self, job: &RowJob<'_>, heights: &mut [f64], last: &mut [u32]) -> RowCut {
        match self {
            Primitive::Linear(s) => Sweep::cut_row(s, job, heights, last),
            Primitive::Instance(s) => Sweep::cut_row(s, job, heights, last),
        }
    }
}

/// A motion turned into primitives, with the sampling bound it achieved.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionSweep {
    /// The primitives, in order along the motion.
    pub primitives: Vec<Primitive>,
    /// 3D distance bound between the simulated and true swept solids, mm (0: exact).
    pub bound: f64,
    /// The tilted tool was sampled by the second-order bound ([`crate::sweep_bound`]).
    pub second_order: bool,
}

/// How sampled motions are sampled.
#[derive(Debug, Clone, Copy)]
pub struct Sampling<'a> {
    /// Distance bound, mm.
    pub tol: f64,
    /// A bound of the stock's height (where the sharp top of a tilted tool may cut).
    pub ceiling: &'a StockCeiling,
    /// Sample every tilted motion by the first-order bound (the reference the
    /// second-order sampling is tested against).
    pub first_order: bool,
}

/// Radii, swept angle and rise of an arc motion: `(r1, r2, theta, h)`.
fn arc_shape(m: &Motion, center: &Point3, normal: &Vec3) -> Option<(f64, f64, f64, f64)> {
    let n = normal.try_normalize(LENGTH_EPS)?;
    let flat = |p: &Point3| {
        let v = p - center;
        (v - n * v.dot(&n)).norm()
    };
    let (r1, r2) = (flat(&m.start.cl), flat(&m.end.cl));
    let h = (m.end.cl - m.start.cl).dot(&n);
    let mean = 0.5 * (r1 + r2);
    let len = m.length();
    if mean <= LENGTH_EPS || !len.is_finite() {
        return None;
    }
    Some((r1, r2, (len * len - h * h).max(0.0).sqrt() / mean, h))
}

/// How a motion is swept: exactly, as a polyline of `n` segments, or as `n + 1` tool
/// instances; with the distance bound the sampling keeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SweepPlan {
    Exact,
    Polyline {
        n: usize,
        bound: f64,
    },
    Instances {
        n: usize,
        bound: f64,
        second_order: bool,
    },
}

/// The sampling of motion `m` for `tool` within `sampling`, and the sample count
/// before it is capped (for [`crate::sweep_budget::check_sampling`]).
pub(crate) fn sweep_plan(tool: &SimTool, m: &Motion, sampling: &Sampling<'_>) -> (SweepPlan, f64) {
    let straight = matches!(m.kind, MotionKind::Rapid | MotionKind::Linear);
    let arc = match m.kind {
        MotionKind::Arc { center, normal, .. } => arc_shape(m, &center, &normal),
        _ => None,
    };
    let upright = m.start.is_vertical() && m.end.is_vertical();
    if upright && (straight || arc.is_none()) {
        return (SweepPlan::Exact, 1.0);
    }
    // |P''| in the arc angle (module doc), and the tip path's length bound.
    let bend_of = |(r1, r2, theta, _): (f64, f64, f64, f64)| {
        r1.max(r2) + 2.0 * (r2 - r1).abs() / theta.max(LENGTH_EPS)
    };
    if upright {
        let (_, _, theta, _) = arc.unwrap_or_default();
        let err = bend_of(arc.unwrap_or_default()) * theta * theta / 8.0;
        let (n, wanted) = steps(err, sampling.tol, true);
        let bound = err / (n * n) as f64;
        return (SweepPlan::Polyline { n, bound }, wanted);
    }
    let kin = match arc {
        Some(a @ (r1, r2, theta, h)) => Kinematics {
            path: theta * r1.max(r2) + (r2 - r1).abs() + h.abs(),
            bend: bend_of(a) * theta * theta,
            turn: m.start.axis.angle(&m.end.axis),
        },
        None => Kinematics {
            path: (m.end.cl - m.start.cl).norm(),
            bend: 0.0,
            turn: m.start.axis.angle(&m.end.axis),
        },
    };
    let tol = if matches!(m.kind, MotionKind::Rapid) {
        sampling.tol.max(RAPID_SAMPLE)
    } else {
        sampling.tol
    };
    let first = tool.rounding.first_order(&kin);
    if !sampling.first_order
        && let Some(second) = tool.rounding.second_order(&kin)
    {
        let (n, wanted) = steps(second, tol, true);
        let poses = (0..=n).map(|k| m.point_at(k as f64 / n as f64));
        if tool
            .rounding
            .slab_clear(poses, first / n as f64, sampling.ceiling)
        {
            let bound = second / (n * n) as f64;
            let plan = SweepPlan::Instances {
                n,
                bound,
                second_order: true,
            };
            return (plan, wanted);
        }
    }
    let (n, wanted) = steps(first, tol, false);
    let plan = SweepPlan::Instances {
        n,
        bound: first / n as f64,
        second_order: false,
    };
    (plan, wanted)
}

/// The primitives of motion `m` for `tool`, sampled within `sampling` where the
/// motion is not swept exactly (see the module doc).
pub fn sweep_motion(tool: &SimTool, m: &Motion, sampling: &Sampling<'_>) -> MotionSweep {
    match sweep_plan(tool, m, sampling).0 {
        SweepPlan::Exact => MotionSweep {
            primitives: vec![Primitive::Linear(LinearSweep::new(
                &m.start.cl,
                &m.end.cl,
                tool.radius,
            ))],
            bound: 0.0,
            second_order: false,
        },
        SweepPlan::Polyline { n, bound } => {
            let pts: Vec<Point3> = (0..=n)
                .map(|k| m.point_at(k as f64 / n as f64).cl)
                .collect();
            MotionSweep {
                primitives: pts
                    .windows(2)
                    .map(|w| Primitive::Linear(LinearSweep::new(&w[0], &w[1], tool.radius)))
                    .collect(),
                bound,
                second_order: false,
            }
        }
        SweepPlan::Instances {
            n,
            bound,
            second_order,
        } => MotionSweep {
            primitives: (0..=n)
                .map(|k| {
                    let pose = m.point_at(k as f64 / n as f64);
                    Primitive::Instance(ToolInstance::new(pose, tool.radius, tool.length))
                })
                .collect(),
            bound,
            second_order,
        },
    }
}

/// Least `n >= 1` with `err / n^2 <= tol` (`quadratic`) or `err / n <= tol`, capped at
/// [`crate::sweep_budget::MAX_MOTION_SAMPLES`], and the count before the cap.
fn steps(err: f64, tol: f64, quadratic: bool) -> (usize, f64) {
    if err.is_nan() || err <= tol || !err.is_finite() {
        return (1, 1.0);
    }
    let ratio = err / tol;
    let n = if quadratic { ratio.sqrt() } else { ratio }.ceil().max(1.0);
    (n.min(crate::sweep_budget::MAX_MOTION_SAMPLES) as usize, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_tool::Pose;

    fn motion(kind: MotionKind, a: Pose, b: Pose) -> Motion {
        Motion {
            kind,
            start: a,
            end: b,
            feed: 100.0,
            line: 7,
        }
    }

    #[test]
    fn convexity_of_the_family() {
        for spec in ["flat:d=6", "ball:d=8", "bull:d=10,r=2", "cone:d=6,angle=60"] {
            let t = SimTool::new(&spec.parse().unwrap()).unwrap();
            assert!(t.convex, "{spec}");
        }
    }

    #[test]
    fn arc_chords_meet_their_bound() {
        let tool = SimTool::new(&"ball:d=8".parse().unwrap()).unwrap();
        let v = |x: f64, y: f64, z: f64| Pose::vertical(Point3::new(x, y, z));
        let m = motion(
            MotionKind::Arc {
                center: Point3::origin(),
                normal: Vec3::z(),
                clockwise: false,
                turns: 1,
            },
            v(10.0, 0.0, 0.0),
            v(0.0, 10.0, -1.0),
        );
        let sw = sweep_motion(&tool, &m, &sampling(1e-3, f64::INFINITY, false));
        assert!(sw.bound <= 1e-3 && sw.bound > 0.0);
        // Chord mid-points lie within the bound of the true arc at the same parameter.
        let n = sw.primitives.len();
        for k in 0..n {
            let t = (k as f64 + 0.5) / n as f64;
            let a = m.point_at(k as f64 / n as f64).cl;
            let b = m.point_at((k + 1) as f64 / n as f64).cl;
            let mid = a + (b - a) * 0.5;
            assert!((m.point_at(t).cl - mid).norm() <= sw.bound * (1.0 + 1e-9));
        }
        // Fewer chords would break the bound: the count is the least one.
        let theta = std::f64::consts::FRAC_PI_2;
        let coarser = 10.0 * theta * theta / (8.0 * ((n - 1) * (n - 1)) as f64);
        assert!(coarser > 1e-3);
    }

    fn sampling(tol: f64, stock_top: f64, first_order: bool) -> Sampling<'static> {
        let ceiling = Box::leak(Box::new(StockCeiling::Level(stock_top)));
        Sampling {
            tol,
            ceiling,
            first_order,
        }
    }

    #[test]
    fn tilted_motion_is_sampled_within_its_bound() {
        let tool = SimTool::new(&"ball:d=8".parse().unwrap()).unwrap();
        let a = Pose::new(Point3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.1, 1.0)).unwrap();
        let b = Pose::new(Point3::new(2.0, 0.0, 0.0), Vec3::new(0.0, -0.1, 1.0)).unwrap();
        let m = motion(MotionKind::Linear, a, b);
        let turn = a.axis.angle(&b.axis);
        // First order: half the travel of the farthest tool point per sample.
        let sw = sweep_motion(&tool, &m, &sampling(0.01, 0.0, true));
        assert!(sw.bound <= 0.01 && !sw.second_order);
        let travel = 2.0 + tool.reach() * turn;
        assert_eq!(sw.primitives.len(), (travel / 0.02).ceil() as usize + 1);
        // The top slab (3 mm above the tip at the least) stands above a stock at 2:
        // second order, (A + V^2 / rho) / (8 n^2) with the core's reach.
        let sw = sweep_motion(&tool, &m, &sampling(0.01, 2.0, false));
        let bc = (tool.length - 4.0).hypot(0.0);
        let v = 2.0 + turn * bc;
        let k = (turn * turn * bc + v * v / 4.0) / 8.0;
        assert!(sw.second_order && sw.bound <= 0.01);
        assert_eq!(sw.primitives.len(), (k / 0.01).sqrt().ceil() as usize + 1);
        assert!(sw.primitives.len() * 4 < (travel / 0.02) as usize);
        // A stock that reaches the slab: first order again.
        let deep = sweep_motion(&tool, &m, &sampling(0.01, 40.0, false));
        assert!(!deep.second_order);
        assert_eq!(deep.primitives.len(), (travel / 0.02).ceil() as usize + 1);
        // A flat end mill's edge is sharp: first order.
        let flat = SimTool::new(&"flat:d=8".parse().unwrap()).unwrap();
        assert!(!sweep_motion(&flat, &m, &sampling(0.01, -100.0, false)).second_order);
        let vert = sweep_motion(
            &tool,
            &motion(
                MotionKind::Rapid,
                Pose::vertical(Point3::origin()),
                Pose::vertical(Point3::new(5.0, 1.0, 2.0)),
            ),
            &sampling(0.01, f64::INFINITY, false),
        );
        assert_eq!((vert.primitives.len(), vert.bound), (1, 0.0));
    }
}
