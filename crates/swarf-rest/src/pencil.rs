//! Flow-cut (pencil) cleanup (thesis 002 §5.4): passes along the cleanup tool's
//! curves of bitangency, with parallel passes on each side.
//!
//! **The locus.** The cleanup tool's bitangency points are found as the reference
//! tool's are: crease scans in two directions ([`crate::detect::reference_pairs`]
//! with the cleanup tool); each is a CL point where the tool touches both sides of
//! a valley at once, at the exact drop height. Those inside a region are grouped by
//! the spatial directory (pitch half the cleanup tool's radius) and ordered into
//! chains ([`crate::order`]).
//!
//! **Densifying.** Between two neighbouring locus points the CL curve of the valley
//! is the crease of two sheets (the tool resting on one side or the other), and the
//! straight move between them may cut under the sheet it drifts onto. The drop at
//! the XY midpoint tells: when it is above the chord by more than the tolerance, the
//! locus point between them is found where the line through the midpoint across the
//! chord crosses the crease ([`swarf_path::track::crease_track`]) and inserted, and
//! both halves are checked again. Where no crease is found (the valley ends or
//! branches) the chain is cut there, so every CL point of a pencil pass is a double
//! contact and no move leaves the CL surface by more than the tolerance at its
//! midpoint.
//!
//! **Parallel passes.** Up to `passes` more on each side, offset in XY from the
//! centre pass along its normals at a constant stepover along the surface
//! ([`crate::stepping`]), dropped onto the part as any track
//! ([`swarf_path::track::drop_track`]) and clipped to the region.

use crate::pair::{DepthProbe, RestPair};
use crate::pocket::MIN_STEP_FRACTION;
use crate::region::RestRegion;
use crate::stepping::step_out;
use geo::{Contains, Point};
use swarf_geom::TriMesh;
use swarf_path::track::{Track, crease_track, drop_track};
use swarf_tool::Pose;
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::{Pass, PathPoint};

/// Deepest recursion of the densification (each level halves a gap).
pub const MAX_SPLITS: usize = 24;
/// Gaps shorter than this are not split further, mm.
pub const MIN_GAP: f64 = 1e-4;

/// How a region's pencil passes are made.
pub struct Pencil<'a> {
    /// The part.
    pub mesh: &'a TriMesh,
    /// The part prepared for the cleanup tool.
    pub dropper: &'a MeshDropper,
    /// Depths under the cleanup tool (made from `dropper`).
    pub probe: DepthProbe<'a>,
    /// Chordal tolerance, mm.
    pub tolerance: f64,
    /// Parallel passes on each side.
    pub passes: usize,
    /// Distance between parallel passes, mm.
    pub stepover: f64,
}

