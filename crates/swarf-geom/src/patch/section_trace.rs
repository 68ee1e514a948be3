//! Tracing one branch of a patch-plane intersection curve (predictor-corrector).
//!
//! The section is the zero set of `f(u, v) = n . S(u, v) - d` in the parameter plane,
//! with gradient `g = (n . S_u, n . S_v)`. Along it the tangent in parameters is
//! `t = (g_v, -g_u)` (kept with one sign for the whole branch) and in space
//! `T = t_u S_u + t_v S_v`.
//!
//! - **Step.** The section curve lies in the plane, so its curvature vector `kappa w`
//!   (`w = n x T/|T|`) has normal component `k_n(T)` (Meusnier): `kappa = k_n / (w . N)`,
//!   and `w . N = +-|n x N|`, the sine of the angle between plane and surface normals. A
//!   chord of length `h` on a circle of curvature `kappa` sags `kappa h^2 / 8`, so
//!   `h = sqrt(8 s tol / kappa)` with a safety share `s`; the step is also held within
//!   one seed-grid cell in parameters so that it cannot jump to another branch.
//! - **Predictor** `(u, v) + h t/|T|`, cut short where it meets the domain boundary;
//!   **corrector**: Newton on `f` along `g` (the minimum-norm step), clamped into the
//!   domain: a coordinate that would leave it stays on its bound and Newton goes on in
//!   the other coordinate alone, which lands exactly on the boundary crossing where a
//!   branch leaves the patch.
//! - **Check and refine.** A step is kept when the curve points at 1/4, 1/2 and 3/4 of
//!   the parameter chord (corrected onto the curve) lie within the tolerance of the 3D
//!   chord and inside the domain (else the curve left the patch in between; only next
//!   to an exit point may they lie on the boundary), the new point is about `h` away and the tangent has not reversed; otherwise
//!   `h` halves (Allgower & Georg, "Introduction to Numerical Continuation Methods",
//!   ch. 6, step-length adaptation).
//! - **End.** On the domain boundary, when the branch comes back to its start heading
//!   the same way (a closed loop), or when the step collapses: then on the nearest
//!   domain edge if the crossing there is within the tolerance (a branch grazing the
//!   boundary), else where it stopped (a singular point, where `g = 0`).

use super::Patch;
use super::section::SurfaceSample;
use crate::math::{Vec3, point_segment_distance};
use crate::tol::{MAX_NEWTON_ITERATIONS, SOLVER_LENGTH};

/// Share of `tol` the curvature-based step aims at (the rest absorbs its variation).
const STEP_SHARE: f64 = 0.5;
/// Share of `tol` the chord check allows.
const CHORD_SHARE: f64 = 0.9;
/// Parameter chord fractions at which the curve is compared with the chord.
const CHECK_AT: [f64; 3] = [0.25, 0.5, 0.75];
/// A branch stops after this many samples (a guard against a stalled trace).
const MAX_SAMPLES: usize = 200_000;
/// A step shorter than this fraction of the patch size ends the branch.
const MIN_STEP_REL: f64 = 1e-9;

/// How a traced branch ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum End {
    /// It reached the domain boundary.
    Boundary,
    /// It came back to its first sample.
    Closed,
    /// The step collapsed (singular point) or the sample budget ran out.
    Stalled,
}

/// The implicit function of a plane section on a patch, with the tracing tolerances.
pub(super) struct Section<'a> {
    pub(super) patch: &'a Patch,
    pub(super) normal: Vec3,
    pub(super) offset: f64,
    pub(super) tol: f64,
    /// Largest parameter step in each direction (one seed-grid cell).
    pub(super) cell: [f64; 2],
    pub(super) dom: [[f64; 2]; 2],
    /// Shortest 3D step before a branch is abandoned, mm.
    pub(super) min_step: f64,
}

impl<'a> Section<'a> {
    pub(super) fn new(
        patch: &'a Patch,
        normal: Vec3,
        offset: f64,
        tol: f64,
        cell: [f64; 2],
    ) -> Self {
        let size = patch.control_box().size().norm();
        Section {
            patch,
            normal,
            offset,
            tol,
            cell,
            dom: patch.domain(),
            min_step: MIN_STEP_REL * size.max(1.0),
        }
    }

    /// `f(u, v)`, mm.
    pub(super) fn f(&self, uv: [f64; 2]) -> f64 {
        self.normal.dot(&self.patch.eval(uv[0], uv[1]).coords) - self.offset
    }

