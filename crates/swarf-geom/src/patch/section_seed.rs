//! Seeds for plane sections: one point on every branch (see [`super::section`]).
//!
//! Roots of `f = n . S - d` on the edges of a parameter grid (sign changes, by the
//! Illinois variant of regula falsi, exact on the iso-line); pairs of roots hidden inside
//! one edge (a dip of `f` toward the other sign, found by bisection on the slope); and
//! loops inside one cell (Newton on `grad f = 0` toward the critical point that every
//! small loop surrounds; Patrikalakis & Maekawa, "Shape Interrogation for Computer Aided
//! Design and Manufacturing", ch. 5.8).

use super::section_trace::Section;
use crate::tol::{MAX_NEWTON_ITERATIONS, SOLVER_LENGTH};

/// Iterations of regula falsi along a seed segment.
const MAX_BRACKET_ITERATIONS: usize = 200;

/// A root of `f` found on a grid edge or a segment.
#[derive(Debug, Clone, Copy)]
pub(super) struct Seed {
    pub(super) uv: [f64; 2],
    pub(super) boundary: bool,
    pub(super) used: bool,
}

/// Roots of `f` on the seed grid's edges and near extrema of `f` (module doc).
pub(super) fn seeds(sec: &Section, grid: &[Vec<f64>; 2]) -> Vec<Seed> {
    let [gu, gv] = grid;
    let (nu, nv) = (gu.len(), gv.len());
    let (f, grad): (Vec<f64>, Vec<[f64; 2]>) = gu
        .iter()
        .flat_map(|u| gv.iter().map(|v| sec.f_grad([*u, *v])))
        .unzip();
    let at = |i: usize, j: usize| [gu[i], gv[j]];
    let mut out = Vec::new();
    let mut edge = |a: (usize, usize), b: (usize, usize), boundary: bool| {
        let (ka, kb) = (a.0 * nv + a.1, b.0 * nv + b.1);
        let (pa, pb) = (at(a.0, a.1), at(b.0, b.1));
        let seed = if (f[ka] >= 0.0) != (f[kb] >= 0.0) {
            root_on_segment(sec, pa, pb, f[ka], f[kb])
        } else {
            let dir = usize::from(a.0 == b.0);
            dip_seed(sec, pa, pb, f[ka], [grad[ka][dir], grad[kb][dir]])
        };
        if let Some(uv) = seed {
            out.push(Seed {
                uv,
                boundary,
                used: false,
            });
        }
    };
    for i in 0..nu {
        for j in 0..nv {
            if i + 1 < nu {
                edge((i, j), (i + 1, j), j == 0 || j + 1 == nv);
            }
            if j + 1 < nv {
                edge((i, j), (i, j + 1), i == 0 || i + 1 == nu);
            }
        }
    }
    for i in 0..nu - 1 {
        for j in 0..nv - 1 {
            let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)].map(|(a, b)| a * nv + b);
            let same_sign = corners
                .iter()
                .all(|k| (f[*k] >= 0.0) == (f[corners[0]] >= 0.0));
            let turns = |dir: usize| {
                let s = corners.map(|k| grad[k][dir] >= 0.0);
                s.iter().any(|x| *x != s[0])
            };
            if !(same_sign && turns(0) && turns(1)) {
                continue;
            }
            let (corner, centre) = (
                at(i, j),
                [0.5 * (gu[i] + gu[i + 1]), 0.5 * (gv[j] + gv[j + 1])],
            );
            if let Some(uv) = loop_seed(sec, corner, f[corners[0]], centre) {
                out.push(Seed {
                    uv,
                    boundary: false,
                    used: false,
                });
            }
        }
    }
    out
}

/// On a grid edge whose ends have the same sign but whose slopes along it (`slope`, at
/// `a` and `b`) both head toward the other sign inside it, the extremum between them
/// (bisection on the slope); a root between `a` and it when the extremum has the other
/// sign: a small arc or loop crossing the edge twice.
fn dip_seed(sec: &Section, a: [f64; 2], b: [f64; 2], fa: f64, slope: [f64; 2]) -> Option<[f64; 2]> {
    let toward = if fa >= 0.0 { -1.0 } else { 1.0 };
    if !(slope[0] * toward > 0.0 && slope[1] * toward < 0.0) {
        return None;
    }
    let dir = usize::from(a[0] == b[0]);
    let at = |s: f64| [a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s];
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..MAX_BRACKET_ITERATIONS.min(60) {
        let mid = 0.5 * (lo + hi);
        let (_, g) = sec.f_grad(at(mid));
        if g[dir] * toward > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let ext = at(0.5 * (lo + hi));
    let f_ext = sec.f(ext);
    ((f_ext >= 0.0) != (fa >= 0.0))
        .then(|| root_on_segment(sec, a, ext, fa, f_ext))
        .flatten()
}

/// Newton on `grad f = 0` from `start` toward the critical point of `f` in a cell
/// whose `corner` has the value `f_corner`; a root on the segment from the corner to
/// the first iterate of the other sign.
fn loop_seed(sec: &Section, corner: [f64; 2], f_corner: f64, start: [f64; 2]) -> Option<[f64; 2]> {
    let mut uv = start;
    for _ in 0..MAX_NEWTON_ITERATIONS {
        let f_here = sec.f(uv);
        if (f_here >= 0.0) != (f_corner >= 0.0) {
            return root_on_segment(sec, corner, uv, f_corner, f_here);
        }
        let d = sec.patch.derivs(uv[0], uv[1]);
        let n = &sec.normal;
        let g = [n.dot(&d.du), n.dot(&d.dv)];
        let h = [n.dot(&d.duu), n.dot(&d.duv), n.dot(&d.dvv)];
        let det = h[0] * h[2] - h[1] * h[1];
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let step = [
            (h[2] * g[0] - h[1] * g[1]) / det,
            (h[0] * g[1] - h[1] * g[0]) / det,
        ];
        let next = [0, 1].map(|k| (uv[k] - step[k]).clamp(sec.dom[k][0], sec.dom[k][1]));
        let far = (0..2).any(|k| (next[k] - start[k]).abs() > 2.0 * sec.cell[k]);
        if far || next == uv {
            return None;
        }
        uv = next;
    }
    None
}

/// A root of `f` on the segment `[a, b]` whose ends have opposite signs (Illinois).
fn root_on_segment(sec: &Section, a: [f64; 2], b: [f64; 2], fa: f64, fb: f64) -> Option<[f64; 2]> {
    let at = |s: f64| [a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s];
    let (mut s0, mut s1, mut f0, mut f1) = (0.0, 1.0, fa, fb);
    let mut side = 0;
    let mut best = (f64::INFINITY, a);
    for _ in 0..MAX_BRACKET_ITERATIONS {
        let s = ((s0 * f1 - s1 * f0) / (f1 - f0)).clamp(s0, s1);
        let p = at(s);
        let fs = sec.f(p);
        if fs.abs() < best.0 {
            best = (fs.abs(), p);
        }
        if fs.abs() <= SOLVER_LENGTH || s1 - s0 <= f64::EPSILON {
            break;
        }
        if (fs >= 0.0) == (f1 >= 0.0) {
            (s1, f1) = (s, fs);
            if side == -1 {
                f0 *= 0.5;
            }
            side = -1;
        } else {
            (s0, f0) = (s, fs);
            if side == 1 {
                f1 *= 0.5;
            }
            side = 1;
        }
    }
    (best.0 <= SOLVER_LENGTH).then_some(best.1)
}
