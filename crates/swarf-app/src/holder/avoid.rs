//! Five-axis holder avoidance: a positioned ball-end path whose shank or holder
//! meets the part is tilted clear, pose by pose, instead of refused.
//!
//! At each colliding pose the least extra tilt that clears is searched
//! ([`clearing_tilt`]) away from where the piece touches (the direction from the
//! contact to the tip, normal to the axis), about the ball's centre: a ball is the
//! same solid about its centre whatever its axis, so its cut does not change and
//! only the tip moves, to `centre - R a'` (the flutes above the ball lean with the
//! axis: the caller runs the positioning's gouge check again). A collision between
//! two poses of a pass asks its tilt of both ends.
//!
//! Along each pass the tilts are spread under the positioning's tilt-rate limit
//! `r` (radians per mm of the tip's path): the applied tilt is `T(s) = max_k (t_k -
//! r |s - s_k|)`, the least tilt that is at least every asked `t_k` at its pose
//! `s_k` and changes by at most `r` per mm (the envelope the gouge-free lead is
//! smoothed by); its direction is that of the nearest pose that asks. The path is
//! checked again and the round repeated on what still collides, [`ROUNDS`] times
//! at most; what no tilt up to the limit clears is left as it was, and the job is
//! refused naming it ([`super::path::refusal`]).
//!
//! The limit of a gouge-free lead is kept: a tilted axis may lean from the
//! contact's normal by at most `max_alpha` (or as far as it leaned before).

use super::HolderCheck;
use super::path::check_path;
use crate::error::Result;
use serde::Serialize;
use std::collections::BTreeMap;
use swarf_fiveaxis::autotilt::smooth;
use swarf_geom::{TriMesh, Vec3};
use swarf_tool::holder::tilted::{Tilt, TiltSearch, clearing_tilt};
use swarf_tool::library::LibraryTool;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::Toolpath;

/// Rounds of check, tilt and spread.
pub const ROUNDS: usize = 4;

/// Added to each tilt asked, radians (the bisection's answer may clear by nothing).
const MARGIN: f64 = 1e-5;

/// The bracket each tilt search is refined to, radians (0.0006 degrees).
const SEARCH_TOLERANCE: f64 = 1e-5;

/// Colliding poses searched at most in one round (each search lays the mesh out
/// along a few dozen axes); a path with more is left to the refusal, which names
/// the stick-out that clears.
pub const MAX_SEARCHED: usize = 5_000;

/// How far avoidance may tilt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest change of the tilt per mm of the tip's path, radians per mm.
    pub max_rate: f64,
    /// Largest extra tilt of one search, radians.
    pub max_tilt: f64,
    /// Largest angle of an axis from its contact's normal, radians (`None`: no
    /// limit but `max_tilt`).
    pub max_lean: Option<f64>,
}

/// What avoidance changed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Avoidance {
    /// Poses whose axis was turned.
    pub tilted_poses: usize,
    /// The largest angle between a pose's axis before and after, degrees.
    pub largest_tilt_deg: f64,
    /// Rounds of check and tilt run.
    pub rounds: usize,
}

impl Avoidance {
    /// The program's header line.
    pub fn note(&self) -> String {
        format!(
            "holder: {} poses tilted clear, up to {:.3} deg",
            self.tilted_poses, self.largest_tilt_deg
        )
    }
}

/// The tilt one pose asks: its amount (radians) and direction (unit, any length
/// along the axis is removed when applied).
#[derive(Debug, Clone, Copy)]
struct Ask {
    tilt: f64,
    toward: Vec3,
}

