//! B-rep topology (ISO 10303-42 section 5): shells -> `ADVANCED_FACE` -> bounds ->
//! `EDGE_LOOP` -> `ORIENTED_EDGE` -> `EDGE_CURVE` -> `VERTEX_POINT`, walked by type
//! (never by following arbitrary references, so cyclic files cannot loop), and each
//! face's loops sampled in 3D with every `EDGE_CURVE` sampled once, so faces sharing
//! an edge share its points.

use super::curves::{Geo, sample_edge};
use super::graph::Ent;
use super::surfaces::{Surf, SurfFail, reverse_u, surface};
use super::uv;
use crate::error::IoError;
use std::collections::{HashMap, HashSet};
use swarf_geom::{Face, Patch, Point3, Trim};

/// Two consecutive edges of a loop must meet within this, mm.
pub const LOOP_GAP: f64 = 1e-4;

/// The faces to read, with whether an `ORIENTED_FACE` reverses them: those of the
/// shells in file order, or every face when the file has no shell.
pub fn face_ids(geo: &Geo<'_>) -> Result<Vec<(u64, bool)>, IoError> {
    let g = geo.g;
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for id in &g.ex.order {
        let e = g.parts(*id, None)?[0];
        if e.name == "CLOSED_SHELL" || e.name == "OPEN_SHELL" {
            for f in e.refs(1)? {
                let fe = g.get(f, &["ADVANCED_FACE", "FACE_SURFACE", "ORIENTED_FACE"], &e)?;
                let (f, flip) = if fe.name == "ORIENTED_FACE" {
                    (fe.refr(2)?, !fe.boolean(3)?)
                } else {
                    (f, false)
                };
                if seen.insert(f) {
                    out.push((f, flip));
                }
            }
        }
    }
    if out.is_empty() {
        for id in &g.ex.order {
            let e = g.parts(*id, None)?[0];
            if e.name == "ADVANCED_FACE" || e.name == "FACE_SURFACE" {
                out.push((*id, false));
            }
        }
    }
    Ok(out)
}

/// A face read: its patch and trimming, or why it was skipped.
pub enum FaceResult {
    /// The face.
    Read(Patch, Face),
    /// Skipped: `#id NAME: why`.
    Skipped(IoError),
}

/// Edge samples shared between faces, by `EDGE_CURVE` id, from its start vertex.
pub type EdgeCache = HashMap<u64, Vec<Point3>>;

struct Bound {
    outer: bool,
    points: Vec<Point3>,
    edges: Vec<u64>,
}

