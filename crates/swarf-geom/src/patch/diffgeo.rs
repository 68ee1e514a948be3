//! Differential geometry at a surface point: unit normal, fundamental forms, normal and
//! principal curvatures.
//!
//! With `n = (S_u x S_v) / |S_u x S_v|`, the first fundamental form is `E = S_u.S_u`,
//! `F = S_u.S_v`, `G = S_v.S_v` and the second `L = S_uu.n`, `M = S_uv.n`, `N = S_vv.n`
//! (do Carmo, ch. 3-2/3-3; paper 004 uses the same normal curvature for the side step).
//! The normal curvature along a tangent `t = a S_u + b S_v` is
//! `k(t) = (L a^2 + 2 M a b + N b^2) / (E a^2 + 2 F a b + G b^2)`: **positive when the
//! surface bends toward `n`** (a sphere has `+1/R` with the inward normal, `-1/R` with the
//! outward one).
//!
//! Principal curvatures: write `S_u = (a, 0)` and `S_v = (b, c)` in the orthonormal
//! tangent frame `e1 = S_u/|S_u|`, `e2 = n x e1`, so the parameter-to-frame map is
//! `J = [[a, b], [0, c]]`. The shape operator in that frame is the symmetric matrix
//! `W = J^-T [[L, M], [M, N]] J^-1`; its eigenvalues are `k1 >= k2` and a Jacobi
//! rotation by `theta = atan2(2 W12, W11 - W22) / 2` gives orthogonal principal
//! directions directly in 3D. `K = k1 k2` and `H = (k1 + k2) / 2`. With `a^2 = E`,
//! `b = F / a` and `c = |S_u x S_v| / a` (= `S_v . e2`), writing `D = |S_u x S_v|`,
//! `W11 = L / E`, `W12 = (M E - L F) / (E D)`, `W22 = (L F^2 - 2 M F E + N E^2) / (E D^2)`:
//! scalar products, one square root and two divisions, so the principal curvatures
//! alone ([`SurfaceDerivs::principal_curvatures`]) need no unit vectors.

use super::Patch;
use super::eval::SurfaceDerivs;
use crate::math::Vec3;
use crate::solve::{DEGENERATE_NORMAL_REL, UMBILIC_REL};
use crate::tol::LENGTH_EPS;

/// First (`e, f, g`) and second (`l, m, n`) fundamental forms at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FundamentalForms {
    /// `S_u . S_u`, mm^2.
    pub e: f64,
    /// `S_u . S_v`, mm^2.
    pub f: f64,
    /// `S_v . S_v`, mm^2.
    pub g: f64,
    /// `S_uu . n`, mm.
    pub l: f64,
    /// `S_uv . n`, mm.
    pub m: f64,
    /// `S_vv . n`, mm.
    pub n: f64,
}

/// Principal curvatures and directions at a point (sign convention of the module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// Larger principal curvature, 1/mm.
    pub k1: f64,
    /// Smaller principal curvature, 1/mm.
    pub k2: f64,
    /// Unit 3D tangent along which the normal curvature is `k1`.
    pub dir1: Vec3,
    /// Unit 3D tangent along which the normal curvature is `k2` (orthogonal to `dir1`).
    pub dir2: Vec3,
    /// Gaussian curvature `k1 k2`, 1/mm^2.
    pub gaussian: f64,
    /// Mean curvature `(k1 + k2) / 2`, 1/mm.
    pub mean: f64,
}

impl SurfaceDerivs {
    /// Unit normal along `du x dv`; `None` where the parametrisation is degenerate (a
    /// collapsed edge, parallel partials) or not finite.
    pub fn normal(&self) -> Option<Vec3> {
        let (c, len) = self.cross_len()?;
        Some(c / len)
    }

    /// `S_u x S_v` and its length where the parametrisation is regular (see
    /// [`SurfaceDerivs::normal`]).
    #[inline]
    fn cross_len(&self) -> Option<(Vec3, f64)> {
        let c = self.du.cross(&self.dv);
        let scale = self.du.norm_squared() + self.dv.norm_squared();
        let len = c.norm();
        (len.is_finite() && len > DEGENERATE_NORMAL_REL * scale && len > 0.0).then_some((c, len))
    }

