//! Drop onto one triangle: the vertex, facet and edge cases and their maximum.
//!
//! The cutter's lower surface over the disc `rho <= R` about `(x, y)` is
//! `z = tip + h(rho)` ([`super::envelope`]); it touches the triangle without
//! penetrating it at the lowest tip height `max over q in T of q.z - h(|q.xy - (x, y)|)`
//! (thesis 002 §6.2: "the point that has the maximum Z value is used as the final tool
//! location point"). `h` is convex, so the maximised function is concave on the
//! convex set `T ∩ disc`: its maximum lies at a vertex, inside an edge, or inside the
//! facet, and each case has a closed form or a guaranteed 1-D solve:
//!
//! - **vertex** `p`: `tip = p.z - h(|p.xy - (x, y)|)`, written once over the profile;
//! - **facet** with upward unit normal `n`: the profile point whose outward normal is
//!   `-n` ([`Profile::contact_for_normal`], the tool crate's contact API) touches
//!   the plane; with `(rho_c, z_c)` that point and `u` its radial direction, the CC
//!   point is `(x, y) + rho_c u` in XY, valid when it lies in the triangle's XY
//!   projection; its height comes from barycentric interpolation (bounded by the
//!   corner heights however steep the facet), and `tip = cc.z - z_c`. Normals steeper
//!   than the side line (a taper's flank) touch at the rim `(R, h(R))`;
//! - **edge**: a 1-D concave maximisation along the edge ([`super::edge`]).
//!
//! A vertical facet (`n.z = 0`) has no interior maximum that its edges miss: the
//! cutter touches it along a vertical line ending on an edge. Inside the triangle the
//! candidates are compared with `>` in the order vertices, edges, facet, so ties keep
//! the first (deterministic).

use super::edge::edge_argmax;
use super::{DropCutter, Feature, TriContact};
use swarf_geom::{Point3, Vec3};

/// Drop onto vertex `k` of `tri`: the tip height at which the cutter at `xy` touches
/// it, and the contact; `None` when the vertex is beyond the cutter's reach.
///
/// # Units
/// mm.
pub fn vertex_drop(
    tool: &DropCutter,
    xy: [f64; 2],
    tri: &[Point3; 3],
    k: usize,
) -> Option<TriContact> {
    let p = tri.get(k)?;
    let (dx, dy) = (p.x - xy[0], p.y - xy[1]);
    let d2 = dx * dx + dy * dy;
    if d2.is_nan() || d2 > tool.radius2 {
        return None;
    }
    Some(TriContact {
        z: p.z - tool.envelope.height(d2.sqrt()),
        cc: *p,
        feature: Feature::Vertex(k as u8),
    })
}

/// Drop onto edge `k` of `tri` (from corner `k` to corner `k + 1 mod 3`): the contact
/// inside the edge, or `None` when the edge's maximum is at an end (a vertex case),
/// the edge is vertical or out of reach.
///
/// # Units
/// mm.
pub fn edge_drop(
    tool: &DropCutter,
    xy: [f64; 2],
    tri: &[Point3; 3],
    k: usize,
) -> Option<TriContact> {
    let a = tri.get(k)?;
    let b = tri[(k + 1) % 3];
    let (ax, ay) = (a.x - xy[0], a.y - xy[1]);
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len = dx.hypot(dy);
    if len.is_nan() || len <= 0.0 {
        return None;
    }
    let (tx, ty) = (dx / len, dy / len);
    let d0 = (ax * ty - ay * tx).abs();
    if d0.is_nan() || d0 > tool.radius {
        return None;
    }
    let sa = ax * tx + ay * ty;
    let m = (b.z - a.z) / len;
    let (s, h) = edge_argmax(tool, d0, m);
    let u = (s - sa) / len;
    if !(u > 0.0 && u < 1.0) {
        return None;
    }
    let cc = Point3::new(a.x + u * dx, a.y + u * dy, a.z + u * (b.z - a.z));
    Some(TriContact {
        z: cc.z - h,
        cc,
        feature: Feature::Edge(k as u8),
    })
}