/// Reads face `#id`, reversed when `flip` (an `ORIENTED_FACE` said so).
///
/// # Errors
/// Malformed topology or geometry, open or crossing loops: naming the entity.
pub fn face(
    geo: &Geo<'_>,
    (id, flip): (u64, bool),
    cache: &mut EdgeCache,
    chord: f64,
) -> Result<FaceResult, IoError> {
    let g = geo.g;
    let fe = g.parts(id, None)?[0];
    let name = fe.string(0)?;
    let same_sense = fe.boolean(3)? != flip;
    let surface_label = surface_label(g, fe.refr(2)?)?;
    let surf = match surface(geo, fe.refr(2)?, &fe) {
        Ok(s) => s,
        Err(SurfFail::Unsupported(e)) => return Ok(FaceResult::Skipped(e)),
        Err(SurfFail::Bad(e)) => return Err(e),
    };
    let mut bounds = Vec::new();
    for b in fe.refs(1)? {
        let be = g.get(b, &["FACE_OUTER_BOUND", "FACE_BOUND"], &fe)?;
        let le = g.get(be.refr(1)?, &["EDGE_LOOP", "VERTEX_LOOP", "POLY_LOOP"], &be)?;
        if le.name != "EDGE_LOOP" {
            continue; // a loop of one vertex (apex, pole) bounds nothing
        }
        let (points, edges) = match edge_loop(geo, &le, cache, chord) {
            Ok(x) => x,
            Err(SurfFail::Unsupported(e)) => return Ok(FaceResult::Skipped(e)),
            Err(SurfFail::Bad(e)) => return Err(e),
        };
        bounds.push(Bound {
            outer: be.name == "FACE_OUTER_BOUND",
            points,
            edges,
        });
    }
    if bounds.is_empty() {
        return Err(fe.err("expected at least one EDGE_LOOP bound"));
    }
    let mut count: HashMap<u64, usize> = HashMap::new();
    for b in &bounds {
        for e in &b.edges {
            *count.entry(*e).or_default() += 1;
        }
    }
    let seams: Vec<Vec<Point3>> = count
        .iter()
        .filter(|(_, c)| **c > 1)
        .filter_map(|(e, _)| cache.get(e).cloned())
        .collect();
    let all_seam = count.values().all(|c| *c > 1);
    let loops3: Vec<Vec<Point3>> = bounds.iter().map(|b| b.points.clone()).collect();
    let (patch, mut loops) = patch_and_loops(&fe, &surf, &loops3, &seams)?;
    // The outer loop first: the file's FACE_OUTER_BOUND, else the widest in (u, v).
    let outer = bounds
        .iter()
        .position(|b| b.outer)
        .unwrap_or_else(|| widest(&loops));
    loops.swap(0, outer);
    let trim = if all_seam || uv::covers_domain(&loops, patch.domain()) {
        None
    } else {
        Some(Trim::new(loops).map_err(|e| {
            fe.err(format!(
                "trimming loops: {e} (expected closed loops that do not cross, holes inside the \
                 outer loop)"
            ))
        })?)
    };
    let patch = if same_sense { patch } else { reverse_u(&patch) };
    let trim = match (same_sense, trim) {
        (false, Some(t)) => {
            Some(mirror_u(&t, patch.domain()[0]).map_err(|e| fe.err(e.to_string()))?)
        }
        (_, t) => t,
    };
    let face = Face {
        name: (!name.is_empty()).then(|| name.to_string()),
        surface: Some(surface_label),
        trim,
    };
    Ok(FaceResult::Read(patch, face))
}

/// The face's patch and its loops in `(u, v)`.
fn patch_and_loops(
    fe: &Ent<'_>,
    surf: &Surf,
    loops3: &[Vec<Point3>],
    seams: &[Vec<Point3>],
) -> Result<(Patch, uv::UvLoops), IoError> {
    Ok(match surf {
        Surf::Spline(p) => {
            let l = uv::project_loops(p, loops3).map_err(|m| fe.err(m))?;
            (p.clone(), l)
        }
        Surf::Extrusion {
            degree,
            knots,
            points,
            dir,
        } => {
            let p = uv::extrusion(*degree, knots, points, dir, loops3).map_err(|m| fe.err(m))?;
            let l = uv::project_loops(&p, loops3).map_err(|m| fe.err(m))?;
            (p, l)
        }
        s => uv::elementary(s, loops3, seams).map_err(|m| fe.err(m))?,
    })
}

/// `#id NAME` of a surface entity, for reports: a complex entity by its B-spline
/// part, with `(rational)` when it has weights.
fn surface_label(g: &super::graph::Graph<'_>, id: u64) -> Result<String, IoError> {
    let parts = g.parts(id, None)?;
    let has = |n: &str| parts.iter().any(|p| p.name == n);
    let name = if has("B_SPLINE_SURFACE_WITH_KNOTS") {
        "B_SPLINE_SURFACE_WITH_KNOTS"
    } else {
        parts.first().map_or("?", |p| p.name)
    };
    let rational = if has("RATIONAL_B_SPLINE_SURFACE") {
        " (rational)"
    } else {
        ""
    };
    Ok(format!("#{id} {name}{rational}"))
}

