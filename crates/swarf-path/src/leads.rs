//! Lead-in and lead-out moves of three-axis passes: a horizontal arc tangent to the
//! pass at its end, a ramp along the pass's direction at a stated angle, or both (a
//! rising arc), each gouge-checked by exact drops.
//!
//! The lead-in arc of radius `r` ends at the pass's first point `p0` tangent to its
//! first direction `d`: its centre is `p0 + r n` (`n` the left normal of `d`) and it
//! runs counter-clockwise through a quarter turn, `c + r (cos a, sin a)` for `a` from
//! `a0 - 90` to `a0` degrees (the tangent of a counter-clockwise circle at `-n` is
//! `d`). The lead-out continues the pass's last direction the same way. A ramp rises
//! from the pass's end at `tan(angle)` per mm of lead length (along the arc, or
//! straight back along `d` over the approach height when there is no arc). Every lead
//! point stands at the higher of its planned height and the cutter's drop height
//! there ([`MeshDropper`]): a lead never cuts below the part.

use crate::error::PathError;
use swarf_geom::Point3;
use swarf_tool::Pose;
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::{Pass, PathPoint};

/// Angular step of the lead arcs, radians (5 degrees).
const ARC_STEP: f64 = 5.0 * std::f64::consts::PI / 180.0;
/// Horizontal moves shorter than this give no direction, mm.
const MIN_STEP: f64 = 1e-6;

/// Which leads to add.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Leads {
    /// Radius of the lead arcs, mm (none: no arcs).
    pub arc_radius: Option<f64>,
    /// Ramp angle of the leads from the horizontal, radians (none: level leads).
    pub ramp_angle: Option<f64>,
    /// Height a straight ramp climbs, mm (the linking's approach).
    pub ramp_height: f64,
}

impl Leads {
    /// Whether any lead is asked for.
    pub fn any(&self) -> bool {
        self.arc_radius.is_some() || self.ramp_angle.is_some()
    }

    /// Checks the domains: radius 0.01 to 1000 mm, angle 0.5 to 60 degrees.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming `lead_radius` or
    /// `ramp_angle`.
    pub fn check(&self) -> Result<(), PathError> {
        if let Some(r) = self.arc_radius
            && !(0.01..=1000.0).contains(&r)
        {
            return Err(PathError::InvalidParameter {
                field: "lead_radius".into(),
                message: format!("{r} mm: expected 0.01 to 1000 mm"),
            });
        }
        if let Some(a) = self.ramp_angle
            && !(0.5f64.to_radians()..=60f64.to_radians()).contains(&a)
        {
            return Err(PathError::InvalidParameter {
                field: "ramp_angle".into(),
                message: format!(
                    "{} degrees: expected 0.5 to 60 degrees",
                    swarf_geom::units::shown_degrees(a)
                ),
            });
        }
        Ok(())
    }
}

/// Adds the leads to every pass whose poses are vertical (module doc).
///
/// # Errors
/// As [`Leads::check`].
pub fn add_leads(
    passes: &mut [Pass],
    dropper: &MeshDropper,
    leads: &Leads,
) -> Result<(), PathError> {
    leads.check()?;
    if !leads.any() {
        return Ok(());
    }
    let mut scratch = DropScratch::default();
    for pass in passes.iter_mut() {
        let vertical = pass.points.iter().all(|p| p.pose.is_vertical());
        if pass.points.len() < 2 || !vertical {
            continue;
        }
        let pts: Vec<Point3> = pass.points.iter().map(|p| p.pose.cl).collect();
        let (Some(d_in), Some(d_out)) = (direction(pts.iter()), direction(pts.iter().rev())) else {
            continue;
        };
        let first = pts[0];
        let last = pts[pts.len() - 1];
        let mut lead_in = lead(first, [-d_in[0], -d_in[1]], leads, true);
        lead_in.reverse();
        let lead_out = lead(last, d_out, leads, false);
        let lift = |xy: [f64; 3], s: &mut DropScratch| {
            let z = dropper
                .drop(xy[0], xy[1], s)
                .map_or(xy[2], |h| h.z.max(xy[2]));
            PathPoint::new(Pose::vertical(Point3::new(xy[0], xy[1], z)))
        };
        let head: Vec<PathPoint> = lead_in.iter().map(|p| lift(*p, &mut scratch)).collect();
        let tail: Vec<PathPoint> = lead_out.iter().map(|p| lift(*p, &mut scratch)).collect();
        let body = std::mem::take(&mut pass.points);
        pass.points = head.into_iter().chain(body).chain(tail).collect();
    }
    Ok(())
}

/// The unit horizontal direction of the first move of `pts` that has one, pointing
/// along the iteration (for a reversed iterator: the last move, backwards).
fn direction<'a>(mut pts: impl Iterator<Item = &'a Point3>) -> Option<[f64; 2]> {
    let p0 = *pts.next()?;
    pts.find_map(|p| {
        let (dx, dy) = (p.x - p0.x, p.y - p0.y);
        let len = dx.hypot(dy);
        (len > MIN_STEP).then(|| [dx / len, dy / len])
    })
}

/// The lead points leaving `from` (excluded) heading `d` (for a lead-in, `d` points
/// back along the pass and the points come out in leaving order): a quarter arc
/// turning clockwise for a lead-in seen leaving (counter-clockwise when cut), or
/// counter-clockwise for a lead-out, and a ramp.
fn lead(from: Point3, d: [f64; 2], leads: &Leads, lead_in: bool) -> Vec<[f64; 3]> {
    let rise = leads.ramp_angle.map_or(0.0, f64::tan);
    match leads.arc_radius {
        Some(r) => {
            // Lead-in, cut counter-clockwise ending along -d: leaving backwards it
            // turns clockwise; the centre is on the right of the leaving direction.
            let (side, turn) = if lead_in { (-1.0, -1.0) } else { (1.0, 1.0) };
            let n = [-d[1] * side, d[0] * side];
            let c = [from.x + r * n[0], from.y + r * n[1]];
            let a0 = (from.y - c[1]).atan2(from.x - c[0]);
            let steps = (std::f64::consts::FRAC_PI_2 / ARC_STEP).ceil() as usize;
            (1..=steps)
                .map(|k| {
                    let t = std::f64::consts::FRAC_PI_2 * k as f64 / steps as f64;
                    let a = a0 + turn * t;
                    [
                        c[0] + r * a.cos(),
                        c[1] + r * a.sin(),
                        from.z + rise * r * t,
                    ]
                })
                .collect()
        }
        None => {
            let len = if rise > 0.0 {
                leads.ramp_height / rise
            } else {
                0.0
            };
            let steps = (len / 1.0).ceil().max(1.0) as usize;
            (1..=steps)
                .map(|k| {
                    let s = len * k as f64 / steps as f64;
                    [from.x + s * d[0], from.y + s * d[1], from.z + rise * s]
                })
                .collect()
        }
    }
}
