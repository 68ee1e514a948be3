//! Clipping planned passes to trimmed faces: the one clip used by all three iso
//! strategies.
//!
//! The iso strategies plan on a face's whole patch rectangle; a trimmed face keeps
//! only the part of each pass whose CC points lie inside its trimming loops. A pass
//! is walked in order; where consecutive CC points change side (in or out of
//! [`swarf_geom::trim::Trim::contains`]), the crossing is found by bisection on the straight uv
//! segment between them ([`CROSSING_STEPS`] halvings, so within `2^-40` of the
//! segment's uv length) and the pass is ended (or started) at the CL point of the
//! inside end of the bracket. Pieces whose CC polyline is shorter than the tolerance
//! are dropped. Passes on faces without a trim are returned untouched, so untrimmed
//! parts plan exactly as before. The trim boundary itself is then covered by the
//! boundary passes ([`crate::strategy::iso::boundary`]), as patch edges are.

use crate::ordering::Row;
use crate::strategy::iso::setup::IsoSetup;
use swarf_geom::Part;
use swarf_toolpath::{Pass, PathPoint};

/// Halvings locating where a pass crosses a trimming loop.
const CROSSING_STEPS: usize = 40;

/// Whether the contact of `p` lies inside its face's trimming loops (points without
/// a contact, and on faces without a trim, count as inside).
pub fn inside(part: &Part, p: &PathPoint) -> bool {
    p.contact.is_none_or(|c| {
        part.trim(c.face)
            .is_none_or(|t| t.contains(c.uv[0], c.uv[1]))
    })
}

/// `rows` with every pass clipped to its face (module doc).
pub fn clip_rows(setup: &IsoSetup<'_>, rows: Vec<Row>) -> Vec<Row> {
    let part = setup.part;
    if part.faces.iter().all(|f| f.trim.is_none()) {
        return rows;
    }
    rows.into_iter()
        .map(|row| row.into_iter().flat_map(|p| clip_pass(setup, p)).collect())
        .filter(|row: &Row| !row.is_empty())
        .collect()
}

/// The pieces of `pass` inside its face (module doc).
pub fn clip_pass(setup: &IsoSetup<'_>, pass: Pass) -> Vec<Pass> {
    let part = setup.part;
    let trimmed = |p: &PathPoint| p.contact.is_some_and(|c| part.trim(c.face).is_some());
    if !pass.points.iter().any(trimmed) {
        return vec![pass];
    }
    let min_length = setup.params.finish.tolerance;
    let mut out = Vec::new();
    let mut piece: Vec<PathPoint> = Vec::new();
    let mut prev: Option<(PathPoint, bool)> = None;
    for p in pass.points {
        let now = inside(part, &p);
        if let Some((q, was)) = prev
            && was != now
        {
            let (a, b) = if was { (&q, &p) } else { (&p, &q) };
            if let Some(x) = crossing(setup, a, b) {
                piece.push(x);
            }
            if was {
                push_piece(&mut out, std::mem::take(&mut piece), pass.skim, min_length);
            }
        }
        if now {
            piece.push(p);
        }
        prev = Some((p, now));
    }
    push_piece(&mut out, piece, pass.skim, min_length);
    out
}

fn push_piece(out: &mut Vec<Pass>, points: Vec<PathPoint>, skim: Option<f64>, min_length: f64) {
    let length: f64 = points
        .windows(2)
        .filter_map(|w| Some((w[1].contact?.point - w[0].contact?.point).norm()))
        .sum();
    if points.len() >= 2 && length >= min_length {
        out.push(Pass {
            points,
            skim: if out.is_empty() { skim } else { None },
            clear_from: None,
        });
    }
}

/// The CL point where the uv segment from `a` (inside) to `b` (outside) leaves the
/// face, on the inside of the bisection bracket; `None` when it cannot be evaluated
/// or the two points are on different patches.
fn crossing(setup: &IsoSetup<'_>, a: &PathPoint, b: &PathPoint) -> Option<PathPoint> {
    let (ca, cb) = (a.contact?, b.contact?);
    if ca.face != cb.face {
        return None;
    }
    let at = |t: f64| {
        [
            ca.uv[0] + t * (cb.uv[0] - ca.uv[0]),
            ca.uv[1] + t * (cb.uv[1] - ca.uv[1]),
        ]
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..CROSSING_STEPS {
        let mid = 0.5 * (lo + hi);
        let [u, v] = at(mid);
        if setup.part.trim(ca.face).is_none_or(|t| t.contains(u, v)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if lo == 0.0 {
        return None;
    }
    let [u, v] = at(lo);
    setup.reachable(&setup.cl_map(ca.face), u, v)
}
