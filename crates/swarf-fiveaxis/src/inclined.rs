//! Inclined-tool (Sturz) positioning along CC paths (thesis 000 §7.3.1, eqs. 7.1-7.4).
//!
//! At a CC point with unit surface normal `n` (out of the material) and feed direction
//! `f`, the tool axis lies in the plane of `n` and `f`, inclined from `n` by the lead
//! angle `alpha` toward the feed: with the unit tangent feed `f_t = unit(f - (f.n) n)`,
//!
//! ```text
//! a = cos(alpha) n + sin(alpha) f_t                                   (eq. 7.3)
//! ```
//!
//! and the tool is placed tangent to the surface at the CC point
//! ([`swarf_tool::Cutter::pose_from_contact`]); for the torus this is eqs. 7.1 and 7.4,
//! `C_insert = CC + r n`, `T = C_insert + R (sin(alpha) n - cos(alpha) f_t)`, the tip a
//! corner radius below `T`. The tool then touches with the front of its bottom and its
//! back is raised by about `2 R sin(alpha)`: "the tool was programmed to machine only
//! with its front ... gouging can be defined as the interference of the back of the
//! tool" (thesis ch. 8). Thesis eq. 7.2 as printed, `e = n x (n x f)`, is `-f_t`, which
//! would put the contact at the back; eqs. 7.3-7.4 with `e = f_t` are what ch. 8
//! describes, and what is implemented here.
//!
//! An optional tilt (side) angle `beta` turns the axis about the feed direction toward
//! the left side `s = n x f_t` (left when looking down the normal):
//! `a = cos(alpha) (cos(beta) n + sin(beta) s) + sin(alpha) f_t`, a unit vector since
//! `n`, `s`, `f_t` are orthonormal.
//!
//! The feed direction at a CC point is the chord of the CC path through it: the central
//! difference `p[i+1] - p[i-1]` inside a pass, one-sided at its ends.

use crate::error::FiveAxisError;
use serde::{Deserialize, Serialize};
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Point3, Vec3};
use swarf_tool::{Cutter, Pose, Profile};
use swarf_toolpath::{Contact, Pass, PathPoint};

/// Lead and tilt angles of the inclined-tool method, radians.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Inclination {
    /// Lead (Sturz) angle from the surface normal toward the feed direction.
    pub lead: f64,
    /// Tilt (side) angle about the feed direction, toward the left of the feed.
    pub tilt: f64,
}

impl Inclination {
    /// A lead angle without tilt, radians.
    pub fn lead(lead: f64) -> Self {
        Inclination { lead, tilt: 0.0 }
    }
}

/// The tool axis of the inclined-tool method at a point with unit surface `normal` and
/// feed direction `feed` (module doc). `None` when the normal is zero or the feed is
/// (nearly) parallel to the normal, so that no feed direction lies in the tangent plane.
pub fn tool_axis(normal: &Vec3, feed: &Vec3, incl: Inclination) -> Option<Vec3> {
    let n = normal.try_normalize(LENGTH_EPS)?;
    let ft = (feed - feed.dot(&n) * n).try_normalize(LENGTH_EPS * feed.norm().max(1.0))?;
    let s = n.cross(&ft);
    let (sa, ca) = incl.lead.sin_cos();
    let (sb, cb) = incl.tilt.sin_cos();
    Some(ca * (cb * n + sb * s) + sa * ft)
}

/// Feed directions along a CC path: central differences inside, one-sided at the ends
/// (not normalised). `None` for a path of fewer than two points.
pub fn feed_directions(points: &[Point3]) -> Option<Vec<Vec3>> {
    let n = points.len();
    if n < 2 {
        return None;
    }
    Some(
        (0..n)
            .map(|i| points[(i + 1).min(n - 1)] - points[i.saturating_sub(1)])
            .collect(),
    )
}

/// The pose of the inclined tool at `contact` with feed direction `feed`; `None` when the
/// tool cannot touch there (see [`tool_axis`] and [`Profile::cl_offset`]).
///
/// # Units
/// mm, radians.
pub fn inclined_pose(
    profile: &Profile,
    contact: &Contact,
    feed: &Vec3,
    incl: Inclination,
) -> Option<Pose> {
    let axis = tool_axis(&contact.normal, feed, incl)?;
    let offset = profile.cl_offset(&contact.normal, &axis)?;
    Some(Pose {
        cl: contact.point + offset,
        axis,
    })
}