    /// `f` and its gradient.
    pub(super) fn f_grad(&self, uv: [f64; 2]) -> (f64, [f64; 2]) {
        let d = self.patch.derivs(uv[0], uv[1]);
        let f = self.normal.dot(&d.point.coords) - self.offset;
        (f, [self.normal.dot(&d.du), self.normal.dot(&d.dv)])
    }

    pub(super) fn sample(&self, uv: [f64; 2]) -> SurfaceSample {
        SurfaceSample {
            u: uv[0],
            v: uv[1],
            point: self.patch.eval(uv[0], uv[1]),
        }
    }

    pub(super) fn on_boundary(&self, uv: [f64; 2]) -> bool {
        (0..2).any(|k| uv[k] <= self.dom[k][0] || uv[k] >= self.dom[k][1])
    }

    /// Newton onto `f = 0` from `uv`, clamped into the domain (module doc).
    pub(super) fn correct(&self, uv: [f64; 2]) -> Option<[f64; 2]> {
        self.correct_with(uv, [false; 2])
    }

    /// [`Section::correct`] with the coordinates marked in `fixed` held from the start.
    fn correct_with(&self, uv: [f64; 2], mut fixed: [bool; 2]) -> Option<[f64; 2]> {
        let mut uv = [0, 1].map(|k| uv[k].clamp(self.dom[k][0], self.dom[k][1]));
        for _ in 0..MAX_NEWTON_ITERATIONS {
            let (f, g) = self.f_grad(uv);
            if f.abs() <= SOLVER_LENGTH {
                return Some(uv);
            }
            let free: [f64; 2] = [0, 1].map(|k| if fixed[k] { 0.0 } else { g[k] });
            let norm2 = free[0] * free[0] + free[1] * free[1];
            if norm2.is_nan() || norm2 <= 0.0 || !f.is_finite() {
                return None;
            }
            for k in 0..2 {
                let next = uv[k] - f * free[k] / norm2;
                let clamped = next.clamp(self.dom[k][0], self.dom[k][1]);
                fixed[k] |= clamped != next;
                uv[k] = clamped;
            }
        }
        None
    }

    /// Unit 3D tangent, the parameter step per mm along it, and the step length that
    /// the section curve's curvature allows, at `uv` heading along `sign`.
    fn heading(&self, uv: [f64; 2], sign: f64) -> Option<(Vec3, [f64; 2], f64)> {
        let d = self.patch.derivs(uv[0], uv[1]);
        let g = [self.normal.dot(&d.du), self.normal.dot(&d.dv)];
        let t = [sign * g[1], -sign * g[0]];
        let tangent = d.du * t[0] + d.dv * t[1];
        let len = tangent.norm();
        if len.is_nan() || len <= 0.0 || !len.is_finite() {
            return None;
        }
        let unit = tangent / len;
        let per_mm = [t[0] / len, t[1] / len];
        let sine = d.normal().map_or(0.0, |n| n.cross(&self.normal).norm());
        let kn = d.normal_curvature(&unit).unwrap_or(0.0).abs();
        let kappa = if sine > 0.0 { kn / sine } else { f64::INFINITY };
        let by_curvature = (8.0 * STEP_SHARE * self.tol / kappa).sqrt();
        let by_cell = (0..2)
            .map(|k| self.cell[k] / per_mm[k].abs())
            .fold(f64::INFINITY, f64::min);
        Some((unit, per_mm, by_curvature.min(by_cell)))
    }

    /// `from + step`, or where that step first meets the domain boundary.
    fn onto_domain(&self, from: [f64; 2], step: [f64; 2]) -> [f64; 2] {
        let mut frac = 1.0f64;
        for k in 0..2 {
            let to = from[k] + step[k];
            if to < self.dom[k][0] && step[k] < 0.0 {
                frac = frac.min((self.dom[k][0] - from[k]) / step[k]);
            } else if to > self.dom[k][1] && step[k] > 0.0 {
                frac = frac.min((self.dom[k][1] - from[k]) / step[k]);
            }
        }
        let frac = frac.max(0.0);
        [0, 1].map(|k| (from[k] + step[k] * frac).clamp(self.dom[k][0], self.dom[k][1]))
    }

