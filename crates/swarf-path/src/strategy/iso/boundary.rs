//! Boundary passes: where the planned passes leave more than `h` on a patch edge.
//!
//! The side-step schedules guarantee the scallop *between* adjacent passes. At the
//! boundary of a patch two things can leave more: drive planes oblique to the edges
//! end adjacent pieces on different edges around a corner, so the corner lies between
//! pass ends rather than between passes; and a path family may end short of an edge.
//! So after planning, every patch edge is sampled at a quarter of the coverage radius
//! `sqrt(2 r h)` (local maxima refined by golden-section search) and the material left
//! at each sample is measured: each pass's swept
//! tool is taken as the swept ball of the cutter's least effective radius `r_e`
//! tangent at its CC points (the ball exactly; for other cutters a ball inside the
//! tool near its contact, so the measure errs toward more material), and the material
//! at a point is where the ray along its normal first enters one of those capsules.
//! Stretches of an edge above `h` (by more than the schedules' own modelling error of
//! a fraction of a percent, `COVERED_SLACK`), widened by one coverage radius each
//! way, become passes along the edge, cut last. Points under another patch are
//! skipped. On a trimmed face the edges are its trimming loops instead of the patch
//! rectangle's sides ([`crate::strategy::iso::boundary_edges`]).

use crate::ordering::Row;
use crate::stepping::forward_step::sample_curve;
use crate::strategy::iso::boundary_edges::face_edges;
use crate::strategy::iso::setup::IsoSetup;
use rayon::prelude::*;
use swarf_geom::math::ray_capsule;
use swarf_geom::solve::golden_max;
use swarf_geom::{Point3, Vec3};
use swarf_toolpath::Pass;

/// Edge samples per coverage radius.
const SAMPLES_PER_RADIUS: f64 = 4.0;
/// Material up to this factor of `h` counts as covered: the passes' own scallop
/// models are exact to a fraction of a percent, and a boundary pass is for corners
/// left clearly above `h` (dimensionless).
const COVERED_SLACK: f64 = 1.02;
/// Local maxima below this fraction of the limit are not refined (a crest above the
/// limit has a sample within an eighth of the coverage radius of it, which the
/// material's rise from the neighbouring contacts keeps well above this).
const CREST_FLOOR: f64 = 0.5;
/// Golden-section steps refining a crest along an edge.
const GOLDEN_STEPS: usize = 30;
/// Side of the capsules' XY grid cells, in capsule radii.
const CELL_RADII: f64 = 0.5;
/// Most samples along one edge.
const MAX_EDGE_SAMPLES: usize = 200_000;

/// Extra passes along the patch edges that `rows` leave more than `h` on (module doc).
pub fn boundary_passes(setup: &IsoSetup<'_>, rows: &[Row]) -> Vec<Pass> {
    let h = setup.side.h();
    let r = setup.side.min_effective_radius();
    let reach = (2.0 * r * h - h * h).max(0.0).sqrt();
    let capsules = Capsules::new(rows, r);
    let mut out = Vec::new();
    for (face, patch) in setup.part.patches.iter().enumerate() {
        let map = setup.cl_map(face);
        for edge in face_edges(setup.part, face) {
            let uv = |t: f64| edge.uv(t);
            let free = edge.range();
            let length = edge_length(patch, &uv, free);
            let n = ((length * SAMPLES_PER_RADIUS / reach.max(1e-9)).ceil() as usize)
                .clamp(2, MAX_EDGE_SAMPLES);
            let ts: Vec<f64> = (0..=n)
                .map(|k| free[0] + (free[1] - free[0]) * k as f64 / n as f64)
                .collect();
            let material = |t: f64| {
                let (u, v) = uv(t);
                setup
                    .reachable(&map, u, v)
                    .and_then(|p| p.contact)
                    .map_or(0.0, |c| capsules.material(&c.point, &c.normal))
            };
            let bare = bare_samples(&ts, &material, COVERED_SLACK * h);
            let widen = ((n as f64) * reach / length.max(1e-9)).ceil() as usize;
            for (a, b) in stretches(&bare, widen) {
                let f = |t: f64| {
                    let (u, v) = uv(t);
                    setup.reachable(&map, u, v)
                };
                for run in sample_curve(&f, ts[a], ts[b], &setup.step) {
                    out.push(Pass {
                        points: run.into_iter().map(|s| s.point).collect(),
                        ..Pass::default()
                    });
                }
            }
        }
    }
    out
}

