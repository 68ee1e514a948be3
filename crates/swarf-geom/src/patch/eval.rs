//! Point and exact first and second partial derivatives of a patch.
//!
//! Tensor-product de Boor sum: `S(u, v) = sum_i sum_j N_i(u) M_j(v) P_ij` over the
//! `(p+1) x (q+1)` functions non-zero on the spans holding `(u, v)`; a partial derivative
//! replaces `N` or `M` by its derivative ([`super::basis`]). The sum runs row by row:
//! each row is first contracted along v with `M, M', M''`, then folded into the six
//! results with `N, N', N''`, so a bicubic costs 16 x 3 + 4 x 6 vector multiply-adds.
//! The common degree pairs are compiled with the degrees as constants, so that the short
//! loops unroll.
//!
//! On a grid of parameters ([`Patch::derivs_on_grid`]) the row contractions depend on
//! v alone: they run once per v over every row of the net, and each u then costs only
//! the fold, `6 (p + 1)` multiply-adds (24 for a bicubic instead of 72 plus two basis
//! evaluations); the basis functions are computed once per u and once per v. The
//! contraction and the fold are the same functions as for one point, applied in the
//! same order, so a grid value is bit for bit `Patch::derivs` there.
//!
//! A NURBS patch is the projection of a polynomial patch in homogeneous space,
//! `A(u, v) = sum N M w_ij P_ij`, `w(u, v) = sum N M w_ij`, `S = A / w`. Differentiating
//! `A = w S` (The NURBS Book eq. 4.20, the idea of A4.4) gives
//!
//! - `S_u = (A_u - w_u S) / w`, `S_v = (A_v - w_v S) / w`,
//! - `S_uu = (A_uu - 2 w_u S_u - w_uu S) / w`, `S_vv = (A_vv - 2 w_v S_v - w_vv S) / w`,
//! - `S_uv = (A_uv - w_u S_v - w_v S_u - w_uv S) / w`.
//!
//! Everything lives on the stack. The curvo crate evaluates rational derivatives of any
//! order into heap-allocated tables on each call; this kernel's hot loops (projection,
//! drop-cutter onto patches, curvature surveys) need exactly orders 0..2 many million
//! times, so it has its own small evaluator.

use super::Patch;
use super::basis::{BasisDerivs, MAX_ORDER, basis_derivs_n, basis_funs_n, find_span};
use crate::math::{Point3, Vec3};
use nalgebra::{SVector, Vector4};

/// A surface point with its exact first and second partial derivatives, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceDerivs {
    /// `S(u, v)`.
    pub point: Point3,
    /// `dS/du`.
    pub du: Vec3,
    /// `dS/dv`.
    pub dv: Vec3,
    /// `d2S/du2`.
    pub duu: Vec3,
    /// `d2S/dudv`.
    pub duv: Vec3,
    /// `d2S/dv2`.
    pub dvv: Vec3,
}

impl Patch {
    /// `(u, v)` clamped into the patch's domain (NaN stays NaN).
    pub fn clamp_params(&self, u: f64, v: f64) -> (f64, f64) {
        let [[u0, u1], [v0, v1]] = self.domain();
        (u.clamp(u0, u1), v.clamp(v0, v1))
    }

    /// The surface point at `(u, v)`; parameters outside the domain are clamped into it.
    ///
    /// # Units
    /// mm.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3};
    /// let p = Patch::bezier([1, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 2.0, 0.0),
    ///     Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 2.0, 4.0),
    /// ]).unwrap();
    /// assert_eq!(p.eval(0.5, 0.5), Point3::new(1.0, 1.0, 1.0));
    /// ```
    pub fn eval(&self, u: f64, v: f64) -> Point3 {
        match self.degree {
            [3, 3] => self.eval_of::<4, 4>(u, v),
            [2, 2] => self.eval_of::<3, 3>(u, v),
            [1, 1] => self.eval_of::<2, 2>(u, v),
            [2, 1] => self.eval_of::<3, 2>(u, v),
            [1, 2] => self.eval_of::<2, 3>(u, v),
            _ => self.eval_of::<MAX_ORDER, MAX_ORDER>(u, v),
        }
    }

    /// The degrees `[u, v]` for `OU`, `OV` basis functions per direction (read from
    /// the patch when the order is [`MAX_ORDER`]).
    #[inline(always)]
    fn degrees_of<const OU: usize, const OV: usize>(&self) -> [usize; 2] {
        [
            if OU < MAX_ORDER {
                OU - 1
            } else {
                self.degree[0]
            },
            if OV < MAX_ORDER {
                OV - 1
            } else {
                self.degree[1]
            },
        ]
    }

