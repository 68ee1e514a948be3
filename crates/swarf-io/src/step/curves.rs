//! Points, directions, placements and the edge curves of ISO 10303-42 (`LINE`,
//! `CIRCLE`, `ELLIPSE`, `B_SPLINE_CURVE_WITH_KNOTS` simple or rational complex,
//! `TRIMMED_CURVE`, `SURFACE_CURVE`, `SEAM_CURVE`), and the sampling of an edge
//! between its vertices within a chordal tolerance.
//!
//! Conics are sampled by angle: a circle of radius `r` has sag `r (1 - cos(dt/2))`,
//! so `dt = 2 acos(1 - tol / r)`; an ellipse's sag is at most `a^3 / b^2 * dt^2 / 8`
//! (largest speed `a` times largest curvature `a / b^2`). B-splines use
//! [`NurbsCurve::polyline`]. An edge's ends are its vertices: the curve parameters
//! of the vertices are found in closed form for lines and conics, and by the closest
//! sample plus Newton steps for B-splines.

use super::graph::{Ent, Graph, nums_of};
use super::parser::Value;
use super::surfaces::SurfFail;
use crate::error::IoError;
use swarf_geom::patch::Frame;
use swarf_geom::{NurbsCurve, Point3, Vec3};

/// A curve in mm.
pub enum Curve {
    /// A straight edge between its vertices.
    Line,
    /// `frame.origin + a cos t x + b sin t y` (a circle when `a == b`).
    Conic { frame: Frame, a: f64, b: f64 },
    /// B-spline or NURBS.
    Nurbs(NurbsCurve),
}

/// Most curve indirections followed (`SURFACE_CURVE` of `TRIMMED_CURVE` of ...).
const MAX_CURVE_CHAIN: usize = 8;

/// Reading context: the graph and the length scale to mm.
pub struct Geo<'a> {
    /// The entity graph.
    pub g: &'a Graph<'a>,
    /// mm per file length unit.
    pub mm: f64,
    /// Radians per file angle unit.
    pub rad: f64,
}

