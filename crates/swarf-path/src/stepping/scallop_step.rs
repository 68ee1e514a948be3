//! The next iso-scallop CC point from a point of the current path (Feng & Li 2002).
//!
//! Feng and Li build the next path from the current one in two steps: the scallop
//! curve (where the envelopes of the two tools meet, on the surface offset by `h`),
//! then the next CL path a tool radius from it, both in planes normal to the paths,
//! assuming the tangents of adjacent paths parallel (paper 004, fig. 7). This file
//! does the same in one solve per CC point `P` of the current path (unit normal `N`
//! toward the tool, tangent `T`, side direction `B = N x T` pointing away from the
//! covered side):
//!
//! 1. Candidates `q(w)` lie on the surface in the plane through `P` normal to `T` (the
//!    cross-section), at side offset `B . (q - P) = w` ([`crate::section_point`]).
//! 2. The scallop height `s(w)` between the tool at `P` and the tool at `q(w)` is
//!    measured in that plane ([`crate::stepping::scallop_crest`]: the crossing of the two tool
//!    circles nearest the surface, and its distance to the surface).
//! 3. `s(w) = h` is solved for `w` by regula falsi (Illinois) from the local estimate
//!    of [`crate::stepping::side_step`], so the crest lies on the offset surface at `h` exactly
//!    as in Feng and Li, without their offset surfaces.
//!
//! Boundaries: when the cross-section leaves the patch before the scallop reaches `h`
//! through an edge running along the path (the far edge), the surface up to that edge
//! is covered if the station's tool alone leaves at most `h` there (the height where
//! the ray along the normal at the edge point enters its envelope); then no point
//! follows. Otherwise the next point is where the section leaves (the next path then
//! runs along that edge), and a point whose cross-section leaves at once is dropped.
//! When it leaves through an edge the path ends on (a side edge), the station gives
//! no point: the path's end on that edge is carried by its end station, which, lying
//! on the edge with `B` along it, slides along the edge (paths keep spanning the
//! patch from edge to edge).

use crate::cl_curve::tool_side_normal;
use crate::section_point::{Edge, PlaneEq, Solved, on_edge, two_planes};
use crate::stepping::scallop_crest::{alone, scallop};
use crate::stepping::side_step::SideStep;
use swarf_geom::{Patch, Point3, SurfaceDerivs, Vec3};

/// Relative accuracy of the scallop height at the solved side offset.
pub const SCALLOP_REL: f64 = 1e-3;
/// Iterations of the side-offset root finder.
const ROOT_ITERATIONS: usize = 40;
/// Growth of the side offset while bracketing the root.
const BRACKET_GROWTH: f64 = 1.5;
/// A side offset below this is no step: the point is dropped, mm.
const MIN_OFFSET: f64 = 1e-6;
/// A direction with more than this share along an edge runs along it (a station on
/// the edge slides; an exit through it is through the far edge).
const HALF: f64 = 0.5;
/// A path's end station on an edge slides along it when its side direction has at
/// least this share along the edge (the path ends on that edge and must keep reaching
/// it; a side direction straight across the edge means the path runs along it).
const END_SLIDE_SHARE: f64 = 0.2;
/// Parameters within this fraction of the range of a bound are on that edge.
const ON_EDGE_REL: f64 = 1e-9;

/// A point of the current path, with its frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    /// Parameters.
    pub uv: [f64; 2],
    /// Derivatives at `uv`.
    pub d: SurfaceDerivs,
    /// Unit normal toward the tool.
    pub normal: Vec3,
    /// Unit path tangent (in the tangent plane).
    pub tangent: Vec3,
    /// Unit side direction, away from the covered side.
    pub side: Vec3,
    /// Local side step of the scallop model (initial guess), mm.
    pub step: f64,
    /// Effective cutting radius here, mm.
    pub radius: f64,
    /// True at the first and last station of a path.
    pub end: bool,
}

/// The next CC point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NextPoint {
    /// Parameters.
    pub uv: [f64; 2],
    /// The point, mm.
    pub point: Point3,
    /// Distance from the station, mm.
    pub across: f64,
    /// Scallop height between the two tools there, mm (`h`, or less at a boundary).
    pub scallop: f64,
    /// True when the point slid along the edge its station lies on (a path end).
    pub slid: bool,
}

/// How the side offset moves the candidate point.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// In the cross-section plane.
    Plane,
    /// Along a patch edge.
    Slide(Edge),
}

