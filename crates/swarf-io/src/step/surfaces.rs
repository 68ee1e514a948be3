//! Face surfaces: `B_SPLINE_SURFACE_WITH_KNOTS` (simple, or the rational complex
//! instance `(BOUNDED_SURFACE() B_SPLINE_SURFACE(..) B_SPLINE_SURFACE_WITH_KNOTS(..)
//! .. RATIONAL_B_SPLINE_SURFACE(..) ..)` that OpenCASCADE writes) read as they are,
//! `SURFACE_OF_LINEAR_EXTRUSION` of a B-spline curve (exact: degree 1 along the
//! vector), and the elementary surfaces (ISO 10303-42 `plane`, `cylindrical_surface`,
//! `conical_surface`, `spherical_surface`, `toroidal_surface`) kept as closed forms
//! (unclamped B-spline knots are clamped, [`super::clamp`])
//! until the face's edges size them ([`super::uv`]).

use super::clamp::{Hom, clamp};
use super::curves::{Geo, expand_knots, nested_nums};
use super::graph::Ent;
use crate::error::IoError;
use swarf_geom::patch::Frame;
use swarf_geom::{Patch, Point3};

/// A face's surface, in mm and radians.
pub enum Surf {
    /// `PLANE`.
    Plane(Frame),
    /// `CYLINDRICAL_SURFACE`: radius.
    Cylinder(Frame, f64),
    /// `CONICAL_SURFACE`: radius at the placement, semi-angle.
    Cone(Frame, f64, f64),
    /// `SPHERICAL_SURFACE`: radius.
    Sphere(Frame, f64),
    /// `TOROIDAL_SURFACE`: major and minor radius.
    Torus(Frame, f64, f64),
    /// A B-spline or NURBS surface.
    Spline(Patch),
    /// `SURFACE_OF_LINEAR_EXTRUSION` of a B-spline curve: `S(u, v) = C(u) + v dir`,
    /// `dir` a unit vector, `v` in mm; the curve clamped, homogeneous points.
    Extrusion {
        /// Degree of the curve.
        degree: usize,
        /// Its clamped knots.
        knots: Vec<f64>,
        /// Its homogeneous control points.
        points: Vec<Hom>,
        /// Unit extrusion direction.
        dir: swarf_geom::Vec3,
    },
}

/// Why a surface was not read.
pub enum SurfFail {
    /// A type or form this reader does not handle: skip or refuse by the options.
    Unsupported(IoError),
    /// Malformed input.
    Bad(IoError),
}

impl From<IoError> for SurfFail {
    fn from(e: IoError) -> Self {
        SurfFail::Bad(e)
    }
}

/// The surface `#id` of face `face`.
///
/// # Errors
/// [`SurfFail::Unsupported`] for other surface types;
/// [`SurfFail::Bad`] for malformed entities.
pub fn surface(geo: &Geo<'_>, id: u64, face: &Ent<'_>) -> Result<Surf, SurfFail> {
    let parts = geo.g.parts(id, Some(face))?;
    if parts
        .iter()
        .any(|p| p.name == "B_SPLINE_SURFACE_WITH_KNOTS")
    {
        return spline(geo, &parts).map(Surf::Spline);
    }
    let e = parts[0];
    let frame = |e: &Ent<'_>| geo.frame(e.refr(1)?, e);
    let len = |i: usize| -> Result<f64, IoError> {
        let x = e.num(i)? * geo.mm;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(e.arg_err(i, "a positive length"))
        }
    };
    Ok(match e.name {
        "PLANE" => Surf::Plane(frame(&e)?),
        "CYLINDRICAL_SURFACE" => Surf::Cylinder(frame(&e)?, len(2)?),
        "CONICAL_SURFACE" => {
            let r = e.num(2)? * geo.mm;
            let a = e.num(3)? * geo.rad;
            if !(r >= 0.0 && a > 0.0 && a < std::f64::consts::FRAC_PI_2) {
                return Err(e
                    .err("expected a radius >= 0 and a semi-angle in (0, 90) degrees")
                    .into());
            }
            Surf::Cone(frame(&e)?, r, a)
        }
        "SPHERICAL_SURFACE" => Surf::Sphere(frame(&e)?, len(2)?),
        "TOROIDAL_SURFACE" => Surf::Torus(frame(&e)?, len(2)?, len(3)?),
        "SURFACE_OF_LINEAR_EXTRUSION" => extrusion(geo, &e)?,
        other => {
            return Err(SurfFail::Unsupported(e.err(format!(
                "unsupported surface type {other} (supported: B_SPLINE_SURFACE_WITH_KNOTS, PLANE, \
                 CYLINDRICAL_SURFACE, CONICAL_SURFACE, SPHERICAL_SURFACE, TOROIDAL_SURFACE, \
                 SURFACE_OF_LINEAR_EXTRUSION)"
            ))));
        }
    })
}