    /// [`Patch::eval`] with `OU`, `OV` basis functions per direction: the orders
    /// (degree + 1) as compile-time constants, or [`MAX_ORDER`] to read the degrees.
    #[inline(always)]
    fn eval_of<const OU: usize, const OV: usize>(&self, u: f64, v: f64) -> Point3 {
        let (u, v) = self.clamp_params(u, v);
        let [pu, pv] = self.degrees_of::<OU, OV>();
        let su = find_span(&self.knots[0], pu, u);
        let sv = find_span(&self.knots[1], pv, v);
        let nu = basis_funs_n::<OU>(&self.knots[0], pu, su, u);
        let nv = basis_funs_n::<OV>(&self.knots[1], pv, sv, v);
        let first = (su - pu) * self.count[1] + sv - pv;
        let nv_count = self.count[1];
        match &self.weights {
            None => Point3::from(sum_values(
                [pu, pv],
                nv_count,
                &nu,
                &nv,
                first,
                &self.points,
                None,
                |p, _| p.coords,
            )),
            Some(w) => {
                let a = sum_values(
                    [pu, pv],
                    nv_count,
                    &nu,
                    &nv,
                    first,
                    &self.points,
                    Some(w),
                    homogeneous,
                );
                let inv = 1.0 / a.w;
                Point3::new(a.x * inv, a.y * inv, a.z * inv)
            }
        }
    }

    /// The point and its exact first and second partial derivatives at `(u, v)`;
    /// parameters outside the domain are clamped into it. No allocation.
    ///
    /// # Units
    /// mm (per unit parameter for the derivatives).
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        match self.degree {
            [3, 3] => self.derivs_of::<4, 4>(u, v),
            [2, 2] => self.derivs_of::<3, 3>(u, v),
            [1, 1] => self.derivs_of::<2, 2>(u, v),
            [2, 1] => self.derivs_of::<3, 2>(u, v),
            [1, 2] => self.derivs_of::<2, 3>(u, v),
            _ => self.derivs_of::<MAX_ORDER, MAX_ORDER>(u, v),
        }
    }

    /// [`Patch::derivs`] with the orders as in [`Patch::eval_of`].
    #[inline(always)]
    fn derivs_of<const OU: usize, const OV: usize>(&self, u: f64, v: f64) -> SurfaceDerivs {
        let (u, v) = self.clamp_params(u, v);
        let [pu, pv] = self.degrees_of::<OU, OV>();
        let bu = basis_derivs_n::<OU>(&self.knots[0], pu, u);
        let bv = basis_derivs_n::<OV>(&self.knots[1], pv, v);
        let nv = self.count[1];
        match &self.weights {
            None => polynomial(&sum_derivs(
                [pu, pv],
                nv,
                &bu,
                &bv,
                &self.points,
                None,
                lift3,
            )),
            Some(w) => {
                let a = sum_derivs([pu, pv], nv, &bu, &bv, &self.points, Some(w), homogeneous);
                rational_quotient(&a)
            }
        }
    }

    /// [`Patch::derivs`] at every `(us[i], vs[j])`, handed over one v at a time:
    /// `f(j, column)` with `column[i]` at `(us[i], vs[j])`. The values are bit for bit
    /// those of `derivs` (module doc), at about a fifth of the cost per point.
    /// Parameters are clamped into the domain.
    ///
    /// # Units
    /// mm (per unit parameter for the derivatives).
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3};
    /// let p = Patch::bezier([2, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0),
    ///     Point3::new(1.0, 0.0, 2.0), Point3::new(1.0, 1.0, 2.0),
    ///     Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 1.0, 0.0),
    /// ]).unwrap();
    /// let (us, vs) = ([0.0, 0.3, 1.0], [0.25, 0.5]);
    /// p.derivs_on_grid(&us, &vs, |j, column| {
    ///     for (i, d) in column.iter().enumerate() {
    ///         assert_eq!(*d, p.derivs(us[i], vs[j]));
    ///     }
    /// });
    /// ```
    pub fn derivs_on_grid(
        &self,
        us: &[f64],
        vs: &[f64],
        mut f: impl FnMut(usize, &[SurfaceDerivs]),
    ) {
        match self.degree {
            [3, 3] => self.grid_of::<4, 4>(us, vs, &mut f),
            [2, 2] => self.grid_of::<3, 3>(us, vs, &mut f),
            [1, 1] => self.grid_of::<2, 2>(us, vs, &mut f),
            [2, 1] => self.grid_of::<3, 2>(us, vs, &mut f),
            [1, 2] => self.grid_of::<2, 3>(us, vs, &mut f),
            _ => self.grid_of::<MAX_ORDER, MAX_ORDER>(us, vs, &mut f),
        }
    }

    /// [`Patch::derivs_on_grid`] with the orders as in [`Patch::eval_of`].
    fn grid_of<const OU: usize, const OV: usize>(
        &self,
        us: &[f64],
        vs: &[f64],
        f: &mut impl FnMut(usize, &[SurfaceDerivs]),
    ) {
        let [pu, _] = self.degrees_of::<OU, OV>();
        let bus: Vec<BasisDerivs<OU>> = us
            .iter()
            .map(|&u| {
                let (u, _) = self.clamp_params(u, 0.0);
                basis_derivs_n::<OU>(&self.knots[0], pu, u)
            })
            .collect();
        match &self.weights {
            None => self.grid_with::<3, OU, OV>(&bus, vs, None, lift3, polynomial, f),
            Some(w) => {
                self.grid_with::<4, OU, OV>(&bus, vs, Some(w), homogeneous, rational_quotient, f);
            }
        }
    }

    /// The loop of [`Patch::grid_of`] on the lifted net: per v the contraction of every
    /// row, then per u (basis `bus`) the fold.
    #[inline(always)]
    fn grid_with<const D: usize, const OU: usize, const OV: usize>(
        &self,
        bus: &[BasisDerivs<OU>],
        vs: &[f64],
        weights: Option<&[f64]>,
        lift: impl Fn(&Point3, f64) -> SVector<f64, D>,
        finish: impl Fn(&[SVector<f64, D>; 6]) -> SurfaceDerivs,
        f: &mut impl FnMut(usize, &[SurfaceDerivs]),
    ) {
        let [pu, pv] = self.degrees_of::<OU, OV>();
        let [nu, nv] = self.count;
        let mut rows = vec![[SVector::<f64, D>::zeros(); 3]; nu];
        let mut column = Vec::with_capacity(bus.len());
        for (j, &v) in vs.iter().enumerate() {
            let (_, v) = self.clamp_params(0.0, v);
            let bv = basis_derivs_n::<OV>(&self.knots[1], pv, v);
            for (a, r) in rows.iter_mut().enumerate() {
                let row = net_row(&self.points, weights, a * nv + bv.span - pv, pv + 1);
                *r = contract_row(row, &bv, &lift);
            }
            column.clear();
            column.extend(bus.iter().map(|bu| {
                let mut out = [SVector::<f64, D>::zeros(); 6];
                for a in 0..pu + 1 {
                    fold_row(&mut out, &rows[bu.span - pu + a], bu, a);
                }
                finish(&out)
            }));
            f(j, &column);
        }
    }
}