/// What becomes of a station on the next path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Next {
    /// The next CC point.
    Point(NextPoint),
    /// No point here, the next path goes on past: the cross-section leaves through an
    /// edge the path ends on (a side edge; the path's end on that edge is carried by
    /// its end station), or the solver found no point.
    Skip,
    /// The surface beyond is covered (the cross-section leaves at once through the far
    /// boundary, or the tool here alone leaves at most `h` up to it): the next path is
    /// cut here. In the second case the point where the section leaves is given: a
    /// next path that starts or ends beside this station continues to it along the
    /// edge, so that no stretch of the edge falls between the two.
    Covered(Option<NextPoint>),
}

/// The next CC point from `st` on `patch` for the scallop model `side` (module doc).
pub fn next_point(patch: &Patch, side: &SideStep, st: &Station) -> Next {
    let Some(mode) = mode(patch, st) else {
        return Next::Covered(None);
    };
    let h = side.h();
    let eval = |w: f64, guess: [f64; 2]| candidate(patch, side, st, mode, w, guess);
    let mut lo = Bound {
        w: 0.0,
        f: -h,
        q: None,
    };
    let mut w = st.step.max(MIN_OFFSET * 10.0);
    let mut guess = side_guess(st, w);
    for _ in 0..ROOT_ITERATIONS {
        let c = match eval(w, guess) {
            Some(Ok(c)) => c,
            Some(Err(SideExit)) => return Next::Skip,
            None => return lo.q.map_or(Next::Skip, Next::Point),
        };
        if c.beyond && c.w <= MIN_OFFSET {
            return Next::Covered(None);
        }
        if c.s <= h && c.beyond {
            if alone(side, st, &c.q.point, &c.normal) <= h {
                return Next::Covered(Some(c.q.with_scallop(c.s)));
            }
            return Next::Point(c.q.with_scallop(c.s));
        }
        if c.s > h {
            let hi = Bound {
                w: c.w,
                f: c.s - h,
                q: Some(c.q),
            };
            return refine(lo, hi, h, &eval).map_or(Next::Skip, Next::Point);
        }
        lo = Bound {
            w: c.w,
            f: c.s - h,
            q: Some(c.q.with_scallop(c.s)),
        };
        guess = c.q.uv;
        w *= BRACKET_GROWTH;
    }
    lo.q.map_or(Next::Skip, Next::Point)
}

/// The cross-section left through a side edge (see [`Next::Skip`]).
#[derive(Debug, Clone, Copy)]
struct SideExit;

/// The point at side offset `w` from `st` (a step shorter than the solved one, so
/// its scallop is at most `h`), or `None` where it cannot be placed (the station is
/// dropped or the section leaves the patch first).
pub fn point_at_offset(patch: &Patch, side: &SideStep, st: &Station, w: f64) -> Option<NextPoint> {
    let mode = mode(patch, st)?;
    match candidate(patch, side, st, mode, w, [f64::NAN; 2])? {
        Ok(c) if !c.beyond => Some(c.q.with_scallop(c.s)),
        _ => None,
    }
}

/// One end of the root bracket: side offset, `s(w) - h`, the point.
#[derive(Debug, Clone, Copy)]
struct Bound {
    w: f64,
    f: f64,
    q: Option<NextPoint>,
}

/// Illinois regula falsi on `s(w) - h` between `lo` (below) and `hi` (above); the
/// answer keeps the scallop at most `h`.
fn refine(
    mut lo: Bound,
    mut hi: Bound,
    h: f64,
    eval: &impl Fn(f64, [f64; 2]) -> Option<Result<Cand, SideExit>>,
) -> Option<NextPoint> {
    let mut last = 0;
    for _ in 0..ROOT_ITERATIONS {
        let fhi = if hi.f.is_finite() { hi.f } else { h };
        let mut w = lo.w - lo.f * (hi.w - lo.w) / (fhi - lo.f);
        if !(w > lo.w && w < hi.w) {
            w = 0.5 * (lo.w + hi.w);
        }
        let guess = lo.q.or(hi.q).map_or([f64::NAN; 2], |q| q.uv);
        let Some(Ok(c)) = eval(w, guess) else {
            break;
        };
        if c.s <= h {
            lo = Bound {
                w: c.w,
                f: c.s - h,
                q: Some(c.q.with_scallop(c.s)),
            };
            if c.s >= h * (1.0 - SCALLOP_REL) || c.beyond {
                break;
            }
            if last == -1 {
                hi.f *= 0.5;
            }
            last = -1;
        } else {
            hi = Bound {
                w: c.w,
                f: c.s - h,
                q: Some(c.q),
            };
            if last == 1 {
                lo.f *= 0.5;
            }
            last = 1;
        }
        if hi.w - lo.w <= MIN_OFFSET {
            break;
        }
    }
    lo.q
}

