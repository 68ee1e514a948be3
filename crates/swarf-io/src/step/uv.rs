//! From a face's surface and its edge loops in 3D to a patch and its trimming loops
//! in `(u, v)`.
//!
//! **Elementary surfaces** are sized from the loops in the surface's local frame:
//! a plane or a cylinder/cone height by the loops' box plus a margin; an angle
//! (longitude, the torus tube angle) by the loops' largest angular gap, the patch's
//! seam put in its middle, or, when the face has a seam edge (an edge used twice),
//! one full turn starting at the seam. Loop points then map to `(u, v)` in closed
//! form: local coordinates, angles taken within the window (a window is at most one
//! turn, so each angle has one place in it) and [`arc_parameter`]; a run of points on
//! the seam of a full turn takes the side of its neighbour off the seam (the one
//! before it, or after it when a pole comes before). A point on the axis (a
//! pole, a cone apex) takes the longitudes of its two neighbours: a straight `u`
//! segment along the degenerate edge.
//!
//! **B-spline surfaces** map by projection with continuation: the loop starts at the
//! sampled point whose projection is farthest from the patch boundary; each next
//! point is projected from the previous `(u, v)` ([`Patch::project_from`]), globally
//! when that fails.
//!
//! A face whose loops are its whole domain (only seam edges, or one loop around the
//! patch boundary) gets no trim.

use super::clamp::Hom;
use super::surfaces::Surf;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use swarf_geom::patch::arc_parameter;
use swarf_geom::{Patch, Point3, Vec3};

/// Margin around the loops' extent for unbounded directions, relative to the extent.
const MARGIN_REL: f64 = 0.02;
/// Absolute margin, mm (or radians for angles).
const MARGIN_ABS: f64 = 1e-3;
/// Points closer than this to the axis (relative to the surface size) are poles.
const POLE_REL: f64 = 1e-9;
/// A loop point further than this from the patch after projection (mm) is refused.
const MAX_PROJECTION_GAP: f64 = 1e-4;

/// Local coordinates of a point: `[a, b]` the two surface coordinates before the arc
/// reparametrisation, and whether it is a pole.
type Local = ([f64; 2], bool);

/// Loops in a patch's `(u, v)`.
pub type UvLoops = Vec<Vec<[f64; 2]>>;

/// What the loops need: coordinates per direction and which are angles.
fn locals(s: &Surf, p: &Point3) -> Local {
    let (f, r) = match s {
        Surf::Plane(f) => {
            let l = f.to_local(p);
            return ([l[0], l[1]], false);
        }
        Surf::Cylinder(f, r) | Surf::Cone(f, r, _) | Surf::Sphere(f, r) => (f, *r),
        Surf::Torus(f, big, _) => (f, *big),
        Surf::Spline(_) | Surf::Extrusion { .. } => return ([0.0, 0.0], false),
    };
    let l = f.to_local(p);
    let rho = l[0].hypot(l[1]);
    let pole = rho <= POLE_REL * r.max(1.0);
    let th = l[1].atan2(l[0]);
    let b = match s {
        Surf::Sphere(..) => l[2].atan2(rho),
        Surf::Torus(_, big, _) => l[2].atan2(rho - big),
        _ => l[2],
    };
    ([th, b], pole)
}

/// Which directions are angles (periodic).
fn periodic(s: &Surf) -> [bool; 2] {
    match s {
        Surf::Plane(_) | Surf::Spline(_) | Surf::Extrusion { .. } => [false, false],
        Surf::Torus(..) => [true, true],
        _ => [true, false],
    }
}

/// Circular spread of angles around their first.
fn spread(a: &[f64]) -> f64 {
    a.iter()
        .map(|x| {
            let d = (x - a[0]).rem_euclid(TAU);
            d.min(TAU - d)
        })
        .fold(0.0, f64::max)
}

/// The window of an angle direction: a full turn from the seam, or the complement of
/// the largest gap with margins.
fn angle_window(angles: &[f64], seam: Option<f64>) -> [f64; 2] {
    if let Some(s) = seam {
        return [s, s + TAU];
    }
    let mut a: Vec<f64> = angles.iter().map(|x| x.rem_euclid(TAU)).collect();
    a.sort_by(f64::total_cmp);
    let mut gap = (a[0] + TAU - a[a.len() - 1], a[0]);
    for w in a.windows(2) {
        if w[1] - w[0] > gap.0 {
            gap = (w[1] - w[0], w[1]);
        }
    }
    let span = TAU - gap.0;
    let m = (MARGIN_REL * span + MARGIN_ABS).min(gap.0 / 4.0);
    let start = gap.1 - m;
    [start, start + span + 2.0 * m]
}

fn linear_window(v: &[f64]) -> [f64; 2] {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let m = MARGIN_REL * (hi - lo) + MARGIN_ABS;
    [lo - m, hi + m]
}