/// `SURFACE_OF_LINEAR_EXTRUSION(name, swept_curve, VECTOR)` of a B-spline curve.
fn extrusion(geo: &Geo<'_>, e: &Ent<'_>) -> Result<Surf, SurfFail> {
    let vec = geo.g.get(e.refr(2)?, &["VECTOR"], e)?;
    let dir = geo.direction(vec.refr(1)?, &vec)?;
    let parts = geo.g.parts(e.refr(1)?, Some(e))?;
    if !parts.iter().any(|p| p.name == "B_SPLINE_CURVE_WITH_KNOTS") {
        return Err(SurfFail::Unsupported(e.err(format!(
            "swept curve #{} {}: only B-spline swept curves are supported",
            parts[0].id, parts[0].name
        ))));
    }
    let (degree, knots, pts, weights, wk) = geo.bspline_raw(&parts)?;
    let hom: Vec<Hom> = pts
        .iter()
        .enumerate()
        .map(|(i, q)| {
            let w = weights
                .as_ref()
                .and_then(|w| w.get(i))
                .copied()
                .unwrap_or(1.0);
            [q.x * w, q.y * w, q.z * w, w]
        })
        .collect();
    let bad =
        || wk.err("expected a valid B-spline curve (knots = points + degree + 1, weights > 0)");
    if weights
        .as_ref()
        .is_some_and(|w| w.len() != pts.len() || w.iter().any(|x| *x <= 0.0))
    {
        return Err(bad().into());
    }
    let (knots, points) = if clamped(&knots, degree) {
        (knots, hom)
    } else {
        clamp(degree, &knots, &hom).ok_or_else(bad)?
    };
    Ok(Surf::Extrusion {
        degree,
        knots,
        points,
        dir,
    })
}

fn clamped(k: &[f64], p: usize) -> bool {
    let n = k.len();
    n >= 2 * (p + 1)
        && k[..=p].iter().all(|x| *x == k[0])
        && k[n - p - 1..].iter().all(|x| *x == k[n - 1])
}