/// A candidate at a side offset with its scallop height.
struct Cand {
    q: NextPoint,
    /// Scallop height, mm.
    s: f64,
    /// Side offset actually reached, mm.
    w: f64,
    /// True when the cross-section left the patch first: `q` is where it leaves.
    beyond: bool,
    /// Unit surface normal at `q`, toward the tool.
    normal: Vec3,
}

impl NextPoint {
    fn with_scallop(mut self, s: f64) -> NextPoint {
        self.scallop = s;
        self
    }
}

fn candidate(
    patch: &Patch,
    side: &SideStep,
    st: &Station,
    mode: Mode,
    w: f64,
    guess: [f64; 2],
) -> Option<Result<Cand, SideExit>> {
    let p = st.d.point;
    let offset = PlaneEq {
        normal: st.side,
        offset: st.side.dot(&p.coords) + w,
    };
    let section = PlaneEq {
        normal: st.tangent,
        offset: st.tangent.dot(&p.coords),
    };
    let guess = if guess[0].is_finite() {
        guess
    } else {
        side_guess(st, w)
    };
    let (uv, d, beyond) = match mode {
        Mode::Slide(edge) => match on_edge(patch, edge, guess[1 - edge.dir], &offset) {
            Some((uv, d)) => (uv, d, false),
            None => {
                let (uv, d) = corner_beyond(patch, edge, st, &offset)?;
                (uv, d, true)
            }
        },
        Mode::Plane => match two_planes(patch, guess, &section, &offset) {
            Solved::Inside { uv, d } => (uv, d, false),
            Solved::Exit { uv, edge } => {
                let (uv, d) = on_edge(patch, edge, uv[1 - edge.dir], &section)?;
                if along_share(&d, edge, &st.tangent) < HALF {
                    return Some(Err(SideExit));
                }
                (uv, d, true)
            }
            Solved::Failed => return None,
        },
    };
    let q = NextPoint {
        uv,
        point: d.point,
        across: (d.point - p).norm(),
        scallop: 0.0,
        slid: matches!(mode, Mode::Slide(_)),
    };
    Some(Ok(Cand {
        q,
        s: scallop(patch, side, st, &d, uv),
        w: st.side.dot(&(d.point - p)),
        beyond,
        normal: tool_side_normal(&d).unwrap_or(st.normal),
    }))
}

/// How much of the tangent direction `dir` runs along `edge` rather than across it:
/// with `dir = a S_u + b S_v`, the share `|along| / (|along| + |across|)` of the two
/// components (for an edge of fixed u, `b S_v` runs along it and `a S_u` across).
fn along_share(d: &SurfaceDerivs, edge: Edge, dir: &Vec3) -> f64 {
    let (e, f, g) = (d.du.dot(&d.du), d.du.dot(&d.dv), d.dv.dot(&d.dv));
    let det = e * g - f * f;
    if det <= 0.0 {
        return 0.0;
    }
    let (p, q) = (d.du.dot(dir), d.dv.dot(dir));
    let (a, b) = ((g * p - f * q) / det, (e * q - f * p) / det);
    let (across_u, along_v) = ((a * d.du).norm(), (b * d.dv).norm());
    let (across, along) = if edge.dir == 0 {
        (across_u, along_v)
    } else {
        (along_v, across_u)
    };
    if along + across == 0.0 {
        0.0
    } else {
        along / (along + across)
    }
}

/// The end of `edge` that the offset plane lies beyond (the corner where a sliding
/// point leaves the patch).
fn corner_beyond(
    patch: &Patch,
    edge: Edge,
    st: &Station,
    offset: &PlaneEq,
) -> Option<([f64; 2], SurfaceDerivs)> {
    let dom = patch.domain();
    let free = 1 - edge.dir;
    let ends = [0, 1].map(|k| {
        let mut uv = [0.0; 2];
        uv[edge.dir] = dom[edge.dir][edge.end];
        uv[free] = dom[free][k];
        uv
    });
    let ahead = ends
        .into_iter()
        .map(|uv| (uv, patch.derivs(uv[0], uv[1])))
        .filter(|(_, d)| st.side.dot(&(d.point - st.d.point)) > 0.0)
        .max_by(|a, b| {
            let sa = offset.normal.dot(&a.1.point.coords);
            let sb = offset.normal.dot(&b.1.point.coords);
            sa.total_cmp(&sb)
        })?;
    (offset.normal.dot(&ahead.1.point.coords) < offset.offset).then_some(ahead)
}