/// The patch of an elementary surface over windows fitting `loops`, with the loops
/// in its `(u, v)`; `seams` are the samples of the face's seam edges.
///
/// # Errors
/// A message when the patch cannot be built.
pub fn elementary(
    s: &Surf,
    loops: &[Vec<Point3>],
    seams: &[Vec<Point3>],
) -> Result<(Patch, UvLoops), String> {
    let per = periodic(s);
    let loc: Vec<Vec<Local>> = loops
        .iter()
        .map(|l| l.iter().map(|p| locals(s, p)).collect())
        .collect();
    let mut win = [[0.0; 2]; 2];
    for d in 0..2 {
        let vals: Vec<f64> = loc
            .iter()
            .flatten()
            .filter(|x| !(x.1 && d == 0))
            .map(|x| x.0[d])
            .collect();
        if vals.is_empty() {
            return Err("the face's edges lie on the surface's axis".into());
        }
        win[d] = if per[d] {
            let seam = seams.iter().find_map(|sm| {
                let a: Vec<f64> = sm
                    .iter()
                    .map(|p| locals(s, p))
                    .filter(|x| !x.1)
                    .map(|x| x.0[d])
                    .collect();
                (!a.is_empty() && spread(&a) < 1e-7).then(|| a[0])
            });
            angle_window(&vals, seam)
        } else {
            linear_window(&vals)
        };
    }
    match s {
        Surf::Sphere(..) => win[1] = [win[1][0].max(-FRAC_PI_2), win[1][1].min(FRAC_PI_2)],
        Surf::Cone(_, r, a) => {
            let apex = -r / a.tan();
            win[1][0] = win[1][0].max(apex);
        }
        _ => {}
    }
    let patch = build(s, win).map_err(|e| e.to_string())?;
    let uv = loc.iter().map(|l| unwrap(l, &win, per, s)).collect();
    Ok((patch, uv))
}

fn build(s: &Surf, w: [[f64; 2]; 2]) -> Result<Patch, swarf_geom::GeomError> {
    match s {
        Surf::Plane(f) => Patch::plane(f, w[0], w[1]),
        Surf::Cylinder(f, r) => Patch::cylinder(f, *r, w[0], w[1]),
        Surf::Cone(f, r, a) => Patch::cone(f, *r, *a, w[0], w[1]),
        Surf::Sphere(f, r) => Patch::sphere(f, *r, w[0], w[1]),
        Surf::Torus(f, big, small) => Patch::torus(f, *big, *small, w[0], w[1]),
        Surf::Spline(p) => Ok(p.clone()),
        Surf::Extrusion { .. } => Err(swarf_geom::GeomError::patch(
            "surface",
            "an extrusion is sized by uv::extrusion",
        )),
    }
}

/// One loop's local coordinates to patch `(u, v)`.
fn unwrap(l: &[Local], win: &[[f64; 2]; 2], per: [bool; 2], s: &Surf) -> Vec<[f64; 2]> {
    let n = l.len();
    let mut out: Vec<[f64; 2]> = l
        .iter()
        .map(|(c, pole)| {
            let mut q = *c;
            if *pole {
                q[0] = f64::NAN;
            }
            for d in 0..2 {
                if per[d] && !q[d].is_nan() {
                    q[d] = (win[d][0] + (q[d] - win[d][0]).rem_euclid(TAU)).min(win[d][1]);
                }
            }
            q
        })
        .collect();
    for d in 0..2 {
        if per[d] && win[d][1] - win[d][0] >= TAU * (1.0 - 1e-12) {
            seam_sides(l, &mut out, d, win[d]);
        }
    }
    let mut res = Vec::with_capacity(n + 4);
    for i in 0..n {
        if out[i][0].is_nan() {
            // A pole: straight along u from the previous to the next longitude.
            let find = |step: isize| {
                (1..n as isize)
                    .map(|k| out[(i as isize + step * k).rem_euclid(n as isize) as usize][0])
                    .find(|u| !u.is_nan())
                    .unwrap_or(win[0][0])
            };
            res.push([find(-1), out[i][1]]);
            res.push([find(1), out[i][1]]);
        } else {
            res.push(out[i]);
        }
    }
    for q in &mut res {
        for d in 0..2 {
            if per[d] || (d == 1 && matches!(s, Surf::Sphere(..))) {
                q[d] = arc_parameter(win[d], q[d]);
            }
        }
    }
    res
}

/// Puts each run of loop points on the seam of a full-turn direction `d` on the side
/// of its neighbour off the seam: the one before the run, or after it when the run
/// starts at a pole. Continuation alone cannot tell the side of a seam walked right
/// after a pole (a cone's apex): no point between says which way it went.
fn seam_sides(l: &[Local], out: &mut [[f64; 2]], d: usize, w: [f64; 2]) {
    let n = l.len();
    let on_seam = |i: usize| {
        !(l[i].1 && d == 0) && {
            let x = (l[i].0[d] - w[0]).rem_euclid(TAU);
            x.min(TAU - x) < 1e-9
        }
    };
    let free = |i: usize| !(on_seam(i) || (l[i].1 && d == 0));
    let Some(anchor) = (0..n).find(|i| free(*i)) else {
        return;
    };
    let side = |q: f64| if q - w[0] < PI { w[0] } else { w[1] };
    let mut k = 0;
    while k < n {
        let i = (anchor + k) % n;
        if !on_seam(i) {
            k += 1;
            continue;
        }
        let run_start = k;
        while k < n && on_seam((anchor + k) % n) {
            k += 1;
        }
        let before = (anchor + run_start + n - 1) % n;
        let after = (anchor + k) % n;
        let pick = if free(before) {
            Some(side(out[before][d]))
        } else if free(after) {
            Some(side(out[after][d]))
        } else {
            None
        };
        if let Some(v) = pick {
            for j in run_start..k {
                out[(anchor + j) % n][d] = v;
            }
        }
    }
}

