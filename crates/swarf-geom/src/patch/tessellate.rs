//! Adaptive tessellation of a patch within a chordal tolerance.
//!
//! **Error bound.** Let `T` be a triangle in the parameter plane and `L` the linear
//! interpolant of `S` at its corners. Taylor-expanding `S(x_i)` about any `x` in `T`
//! and using `sum l_i (x_i - x) = 0` (barycentric `l_i`) gives
//! `|L(x) - S(x)| <= 1/2 sum l_i Q(x_i - x)` with
//! `Q(d) = M_uu d_u^2 + 2 M_uv |d_u d_v| + M_vv d_v^2 <= a d_u^2 + b d_v^2`,
//! `a = M_uu + M_uv`, `b = M_vv + M_uv`, where `M` bound `|S_uu|, |S_uv|, |S_vv|` on the
//! cell. In the coordinates `(sqrt(a) u, sqrt(b) v)` the sum is the linear
//! interpolation error of `|x|^2`, whose maximum over `T` is the squared radius of the
//! smallest circle holding `T` (Waldron 1998, "The error in linear interpolation at the
//! vertices of a simplex"). Any triangle inside a `du x dv` cell fits in the cell's
//! circumcircle, so every triangulation of the cell (its two halves, or a fan through
//! T-junction points, see [`super::stitch`]) is within `(a du^2 + b dv^2) / 8` of the
//! surface, and that distance also bounds the distance to the closest surface point.
//!
//! **Cells.** An initial tensor grid per knot span equidistributes that bound: second
//! derivatives are sampled on a grid of the span, their largest values along each
//! parameter line give a density `du(u) = sqrt(8 s tol / a(u))` (`s` = [`GRID_SHARE`]
//! of the budget per direction), and breakpoints are placed at equal steps of its
//! integral, at least [`MIN_CELLS`] per span. Then every cell is checked with the bound,
//! taking `M` as the largest second derivatives at nine samples of the cell plus their
//! spread about the centre (the variation the samples can miss), and with the true
//! deviation of edge and diagonal midpoints from their chords; a failing cell splits
//! across the direction that dominates the bound (both when neither dominates by 4x),
//! so anisotropic regions get long thin cells. Cell sizes scale as `sqrt(tol)`, the
//! triangle count as `1 / tol`.

use super::Patch;
use super::eval::SurfaceDerivs;
use super::stitch::{Cell, Mesher, SPAN, Spans};
use crate::error::GeomError;
use crate::math::{Point3, Vec3};
use crate::mesh::TriMesh;

/// Every knot span has at least this many initial cells in each direction, so the nine
/// samples of a cell never straddle a whole wave of the surface.
const MIN_CELLS: usize = 4;
/// Second-derivative samples per direction for the initial grid, over all spans.
const PROFILE_BUDGET: usize = 256;
/// Most cells a mesh may have (each makes two or more triangles); a smaller tolerance
/// is refused rather than exhausting memory.
const MAX_CELLS: usize = 1 << 24;
/// Share of `tol` the initial grid spends on each direction (the rest is margin for
/// the variation inside a cell, so that few initial cells need splitting).
const GRID_SHARE: f64 = 0.4;
/// A cell's bound dominates in one direction when it is this many times the other's.
const ANISOTROPY: f64 = 4.0;

impl Patch {
    /// A triangle mesh within `tol` of the patch: adaptive in `(u, v)`, without cracks
    /// or T-junction gaps, triangles oriented like the patch normal `du x dv`.
    ///
    /// # Units
    /// `tol` in mm: the distance from any point of the mesh to the surface.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `tol` when it is not finite and > 0, or
    /// so small that the mesh would need more than 2^24 cells.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3};
    /// let flat = Patch::bezier([1, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0),
    ///     Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0),
    /// ]).unwrap();
    /// let mesh = flat.tessellate(0.01).unwrap();
    /// assert_eq!(mesh.triangles.len(), 32); // the minimum 4 x 4 cells, 2 triangles each
    /// ```
    pub fn tessellate(&self, tol: f64) -> Result<TriMesh, GeomError> {
        let tol = GeomError::check_positive("tol", tol)?;
        let spans = Spans::new(self);
        let leaves = self.refine(&spans, tol)?;
        Ok(Mesher::new(self, &spans, &leaves).run())
    }

