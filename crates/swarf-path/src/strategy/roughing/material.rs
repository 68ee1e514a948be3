//! Where a ring meets material: the whole ring, stretches of it, or none of it.
//!
//! A point of a ring meets material when the stock stands above the level
//! ([`super::MATERIAL_EPS`]) at the point or at samples round it (16 directions at
//! 0.35, 0.7, 0.98 and 1.2 tool radii: the last a margin, so that the samples'
//! gaps at the rim do not let a stretch end on material). The ring is sampled at most
//! half a radius apart, so nothing as wide as the tool between two of its points is
//! missed. A ring that meets material only in stretches (rest roughing: what the
//! previous tool left in corners) is cut in those stretches, each lengthened by one
//! sample at either end so that it starts and ends clear of material, where the
//! tool may come down from above.

use super::regions::Ring;
use super::{MATERIAL_EPS, RoughingStock};

/// Samples of a ring at most this many tool radii apart.
const SPACING: f64 = 0.5;
/// Directions sampled round a point.
const DIRECTIONS: usize = 16;
/// Radii sampled, in tool radii.
const RADII: [f64; 4] = [0.35, 0.7, 0.98, 1.2];

/// How much of a ring meets material.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Reach {
    /// All of it (or enough that it is cut whole).
    Whole,
    /// These stretches (open paths, ends clear of material).
    Stretches(Vec<Ring>),
}

/// How much of `lp` meets material above `z` for a tool of `radius` (module doc);
/// `None` when none of it does.
pub(crate) fn reach(lp: &Ring, z: f64, radius: f64, stock: &RoughingStock<'_>) -> Option<Reach> {
    let pts = densified(lp, SPACING * radius);
    let near: Vec<bool> = pts
        .iter()
        .map(|p| near_material(*p, z, radius, stock))
        .collect();
    let Some(clear) = near.iter().position(|n| !n) else {
        return Some(Reach::Whole);
    };
    if !near.contains(&true) {
        return None;
    }
    // From a clear point round the loop: runs of near points, each with the clear
    // point before and after it.
    let n = pts.len();
    let mut stretches = Vec::new();
    let mut run: Vec<[f64; 2]> = Vec::new();
    for k in 0..=n {
        let i = (clear + k) % n;
        if near[i] {
            if run.is_empty() {
                run.push(pts[(i + n - 1) % n]);
            }
            run.push(pts[i]);
        } else if !run.is_empty() {
            run.push(pts[i]);
            stretches.push(std::mem::take(&mut run));
        }
    }
    Some(Reach::Stretches(stretches))
}

/// Whether material stands above `z` within `radius` of `p` (module doc).
fn near_material(p: [f64; 2], z: f64, radius: f64, stock: &RoughingStock<'_>) -> bool {
    let level = z + MATERIAL_EPS;
    (stock.material)(p[0], p[1]) > level
        || RADII.iter().any(|f| {
            (0..DIRECTIONS).any(|k| {
                let a = std::f64::consts::TAU * k as f64 / DIRECTIONS as f64;
                let r = f * radius;
                (stock.material)(p[0] + r * a.cos(), p[1] + r * a.sin()) > level
            })
        })
}

/// `lp` with points put in so that no two in a row are more than `step` apart.
fn densified(lp: &Ring, step: f64) -> Ring {
    let n = lp.len();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let (a, b) = (lp[i], lp[(i + 1) % n]);
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let parts = (len / step).ceil().clamp(1.0, 1e6) as usize;
        for j in 0..parts {
            let t = j as f64 / parts as f64;
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Ring {
        vec![[0.0, 0.0], [40.0, 0.0], [40.0, 40.0], [0.0, 40.0]]
    }

    #[test]
    fn a_ring_meets_material_whole_in_stretches_or_not_at_all() {
        let everywhere = |_: f64, _: f64| 10.0;
        let nowhere = |_: f64, _: f64| f64::NEG_INFINITY;
        // A post of material of radius 1 at the middle of the bottom side, far from
        // every vertex of the loop.
        let post = |x: f64, y: f64| {
            if (x - 20.0).hypot(y + 3.0) < 1.0 {
                10.0
            } else {
                f64::NEG_INFINITY
            }
        };
        fn stock<'a>(m: &'a (dyn Fn(f64, f64) -> f64 + Sync)) -> RoughingStock<'a> {
            RoughingStock {
                min: [0.0, 0.0],
                max: [40.0, 40.0],
                top: 10.0,
                material: m,
            }
        }
        let lp = square();
        assert_eq!(
            reach(&lp, 0.0, 5.0, &stock(&everywhere)),
            Some(Reach::Whole)
        );
        assert_eq!(reach(&lp, 0.0, 5.0, &stock(&nowhere)), None);
        let Some(Reach::Stretches(s)) = reach(&lp, 0.0, 5.0, &stock(&post)) else {
            panic!("one stretch expected");
        };
        assert_eq!(s.len(), 1);
        // The tool on y = 0 meets the post (radius 1 at (20, -3)) for |x - 20| <
        // sqrt(6² - 3²): the stretch covers that, and its ends are clear of it.
        let meets = 27f64.sqrt();
        let xs: Vec<f64> = s[0].iter().map(|p| p[0]).collect();
        let (lo, hi) = (xs[0], xs[xs.len() - 1]);
        assert!(s[0].iter().all(|p| p[1] == 0.0));
        assert!(lo < 20.0 - meets && hi > 20.0 + meets, "{lo} {hi}");
        assert!(hi - lo < 2.0 * (meets + 1.2 * 5.0), "{lo} {hi}");
        for x in [lo, hi] {
            assert!((x - 20.0).hypot(3.0) >= 6.0, "{x}");
        }
    }
}