    /// True when the curve between samples `a` and `b` stays within the tolerance of
    /// their chord at the check fractions.
    pub(super) fn chord_ok(&self, a: &SurfaceSample, b: &SurfaceSample) -> bool {
        let (pa, pb) = (a.point, b.point);
        let exits = self.on_boundary([b.u, b.v]);
        CHECK_AT.iter().all(|s| {
            let uv = [a.u + (b.u - a.u) * s, a.v + (b.v - a.v) * s];
            self.correct(uv).is_some_and(|c| {
                let q = self.patch.eval(c[0], c[1]);
                let at_exit = exits && (q - pb).norm() <= 0.25 * (pb - pa).norm();
                let stays_inside = at_exit || !self.on_boundary(c);
                stays_inside && point_segment_distance(&q, &pa, &pb) <= CHORD_SHARE * self.tol
            })
        })
    }

    /// Traces from `start` along `sign` until the boundary, an interior start again
    /// heading the same way (a closed loop when `may_close`, else a stall, so that no
    /// trace runs round forever), or a stall. The returned samples begin with `start`.
    pub(super) fn trace(
        &self,
        start: SurfaceSample,
        sign: f64,
        may_close: bool,
    ) -> (Vec<SurfaceSample>, End) {
        let mut out = vec![start];
        let mut h = f64::INFINITY;
        let Some((start_tangent, _, _)) = self.heading([start.u, start.v], sign) else {
            return (out, End::Stalled);
        };
        while out.len() < MAX_SAMPLES {
            let cur = out[out.len() - 1];
            let Some((tangent, per_mm, h_max)) = self.heading([cur.u, cur.v], sign) else {
                return (out, End::Stalled);
            };
            let back = start.point - cur.point;
            let closing = out.len() > 2
                && !self.on_boundary([start.u, start.v])
                && back.dot(&tangent) > 0.0
                && back.dot(&start_tangent) > 0.0
                && tangent.dot(&start_tangent) > 0.0;
            if closing && back.norm() <= h_max && self.chord_ok(&cur, &start) {
                let end = if may_close { End::Closed } else { End::Stalled };
                return (out, end);
            }
            h = (2.0 * h).min(h_max);
            let Some(next) = self.step(&cur, &tangent, per_mm, &mut h, sign) else {
                return match self.finish_on_boundary(&cur) {
                    Some(last) => {
                        out.push(last);
                        (out, End::Boundary)
                    }
                    None => (out, End::Stalled),
                };
            };
            let on_edge = self.on_boundary([next.u, next.v]);
            out.push(next);
            if on_edge {
                return (out, End::Boundary);
            }
        }
        (out, End::Stalled)
    }

    /// Where a stalled trace is within the tolerance of the nearest domain edge (a
    /// branch grazing the boundary as it leaves), the crossing on that edge.
    fn finish_on_boundary(&self, cur: &SurfaceSample) -> Option<SurfaceSample> {
        let (k, bound) = (0..2)
            .flat_map(|k| self.dom[k].map(|b| (k, b)))
            .min_by(|a, b| {
                let gap =
                    |(k, bound): (usize, f64)| ([cur.u, cur.v][k] - bound).abs() / self.cell[k];
                gap(*a).total_cmp(&gap(*b))
            })?;
        let mut uv = [cur.u, cur.v];
        uv[k] = bound;
        let mut fixed = [false; 2];
        fixed[k] = true;
        let last = self.sample(self.correct_with(uv, fixed)?);
        let near = (last.point - cur.point).norm() <= self.tol;
        (near && last != *cur).then_some(last)
    }

    /// One accepted step from `cur`, halving `h` until the checks pass.
    fn step(
        &self,
        cur: &SurfaceSample,
        tangent: &Vec3,
        per_mm: [f64; 2],
        h: &mut f64,
        sign: f64,
    ) -> Option<SurfaceSample> {
        while *h >= self.min_step {
            let pred = self.onto_domain([cur.u, cur.v], [per_mm[0] * *h, per_mm[1] * *h]);
            let next = self.correct(pred).map(|uv| self.sample(uv));
            if let Some(n) = next {
                let dist = (n.point - cur.point).norm();
                let edge = self.on_boundary([n.u, n.v]) && dist > 0.0;
                let moved = dist < 2.0 * *h && (dist > 0.25 * *h || edge);
                let ahead = (n.point - cur.point).dot(tangent) > 0.0;
                let same_way = self
                    .heading([n.u, n.v], sign)
                    .is_some_and(|(t, _, _)| t.dot(tangent) > 0.0);
                if moved && ahead && same_way && self.chord_ok(cur, &n) {
                    return Some(n);
                }
            }
            *h *= 0.5;
        }
        None
    }
}
