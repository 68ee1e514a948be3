//! The spin zone on a reference line (module doc of [`crate::dsm`]).

use super::{Dsm, ROOT_TOL, Station};
use crate::error::FiveAxisError;
use serde::Serialize;
use swarf_geom::solve::{golden_max, illinois};

/// Offsets are scanned in steps of this fraction of the tool radius.
pub const OFFSET_SCAN: f64 = 0.05;
/// Spins scanned per full turn when the best spin is sought.
pub const TURN_SAMPLES: usize = 72;
/// Golden-section steps refining the best spin.
pub const GOLDEN_STEPS: usize = 60;

/// The part of the tool that binds at the real limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Binding {
    /// The insert's ball at `P` (the paper's limit): the real limit is the ball limit.
    InsertBall,
    /// Another part of the insert (torus or ball end).
    Insert,
    /// The flat bottom.
    Bottom,
    /// The cylindrical flute above the insert.
    Flute,
    /// The top of the flutes (the tool's length).
    Top,
}

/// The spin zone of one band on one reference line: offsets from the edge toward
/// the face spun onto.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Zone {
    /// The dropped tool starts to touch the other face, mm.
    pub t1: f64,
    /// The insert's ball at `P` touches the other face: past it every spin gouges, mm.
    pub t2_ball: f64,
    /// The real limit with the whole cutter, mm (at most `t2_ball`).
    pub t2: f64,
    /// What binds at `t2`.
    pub binding: Binding,
}

impl Dsm {
    /// The clearance from the other face of the tool dropped on face `k` at offset
    /// `w`, spun by `angle`; `None` where the drop fails.
    fn spun_gap(&self, st: &Station, k: usize, w: f64, angle: f64) -> Option<f64> {
        let d = self.drop_on(k, self.footprint(st, k, w)).ok()?;
        Some(self.gap(1 - k, &self.spun(&d, angle)))
    }

    /// The signed distance of the insert's ball at `P` from the other face (0 where
    /// it touches), for the drop on face `k` at offset `w`.
    fn ball_gap(&self, st: &Station, k: usize, w: f64) -> Option<f64> {
        let d = self.drop_on(k, self.footprint(st, k, w)).ok()?;
        let (r, _) = self.insert();
        let centre = d.p + d.normal * r;
        let face = self.face(1 - k).patch();
        let proj = face.project(&centre);
        let n = face.derivs(proj.u, proj.v).normal()?;
        let n = if n.z < 0.0 { -n } else { n };
        let side = (centre - proj.point).dot(&n).signum();
        Some(side * proj.distance - r)
    }

    /// The best spin's clearance (maximised over the full turn) at offset `w`, and
    /// that spin.
    fn best_spin(&self, st: &Station, k: usize, w: f64) -> Option<(f64, f64)> {
        let d = self.drop_on(k, self.footprint(st, k, w)).ok()?;
        let f = |a: f64| self.gap(1 - k, &self.spun(&d, a));
        let step = std::f64::consts::TAU / TURN_SAMPLES as f64;
        let (a0, _) = (0..TURN_SAMPLES)
            .map(|i| {
                let a = -std::f64::consts::PI + i as f64 * step;
                (a, f(a))
            })
            .max_by(|x, y| x.1.total_cmp(&y.1))?;
        let g = golden_max(f, a0 - step, a0 + step, GOLDEN_STEPS);
        g.best.map(|(a, v)| (v, a))
    }

    /// The first offset past `from` (scanning by `step` up to `to`) where `f` turns
    /// from `>= 0` to `< 0`, refined; `None` where it does not.
    fn descent(f: impl Fn(f64) -> Option<f64>, from: f64, to: f64, step: f64) -> Option<f64> {
        let n = ((to - from) / step).ceil().clamp(1.0, 1e5) as usize;
        let mut prev: Option<(f64, f64)> = None;
        for i in 0..=n {
            let w = from + (to - from) * i as f64 / n as f64;
            let Some(v) = f(w) else { continue };
            if let Some(prev) = prev
                && prev.1 >= 0.0
                && v < 0.0
            {
                let g = |x: f64| f(x).unwrap_or(f64::NAN);
                let [ok, _] = illinois(g, prev.0, w, prev.1, v, ROOT_TOL, 200);
                return Some(ok.0);
            }
            prev = Some((w, v));
        }
        None
    }

    /// The spin zone on `station`'s reference line for the tool dropped on face `k`.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] on `zone` where the dropped tool never
    /// starts to touch the other face within two tool radii of the edge, where the
    /// ball limit is not found past `T1`, or where the zone is empty (the real limit
    /// not past `T1`), naming the station.
    pub fn zone(&self, station: &Station, k: usize) -> Result<Zone, FiveAxisError> {
        let radius = self.cutter.radius();
        let bad = |m: &str| {
            FiveAxisError::parameter(
                "zone",
                format!("station {:.4}, face {k} dropped: {m}", station.s),
            )
        };
        let step = OFFSET_SCAN * radius;
        let first = |w: f64| self.spun_gap(station, k, w, 0.0);
        let t1 = Self::descent(first, -2.0 * radius, 2.0 * radius, step).ok_or_else(|| {
            bad("the dropped tool never touches the other face within two tool radii of the edge")
        })?;
        let ball = |w: f64| self.ball_gap(station, k, w);
        let t2_ball = Self::descent(ball, t1, t1 + 3.0 * radius, step).ok_or_else(|| {
            // Say why: usually the drops past T1 fall off a face (a cutter too large
            // for the faces).
            let why = (1..=12)
                .find_map(|i| {
                    let w = t1 + 0.25 * radius * f64::from(i);
                    self.drop_on(k, self.footprint(station, k, w)).err()
                })
                .map_or_else(String::new, |e| format!(" ({e})"));
            bad(&format!(
                "the insert's ball never reaches the other face past T1 = {t1:.6}{why}"
            ))
        })?;
        let best = |w: f64| self.best_spin(station, k, w).map(|b| b.0);
        let inside = t1 + 1e-9 * radius;
        let t2 = Self::descent(best, inside, t2_ball + step, 0.1 * (t2_ball - t1).max(1e-6))
            .unwrap_or(t2_ball)
            .min(t2_ball);
        if t2 <= t1 {
            return Err(bad(&format!(
                "empty zone: T2 = {t2:.6} is not past T1 = {t1:.6} (the cutter does not fit the valley)"
            )));
        }
        let binding = if (t2_ball - t2).abs() <= 1e-6 {
            Binding::InsertBall
        } else {
            self.binding_at(station, k, t2)
        };
        Ok(Zone {
            t1,
            t2_ball,
            t2,
            binding,
        })
    }

    /// The tool part nearest the other face at the best spin at offset `w`.
    fn binding_at(&self, station: &Station, k: usize, w: f64) -> Binding {
        let Some((_, angle)) = self.best_spin(station, k, w) else {
            return Binding::Insert;
        };
        let Ok(d) = self.drop_on(k, self.footprint(station, k, w)) else {
            return Binding::Insert;
        };
        let pose = self.spun(&d, angle);
        let Some(c) = self.clearance(1 - k, &pose) else {
            return Binding::Insert;
        };
        let (rho, z) = pose.to_rho_z(&c.point);
        let (r, inner) = self.insert();
        if z >= self.profile.length() - 1e-6 {
            Binding::Top
        } else if z <= 1e-9 && rho <= inner {
            Binding::Bottom
        } else if z < r {
            Binding::Insert
        } else {
            Binding::Flute
        }
    }
}
