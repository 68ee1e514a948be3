//! One level's clearing rings and the order they are cut in.
//!
//! Ring `k` of a level is the boundary of `A_k = {D >= d_k}`, where `D` is the
//! distance from the boundary of the tool centre's allowed region `A_0` and
//! `d_k = s_0 + ... + s_(k-1)` the stepovers of the rings outside it (each ring's
//! own, from its corner radius: `corners.rs`): `A_0` from the waterline contour of
//! the level, `A_k` its inward offset by `d_k` (geo's buffers). Each connected part of `A_k` is a [`Region`]: an outer
//! loop (allowed inside, counter-clockwise) and the hole loops round the islands in
//! it (clockwise). A region of ring `k + 1` lies in exactly one region of ring `k`,
//! its parent, which makes a forest. Regions are cut children first (post-order): a
//! leaf is where the tool enters the level (the innermost ring of a pocket, entered
//! by a ramp along its own loop), and every parent is cut right after its last
//! child, a stepover outside it, so the cut grows outwards ring by ring and every
//! ring removes a band of its stepover. The tool stays at the level from a child to
//! its parent; it leaves the level only to reach another leaf.
//!
//! Every point of `A_0` is within one stepover of some ring (the distance falls at
//! unit rate towards the boundary), so with a stepover below the tool radius the
//! rings clear the whole level. A sharp inner region (too narrow to open) is not
//! made a ring when the tool on the ring outside it reaches all of it
//! ([`covered`]): its ring would only pivot in material already cut.

use super::corners::{loops_of, offset, opened};
use geo::{Area, BooleanOps, Contains, Coord, LineString, MultiPolygon, Polygon};

/// A ridge is farther than the stepover times this from every child: the band of a
/// right-angled corner is `s √2` wide at its apex (`corners.rs`), and a little more
/// is the polygon offsets' noise.
const RIDGE_REACH: f64 = 1.45;
/// Smaller ridges (in squared reaches) are noise of the polygon offsets.
const RIDGE_AREA: f64 = 2.0;

/// A closed loop of tool-centre positions (first point not repeated).
pub(crate) type Ring = Vec<[f64; 2]>;

/// A connected part of one ring's allowed set.
#[derive(Debug, Clone)]
pub(crate) struct Region {
    /// The ring index `k`.
    pub ring: usize,
    /// The loops to cut: outer first, then holes, each in cutting direction (climb);
    /// rounded when the rings are.
    pub loops: Vec<Ring>,
    /// The part of `A_k` itself (not rounded).
    pub outline: Polygon,
    /// What the loops bound (the outline opened, or the outline).
    pub shape: MultiPolygon,
    /// Index of the parent region (ring `k - 1`), if any.
    pub parent: Option<usize>,
    /// The radius that opened the loops (`None`: left sharp).
    pub rho: Option<f64>,
}

/// `A_0` as polygons from the level's contour loops (waterline orientation: the
/// allowed region on the left of travel). Holes belong to the smallest outer loop
/// containing them.
pub(crate) fn allowed(loops: Vec<Ring>) -> Vec<Polygon> {
    let (mut outer, mut holes) = (Vec::new(), Vec::new());
    for lp in loops.into_iter().filter(|l| l.len() > 2) {
        let ls = line(&lp);
        let area = Polygon::new(ls.clone(), Vec::new()).signed_area();
        if area > 0.0 {
            outer.push((ls, area, Vec::new()));
        } else {
            holes.push(ls);
        }
    }
    for hole in holes {
        let p = hole.0[0];
        let owner = outer
            .iter()
            .enumerate()
            .filter(|(_, (ls, _, _))| Polygon::new(ls.clone(), Vec::new()).contains(&p))
            .min_by(|a, b| a.1.1.total_cmp(&b.1.1).then(a.0.cmp(&b.0)))
            .map(|(k, _)| k);
        if let Some(k) = owner {
            outer[k].2.push(hole);
        }
    }
    outer
        .into_iter()
        .map(|(ls, _, holes)| Polygon::new(ls, holes))
        .collect()
}

