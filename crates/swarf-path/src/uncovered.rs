//! Regions a strategy could not cover as planned, grouped for the report.
//!
//! Points are binned per patch on a `CELLS x CELLS` grid over its parameter domain;
//! marked cells that share an edge form one region (4-connected components), reported
//! as the parameter box of its points with a reason. This is coarse on purpose: it
//! names where to look, it does not outline the region.

use crate::plan::Uncovered;
use std::collections::BTreeMap;
use swarf_geom::Part;

/// Grid cells per parameter direction.
const CELLS: usize = 32;

/// A point of a region: patch, parameters and a value to report (a lift, ...).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marked {
    /// Patch index.
    pub face: usize,
    /// Surface parameters.
    pub uv: [f64; 2],
    /// The figure reported as the region's maximum (mm).
    pub value: f64,
}

/// Groups `points` into regions; `reason(count, max_value)` words each region's
/// reason.
pub fn regions(
    part: &Part,
    points: &[Marked],
    reason: impl Fn(usize, f64) -> String,
) -> Vec<Uncovered> {
    let mut by_cell: BTreeMap<(usize, usize, usize), Vec<Marked>> = BTreeMap::new();
    for m in points {
        let Some(patch) = part.patches.get(m.face) else {
            continue;
        };
        let dom = patch.domain();
        let cell = |k: usize| {
            let t = (m.uv[k] - dom[k][0]) / (dom[k][1] - dom[k][0]);
            ((t * CELLS as f64).floor().max(0.0) as usize).min(CELLS - 1)
        };
        by_cell
            .entry((m.face, cell(0), cell(1)))
            .or_default()
            .push(*m);
    }
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for &start in by_cell.keys() {
        if !seen.insert(start) {
            continue;
        }
        let mut stack = vec![start];
        let mut members: Vec<Marked> = Vec::new();
        while let Some((f, i, j)) = stack.pop() {
            members.extend(&by_cell[&(f, i, j)]);
            let near = [
                (i.wrapping_sub(1), j),
                (i + 1, j),
                (i, j.wrapping_sub(1)),
                (i, j + 1),
            ];
            for (a, b) in near {
                let key = (f, a, b);
                if by_cell.contains_key(&key) && seen.insert(key) {
                    stack.push(key);
                }
            }
        }
        out.push(describe(start.0, &members, &reason));
    }
    out
}

fn describe(face: usize, members: &[Marked], reason: &impl Fn(usize, f64) -> String) -> Uncovered {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut worst: f64 = 0.0;
    for m in members {
        for k in 0..2 {
            lo[k] = lo[k].min(m.uv[k]);
            hi[k] = hi[k].max(m.uv[k]);
        }
        worst = worst.max(m.value);
    }
    Uncovered {
        region: format!(
            "patch {face}, u in [{:.4}, {:.4}], v in [{:.4}, {:.4}]",
            lo[0], hi[0], lo[1], hi[1]
        ),
        reason: reason(members.len(), worst),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Patch, Point3};

    #[test]
    fn neighbouring_cells_merge_and_distant_ones_do_not() {
        let flat = Patch::bezier(
            [1, 1],
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(1.0, 1.0, 0.0),
            ],
        )
        .unwrap();
        let part = Part::new("flat", vec![flat.clone(), flat]);
        let m = |face, u, v, value| Marked {
            face,
            uv: [u, v],
            value,
        };
        let pts = [
            m(0, 0.10, 0.10, 0.2),
            m(0, 0.13, 0.10, 0.5),
            m(0, 0.16, 0.11, 0.1),
            m(0, 0.90, 0.90, 0.3),
            m(1, 0.10, 0.10, 0.4),
        ];
        let r = regions(&part, &pts, |n, w| format!("{n} points, up to {w:.1} mm"));
        assert_eq!(r.len(), 3);
        assert_eq!(
            r[0].region,
            "patch 0, u in [0.1000, 0.1600], v in [0.1000, 0.1100]"
        );
        assert_eq!(r[0].reason, "3 points, up to 0.5 mm");
        assert_eq!(r[1].reason, "1 points, up to 0.3 mm");
        assert!(r[2].region.starts_with("patch 1"));
    }
}
