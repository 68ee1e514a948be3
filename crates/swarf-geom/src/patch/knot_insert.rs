//! Knot insertion (Boehm's algorithm): the same surface with one more knot.
//!
//! Inserting `t` once into `[U_k, U_{k+1})` of a degree-`p` direction where `t` already
//! has multiplicity `s` (The NURBS Book eq. 5.15, A5.1 with `r = 1`) replaces the control
//! points `P_{k-p+1} .. P_{k-s}` of every iso-curve in that direction by
//! `Q_i = a_i P_i + (1 - a_i) P_{i-1}`, `a_i = (t - U_i) / (U_{i+p} - U_i)`, keeps the
//! points before and shifts the ones after by one. A NURBS patch is refined on its
//! homogeneous points `(w P, w)`, so the rational surface is unchanged too.
//!
//! Inserting every interior knot until its multiplicity is the degree cuts the patch
//! into Bezier patches, one per pair of spans (The NURBS Book §5.3): the power form of
//! [`super::PowerPatch`] and the surface box of [`super::surface_box`] start from
//! those nets ([`Patch::bezier_spans`]). The refinement runs on the homogeneous net
//! itself, without a [`Patch`] (and its checks) per inserted knot.

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
        let mut net = HomNet::of(self);
        net.insert(dir, t);
        let points = net
            .hom
            .iter()
            .map(|h| crate::math::Point3::new(h.x / h.w, h.y / h.w, h.z / h.w))
            .collect();
        let weights = self
            .weights
            .as_ref()
            .map(|_| net.hom.iter().map(|h| h.w).collect());
        let [ku, kv] = net.knots;
        Patch::new(self.degree, points, [Some(ku), Some(kv)], weights)
    }

    /// The patch cut into its Bezier patches (module doc).
    pub(crate) fn bezier_spans(&self) -> BezierSpans {
        let mut net = HomNet::of(self);
        for dir in 0..2 {
            let p = self.degree[dir];
            let knots = self.knots[dir].clone();
            let (lo, hi) = (knots[0], knots[knots.len() - 1]);
            let mut k = 0;
            while k < knots.len() {
                let t = knots[k];
                let mult = knots[k..].iter().take_while(|&&x| x == t).count();
                if t > lo && t < hi {
                    for _ in mult..p {
                        net.insert(dir, t);
                    }
                }
                k += mult;
            }
        }
        let [p, q] = self.degree;
        let breaks = net.knots.clone().map(|mut b| {
            b.dedup();
            b
        });
        let spans = [breaks[0].len() - 1, breaks[1].len() - 1];
        let nv = net.count[1];
        let mut nets = Vec::with_capacity(spans[0] * spans[1]);
        for a in 0..spans[0] {
            for b in 0..spans[1] {
                let span = (0..=p).flat_map(|i| {
                    let row = (a * p + i) * nv + b * q;
                    net.hom[row..=row + q].iter().map(|h| [h.x, h.y, h.z, h.w])
                });
                nets.push(span.collect());
            }
        }
        BezierSpans {
            degree: self.degree,
            breaks,
            nets,
        }
    }
}

/// A patch cut into Bezier patches ([`Patch::bezier_spans`]).
pub(crate) struct BezierSpans {
    /// `[p, q]`, as the patch's.
    pub degree: [usize; 2],
    /// Span boundaries per direction (the distinct knots).
    pub breaks: [Vec<f64>; 2],
    /// Per span pair, u-major (`a * spans_v + b`), the `(p + 1) * (q + 1)` homogeneous
    /// control points `(w x, w y, w z, w)` of its Bezier patch, row-major.
    pub nets: Vec<Vec<[f64; 4]>>,
}

/// A patch's knots and homogeneous control net, refined in place.
struct HomNet {
    degree: [usize; 2],
    knots: [Vec<f64>; 2],
    count: [usize; 2],
    hom: Vec<Vector4<f64>>,
}

impl HomNet {
    fn of(patch: &Patch) -> HomNet {
        let [nu, nv] = patch.count;
        let hom = (0..nu * nv)
            .map(|k| {
                let (q, w) = (patch.point(k / nv, k % nv), patch.weight(k / nv, k % nv));
                Vector4::new(q.x * w, q.y * w, q.z * w, w)
            })
            .collect();
        HomNet {
            degree: patch.degree,
            knots: patch.knots.clone(),
            count: patch.count,
            hom,
        }
    }

    /// Inserts `t` once in direction `dir` (module doc); `t` lies strictly inside the
    /// range with a multiplicity below the degree.
    fn insert(&mut self, dir: usize, t: f64) {
        let p = self.degree[dir];
        let knots = &self.knots[dir];
        let s = knots.iter().filter(|k| **k == t).count();
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
                    self.hom[a * nv + b]
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
        self.knots[dir].insert(k + 1, t);
        self.count = new_count;
        self.hom = hom;
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
