//! The 2D spatial directory (thesis 002 §5.2.1): grouping rest samples by where
//! they are.
//!
//! Each sample's XY point is filed under its nearest vertex of a grid of pitch `p`
//! (the thesis takes half the reference tool's radius); vertices holding a sample
//! are *black*. Black vertices that are neighbours are connected, and the connected
//! sets are the groups. The thesis's list of neighbours of `(i, j)` lost an entry and
//! repeats another in extraction; the neighbourhood its figure 26 describes is the
//! 8-neighbourhood `(i + di, j + dj)`, `di, dj` in `{-1, 0, 1}`, not both zero (its
//! row-by-row tracing only looks back at the four already visited: `(i-1, j-1)`,
//! `(i, j-1)`, `(i+1, j-1)`, `(i-1, j)`; connected components are what the tracing
//! builds once polylines that meet at branching points are joined, so they are
//! computed here directly with a union-find over the black vertices).
//!
//! Neighbouring vertices may still lie on two sides of a thin wall: the caller's
//! `linked` test on one sample of each (the lowest-numbered) decides whether an
//! adjacency counts (the thesis uses the contact normals; see [`crate::region`]).
//!
//! The grid is sparse (a sorted map of black vertices), so its size never depends on
//! the extent of the samples; groups come out ordered by their first sample and hold
//! their samples in ascending order, whatever the input's spread.

use std::collections::BTreeMap;

/// Groups of the indices of `points` (module doc): vertices of pitch `pitch` (mm),
/// adjacency filtered by `linked(i, j)` on a representative sample of each vertex.
///
/// # Example
/// ```
/// use swarf_rest::directory::group;
/// let pts = [[0.0, 0.0], [1.0, 0.1], [2.0, 0.0], [9.0, 9.0]];
/// assert_eq!(group(&pts, 1.0, |_, _| true), vec![vec![0, 1, 2], vec![3]]);
/// ```
pub fn group(
    points: &[[f64; 2]],
    pitch: f64,
    linked: impl Fn(usize, usize) -> bool,
) -> Vec<Vec<usize>> {
    let mut cells: BTreeMap<(i64, i64), Vec<usize>> = BTreeMap::new();
    for (k, p) in points.iter().enumerate() {
        if !(p[0].is_finite() && p[1].is_finite()) || pitch.is_nan() || pitch <= 0.0 {
            continue;
        }
        let key = ((p[0] / pitch).round() as i64, (p[1] / pitch).round() as i64);
        cells.entry(key).or_default().push(k);
    }
    let keys: Vec<(i64, i64)> = cells.keys().copied().collect();
    let index: BTreeMap<(i64, i64), usize> =
        keys.iter().enumerate().map(|(i, k)| (*k, i)).collect();
    let mut parent: Vec<usize> = (0..keys.len()).collect();
    for (v, &(i, j)) in keys.iter().enumerate() {
        for (di, dj) in [(-1, -1), (0, -1), (1, -1), (-1, 0)] {
            let Some(&w) = index.get(&(i + di, j + dj)) else {
                continue;
            };
            if linked(cells[&keys[v]][0], cells[&keys[w]][0]) {
                let (a, b) = (find(&mut parent, v), find(&mut parent, w));
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (v, key) in keys.iter().enumerate() {
        let root = find(&mut parent, v);
        groups.entry(root).or_default().extend(&cells[key]);
    }
    let mut out: Vec<Vec<usize>> = groups
        .into_values()
        .map(|mut g| {
            g.sort_unstable();
            g
        })
        .collect();
    out.sort_by_key(|g| g[0]);
    out
}

fn find(parent: &mut [usize], mut v: usize) -> usize {
    while parent[v] != v {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_neighbours_join_and_gaps_split() {
        // An L of vertices and a diagonal step join; two vertices apart do not.
        let pts = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [4.0, 2.0],
            [0.1, -0.2],
        ];
        assert_eq!(
            group(&pts, 1.0, |_, _| true),
            vec![vec![0, 1, 2, 3, 5], vec![4]]
        );
        // A wall between x <= 1 and x >= 2 cuts the group.
        let wall = |a: usize, b: usize| (pts[a][0] <= 1.5) == (pts[b][0] <= 1.5);
        assert_eq!(
            group(&pts, 1.0, wall),
            vec![vec![0, 1, 5], vec![2, 3], vec![4]]
        );
        // Non-finite points and a bad pitch file nothing.
        assert!(group(&[[f64::NAN, 0.0]], 1.0, |_, _| true).is_empty());
        assert!(group(&pts, 0.0, |_, _| true).is_empty());
    }

    #[test]
    fn every_neighbourhood_direction_connects() {
        for di in -1i32..=1 {
            for dj in -1i32..=1 {
                if (di, dj) == (0, 0) {
                    continue;
                }
                let pts = [[0.0, 0.0], [f64::from(di), f64::from(dj)]];
                assert_eq!(group(&pts, 1.0, |_, _| true).len(), 1, "{di} {dj}");
            }
        }
    }
}
