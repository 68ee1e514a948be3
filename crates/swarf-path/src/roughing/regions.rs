//! One level's clearing rings and the order they are cut in.
//!
//! Ring `k` of a level is the boundary of `A_k = {D >= k s}`, where `D` is the
//! distance from the boundary of the tool centre's allowed region `A_0` and `s` the
//! stepover: the waterline loops of the cutter widened by `k s` ([`super::widened`]).
//! Each connected part of `A_k` is a [`Region`]: one outer loop (allowed inside,
//! counter-clockwise, positive area) and the hole loops around the islands in it
//! (clockwise). A region of ring `k + 1` lies in exactly one region of ring `k`, its
//! parent, which makes a forest. Regions are cut children first (post-order): a leaf
//! is where the tool enters the level (the innermost ring of a pocket, entered by a
//! ramp along its own loop), and every parent is cut right after its last child, a
//! stepover outside it, so the cut grows outwards ring by ring and every ring removes
//! a band of one stepover. The tool stays at the level from a child to its parent;
//! it leaves the level only to reach another leaf.
//!
//! Every point of `A_0` is within one stepover of some ring (the distance falls at
//! unit rate towards the boundary), so with a stepover below the tool radius the
//! rings clear the whole level.

use geo::{Area, Contains, Coord, LineString, Polygon};

/// A closed loop of tool-centre positions (first point not repeated).
pub(crate) type Ring = Vec<[f64; 2]>;

/// A connected part of one ring's allowed set.
#[derive(Debug, Clone)]
pub(crate) struct Region {
    /// The ring index `k`.
    pub ring: usize,
    /// Outer loop first, then holes, each in cutting direction (climb).
    pub loops: Vec<Ring>,
    /// Index of the parent region (ring `k - 1`), if any.
    pub parent: Option<usize>,
}

/// The regions of one ring from its loops (waterline orientation: allowed region on
/// the left of travel). Holes belong to the smallest outer loop containing them.
pub(crate) fn regions_of(ring: usize, loops: Vec<Ring>) -> Vec<Region> {
    let (mut outer, mut holes) = (Vec::new(), Vec::new());
    for lp in loops.into_iter().filter(|l| l.len() > 2) {
        let poly = polygon(&lp);
        let area = poly.signed_area();
        if area > 0.0 {
            outer.push((poly, area, lp));
        } else {
            holes.push(lp);
        }
    }
    let mut regions: Vec<Region> = outer
        .iter()
        .map(|(_, _, lp)| Region {
            ring,
            loops: vec![lp.clone()],
            parent: None,
        })
        .collect();
    for hole in holes {
        let p = Coord {
            x: hole[0][0],
            y: hole[0][1],
        };
        let owner = outer
            .iter()
            .enumerate()
            .filter(|(_, (poly, _, _))| poly.contains(&p))
            .min_by(|a, b| a.1.1.total_cmp(&b.1.1).then(a.0.cmp(&b.0)))
            .map(|(k, _)| k);
        if let Some(k) = owner {
            regions[k].loops.push(hole);
        }
    }
    regions
}

/// Sets each region's parent: the region of the ring before whose outer loop holds
/// the first point of its outer loop (`all` holds every ring's regions in ring order;
/// `first_of[k]` is the index of ring `k`'s first region).
pub(crate) fn link_parents(all: &mut [Region], first_of: &[usize]) {
    let outers: Vec<Polygon> = all.iter().map(|r| polygon(&r.loops[0])).collect();
    for i in 0..all.len() {
        let k = all[i].ring;
        if k == 0 {
            continue;
        }
        let p = Coord {
            x: all[i].loops[0][0][0],
            y: all[i].loops[0][0][1],
        };
        let (lo, hi) = (first_of[k - 1], first_of[k]);
        all[i].parent = (lo..hi).find(|&j| outers[j].contains(&p));
    }
}

/// Regions in cutting order (post-order over the forest), each with whether the
/// tool must enter anew (it does not come from a child cut just before).
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
                let fresh = children[node].is_empty();
                order.push((node, fresh));
            }
        }
    }
    order
}

/// A loop as a closed geo polygon.
pub(crate) fn polygon(lp: &[[f64; 2]]) -> Polygon {
    let mut coords: Vec<Coord> = lp.iter().map(|p| Coord { x: p[0], y: p[1] }).collect();
    if let Some(&first) = coords.first() {
        coords.push(first);
    }
    Polygon::new(LineString::new(coords), Vec::new())
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
    fn holes_go_to_the_smallest_outer_loop_and_children_come_first() {
        // Ring 0: a big square with an island; ring 1: two squares inside it.
        let r0 = regions_of(
            0,
            vec![square([0.0, 0.0], 10.0, true), square([0.0, 0.0], 1.0, false)],
        );
        assert_eq!(r0.len(), 1);
        assert_eq!(r0[0].loops.len(), 2);
        let r1 = regions_of(
            1,
            vec![square([-5.0, 0.0], 2.0, true), square([5.0, 0.0], 2.0, true)],
        );
        let mut all: Vec<Region> = r0.into_iter().chain(r1).collect();
        link_parents(&mut all, &[0, 1, 3]);
        assert_eq!(all[1].parent, Some(0));
        assert_eq!(all[2].parent, Some(0));
        let order = cutting_order(&all);
        assert_eq!(order, vec![(1, true), (2, true), (0, false)]);
    }
}
