//! A patch in power form per span, for the millions of exact point-and-tangent
//! evaluations the height-field query needs ([`crate::height`]).
//!
//! The design heights of the dexel verifier solve a vertical ray against the part at every cell centre (8
//! million on wave.toml at 0.05 mm), about three Newton steps each, every step a point
//! with its first derivatives. The general evaluator of the geometry kernel
//! (`Patch::derivs`, de Boor with second derivatives) costs about 570 ns a call in a
//! release build here, which alone would take ~7 s on two cores; this form costs a few
//! tens of nanoseconds. It is exact up to rounding (the same polynomials in another
//! basis), and a test holds it to the kernel's evaluator.
//!
//! Construction (The NURBS Book §5.3 and §6.6): insert every interior knot until its
//! multiplicity is the degree (decomposition into Bezier patches, the kernel's
//! `Patch::bezier_spans`); then, per span, take the homogeneous control points
//! `(w x, w y, w z, w)` and change basis from Bernstein to monomials,
//! `a_k = sum_{i<=k} C(p, k) C(k, i) (-1)^(k-i) B_i`, in u and then in v. Evaluation is
//! Horner's rule in the span's local parameters; a rational patch divides by the
//! weight polynomial (`S_u = (H_u - w_u S) / w`).

use super::Patch;
use crate::error::GeomError;
use crate::math::{Point3, Vec3};

/// A patch as polynomials per span.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerPatch {
    degree: [usize; 2],
    /// Span boundaries per direction (distinct knots).
    breaks: [Vec<f64>; 2],
    /// Per span (u-major), `(p + 1) * (q + 1)` homogeneous coefficients, index
    /// `k * (q + 1) + l` for `s^k t^l`.
    coef: Vec<[f64; 4]>,
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Bernstein coefficients to monomial coefficients (in place, one direction).
fn to_monomial(b: &[[f64; 4]]) -> Vec<[f64; 4]> {
    let p = b.len() - 1;
    (0..=p)
        .map(|k| {
            let mut a = [0.0; 4];
            for (i, bi) in b.iter().enumerate().take(k + 1) {
                let c = binomial(p, k) * binomial(k, i) * if (k - i) % 2 == 0 { 1.0 } else { -1.0 };
                for d in 0..4 {
                    a[d] += c * bi[d];
                }
            }
            a
        })
        .collect()
}

impl PowerPatch {
    /// Converts `patch`.
    ///
    /// # Errors
    /// The [`GeomError`] of a knot insertion that fails (it cannot for a valid patch).
    pub fn new(patch: &Patch) -> Result<PowerPatch, GeomError> {
        let bez = patch.bezier_spans();
        let [p, q] = bez.degree;
        let mut coef = Vec::with_capacity(bez.nets.len() * (p + 1) * (q + 1));
        for net in &bez.nets {
            // monomial in u for each v-row of Bernstein points, then in v
            let rows: Vec<Vec<[f64; 4]>> = (0..=q)
                .map(|j| to_monomial(&(0..=p).map(|i| net[i * (q + 1) + j]).collect::<Vec<_>>()))
                .collect();
            let mut span = vec![[0.0; 4]; (p + 1) * (q + 1)];
            for k in 0..=p {
                let col = to_monomial(&(0..=q).map(|j| rows[j][k]).collect::<Vec<_>>());
                for (l, c) in col.into_iter().enumerate() {
                    span[k * (q + 1) + l] = c;
                }
            }
            coef.extend(span);
        }
        Ok(PowerPatch {
            degree: [p, q],
            breaks: bez.breaks,
            coef,
        })
    }

    /// Span index and local parameter of `t` in direction `d` (clamped), with the
    /// span's width.
    #[inline(always)]
    fn locate(&self, d: usize, t: f64) -> (usize, f64, f64) {
        let b = &self.breaks[d];
        let n = b.len() - 1;
        let t = t.clamp(b[0], b[n]);
        let k = if n == 1 {
            0
        } else {
            b.partition_point(|&x| x <= t).clamp(1, n) - 1
        };
        let w = b[k + 1] - b[k];
        (k, (t - b[k]) / w, w)
    }

    /// The point and its first partial derivatives at `(u, v)` (clamped into the
    /// domain).
    ///
    /// # Units
    /// mm, and mm per unit parameter.
    #[inline]
    pub fn eval1(&self, u: f64, v: f64) -> (Point3, Vec3, Vec3) {
        // Constant degrees let the inlined loops unroll for the common cases.
        match self.degree {
            [3, 3] => self.eval1_deg(u, v, 3, 3),
            [2, 2] => self.eval1_deg(u, v, 2, 2),
            [1, 1] => self.eval1_deg(u, v, 1, 1),
            [3, 2] => self.eval1_deg(u, v, 3, 2),
            [2, 3] => self.eval1_deg(u, v, 2, 3),
            [p, q] => self.eval1_deg(u, v, p, q),
        }
    }

