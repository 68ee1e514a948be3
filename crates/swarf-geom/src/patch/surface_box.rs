//! The box of a patch's surface to a tolerance, by Bezier subdivision (branch and
//! bound).
//!
//! A Bezier patch lies in the convex hull of its control points and passes through its
//! four corner points; a rational one too, its homogeneous weights being positive (The
//! NURBS Book §4.4). So over one Bezier net, for a coordinate `c`,
//! `max_corners c <= max_surface c <= max_net c`. Halving a net in one direction (de
//! Casteljau at 1/2 on the homogeneous points) gives the nets of the two halves of the
//! surface; their control points close in on the surface as the square of the width,
//! so the upper bounds fall towards the attained values.
//!
//! The search starts from the patch's Bezier nets ([`Patch::bezier_spans`]) and keeps
//! them in a heap by upper bound; it halves the net of the largest bound and raises the
//! best attained value with the new corners until the largest bound is within `tol` of
//! it. Then every surface point's `c` lies below that bound, and a surface point
//! reaches the best value: the true maximum is pinned in `[best, best + tol]`. Nets
//! whose bound is already within `tol` of the best are dropped as they are made, so the
//! work gathers near the extreme: about a dozen halvings for an interior extreme of a
//! smooth patch, none where the extreme is a corner (the common case of x and y).
//!
//! A polynomial net is halved across the direction where the coordinate's control
//! values have the larger second difference (a net linear in a direction needs no
//! halving across it: its bound already sits on the boundary curves), so a ridge along
//! a parameter line costs one net per level; a rational net alternates directions, as
//! the weights can bend a direction whose control values are linear. The tolerance is
//! raised to [`ROUNDING_REL`] of the patch's size where rounding of the halvings would
//! otherwise keep the bounds from meeting it, and a search stops after
//! [`MAX_HALVINGS`] halvings (a hostile net): its bound is reported as it stands.

use super::Patch;
use super::basis::MAX_ORDER;
use crate::error::GeomError;
use crate::math::{Aabb, Point3};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Relative rounding of a coordinate after the halvings of one search (dimensionless):
/// the tolerance is at least this times the largest control coordinate.
const ROUNDING_REL: f64 = 1e-12;
/// Most halvings of one search (one coordinate, one side); a smooth patch needs tens.
const MAX_HALVINGS: usize = 1 << 16;

/// A patch's box to a tolerance ([`Patch::surface_box`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceBox {
    /// Spanned by surface points: each face of the box touches the surface.
    pub inner: Aabb,
    /// Holds the whole surface; each face within the tolerance of `inner`'s.
    pub outer: Aabb,
}

impl Patch {
    /// The box of the surface to `tol` (module doc): `inner` is spanned by surface
    /// points, `outer` holds the surface, and each face of `outer` lies within `tol`
    /// of `inner`'s (within `1e-12` of the patch's largest coordinate, if that is more,
    /// and except for nets that defeat 65,536 halvings of one search, where `outer` is still
    /// a true bound).
    ///
    /// # Units
    /// `tol` and the boxes in mm.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `tol` when it is not finite and > 0.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3};
    /// // z = 4 u (1 - u): a parabolic arch of height 1 at u = 1/2, inside the edges.
    /// let arch = Patch::bezier([2, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0),
    ///     Point3::new(1.0, 0.0, 2.0), Point3::new(1.0, 1.0, 2.0),
    ///     Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 1.0, 0.0),
    /// ]).unwrap();
    /// let b = arch.surface_box(1e-9).unwrap();
    /// assert!(b.inner.max.z <= 1.0 && b.inner.max.z > 1.0 - 1e-9);
    /// assert!(b.outer.max.z >= 1.0 && b.outer.max.z < 1.0 + 1e-9);
    /// assert_eq!(b.inner.max.x, 2.0);
    /// ```
    pub fn surface_box(&self, tol: f64) -> Result<SurfaceBox, GeomError> {
        let tol = GeomError::check_positive("tol", tol)?;
        let spans = self.bezier_spans();
        let size = self
            .points()
            .iter()
            .flat_map(|p| p.coords.iter().map(|c| c.abs()))
            .fold(0.0, f64::max);
        let search = Search {
            degree: spans.degree,
            rational: self.weights().is_some(),
            tol: tol.max(ROUNDING_REL * size),
        };
        let mut inner = [[0.0; 3]; 2];
        let mut outer = [[0.0; 3]; 2];
        for coord in 0..3 {
            for (side, sign) in [(0, -1.0), (1, 1.0)] {
                let (best, bound) = search.extreme(&spans.nets, coord, sign);
                inner[side][coord] = sign * best;
                outer[side][coord] = sign * bound;
            }
        }
        let aabb = |b: [[f64; 3]; 2]| Aabb {
            min: Point3::from(b[0]),
            max: Point3::from(b[1]),
        };
        Ok(SurfaceBox {
            inner: aabb(inner),
            outer: aabb(outer),
        })
    }
}