/// Drop onto the interior of `tri`'s facet: the contact when the touching point lies
/// inside the triangle's XY projection, else `None` (also for vertical and degenerate
/// triangles).
///
/// # Units
/// mm.
pub fn facet_drop(tool: &DropCutter, xy: [f64; 2], tri: &[Point3; 3]) -> Option<TriContact> {
    let [p0, p1, p2] = tri;
    let mut n = (p1 - p0).cross(&(p2 - p0));
    if n.z < 0.0 {
        n = -n;
    }
    let norm = n.norm();
    if !(n.z > 0.0 && norm.is_finite()) {
        return None;
    }
    let n = n / norm;
    let (rho, zc, u) = facet_contact(tool, &n);
    let q = [xy[0] + rho * u.x, xy[1] + rho * u.y];
    let lam = barycentric_xy(tri, q)?;
    let z = lam[0] * p0.z + lam[1] * p1.z + lam[2] * p2.z;
    Some(TriContact {
        z: z - zc,
        cc: Point3::new(q[0], q[1], z),
        feature: Feature::Facet,
    })
}

/// The profile point touching a plane of upward unit normal `n`: `(rho, z, u)`.
fn facet_contact(tool: &DropCutter, n: &Vec3) -> (f64, f64, Vec3) {
    if let Some((c, u)) = tool.profile.contact_for_normal(n, &Vec3::z()) {
        return (c.point.rho, c.point.z, u);
    }
    let across = n.x.hypot(n.y);
    let u = Vec3::new(-n.x / across, -n.y / across, 0.0);
    (tool.radius, tool.envelope.top(), u)
}

/// Barycentric coordinates of `q` in the XY projection of `tri`, when `q` lies in it
/// (closed), from edge functions relative to `q`.
fn barycentric_xy(tri: &[Point3; 3], q: [f64; 2]) -> Option<[f64; 3]> {
    let r = tri.map(|p| [p.x - q[0], p.y - q[1]]);
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let e = [cross(r[1], r[2]), cross(r[2], r[0]), cross(r[0], r[1])];
    let total = e[0] + e[1] + e[2];
    if total == 0.0 || !total.is_finite() {
        return None;
    }
    let lam = e.map(|v| v / total);
    lam.iter().all(|&l| l >= 0.0).then_some(lam)
}

