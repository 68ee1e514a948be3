//! The scallop between two tools in a cross-section of the surface (Feng & Li 2002,
//! the scallop point; paper 004 fig. 7).
//!
//! In the plane through a CC point `P` normal to its path tangent `T`, each tool's
//! envelope is taken as a circle of radius `r` tangent to the surface at its contact:
//! about `P + r N` for the tool at `P`, and for the tool touching the surface at `Q`
//! about `Q + r N'` projected into the plane (with the paths' tangents parallel, Feng
//! and Li's assumption, the swept envelope of the next path cuts the plane in exactly
//! that circle; where they are not, the true section is an ellipse around it and the
//! true scallop is smaller). The two circles cross at two points; the one nearer the
//! surface (the midpoint of `P` and `Q`) is the scallop crest, and its distance to the
//! surface along the normal at its foot (the patch's projection; beyond an edge, the
//! distance to the tangent plane there, i.e. the surface continued) is the scallop
//! height.
//!
//! The radius `r` is the station's ([`Station::radius`]: a ball's own radius, exactly
//! its envelope; for other cutters the effective radius [`crate::strategy::iso::scallop`] plans
//! with), except across a convex ridge, where the tools touch with their corners
//! facing and the corner radius is used ([`crate::stepping::side_step`], "Convex ridges"). A
//! sharp rim (flat end mill) cuts no ridge between two passes at any step; it keeps
//! the station's radius here and [`crate::strategy::iso::scallop`] reports the ridge uncovered.

use crate::cl_curve::tool_side_normal;
use crate::stepping::scallop_step::Station;
use crate::stepping::side_step::{SideStep, corners_face};
use swarf_geom::{Patch, Point3, SurfaceDerivs, Vec3};

/// Scallop height between the tool at the station and the tool touching the surface
/// at `d` (parameters `uv`), in the station's cross-section (module doc), mm;
/// infinite where the two envelopes do not meet.
pub fn scallop(
    patch: &Patch,
    side: &SideStep,
    st: &Station,
    d: &SurfaceDerivs,
    uv: [f64; 2],
) -> f64 {
    let Some(n) = tool_side_normal(d) else {
        return f64::INFINITY;
    };
    let r = radius(side, st, &d.point, &n);
    if r <= 0.0 {
        return f64::INFINITY;
    }
    let t = st.tangent;
    let c1 = st.d.point + r * st.normal;
    let c2 = d.point + r * n;
    let c2 = c2 - (c2 - st.d.point).dot(&t) * t;
    let mid = Point3::from(0.5 * (st.d.point.coords + d.point.coords));
    let Some(crest) = crest(&c1, r, &c2, r, &mid) else {
        return f64::INFINITY;
    };
    let pr = patch.project_from(&crest, 0.5 * (st.uv[0] + uv[0]), 0.5 * (st.uv[1] + uv[1]));
    let below = patch.derivs(pr.u, pr.v);
    // Along the normal at the foot: the distance inside the patch, and the distance to
    // the tangent plane at the edge where the crest lies beyond it.
    tool_side_normal(&below).map_or(pr.distance, |nn| (crest - pr.point).dot(&nn))
}

/// The circle radius for the station's tool and the tool touching `q` with normal
/// `n` (module doc).
fn radius(side: &SideStep, st: &Station, q: &Point3, n: &Vec3) -> f64 {
    if side.corner() > 0.0 && corners_face(&st.normal, n, &(q - st.d.point)) {
        side.corner()
    } else {
        st.radius
    }
}

/// The crossing of two coplanar circles nearest `near`; `None` when they do not meet.
fn crest(c1: &Point3, r1: f64, c2: &Point3, r2: f64, near: &Point3) -> Option<Point3> {
    let d = c2 - c1;
    let len = d.norm();
    if len == 0.0 || len > r1 + r2 || len < (r1 - r2).abs() {
        return None;
    }
    let a = (r1 * r1 - r2 * r2 + len * len) / (2.0 * len);
    let hh = (r1 * r1 - a * a).max(0.0).sqrt();
    let e = d / len;
    let base = c1 + a * e;
    let mut perp = (near - base) - e * e.dot(&(near - base));
    if perp.norm() == 0.0 {
        return Some(base);
    }
    perp.normalize_mut();
    Some(base + hh * perp)
}

/// Material left at the surface point `q` (unit normal `normal`, toward the tool) by
/// the station's tool alone: where the ray along the normal enters its circle (of the
/// corner radius across a convex ridge: module doc).
pub fn alone(side: &SideStep, st: &Station, q: &Point3, normal: &Vec3) -> f64 {
    let r = radius(side, st, q, normal);
    let centre = st.d.point + r * st.normal;
    let m = q - centre;
    let b = m.dot(normal);
    let cc = m.norm_squared() - r * r;
    if cc <= 0.0 {
        return 0.0;
    }
    let disc = b * b - cc;
    if disc < 0.0 {
        return f64::INFINITY;
    }
    let t = -b - disc.sqrt();
    if t >= 0.0 { t } else { f64::INFINITY }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crest_of_two_equal_circles_is_on_the_bisector_nearest_the_surface() {
        // Two circles of radius 4 centred 3 apart at height 4 over the plane z = 0:
        // they cross at z = 4 -+ sqrt(16 - 2.25).
        let c1 = Point3::new(0.0, 0.0, 4.0);
        let c2 = Point3::new(3.0, 0.0, 4.0);
        let low = crest(&c1, 4.0, &c2, 4.0, &Point3::new(1.5, 0.0, 0.0)).unwrap();
        assert!((low - Point3::new(1.5, 0.0, 4.0 - 13.75f64.sqrt())).norm() < 1e-12);
        let high = crest(&c1, 4.0, &c2, 4.0, &Point3::new(1.5, 0.0, 10.0)).unwrap();
        assert!((high.z - (4.0 + 13.75f64.sqrt())).abs() < 1e-12);
        assert!(crest(&c1, 1.0, &c2, 1.0, &Point3::origin()).is_none());
    }
}
