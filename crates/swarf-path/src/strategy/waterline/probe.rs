//! Exact points of a level's contour: root finding on the drop height.
//!
//! A point is inside a level `z` when the cutter's drop height there is above
//! `z + Z_EPS` (the tool cannot stand at `z`), outside otherwise (off the mesh
//! included). Between an inside and an outside point the contour is bracketed and
//! found by the Illinois variant of regula falsi on `drop - z`, with a bisection step
//! whenever two steps have not halved the bracket (the drop height jumps at cliffs:
//! a flat end beside a wall, where no point has drop height `z` and the contour is
//! the jump itself). The bracket ends within [`ROOT_TOL`] of each other; the inside
//! end is returned, so its drop height is at least `z` and a point within `ROOT_TOL`
//! has it at most `z + Z_EPS`.
//!
//! Between two consecutive contour points the chord is checked at its midpoint: the
//! contour must cross the normal there within the tolerance, and the drop height at
//! the chord's quarter points and midpoint may stand at most the tolerance above the
//! level (five drops; the second test matters where the drop height rises steeply, so
//! that a chord a little inside the contour cuts deep). Where the drop height is too
//! high, the chord is split at the crossing nearest that point, unless the height
//! jumps there (a cliff, the mesh's edge: the XY test alone holds). Where it
//! does not, the crossing nearest the midpoint is searched along the normal and
//! inserted, and both halves are checked again.

use swarf_tool::drop::{DropResult, DropScratch, MeshDropper};

/// Inside means a drop height above `z + Z_EPS`, mm: a floor lying exactly at a
/// level (up to rounding) is outside, so the tool runs along its walls.
pub const Z_EPS: f64 = 1e-7;
/// Bracket width at which a contour point is accepted, mm.
pub const ROOT_TOL: f64 = 1e-9;
/// Most steps of one root search.
const ROOT_STEPS: usize = 200;
/// Chords shorter than this are not refined, mm.
pub const MIN_CHORD: f64 = 1e-4;
/// Where along a chord its gouge is checked (fractions of its length).
const GOUGE_PROBES: [f64; 3] = [0.25, 0.5, 0.75];
/// A drop height rising faster than this per mm across the contour is a jump.
const CLIFF_SLOPE: f64 = 100.0;
/// Deepest chord refinement of one segment.
const MAX_DEPTH: usize = 24;

/// A point of a contour: its XY and the drop at its inside end (tip height at least
/// the level; its contact is the contour point's contact).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContourPoint {
    pub xy: [f64; 2],
    pub hit: DropResult,
}

/// Drops at one level.
pub(crate) struct Probe<'a> {
    pub dropper: &'a MeshDropper,
    pub z: f64,
}