/// The regions of ring `k`: `A_0` offset inwards by `d` (the stepovers of the rings
/// outside it), each part opened by `rho` when given ([`super::corners`]).
pub(crate) fn ring_regions(a0: &[Polygon], k: usize, d: f64, rho: Option<f64>) -> Vec<Region> {
    let parts: Vec<Polygon> = if k == 0 {
        a0.to_vec()
    } else {
        a0.iter().flat_map(|p| offset(p, -d)).collect()
    };
    parts
        .into_iter()
        .filter(|p| p.unsigned_area() > 0.0)
        .map(|outline| {
            let (cut, rho) = match rho.and_then(|r| opened(&outline, r)) {
                Some((cut, r)) => (cut, Some(r)),
                None => (MultiPolygon::new(vec![outline.clone()]), None),
            };
            Region {
                ring: k,
                loops: cut.iter().flat_map(loops_of).collect(),
                outline,
                shape: cut,
                parent: None,
                rho,
            }
        })
        .collect()
}

/// Whether a tool of radius `reach` on the loops of `outer` covers all of
/// `region`: it is thinner than `2 margin` (nothing is left of it eroded by
/// `margin`), and every vertex of its outline is within `reach - margin` of a loop.
pub(crate) fn covered(region: &Region, outer: &[Region], reach: f64, margin: f64) -> bool {
    if offset(&region.outline, -margin).unsigned_area() > 0.0 {
        return false;
    }
    let loops: Vec<&Ring> = outer.iter().flat_map(|r| &r.loops).collect();
    region.outline.exterior().0.iter().all(|c| {
        loops
            .iter()
            .any(|lp| distance_to_loop(lp, [c.x, c.y]).1 + margin <= reach)
    })
}

/// The point of the closed loop `lp` nearest `q`: the index `j` of the segment
/// from `lp[j]` to `lp[j + 1]` it lies on, its distance, and the point.
pub(crate) fn distance_to_loop(lp: &[[f64; 2]], q: [f64; 2]) -> (usize, f64, [f64; 2]) {
    let n = lp.len();
    let mut best = (0, f64::INFINITY, lp.first().copied().unwrap_or(q));
    for j in 0..n {
        let (a, b) = (lp[j], lp[(j + 1) % n]);
        let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = ux * ux + uy * uy;
        let t = if len2 > 0.0 {
            (((q[0] - a[0]) * ux + (q[1] - a[1]) * uy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let p = [a[0] + t * ux, a[1] + t * uy];
        let d = (q[0] - p[0]).hypot(q[1] - p[1]);
        if d < best.1 {
            best = (j, d, p);
        }
    }
    best
}

/// Adds, as leaves inside each region that has children, the parts of it farther
/// than its ring's stepover (`steps[k]` for ring `k`, times [`RIDGE_REACH`]) from
/// every child: ridges of
/// the distance from the boundary (a band between two islands that closes before
/// the next ring), where the region's own loops would have uncut material on both
/// sides. Cut first, by a ramp along their outline, they leave the loops one band.
pub(crate) fn add_ridges(all: &mut Vec<Region>, steps: &[f64]) {
    let n = all.len();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, r) in all.iter().enumerate() {
        if let Some(p) = r.parent {
            children[p].push(i);
        }
    }
    for (p, kids) in children.iter().enumerate() {
        if kids.is_empty() {
            continue;
        }
        let reach = steps.get(all[p].ring).copied().unwrap_or(0.0) * RIDGE_REACH;
        let near: Vec<Polygon> = kids
            .iter()
            .flat_map(|&c| all[c].shape.0.iter().flat_map(|g| offset(g, reach)))
            .collect();
        let far = all[p].shape.difference(&MultiPolygon::new(near));
        for part in far {
            if part.unsigned_area() < RIDGE_AREA * reach * reach {
                continue;
            }
            all.push(Region {
                ring: all[p].ring + 1,
                loops: loops_of(&part),
                shape: MultiPolygon::new(vec![part.clone()]),
                outline: part,
                parent: Some(p),
                rho: None,
            });
        }
    }
}

/// Sets each region's parent: the region of the ring before whose outline holds the
/// first point of its own (`all` holds every ring's regions in ring order;
/// `first_of[k]` is the index of ring `k`'s first region).
pub(crate) fn link_parents(all: &mut [Region], first_of: &[usize]) {
    for i in 0..all.len() {
        let k = all[i].ring;
        if k == 0 {
            continue;
        }
        let p = all[i].outline.exterior().0[0];
        let (lo, hi) = (first_of[k - 1], first_of[k]);
        all[i].parent = (lo..hi).find(|&j| all[j].outline.contains(&p));
    }
}

/// Regions in cutting order (post-order over the forest), each with whether it is
/// a leaf (the tool enters there).
pub(crate) fn cutting_order(all: &[Region]) -> Vec<(usize, bool)> {
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); all.len()];
    let mut roots = Vec::new();
    for (i, r) in all.iter().enumerate() {
        match r.parent {
            Some(p) => children[p].push(i),
            None => roots.push(i),
        }
    }
    let mut order = Vec::with_capacity(all.len());
    for root in roots {
        // Iterative post-order: (node, next child to visit).
        let mut stack = vec![(root, 0usize)];
        while let Some(&mut (node, ref mut next)) = stack.last_mut() {
            if let Some(&c) = children[node].get(*next) {
                *next += 1;
                stack.push((c, 0));
            } else {
                stack.pop();
                order.push((node, children[node].is_empty()));
            }
        }
    }
    order
}