/// One net waiting in the heap, with its upper bound.
struct Item {
    bound: f64,
    depth: usize,
    net: Vec<[f64; 4]>,
}

impl PartialEq for Item {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Item {}

impl PartialOrd for Item {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Item {
    fn cmp(&self, other: &Self) -> Ordering {
        self.bound.total_cmp(&other.bound)
    }
}

/// The settings shared by the six searches of one patch.
struct Search {
    degree: [usize; 2],
    rational: bool,
    tol: f64,
}

impl Search {
    /// The best attained value and an upper bound of `sign * c` (`c` = coordinate
    /// `coord`) over the surface of the Bezier `nets`.
    fn extreme(&self, nets: &[Vec<[f64; 4]>], coord: usize, sign: f64) -> (f64, f64) {
        let value = |h: &[f64; 4]| sign * h[coord] / h[3];
        let [p, q] = self.degree;
        let corners = [0, q, p * (q + 1), p * (q + 1) + q];
        let attained = |net: &[[f64; 4]]| {
            corners
                .iter()
                .map(|&k| value(&net[k]))
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let bound = |net: &[[f64; 4]]| net.iter().map(value).fold(f64::NEG_INFINITY, f64::max);
        let mut best = nets
            .iter()
            .map(|n| attained(n))
            .fold(f64::NEG_INFINITY, f64::max);
        let mut dropped = best;
        let mut heap: BinaryHeap<Item> = nets
            .iter()
            .map(|n| Item {
                bound: bound(n),
                depth: 0,
                net: n.clone(),
            })
            .collect();
        let mut halvings = 0;
        while let Some(item) = heap.pop() {
            if item.bound <= best + self.tol || halvings == MAX_HALVINGS {
                return (best, dropped.max(item.bound));
            }
            halvings += 1;
            let dir = self.split_dir(&item.net, item.depth, &value);
            for net in self.halves(&item.net, dir) {
                best = best.max(attained(&net));
                let b = bound(&net);
                if b <= best + self.tol {
                    dropped = dropped.max(b);
                } else {
                    heap.push(Item {
                        bound: b,
                        depth: item.depth + 1,
                        net,
                    });
                }
            }
        }
        (best, dropped)
    }

    /// The direction (0 = u, 1 = v) to halve `net` across (module doc).
    fn split_dir(
        &self,
        net: &[[f64; 4]],
        depth: usize,
        value: &impl Fn(&[f64; 4]) -> f64,
    ) -> usize {
        if self.rational {
            return depth % 2;
        }
        let [p, q] = self.degree;
        let c = |i: usize, j: usize| value(&net[i * (q + 1) + j]);
        let mut second = [0.0f64; 2];
        for i in 0..=p {
            for j in 0..=q {
                if i >= 1 && i < p {
                    second[0] = second[0].max((c(i - 1, j) - 2.0 * c(i, j) + c(i + 1, j)).abs());
                }
                if j >= 1 && j < q {
                    second[1] = second[1].max((c(i, j - 1) - 2.0 * c(i, j) + c(i, j + 1)).abs());
                }
            }
        }
        usize::from(second[1] > second[0])
    }

    /// The nets of the two halves of `net` across direction `dir` (de Casteljau at
    /// 1/2 along every line of the net in that direction).
    fn halves(&self, net: &[[f64; 4]], dir: usize) -> [Vec<[f64; 4]>; 2] {
        let [p, q] = self.degree;
        // `lines` lines of `len` points; point `k` of line `l` at `l * across + k * along`.
        let (lines, len, across, along) = if dir == 0 {
            (q + 1, p + 1, 1, q + 1)
        } else {
            (p + 1, q + 1, q + 1, 1)
        };
        let mut left = net.to_vec();
        let mut right = net.to_vec();
        let mut work = [[0.0; 4]; MAX_ORDER];
        for l in 0..lines {
            let at = |k: usize| l * across + k * along;
            for (k, w) in work.iter_mut().enumerate().take(len) {
                *w = net[at(k)];
            }
            for r in 0..len {
                left[at(r)] = work[0];
                right[at(len - 1 - r)] = work[len - 1 - r];
                for k in 0..len - 1 - r {
                    work[k] = midpoint(&work[k], &work[k + 1]);
                }
            }
        }
        [left, right]
    }
}

/// `(a + b) / 2` without overflow for finite inputs.
fn midpoint(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [0, 1, 2, 3].map(|k| 0.5 * a[k] + 0.5 * b[k])
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{
        nurbs_spline, quarter_cylinder, shared_patches, sphere_octant, wave,
    };
    use super::*;
    use proptest::prelude::*;

    /// Bernstein coefficients of `sum_k a_k t^k` (degree `n = a.len() - 1`):
    /// `b_i = sum_{k <= i} C(i, k) / C(n, k) a_k`.
    fn bernstein(a: &[f64]) -> Vec<f64> {
        let c =
            |n: usize, k: usize| (0..k).fold(1.0, |acc, m| acc * (n - m) as f64 / (m + 1) as f64);
        let n = a.len() - 1;
        (0..=n)
            .map(|i| (0..=i).map(|k| c(i, k) / c(n, k) * a[k]).sum())
            .collect()
    }

    /// The surface points on a `(n + 1)^2` grid.
    fn samples(p: &Patch, n: usize) -> Vec<Point3> {
        let [[u0, u1], [v0, v1]] = p.domain();
        let t = |a: f64, b: f64, k: usize| a + (b - a) * k as f64 / n as f64;
        (0..=n)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| p.eval(t(u0, u1, i), t(v0, v1, j)))
            .collect()
    }

