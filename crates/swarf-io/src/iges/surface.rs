//! Surfaces: entity 128 (rational B-spline surface, IGES 5.3 sec. 4.24) as a swarf
//! [`Patch`] in mm, and the bilinear patch standing for a 108 plane (module doc of
//! [`super`]).

use super::{Iges, Params, Problem};
use crate::clamp::clamp;
use swarf_geom::{Patch, Point3, Vec3};

/// A declared parameter range within this fraction of the knot domain is the
/// whole domain.
const RANGE_EPS: f64 = 1e-9;
/// Margin around a plane's boundary box, as a fraction of its larger side.
const PLANE_MARGIN: f64 = 0.01;

impl Iges<'_> {
    /// The 128 at `de` in mm, knots clamped, points in swarf's order.
    ///
    /// # Errors
    /// Bad parameters, or a surface the kernel rejects (degree, knots, weights).
    pub(crate) fn nurbs_surface(&self, de: usize) -> Result<Patch, Problem> {
        let p = self.params(de, "surface")?;
        if p.ty != 128 {
            return Err(p.unsupported(format!(
                "surface type {} (expected 128, or 108 in a 144)",
                p.ty
            )));
        }
        let size = p.toks.len();
        let k = [p.count(self, 1, size)?, p.count(self, 2, size)?];
        let deg = [p.count(self, 3, size)?, p.count(self, 4, size)?];
        let n = [k[0] + 1, k[1] + 1];
        let nk = [n[0] + deg[0] + 1, n[1] + deg[1] + 1];
        let count = n[0] * n[1];
        if 4 * count > size {
            return Err(self
                .err(
                    de,
                    format!(
                        "{} x {} control points need more parameters than the entity's {size}",
                        n[0], n[1]
                    ),
                )
                .into());
        }
        let mut at = 10;
        let ku = p.reals(self, at, nk[0])?;
        at += nk[0];
        let kv = p.reals(self, at, nk[1])?;
        at += nk[1];
        let w = p.reals(self, at, count)?;
        at += count;
        let xyz = p.reals(self, at, 3 * count)?;
        let rational = p.int(self, 7)? == 0;
        let map = self.transform_of(de)?;
        let s = self.rec.mm_per_unit;
        // rows along u: row i holds (w x, w y, w z, w) of points (i, 0..n_v)
        let rows: Vec<Vec<f64>> = (0..n[0])
            .map(|i| {
                (0..n[1])
                    .flat_map(|j| {
                        let f = i + j * n[0];
                        let q =
                            map.apply(&Point3::new(xyz[3 * f], xyz[3 * f + 1], xyz[3 * f + 2])) * s;
                        let wf = if rational { w[f] } else { 1.0 };
                        [wf * q.x, wf * q.y, wf * q.z, wf]
                    })
                    .collect()
            })
            .collect();
        let bad = |e: &dyn std::fmt::Display| -> Problem {
            self.err(de, format!("rational B-spline surface: {e}"))
                .into()
        };
        knots_ok(&ku, deg[0]).map_err(|m| bad(&format!("knots_u: {m}")))?;
        knots_ok(&kv, deg[1]).map_err(|m| bad(&format!("knots_v: {m}")))?;
        if let Some(k) = w.iter().position(|x| rational && *x <= 0.0) {
            return Err(bad(&format!("weights[{k}]: expected > 0, found {}", w[k])));
        }
        let (points, weights, ku, kv) = clamped(deg, n[1], ku, kv, rows);
        Patch::new(
            deg,
            points,
            [Some(ku), Some(kv)],
            rational.then_some(weights),
        )
        .map_err(|e| bad(&e))
    }

    /// The rectangle `[U0, U1] x [V0, V1]` that the 128 at `de` declares as its
    /// surface (its last four parameters), as a loop, when it is strictly inside the
    /// patch's domain; `None` for the whole domain or values that do not make a
    /// rectangle inside it.
    pub(crate) fn declared_range(&self, de: usize, patch: &Patch) -> Option<Vec<[f64; 2]>> {
        let p = self.params(de, "surface").ok()?;
        let len = p.toks.len();
        let c = |k| p.count(self, k, len).ok();
        let (k1, k2, m1, m2) = (c(1)?, c(2)?, c(3)?, c(4)?);
        let at = 10 + (k1 + m1 + 2) + (k2 + m2 + 2) + 4 * (k1 + 1) * (k2 + 1);
        let r = p.reals(self, at, 4).ok()?;
        let dom = patch.domain();
        let mut lo = [0.0; 2];
        let mut hi = [0.0; 2];
        let mut inside = false;
        for d in 0..2 {
            let eps = RANGE_EPS * (dom[d][1] - dom[d][0]);
            lo[d] = r[2 * d].max(dom[d][0]);
            hi[d] = r[2 * d + 1].min(dom[d][1]);
            if hi[d] - lo[d] <= eps {
                return None;
            }
            inside |= lo[d] > dom[d][0] + eps || hi[d] < dom[d][1] - eps;
        }
        inside.then(|| {
            vec![
                [lo[0], lo[1]],
                [hi[0], lo[1]],
                [hi[0], hi[1]],
                [lo[0], hi[1]],
            ]
        })
    }

    /// A bilinear patch on the 108 plane at `p` covering `outline` (mm) with a margin;
    /// `(u, v)` are mm along an orthonormal frame of the plane.
    pub(crate) fn plane_patch(&self, p: &Params, outline: &[Point3]) -> Result<Patch, Problem> {
        let v = p.reals(self, 1, 4)?;
        let map = self.transform_of(p.de)?;
        let n0 = Vec3::new(v[0], v[1], v[2]);
        let len = n0.norm();
        if len == 0.0 || !len.is_finite() {
            return Err(self
                .err(p.de, "plane: expected a non-zero normal (A, B, C)")
                .into());
        }
        let origin = map.apply(&Point3::from(n0 * (v[3] / (len * len)))) * self.rec.mm_per_unit;
        let tip =
            map.apply(&Point3::from(n0 * (v[3] / (len * len)) + n0 / len)) * self.rec.mm_per_unit;
        let n = (tip - origin).normalize();
        let e1 = if n.x.abs() < 0.9 {
            Vec3::x()
        } else {
            Vec3::y()
        };
        let e1 = (e1 - n * n.dot(&e1)).normalize();
        let e2 = n.cross(&e1);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in outline {
            let d = q - origin;
            for (k, e) in [e1, e2].iter().enumerate() {
                lo[k] = lo[k].min(d.dot(e));
                hi[k] = hi[k].max(d.dot(e));
            }
        }
        let pad = PLANE_MARGIN * (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let (lo, hi) = (lo.map(|x| x - pad), hi.map(|x| x + pad));
        let at = |a: f64, b: f64| origin + e1 * a + e2 * b;
        let pts = vec![
            at(lo[0], lo[1]),
            at(lo[0], hi[1]),
            at(hi[0], lo[1]),
            at(hi[0], hi[1]),
        ];
        let knots = |k: usize| Some(vec![lo[k], lo[k], hi[k], hi[k]]);
        Patch::new([1, 1], pts, [knots(0), knots(1)], None).map_err(|e| {
            self.err(p.de, format!("plane bounded by its trimming curves: {e}"))
                .into()
        })
    }
}

