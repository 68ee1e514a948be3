//! The ranges of a patch's principal curvatures over a parameter grid.
//!
//! The principal curvatures `k1 >= k2` ([`SurfaceDerivs::principal_curvatures`], sign
//! convention there) are evaluated at the `n x n` points `u_i = u0 + (u1 - u0) i / (n - 1)`,
//! `v_j` alike (corners and edges included), with the grid evaluator
//! ([`Patch::derivs_on_grid`]: the net's rows contracted once per v, basis functions
//! once per u and per v). Points without a normal (a collapsed edge, parallel partials) or
//! whose curvature overflows are skipped.
//!
//! The ranges are sampled, not bounded: each reported extreme is attained at a grid
//! point, so the true range over the patch holds the reported one, and an extreme
//! between grid points is missed by at most the curvature's variation across one grid
//! cell. Exact wherever the extremes lie on grid points, as at the corners and edge
//! points of a surface whose curvature is monotone along its parameter lines.

use super::Patch;
use super::eval::SurfaceDerivs;
use crate::error::GeomError;

/// The ranges of the principal curvatures over a grid ([`Patch::curvature_range`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvatureRange {
    /// `[min, max]` of the larger principal curvature, 1/mm.
    pub k1: [f64; 2],
    /// `[min, max]` of the smaller principal curvature, 1/mm.
    pub k2: [f64; 2],
    /// Grid points with a curvature (the others have no normal).
    pub regular: usize,
}

impl Patch {
    /// The ranges of the principal curvatures at the `samples x samples` points of a
    /// uniform parameter grid (module doc); `None` when no grid point has a normal.
    ///
    /// # Units
    /// 1/mm, positive when the surface bends toward its normal `du x dv`.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `samples` when it is below 2.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3};
    /// // z = x^2 / 2 over x in [0, 1]: curvature 1 at x = 0, 2^-1.5 at x = 1.
    /// let p = Patch::bezier([2, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0),
    ///     Point3::new(0.5, 0.0, 0.0), Point3::new(0.5, 1.0, 0.0),
    ///     Point3::new(1.0, 0.0, 0.5), Point3::new(1.0, 1.0, 0.5),
    /// ]).unwrap();
    /// let r = p.curvature_range(11).unwrap().unwrap();
    /// assert!((r.k1[1] - 1.0).abs() < 1e-12 && (r.k1[0] - 2f64.powf(-1.5)).abs() < 1e-12);
    /// assert!(r.k2[0].abs() < 1e-12 && r.k2[1].abs() < 1e-12 && r.regular == 121);
    /// ```
    pub fn curvature_range(&self, samples: usize) -> Result<Option<CurvatureRange>, GeomError> {
        if samples < 2 {
            return Err(GeomError::InvalidParameter {
                name: "samples".into(),
                value: samples as f64,
                expected: "at least 2 grid points per direction".into(),
            });
        }
        let n = (samples - 1) as f64;
        let [[u0, u1], [v0, v1]] = self.domain();
        let us: Vec<f64> = (0..samples)
            .map(|i| u0 + (u1 - u0) * i as f64 / n)
            .collect();
        let vs: Vec<f64> = (0..samples)
            .map(|j| v0 + (v1 - v0) * j as f64 / n)
            .collect();
        let mut k1 = [f64::INFINITY, f64::NEG_INFINITY];
        let mut k2 = k1;
        let mut regular = 0;
        self.derivs_on_grid(&us, &vs, |_, column: &[SurfaceDerivs]| {
            for [a, b] in column
                .iter()
                .filter_map(SurfaceDerivs::principal_curvatures)
            {
                if a.is_finite() && b.is_finite() {
                    k1 = [k1[0].min(a), k1[1].max(a)];
                    k2 = [k2[0].min(b), k2[1].max(b)];
                    regular += 1;
                }
            }
        });
        Ok((regular > 0).then_some(CurvatureRange { k1, k2, regular }))
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{die, quarter_cylinder, sphere_octant, wave};
    use super::*;
    use crate::math::Point3;

    /// The ranges point by point with [`Patch::curvature_at`]: the oracle.
    fn one_by_one(p: &Patch, n: usize) -> Option<CurvatureRange> {
        let [[u0, u1], [v0, v1]] = p.domain();
        let mut k1 = [f64::INFINITY, f64::NEG_INFINITY];
        let mut k2 = k1;
        let mut regular = 0;
        for i in 0..n {
            for j in 0..n {
                let u = u0 + (u1 - u0) * i as f64 / (n - 1) as f64;
                let v = v0 + (v1 - v0) * j as f64 / (n - 1) as f64;
                if let Some(c) = p.curvature_at(u, v) {
                    k1 = [k1[0].min(c.k1), k1[1].max(c.k1)];
                    k2 = [k2[0].min(c.k2), k2[1].max(c.k2)];
                    regular += 1;
                }
            }
        }
        (regular > 0).then_some(CurvatureRange { k1, k2, regular })
    }

    #[test]
    fn quadrics_have_their_constant_curvatures() {
        let r = 5.0;
        let c = quarter_cylinder(r, 2.0)
            .curvature_range(21)
            .unwrap()
            .unwrap();
        assert_eq!(c.regular, 21 * 21);
        assert!(c.k1.iter().all(|k| k.abs() < 1e-12), "{c:?}");
        assert!(c.k2.iter().all(|k| (k + 1.0 / r).abs() < 1e-12), "{c:?}");
        // the pole row (u = 1) is collapsed: no normal there
        let s = sphere_octant(r).curvature_range(21).unwrap().unwrap();
        assert_eq!(s.regular, 20 * 21);
        let all = s.k1.iter().chain(&s.k2);
        assert!(all.clone().all(|k| (k - 1.0 / r).abs() < 1e-9), "{s:?}");
    }

    #[test]
    fn grid_ranges_are_those_of_point_evaluation() {
        for p in [wave(), die(), sphere_octant(3.0)] {
            assert_eq!(p.curvature_range(37).unwrap(), one_by_one(&p, 37));
        }
    }

    #[test]
    fn no_normal_and_too_few_samples() {
        let line = (0..4).map(|k| Point3::new(k as f64, 0.0, 0.0)).collect();
        let p = Patch::bezier([1, 1], line).unwrap();
        assert_eq!(p.curvature_range(11).unwrap(), None);
        for n in [0, 1] {
            let e = wave().curvature_range(n).unwrap_err();
            assert!(e.to_string().starts_with("samples = "), "{e}");
        }
    }
}