    /// `inner` within `outer`, the gap at most `tol` (plus rounding), every sample inside
    /// `outer` and none beyond `inner` by more than `tol`.
    fn check(p: &Patch, tol: f64, name: &str) -> SurfaceBox {
        let b = p.surface_box(tol).unwrap();
        let slack = 1e-12 * p.control_box().size().norm().max(1.0);
        for k in 0..3 {
            let (lo, hi) = (b.outer.min[k], b.outer.max[k]);
            assert!(
                lo <= b.inner.min[k] && b.inner.max[k] <= hi,
                "{name}[{k}]: {b:?}"
            );
            assert!(
                b.inner.min[k] - lo <= tol + slack,
                "{name}[{k}] low gap: {b:?}"
            );
            assert!(
                hi - b.inner.max[k] <= tol + slack,
                "{name}[{k}] high gap: {b:?}"
            );
        }
        let sampled = Aabb::from_points(&samples(p, 40));
        for k in 0..3 {
            assert!(
                sampled.min[k] >= b.outer.min[k] - slack,
                "{name}[{k}] below outer"
            );
            assert!(
                sampled.max[k] <= b.outer.max[k] + slack,
                "{name}[{k}] above outer"
            );
            assert!(
                sampled.min[k] >= b.inner.min[k] - tol - slack,
                "{name}[{k}] inner min"
            );
            assert!(
                sampled.max[k] <= b.inner.max[k] + tol + slack,
                "{name}[{k}] inner max"
            );
        }
        b
    }