/// Which samples `ts` of an edge are left with more than `limit`: the samples
/// themselves, and the local maxima of the samples refined by golden-section search
/// between their neighbours (crests between passes that meet the edge obliquely are
/// sharp, narrower than the sample spacing).
fn bare_samples(ts: &[f64], material: &(impl Fn(f64) -> f64 + Sync), limit: f64) -> Vec<bool> {
    let m: Vec<f64> = ts.par_iter().map(|&t| material(t)).collect();
    (0..ts.len())
        .into_par_iter()
        .map(|k| {
            if m[k] > limit {
                return true;
            }
            let crest = k > 0
                && k + 1 < ts.len()
                && m[k] >= m[k - 1]
                && m[k] >= m[k + 1]
                && m[k] > CREST_FLOOR * limit;
            if !crest {
                return false;
            }
            let [a, b] = golden_max(material, ts[k - 1], ts[k + 1], GOLDEN_STEPS).bracket;
            material(0.5 * (a + b)) > limit
        })
        .collect()
}

/// Length of an edge curve (chord sum over a fine sampling), mm.
fn edge_length(patch: &swarf_geom::Patch, uv: &impl Fn(f64) -> (f64, f64), range: [f64; 2]) -> f64 {
    let n = 256;
    let at = |k: usize| {
        let (u, v) = uv(range[0] + (range[1] - range[0]) * k as f64 / n as f64);
        patch.eval(u, v)
    };
    (0..n).map(|k| (at(k + 1) - at(k)).norm()).sum()
}

/// Index ranges of the `true` runs of `bare`, each widened by `widen` both ways and
/// merged where they meet.
fn stretches(bare: &[bool], widen: usize) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = Vec::new();
    let last = bare.len().saturating_sub(1);
    let mut k = 0;
    while k < bare.len() {
        if !bare[k] {
            k += 1;
            continue;
        }
        let start = k;
        while k < bare.len() && bare[k] {
            k += 1;
        }
        let (a, b) = (start.saturating_sub(widen), (k - 1 + widen).min(last));
        match out.last_mut() {
            Some(prev) if prev.1 >= a => prev.1 = prev.1.max(b),
            _ => out.push((a, b)),
        }
    }
    out
}

/// Swept balls of the passes, bucketed on an XY grid.
struct Capsules {
    r: f64,
    segs: Vec<(Point3, Point3)>,
    origin: [f64; 2],
    cell: f64,
    dims: [usize; 2],
    cells: Vec<Vec<u32>>,
}

impl Capsules {
    fn new(rows: &[Row], r: f64) -> Capsules {
        let mut segs = Vec::new();
        for pass in rows.iter().flatten() {
            let c: Vec<Point3> = pass
                .points
                .iter()
                .filter_map(|p| p.contact.map(|c| c.point + r * c.normal))
                .collect();
            if c.len() == 1 {
                segs.push((c[0], c[0]));
            }
            segs.extend(c.windows(2).map(|w| (w[0], w[1])));
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (a, b) in &segs {
            for p in [a, b] {
                lo = [lo[0].min(p.x), lo[1].min(p.y)];
                hi = [hi[0].max(p.x), hi[1].max(p.y)];
            }
        }
        let cell = CELL_RADII * r;
        let origin = [lo[0] - r, lo[1] - r];
        let dims = [0, 1].map(|k| {
            if hi[k] >= lo[k] {
                ((hi[k] - lo[k] + 2.0 * r) / cell).ceil() as usize + 1
            } else {
                1
            }
        });
        let mut caps = Capsules {
            r,
            segs,
            origin,
            cell,
            dims,
            cells: vec![Vec::new(); dims[0] * dims[1]],
        };
        for k in 0..caps.segs.len() {
            let (a, b) = caps.segs[k];
            let (x0, x1) = (
                caps.index(0, a.x.min(b.x) - r),
                caps.index(0, a.x.max(b.x) + r),
            );
            let (y0, y1) = (
                caps.index(1, a.y.min(b.y) - r),
                caps.index(1, a.y.max(b.y) + r),
            );
            for j in y0..=y1 {
                for i in x0..=x1 {
                    caps.cells[j * dims[0] + i].push(k as u32);
                }
            }
        }
        caps
    }

    fn index(&self, axis: usize, v: f64) -> usize {
        let i = ((v - self.origin[axis]) / self.cell).floor();
        (i.max(0.0) as usize).min(self.dims[axis] - 1)
    }

    /// Material above `p` along the unit normal `n`: where the ray first enters a
    /// capsule (0 inside one, infinity when none is above).
    fn material(&self, p: &Point3, n: &Vec3) -> f64 {
        let cell = self.index(1, p.y) * self.dims[0] + self.index(0, p.x);
        self.cells[cell]
            .iter()
            .map(|&k| {
                let (a, b) = self.segs[k as usize];
                ray_capsule(p, n, &a, &b, self.r)
            })
            .fold(f64::INFINITY, f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stretches_widen_and_merge() {
        let b = |s: &str| s.chars().map(|c| c == '1').collect::<Vec<bool>>();
        assert_eq!(stretches(&b("0001100000011"), 1), vec![(2, 5), (10, 12)]);
        assert_eq!(stretches(&b("0100010"), 2), vec![(0, 6)]);
        assert!(stretches(&b("0000"), 3).is_empty());
    }
}