/// A loop as a closed line string.
fn line(lp: &[[f64; 2]]) -> LineString {
    let mut coords: Vec<Coord> = lp.iter().map(|p| Coord { x: p[0], y: p[1] }).collect();
    coords.push(coords[0]);
    LineString::new(coords)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(c: [f64; 2], h: f64, ccw: bool) -> Ring {
        let mut lp = vec![
            [c[0] - h, c[1] - h],
            [c[0] + h, c[1] - h],
            [c[0] + h, c[1] + h],
            [c[0] - h, c[1] + h],
        ];
        if !ccw {
            lp.reverse();
        }
        lp
    }

    #[test]
    fn a_dumbbell_splits_and_its_lobes_are_cut_first() {
        // Two 20 x 20 squares joined by a 4 wide neck, an island in the left one.
        let shape = vec![
            [0.0, 0.0],
            [20.0, 0.0],
            [20.0, 8.0],
            [30.0, 8.0],
            [30.0, 0.0],
            [50.0, 0.0],
            [50.0, 20.0],
            [30.0, 20.0],
            [30.0, 12.0],
            [20.0, 12.0],
            [20.0, 20.0],
            [0.0, 20.0],
        ];
        let a0 = allowed(vec![shape, square([10.0, 10.0], 1.0, false)]);
        assert_eq!(a0.len(), 1);
        assert_eq!(a0[0].interiors().len(), 1);
        let mut all = ring_regions(&a0, 0, 0.0, None);
        assert!(all.iter().all(|r| r.rho.is_none()));
        let mut first_of = vec![0];
        for k in 1..4 {
            first_of.push(all.len());
            all.extend(ring_regions(&a0, k, 3.0 * k as f64, None));
        }
        first_of.push(all.len());
        // Ring 1 (3 in) keeps the 4 wide neck? No: it closes at 2 in, so two lobes.
        assert_eq!(first_of[2] - first_of[1], 2);
        link_parents(&mut all, &first_of);
        assert!(all[1..].iter().all(|r| r.parent.is_some()));
        let order = cutting_order(&all);
        assert_eq!(order.last(), Some(&(0, false)));
        let leaves = order.iter().filter(|o| o.1).count();
        assert_eq!(leaves, 2, "one entry per lobe: {order:?}");
    }
}
