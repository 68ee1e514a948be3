//! The facet case, and the plane bound that settles most triangles at once.
//!
//! A facet with upward unit normal `n` (`a = |n_xy|`, `n_z > 0`) is touched by the
//! point `(rho_c, z_c)` of the cutter's lower surface whose normal is `n`
//! ([`super::Envelope::contact_for_tilt`]), on the uphill side: in XY the CC point is
//! `(x, y) + rho_c u` with `u = -n_xy / a`. That point maximises `q.z - h(rho)` over
//! the whole plane within reach (the function is concave there and stationary at the
//! contact, or, past the flank, largest on the rim). Hence:
//!
//! - when it lies in the triangle's XY projection, it is the triangle's drop (no
//!   vertex or edge can do better); its height comes from barycentric interpolation
//!   from the first corner, `p0.z + l1 (p1.z - p0.z) + l2 (p2.z - p0.z)`, bounded
//!   by the corner heights however steep the facet and exact on a level facet (the
//!   same height everywhere on it, as OpenCAMLib gives it);
//! - otherwise the plane's drop `plane(cc) - z_c` is an upper bound for the whole
//!   triangle, and a triangle whose bound is below the best height found so far is
//!   done with without touching its vertices and edges. The plane height at `cc` is
//!   ill-conditioned for steep or sliver triangles (`1 / n_z` and `1 / sin` of the
//!   smallest angle amplify rounding), so the bound is used only for `n_z >=`
//!   [`BOUND_MIN_NZ`] and triangles whose area is at least [`BOUND_MIN_SHAPE`] times
//!   the square of the longest edge, with a margin of [`BOUND_MARGIN_REL`] times the
//!   size of the numbers involved (far above their rounding there).

use super::{DropCutter, Feature, TriContact};
use swarf_geom::Point3;

/// Smallest `n_z` for which the plane bound is used.
pub const BOUND_MIN_NZ: f64 = 1e-2;
/// Smallest `2 area / longest edge^2` for which the plane bound is used.
pub const BOUND_MIN_SHAPE: f64 = 1e-3;
/// Margin of the plane bound relative to the coordinates involved (mm per mm).
pub const BOUND_MARGIN_REL: f64 = 1e-9;

/// The drop onto a triangle's plane: the contact when it is inside the triangle,
/// else an upper bound for the triangle's drop when that is reliable.
pub(crate) enum PlaneDrop {
    /// The facet contact, which is the triangle's drop.
    Inside(TriContact),
    /// The triangle's drop is at most this (mm).
    Bound(f64),
    /// No reliable bound (steep, sliver, vertical, degenerate or non-finite).
    Unknown,
}

/// The facet contact or bound at `xy` (module doc).
pub(crate) fn plane_drop(tool: &DropCutter, xy: [f64; 2], tri: &[Point3; 3]) -> PlaneDrop {
    let [p0, p1, p2] = tri;
    let mut n = (p1 - p0).cross(&(p2 - p0));
    if n.z < 0.0 {
        n = -n;
    }
    let norm = n.norm();
    if !(n.z > 0.0 && norm.is_finite()) {
        return PlaneDrop::Unknown;
    }
    let n = n / norm;
    let a = (n.x * n.x + n.y * n.y).sqrt();
    let (rho, zc) = tool.envelope.contact_for_tilt(a, n.z);
    let q = if a > 0.0 {
        [xy[0] - rho * n.x / a, xy[1] - rho * n.y / a]
    } else {
        xy
    };
    if let Some(lam) = barycentric_xy(tri, q) {
        let z = p0.z + lam[1] * (p1.z - p0.z) + lam[2] * (p2.z - p0.z);
        return PlaneDrop::Inside(TriContact {
            z: z - zc,
            cc: Point3::new(q[0], q[1], z),
            feature: Feature::Facet,
        });
    }
    let longest2 = (p1 - p0)
        .norm_squared()
        .max((p2 - p1).norm_squared())
        .max((p0 - p2).norm_squared());
    if n.z < BOUND_MIN_NZ || norm < BOUND_MIN_SHAPE * longest2 {
        return PlaneDrop::Unknown;
    }
    let (dx, dy) = (q[0] - p0.x, q[1] - p0.y);
    let rise = (n.x * dx + n.y * dy) / n.z;
    let scale = 1.0 + p0.z.abs() + rise.abs() + dx.abs() + dy.abs() + zc.abs();
    PlaneDrop::Bound(p0.z - rise - zc + BOUND_MARGIN_REL * scale)
}

/// Barycentric coordinates of `q` in the XY projection of `tri`, when `q` lies in it
/// (closed), from edge functions relative to `q`.
pub(crate) fn barycentric_xy(tri: &[Point3; 3], q: [f64; 2]) -> Option<[f64; 3]> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cutter;
    use crate::drop::kernel::{edge_drop, vertex_drop};
    use proptest::prelude::*;

    fn tool(spec: &str) -> DropCutter {
        DropCutter::new(&spec.parse::<Cutter>().unwrap())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// The bound is never below any vertex or edge contact of the triangle.
        #[test]
        fn plane_bound_bounds_vertices_and_edges(
            c in prop::array::uniform9(-5.0..5.0f64),
            xy in prop::array::uniform2(-6.0..6.0f64),
            which in 0..4usize,
        ) {
            let t = tool(["ball:d=8", "bull:d=10,r=2", "cone:d=8,angle=70", "flat:d=6"][which]);
            let tri = [
                Point3::new(c[0], c[1], c[2]),
                Point3::new(c[3], c[4], c[5]),
                Point3::new(c[6], c[7], c[8]),
            ];
            if let PlaneDrop::Bound(b) = plane_drop(&t, xy, &tri) {
                for k in 0..3 {
                    for f in [vertex_drop(&t, xy, &tri, k), edge_drop(&t, xy, &tri, k)].into_iter().flatten() {
                        prop_assert!(f.z <= b, "{:?} above bound {}", f, b);
                    }
                }
            }
        }
    }

    #[test]
    fn slivers_and_steep_facets_give_no_bound() {
        let ball = tool("ball:d=8");
        let p = Point3::new;
        let sliver = [p(-5.0, 0.0, 0.0), p(5.0, 0.0, 0.0), p(0.0, 1e-5, 0.0)];
        assert!(matches!(
            plane_drop(&ball, [0.0, 3.0], &sliver),
            PlaneDrop::Unknown
        ));
        let steep = [p(-5.0, 1.0, 0.0), p(5.0, 1.0, 0.0), p(0.0, 1.001, 5.0)];
        assert!(matches!(
            plane_drop(&ball, [0.0, -3.0], &steep),
            PlaneDrop::Unknown
        ));
        let flat = [p(1.0, 1.0, 2.0), p(3.0, 1.0, 2.0), p(1.0, 3.0, 2.0)];
        for xy in [[1.3, 1.7], [2.1, 1.1], [1.0 + 1.0 / 3.0, 1.2]] {
            match plane_drop(&ball, xy, &flat) {
                PlaneDrop::Inside(c) => assert_eq!(c.z, 2.0, "level facets are exact"),
                _ => panic!("expected a contact at {xy:?}"),
            }
        }
        match plane_drop(&ball, [0.0, 0.0], &flat) {
            PlaneDrop::Bound(b) => assert!((b - 2.0).abs() < 1e-8),
            _ => panic!("expected a bound"),
        }
    }
}