    /// The initial grid's cells, split until each one passes [`Patch::split_dirs`].
    pub(super) fn refine(&self, spans: &Spans, tol: f64) -> Result<Vec<Cell>, GeomError> {
        let [ku, kv] = self.initial_grid(spans, tol)?;
        let mut stack: Vec<Cell> = Vec::new();
        for u in ku.windows(2) {
            for v in kv.windows(2) {
                stack.push(Cell {
                    lo: [u[0], v[0]],
                    hi: [u[1], v[1]],
                });
            }
        }
        let mut leaves = Vec::new();
        while let Some(c) = stack.pop() {
            check_size(tol, (leaves.len() + stack.len()) as f64)?;
            let [su, sv] = self.split_dirs(spans, &c, tol);
            if !su && !sv {
                leaves.push(c);
                continue;
            }
            let mid = [0, 1].map(|k| c.lo[k] + (c.hi[k] - c.lo[k]) / 2);
            let halves = |k: usize, split: bool| {
                if split {
                    vec![[c.lo[k], mid[k]], [mid[k], c.hi[k]]]
                } else {
                    vec![[c.lo[k], c.hi[k]]]
                }
            };
            for u in halves(0, su) {
                for v in halves(1, sv) {
                    stack.push(Cell {
                        lo: [u[0], v[0]],
                        hi: [u[1], v[1]],
                    });
                }
            }
        }
        Ok(leaves)
    }

    /// Cell boundaries (keys) of a tensor grid whose spacing follows the second
    /// derivatives sampled on each span (module doc), per direction.
    fn initial_grid(&self, spans: &Spans, tol: f64) -> Result<[Vec<u64>; 2], GeomError> {
        let per_span = [0, 1].map(|dir| {
            let p = self.degree()[dir];
            (PROFILE_BUDGET / spans.0[dir].len()).clamp(2 * (p + 1), 8 * (p + 1))
        });
        let params: [Vec<f64>; 2] = [0, 1].map(|dir| {
            let n = per_span[dir] as u64;
            let count = spans.0[dir].len() as u64 * n;
            (0..=count)
                .map(|k| spans.param(dir, k * SPAN / n))
                .collect()
        });
        let mut profile = [vec![0.0f64; params[0].len()], vec![0.0f64; params[1].len()]];
        for (i, u) in params[0].iter().enumerate() {
            for (j, v) in params[1].iter().enumerate() {
                let d = self.derivs(*u, *v);
                let (uu, uv, vv) = (d.duu.norm(), d.duv.norm(), d.dvv.norm());
                profile[0][i] = profile[0][i].max(uu + uv);
                profile[1][j] = profile[1][j].max(vv + uv);
            }
        }
        let density: [Vec<Vec<f64>>; 2] = [0, 1].map(|dir| {
            let n = per_span[dir];
            spans.0[dir]
                .iter()
                .enumerate()
                .map(|(s, [a, b])| {
                    profile[dir][s * n..=(s + 1) * n]
                        .windows(2)
                        .map(|w| (b - a) * (w[0].max(w[1]) / (8.0 * GRID_SHARE * tol)).sqrt())
                        .collect()
                })
                .collect()
        });
        let cells = density
            .each_ref()
            .map(|d| d.iter().map(|s| cell_count(s) as f64).sum::<f64>());
        check_size(tol, cells[0] * cells[1])?;
        Ok(density.map(|d| {
            let mut keys = vec![0];
            for (s, dens) in d.iter().enumerate() {
                keys.extend(equidistribute(dens).map(|x| s as u64 * SPAN + x));
            }
            keys
        }))
    }

    /// Whether cell `c` must split across u and across v (module doc).
    fn split_dirs(&self, spans: &Spans, c: &Cell, tol: f64) -> [bool; 2] {
        let divisible = [0, 1].map(|k| c.hi[k] - c.lo[k] >= 2);
        let [u0, u1] = [spans.param(0, c.lo[0]), spans.param(0, c.hi[0])];
        let [v0, v1] = [spans.param(1, c.lo[1]), spans.param(1, c.hi[1])];
        let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let d: [[SurfaceDerivs; 3]; 3] =
            [u0, um, u1].map(|u| [v0, vm, v1].map(|v| self.derivs(u, v)));
        let bound = |f: fn(&SurfaceDerivs) -> Vec3| {
            let centre = f(&d[1][1]);
            let (mut top, mut spread) = (0.0f64, 0.0f64);
            for s in d.iter().flatten() {
                top = top.max(f(s).norm());
                spread = spread.max((f(s) - centre).norm());
            }
            top + spread
        };
        let (muu, muv, mvv) = (bound(|s| s.duu), bound(|s| s.duv), bound(|s| s.dvv));
        let a = (muu + muv) * (u1 - u0).powi(2);
        let b = (mvv + muv) * (v1 - v0).powi(2);
        if (a + b) / 8.0 <= tol && chord_deviation(&d) <= tol {
            return [false, false];
        }
        let dirs = if a > ANISOTROPY * b {
            [true, false]
        } else if b > ANISOTROPY * a {
            [false, true]
        } else {
            [true, true]
        };
        let split = [dirs[0] && divisible[0], dirs[1] && divisible[1]];
        if split == [false, false] {
            divisible
        } else {
            split
        }
    }
}