impl Probe<'_> {
    /// `drop - z`, `-inf` off the mesh, and the drop.
    fn eval(&self, p: [f64; 2], s: &mut DropScratch) -> (f64, Option<DropResult>) {
        match self.dropper.drop(p[0], p[1], s) {
            Some(h) => (h.z - self.z - Z_EPS, Some(h)),
            None => (f64::NEG_INFINITY, None),
        }
    }

    /// True when `p` is inside.
    pub fn inside(&self, p: [f64; 2], s: &mut DropScratch) -> bool {
        self.eval(p, s).0 > 0.0
    }

    /// The contour point between `a` (inside, drop `ha`) and `b` (outside).
    pub fn root(&self, a: [f64; 2], b: [f64; 2], s: &mut DropScratch) -> Option<ContourPoint> {
        let (fa0, ha) = self.eval(a, s);
        let mut hit = ha?;
        let (mut ta, mut tb) = (0.0f64, 1.0f64);
        let (mut fa, mut fb) = (fa0, self.eval(b, s).0);
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let at = |t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        let mut width = 1.0;
        let mut side = 0i8;
        for step in 0..ROOT_STEPS {
            if (tb - ta) * len <= ROOT_TOL {
                break;
            }
            let bisect = step % 2 == 1 && (tb - ta) > 0.5 * width || !fb.is_finite();
            if step % 2 == 1 {
                width = tb - ta;
            }
            let t = if bisect {
                0.5 * (ta + tb)
            } else {
                (ta - fa * (tb - ta) / (fb - fa)).clamp(ta, tb)
            };
            let t = if t <= ta || t >= tb {
                0.5 * (ta + tb)
            } else {
                t
            };
            let (f, h) = self.eval(at(t), s);
            if f > 0.0 {
                (ta, fa) = (t, f);
                hit = h?;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            } else {
                (tb, fb) = (t, f);
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            }
        }
        Some(ContourPoint { xy: at(ta), hit })
    }

    /// The points to insert between `a` and `b` so that every chord's midpoint is
    /// within `tol` of the contour and no chord gouges more than `tol` at its checks, appended to `out` in order (`a` and `b` not
    /// included). `right_inside`: the inside lies to the right of `a -> b`.
    #[allow(clippy::too_many_arguments)]
    pub fn refine(
        &self,
        a: ContourPoint,
        b: ContourPoint,
        tol: f64,
        right_inside: bool,
        s: &mut DropScratch,
        out: &mut Vec<ContourPoint>,
        depth: usize,
    ) {
        let d = [b.xy[0] - a.xy[0], b.xy[1] - a.xy[1]];
        let len = d[0].hypot(d[1]);
        if depth >= MAX_DEPTH || len < MIN_CHORD.max(2.0 * tol) {
            return;
        }
        let sign = if right_inside { 1.0 } else { -1.0 };
        let n_in = [sign * d[1] / len, -sign * d[0] / len];
        let at = |t: f64| [a.xy[0] + t * d[0], a.xy[1] + t * d[1]];
        let split = match self.gouge_split(at, n_in, tol, len, s) {
            Some(c) => Some(c),
            None => {
                let m = at(0.5);
                let along = |t: f64| [m[0] + t * n_in[0], m[1] + t * n_in[1]];
                if self.inside(along(tol), s) && !self.inside(along(-tol), s) {
                    return;
                }
                self.nearest_crossing(along, tol, len, s)
            }
        };
        let Some(c) = split else {
            return;
        };
        self.refine(a, c, tol, right_inside, s, out, depth + 1);
        out.push(c);
        self.refine(c, b, tol, right_inside, s, out, depth + 1);
    }

    /// Where a chord `at(t)` (`t` in `[0, 1]`, inward normal `n_in`) gouges more than
    /// `tol` below the drop height at one of its [`GOUGE_PROBES`], the contour
    /// crossing nearest the deepest probe to split it at. A probe within `tol` of the
    /// contour in XY whose drop height rises faster than [`CLIFF_SLOPE`] stands at a
    /// jump (a cliff, the mesh's edge), where the XY distance is the interference and
    /// the height says nothing.
    fn gouge_split(
        &self,
        at: impl Fn(f64) -> [f64; 2],
        n_in: [f64; 2],
        tol: f64,
        len: f64,
        s: &mut DropScratch,
    ) -> Option<ContourPoint> {
        let (worst, excess) = GOUGE_PROBES
            .iter()
            .map(|&t| (t, self.eval(at(t), s).0))
            .fold(
                (0.5, f64::NEG_INFINITY),
                |w, p| if p.1 > w.1 { p } else { w },
            );
        if excess <= tol {
            return None;
        }
        let m = at(worst);
        let c = self.nearest_crossing(|t| [m[0] + t * n_in[0], m[1] + t * n_in[1]], tol, len, s)?;
        let e = (c.xy[0] - m[0]).hypot(c.xy[1] - m[1]);
        (e > tol || excess <= CLIFF_SLOPE * e).then_some(c)
    }

    /// The contour crossing of the normal line `along(t)` nearest `t = 0`, searched
    /// in growing steps from `tol` out to `reach` on both sides.
    fn nearest_crossing(
        &self,
        along: impl Fn(f64) -> [f64; 2],
        tol: f64,
        reach: f64,
        s: &mut DropScratch,
    ) -> Option<ContourPoint> {
        let m_inside = self.inside(along(0.0), s);
        let mut t = tol;
        while t <= reach {
            for sgn in [1.0, -1.0] {
                let q = along(sgn * t);
                if self.inside(q, s) != m_inside {
                    let (i, o) = if m_inside {
                        (along(0.0), q)
                    } else {
                        (q, along(0.0))
                    };
                    return self.root(i, o, s);
                }
            }
            t *= 2.0;
        }
        None
    }
}