/// Places the inclined tool at every contact of a CC path, with the lead angle
/// `leads[i]` at contact `i` (one value for all when `leads` has length 1) and a fixed
/// tilt. `pass` names the pass in errors.
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`FiveAxisError::InvalidParameter`] for fewer than two contacts or a `leads` of the
/// wrong length; [`FiveAxisError::Positioning`] naming the first contact where the
/// tool cannot be placed (degenerate feed, or a normal facing the non-cutting top).
pub fn incline_pass(
    cutter: &Cutter,
    contacts: &[Contact],
    leads: &[f64],
    tilt: f64,
    pass: usize,
) -> Result<Pass, FiveAxisError> {
    if leads.len() != 1 && leads.len() != contacts.len() {
        return Err(FiveAxisError::parameter(
            "leads",
            format!(
                "expected 1 or {} lead angles, found {}",
                contacts.len(),
                leads.len()
            ),
        ));
    }
    let points: Vec<Point3> = contacts.iter().map(|c| c.point).collect();
    let feeds = feed_directions(&points).ok_or_else(|| {
        FiveAxisError::parameter(
            format!("pass {pass}"),
            "a pass needs at least two contact points to give a feed direction",
        )
    })?;
    let profile = cutter.profile();
    let mut out = Vec::with_capacity(contacts.len());
    for (index, (c, f)) in contacts.iter().zip(&feeds).enumerate() {
        let lead = leads[if leads.len() == 1 { 0 } else { index }];
        let pose = inclined_pose(&profile, c, f, Inclination { lead, tilt }).ok_or_else(|| {
            FiveAxisError::Positioning {
                pass,
                index,
                message: format!(
                    "cannot place the tool tangent at CC ({:.4}, {:.4}, {:.4}) with lead {:.3} \
                     degrees: the feed is parallel to the normal or the normal faces the top \
                     of the tool",
                    c.point.x,
                    c.point.y,
                    c.point.z,
                    lead.to_degrees()
                ),
            }
        })?;
        out.push(PathPoint {
            pose,
            contact: Some(*c),
            lifted: 0.0,
        });
    }
    Ok(Pass {
        points: out,
        ..Pass::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contact(p: Point3, n: Vec3) -> Contact {
        Contact {
            point: p,
            normal: n.normalize(),
            face: 0,
            uv: [f64::NAN; 2],
        }
    }

    #[test]
    fn axis_leans_toward_the_feed_and_front_touches() {
        let n = Vec3::z();
        let a = tool_axis(&n, &Vec3::new(1.0, 0.0, 0.3), Inclination::lead(0.1)).unwrap();
        assert!((a - Vec3::new(0.1f64.sin(), 0.0, 0.1f64.cos())).norm() < 1e-15);
        // Bull nose d = 10, r = 2 (torus radius 3): eq. 7.4 with e = f_t.
        let bull = Cutter::bull(10.0, 2.0, None).unwrap();
        let c = contact(Point3::new(1.0, 2.0, 3.0), n);
        let pose = inclined_pose(&bull.profile(), &c, &Vec3::x(), Inclination::lead(0.1)).unwrap();
        let (s, co) = 0.1f64.sin_cos();
        let insert = c.point + 2.0 * n;
        let t = insert + 3.0 * (s * n - co * Vec3::x());
        assert!((pose.cl - (t - 2.0 * pose.axis)).norm() < 1e-12);
        // The contact is ahead of the axis: the front cuts.
        assert!((c.point - pose.cl).dot(&Vec3::x()) > 0.0);
        // The lowest point of the back insert is raised by 2 R sin(alpha) + r (1 - cos(alpha))
        // above the tangent plane.
        let back = pose.cl - 3.0 * Vec3::new(co, 0.0, -s);
        let raised = 2.0 * 3.0 * s + 2.0 * (1.0 - co);
        assert!((back.z - c.point.z - raised).abs() < 1e-12);
    }

    #[test]
    fn tilt_turns_about_the_feed() {
        let n = Vec3::z();
        let a = tool_axis(
            &n,
            &Vec3::x(),
            Inclination {
                lead: 0.2,
                tilt: 0.3,
            },
        )
        .unwrap();
        assert!((a.norm() - 1.0).abs() < 1e-15);
        // Left of +x seen from +z is +y.
        assert!(a.y > 0.0 && a.x > 0.0);
        assert!((a.x - 0.2f64.sin()).abs() < 1e-15);
        assert!((a.y - 0.2f64.cos() * 0.3f64.sin()).abs() < 1e-15);
        assert!(tool_axis(&n, &Vec3::z(), Inclination::lead(0.1)).is_none());
        assert!(tool_axis(&Vec3::zeros(), &Vec3::x(), Inclination::lead(0.1)).is_none());
    }

    #[test]
    fn feed_directions_are_chords() {
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(3.0, 1.0, 0.0),
        ];
        let f = feed_directions(&p).unwrap();
        assert_eq!(f[0], Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(f[1], Vec3::new(3.0, 1.0, 0.0));
        assert_eq!(f[2], Vec3::new(2.0, 1.0, 0.0));
        assert!(feed_directions(&p[..1]).is_none());
    }

    #[test]
    fn pass_errors_name_the_point() {
        let bull = Cutter::bull(10.0, 2.0, None).unwrap();
        let mut cs: Vec<Contact> = (0..4)
            .map(|i| contact(Point3::new(i as f64, 0.0, 0.0), Vec3::z()))
            .collect();
        let pass = incline_pass(&bull, &cs, &[0.05], 0.0, 7).unwrap();
        assert_eq!(pass.points.len(), 4);
        assert!(pass.points.iter().all(|p| p.contact.is_some()));
        cs[2].normal = Vec3::x();
        let e = incline_pass(&bull, &cs, &[0.05], 0.0, 7).unwrap_err();
        assert!(e.to_string().starts_with("pass 7, point 2:"), "{e}");
        let e = incline_pass(&bull, &cs[..1], &[0.05], 0.0, 7).unwrap_err();
        assert!(e.to_string().contains("at least two"), "{e}");
        let e = incline_pass(&bull, &cs, &[0.05, 0.1], 0.0, 7).unwrap_err();
        assert!(e.to_string().contains("lead angles"), "{e}");
    }
}
