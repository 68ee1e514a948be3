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
//!   [`ToolInstance`]s at `t = k / n`. Between samples the tip moves at most
//!   `S / n` (S the tip path's length bound: the chord, or `Theta r_max + |r2 - r1| +
//!   |h|` on an arc) and the axis turns by at most `alpha / n` (alpha the angle between
//!   the end axes, slerp turning uniformly), which moves any tool point by at most
//!   `(S + B alpha) / n`, `B = sqrt(R^2 + H^2)` the tool's reach from its tip. Every
//!   position of the motion is within half a step of a sample, so every point of the
//!   true swept solid lies within `delta = (S + B alpha) / (2 n)` of the sampled union
//!   (which lies inside the true solid): the simulated surface may stand up to `delta`
//!   (measured in 3D, i.e. along the surface normal) above the true one, never below.
//!   `n` is the least count with `delta <= sample_tol`; rapids use the coarser
//!   [`RAPID_SAMPLE`] (a rapid that touches material is reported anyway).

use crate::error::SimError;
use crate::grid::Grid;
use crate::sweep_linear::{LinearSweep, RowCut};
use crate::sweep_tilted::ToolInstance;
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Point3, Vec3};
use swarf_tool::drop::Envelope;
use swarf_tool::{Cutter, Profile};
use swarf_toolpath::{Motion, MotionKind};

/// Sampling tolerance for five-axis rapids, mm (at least this coarse).
pub const RAPID_SAMPLE: f64 = 0.1;

/// A cutter prepared for simulation.
#[derive(Debug, Clone, Copy)]
pub struct SimTool {
    /// The cutter.
    pub cutter: Cutter,
    profile: Profile,
    envelope: Envelope,
    radius: f64,
    length: f64,
    convex: bool,
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
        Ok(SimTool {
            cutter: *cutter,
            profile,
            envelope,
            radius: envelope.radius().max(profile.radius()),
            length: profile.length(),
            convex: profile.is_convex(),
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
            if self.floor(x, y) >= h {
                continue;
            }
            let z = self.lowest(&job.tool.profile, job.tool.convex, (x, y), h);
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
    Polyline { n: usize, bound: f64 },
    Instances { n: usize, bound: f64 },
}

/// The sampling of motion `m` for `tool` within `sample_tol` (mm), and the sample
/// count before it is capped (for [`crate::sweep_budget::check_sampling`]).
pub(crate) fn sweep_plan(tool: &SimTool, m: &Motion, sample_tol: f64) -> (SweepPlan, f64) {
    let straight = matches!(m.kind, MotionKind::Rapid | MotionKind::Linear);
    let arc = match m.kind {
        MotionKind::Arc { center, normal, .. } => arc_shape(m, &center, &normal),
        _ => None,
    };
    let upright = m.start.is_vertical() && m.end.is_vertical();
    if upright && (straight || arc.is_none()) {
        return (SweepPlan::Exact, 1.0);
    }
    if upright {
        let (r1, r2, theta, _) = arc.unwrap_or_default();
        let big_m = r1.max(r2) + 2.0 * (r2 - r1).abs() / theta.max(LENGTH_EPS);
        let err = big_m * theta * theta / 8.0;
        let (n, wanted) = steps(err, sample_tol, true);
        let bound = err / (n * n) as f64;
        return (SweepPlan::Polyline { n, bound }, wanted);
    }
    let path = match arc {
        Some((r1, r2, theta, h)) => theta * r1.max(r2) + (r2 - r1).abs() + h.abs(),
        None => (m.end.cl - m.start.cl).norm(),
    };
    let turn = m.start.axis.angle(&m.end.axis);
    let travel = path + tool.reach() * turn;
    let tol = if matches!(m.kind, MotionKind::Rapid) {
        sample_tol.max(RAPID_SAMPLE)
    } else {
        sample_tol
    };
    let (n, wanted) = steps(0.5 * travel, tol, false);
    let bound = 0.5 * travel / n as f64;
    (SweepPlan::Instances { n, bound }, wanted)
}

/// The primitives of motion `m` for `tool`, sampled within `sample_tol` (mm) where
/// the motion is not swept exactly (see the module doc).
pub fn sweep_motion(tool: &SimTool, m: &Motion, sample_tol: f64) -> MotionSweep {
    match sweep_plan(tool, m, sample_tol).0 {
        SweepPlan::Exact => MotionSweep {
            primitives: vec![Primitive::Linear(LinearSweep::new(
                &m.start.cl,
                &m.end.cl,
                tool.radius,
            ))],
            bound: 0.0,
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
            }
        }
        SweepPlan::Instances { n, bound } => MotionSweep {
            primitives: (0..=n)
                .map(|k| {
                    let pose = m.point_at(k as f64 / n as f64);
                    Primitive::Instance(ToolInstance::new(pose, tool.radius, tool.length))
                })
                .collect(),
            bound,
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
        let sw = sweep_motion(&tool, &m, 1e-3);
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

    #[test]
    fn tilted_motion_is_sampled_within_its_bound() {
        let tool = SimTool::new(&"ball:d=8".parse().unwrap()).unwrap();
        let a = Pose::new(Point3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.1, 1.0)).unwrap();
        let b = Pose::new(Point3::new(2.0, 0.0, 0.0), Vec3::new(0.0, -0.1, 1.0)).unwrap();
        let sw = sweep_motion(&tool, &motion(MotionKind::Linear, a, b), 0.01);
        assert!(sw.bound <= 0.01);
        let travel = 2.0 + tool.reach() * a.axis.angle(&b.axis);
        assert_eq!(sw.primitives.len(), (travel / 0.02).ceil() as usize + 1);
        let vert = sweep_motion(
            &tool,
            &motion(
                MotionKind::Rapid,
                Pose::vertical(Point3::origin()),
                Pose::vertical(Point3::new(5.0, 1.0, 2.0)),
            ),
            0.01,
        );
        assert_eq!((vert.primitives.len(), vert.bound), (1, 0.0));
    }
}
