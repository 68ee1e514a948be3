//! Knot insertion (Boehm's algorithm): the same surface with one more knot.
//!
//! Inserting `t` once into `[U_k, U_{k+1})` of a degree-`p` direction where `t` already
//! has multiplicity `s` (The NURBS Book eq. 5.15, A5.1 with `r = 1`) replaces the control
//! points `P_{k-p+1} .. P_{k-s}` of every iso-curve in that direction by
//! `Q_i = a_i P_i + (1 - a_i) P_{i-1}`, `a_i = (t - U_i) / (U_{i+p} - U_i)`, keeps the
//! points before and shifts the ones after by one. A NURBS patch is refined on its
//! homogeneous points `(w P, w)`, so the rational surface is unchanged too.

use super::Patch;
use super::basis::find_span;
use crate::error::GeomError;
use nalgebra::Vector4;

impl Patch {
    /// The same surface with the knot `t` inserted once in direction `dir` (0 = u,
    /// 1 = v): one more row (u) or column (v) of control points.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `dir` when it is not 0 or 1, naming `t`
    /// when it is not strictly inside the parameter range or already has multiplicity
    /// equal to the degree (which would make the surface discontinuous).
    pub fn insert_knot(&self, dir: usize, t: f64) -> Result<Patch, GeomError> {
        if dir > 1 {
            return Err(GeomError::InvalidParameter {
                name: "dir".into(),
                value: dir as f64,
                expected: "0 (u) or 1 (v)".into(),
            });
        }
        let p = self.degree[dir];
        let knots = &self.knots[dir];
        let [lo, hi] = self.domain()[dir];
        if !(t > lo && t < hi) {
            return Err(GeomError::InvalidParameter {
                name: "t".into(),
                value: t,
                expected: format!("a knot strictly inside ({lo}, {hi})"),
            });
        }
        let s = knots.iter().filter(|k| **k == t).count();
        if s >= p {
            return Err(GeomError::InvalidParameter {
                name: "t".into(),
                value: t,
                expected: format!("a knot of multiplicity below the degree {p}, found {s}"),
            });
        }
        let k = find_span(knots, p, t);
        let alpha: Vec<f64> = (k + 1 - p..=k - s)
            .map(|i| (t - knots[i]) / (knots[i + p] - knots[i]))
            .collect();
        let [nu, nv] = self.count;
        let new_count = if dir == 0 { [nu + 1, nv] } else { [nu, nv + 1] };
        let mut hom = Vec::with_capacity(new_count[0] * new_count[1]);
        for i in 0..new_count[0] {
            for j in 0..new_count[1] {
                let (c, fetch) = if dir == 0 { (i, (0, j)) } else { (j, (i, 0)) };
                let at = |m: usize| {
                    let (a, b) = if dir == 0 { (m, fetch.1) } else { (fetch.0, m) };
                    let w = self.weight(a, b);
                    let q = self.point(a, b);
                    Vector4::new(q.x * w, q.y * w, q.z * w, w)
                };
                hom.push(if c + p <= k {
                    at(c)
                } else if c > k - s {
                    at(c - 1)
                } else {
                    let a = alpha[c + p - k - 1];
                    at(c) * a + at(c - 1) * (1.0 - a)
                });
            }
        }
        let mut new_knots = knots.clone();
        new_knots.insert(k + 1, t);
        let mut all_knots = [Some(self.knots[0].clone()), Some(self.knots[1].clone())];
        all_knots[dir] = Some(new_knots);
        let points = hom
            .iter()
            .map(|h| crate::math::Point3::new(h.x / h.w, h.y / h.w, h.z / h.w))
            .collect();
        let weights = self
            .weights
            .as_ref()
            .map(|_| hom.iter().map(|h| h.w).collect());
        Patch::new(self.degree, points, all_knots, weights)
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{nurbs_spline, sphere_octant, wave};
    use super::*;
    use proptest::prelude::*;

    fn same_surface(a: &Patch, b: &Patch, eps: f64) {
        for i in 0..=12 {
            for j in 0..=12 {
                let [[u0, u1], [v0, v1]] = a.domain();
                let u = u0 + (u1 - u0) * f64::from(i) / 12.0;
                let v = v0 + (v1 - v0) * f64::from(j) / 12.0;
                let (da, db) = (a.derivs(u, v), b.derivs(u, v));
                assert!((da.point - db.point).norm() < eps, "at ({u}, {v})");
                assert!((da.du - db.du).norm() < 1e3 * eps, "du at ({u}, {v})");
            }
        }
    }

    #[test]
    fn rejects_bad_knots_and_directions() {
        let p = wave();
        assert!(
            matches!(p.insert_knot(2, 0.5), Err(GeomError::InvalidParameter { name, .. }) if name == "dir")
        );
        for t in [0.0, 1.0, -0.5, f64::NAN] {
            let e = p.insert_knot(0, t).unwrap_err();
            assert!(e.to_string().starts_with("t = "), "{e}");
        }
        let twice = p.insert_knot(1, 0.3).unwrap().insert_knot(1, 0.3).unwrap();
        let thrice = twice.insert_knot(1, 0.3).unwrap();
        assert_eq!(thrice.count(), [4, 7]);
        let e = thrice.insert_knot(1, 0.3).unwrap_err();
        assert!(e.to_string().contains("multiplicity"), "{e}");
        same_surface(&p, &thrice, 1e-11);
    }

    #[test]
    fn rational_sphere_stays_a_sphere() {
        let p = sphere_octant(4.0)
            .insert_knot(0, 0.3)
            .unwrap()
            .insert_knot(1, 0.8)
            .unwrap();
        assert_eq!(p.count(), [4, 4]);
        for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.9, 0.95)] {
            assert!(((p.eval(u, v).coords.norm()) - 4.0).abs() < 1e-12);
        }
        same_surface(&sphere_octant(4.0), &p, 1e-12);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        #[test]
        fn insertion_leaves_the_surface_unchanged(
            knots in proptest::collection::vec((0usize..2, 0.01..0.99f64), 1..4),
            jitter in proptest::collection::vec(-5.0..5.0f64, 70),
        ) {
            let base = nurbs_spline();
            let pts: Vec<_> = base.points().iter().zip(&jitter).map(|(q, d)| q + crate::Vec3::new(0.0, 0.0, *d)).collect();
            let kn = [Some(base.knots(0).to_vec()), Some(base.knots(1).to_vec())];
            let w = base.weights().map(<[f64]>::to_vec);
            let start = Patch::new(base.degree(), pts, kn, w).unwrap();
            let mut p = start.clone();
            for (dir, f) in knots {
                let [lo, hi] = p.domain()[dir];
                p = p.insert_knot(dir, lo + (hi - lo) * f).unwrap();
            }
            same_surface(&start, &p, 1e-10);
        }
    }
}