/// Drop onto the whole triangle: the highest of its vertex, edge and facet contacts
/// (ties keep the first in that order); `None` when the cutter at `xy` cannot reach it.
///
/// # Units
/// mm.
///
/// # Example
/// ```
/// use swarf_geom::Point3;
/// use swarf_tool::drop::{DropCutter, Feature, triangle_drop};
/// let ball = DropCutter::new(&"ball:d=8".parse().unwrap());
/// let tri = [Point3::new(-10.0, -10.0, 1.0), Point3::new(10.0, -10.0, 1.0), Point3::new(0.0, 10.0, 1.0)];
/// let c = triangle_drop(&ball, [0.0, 0.0], &tri).unwrap();
/// assert_eq!((c.z, c.feature), (1.0, Feature::Facet));
/// ```
pub fn triangle_drop(tool: &DropCutter, xy: [f64; 2], tri: &[Point3; 3]) -> Option<TriContact> {
    let mut best: Option<TriContact> = None;
    let mut take = |c: Option<TriContact>| {
        if let Some(c) = c
            && best.is_none_or(|b| c.z > b.z)
        {
            best = Some(c);
        }
    };
    for k in 0..3 {
        take(vertex_drop(tool, xy, tri, k));
    }
    for k in 0..3 {
        take(edge_drop(tool, xy, tri, k));
    }
    take(facet_drop(tool, xy, tri));
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cutter;

    fn tool(spec: &str) -> DropCutter {
        DropCutter::new(&spec.parse::<Cutter>().unwrap())
    }

    fn p(x: f64, y: f64, z: f64) -> Point3 {
        Point3::new(x, y, z)
    }

    #[test]
    fn ball_on_an_inclined_plane_matches_the_closed_form() {
        // Plane z = y / 2 (slope angle t, tan t = 1/2): the ball centre sits R / cos t
        // above the plane, so the tip is at z(x, y) + R (1 / cos t - 1).
        let ball = tool("ball:d=8");
        let tri = [
            p(-50.0, -50.0, -25.0),
            p(50.0, -50.0, -25.0),
            p(0.0, 50.0, 25.0),
        ];
        let c = triangle_drop(&ball, [2.0, 2.0], &tri).unwrap();
        let want = 1.0 + 4.0 * (1.25f64.sqrt() - 1.0);
        assert!((c.z - want).abs() < 1e-12, "{} vs {want}", c.z);
        assert_eq!(c.feature, Feature::Facet);
        // The CC point lies on the plane and on the ball.
        assert!((c.cc.z - c.cc.y / 2.0).abs() < 1e-12);
        let centre = p(2.0, 2.0, c.z + 4.0);
        assert!(((c.cc - centre).norm() - 4.0).abs() < 1e-12);
    }

    #[test]
    fn flat_end_touches_a_tilted_facet_with_its_rim() {
        let flat = tool("flat:d=6");
        let tri = [
            p(-50.0, -50.0, -25.0),
            p(50.0, -50.0, -25.0),
            p(0.0, 50.0, 25.0),
        ];
        let c = facet_drop(&flat, [0.0, 0.0], &tri).unwrap();
        assert!((c.z - 1.5).abs() < 1e-12 && (c.cc - p(0.0, 3.0, 1.5)).norm() < 1e-12);
    }

    #[test]
    fn cone_tip_sits_on_shallow_facets_and_flank_on_edges() {
        let cone = tool("cone:d=10,angle=90");
        let tri = [
            p(-50.0, -50.0, 0.0),
            p(50.0, -50.0, 0.0),
            p(0.0, 50.0, 10.0),
        ];
        let c = triangle_drop(&cone, [0.0, 0.0], &tri).unwrap();
        assert!((c.z - 5.0).abs() < 1e-12 && c.feature == Feature::Facet);
        // A horizontal ridge line at height 3, 2 mm beside the axis: the 45-degree
        // flank touches it at rho = 2, so the tip is at 3 - 2.
        let ridge = [p(-20.0, 2.0, 3.0), p(20.0, 2.0, 3.0), p(0.0, 40.0, -30.0)];
        let c = triangle_drop(&cone, [0.0, 0.0], &ridge).unwrap();
        assert!((c.z - 1.0).abs() < 1e-12, "{c:?}");
        assert_eq!(c.feature, Feature::Edge(0));
    }

    #[test]
    fn vertex_wins_under_a_spike_and_nothing_out_of_reach() {
        let ball = tool("ball:d=8");
        let spike = [p(1.0, 0.0, 10.0), p(30.0, 0.0, 0.0), p(30.0, 5.0, 0.0)];
        let c = triangle_drop(&ball, [0.0, 0.0], &spike).unwrap();
        assert_eq!(c.feature, Feature::Vertex(0));
        assert!((c.z - (10.0 - (4.0 - 15f64.sqrt()))).abs() < 1e-12);
        let far = [p(10.0, 10.0, 0.0), p(11.0, 10.0, 0.0), p(10.0, 11.0, 0.0)];
        assert!(triangle_drop(&ball, [0.0, 0.0], &far).is_none());
    }

    #[test]
    fn degenerate_and_vertical_triangles_still_drop_on_edges() {
        let ball = tool("ball:d=8");
        let wall = [p(-10.0, 1.0, 0.0), p(10.0, 1.0, 0.0), p(0.0, 1.0, 5.0)];
        assert!(facet_drop(&ball, [0.0, 0.0], &wall).is_none());
        let c = triangle_drop(&ball, [0.0, 0.0], &wall).unwrap();
        // The top vertex, 1 mm from the axis.
        assert!((c.z - (5.0 - (4.0 - 15f64.sqrt()))).abs() < 1e-12);
        let needle = [p(0.0, 0.0, 1.0), p(0.0, 0.0, 2.0), p(0.0, 0.0, 3.0)];
        assert_eq!(triangle_drop(&ball, [0.0, 0.0], &needle).unwrap().z, 3.0);
        let nan = [p(f64::NAN, 0.0, 1.0), p(0.0, 1.0, 2.0), p(1.0, 0.0, 3.0)];
        let c = triangle_drop(&ball, [0.0, 0.0], &nan).unwrap();
        assert!(c.z.is_finite());
    }

    #[test]
    fn steep_facet_beyond_a_taper_touches_at_the_rim() {
        // Taper ball, 10-degree flank: a facet steeper than 80 degrees meets the
        // rim at the top of the flutes.
        let taper = tool("taperball:d=6,angle=10,tip=1,length=10");
        let dc = &taper;
        let top = dc.envelope.top();
        let r = dc.radius;
        let n = Vec3::new(-0.99, 0.0, (1.0f64 - 0.99 * 0.99).sqrt());
        let (rho, z, u) = facet_contact(dc, &n);
        assert_eq!((rho, z), (r, top));
        assert!((u - Vec3::x()).norm() < 1e-15);
    }
}