/// Weights of a polynomial row.
const ONES: [f64; MAX_ORDER] = [1.0; MAX_ORDER];

/// The control points `first + a nv .. + p_v` of row `a` with their weights (1 when
/// polynomial): one bounds check per row.
#[inline(always)]
fn net_row<'a>(
    points: &'a [Point3],
    weights: Option<&'a [f64]>,
    start: usize,
    len: usize,
) -> impl Iterator<Item = (&'a Point3, &'a f64)> {
    let w = weights.map_or(&ONES[..len], |w| &w[start..start + len]);
    points[start..start + len].iter().zip(w)
}

/// `sum N_a M_b lift(P_ab, w_ab)` over the non-zero functions of degrees `deg`, on a net
/// `nv` points wide, `first` = index of the first point.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn sum_values<const D: usize, const OU: usize, const OV: usize>(
    deg: [usize; 2],
    nv: usize,
    nu_funs: &[f64; OU],
    nv_funs: &[f64; OV],
    first: usize,
    points: &[Point3],
    weights: Option<&[f64]>,
    lift: impl Fn(&Point3, f64) -> SVector<f64, D>,
) -> SVector<f64, D> {
    let mut out = SVector::<f64, D>::zeros();
    for (a, na) in nu_funs[..deg[0] + 1].iter().enumerate() {
        let mut s = SVector::<f64, D>::zeros();
        let row = net_row(points, weights, first + a * nv, deg[1] + 1);
        for ((c, w), nb) in row.zip(nv_funs) {
            s += lift(c, *w) * *nb;
        }
        out += s * *na;
    }
    out
}