/// Index of the loop with the largest `(u, v)` box.
fn widest(loops: &[Vec<[f64; 2]>]) -> usize {
    let area = |l: &Vec<[f64; 2]>| {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in l {
            for d in 0..2 {
                lo[d] = lo[d].min(q[d]);
                hi[d] = hi[d].max(q[d]);
            }
        }
        (hi[0] - lo[0]) * (hi[1] - lo[1])
    };
    (0..loops.len())
        .max_by(|a, b| area(&loops[*a]).total_cmp(&area(&loops[*b])))
        .unwrap_or(0)
}

/// The trim of a patch whose `u` was reversed over `du`: `u -> du0 + du1 - u`.
fn mirror_u(t: &Trim, du: [f64; 2]) -> Result<Trim, swarf_geom::GeomError> {
    let loops = t
        .loops()
        .iter()
        .map(|l| l.iter().map(|q| [du[0] + du[1] - q[0], q[1]]).collect())
        .collect();
    Trim::new(loops)
}

/// The points of an `EDGE_LOOP` (closed implicitly) and its `EDGE_CURVE` ids.
fn edge_loop(
    geo: &Geo<'_>,
    le: &Ent<'_>,
    cache: &mut EdgeCache,
    chord: f64,
) -> Result<(Vec<Point3>, Vec<u64>), SurfFail> {
    let g = geo.g;
    let mut pts: Vec<Point3> = Vec::new();
    let mut edges = Vec::new();
    let oes = le.refs(1)?;
    if oes.is_empty() {
        return Err(le.err("expected at least one ORIENTED_EDGE").into());
    }
    for (k, oe) in oes.iter().enumerate() {
        let oe = g.get(*oe, &["ORIENTED_EDGE"], le)?;
        let forward = oe.boolean(4)?;
        let eid = oe.refr(3)?;
        let ee = g.get(eid, &["EDGE_CURVE"], &oe)?;
        if let std::collections::hash_map::Entry::Vacant(slot) = cache.entry(eid) {
            slot.insert(edge_points(geo, &ee, chord)?);
        }
        let s = &cache[&eid];
        let it: Box<dyn Iterator<Item = &Point3>> = if forward {
            Box::new(s.iter())
        } else {
            Box::new(s.iter().rev())
        };
        let seg: Vec<Point3> = it.copied().collect();
        if let Some(last) = pts.last() {
            let gap = (seg[0] - last).norm();
            if gap > LOOP_GAP {
                return Err(SurfFail::Bad(le.err(format!(
                    "open loop: edge {} (#{}) starts {gap:.3e} mm from the end of the edge before \
                     it (expected consecutive edges to meet within {LOOP_GAP:e} mm)",
                    k + 1,
                    ee.id
                ))));
            }
            pts.extend_from_slice(&seg[1..]);
        } else {
            pts.extend_from_slice(&seg);
        }
        edges.push(eid);
    }
    let gap = (pts[0] - pts[pts.len() - 1]).norm();
    if gap > LOOP_GAP {
        return Err(SurfFail::Bad(le.err(format!(
            "open loop: the last edge ends {gap:.3e} mm from the start of the first (expected \
             within {LOOP_GAP:e} mm)"
        ))));
    }
    if pts.len() > 1 {
        pts.pop();
    }
    Ok((pts, edges))
}

/// Samples of `EDGE_CURVE` `ee` from its start to its end vertex.
fn edge_points(geo: &Geo<'_>, ee: &Ent<'_>, chord: f64) -> Result<Vec<Point3>, SurfFail> {
    let g = geo.g;
    let vertex = |i: usize| -> Result<Point3, IoError> {
        let v = g.get(ee.refr(i)?, &["VERTEX_POINT"], ee)?;
        geo.point(v.refr(1)?, &v)
    };
    let (a, b) = (vertex(1)?, vertex(2)?);
    let curve = geo.curve(ee.refr(3)?, ee)?;
    sample_edge(&curve, a, b, ee.boolean(4)?, chord).map_err(|m| SurfFail::Bad(ee.err(m)))
}
