//! Ordering a group of samples into a smooth open path (thesis 002 §5.2.2).
//!
//! The thesis anneals the points of a group into the shortest open path through
//! them (a travelling-salesman path, by simulated annealing). Here the same
//! objective is reached deterministically: a nearest-neighbour chain from an end of
//! the group (the sample farthest from the first one, an end of the group's longest
//! extent), then 2-opt moves (reverse a stretch of the path when that shortens it,
//! including the two ends) until none improves by more than [`IMPROVE_EPS`] or
//! [`MAX_SWEEPS`] sweeps have run. For points along a curve sampled finer than its
//! curvature radius, the result visits them in curve order; unlike annealing it
//! needs no seed, and the same input always gives the same path.
//!
//! The path is then cut where consecutive points are further apart than a link
//! length: a branching valley becomes several open chains rather than one path that
//! jumps across the region.

/// A 2-opt move must shorten the path by more than this, mm.
pub const IMPROVE_EPS: f64 = 1e-9;
/// Most 2-opt sweeps over the path.
pub const MAX_SWEEPS: usize = 50;
/// Groups up to this size get 2-opt over all pairs; larger ones within a window.
pub const FULL_2OPT: usize = 400;
/// Window of the 2-opt on large groups (path positions).
pub const WINDOW: usize = 64;

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The order of `points` along a short open path through all of them (module doc).
///
/// # Example
/// ```
/// use swarf_rest::order::open_path;
/// let pts = [[2.0, 0.0], [0.0, 0.0], [3.0, 0.1], [1.0, 0.0]];
/// assert_eq!(open_path(&pts), vec![1, 3, 0, 2]);
/// ```
pub fn open_path(points: &[[f64; 2]]) -> Vec<usize> {
    let n = points.len();
    if n < 3 {
        return (0..n).collect();
    }
    let start = (0..n).fold(0, |m, k| {
        if dist(points[k], points[0]) > dist(points[m], points[0]) {
            k
        } else {
            m
        }
    });
    let mut path = vec![start];
    let mut left: Vec<usize> = (0..n).filter(|&k| k != start).collect();
    while !left.is_empty() {
        let here = points[*path.last().unwrap_or(&start)];
        let (pos, _) = left
            .iter()
            .enumerate()
            .map(|(i, &k)| (i, dist(here, points[k])))
            .fold(
                (0, f64::INFINITY),
                |m, (i, d)| if d < m.1 { (i, d) } else { m },
            );
        path.push(left.remove(pos));
    }
    two_opt(points, &mut path);
    path
}

/// Improves `path` by 2-opt moves (module doc).
fn two_opt(points: &[[f64; 2]], path: &mut [usize]) {
    let n = path.len();
    let window = if n <= FULL_2OPT { n } else { WINDOW };
    let p = |path: &[usize], i: usize| points[path[i]];
    for _ in 0..MAX_SWEEPS {
        let mut improved = false;
        for i in 0..n - 1 {
            for j in i + 1..n.min(i + 1 + window) {
                // Reverse path[i..=j]: the edges (i-1, i) and (j, j+1) change.
                let before = if i > 0 {
                    dist(p(path, i - 1), p(path, i))
                } else {
                    0.0
                } + if j + 1 < n {
                    dist(p(path, j), p(path, j + 1))
                } else {
                    0.0
                };
                let after = if i > 0 {
                    dist(p(path, i - 1), p(path, j))
                } else {
                    0.0
                } + if j + 1 < n {
                    dist(p(path, i), p(path, j + 1))
                } else {
                    0.0
                };
                if after < before - IMPROVE_EPS {
                    path[i..=j].reverse();
                    improved = true;
                }
            }
        }
        if !improved {
            break;
        }
    }
}

/// `order` cut into runs whose consecutive points are at most `link` apart.
pub fn chains(points: &[[f64; 2]], order: &[usize], link: f64) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    for &k in order {
        match out.last_mut() {
            Some(c)
                if c.last()
                    .is_some_and(|&l| dist(points[l], points[k]) <= link) =>
            {
                c.push(k)
            }
            _ => out.push(vec![k]),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn length(points: &[[f64; 2]], path: &[usize]) -> f64 {
        path.windows(2)
            .map(|w| dist(points[w[0]], points[w[1]]))
            .sum()
    }

    #[test]
    fn points_on_an_arc_come_out_in_arc_order() {
        // 60 points on a quarter circle of radius 20, filed in a scrambled order.
        let n = 60;
        let perm: Vec<usize> = (0..n).map(|k| (k * 37) % n).collect();
        let pts: Vec<[f64; 2]> = perm
            .iter()
            .map(|&k| {
                let a = std::f64::consts::FRAC_PI_2 * k as f64 / (n - 1) as f64;
                [20.0 * a.cos(), 20.0 * a.sin()]
            })
            .collect();
        let path = open_path(&pts);
        let along: Vec<usize> = path.iter().map(|&i| perm[i]).collect();
        let forward: Vec<usize> = (0..n).collect();
        let backward: Vec<usize> = (0..n).rev().collect();
        assert!(along == forward || along == backward, "{along:?}");
    }

    #[test]
    fn short_sets_match_the_brute_force_optimum() {
        // Brute force over all orders of 7 points (an oracle sharing nothing with the
        // heuristic): 2-opt from the nearest-neighbour chain reaches the optimum here.
        let pts = [
            [0.0, 0.0],
            [5.0, 1.0],
            [1.0, 0.5],
            [4.0, -1.0],
            [2.0, 0.0],
            [3.0, 0.8],
            [6.0, 0.0],
        ];
        let mut best = f64::INFINITY;
        let mut perm: Vec<usize> = (0..pts.len()).collect();
        permute(&mut perm, 0, &mut |p| best = best.min(length(&pts, p)));
        let got = length(&pts, &open_path(&pts));
        assert!(got <= best * 1.05 + 1e-12, "{got} vs {best}");
    }

    fn permute(v: &mut Vec<usize>, k: usize, f: &mut impl FnMut(&[usize])) {
        if k == v.len() {
            f(v);
            return;
        }
        for i in k..v.len() {
            v.swap(k, i);
            permute(v, k + 1, f);
            v.swap(k, i);
        }
    }

    #[test]
    fn chains_cut_at_long_links() {
        let pts = [[0.0, 0.0], [1.0, 0.0], [5.0, 0.0], [6.0, 0.0]];
        assert_eq!(
            chains(&pts, &[0, 1, 2, 3], 1.5),
            vec![vec![0, 1], vec![2, 3]]
        );
        assert!(chains(&pts, &[], 1.0).is_empty());
    }
}
