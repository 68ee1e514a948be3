//! Radial engagement measured on the stock: how much of the cutter's rim is in
//! material while a 3-axis program runs, motion by motion.
//!
//! The engagement angle of a tool position is the angle of the rim, in the front
//! half of the cutter (towards the motion), that meets material the cutter is about
//! to remove. A straight stretch beside a wall of material `w` wide gives
//! `acos(1 - w / R)`; a slot, 180 degrees. It is measured, not assumed: before a
//! horizontal cutting motion is applied to the stock, positions along it
//! [`STEP_FRACTION`] of the radius apart are taken, and at each the rim is sampled
//! every [`RIM_STEP_DEG`] degrees just inside the cutter's radius. A rim point is
//! engaged when the stock's cell there stands above the cutter's lower envelope at
//! that radius (by more than [`MATERIAL_TOL`]) and no earlier position of the same
//! motion covered it (the motion clears its own trail). The motion's engagement is
//! its largest; then the motion is simulated ([`crate::simulate_from`]) and the next
//! is measured on the stock it left. Plunges, ramps, arcs and rapids are simulated
//! but not measured (their load is axial or not radial).

use crate::dexel::Dexel;
use crate::progress::Progress;
use crate::simulate::{SimOptions, simulate_from};
use crate::sweep::SimTool;
use serde::Serialize;
use swarf_toolpath::{Motion, MotionKind};

/// Spacing of the measured positions along a motion, as a fraction of the radius.
pub const STEP_FRACTION: f64 = 0.05;
/// Angular spacing of the rim samples, degrees.
pub const RIM_STEP_DEG: f64 = 1.0;
/// Material less than this above the envelope is not engaged, mm.
pub const MATERIAL_TOL: f64 = 1e-3;
/// Motions whose ends differ in height by less than this are horizontal, mm.
const LEVEL_TOL: f64 = 1e-9;

/// Engagement of every motion of a program.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Engagement {
    /// Per motion: the largest engagement angle, radians; `None` for motions not
    /// measured (rapids, arcs, motions that are not horizontal).
    pub per_motion: Vec<Option<f64>>,
    /// Rapids that removed material while the program was simulated (as
    /// [`crate::SimReport::rapid_cuts`]).
    pub rapid_cuts: Vec<crate::simulate::MotionNote>,
}

impl Engagement {
    /// The same with the motions marked in `left_out` not measured (a roughing's
    /// entry ramps, slots by design).
    pub fn without(&self, left_out: &[bool]) -> Engagement {
        let per_motion = self
            .per_motion
            .iter()
            .enumerate()
            .map(|(k, a)| a.filter(|_| !left_out.get(k).copied().unwrap_or(false)))
            .collect();
        Engagement {
            per_motion,
            rapid_cuts: self.rapid_cuts.clone(),
        }
    }

    /// The measured angles (radians) of the motions that cut (engagement above 0).
    pub fn cutting(&self) -> Vec<f64> {
        self.per_motion
            .iter()
            .flatten()
            .copied()
            .filter(|a| *a > 0.0)
            .collect()
    }

    /// The largest measured angle, radians (0 for none).
    pub fn max(&self) -> f64 {
        self.cutting().into_iter().fold(0.0, f64::max)
    }

    /// Counts of cutting motions by engagement, in bins of `bin` degrees from 0.
    pub fn histogram(&self, bin: f64) -> Vec<usize> {
        let mut out = Vec::new();
        for a in self.cutting() {
            let k = (a.to_degrees() / bin).floor().max(0.0) as usize;
            if out.len() <= k {
                out.resize(k + 1, 0);
            }
            out[k] += 1;
        }
        out
    }
}

/// Measures and simulates `motions` on `dexel` with `tool` (module doc); motion `k`
/// is recorded in the stock as `first + k`.
///
/// # Units
/// mm, radians.
pub fn measure_engagement(
    dexel: &mut Dexel,
    tool: &SimTool,
    motions: &[Motion],
    first: usize,
    opts: &SimOptions,
    progress: &dyn Progress,
) -> Engagement {
    let mut out = Engagement {
        per_motion: Vec::with_capacity(motions.len()),
        rapid_cuts: Vec::new(),
    };
    progress.begin("measuring engagement", motions.len() as u64);
    for (k, m) in motions.iter().enumerate() {
        let measured = (k > 0 || opts.known_start) && is_level_cut(m);
        out.per_motion
            .push(measured.then(|| motion_engagement(dexel, tool, m)));
        let opts = SimOptions {
            known_start: opts.known_start || k > 0,
            ..*opts
        };
        let sim = simulate_from(
            dexel,
            tool,
            std::slice::from_ref(m),
            first + k,
            &opts,
            &Quietly,
        );
        out.rapid_cuts.extend(sim.rapid_cuts);
        progress.advance(1);
    }
    progress.end();
    out
}

/// A vertical-tool straight cutting motion at one height.
fn is_level_cut(m: &Motion) -> bool {
    matches!(m.kind, MotionKind::Linear)
        && (m.end.cl.z - m.start.cl.z).abs() < LEVEL_TOL
        && m.start.is_vertical()
        && m.end.is_vertical()
}

/// The largest engagement along `m` on the stock as it stands.
fn motion_engagement(dexel: &Dexel, tool: &SimTool, m: &Motion) -> f64 {
    let (a, b) = ([m.start.cl.x, m.start.cl.y], [m.end.cl.x, m.end.cl.y]);
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    if len == 0.0 {
        return 0.0;
    }
    let r = tool.radius();
    let dir = [(b[0] - a[0]) / len, (b[1] - a[1]) / len];
    let grid = dexel.grid();
    let rim = r - 0.5 * grid.cell.min(r);
    let lift = m.start.cl.z + tool.envelope().height(rim) + MATERIAL_TOL;
    let steps = (len / (STEP_FRACTION * r)).ceil().max(1.0) as usize;
    let samples = (180.0 / RIM_STEP_DEG).round() as usize;
    let mut worst: f64 = 0.0;
    for j in 1..=steps {
        let t = len * j as f64 / steps as f64;
        let p = [a[0] + t * dir[0], a[1] + t * dir[1]];
        let before = t - len / steps as f64;
        let mut engaged = 0usize;
        for s in 0..samples {
            // Angles from -90 to +90 degrees about the motion's direction.
            let phi = ((s as f64 + 0.5) / samples as f64 - 0.5) * std::f64::consts::PI;
            let (c, sn) = (phi.cos(), phi.sin());
            let u = [dir[0] * c - dir[1] * sn, dir[0] * sn + dir[1] * c];
            let q = [p[0] + rim * u[0], p[1] + rim * u[1]];
            // Covered by this motion's earlier positions (start to `before`)?
            let along = (q[0] - a[0]) * dir[0] + (q[1] - a[1]) * dir[1];
            let foot = along.clamp(0.0, before);
            let d = (q[0] - a[0] - foot * dir[0]).hypot(q[1] - a[1] - foot * dir[1]);
            if d < rim {
                continue;
            }
            let Some((i, jj)) = grid.cell_of(q[0], q[1]) else {
                continue;
            };
            if dexel.height(i, jj) > lift {
                engaged += 1;
            }
        }
        worst = worst.max(engaged as f64 * std::f64::consts::PI / samples as f64);
    }
    worst
}

/// No progress for the per-motion simulations (the measurement reports its own).
struct Quietly;

impl Progress for Quietly {}