impl Pencil<'_> {
    /// The pencil passes of `region` from the locus `chains` (ordered pairs of the
    /// cleanup tool inside it), side by side: the outermost on the left first, then
    /// inwards, the centre, and out to the right, every other one reversed.
    pub fn passes(&self, region: &RestRegion, chains: &[Vec<RestPair>]) -> Vec<Pass> {
        let mut scratch = DropScratch::default();
        let mut out = Vec::new();
        for chain in chains {
            for centre in self.densify(chain, &mut scratch) {
                let first = vec![Pass {
                    points: centre.iter().map(point_of).collect(),
                    ..Pass::default()
                }];
                let side = |sign: f64, scratch: &mut DropScratch| {
                    step_out(
                        &first,
                        self.stepover,
                        MIN_STEP_FRACTION * self.stepover,
                        self.passes,
                        |d| {
                            let track = Track::new(&offset(&centre, sign * d))?;
                            let got = drop_track(
                                self.mesh,
                                self.dropper,
                                &track,
                                self.tolerance,
                                scratch,
                            );
                            let kept: Vec<Pass> = got
                                .pieces
                                .into_iter()
                                .flat_map(|p| clip(p, region))
                                .collect();
                            (!kept.is_empty()).then_some(kept)
                        },
                    )
                };
                let left = side(1.0, &mut scratch);
                let right = side(-1.0, &mut scratch);
                out.extend(left.into_iter().rev().flatten());
                out.extend(first);
                out.extend(right.into_iter().flatten());
            }
        }
        for (k, p) in out.iter_mut().enumerate() {
            if k % 2 == 1 {
                p.points.reverse();
            }
        }
        out
    }

    /// The chain with locus points inserted where a move would leave the CL surface
    /// (module doc), cut where none is found.
    fn densify(&self, chain: &[RestPair], scratch: &mut DropScratch) -> Vec<Vec<RestPair>> {
        let mut out: Vec<Vec<RestPair>> = Vec::new();
        let mut cur: Vec<RestPair> = Vec::new();
        for q in chain {
            match cur.last() {
                None => cur.push(*q),
                Some(p) => {
                    let mut between = Vec::new();
                    if self.fill(p, q, 0, scratch, &mut between) {
                        cur.extend(between);
                    } else {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.push(*q);
                }
            }
        }
        out.push(cur);
        out.retain(|c| c.len() > 1);
        out
    }

    /// Pushes the locus points needed between `p` and `q`; false when the crease is
    /// lost between them.
    fn fill(
        &self,
        p: &RestPair,
        q: &RestPair,
        level: usize,
        scratch: &mut DropScratch,
        out: &mut Vec<RestPair>,
    ) -> bool {
        let (mx, my) = (0.5 * (p.cl.x + q.cl.x), 0.5 * (p.cl.y + q.cl.y));
        let Some(hit) = self.dropper.drop(mx, my, scratch) else {
            return false;
        };
        if hit.z - 0.5 * (p.cl.z + q.cl.z) <= self.tolerance {
            return true;
        }
        let (dx, dy) = (q.cl.x - p.cl.x, q.cl.y - p.cl.y);
        let len = dx.hypot(dy);
        if level >= MAX_SPLITS || len < MIN_GAP {
            return false;
        }
        let half = len.max(self.dropper.tool().radius() * 0.5);
        let (nx, ny) = (-dy / len * half, dx / len * half);
        let Some(track) = Track::new(&[[mx - nx, my - ny], [mx + nx, my + ny]]) else {
            return false;
        };
        let found = crease_track(self.mesh, self.dropper, &track, self.tolerance, scratch)
            .into_iter()
            .filter_map(|d| self.probe.valley(&d))
            .min_by(|a, b| {
                let d = |r: &RestPair| (r.cl.x - mx).hypot(r.cl.y - my);
                d(a).total_cmp(&d(b))
            });
        let Some(r) = found else {
            return false;
        };
        if !self.fill(p, &r, level + 1, scratch, out) {
            return false;
        }
        out.push(r);
        self.fill(&r, q, level + 1, scratch, out)
    }
}

/// The path point of a locus pair: its CL point (the contact is a pair, not one
/// point, and is left out).
fn point_of(p: &RestPair) -> PathPoint {
    PathPoint::new(Pose::vertical(p.cl))
}

/// The XY polyline of `centre` offset by `d` to its left (per-vertex normals: the
/// mean of the adjacent pieces' normals).
fn offset(centre: &[RestPair], d: f64) -> Vec<[f64; 2]> {
    let pts: Vec<[f64; 2]> = centre.iter().map(|p| [p.cl.x, p.cl.y]).collect();
    let n = pts.len();
    let normal = |a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l = dx.hypot(dy);
        if l > 0.0 {
            [-dy / l, dx / l]
        } else {
            [0.0, 0.0]
        }
    };
    (0..n)
        .map(|k| {
            let before = if k > 0 {
                normal(pts[k - 1], pts[k])
            } else {
                [0.0, 0.0]
            };
            let after = if k + 1 < n {
                normal(pts[k], pts[k + 1])
            } else {
                [0.0, 0.0]
            };
            let (sx, sy) = (before[0] + after[0], before[1] + after[1]);
            let l = sx.hypot(sy);
            let m = if l > 0.0 {
                [sx / l, sy / l]
            } else {
                [0.0, 0.0]
            };
            [pts[k][0] + d * m[0], pts[k][1] + d * m[1]]
        })
        .collect()
}

/// The runs of `piece` inside `region`'s boundary, as passes of two points or more.
pub(crate) fn clip(piece: Vec<PathPoint>, region: &RestRegion) -> Vec<Pass> {
    let mut out = Vec::new();
    let mut cur: Vec<PathPoint> = Vec::new();
    for p in piece {
        if region
            .boundary
            .contains(&Point::new(p.pose.cl.x, p.pose.cl.y))
        {
            cur.push(p);
        } else if !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
    }
    out.push(cur);
    out.into_iter()
        .filter(|c| c.len() > 1)
        .map(|points| Pass {
            points,
            ..Pass::default()
        })
        .collect()
}