/// Fails when a mesh of `cells` cells (two or more triangles each) is too large.
fn check_size(tol: f64, cells: f64) -> Result<(), GeomError> {
    if cells <= MAX_CELLS as f64 {
        Ok(())
    } else {
        Err(GeomError::InvalidParameter {
            name: "tol".into(),
            value: tol,
            expected: format!(
                "a tolerance this patch can be meshed within using at most {MAX_CELLS} cells \
                 (about {:.0e} needed)",
                cells
            ),
        })
    }
}

/// Number of intervals [`equidistribute`] makes for `density`.
fn cell_count(density: &[f64]) -> usize {
    let total: f64 = density.iter().sum::<f64>() / density.len() as f64;
    if total < 1e15 {
        (total.ceil() as usize).max(MIN_CELLS)
    } else {
        // Too many, infinite (a tolerance of 5e-324 mm) or NaN: refused by the
        // caller's size check, never an endless refinement.
        usize::MAX
    }
}

/// Interior breakpoints and the end (key offsets within one span) of the fewest
/// intervals with at most one unit of the piecewise-constant `density` each (sample
/// interval `k` covers `[k, k + 1] / density.len()` of the span); [`MIN_CELLS`] equal
/// intervals when that many suffice.
fn equidistribute(density: &[f64]) -> impl Iterator<Item = u64> + '_ {
    let n = density.len() as f64;
    let total: f64 = density.iter().sum::<f64>() / n;
    let cells = cell_count(density);
    let mut k = 0;
    let mut before = 0.0;
    (1..=cells).map(move |m| {
        if m == cells || total <= MIN_CELLS as f64 || !total.is_finite() {
            return SPAN * m as u64 / cells as u64;
        }
        let target = total * m as f64 / cells as f64;
        while k + 1 < density.len() && before + density[k] / n < target {
            before += density[k] / n;
            k += 1;
        }
        let within = if density[k] > 0.0 {
            ((target - before) * n / density[k]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        ((k as f64 + within) / n * SPAN as f64).round() as u64
    })
}

/// Largest distance of an edge midpoint from its edge chord, and of the centre from
/// the better diagonal's midpoint, on the 3 x 3 samples `d[i][j]` of a cell.
fn chord_deviation(d: &[[SurfaceDerivs; 3]; 3]) -> f64 {
    let p = |i: usize, j: usize| d[i][j].point;
    let off = |m: Point3, a: Point3, b: Point3| (m - nalgebra::center(&a, &b)).norm();
    let edges = [
        off(p(1, 0), p(0, 0), p(2, 0)),
        off(p(1, 2), p(0, 2), p(2, 2)),
        off(p(0, 1), p(0, 0), p(0, 2)),
        off(p(2, 1), p(2, 0), p(2, 2)),
    ];
    let centre = off(p(1, 1), p(0, 0), p(2, 2)).min(off(p(1, 1), p(2, 0), p(0, 2)));
    edges.iter().fold(centre, |m, e| m.max(*e))
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{die, nurbs_spline, quarter_cylinder, sphere_octant, wave};
    use super::*;
    use proptest::prelude::*;
    use std::collections::{HashMap, HashSet};

    /// Largest distance from the patch of three interior barycentric points on every
    /// `stride`-th triangle, measured by projection. Also checks each triangle's normal
    /// agrees with the patch normal there.
    fn max_deviation(patch: &Patch, mesh: &TriMesh, stride: usize) -> f64 {
        let bary = [[0.6, 0.2, 0.2], [0.2, 0.5, 0.3], [1.0 / 3.0; 3]];
        let mut worst = 0.0f64;
        for t in mesh.triangles.iter().step_by(stride) {
            let p = t.map(|i| mesh.vertices[i as usize]);
            let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
            for b in bary {
                let q = Point3::from(p[0].coords * b[0] + p[1].coords * b[1] + p[2].coords * b[2]);
                let pr = patch.project(&q);
                assert!(pr.status.converged(), "{pr:?}");
                worst = worst.max(pr.distance);
                if let Some(normal) = patch.derivs(pr.u, pr.v).normal() {
                    assert!(n.dot(&normal) > 0.0, "triangle {t:?} faces away");
                }
            }
        }
        worst
    }

    /// Each directed edge used once, every undirected edge at most twice, the Euler
    /// characteristic of a disk (a T-junction would leave a slit, a hole), and the
    /// boundary as long as the patch's boundary curves.
    fn check_watertight(patch: &Patch, mesh: &TriMesh, tol: f64) {
        let mut directed = HashSet::new();
        let mut undirected: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                assert!(directed.insert((a, b)), "directed edge {a}-{b} twice");
                *undirected.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let (v, e, f) = (
            mesh.vertices.len() as i64,
            undirected.len() as i64,
            mesh.triangles.len() as i64,
        );
        assert_eq!(v - e + f, 1, "Euler characteristic of a disk");
        let rim: f64 = undirected
            .iter()
            .filter(|(_, n)| **n == 1)
            .map(|((a, b), _)| (mesh.vertices[*a as usize] - mesh.vertices[*b as usize]).norm())
            .sum();
        let [[u0, u1], [v0, v1]] = patch.domain();
        let n = 4000;
        let mut want = 0.0;
        for k in 0..n {
            let (s, t) = (f64::from(k) / f64::from(n), f64::from(k + 1) / f64::from(n));
            let lerp = |a: f64, b: f64, x: f64| a + (b - a) * x;
            for (pa, pb) in [
                (
                    patch.eval(lerp(u0, u1, s), v0),
                    patch.eval(lerp(u0, u1, t), v0),
                ),
                (
                    patch.eval(lerp(u0, u1, s), v1),
                    patch.eval(lerp(u0, u1, t), v1),
                ),
                (
                    patch.eval(u0, lerp(v0, v1, s)),
                    patch.eval(u0, lerp(v0, v1, t)),
                ),
                (
                    patch.eval(u1, lerp(v0, v1, s)),
                    patch.eval(u1, lerp(v0, v1, t)),
                ),
            ] {
                want += (pb - pa).norm();
            }
        }
        assert!(
            rim <= want + 1e-9 && rim > want * (1.0 - tol),
            "rim {rim} vs boundary {want}"
        );
    }

    #[test]
    fn invalid_tolerances_are_named() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 5e-324, 1e-300, 1e-9] {
            let e = wave().tessellate(bad).unwrap_err();
            assert!(
                matches!(&e, GeomError::InvalidParameter { name, .. } if name == "tol"),
                "{e}"
            );
        }
    }

    #[test]
    fn meshes_are_crack_free_and_oriented() {
        for (patch, tol) in [(wave(), 0.05), (die(), 0.02), (nurbs_spline(), 0.05)] {
            let mesh = patch.tessellate(tol).unwrap();
            check_watertight(&patch, &mesh, tol);
            assert!(max_deviation(&patch, &mesh, 7) <= tol);
        }
    }

    #[test]
    fn quadrics_and_collapsed_edges() {
        let sphere = sphere_octant(20.0);
        let mesh = sphere.tessellate(0.01).unwrap();
        for t in &mesh.triangles {
            let p = t.map(|i| mesh.vertices[i as usize]);
            let c = (p[0].coords + p[1].coords + p[2].coords) / 3.0;
            assert!(20.0 - c.norm() <= 0.01 + 1e-12, "sphere chord too deep");
            let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
            assert!(n.dot(&c) < 0.0, "du x dv points inward on this octant");
        }
        let cyl = quarter_cylinder(5.0, 40.0).tessellate(0.001).unwrap();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for t in &cyl.triangles {
            let p = t.map(|i| cyl.vertices[i as usize]);
            let zs = p.map(|q| q.z);
            lo = lo.min(zs.iter().fold(f64::INFINITY, |a, b| a.min(*b)));
            hi = hi.max(zs.iter().fold(0.0, |a: f64, b| a.max(*b)));
        }
        assert!(lo.abs() < 1e-12 && (hi - 40.0).abs() < 1e-12, "{lo} {hi}");
        for q in &cyl.vertices {
            let level = q.z / 5.0;
            let msg = "anisotropic: 4 cells along z, their centres only for fans";
            assert!((level - level.round()).abs() < 1e-12, "{msg}");
        }
    }

    #[test]
    fn wave_count_grows_like_one_over_tol() {
        let counts: Vec<usize> = [0.1, 0.01]
            .iter()
            .map(|t| wave().tessellate(*t).unwrap().triangles.len())
            .collect();
        let ratio = counts[1] as f64 / counts[0] as f64;
        assert!((5.0..=15.0).contains(&ratio), "{counts:?}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]

        #[test]
        fn mesh_stays_within_tolerance(log_tol in -1.7..0.0f64, which_die in any::<bool>()) {
            let tol = 10f64.powf(log_tol);
            let patch = if which_die { die() } else { wave() };
            let mesh = patch.tessellate(tol).unwrap();
            let stride = (mesh.triangles.len() / 400).max(1);
            let worst = max_deviation(&patch, &mesh, stride);
            prop_assert!(worst <= tol, "deviation {worst} > tol {tol}");
        }
    }
}