/// Tilts the passes of `toolpath` (a positioned five-axis path) until `tool`'s
/// shank and holder clear `mesh`, within `limits` (module doc). `None` when no
/// pose was tilted: nothing collided, no tilt cleared, more than [`MAX_SEARCHED`]
/// poses collided, or the tool is not a ball (its cut would change with the axis).
/// What still collides is refused by the caller's check.
///
/// # Errors
/// A shank or holder segment the kernel refuses.
pub fn avoid(
    mesh: &TriMesh,
    tool: &LibraryTool,
    toolpath: &mut Toolpath,
    limits: &Limits,
) -> Result<Option<Avoidance>> {
    let Cutter::Ball { radius, .. } = tool.assembly.cutter else {
        return Ok(None);
    };
    let before: Vec<Vec<Vec3>> = toolpath
        .passes
        .iter()
        .map(|p| p.points.iter().map(|q| q.pose.axis).collect())
        .collect();
    let search = TiltSearch {
        max_tilt: limits.max_tilt,
        tolerance: SEARCH_TOLERANCE,
        pivot: radius,
        ..TiltSearch::default()
    };
    let mut rounds = 0;
    for _ in 0..ROUNDS {
        let check = check_path(mesh, toolpath, tool, "")?;
        if check.collisions.is_empty() || check.collisions.len() > MAX_SEARCHED {
            break;
        }
        rounds += 1;
        let asks = asks(mesh, tool, &check, &search)?;
        if asks.is_empty() {
            break;
        }
        for (p, pass_asks) in by_pass(asks) {
            spread_and_tilt(toolpath, p, &pass_asks, radius, limits);
        }
    }
    let mut tilted_poses = 0;
    let mut largest = 0f64;
    for (pass, axes) in toolpath.passes.iter().zip(&before) {
        for (q, a) in pass.points.iter().zip(axes) {
            let angle = q.pose.axis.angle(a);
            if angle > 0.0 {
                tilted_poses += 1;
                largest = largest.max(angle);
            }
        }
    }
    if tilted_poses == 0 {
        return Ok(None);
    }
    Ok(Some(Avoidance {
        tilted_poses,
        largest_tilt_deg: largest.to_degrees(),
        rounds,
    }))
}

/// The tilt each colliding pose asks of the pass points it lies between, keyed by
/// pass and point; collisions no tilt clears ask nothing.
fn asks(
    mesh: &TriMesh,
    tool: &LibraryTool,
    check: &HolderCheck,
    search: &TiltSearch,
) -> Result<BTreeMap<[usize; 2], Ask>> {
    let mut out: BTreeMap<[usize; 2], Ask> = BTreeMap::new();
    for c in &check.collisions {
        let Some([p, k]) = c.pass else { continue };
        let pose = Pose {
            cl: c.cl,
            axis: c.axis,
        };
        let toward = c.cl - c.contact;
        let Tilt::Clears { tilt, .. } =
            clearing_tilt(&tool.assembly, mesh, &pose, &toward, search)?
        else {
            continue;
        };
        let ask = Ask {
            tilt: tilt + MARGIN,
            toward,
        };
        for key in [[p, k.saturating_sub(1)], [p, k]] {
            let e = out.entry(key).or_insert(Ask { tilt: 0.0, toward });
            if ask.tilt > e.tilt {
                *e = ask;
            }
        }
    }
    Ok(out)
}

/// `asks` grouped by pass: each pass's `(point, ask)` in point order.
fn by_pass(asks: BTreeMap<[usize; 2], Ask>) -> BTreeMap<usize, Vec<(usize, Ask)>> {
    let mut out: BTreeMap<usize, Vec<(usize, Ask)>> = BTreeMap::new();
    for ([p, k], ask) in asks {
        out.entry(p).or_default().push((k, ask));
    }
    out
}

/// Spreads the asks of pass `p` under the rate limit ([`smooth`], the least
/// envelope the gouge-free lead is smoothed by) and turns its axes about the ball
/// centres, each toward the direction of the nearest ask (module doc).
fn spread_and_tilt(
    toolpath: &mut Toolpath,
    p: usize,
    asks: &[(usize, Ask)],
    radius: f64,
    limits: &Limits,
) {
    let points = &mut toolpath.passes[p].points;
    let n = points.len();
    let mut s = vec![0.0; n];
    for i in 1..n {
        s[i] = s[i - 1] + (points[i].pose.cl - points[i - 1].pose.cl).norm();
    }
    let mut tilts = vec![0.0; n];
    for &(k, ask) in asks {
        tilts[k] = ask.tilt;
    }
    smooth(&mut tilts, &s, limits.max_rate);
    for (i, point) in points.iter_mut().enumerate() {
        let nearest = asks
            .iter()
            .min_by(|x, y| (s[x.0] - s[i]).abs().total_cmp(&(s[y.0] - s[i]).abs()));
        let (Some(&(_, ask)), true) = (nearest, tilts[i] > 0.0) else {
            continue;
        };
        let a = point.pose.axis;
        let Some(d) = (ask.toward - ask.toward.dot(&a) * a).try_normalize(1e-12) else {
            continue;
        };
        let t = tilts[i].min(limits.max_tilt);
        let axis = a * t.cos() + d * t.sin();
        if let (Some(max), Some(c)) = (limits.max_lean, &point.contact)
            && axis.angle(&c.normal) > max.max(a.angle(&c.normal)) + 1e-12
        {
            continue;
        }
        let centre = point.pose.cl + radius * a;
        point.pose = Pose {
            cl: centre - radius * axis,
            axis,
        };
    }
}