impl Geo<'_> {
    /// `CARTESIAN_POINT` `#id` in mm.
    pub fn point(&self, id: u64, from: &Ent<'_>) -> Result<Point3, IoError> {
        let e = self.g.get(id, &["CARTESIAN_POINT"], from)?;
        let c = e.nums(1)?;
        match c.as_slice() {
            [x, y, z] => Ok(Point3::new(x * self.mm, y * self.mm, z * self.mm)),
            [x, y] => Ok(Point3::new(x * self.mm, y * self.mm, 0.0)),
            _ => Err(e.arg_err(1, "2 or 3 coordinates")),
        }
    }

    /// `DIRECTION` `#id`, normalised.
    pub fn direction(&self, id: u64, from: &Ent<'_>) -> Result<Vec3, IoError> {
        let e = self.g.get(id, &["DIRECTION"], from)?;
        let c = e.nums(1)?;
        let v = match c.as_slice() {
            [x, y, z] => Vec3::new(*x, *y, *z),
            [x, y] => Vec3::new(*x, *y, 0.0),
            _ => return Err(e.arg_err(1, "2 or 3 ratios")),
        };
        let n = v.norm();
        if !(n > 1e-300 && n.is_finite()) {
            return Err(e.arg_err(1, "a non-zero direction"));
        }
        Ok(v / n)
    }

    /// `AXIS2_PLACEMENT_3D` `#id` as a right-handed frame (z = axis, default +z; x =
    /// the reference direction made perpendicular, default any).
    pub fn frame(&self, id: u64, from: &Ent<'_>) -> Result<Frame, IoError> {
        let e = self.g.get(id, &["AXIS2_PLACEMENT_3D"], from)?;
        let origin = self.point(e.refr(1)?, &e)?;
        let z = match e.arg(2, "axis")? {
            Value::Ref(r) => self.direction(*r, &e)?,
            _ => Vec3::z(),
        };
        let guess = match e.arg(3, "ref_direction")? {
            Value::Ref(r) => self.direction(*r, &e)?,
            _ => {
                if z.x.abs() < 0.9 {
                    Vec3::x()
                } else {
                    Vec3::y()
                }
            }
        };
        let x = guess - z * guess.dot(&z);
        if x.norm() < 1e-12 {
            return Err(e.err("the reference direction is parallel to the axis"));
        }
        let x = x.normalize();
        Ok(Frame {
            origin,
            x,
            y: z.cross(&x),
            z,
        })
    }

    /// The 3D curve `#id` (through trimmed and surface curves).
    ///
    /// # Errors
    /// [`SurfFail::Unsupported`] for other curve types, [`SurfFail::Bad`] for
    /// malformed ones.
    pub fn curve(&self, id: u64, from: &Ent<'_>) -> Result<Curve, SurfFail> {
        let mut id = id;
        let mut from = *from;
        for _ in 0..MAX_CURVE_CHAIN {
            let parts = self.g.parts(id, Some(&from))?;
            let e = parts[0];
            let names: Vec<&str> = parts.iter().map(|p| p.name).collect();
            if names.contains(&"B_SPLINE_CURVE_WITH_KNOTS") {
                return Ok(self.bspline(&parts).map(Curve::Nurbs)?);
            }
            match e.name {
                "LINE" => return Ok(Curve::Line),
                "CIRCLE" => {
                    let r = e.num(2)? * self.mm;
                    if r <= 0.0 {
                        return Err(e.arg_err(2, "a positive radius").into());
                    }
                    let frame = self.frame(e.refr(1)?, &e)?;
                    return Ok(Curve::Conic { frame, a: r, b: r });
                }
                "ELLIPSE" => {
                    let (a, b) = (e.num(2)? * self.mm, e.num(3)? * self.mm);
                    if !(a > 0.0 && b > 0.0) {
                        return Err(e.arg_err(3, "positive semi-axes").into());
                    }
                    let frame = self.frame(e.refr(1)?, &e)?;
                    return Ok(Curve::Conic { frame, a, b });
                }
                "TRIMMED_CURVE" | "SURFACE_CURVE" | "SEAM_CURVE" => {
                    id = e.refr(1)?;
                    from = e;
                }
                other => {
                    return Err(SurfFail::Unsupported(e.err(format!(
                        "unsupported curve type {other} (supported: LINE, CIRCLE, ELLIPSE, \
                         B_SPLINE_CURVE_WITH_KNOTS, TRIMMED_CURVE, SURFACE_CURVE, SEAM_CURVE)"
                    ))));
                }
            }
        }
        Err(from.err("curve references nest too deep").into())
    }

    fn bspline(&self, parts: &[Ent<'_>]) -> Result<NurbsCurve, IoError> {
        let (degree, flat, points, weights, wk) = self.bspline_raw(parts)?;
        NurbsCurve::new(degree, flat, points, weights)
            .map_err(|e| wk.err(format!("invalid B-spline curve: {e}")))
    }

    /// A B-spline curve's degree, knots, points and weights as written (for surfaces
    /// built on a curve), and its `B_SPLINE_CURVE_WITH_KNOTS` record for messages.
    pub fn bspline_raw<'e>(&self, parts: &[Ent<'e>]) -> Result<RawCurve<'e>, IoError> {
        let by = |n: &str| parts.iter().find(|p| p.name == n).copied();
        let wk = by("B_SPLINE_CURVE_WITH_KNOTS").ok_or_else(|| parts[0].err("no knots"))?;
        // Simple: (name, degree, points, form, closed, self_int, mults, knots, spec).
        // Complex: B_SPLINE_CURVE(degree, points, ...) + WITH_KNOTS(mults, knots, spec).
        let (curve, c0, knots, k0) = match by("B_SPLINE_CURVE") {
            Some(bc) => (bc, 0, wk, 0),
            None => (wk, 1, wk, 6),
        };
        let degree = curve.int(c0)?;
        let points = curve
            .refs(c0 + 1)?
            .into_iter()
            .map(|r| self.point(r, &curve))
            .collect::<Result<Vec<_>, _>>()?;
        let mults = knots.nums(k0)?;
        let vals = knots.nums(k0 + 1)?;
        let flat = expand_knots(&mults, &vals).ok_or_else(|| {
            knots.arg_err(k0, "positive integer multiplicities, one per knot value")
        })?;
        let weights = match by("RATIONAL_B_SPLINE_CURVE") {
            Some(r) => Some(r.nums(0)?),
            None => None,
        };
        Ok((degree, flat, points, weights, wk))
    }
}

/// Degree, knots, points, weights and the knots' record of a B-spline curve.
pub type RawCurve<'e> = (usize, Vec<f64>, Vec<Point3>, Option<Vec<f64>>, Ent<'e>);

/// Knot values repeated by their multiplicities.
pub fn expand_knots(mults: &[f64], vals: &[f64]) -> Option<Vec<f64>> {
    if mults.len() != vals.len() {
        return None;
    }
    let mut out = Vec::new();
    for (m, v) in mults.iter().zip(vals) {
        if !(*m >= 1.0 && m.fract() == 0.0 && *m < 64.0) {
            return None;
        }
        out.extend(std::iter::repeat_n(*v, *m as usize));
    }
    Some(out)
}