    /// First and second fundamental forms. Where [`SurfaceDerivs::normal`] is `None`
    /// the second form is undefined and `l = m = n = 0`.
    pub fn fundamental_forms(&self) -> FundamentalForms {
        let n = self.normal().unwrap_or_else(Vec3::zeros);
        FundamentalForms {
            e: self.du.norm_squared(),
            f: self.du.dot(&self.dv),
            g: self.dv.norm_squared(),
            l: self.duu.dot(&n),
            m: self.duv.dot(&n),
            n: self.dvv.dot(&n),
        }
    }

    /// Normal curvature along the 3D direction `tangent`, first projected onto the
    /// tangent plane. `None` at a degenerate point or when `tangent` is (nearly) normal.
    ///
    /// # Units
    /// 1/mm, positive when the surface bends toward [`SurfaceDerivs::normal`].
    pub fn normal_curvature(&self, tangent: &Vec3) -> Option<f64> {
        let frame = self.frame()?;
        let t = frame.normal.cross(&tangent.cross(&frame.normal));
        let t = t.try_normalize(LENGTH_EPS * tangent.norm().max(1.0))?;
        let (x, y) = (t.dot(&frame.e1), t.dot(&frame.e2));
        let w = frame.w;
        Some(w[0] * x * x + 2.0 * w[1] * x * y + w[2] * y * y)
    }

    /// Principal curvatures and directions; `None` at a degenerate point.
    ///
    /// # Units
    /// 1/mm (sign convention of the module doc).
    pub fn curvature(&self) -> Option<Curvature> {
        let frame = self.frame()?;
        let p = Principal::of(frame.w);
        let [w11, w12, w22] = frame.w;
        let umbilic = 2.0 * p.half_gap <= UMBILIC_REL * p.k1.abs().max(p.k2.abs());
        let theta = if umbilic {
            0.0
        } else {
            0.5 * (2.0 * w12).atan2(w11 - w22)
        };
        let (s, c) = theta.sin_cos();
        Some(Curvature {
            k1: p.k1,
            k2: p.k2,
            dir1: frame.e1 * c + frame.e2 * s,
            dir2: frame.e2 * c - frame.e1 * s,
            gaussian: p.k1 * p.k2,
            mean: p.mean,
        })
    }

    /// The principal curvatures `[k1, k2]` alone, bit for bit those of
    /// [`SurfaceDerivs::curvature`] at a third of its cost (no directions, no unit
    /// vectors); `None` at a degenerate point.
    ///
    /// # Units
    /// 1/mm (sign convention of the module doc).
    pub fn principal_curvatures(&self) -> Option<[f64; 2]> {
        let (cross, len) = self.cross_len()?;
        let p = Principal::of(self.shape_operator(&cross, len));
        Some([p.k1, p.k2])
    }

    /// The shape operator `[W11, W12, W22]` in the frame `e1, e2` from scalar products
    /// (module doc), given `S_u x S_v` and its length.
    #[inline]
    fn shape_operator(&self, cross: &Vec3, len: f64) -> [f64; 3] {
        let (e, f) = (self.du.norm_squared(), self.du.dot(&self.dv));
        let il = 1.0 / len;
        let (l, m, n) = (
            self.duu.dot(cross) * il,
            self.duv.dot(cross) * il,
            self.dvv.dot(cross) * il,
        );
        let ie = 1.0 / e;
        [
            l * ie,
            (m * e - l * f) * ie * il,
            (l * f * f - 2.0 * m * f * e + n * e * e) * ie * il * il,
        ]
    }

    /// Orthonormal tangent frame and the shape operator in it (module doc).
    fn frame(&self) -> Option<Frame> {
        let (cross, len) = self.cross_len()?;
        let normal = cross / len;
        let e1 = self.du / self.du.norm();
        Some(Frame {
            normal,
            e1,
            e2: normal.cross(&e1),
            w: self.shape_operator(&cross, len),
        })
    }
}

/// `e1, e2, n` and the shape operator `[W11, W12, W22]` in `(e1, e2)`.
struct Frame {
    normal: Vec3,
    e1: Vec3,
    e2: Vec3,
    w: [f64; 3],
}

/// The eigenvalues `k1 >= k2` of a shape operator, with their mean and half gap.
struct Principal {
    k1: f64,
    k2: f64,
    mean: f64,
    half_gap: f64,
}

