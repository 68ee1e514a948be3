//! Intersection of a patch with a plane: every branch of the section curve.
//!
//! The section is the zero set of `f(u, v) = n . S(u, v) - d` in the parameter plane.
//!
//! 1. **Seeds.** `f` is sampled on a grid (`4 (degree + 1)` cells per knot span, at
//!    least 8, at most 128 per direction); every grid edge whose ends differ in sign
//!    holds a root, found by the Illinois variant of regula falsi along the edge (exact
//!    on the iso-line, so seeds on the domain boundary lie exactly on it). An edge whose
//!    ends agree in sign but whose end slopes both head for the other sign is searched
//!    for its extremum (a small arc or loop crossing it twice). A closed loop
//!    small enough to cross no grid edge surrounds a critical point of `f` (where the
//!    plane is parallel to the tangent plane): in each cell whose corners agree in sign
//!    while both components of `grad f` change sign among them, Newton on `grad f = 0`
//!    walks from the centre toward it, and the first iterate where `f` changes sign
//!    gives a seed by regula falsi on the segment from a corner.
//! 2. **Branches.** Branches that leave the patch are traced from their boundary seeds,
//!    inward; the seeds left over are on closed loops (or on branches whose boundary
//!    crossings the grid missed) and are traced both ways ([`super::section_trace`]).
//!    After each branch, the seeds lying on it are retired, so no branch is traced twice.
//!
//! The curvature-driven step control and the midpoint checks of the tracer keep every
//! chord within `tol` of the curve; every sample is on the plane to
//! [`crate::tol::SOLVER_LENGTH`] (Barnhill & Kersey, "A marching method for parametric
//! surface/surface intersection", CAGD 7, 1990, for the marching scheme; Patrikalakis &
//! Maekawa, "Shape Interrogation", ch. 5.8, for seeding loops from critical points).

use super::Patch;
use super::section_seed::{Seed, seeds};
use super::section_trace::{End, Section};
use crate::error::GeomError;
use crate::math::{Plane, Point3, Polyline, point_segment_distance};
use crate::tol::SOLVER_LENGTH;
use serde::{Deserialize, Serialize};

/// A seed within this many seed-grid cells of a traced branch (in parameters) and
/// within twice the tolerance of it in space belongs to it.
const SEED_ON_BRANCH_CELLS: f64 = 0.25;

/// A point of a patch with its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SurfaceSample {
    /// Parameter u.
    pub u: f64,
    /// Parameter v.
    pub v: f64,
    /// `S(u, v)`, mm.
    pub point: Point3,
}

/// One branch of a plane section: samples in order along the curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SectionCurve {
    /// The samples; consecutive ones are joined by chords within the tolerance.
    pub samples: Vec<SurfaceSample>,
    /// True for a closed loop (the last sample joins the first); open branches end on
    /// the patch boundary (or, rarely, at a singular point of the section).
    pub closed: bool,
}

impl SectionCurve {
    /// The samples' points as a polyline, closed like the curve.
    pub fn to_polyline(&self) -> Polyline {
        Polyline {
            points: self.samples.iter().map(|s| s.point).collect(),
            closed: self.closed,
        }
    }
}

