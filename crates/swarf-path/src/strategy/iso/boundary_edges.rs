//! The edges of a face that boundary passes run along: the four sides of the patch
//! rectangle for a whole patch; for a trimmed face its trimming loops (outer and
//! holes), which replace the sides (a side outside the trim bounds nothing). A loop
//! is parameterised by its uv arc length, closed back to its first point.

use swarf_geom::Part;
use swarf_geom::trim::Uv;

/// One edge curve in a patch's `(u, v)`.
pub enum Edge<'a> {
    /// The side where parameter `dir` (0: u, 1: v) equals `fixed`; the other
    /// parameter runs over `free`.
    Side {
        /// Which parameter is fixed.
        dir: usize,
        /// Its value.
        fixed: f64,
        /// Range of the other parameter.
        free: [f64; 2],
    },
    /// A closed trimming loop and its cumulative uv chord lengths (one more than points).
    Loop(&'a [Uv], Vec<f64>),
}

impl Edge<'_> {
    /// The parameter range of the edge.
    pub fn range(&self) -> [f64; 2] {
        match self {
            Edge::Side { free, .. } => *free,
            Edge::Loop(_, s) => [0.0, *s.last().unwrap_or(&0.0)],
        }
    }

    /// The `(u, v)` at parameter `t` of the edge.
    pub fn uv(&self, t: f64) -> (f64, f64) {
        match self {
            Edge::Side { dir, fixed, .. } => {
                if *dir == 0 {
                    (*fixed, t)
                } else {
                    (t, *fixed)
                }
            }
            Edge::Loop(pts, s) => {
                let n = pts.len();
                let k = s.partition_point(|&x| x <= t).clamp(1, n) - 1;
                let (a, b) = (pts[k], pts[(k + 1) % n]);
                let len = s[k + 1] - s[k];
                let w = if len > 0.0 {
                    ((t - s[k]) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]))
            }
        }
    }
}

/// The edges of face `face` of `part` (module doc).
pub fn face_edges(part: &Part, face: usize) -> Vec<Edge<'_>> {
    if let Some(trim) = part.trim(face) {
        return trim
            .loops()
            .iter()
            .map(|l| {
                let mut s = vec![0.0];
                for k in 0..l.len() {
                    let (a, b) = (l[k], l[(k + 1) % l.len()]);
                    let d = (b[0] - a[0]).hypot(b[1] - a[1]);
                    s.push(s[k] + d);
                }
                Edge::Loop(l, s)
            })
            .collect();
    }
    let dom = part.patches[face].domain();
    let mut out = Vec::new();
    for (dir, bounds) in dom.iter().enumerate() {
        for &fixed in bounds {
            out.push(Edge::Side {
                dir,
                fixed,
                free: dom[1 - dir],
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::trim::Trim;

    #[test]
    fn loop_edges_walk_the_loop_and_close() {
        let sq = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]];
        let t = Trim::new(vec![sq]).unwrap();
        let s = vec![0.0, 2.0, 3.0, 5.0, 6.0];
        let e = Edge::Loop(&t.loops()[0], s);
        assert_eq!(e.range(), [0.0, 6.0]);
        assert_eq!(e.uv(1.0), (1.0, 0.0));
        assert_eq!(e.uv(2.5), (2.0, 0.5));
        assert_eq!(e.uv(5.5), (0.0, 0.5));
        assert_eq!(e.uv(6.0), (0.0, 0.0));
    }
}