impl Principal {
    #[inline]
    fn of([w11, w12, w22]: [f64; 3]) -> Principal {
        let mean = 0.5 * (w11 + w22);
        let half_gap = (0.25 * (w11 - w22).powi(2) + w12 * w12).sqrt();
        Principal {
            k1: mean + half_gap,
            k2: mean - half_gap,
            mean,
            half_gap,
        }
    }
}

impl Patch {
    /// Principal curvatures at `(u, v)` (clamped into the domain); `None` where the
    /// patch is degenerate.
    ///
    /// # Units
    /// 1/mm, positive when the surface bends toward its normal `du x dv`.
    pub fn curvature_at(&self, u: f64, v: f64) -> Option<Curvature> {
        self.derivs(u, v).curvature()
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{die, quarter_cylinder, shared_patches, sphere_octant, wave};
    use super::*;
    use crate::math::Point3;
    use proptest::prelude::*;

    fn close(a: f64, b: f64, eps: f64) -> bool {
        (a - b).abs() <= eps
    }

    #[test]
    fn cylinder_principal_curvatures() {
        let r = 5.0;
        let p = quarter_cylinder(r, 7.0);
        for (u, v) in [(0.0, 0.0), (0.13, 0.5), (0.5, 0.9), (0.77, 0.3), (1.0, 1.0)] {
            let d = p.derivs(u, v);
            let n = d.normal().unwrap();
            let radial = Vec3::new(d.point.x, d.point.y, 0.0) / r;
            assert!((n - radial).norm() < 1e-12, "outward normal");
            let c = d.curvature().unwrap();
            assert!(
                close(c.k1, 0.0, 1e-9) && close(c.k2, -1.0 / r, 1e-9),
                "{c:?}"
            );
            assert!(c.dir1.cross(&Vec3::z()).norm() < 1e-9, "k1 along the axis");
            assert!(close(c.gaussian, 0.0, 1e-9) && close(c.mean, -0.5 / r, 1e-9));
        }
    }

    #[test]
    fn sphere_curvature_sign_follows_the_normal() {
        let r = 3.0;
        let p = sphere_octant(r);
        let c = p.curvature_at(0.3, 0.6).unwrap();
        assert!(
            close(c.k1, 1.0 / r, 1e-9) && close(c.k2, 1.0 / r, 1e-9),
            "{c:?}"
        );
        let d = p.derivs(0.3, 0.6);
        assert!(d.normal().unwrap().dot(&d.point.coords) < 0.0, "inward");
        assert!(
            c.dir1.dot(&d.du.normalize()) > 1.0 - 1e-12,
            "umbilic: du-aligned"
        );
        let flipped = SurfaceDerivs {
            du: d.dv,
            dv: d.du,
            duu: d.dvv,
            dvv: d.duu,
            ..d
        };
        let c = flipped.curvature().unwrap();
        assert!(
            close(c.k1, -1.0 / r, 1e-9) && close(c.k2, -1.0 / r, 1e-9),
            "{c:?}"
        );
        assert!(close(c.gaussian, 1.0 / (r * r), 1e-9));
    }

    #[test]
    fn pole_and_collapsed_points_have_no_normal() {
        let d = sphere_octant(2.0).derivs(1.0, 0.4);
        assert!(d.normal().is_none());
        assert!(d.curvature().is_none());
        assert!(d.principal_curvatures().is_none());
        assert!(d.normal_curvature(&Vec3::x()).is_none());
        assert_eq!(d.fundamental_forms().l, 0.0);
    }

    #[test]
    fn fundamental_forms_of_die_by_hand() {
        let d = die().derivs(0.4, 0.7);
        let ff = d.fundamental_forms();
        let n = d.du.cross(&d.dv).normalize();
        assert!(close(ff.e, d.du.dot(&d.du), 1e-12) && close(ff.f, d.du.dot(&d.dv), 1e-12));
        assert!(close(ff.l, d.duu.dot(&n), 1e-12) && close(ff.n, d.dvv.dot(&n), 1e-12));
        let c = d.curvature().unwrap();
        let k = (ff.l * ff.n - ff.m * ff.m) / (ff.e * ff.g - ff.f * ff.f);
        let h =
            (ff.e * ff.n + ff.g * ff.l - 2.0 * ff.f * ff.m) / (2.0 * (ff.e * ff.g - ff.f * ff.f));
        assert!(
            close(c.gaussian, k, 1e-12) && close(c.mean, h, 1e-12),
            "{c:?} {k} {h}"
        );
    }

    /// Curvature of the planar normal section through `d.point` along `t`, by fitting a
    /// circle through three surface points found by bisection on the section plane.
    fn section_curvature(p: &Patch, u: f64, v: f64, t: &Vec3) -> f64 {
        let d = p.derivs(u, v);
        let n = d.normal().unwrap();
        let t = (t - n * n.dot(t)).normalize();
        let side = n.cross(&t);
        let h = 1e-3;
        let on_section = |s: f64| -> Point3 {
            let (a, b) = solve_tangent(&d, &(t * s));
            let (mut u1, mut v1) = (u + a, v + b);
            for _ in 0..20 {
                let q = p.derivs(u1, v1);
                let off = (q.point - d.point).dot(&side);
                let along = (q.point - d.point).dot(&t) - s;
                let (da, db) = solve_tangent(&q, &(-(side * off) - t * along));
                u1 += da;
                v1 += db;
            }
            p.eval(u1, v1)
        };
        let (a, b) = (on_section(-h), on_section(h));
        let height = |q: Point3| (q - d.point).dot(&n);
        (height(a) + height(b)) / (h * h)
    }

    /// `(a, b)` with `a du + b dv` the tangent-plane part of `w`.
    fn solve_tangent(d: &SurfaceDerivs, w: &Vec3) -> (f64, f64) {
        let (e, f, g) = (d.du.dot(&d.du), d.du.dot(&d.dv), d.dv.dot(&d.dv));
        let (x, y) = (d.du.dot(w), d.dv.dot(w));
        let det = e * g - f * f;
        ((g * x - f * y) / det, (e * y - f * x) / det)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn sphere_curvature_everywhere(u in 0.0..0.95f64, v in 0.0..1.0f64, r in 0.5..50.0f64) {
            let c = sphere_octant(r).curvature_at(u, v).unwrap();
            prop_assert!(close(c.k1, 1.0 / r, 1e-9) && close(c.k2, 1.0 / r, 1e-9));
            prop_assert!(c.dir1.dot(&c.dir2).abs() < 1e-12);
        }

        #[test]
        fn principal_directions_extremise_normal_curvature(
            which in 0usize..6, u in 0.02..0.98f64, v in 0.02..0.98f64, angle in 0.0..6.3f64,
        ) {
            let p = &shared_patches()[which].1;
            let d = p.derivs(u, v);
            let c = d.curvature().unwrap();
            prop_assert_eq!(d.principal_curvatures(), Some([c.k1, c.k2]));
            let n = d.normal().unwrap();
            prop_assert!((c.dir1.norm() - 1.0).abs() < 1e-12 && c.dir1.dot(&n).abs() < 1e-12);
            prop_assert!(c.dir1.dot(&c.dir2).abs() < 1e-12 && c.dir2.dot(&n).abs() < 1e-12);
            let k1 = d.normal_curvature(&c.dir1).unwrap();
            let k2 = d.normal_curvature(&c.dir2).unwrap();
            prop_assert!(close(k1, c.k1, 1e-12) && close(k2, c.k2, 1e-12));
            let t = c.dir1 * angle.cos() + c.dir2 * angle.sin();
            let euler = c.k1 * angle.cos().powi(2) + c.k2 * angle.sin().powi(2);
            let kt = d.normal_curvature(&(t + n * 3.0)).unwrap();
            prop_assert!(close(kt, euler, 1e-12), "Euler's formula {kt} vs {euler}");
        }

        #[test]
        fn normal_curvature_matches_a_normal_section(
            u in 0.1..0.9f64, v in 0.1..0.9f64, angle in 0.0..3.2f64,
        ) {
            let p = wave();
            let d = p.derivs(u, v);
            let t = d.du.normalize() * angle.cos() + d.dv.normalize() * angle.sin();
            let want = section_curvature(&p, u, v, &t);
            let got = d.normal_curvature(&t).unwrap();
            prop_assert!(close(got, want, 1e-5), "{got} vs section {want}");
        }
    }
}