    #[test]
    fn an_interior_maximum_matches_its_closed_form() {
        // x = 10 u, y = 8 v, z = 2 + 3 u - 4 u^2 + 5 v - 6 v^2 + u v: concave, with its
        // maximum where 3 - 8 u + v = 0 and 5 - 12 v + u = 0.
        let (u, v) = (41.0 / 95.0, 43.0 / 95.0);
        let top = 2.0 + 3.0 * u - 4.0 * u * u + 5.0 * v - 6.0 * v * v + u * v;
        let [bu, bv] = [bernstein(&[0.0, 10.0, 0.0]), bernstein(&[0.0, 8.0, 0.0])];
        let a = [[2.0, 5.0, -6.0], [3.0, 1.0, 0.0], [-4.0, 0.0, 0.0]];
        // z's Bernstein coefficients: convert along v for each power of u, then along u.
        let rows: Vec<Vec<f64>> = a.iter().map(|r| bernstein(r)).collect();
        let z: Vec<Vec<f64>> = (0..3)
            .map(|j| bernstein(&[rows[0][j], rows[1][j], rows[2][j]]))
            .collect();
        let pts = (0..9)
            .map(|k| Point3::new(bu[k / 3], bv[k % 3], z[k % 3][k / 3]))
            .collect();
        let p = Patch::bezier([2, 2], pts).unwrap();
        assert!(
            (p.eval(u, v).z - top).abs() < 1e-12,
            "the net is the polynomial"
        );
        for tol in [1e-3, 1e-6, 1e-9] {
            let b = check(&p, tol, "paraboloid");
            assert!(b.inner.max.z <= top + 1e-12 && b.inner.max.z >= top - tol);
            assert!(b.outer.max.z >= top - 1e-12 && b.outer.max.z <= top + tol);
            // the minimum of a concave function is at a corner: z(1, 1) = 1
            assert_eq!((b.inner.min.z, b.outer.min.z), (1.0, 1.0));
            assert_eq!((b.inner.max.x, b.inner.max.y), (10.0, 8.0));
        }
    }

    #[test]
    fn quadrics_and_shared_parts() {
        let r = 7.0;
        for (name, p, want) in [
            ("sphere", sphere_octant(r), [r, r, r]),
            ("cylinder", quarter_cylinder(r, 3.0), [r, r, 3.0]),
        ] {
            let b = check(&p, 1e-9, name);
            for (k, want) in want.iter().enumerate() {
                assert!(b.inner.min[k].abs() < 1e-12, "{name}[{k}] min");
                assert!((b.inner.max[k] - want).abs() < 1e-9, "{name}[{k}] max");
            }
        }
        for (name, p) in shared_patches() {
            check(&p, 1e-6, name);
        }
        check(&nurbs_spline(), 1e-6, "nurbs spline");
        let b = check(&wave(), 1e-6, "wave");
        assert_eq!([b.inner.min.x, b.inner.min.y], [0.0, 0.0]);
        assert_eq!([b.inner.max.x, b.inner.max.y], [200.0, 100.0]);
    }

    #[test]
    fn invalid_tolerances_are_named() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = wave().surface_box(bad).unwrap_err();
            assert!(e.to_string().starts_with("tol = "), "{e}");
        }
    }

    fn random_patch() -> impl Strategy<Value = Patch> {
        (1usize..5, 1usize..5, any::<bool>()).prop_flat_map(|(du, dv, rational)| {
            let n = (du + 1) * (dv + 1);
            (
                proptest::collection::vec((-50.0..50.0f64, -50.0..50.0f64, -50.0..50.0f64), n),
                proptest::collection::vec(0.2..3.0f64, n),
            )
                .prop_map(move |(raw, w)| {
                    let pts = raw.iter().map(|c| Point3::new(c.0, c.1, c.2)).collect();
                    let w = rational.then_some(w);
                    Patch::new([du, dv], pts, [None, None], w).unwrap()
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn boxes_hold_the_surface_within_tol(p in random_patch(), log_tol in -9.0..-1.0f64) {
            check(&p, 10f64.powf(log_tol), "random");
        }
    }
}