/// `[X, X_u, X_v, X_uu, X_uv, X_vv]` of the tensor sum of `lift(P_ab, w_ab)`.
#[inline(always)]
fn sum_derivs<const D: usize, const OU: usize, const OV: usize>(
    deg: [usize; 2],
    nv: usize,
    bu: &BasisDerivs<OU>,
    bv: &BasisDerivs<OV>,
    points: &[Point3],
    weights: Option<&[f64]>,
    lift: impl Fn(&Point3, f64) -> SVector<f64, D>,
) -> [SVector<f64, D>; 6] {
    let [pu, pv] = deg;
    let first = (bu.span - pu) * nv + bv.span - pv;
    let mut out = [SVector::<f64, D>::zeros(); 6];
    for a in 0..pu + 1 {
        let row = net_row(points, weights, first + a * nv, pv + 1);
        fold_row(&mut out, &contract_row(row, bv, &lift), bu, a);
    }
    out
}

/// `[X, X_v, X_vv]` of one row of the net: `sum_b M_b lift(P_b, w_b)` and the same
/// with `M'` and `M''`.
#[inline(always)]
fn contract_row<'a, const D: usize, const OV: usize>(
    row: impl Iterator<Item = (&'a Point3, &'a f64)>,
    bv: &BasisDerivs<OV>,
    lift: impl Fn(&Point3, f64) -> SVector<f64, D>,
) -> [SVector<f64, D>; 3] {
    let mut s = [SVector::<f64, D>::zeros(); 3];
    for (b, (c, w)) in row.enumerate() {
        let c = lift(c, *w);
        s[0] += c * bv.d[0][b];
        s[1] += c * bv.d[1][b];
        s[2] += c * bv.d[2][b];
    }
    s
}

/// Adds row `a`'s contraction `s` into `out = [X, X_u, X_v, X_uu, X_uv, X_vv]` with
/// `N_a, N'_a, N''_a`.
#[inline(always)]
fn fold_row<const D: usize, const OU: usize>(
    out: &mut [SVector<f64, D>; 6],
    s: &[SVector<f64, D>; 3],
    bu: &BasisDerivs<OU>,
    a: usize,
) {
    let (n0, n1, n2) = (bu.d[0][a], bu.d[1][a], bu.d[2][a]);
    out[0] += s[0] * n0;
    out[1] += s[0] * n1;
    out[2] += s[1] * n0;
    out[3] += s[0] * n2;
    out[4] += s[1] * n1;
    out[5] += s[2] * n0;
}

/// A polynomial patch's control point as it is summed.
#[inline(always)]
fn lift3(p: &Point3, _w: f64) -> Vec3 {
    p.coords
}

/// The derivatives of a polynomial patch from `[S, S_u, S_v, S_uu, S_uv, S_vv]`.
#[inline(always)]
fn polynomial(s: &[Vec3; 6]) -> SurfaceDerivs {
    SurfaceDerivs {
        point: Point3::from(s[0]),
        du: s[1],
        dv: s[2],
        duu: s[3],
        duv: s[4],
        dvv: s[5],
    }
}

/// `(w x, w y, w z, w)`.
#[inline(always)]
fn homogeneous(p: &Point3, w: f64) -> Vector4<f64> {
    Vector4::new(p.x * w, p.y * w, p.z * w, w)
}

/// The quotient rule of the module doc on homogeneous derivatives `[A, A_u, A_v, ...]`.
#[inline(always)]
fn rational_quotient(a: &[Vector4<f64>; 6]) -> SurfaceDerivs {
    let xyz = |h: &Vector4<f64>| Vec3::new(h.x, h.y, h.z);
    let inv = 1.0 / a[0].w;
    let (wu, wv, wuu, wuv, wvv) = (a[1].w, a[2].w, a[3].w, a[4].w, a[5].w);
    let s = xyz(&a[0]) * inv;
    let su = (xyz(&a[1]) - s * wu) * inv;
    let sv = (xyz(&a[2]) - s * wv) * inv;
    let suu = (xyz(&a[3]) - su * (2.0 * wu) - s * wuu) * inv;
    let suv = (xyz(&a[4]) - sv * wu - su * wv - s * wuv) * inv;
    let svv = (xyz(&a[5]) - sv * (2.0 * wv) - s * wvv) * inv;
    SurfaceDerivs {
        point: Point3::from(s),
        du: su,
        dv: sv,
        duu: suu,
        duv: suv,
        dvv: svv,
    }
}

#[cfg(test)]
mod tests;