/// A B-spline surface from its simple or complex instance.
fn spline(geo: &Geo<'_>, parts: &[Ent<'_>]) -> Result<Patch, SurfFail> {
    let by = |n: &str| parts.iter().find(|p| p.name == n).copied();
    let wk = by("B_SPLINE_SURFACE_WITH_KNOTS").ok_or_else(|| parts[0].err("no knots"))?;
    // Simple: (name, du, dv, points, form, uc, vc, si, umult, vmult, uknots, vknots, spec).
    // Complex: B_SPLINE_SURFACE(du, dv, points, ...) + WITH_KNOTS(umult, vmult, uk, vk, spec).
    let (s, c0, k0) = match by("B_SPLINE_SURFACE") {
        Some(bs) => (bs, 0, 0),
        None => (wk, 1, 8),
    };
    let degree = [s.int(c0)?, s.int(c0 + 1)?];
    let rows = s.list(c0 + 2)?;
    let mut points = Vec::new();
    let mut nv = None;
    for row in rows {
        let super::parser::Value::List(r) = row else {
            return Err(s.arg_err(c0 + 2, "a list of lists of points").into());
        };
        if nv.is_some_and(|n| n != r.len()) {
            return Err(s.arg_err(c0 + 2, "rows of equal length").into());
        }
        nv = Some(r.len());
        for v in r {
            let super::parser::Value::Ref(id) = v else {
                return Err(s.arg_err(c0 + 2, "references to CARTESIAN_POINTs").into());
            };
            points.push(geo.point(*id, &s)?);
        }
    }
    let weights = match by("RATIONAL_B_SPLINE_SURFACE") {
        Some(r) => Some(nested_nums(&r, 0)?.concat()),
        None => None,
    };
    let nv = nv.unwrap_or(0);
    if weights.as_ref().is_some_and(|w| w.len() != points.len()) {
        return Err(wk.err("expected one weight per control point").into());
    }
    // Homogeneous grid [i][j], i along u.
    let w = |k: usize| weights.as_ref().map_or(1.0, |w| w[k]);
    let mut grid: Vec<Vec<Hom>> = (0..rows.len())
        .map(|i| {
            (0..nv)
                .map(|j| {
                    let k = i * nv + j;
                    let q = points[k];
                    [q.x * w(k), q.y * w(k), q.z * w(k), w(k)]
                })
                .collect()
        })
        .collect();
    let mut knots = Vec::new();
    for d in 0..2 {
        let m = wk.nums(k0 + d)?;
        let v = wk.nums(k0 + 2 + d)?;
        let mut k = expand_knots(&m, &v).ok_or_else(|| {
            wk.arg_err(
                k0 + d,
                "positive integer multiplicities, one per knot value",
            )
        })?;
        if !clamped(&k, degree[d]) {
            let (nk, ng) = clamp_grid(degree[d], &k, &grid, d).ok_or_else(|| {
                wk.err(format!(
                    "{} knots in {} for degree {} do not fit the control points",
                    k.len(),
                    ["u", "v"][d],
                    degree[d]
                ))
            })?;
            k = nk;
            grid = ng;
        }
        knots.push(k);
    }
    let rational = weights.is_some();
    let flat: Vec<Hom> = grid.concat();
    let points = flat
        .iter()
        .map(|h| Point3::new(h[0] / h[3], h[1] / h[3], h[2] / h[3]))
        .collect();
    let weights = rational.then(|| flat.iter().map(|h| h[3]).collect());
    let kv = knots.pop();
    let ku = knots.pop();
    Patch::new(degree, points, [ku, kv], weights)
        .map_err(|e| SurfFail::Bad(wk.err(format!("invalid B-spline surface: {e}"))))
}

/// The grid with direction `d` (0 = along `i`, 1 = along `j`) clamped.
fn clamp_grid(p: usize, k: &[f64], g: &[Vec<Hom>], d: usize) -> Option<(Vec<f64>, Vec<Vec<Hom>>)> {
    let nj = g.first().map_or(0, Vec::len);
    let rows: Vec<(Vec<f64>, Vec<Hom>)> = if d == 0 {
        (0..nj)
            .map(|j| clamp(p, k, &g.iter().map(|r| r[j]).collect::<Vec<_>>()))
            .collect::<Option<_>>()?
    } else {
        g.iter().map(|r| clamp(p, k, r)).collect::<Option<_>>()?
    };
    let nk = rows.first()?.0.clone();
    let rows: Vec<Vec<Hom>> = rows.into_iter().map(|r| r.1).collect();
    if d == 1 {
        return Some((nk, rows));
    }
    let n = rows[0].len();
    Some((
        nk,
        (0..n)
            .map(|i| rows.iter().map(|c| c[i]).collect())
            .collect(),
    ))
}

/// The patch with its `u` direction reversed (the normal flipped), same surface.
pub fn reverse_u(p: &Patch) -> Patch {
    let [nu, nv] = p.count();
    let ku = p.knots(0);
    let (a, b) = (ku[0], ku[ku.len() - 1]);
    let rk: Vec<f64> = ku.iter().rev().map(|k| a + b - k).collect();
    let idx = |i: usize, j: usize| (nu - 1 - i) * nv + j;
    let pts: Vec<Point3> = (0..nu * nv)
        .map(|k| p.points()[idx(k / nv, k % nv)])
        .collect();
    let w = p
        .weights()
        .map(|w| (0..nu * nv).map(|k| w[idx(k / nv, k % nv)]).collect());
    // Same degrees, counts and validity as `p`: the reversed knots are clamped too.
    Patch::new(p.degree(), pts, [Some(rk), Some(p.knots(1).to_vec())], w)
        .unwrap_or_else(|_| p.clone())
}
