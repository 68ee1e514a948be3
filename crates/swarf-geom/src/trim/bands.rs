//! Horizontal bands of loop edges for the even-odd inside test.

use super::Uv;

/// Most bands an index has.
const MAX_BANDS: usize = 4096;

/// Edges `(loop, index)` grouped by the `v` bands they overlap.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct Bands {
    v0: f64,
    height: f64,
    bands: Vec<Vec<(u32, u32)>>,
}

impl Bands {
    pub(super) fn new(loops: &[Vec<Uv>]) -> Bands {
        let edges: usize = loops.iter().map(Vec::len).sum();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in loops.iter().flatten() {
            lo = lo.min(p[1]);
            hi = hi.max(p[1]);
        }
        let count = ((edges as f64).sqrt().ceil() as usize).clamp(1, MAX_BANDS);
        let height = (hi - lo) / count as f64;
        let mut bands = vec![Vec::new(); count];
        let index = |v: f64| {
            if height > 0.0 {
                (((v - lo) / height) as usize).min(count - 1)
            } else {
                0
            }
        };
        for (li, l) in loops.iter().enumerate() {
            for k in 0..l.len() {
                let (a, b) = (l[k][1], l[(k + 1) % l.len()][1]);
                for band in &mut bands[index(a.min(b))..=index(a.max(b))] {
                    band.push((li as u32, k as u32));
                }
            }
        }
        Bands {
            v0: lo,
            height,
            bands,
        }
    }

    /// Even-odd count of the loop edges crossed by the ray from `(u, v)` along `+u`.
    pub(super) fn contains(&self, loops: &[Vec<Uv>], u: f64, v: f64) -> bool {
        if !(u.is_finite() && v.is_finite()) || self.bands.is_empty() {
            return false;
        }
        let top = self.v0 + self.height * self.bands.len() as f64;
        if v < self.v0 || v > top {
            return false;
        }
        let k = if self.height > 0.0 {
            (((v - self.v0) / self.height) as usize).min(self.bands.len() - 1)
        } else {
            0
        };
        let mut inside = false;
        for &(li, e) in &self.bands[k] {
            let l = &loops[li as usize];
            let (a, b) = (l[e as usize], l[(e as usize + 1) % l.len()]);
            // Half-open in v so a ray through a vertex counts it once.
            if (a[1] > v) != (b[1] > v) {
                let x = a[0] + (v - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                if x > u {
                    inside = !inside;
                }
            }
        }
        inside
    }
}