/// A list of lists of numbers (weights of a rational surface).
pub fn nested_nums(e: &Ent<'_>, i: usize) -> Result<Vec<Vec<f64>>, IoError> {
    e.list(i)?
        .iter()
        .map(|row| match row {
            Value::List(l) => nums_of(l).ok_or_else(|| e.arg_err(i, "lists of numbers")),
            _ => Err(e.arg_err(i, "a list of lists")),
        })
        .collect()
}

/// Angle of `p` on a conic of `frame` with semi-axes `a`, `b`.
fn conic_param(frame: &Frame, a: f64, b: f64, p: &Point3) -> f64 {
    let l = frame.to_local(p);
    (l[1] / b).atan2(l[0] / a)
}

fn conic_at(frame: &Frame, a: f64, b: f64, t: f64) -> Point3 {
    frame.to_world(a * t.cos(), b * t.sin(), 0.0)
}

/// Parameter of the point of `c` closest to `p`: nearest sample, then Newton steps
/// on `(C(t) - p) . C'(t)` with a central-difference derivative.
fn nurbs_param(c: &NurbsCurve, p: &Point3, samples: &[(f64, Point3)]) -> f64 {
    let mut t = samples
        .iter()
        .min_by(|a, b| (a.1 - p).norm().total_cmp(&(b.1 - p).norm()))
        .map_or(c.domain()[0], |s| s.0);
    let [t0, t1] = c.domain();
    let h = (t1 - t0) * 1e-6;
    for _ in 0..20 {
        let (a, b) = ((t - h).max(t0), (t + h).min(t1));
        let d1 = (c.eval(b) - c.eval(a)) / (b - a);
        let f = (c.eval(t) - p).dot(&d1);
        let df = d1.norm_squared();
        if df <= 0.0 {
            break;
        }
        let nt = (t - f / df).clamp(t0, t1);
        if (nt - t).abs() < 1e-15 * (1.0 + t.abs()) {
            t = nt;
            break;
        }
        t = nt;
    }
    t
}

/// Samples of the edge on `curve` from vertex `a` to vertex `b` within chord `tol`:
/// the curve is followed in its own direction when `same_sense`, from `b` back to
/// `a` otherwise, and the result runs from `a` to `b` with the vertices exact.
///
/// # Errors
/// A curve that cannot be sampled (message only; the caller names the entity).
pub fn sample_edge(
    curve: &Curve,
    a: Point3,
    b: Point3,
    same_sense: bool,
    tol: f64,
) -> Result<Vec<Point3>, String> {
    let (s, e) = if same_sense { (a, b) } else { (b, a) };
    let closed = (a - b).norm() <= tol;
    let mut pts = match curve {
        Curve::Line => vec![s, e],
        Curve::Conic {
            frame,
            a: ra,
            b: rb,
        } => {
            let t0 = conic_param(frame, *ra, *rb, &s);
            let mut t1 = conic_param(frame, *ra, *rb, &e);
            while t1 <= t0 + if closed { 1e-9 } else { 0.0 } {
                t1 += std::f64::consts::TAU;
            }
            let (big, small) = (ra.max(*rb), ra.min(*rb));
            let dt = if ra == rb {
                2.0 * (1.0 - (tol / big).min(1.0)).acos()
            } else {
                (8.0 * tol * small * small / (big * big * big)).sqrt()
            };
            let n = (((t1 - t0) / dt.max(1e-6)).ceil() as usize)
                .max(((t1 - t0) / (std::f64::consts::PI / 8.0)).ceil() as usize)
                .max(1);
            if n > swarf_geom::curve::MAX_POLYLINE_POINTS {
                return Err(format!("more than {n} samples for the chord {tol} mm"));
            }
            (0..=n)
                .map(|k| conic_at(frame, *ra, *rb, t0 + (t1 - t0) * k as f64 / n as f64))
                .collect()
        }
        Curve::Nurbs(c) => {
            let [d0, d1] = c.domain();
            let coarse = c
                .polyline(d0, d1, (tol * 100.0).max(1e-3))
                .map_err(|e| e.to_string())?;
            let t0 = nurbs_param(c, &s, &coarse);
            let mut t1 = nurbs_param(c, &e, &coarse);
            if closed || t1 <= t0 {
                if closed && (t1 - d0).abs() < (t1 - d1).abs() {
                    t1 = d1;
                }
                if t1 <= t0 {
                    return Err(format!(
                        "the end vertex lies before the start vertex on the curve (t {t1} <= {t0})"
                    ));
                }
            }
            c.polyline(t0, t1, tol)
                .map_err(|e| e.to_string())?
                .into_iter()
                .map(|x| x.1)
                .collect()
        }
    };
    let n = pts.len();
    pts[0] = s;
    pts[n - 1] = e;
    if !same_sense {
        pts.reverse();
    }
    Ok(pts)
}