impl Patch {
    /// All branches of the intersection of the patch with `plane`, each as samples on
    /// the plane whose chords stay within `tol` of the true curve.
    ///
    /// # Units
    /// `tol` in mm; samples in mm.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `tol` when it is not finite and > 0, or
    /// `plane` when its normal is zero or its offset not finite.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Plane, Point3, Vec3};
    /// let flat = Patch::bezier([1, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 4.0, 0.0),
    ///     Point3::new(4.0, 0.0, 0.0), Point3::new(4.0, 4.0, 4.0),
    /// ]).unwrap();
    /// let plane = Plane::from_point_normal(&Point3::new(0.0, 0.0, 1.0), &Vec3::z()).unwrap();
    /// let curves = flat.intersect_plane(&plane, 0.01).unwrap();
    /// assert_eq!(curves.len(), 1);
    /// assert!(curves[0].samples.iter().all(|s| (s.point.z - 1.0).abs() < 1e-9));
    /// ```
    pub fn intersect_plane(&self, plane: &Plane, tol: f64) -> Result<Vec<SectionCurve>, GeomError> {
        let tol = GeomError::check_positive("tol", tol)?;
        let len = plane.normal.norm();
        if !(len.is_finite() && len > 0.0 && plane.offset.is_finite()) {
            return Err(GeomError::InvalidParameter {
                name: "plane".into(),
                value: len,
                expected: "a finite plane with a non-zero normal".into(),
            });
        }
        let grid = self.seed_params();
        let cell = grid.each_ref().map(|g| {
            g.windows(2)
                .map(|w| w[1] - w[0])
                .fold(f64::INFINITY, f64::min)
        });
        let sec = Section::new(self, plane.normal / len, plane.offset / len, tol, cell);
        let mut seeds = seeds(&sec, &grid);
        seeds.sort_by_key(|s| !s.boundary);
        let mut curves = Vec::new();
        for k in 0..seeds.len() {
            if seeds[k].used {
                continue;
            }
            seeds[k].used = true;
            let start = sec.sample(seeds[k].uv);
            let curve = if seeds[k].boundary {
                from_boundary(&sec, start)
            } else {
                Some(from_interior(&sec, start))
            };
            if let Some(c) = curve.filter(|c| c.samples.len() >= 2) {
                retire_seeds(&sec, &c, &mut seeds);
                curves.push(c);
            }
        }
        Ok(curves)
    }

    /// Seed-grid parameters per direction (module doc).
    fn seed_params(&self) -> [Vec<f64>; 2] {
        [0, 1].map(|dir| {
            let k = &self.knots[dir];
            let p = self.degree[dir];
            let spans: Vec<[f64; 2]> = k[p..k.len() - p]
                .windows(2)
                .filter(|w| w[1] > w[0])
                .map(|w| [w[0], w[1]])
                .collect();
            let per = (4 * (p + 1)).max(8).min((128 / spans.len()).max(2));
            let mut out = vec![spans[0][0]];
            for [a, b] in spans {
                out.extend((1..=per).map(|s| a + (b - a) * s as f64 / per as f64));
            }
            out
        })
    }
}

/// The branch starting at a boundary seed, traced inward; `None` when the curve only
/// touches the boundary there.
fn from_boundary(sec: &Section, start: SurfaceSample) -> Option<SectionCurve> {
    let uv = [start.u, start.v];
    let d = sec.patch.derivs(uv[0], uv[1]);
    let g = [sec.normal.dot(&d.du), sec.normal.dot(&d.dv)];
    let inward = |sign: f64| {
        let t = [sign * g[1], -sign * g[0]];
        (0..2).all(|k| {
            let out_lo = uv[k] <= sec.dom[k][0] && t[k] <= 0.0;
            let out_hi = uv[k] >= sec.dom[k][1] && t[k] >= 0.0;
            !(out_lo || out_hi)
        })
    };
    let sign = [1.0, -1.0].into_iter().find(|s| inward(*s))?;
    let (samples, _) = sec.trace(start, sign, false);
    Some(SectionCurve {
        samples,
        closed: false,
    })
}

/// The branch through an interior seed: a closed loop, or both ways joined.
fn from_interior(sec: &Section, start: SurfaceSample) -> SectionCurve {
    let (forward, end) = sec.trace(start, 1.0, true);
    if end == End::Closed {
        return SectionCurve {
            samples: forward,
            closed: true,
        };
    }
    let (backward, _) = sec.trace(start, -1.0, false);
    let mut samples: Vec<_> = backward[1..].iter().rev().copied().collect();
    samples.extend(forward);
    SectionCurve {
        samples,
        closed: false,
    }
}

