//! CC paths on parallel vertical drive planes at a fixed cross feed and a fixed step,
//! as in the experiments of thesis 000 ch. 6 and 8 ("the feed direction was off the
//! X-axis by 60 degrees and the cross feed was 3.5 mm"; steps of 1 mm along a pass).
//!
//! Plane `k` holds the horizontal line `o_k + t f` with `f = (cos(angle), sin(angle),
//! 0)` and `o_k = (offset + k cross_feed) n`, `n = (-sin(angle), cos(angle), 0)`. Along
//! it, CC points are the design points above `t = t_0 + j step`
//! ([`DesignSurface::locate`]); a run of consecutive points over the design is a pass,
//! and each end of a run is extended to the design's edge by bisection on `t` (to
//! [`EDGE_TOL`]). Normals point to `+z`. Passes alternate direction when `zigzag`.
//! This is the fixed-step counterpart of the iso-planar strategy of swarf-path, whose
//! side step follows a scallop height and whose steps follow a chordal tolerance.

use crate::design::DesignSurface;
use crate::error::FiveAxisError;
use serde::{Deserialize, Serialize};
use swarf_geom::{Aabb, Point3, Vec3};
use swarf_path::Contact;

/// Pass ends are placed within this of the design's edge along the line (mm).
pub const EDGE_TOL: f64 = 1e-6;

/// Drive planes for [`drive_plane_passes`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DrivePlanes {
    /// Feed direction, radians from +X toward +Y.
    pub angle: f64,
    /// Distance between neighbouring planes, mm.
    pub cross_feed: f64,
    /// Distance between CC points along a plane (in XY), mm.
    pub step: f64,
    /// Alternate the direction of consecutive passes.
    pub zigzag: bool,
}

/// CC paths of the design on the drive planes (module doc), in plane order.
///
/// # Errors
/// [`FiveAxisError::InvalidParameter`] when `cross_feed` or `step` is not finite and
/// > 0, or `angle` is not finite.
pub fn drive_plane_passes(
    design: &DesignSurface,
    bounds: &Aabb,
    dp: &DrivePlanes,
) -> Result<Vec<Vec<Contact>>, FiveAxisError> {
    for (name, v) in [("cross_feed", dp.cross_feed), ("step", dp.step)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(FiveAxisError::parameter(
                name,
                format!("expected a finite length > 0 mm, found {v}"),
            ));
        }
    }
    if !dp.angle.is_finite() {
        return Err(FiveAxisError::parameter("angle", "expected a finite angle"));
    }
    let (s, c) = dp.angle.sin_cos();
    let f = Vec3::new(c, s, 0.0);
    let n = Vec3::new(-s, c, 0.0);
    let corners = [
        [bounds.min.x, bounds.min.y],
        [bounds.min.x, bounds.max.y],
        [bounds.max.x, bounds.min.y],
        [bounds.max.x, bounds.max.y],
    ];
    let range = |d: &Vec3| {
        corners
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |r, p| {
                let v = d.x * p[0] + d.y * p[1];
                (r.0.min(v), r.1.max(v))
            })
    };
    let (o0, o1) = range(&n);
    let (t0, t1) = range(&f);
    let mut passes = Vec::new();
    let planes = ((o1 - o0) / dp.cross_feed).floor() as i64;
    for k in 0..=planes.max(0) {
        let o = o0 + 0.5 * ((o1 - o0) - planes as f64 * dp.cross_feed) + k as f64 * dp.cross_feed;
        for run in plane_runs(design, &(o * n), &f, t0, t1, dp.step) {
            passes.push(run);
        }
    }
    if dp.zigzag {
        for (i, p) in passes.iter_mut().enumerate() {
            if i % 2 == 1 {
                p.reverse();
            }
        }
    }
    Ok(passes)
}

