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
//! - **facet** with upward unit normal `n`: the profile point whose normal is `n`
//!   touches the plane ([`super::facet`], written once over the profile's lower
//!   envelope, pinned to [`crate::Profile::contact_for_normal`] by tests); when that
//!   point is inside the triangle it is the triangle's drop, and otherwise the plane's
//!   drop bounds the triangle's from above;
//! - **edge**: a 1-D concave maximisation along the edge ([`super::edge`]).
//!
//! A vertical facet (`n.z = 0`) has no interior maximum that its edges miss: the
//! cutter touches it along a vertical line ending on an edge. Order and ties: the
//! facet is tried first (an inside contact ends the search); then vertices and edges
//! are compared with `>` in that order, so ties keep the first (deterministic).

use super::edge::{edge_argmax, edge_upper_bound};
use super::facet::{PlaneDrop, plane_drop};
use super::{DropCutter, EdgeShape, Feature, TriContact};
use swarf_geom::Point3;

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
    edge_above(tool, xy, tri, k, f64::NEG_INFINITY)
}

/// [`edge_drop`] when it can reach `floor`: `None` early when even the edge's highest
/// end minus `h` at the edge line's distance is below it, or (envelopes of several
/// pieces, whose edge case may need a solve) the tangent bound of the edge's tip
/// height is ([`super::edge::edge_upper_bound`]).
fn edge_above(
    tool: &DropCutter,
    xy: [f64; 2],
    tri: &[Point3; 3],
    k: usize,
    floor: f64,
) -> Option<TriContact> {
    let a = tri.get(k)?;
    let b = tri[(k + 1) % 3];
    let (ax, ay) = (a.x - xy[0], a.y - xy[1]);
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len = (dx * dx + dy * dy).sqrt();
    if len.is_nan() || len <= 0.0 {
        return None;
    }
    let (tx, ty) = (dx / len, dy / len);
    let d0 = (ax * ty - ay * tx).abs();
    if d0.is_nan() || d0 > tool.radius || a.z.max(b.z) - tool.envelope.height(d0) < floor {
        return None;
    }
    let sa = ax * tx + ay * ty;
    let m = (b.z - a.z) / len;
    if tool.shape == EdgeShape::Pieces && floor > f64::NEG_INFINITY {
        let w = (tool.radius2 - d0 * d0).max(0.0).sqrt();
        let (lo, hi) = (sa.max(-w), (sa + len).min(w));
        if lo >= hi {
            return None;
        }
        let tip = |s: f64| {
            a.z + m * (s - sa)
                - tool
                    .envelope
                    .height((d0 * d0 + s * s).sqrt().min(tool.radius))
        };
        if edge_upper_bound(tool, d0, m, [lo, hi], [tip(lo), tip(hi)]) < floor {
            return None;
        }
    }
    let (s, h) = edge_argmax(tool, d0, m, sa, sa + len)?;
    let u = ((s - sa) / len).clamp(0.0, 1.0);
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
    match plane_drop(tool, xy, tri) {
        PlaneDrop::Inside(c) => Some(c),
        PlaneDrop::Bound(_) | PlaneDrop::Unknown => None,
    }
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
    triangle_drop_above(tool, xy, tri, f64::NEG_INFINITY)
}

/// [`triangle_drop`] restricted to contacts at or above `floor` (mm): the same result
/// when the triangle reaches `floor`, else `None`. Edges and the facet that provably
/// stay below `floor` are not solved, which is what makes the mesh drop fast: there
/// `floor` is the best height found on other triangles.
pub fn triangle_drop_above(
    tool: &DropCutter,
    xy: [f64; 2],
    tri: &[Point3; 3],
    floor: f64,
) -> Option<TriContact> {
    match plane_drop(tool, xy, tri) {
        PlaneDrop::Inside(c) => return (c.z >= floor).then_some(c),
        PlaneDrop::Bound(b) if b < floor => return None,
        PlaneDrop::Bound(_) | PlaneDrop::Unknown => {}
    }
    let mut best: Option<TriContact> = None;
    let take = |best: &mut Option<TriContact>, c: Option<TriContact>| {
        if let Some(c) = c
            && c.z >= floor
            && best.is_none_or(|b| c.z > b.z)
        {
            *best = Some(c);
        }
    };
    for k in 0..3 {
        take(&mut best, vertex_drop(tool, xy, tri, k));
    }
    for k in 0..3 {
        let f = best.map_or(floor, |b| b.z.max(floor));
        take(&mut best, edge_above(tool, xy, tri, k, f));
    }
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
        // Taper ball, 10-degree flank: a facet steeper than 80 degrees (rising toward
        // +x) meets the rim at the top of the flutes, on the +x side.
        let taper = tool("taperball:d=6,angle=10,tip=1,length=10");
        let (r, top) = (taper.radius, taper.envelope.top());
        let facet = [p(2.0, -9.0, 0.0), p(2.0, 9.0, 0.0), p(3.5, 0.0, 12.0)];
        let c = facet_drop(&taper, [0.0, 0.0], &facet).unwrap();
        assert!((c.cc.x - r).abs() < 1e-12 && c.cc.y.abs() < 1e-12, "{c:?}");
        assert!((c.z - (8.0 * (r - 2.0) - top)).abs() < 1e-12, "{c:?}");
    }
}