    /// [`PowerPatch::eval1`] with the degrees `p`, `q` passed in (inlined, so constant
    /// degrees unroll).
    #[inline(always)]
    fn eval1_deg(&self, u: f64, v: f64, p: usize, q: usize) -> (Point3, Vec3, Vec3) {
        let (su, s, wu) = self.locate(0, u);
        let (sv, t, wv) = self.locate(1, v);
        let spans_v = self.breaks[1].len() - 1;
        let base = (su * spans_v + sv) * (p + 1) * (q + 1);
        let c = &self.coef[base..base + (p + 1) * (q + 1)];
        horner(c, p, q, s, t, wu, wv)
    }

    /// The parameter domain `[[u0, u1], [v0, v1]]`.
    pub fn domain(&self) -> [[f64; 2]; 2] {
        [0, 1].map(|d| [self.breaks[d][0], self.breaks[d][self.breaks[d].len() - 1]])
    }
}

/// Horner's rule over a span's coefficients, degrees `p`, `q`.
#[inline(always)]
fn horner(
    c: &[[f64; 4]],
    p: usize,
    q: usize,
    s: f64,
    t: f64,
    wu: f64,
    wv: f64,
) -> (Point3, Vec3, Vec3) {
    let mut h = [0.0; 4];
    let mut hs = [0.0; 4];
    let mut ht = [0.0; 4];
    for l in (0..=q).rev() {
        let mut a = [0.0; 4];
        let mut da = [0.0; 4];
        for k in (0..=p).rev() {
            let ck = c[k * (q + 1) + l];
            for d in 0..4 {
                da[d] = da[d] * s + a[d];
                a[d] = a[d] * s + ck[d];
            }
        }
        for d in 0..4 {
            ht[d] = ht[d] * t + h[d];
            h[d] = h[d] * t + a[d];
            hs[d] = hs[d] * t + da[d];
        }
    }
    finish(h, hs, ht, wu, wv)
}

/// Point and derivatives from the homogeneous value and its local derivatives.
#[inline(always)]
fn finish(h: [f64; 4], hs: [f64; 4], ht: [f64; 4], wu: f64, wv: f64) -> (Point3, Vec3, Vec3) {
    let inv = 1.0 / h[3];
    let pt = Vec3::new(h[0], h[1], h[2]) * inv;
    let du = (Vec3::new(hs[0], hs[1], hs[2]) - pt * hs[3]) * (inv / wu);
    let dv = (Vec3::new(ht[0], ht[1], ht[2]) - pt * ht[3]) * (inv / wv);
    (Point3::from(pt), du, dv)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(patch: &Patch) {
        let pp = PowerPatch::new(patch).unwrap();
        let [[u0, u1], [v0, v1]] = patch.domain();
        assert_eq!(pp.domain(), patch.domain());
        for a in 0..=23 {
            for b in 0..=17 {
                let u = u0 + (u1 - u0) * a as f64 / 23.0;
                let v = v0 + (v1 - v0) * b as f64 / 17.0;
                let d = patch.derivs(u, v);
                let (p, du, dv) = pp.eval1(u, v);
                let scale = 1.0 + d.point.coords.norm();
                assert!((p - d.point).norm() < 1e-11 * scale, "{u} {v}");
                assert!((du - d.du).norm() < 1e-9 * (scale + d.du.norm()), "{u} {v}");
                assert!((dv - d.dv).norm() < 1e-9 * (scale + d.dv.norm()), "{u} {v}");
            }
        }
    }

    #[test]
    fn matches_the_kernel_on_bezier_bspline_and_nurbs() {
        let pt = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let mut pts = Vec::new();
        for i in 0..5 {
            for j in 0..4 {
                let (x, y) = (10.0 * i as f64, 7.0 * j as f64);
                pts.push(pt(x + (j as f64).powi(2), y, ((i * 7 + j * 3) % 5) as f64));
            }
        }
        let bez = Patch::bezier([4, 3], pts.clone()).unwrap();
        check(&bez);
        let knots_u = vec![0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0];
        let knots_v = vec![0.0, 0.0, 0.0, 0.5, 2.0, 2.0, 2.0];
        let mut pts2 = Vec::new();
        for i in 0..5 {
            for j in 0..4 {
                pts2.push(pt(5.0 * i as f64, 3.0 * j as f64, ((i + 2 * j) % 3) as f64));
            }
        }
        let bs = Patch::new(
            [2, 2],
            pts2.clone(),
            [Some(knots_u.clone()), Some(knots_v.clone())],
            None,
        )
        .unwrap();
        check(&bs);
        let w: Vec<f64> = (0..20).map(|k| 0.5 + (k % 4) as f64 * 0.4).collect();
        let nurbs = Patch::new([2, 2], pts2, [Some(knots_u), Some(knots_v)], Some(w)).unwrap();
        check(&nurbs);
    }
}
