//! How the tool gets onto a level's rings: down a ramp onto the innermost, and out
//! from each ring to the next by a step spread along the ring just cut.

use super::regions::{self, Ring};
use super::{BLEND_SAMPLES, BLEND_SLOPE, SAME_POINT, dist};

/// Most rounds of a ramp along a loop: a shorter loop would make a helix of
/// vanishing radius (and as many points as it takes).
pub(crate) const MAX_RAMP_ROUNDS: f64 = 20.0;

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
    // Each step ends a segment or goes `max_step`: the length is less than once
    // round, so this bounds the steps (and ends a loop of vanishing segments).
    for _ in 0..4 * n + 2 * BLEND_SAMPLES {
        if gone >= len {
            break;
        }
        let b = lp[(seg + 1) % n];
        let rest = dist(p, b);
        let take = rest.min(max_step).min(len - gone);
        if rest <= SAME_POINT {
            seg = (seg + 1) % n;
            p = b;
            gone += rest;
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
/// way). A loop too short to get down in [`MAX_RAMP_ROUNDS`] rounds is entered
/// straight down instead. Returns where the tool stands on the loop.
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
    if h - z > MAX_RAMP_ROUNDS * length * slope {
        // Too short a loop to ramp down along: straight down, a plunge.
        push([lp[0][0], lp[0][1], z], pts);
        h = z;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A loop of `n` points round a circle of radius `r`.
    fn circle(r: f64, n: usize) -> Ring {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [r * a.cos(), r * a.sin()]
            })
            .collect()
    }

    #[test]
    fn a_ramp_goes_round_at_its_angle_and_a_tiny_loop_is_plunged() {
        let angle = 3f64.to_radians();
        // Radius 5: 2 mm down at 3 degrees is 38.2 mm, 1.2 rounds of 31.4 mm.
        let lp = circle(5.0, 64);
        let mut pts = Vec::new();
        ramp_entry(&lp, 12.0, 10.0, angle, &mut pts);
        let run: f64 = pts
            .windows(2)
            .filter(|w| w[1][2] < w[0][2])
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum();
        assert!((run - 2.0 / angle.tan()).abs() < 1e-6, "{run}");
        assert_eq!(pts.last().unwrap()[2], 10.0);
        // Radius 1e-4: 2 mm would take over 60 000 rounds; straight down instead,
        // then the round at the level.
        let tiny = circle(1e-4, 64);
        let mut pts = Vec::new();
        ramp_entry(&tiny, 12.0, 10.0, angle, &mut pts);
        assert!(pts.len() <= 2 + 65, "{}", pts.len());
        assert!(pts[1..].iter().all(|p| p[2] == 10.0));
    }

    #[test]
    fn a_step_along_a_loop_of_vanishing_segments_ends() {
        // A loop of 1000 segments of 6e-10 mm (each one point by SAME_POINT), the
        // next ring a few 1e-9 mm outside it: the step is longer than SAME_POINT.
        let lp = circle(1e-7, 1000);
        let next = circle(1.2e-7, 1000);
        let from = OnLoop {
            lp: &lp,
            seg: 0,
            p: lp[0],
        };
        let mut pts = Vec::new();
        let end = blend(&from, &next, 0.0, 5.0, &mut pts);
        assert!(end.is_some());
        assert!(pts.len() <= 4 * lp.len() + 2 * BLEND_SAMPLES);
    }
}
