//! Drop and spin at one footprint (module doc of [`crate::dsm`]).

use super::{CONTACT_TOL, Clearance, Dsm, ROOT_TOL, SPIN_SCAN};
use crate::error::FiveAxisError;
use crate::machine::kinematics::rotate;
use serde::Serialize;
use swarf_geom::solve::{golden_max, illinois};
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// Most evaluations of one root refinement.
const ROOT_STEPS: usize = 200;
/// A normal within this angle of vertical cannot serve as a spin axis, radians.
pub const VERTICAL_NORMAL: f64 = 1e-6;

/// The tool dropped on a face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drop {
    /// The face dropped on (0 or 1).
    pub face: usize,
    /// The vertical pose touching it.
    pub pose: Pose,
    /// First contact `P`, mm.
    pub p: Point3,
    /// Face parameters of `P`.
    pub p_uv: [f64; 2],
    /// The face's unit normal at `P` (upward): the spin axis.
    pub normal: Vec3,
}

/// Which way a spin turns about the normal (right-handed about it: positive).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SpinSide {
    /// Positive angle.
    Plus,
    /// Negative angle.
    Minus,
}

/// A spun pose touching both faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spin {
    /// Spin angle about the normal at `P`, radians.
    pub angle: f64,
    /// The pose.
    pub pose: Pose,
    /// Second contact `Q` on the other face, mm.
    pub q: Point3,
    /// Face parameters of `Q`.
    pub q_uv: [f64; 2],
    /// Clearance from the other face (at least 0, at most [`ROOT_TOL`]-close), mm.
    pub clearance: f64,
    /// Clearance from the face dropped on (0 at `P`; below `-CONTACT_TOL` the pose
    /// gouges it elsewhere), mm.
    pub own_clearance: f64,
}

impl Dsm {
    /// The clearance of the tool at `pose` from face `k`; `None` when the face is out
    /// of reach (more than a tool radius away).
    pub fn clearance(&self, k: usize, pose: &Pose) -> Option<Clearance> {
        self.faces[k.min(1)].clearance(&self.profile, pose, self.cutter.radius())
    }

    /// Clearance as a number: out of reach counts as a tool radius.
    pub(super) fn gap(&self, k: usize, pose: &Pose) -> f64 {
        self.clearance(k, pose)
            .map_or(self.cutter.radius(), |c| c.distance)
    }

    /// The tool dropped with a vertical axis at `xy` onto face `k` alone.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] on `footprint` where the face does not
    /// cover `xy`, where the contact falls on the face's boundary (off the patch), or
    /// where the face's normal at the contact is vertical (no spin axis).
    pub fn drop_on(&self, k: usize, xy: [f64; 2]) -> Result<Drop, FiveAxisError> {
        let bad = |m: String| FiveAxisError::parameter("footprint", m);
        let at = |z: f64| Pose::vertical(Point3::new(xy[0], xy[1], z));
        let Some(floor) = self.height(k, xy) else {
            return Err(bad(format!(
                "({:.4}, {:.4}): face {k} does not lie under the footprint",
                xy[0], xy[1]
            )));
        };
        let lo = floor - 1e-3;
        let hi = self.faces[k].patch().control_box().max.z + 1.0;
        let g = |z: f64| self.gap(k, &at(z));
        let [_, top] = illinois(g, lo, hi, g(lo), g(hi), ROOT_TOL, ROOT_STEPS);
        let pose = at(top.0);
        let c = self
            .clearance(k, &pose)
            .ok_or_else(|| bad("no contact".into()))?;
        let face = &self.faces[k];
        if face.on_boundary(c.uv) {
            return Err(bad(format!(
                "({:.4}, {:.4}): the contact with face {k} falls on its boundary (off the patch)",
                xy[0], xy[1]
            )));
        }
        let d = face.patch().derivs(c.uv[0], c.uv[1]);
        let n = d
            .normal()
            .map(|n| if n.z < 0.0 { -n } else { n })
            .ok_or_else(|| bad("degenerate normal at the contact".into()))?;
        if n.z >= VERTICAL_NORMAL.cos() {
            return Err(bad(format!(
                "({:.4}, {:.4}): face {k} is level at the contact: its normal is vertical, no spin axis",
                xy[0], xy[1]
            )));
        }
        Ok(Drop {
            face: k,
            pose,
            p: c.point,
            p_uv: c.uv,
            normal: n,
        })
    }

    /// `drop` spun by `angle` about its normal at `P`.
    pub fn spun(&self, drop: &Drop, angle: f64) -> Pose {
        let n = drop.normal;
        Pose {
            cl: drop.p + rotate(&n, angle, &(drop.pose.cl - drop.p)),
            axis: rotate(&n, angle, &drop.pose.axis),
        }
    }

    /// The least spin of `drop` to `side` that brings the tool clear of the other
    /// face and touching it; `None` when the dropped tool does not touch the other
    /// face (outside the zone, before `T1`) or no spin up to a half turn clears it.
    pub fn spin(&self, drop: &Drop, side: SpinSide) -> Option<Spin> {
        let other = 1 - drop.face;
        let sign = match side {
            SpinSide::Plus => 1.0,
            SpinSide::Minus => -1.0,
        };
        let f = |a: f64| self.gap(other, &self.spun(drop, sign * a));
        let f0 = f(0.0);
        if f0 > CONTACT_TOL {
            return None;
        }
        let root = if f0 >= 0.0 {
            0.0
        } else {
            let steps = (std::f64::consts::PI / SPIN_SCAN).ceil() as usize;
            let (mut prev, mut fp) = (0.0, f0);
            let mut found = None;
            let mut best = (0.0, f0);
            for i in 1..=steps {
                let a = i as f64 * SPIN_SCAN;
                let fa = f(a);
                if fa >= 0.0 {
                    let [_, hi] = illinois(f, prev, a, fp, fa, ROOT_TOL, ROOT_STEPS);
                    found = Some(hi.0);
                    break;
                }
                if fa > best.1 {
                    best = (a, fa);
                }
                (prev, fp) = (a, fa);
            }
            // At the zone's end the clearance only touches 0 (a double root the scan
            // steps over): the best spin, where it clears within the tolerance.
            match found {
                Some(a) => a,
                None => {
                    let g = golden_max(f, best.0 - SPIN_SCAN, best.0 + SPIN_SCAN, 60);
                    let (a, v) = g.best?;
                    if v < -CONTACT_TOL {
                        return None;
                    }
                    a
                }
            }
        };
        let pose = self.spun(drop, sign * root);
        let c = self.clearance(other, &pose)?;
        Some(Spin {
            angle: sign * root,
            pose,
            q: c.point,
            q_uv: c.uv,
            clearance: c.distance,
            own_clearance: self.gap(drop.face, &pose),
        })
    }
}