/// Marks the seeds that lie on `curve` as used.
fn retire_seeds(sec: &Section, curve: &SectionCurve, seeds: &mut [Seed]) {
    let s = &curve.samples;
    let n = s.len();
    let segments = if curve.closed { n } else { n - 1 };
    for seed in seeds.iter_mut().filter(|x| !x.used) {
        let p = sec.patch.eval(seed.uv[0], seed.uv[1]);
        let q = Point3::new(seed.uv[0] / sec.cell[0], seed.uv[1] / sec.cell[1], 0.0);
        let param = |x: &SurfaceSample| Point3::new(x.u / sec.cell[0], x.v / sec.cell[1], 0.0);
        seed.used = (0..segments).any(|k| {
            let (a, b) = (&s[k], &s[(k + 1) % n]);
            point_segment_distance(&q, &param(a), &param(b)) <= SEED_ON_BRANCH_CELLS
                && point_segment_distance(&p, &a.point, &b.point) <= 2.0 * sec.tol + SOLVER_LENGTH
        });
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{die, sphere_octant, wave};
    use super::*;
    use crate::math::Vec3;
    use proptest::prelude::*;

    fn plane(p: [f64; 3], n: [f64; 3]) -> Plane {
        Plane::from_point_normal(&Point3::from(p), &Vec3::from(n)).unwrap()
    }

    /// Distance from the chord midpoint to the curve point on the plane through it
    /// perpendicular to the chord: 2x2 Newton on `(f, (S - M).(B - A))` from the
    /// parameter midpoint. Where that system is ill-conditioned (plane nearly tangent to
    /// the surface), the distance from the chord of the curve point found by bisection
    /// on the parameter line through the parameter midpoint, perpendicular to the
    /// parameter chord.
    fn mid_chord_error(patch: &Patch, pl: &Plane, a: &SurfaceSample, b: &SurfaceSample) -> f64 {
        let m = nalgebra::center(&a.point, &b.point);
        let ab = b.point - a.point;
        let mid = [0.5 * (a.u + b.u), 0.5 * (a.v + b.v)];
        let mut uv = mid;
        for _ in 0..30 {
            let d = patch.derivs(uv[0], uv[1]);
            let r = [pl.signed_distance(&d.point), (d.point - m).dot(&ab)];
            let j = [
                pl.normal.dot(&d.du),
                pl.normal.dot(&d.dv),
                ab.dot(&d.du),
                ab.dot(&d.dv),
            ];
            let det = j[0] * j[3] - j[1] * j[2];
            uv[0] -= (j[3] * r[0] - j[1] * r[1]) / det;
            uv[1] -= (j[0] * r[1] - j[2] * r[0]) / det;
        }
        let q = patch.eval(uv[0], uv[1]);
        let near = (uv[0] - mid[0]).abs() + (uv[1] - mid[1]).abs() < 0.1;
        if near && pl.signed_distance(&q).abs() < 1e-9 && (q - m).dot(&ab).abs() < 1e-9 {
            return (q - m).norm();
        }
        let len = (a.v - b.v).hypot(b.u - a.u);
        let perp = [(a.v - b.v) / len, (b.u - a.u) / len];
        let at = |s: f64| [mid[0] + perp[0] * s, mid[1] + perp[1] * s];
        let f = |s: f64| {
            let p = at(s);
            pl.signed_distance(&patch.eval(p[0], p[1]))
        };
        let f0 = f(0.0);
        let mut reach = 1e-9;
        let other = loop {
            if (f(reach) >= 0.0) != (f0 >= 0.0) {
                break reach;
            }
            if (f(-reach) >= 0.0) != (f0 >= 0.0) {
                break -reach;
            }
            reach *= 2.0;
            assert!(reach < 1.0, "no curve point across the chord");
        };
        let (mut lo, mut hi) = (0.0, other);
        for _ in 0..100 {
            let s = 0.5 * (lo + hi);
            if (f(s) >= 0.0) == (f0 >= 0.0) {
                lo = s;
            } else {
                hi = s;
            }
        }
        let p = at(lo);
        point_segment_distance(&patch.eval(p[0], p[1]), &a.point, &b.point)
    }

    /// On the plane, chords within `tol` at their midpoints, open ends on the boundary.
    fn check_curves(patch: &Patch, pl: &Plane, tol: f64, curves: &[SectionCurve]) {
        let [[u0, u1], [v0, v1]] = patch.domain();
        for c in curves {
            for s in &c.samples {
                assert!(pl.signed_distance(&s.point).abs() < 1e-9, "off the plane");
                assert_eq!(s.point, patch.eval(s.u, s.v));
            }
            let n = c.samples.len();
            let chords = if c.closed { n } else { n - 1 };
            for k in 0..chords {
                let (a, b) = (&c.samples[k], &c.samples[(k + 1) % n]);
                let e = mid_chord_error(patch, pl, a, b);
                assert!(e <= tol, "chord {k} of {n}: {e} > {tol}");
            }
            if !c.closed {
                for s in [&c.samples[0], &c.samples[n - 1]] {
                    assert!(s.u == u0 || s.u == u1 || s.v == v0 || s.v == v1, "{s:?}");
                }
            }
        }
    }

    /// Sign changes of the plane's distance along the patch boundary, densely sampled.
    fn boundary_crossings(patch: &Patch, pl: &Plane) -> usize {
        let n = 4000;
        let [[u0, u1], [v0, v1]] = patch.domain();
        let mut ring = Vec::new();
        for k in 0..n {
            let t = f64::from(k) / f64::from(n);
            ring.push((u0 + (u1 - u0) * t, v0));
        }
        for k in 0..n {
            let t = f64::from(k) / f64::from(n);
            ring.push((u1, v0 + (v1 - v0) * t));
        }
        for k in 0..n {
            let t = f64::from(k) / f64::from(n);
            ring.push((u1 - (u1 - u0) * t, v1));
        }
        for k in 0..n {
            let t = f64::from(k) / f64::from(n);
            ring.push((u0, v1 - (v1 - v0) * t));
        }
        let s: Vec<bool> = ring
            .iter()
            .map(|(u, v)| pl.signed_distance(&patch.eval(*u, *v)) >= 0.0)
            .collect();
        (0..s.len())
            .filter(|&k| s[k] != s[(k + 1) % s.len()])
            .count()
    }

    #[test]
    fn invalid_inputs_are_named() {
        let pl = plane([0.0, 0.0, 30.0], [0.0, 0.0, 1.0]);
        for bad in [0.0, -0.1, f64::NAN] {
            let e = wave().intersect_plane(&pl, bad).unwrap_err();
            assert!(e.to_string().starts_with("tol = "), "{e}");
        }
        let zero = Plane {
            normal: Vec3::zeros(),
            offset: 1.0,
        };
        let e = wave().intersect_plane(&zero, 0.1).unwrap_err();
        assert!(e.to_string().starts_with("plane = "), "{e}");
        let miss = plane([0.0, 0.0, 500.0], [0.0, 0.0, 1.0]);
        assert!(wave().intersect_plane(&miss, 0.1).unwrap().is_empty());
    }

    #[test]
    fn sphere_sections_are_circular_arcs() {
        let r = 5.0;
        let s = sphere_octant(r);
        let tol = 1e-3;
        for (n, d, branches) in [([0.0, 0.0, 1.0], 3.0, 1), ([1.0, 1.0, 1.0], 4.0, 3)] {
            let normal = Vec3::from(n).normalize();
            let pl = Plane { normal, offset: d };
            let curves = s.intersect_plane(&pl, tol).unwrap();
            check_curves(&s, &pl, tol, &curves);
            assert_eq!(curves.len(), branches);
            let (centre, radius) = (Point3::from(normal * d), (r * r - d * d).sqrt());
            for c in &curves {
                assert!(!c.closed);
                for w in c.samples.windows(2) {
                    assert!(((w[0].point - centre).norm() - radius).abs() < 1e-9);
                    let half = 0.5 * (w[1].point - w[0].point).norm();
                    let sagitta = radius - (radius * radius - half * half).sqrt();
                    assert!(sagitta <= tol, "sagitta {sagitta}");
                }
            }
        }
    }

    #[test]
    fn iso_parametric_section_of_wave() {
        let w = wave();
        let pl = plane([77.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let curves = w.intersect_plane(&pl, 0.01).unwrap();
        assert_eq!(curves.len(), 1);
        check_curves(&w, &pl, 0.01, &curves);
        let u = curves[0].samples[0].u;
        assert!(
            curves[0].samples.iter().all(|s| (s.u - u).abs() < 1e-9),
            "x depends on u only"
        );
        let ends = [curves[0].samples[0].v, curves[0].samples.last().unwrap().v];
        assert!(ends == [0.0, 1.0] || ends == [1.0, 0.0], "{ends:?}");
        let length = curves[0].to_polyline().length();
        let dense: f64 = (0..2000)
            .map(|k| {
                (w.eval(u, f64::from(k + 1) / 2000.0) - w.eval(u, f64::from(k) / 2000.0)).norm()
            })
            .sum();
        assert!(
            length <= dense + 1e-9 && length > dense - 0.05,
            "{length} vs {dense}"
        );
    }

    /// A bicubic bump, zero on its border, with its summit away from the seed grid.
    fn bump() -> Patch {
        let z = [
            [0.0; 4],
            [0.0, 30.0, 26.0, 0.0],
            [0.0, 34.0, 29.0, 0.0],
            [0.0; 4],
        ];
        let pts = (0..16)
            .map(|k| {
                Point3::new(
                    20.0 * (k / 4) as f64,
                    20.0 * (k % 4) as f64,
                    z[k / 4][k % 4],
                )
            })
            .collect();
        Patch::bezier([3, 3], pts).unwrap()
    }

    #[test]
    fn closed_loops_large_and_tiny() {
        let b = bump();
        let mut top = (0.5, 0.5);
        for _ in 0..30 {
            let d = b.derivs(top.0, top.1);
            let (g, h) = ([d.du.z, d.dv.z], [d.duu.z, d.duv.z, d.dvv.z]);
            let det = h[0] * h[2] - h[1] * h[1];
            top.0 -= (h[2] * g[0] - h[1] * g[1]) / det;
            top.1 -= (h[0] * g[1] - h[1] * g[0]) / det;
        }
        let summit = b.eval(top.0, top.1).z;
        for (height, tol) in [(8.0, 0.01), (summit - 1e-3, 1e-4)] {
            let pl = plane([0.0, 0.0, height], [0.0, 0.0, 1.0]);
            let curves = b.intersect_plane(&pl, tol).unwrap();
            assert_eq!(curves.len(), 1, "height {height}");
            assert!(curves[0].closed && curves[0].samples.len() >= 4);
            check_curves(&b, &pl, tol, &curves);
            assert!(curves[0].to_polyline().closed);
        }
    }

    /// The full check of one section: [`check_curves`], one open branch per pair of
    /// boundary crossings, and every root on the lines of a 60 x 60 grid (bisection) on
    /// some traced branch.
    fn check_section(patch: &Patch, pl: &Plane, tol: f64) -> Result<(), TestCaseError> {
        let curves = patch.intersect_plane(pl, tol).unwrap();
        check_curves(patch, pl, tol, &curves);
        let open = curves.iter().filter(|c| !c.closed).count();
        prop_assert_eq!(2 * open, boundary_crossings(patch, pl));
        let grid = 60;
        let f = |u: f64, v: f64| pl.signed_distance(&patch.eval(u, v));
        for i in 0..=grid {
            let u = f64::from(i) / f64::from(grid);
            for j in 0..grid {
                let (mut lo, mut hi) = (
                    f64::from(j) / f64::from(grid),
                    f64::from(j + 1) / f64::from(grid),
                );
                let below = f(u, lo) >= 0.0;
                if below == (f(u, hi) >= 0.0) {
                    continue;
                }
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if (f(u, mid) >= 0.0) == below {
                        lo = mid
                    } else {
                        hi = mid
                    }
                }
                let q = patch.eval(u, lo);
                let near = curves.iter().any(|c| {
                    let pts = c.to_polyline().points;
                    let n = pts.len();
                    let chords = if c.closed { n } else { n - 1 };
                    (0..chords).any(|k| {
                        point_segment_distance(&q, &pts[k], &pts[(k + 1) % n]) <= tol + 1e-9
                    })
                });
                prop_assert!(near, "a crossing at {q:?} is on no traced branch");
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        #[test]
        fn random_sections_of_die_and_wave(
            which in any::<bool>(), u in 0.05..0.95f64, v in 0.05..0.95f64,
            theta in 0.0..3.1f64, phi in 0.0..6.3f64, log_tol in -3.0..-0.5f64,
        ) {
            let patch = if which { die() } else { wave() };
            let n = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
            let pl = Plane::from_point_normal(&patch.eval(u, v), &Vec3::from(n)).unwrap();
            check_section(&patch, &pl, 10f64.powf(log_tol))?;
        }

        #[test]
        fn nearly_tangent_sections(
            which in any::<bool>(), u in 0.05..0.95f64, v in 0.05..0.95f64,
            tilt in proptest::collection::vec(-0.05..0.05f64, 3), lift in -0.03..0.03f64,
            log_tol in -3.0..-0.5f64,
        ) {
            let patch = if which { die() } else { wave() };
            let normal = patch.derivs(u, v).normal().unwrap();
            let n = normal + Vec3::new(tilt[0], tilt[1], tilt[2]);
            let pl = Plane::from_point_normal(&(patch.eval(u, v) + normal * lift), &n).unwrap();
            check_section(&patch, &pl, 10f64.powf(log_tol))?;
        }
    }
}
