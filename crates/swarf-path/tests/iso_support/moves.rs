//! The straight cutting moves of a tool path, found near a point through a hierarchy of
//! bounding boxes over each pass's consecutive moves (a pass is a coherent curve, so
//! the boxes of halves of it nest tightly). Written for the oracles alone: the
//! planners index their moves otherwise (a uniform grid), and nothing here is shared
//! with them.

use swarf_geom::{Point3, Vec3};
use swarf_path::Plan;

/// Moves per leaf of the hierarchy.
const LEAF: usize = 8;

/// A node: the XY box of moves `first..last`, and its two halves unless it is a leaf.
struct Node {
    lo: [f64; 2],
    hi: [f64; 2],
    first: usize,
    last: usize,
    halves: Option<(usize, usize)>,
}

/// Moves (segments between consecutive points of each pass, a lone point as a zero
/// segment) in one box hierarchy per pass.
pub struct Moves {
    /// The moves.
    pub segs: Vec<(Point3, Point3)>,
    nodes: Vec<Node>,
    roots: Vec<usize>,
}

impl Moves {
    /// The cutting moves of `plan`, each CL point raised by `lift` along z.
    pub fn new(plan: &Plan, lift: f64) -> Moves {
        let mut moves = Moves {
            segs: Vec::new(),
            nodes: Vec::new(),
            roots: Vec::new(),
        };
        for pass in &plan.toolpath.passes {
            let c: Vec<Point3> = pass
                .points
                .iter()
                .map(|p| p.pose.cl + lift * Vec3::z())
                .collect();
            let first = moves.segs.len();
            if c.len() == 1 {
                moves.segs.push((c[0], c[0]));
            }
            moves.segs.extend(c.windows(2).map(|w| (w[0], w[1])));
            let last = moves.segs.len();
            if last > first {
                let root = moves.build(first, last);
                moves.roots.push(root);
            }
        }
        moves
    }

    /// The node over moves `first..last` (not empty), its halves built first.
    fn build(&mut self, first: usize, last: usize) -> usize {
        let halves = (last - first > LEAF).then(|| {
            let mid = first + (last - first) / 2;
            (self.build(first, mid), self.build(mid, last))
        });
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (a, b) in &self.segs[first..last] {
            for p in [a, b] {
                lo = [lo[0].min(p.x), lo[1].min(p.y)];
                hi = [hi[0].max(p.x), hi[1].max(p.y)];
            }
        }
        self.nodes.push(Node {
            lo,
            hi,
            first,
            last,
            halves,
        });
        self.nodes.len() - 1
    }

    /// Calls `f` with the index (into [`Moves::segs`]) of every move whose XY box,
    /// grown by `reach`, meets the XY box `[lo, hi]`: every move within `reach` of it,
    /// and maybe a few more.
    pub fn for_each_near(&self, lo: [f64; 2], hi: [f64; 2], reach: f64, f: &mut impl FnMut(usize)) {
        for &root in &self.roots {
            self.visit(root, lo, hi, reach, f);
        }
    }

    fn visit(&self, k: usize, lo: [f64; 2], hi: [f64; 2], reach: f64, f: &mut impl FnMut(usize)) {
        let n = &self.nodes[k];
        let apart = (0..2).any(|i| n.lo[i] - reach > hi[i] || n.hi[i] + reach < lo[i]);
        if apart {
            return;
        }
        match n.halves {
            Some((a, b)) => {
                self.visit(a, lo, hi, reach, f);
                self.visit(b, lo, hi, reach, f);
            }
            None => {
                for s in n.first..n.last {
                    let (a, b) = &self.segs[s];
                    let away = (0..2)
                        .any(|i| a[i].min(b[i]) - reach > hi[i] || a[i].max(b[i]) + reach < lo[i]);
                    if !away {
                        f(s);
                    }
                }
            }
        }
    }
}