/// The patch of an extrusion `C(u) + v dir` over a `v` window holding every loop
/// point: `v = (P - C(u)) . dir` lies within `P . dir` minus the range of the control
/// points' `. dir` (convex hull), plus a margin.
///
/// # Errors
/// A message when the patch cannot be built.
pub fn extrusion(
    degree: usize,
    knots: &[f64],
    pts: &[Hom],
    dir: &Vec3,
    loops: &[Vec<Point3>],
) -> Result<Patch, String> {
    let along = |h: &Hom| (h[0] * dir.x + h[1] * dir.y + h[2] * dir.z) / h[3];
    let (cmin, cmax) = pts
        .iter()
        .map(along)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, x| {
            (a.0.min(x), a.1.max(x))
        });
    let l: Vec<f64> = loops.iter().flatten().map(|p| p.coords.dot(dir)).collect();
    let w = linear_window(&[
        l.iter().copied().fold(f64::INFINITY, f64::min) - cmax,
        l.iter().copied().fold(f64::NEG_INFINITY, f64::max) - cmin,
    ]);
    let mut points = Vec::with_capacity(2 * pts.len());
    let mut weights = Vec::with_capacity(2 * pts.len());
    for h in pts {
        let c = Point3::new(h[0] / h[3], h[1] / h[3], h[2] / h[3]);
        for v in w {
            points.push(c + dir * v);
            weights.push(h[3]);
        }
    }
    Patch::new(
        [degree, 1],
        points,
        [Some(knots.to_vec()), Some(vec![w[0], w[0], w[1], w[1]])],
        Some(weights),
    )
    .map_err(|e| e.to_string())
}

/// Loops of a B-spline patch in `(u, v)` by projection with continuation.
///
/// # Errors
/// A message naming the point that does not lie on the surface.
pub fn project_loops(p: &Patch, loops: &[Vec<Point3>]) -> Result<Vec<Vec<[f64; 2]>>, String> {
    let [du, dv] = p.domain();
    let inner = |u: f64, v: f64| {
        ((u - du[0]) / (du[1] - du[0]))
            .min((du[1] - u) / (du[1] - du[0]))
            .min((v - dv[0]) / (dv[1] - dv[0]))
            .min((dv[1] - v) / (dv[1] - dv[0]))
    };
    let mut out = Vec::new();
    for l in loops {
        let n = l.len();
        let step = (n / 16).max(1);
        let (start, first) = (0..n)
            .step_by(step)
            .map(|i| (i, p.project(&l[i])))
            .max_by(|a, b| inner(a.1.u, a.1.v).total_cmp(&inner(b.1.u, b.1.v)))
            .ok_or("an empty loop")?;
        let mut uv = vec![[0.0; 2]; n];
        let mut prev = (first.u, first.v);
        for k in 0..n {
            let i = (start + k) % n;
            let mut pr = p.project_from(&l[i], prev.0, prev.1);
            if pr.distance > MAX_PROJECTION_GAP {
                pr = p.project(&l[i]);
            }
            if pr.distance > MAX_PROJECTION_GAP {
                return Err(format!(
                    "edge point ({:.6}, {:.6}, {:.6}) lies {:.2e} mm off the surface (expected \
                     within {MAX_PROJECTION_GAP:e} mm)",
                    l[i].x, l[i].y, l[i].z, pr.distance
                ));
            }
            prev = (pr.u, pr.v);
            uv[i] = [pr.u, pr.v];
        }
        out.push(uv);
    }
    Ok(out)
}

/// Whether `loops` is one loop running around the boundary of `dom` (the whole patch).
pub fn covers_domain(loops: &[Vec<[f64; 2]>], dom: [[f64; 2]; 2]) -> bool {
    if loops.len() != 1 {
        return false;
    }
    let eps = [
        1e-9 * (dom[0][1] - dom[0][0]),
        1e-9 * (dom[1][1] - dom[1][0]),
    ];
    let on = |q: &[f64; 2]| {
        (0..2).any(|d| (q[d] - dom[d][0]).abs() <= eps[d] || (q[d] - dom[d][1]).abs() <= eps[d])
    };
    let l = &loops[0];
    let area: f64 = (0..l.len())
        .map(|i| {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        .abs()
        / 2.0;
    let full = (dom[0][1] - dom[0][0]) * (dom[1][1] - dom[1][0]);
    l.iter().all(on) && (area - full).abs() <= 1e-6 * full
}