/// The net clamped in u then v: points (swarf's row-major order), weights, knots.
fn clamped(
    deg: [usize; 2],
    n_v: usize,
    mut ku: Vec<f64>,
    mut kv: Vec<f64>,
    mut rows: Vec<Vec<f64>>,
) -> (Vec<Point3>, Vec<f64>, Vec<f64>, Vec<f64>) {
    clamp(deg[0], &mut ku, &mut rows);
    let nu = rows.len();
    let mut cols: Vec<Vec<f64>> = (0..n_v)
        .map(|j| {
            (0..nu)
                .flat_map(|i| rows[i][4 * j..4 * j + 4].to_vec())
                .collect()
        })
        .collect();
    clamp(deg[1], &mut kv, &mut cols);
    let mut points = Vec::with_capacity(nu * cols.len());
    let mut weights = Vec::with_capacity(nu * cols.len());
    for i in 0..nu {
        for c in &cols {
            let h = &c[4 * i..4 * i + 4];
            points.push(Point3::new(h[0] / h[3], h[1] / h[3], h[2] / h[3]));
            weights.push(h[3]);
        }
    }
    (points, weights, ku, kv)
}

/// Knots are finite, non-decreasing and leave a non-empty domain (checked before
/// clamping, which relies on it).
fn knots_ok(k: &[f64], p: usize) -> Result<(), String> {
    if k.iter().any(|x| !x.is_finite()) || k.windows(2).any(|w| w[1] < w[0]) {
        return Err("expected finite, non-decreasing knots".into());
    }
    let n = k.len() - p - 1;
    if k[n] <= k[p] {
        return Err(format!("empty domain [{}, {}]", k[p], k[n]));
    }
    Ok(())
}
