//! How the tool gets onto a level's rings: down a ramp onto the innermost, and out
//! from each ring to the next by a step spread along the ring just cut.

use super::regions::{self, Ring};
use super::{BLEND_SAMPLES, BLEND_SLOPE, SAME_POINT, dist};

/// Where the tool stands on a loop it has cut all round: on the segment from
/// `lp[seg]` to `lp[seg + 1]`, at `p`.
#[derive(Clone, Copy)]
pub(crate) struct OnLoop<'a> {
    pub(crate) lp: &'a Ring,
    pub(crate) seg: usize,
    pub(crate) p: [f64; 2],
}

/// The step from the loop the tool has just cut out to the next ring `next`,
/// spread along the cut loop: the tool follows the cut loop forwards and moves out
/// to the nearest point of `next` in proportion to the length gone, reaching it
/// after the gap over `tan` [`BLEND_SLOPE`] (at most once round the loop). So the
/// band to the next ring is entered at that slope, not square (a step straight
/// across it meets the band's whole width at once). Pushes the points and returns
/// where `next` is reached: its segment and the point; `None` (nothing pushed) when
/// `next` is farther than `reach` (not the ring round the cut one).
pub(crate) fn blend(
    from: &OnLoop<'_>,
    next: &Ring,
    z: f64,
    reach: f64,
    pts: &mut Vec<[f64; 3]>,
) -> Option<(usize, [f64; 2])> {
    let (seg0, gap, p0) = regions::distance_to_loop(next, from.p);
    if gap > reach {
        return None;
    }
    let (lp, n) = (from.lp, from.lp.len());
    let perimeter: f64 = (0..n).map(|i| dist(lp[i], lp[(i + 1) % n])).sum();
    let len = (gap / BLEND_SLOPE).min(perimeter);
    if len <= SAME_POINT || n < 2 {
        return Some((seg0, p0));
    }
    let max_step = len / BLEND_SAMPLES as f64;
    let (mut seg, mut p, mut gone) = (from.seg, from.p, 0.0);
    let mut end = (seg0, p0);
    while gone < len {
        let b = lp[(seg + 1) % n];
        let rest = dist(p, b);
        let take = rest.min(max_step).min(len - gone);
        if rest <= SAME_POINT {
            seg = (seg + 1) % n;
            p = b;
            continue;
        }
        let t = take / rest;
        p = [p[0] + t * (b[0] - p[0]), p[1] + t * (b[1] - p[1])];
        gone += take;
        let (j, _, q) = regions::distance_to_loop(next, p);
        let w = (gone / len).min(1.0);
        pts.push([p[0] + w * (q[0] - p[0]), p[1] + w * (q[1] - p[1]), z]);
        end = (j, q);
    }
    Some(end)
}

/// The ramp into a level along `lp`: from `above` down to `z` at `angle` from the
/// horizontal, going round the loop as often as it takes, then once more round it
/// at the level (the last round of the ramp left a wedge above the level all the
/// way). Returns where the tool stands on the loop.
pub(crate) fn ramp_entry<'a>(
    lp: &'a Ring,
    above: f64,
    z: f64,
    angle: f64,
    pts: &mut Vec<[f64; 3]>,
) -> OnLoop<'a> {
    let slope = angle.tan();
    let n = lp.len();
    let mut h = above.max(z);
    let push = |p: [f64; 3], pts: &mut Vec<[f64; 3]>| {
        let same = pts.last().is_some_and(|q: &[f64; 3]| {
            (q[0] - p[0]).hypot(q[1] - p[1]).hypot(q[2] - p[2]) < SAME_POINT
        });
        if !same {
            pts.push(p);
        }
    };
    push([lp[0][0], lp[0][1], h], pts);
    let length: f64 = (0..n).map(|i| dist(lp[i], lp[(i + 1) % n])).sum();
    let mut reached = OnLoop {
        lp,
        seg: 0,
        p: lp[0],
    };
    if length < 1e-6 {
        push([lp[0][0], lp[0][1], z], pts);
        return reached;
    }
    let mut i = 0;
    while h > z {
        let (a, b) = (lp[i % n], lp[(i + 1) % n]);
        let drop = dist(a, b) * slope;
        if h - drop <= z {
            let t = (h - z) / drop;
            reached = OnLoop {
                lp,
                seg: i % n,
                p: [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])],
            };
            break;
        }
        h -= drop;
        push([b[0], b[1], h], pts);
        i += 1;
    }
    let (j, r) = (reached.seg, reached.p);
    push([r[0], r[1], z], pts);
    for p in lp[j + 1..].iter().chain(&lp[..=j]) {
        push([p[0], p[1], z], pts);
    }
    push([r[0], r[1], z], pts);
    reached
}
