//! Trimming loops: the part of a patch's parameter rectangle that belongs to a face.
//!
//! A CAD face is a patch restricted to a region of its `(u, v)` rectangle bounded by
//! closed loops: one outer loop and any number of holes (STEP `FACE_OUTER_BOUND` and
//! `FACE_BOUND`, IGES 142/144). Here each loop is a polyline in `(u, v)`, sampled by
//! the reader from the exact edge curves within a chordal tolerance in 3D, so that two
//! faces sharing an edge share its sample points (watertight tessellation).
//!
//! **Inside.** A point is inside when a ray along `+u` crosses the loops an odd number
//! of times (even-odd rule: holes need no orientation to be holes). Edges are indexed
//! in horizontal bands of the loops' `v` range so a query reads about `sqrt(n)` edges.
//! [`Trim::new`] still orients the loops (outer counter-clockwise, holes clockwise) so
//! that walking a loop keeps the face on the left, which boundary passes rely on.
//!
//! **Valid loops.** At least three distinct points, finite, a non-zero area, no edge
//! crossing or touching another edge that is not its neighbour on the same loop
//! (a plane sweep over the edges' `u` extents), and every hole inside the outer loop.

mod bands;
mod project;
mod validate;

use crate::error::GeomError;
use bands::Bands;
pub use project::FacePoint;
use serde::{Deserialize, Serialize};

/// A point in a patch's parameter plane, `[u, v]`.
pub type Uv = [f64; 2];

/// The trimming loops of one face, validated and indexed. Build with [`Trim::new`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<Vec<Uv>>", into = "Vec<Vec<Uv>>")]
pub struct Trim {
    loops: Vec<Vec<Uv>>,
    bands: Bands,
}

impl Trim {
    /// Trimming loops in a patch's `(u, v)`: `loops[0]` is the outer loop, the rest
    /// are holes. Each loop is implicitly closed (a last point equal to the first is
    /// dropped, as are repeated consecutive points).
    ///
    /// # Units
    /// Parameter units of the patch.
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] naming `loop[k]` (and the point where it helps)
    /// when there is no loop, a loop has fewer than three distinct points, a point is
    /// not finite, a loop encloses no area, two edges cross or touch, or a hole lies
    /// outside the outer loop.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::trim::Trim;
    /// let square = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    /// let hole = vec![[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]];
    /// let t = Trim::new(vec![square, hole]).unwrap();
    /// assert!(t.contains(0.2, 0.5) && !t.contains(0.5, 0.5) && !t.contains(1.2, 0.5));
    /// let bow = vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 1.0]];
    /// assert!(Trim::new(vec![bow]).unwrap_err().to_string().contains("cross"));
    /// ```
    pub fn new(loops: Vec<Vec<Uv>>) -> Result<Trim, GeomError> {
        let loops = validate::check(loops)?;
        let bands = Bands::new(&loops);
        Ok(Trim { loops, bands })
    }

    /// The loops: `[0]` the outer one, counter-clockwise; then the holes, clockwise.
    pub fn loops(&self) -> &[Vec<Uv>] {
        &self.loops
    }

    /// Whether `(u, v)` is inside the face (even-odd rule; a point exactly on a loop
    /// may go either way).
    pub fn contains(&self, u: f64, v: f64) -> bool {
        self.bands.contains(&self.loops, u, v)
    }

    /// `[[u_min, u_max], [v_min, v_max]]` of the outer loop.
    pub fn uv_box(&self) -> [[f64; 2]; 2] {
        let mut b = [[f64::INFINITY, f64::NEG_INFINITY]; 2];
        for p in &self.loops[0] {
            for d in 0..2 {
                b[d][0] = b[d][0].min(p[d]);
                b[d][1] = b[d][1].max(p[d]);
            }
        }
        b
    }

    /// The parameters `t` in `[0, 1]` where the segment `a + t (b - a)` is inside the
    /// face, as sorted, disjoint intervals (for clipping iso-curves and passes).
    pub fn intervals(&self, a: Uv, b: Uv) -> Vec<[f64; 2]> {
        let mut cuts = vec![0.0, 1.0];
        for l in &self.loops {
            for k in 0..l.len() {
                let (p, q) = (l[k], l[(k + 1) % l.len()]);
                if let Some(t) = segment_cut(a, b, p, q) {
                    cuts.push(t);
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut out: Vec<[f64; 2]> = Vec::new();
        for w in cuts.windows(2) {
            let m = 0.5 * (w[0] + w[1]);
            if w[1] > w[0] && self.contains(a[0] + m * (b[0] - a[0]), a[1] + m * (b[1] - a[1])) {
                match out.last_mut() {
                    Some(last) if last[1] == w[0] => last[1] = w[1],
                    _ => out.push([w[0], w[1]]),
                }
            }
        }
        out
    }

    /// Total number of loop points.
    pub fn point_count(&self) -> usize {
        self.loops.iter().map(Vec::len).sum()
    }
}

impl TryFrom<Vec<Vec<Uv>>> for Trim {
    type Error = GeomError;
    fn try_from(loops: Vec<Vec<Uv>>) -> Result<Trim, GeomError> {
        Trim::new(loops)
    }
}

impl From<Trim> for Vec<Vec<Uv>> {
    fn from(t: Trim) -> Vec<Vec<Uv>> {
        t.loops
    }
}

/// The parameter on `a`-`b` where it crosses the segment `p`-`q`, if they cross.
fn segment_cut(a: Uv, b: Uv, p: Uv, q: Uv) -> Option<f64> {
    let r = [b[0] - a[0], b[1] - a[1]];
    let s = [q[0] - p[0], q[1] - p[1]];
    let den = r[0] * s[1] - r[1] * s[0];
    if den == 0.0 {
        return None;
    }
    let ap = [p[0] - a[0], p[1] - a[1]];
    let t = (ap[0] * s[1] - ap[1] * s[0]) / den;
    let w = (ap[0] * r[1] - ap[1] * r[0]) / den;
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&w)).then_some(t)
}

#[cfg(test)]
mod tests;