/// Runs of CC points along the line `origin + t f`, `t` in `[t0, t1]`.
fn plane_runs(
    design: &DesignSurface,
    origin: &Vec3,
    f: &Vec3,
    t0: f64,
    t1: f64,
    step: f64,
) -> Vec<Vec<Contact>> {
    let at = |t: f64| contact(design, origin.x + t * f.x, origin.y + t * f.y);
    let count = ((t1 - t0) / step).ceil() as usize;
    let mut runs = Vec::new();
    let mut run: Vec<Contact> = Vec::new();
    let mut prev_t = t0;
    let close = |a: &Contact, b: &Contact| (a.point - b.point).xy().norm() < 0.25 * step;
    for j in 0..=count {
        let t = (t0 + j as f64 * step).min(t1);
        match at(t) {
            Some(c) => {
                if run.is_empty()
                    && j > 0
                    && let Some(e) = edge(&at, prev_t, t)
                {
                    run.push(e);
                }
                if run.last().is_none_or(|l| !close(l, &c)) {
                    run.push(c);
                }
            }
            None => {
                if !run.is_empty() {
                    if let Some(e) = edge(&at, t, prev_t) {
                        if run.len() > 1 && run.last().is_some_and(|l| close(l, &e)) {
                            run.pop();
                        }
                        run.push(e);
                    }
                    runs.push(std::mem::take(&mut run));
                }
            }
        }
        prev_t = t;
    }
    if run.len() > 1 {
        runs.push(run);
    }
    runs.retain(|r| r.len() > 1);
    runs
}

/// The design point nearest the edge between `outside` (no design) and `inside`.
fn edge(at: &impl Fn(f64) -> Option<Contact>, outside: f64, inside: f64) -> Option<Contact> {
    let (mut out, mut inn) = (outside, inside);
    let mut best = None;
    while (out - inn).abs() > EDGE_TOL {
        let mid = 0.5 * (out + inn);
        match at(mid) {
            Some(c) => {
                best = Some(c);
                inn = mid;
            }
            None => out = mid,
        }
    }
    best
}

/// The design contact above `(x, y)`, normal toward `+z`.
pub fn contact(design: &DesignSurface, x: f64, y: f64) -> Option<Contact> {
    let l = design.locate(x, y)?;
    let d = design.patch(l.patch)?.derivs(l.u, l.v);
    let n = d.normal()?;
    Some(Contact {
        point: Point3::new(x, y, l.z),
        normal: if n.z < 0.0 { -n } else { n },
        face: l.patch,
        uv: [l.u, l.v],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::tests::die;

    #[test]
    fn die_passes_cover_the_part_at_the_cross_feed() {
        let part = die();
        let design = DesignSurface::new(&part);
        let dp = DrivePlanes {
            angle: 60f64.to_radians(),
            cross_feed: 3.5,
            step: 1.0,
            zigzag: true,
        };
        let passes = drive_plane_passes(&design, &part.control_box(), &dp).unwrap();
        assert!(passes.len() > 30, "{}", passes.len());
        let n = Vec3::new(-dp.angle.sin(), dp.angle.cos(), 0.0);
        let offsets: Vec<f64> = passes.iter().map(|p| n.dot(&p[0].point.coords)).collect();
        for w in offsets.windows(2) {
            assert!((w[1] - w[0] - 3.5).abs() < 1e-9);
        }
        for (i, p) in passes.iter().enumerate() {
            for w in p.windows(2) {
                let d = w[1].point - w[0].point;
                assert!(d.xy().norm() <= 1.25 + 1e-9 && d.xy().norm() >= 0.25);
                let along = d.x * dp.angle.cos() + d.y * dp.angle.sin();
                assert_eq!(along > 0.0, i % 2 == 0);
            }
            for c in p {
                assert!(c.normal.z > 0.0 && (c.normal.norm() - 1.0).abs() < 1e-12);
                let z = design.height(c.point.x, c.point.y).unwrap().0;
                assert!((z - c.point.z).abs() < 1e-12);
            }
        }
        let bad = DrivePlanes { step: 0.0, ..dp };
        assert!(drive_plane_passes(&design, &part.control_box(), &bad).is_err());
    }
}