/// How the station moves (module doc); `None` when it must be dropped.
fn mode(patch: &Patch, st: &Station) -> Option<Mode> {
    let dom = patch.domain();
    let mut plane_ok = true;
    let mut slide: Option<(f64, Edge)> = None;
    for (dir, bounds) in dom.iter().enumerate() {
        let range = bounds[1] - bounds[0];
        for (end, bound) in bounds.iter().enumerate() {
            if (st.uv[dir] - bound).abs() > ON_EDGE_REL * range {
                continue;
            }
            let inward =
                if dir == 0 { st.d.du } else { st.d.dv } * if end == 0 { 1.0 } else { -1.0 };
            let c = along_share(&st.d, Edge { dir, end }, &st.side);
            let threshold = if st.end { END_SLIDE_SHARE } else { HALF };
            if c > threshold && slide.is_none_or(|(b, _)| c > b) {
                slide = Some((c, Edge { dir, end }));
            }
            if st.side.dot(&inward) <= 0.0 {
                plane_ok = false;
            }
        }
    }
    match (slide, plane_ok) {
        (Some((_, edge)), _) => Some(Mode::Slide(edge)),
        (None, true) => Some(Mode::Plane),
        (None, false) => None,
    }
}

/// `uv` moved by about `w` along the side direction (least squares in `S_u, S_v`).
fn side_guess(st: &Station, w: f64) -> [f64; 2] {
    let (a, b) = (st.d.du, st.d.dv);
    let (e, f, g) = (a.dot(&a), a.dot(&b), b.dot(&b));
    let det = e * g - f * f;
    if det == 0.0 {
        return st.uv;
    }
    let (p, q) = (a.dot(&st.side), b.dot(&st.side));
    [
        st.uv[0] + w * (g * p - f * q) / det,
        st.uv[1] + w * (e * q - f * p) / det,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stepping::side_step::ball_step;
    use swarf_tool::Cutter;

    fn point(n: Next) -> NextPoint {
        match n {
            Next::Point(q) => q,
            other => panic!("{other:?}"),
        }
    }

    fn station(p: &Patch, side: &SideStep, uv: [f64; 2]) -> Station {
        let d = p.derivs(uv[0], uv[1]);
        let normal = tool_side_normal(&d).unwrap();
        let tangent = d.du.normalize();
        let sidev = normal.cross(&tangent);
        let sidev = if sidev.y > 0.0 { sidev } else { -sidev };
        Station {
            uv,
            d,
            normal,
            tangent,
            side: sidev,
            step: side.step(-1.0 / 60.0, 0.0),
            radius: 4.0,
            end: uv[0] == 0.0 || uv[0] == 1.0,
        }
    }

    #[test]
    fn cylinder_step_matches_the_exact_circle_form() {
        let p = swarf_testkit::parts::cylinder_patch(1.0);
        let side = SideStep::new(&Cutter::ball(8.0, None).unwrap(), 0.15).unwrap();
        let st = station(&p, &side, [0.5, 0.3]);
        let q = point(next_point(&p, &side, &st));
        // Arc between the CC points on the circle of radius 60.
        let arc = 120.0 * (q.across / 120.0).asin();
        let want = ball_step(4.0, -1.0 / 60.0, 0.15).unwrap();
        assert!((arc - want).abs() < 2e-3 * want, "{arc} vs {want}");
        assert!(q.scallop <= 0.15 && q.scallop >= 0.15 * (1.0 - SCALLOP_REL));
        assert!((q.uv[0] - 0.5).abs() < 1e-9);
    }

    #[test]
    fn far_edge_clamps_then_drops() {
        let p = swarf_testkit::parts::cylinder_patch(1.0);
        let side = SideStep::new(&Cutter::ball(8.0, None).unwrap(), 0.15).unwrap();
        // About 2 mm from the far edge y = 30: the next point is on the edge.
        let st = station(&p, &side, [0.5, 0.97]);
        let q = point(next_point(&p, &side, &st));
        assert!((q.uv[1] - 1.0).abs() < 1e-12 && q.scallop < 0.15);
        // 0.3 mm from it: this tool alone leaves less than h at the edge.
        let st = station(&p, &side, [0.5, 0.995]);
        assert!(matches!(next_point(&p, &side, &st), Next::Covered(_)));
        // On the edge with the side pointing out: dropped.
        let st = station(&p, &side, [0.5, 1.0]);
        assert!(matches!(next_point(&p, &side, &st), Next::Covered(_)));
        // On a side edge (u = 0) the point slides along it.
        let st = station(&p, &side, [0.0, 0.3]);
        let q = point(next_point(&p, &side, &st));
        assert_eq!(q.uv[0], 0.0);
        assert!(q.uv[1] > 0.3);
    }
}
