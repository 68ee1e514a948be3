//! The height query on a part's patches (derivation in [`super`]).

use super::newton::{Ray, vertical_ray};
use super::seed::{Guess, NO_GUESS, Samples, keep_top_two};
use super::triangle::{Lattice, barycentric, cover, query_rect};
use super::{Height, HeightStatus};
use crate::error::GeomError;
use crate::math::{Aabb, Vec3};
use crate::part::Part;
use crate::patch::PowerPatch;
use crate::trim::Trim;
use rayon::prelude::*;

/// A part prepared for height queries: its patches in power form and their sample
/// triangles for the Newton starts.
#[derive(Debug, Clone)]
pub struct PartHeights {
    samples: Samples,
    power: Vec<PowerPatch>,
    /// Per patch, its trimming loops (`None`: the whole patch).
    trims: Vec<Option<Trim>>,
}

impl PartHeights {
    /// Prepares `part` (samples its patches, indexes the samples, converts the
    /// patches to power form). A part without patches has no height anywhere.
    ///
    /// # Errors
    /// The [`GeomError`] of a power-form conversion that fails (it cannot for a valid
    /// patch).
    pub fn new(part: &Part) -> Result<PartHeights, GeomError> {
        let power = part
            .patches
            .iter()
            .map(PowerPatch::new)
            .collect::<Result<_, _>>()?;
        Ok(PartHeights {
            samples: Samples::new(part),
            power,
            trims: (0..part.patches.len())
                .map(|k| part.trim(k).cloned())
                .collect(),
        })
    }

    /// Box around the sampled patches, mm.
    pub fn bounds(&self) -> Aabb {
        self.samples.mesh.aabb()
    }

    /// The part's upper envelope at `(x, y)`: the highest patch point above it;
    /// `None` outside every patch's XY shadow (or for a non-finite point).
    ///
    /// # Units
    /// mm.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Part, Patch, Point3, height::PartHeights};
    /// let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    /// let tilted = Patch::bezier([1, 1], vec![p(0.0, 0.0, 0.0), p(0.0, 10.0, 0.0),
    ///     p(10.0, 0.0, 5.0), p(10.0, 10.0, 5.0)]).unwrap();
    /// let part = Part::new("ramp", vec![tilted]);
    /// let h = PartHeights::new(&part).unwrap();
    /// assert!((h.at(4.0, 3.0).unwrap().z - 2.0).abs() < 1e-9);
    /// assert!(h.at(11.0, 3.0).is_none());
    /// ```
    pub fn at(&self, x: f64, y: f64) -> Option<Height> {
        let s = &self.samples;
        let mut pair = [NO_GUESS; 2];
        let (lo, hi) = query_rect(x, y);
        s.index.for_each_in_rect(lo, hi, |t| {
            let p = s.corners(t);
            if let Some(w) = barycentric(&p, x, y) {
                keep_top_two(&mut pair, s.guess(t, &p, w));
            }
        });
        self.solve(x, y, &pair)
    }

    /// [`PartHeights::at`] for every point, in parallel, answers in order.
    ///
    /// # Units
    /// mm.
    pub fn at_points(&self, points: &[[f64; 2]]) -> Vec<Option<Height>> {
        points.par_iter().map(|&[x, y]| self.at(x, y)).collect()
    }

    /// [`PartHeights::at`] at every point of rows `j0..=j1` of `grid`: calls
    /// `put(index_in_band, height)` where the part has one, `index_in_band = (j - j0)
    /// nx + i`. The starts come from scan-converting the sample triangles over the
    /// band (one index query per band instead of one per point).
    ///
    /// # Units
    /// mm.
    pub fn fill_rows(
        &self,
        grid: &impl Lattice,
        j0: usize,
        j1: usize,
        mut put: impl FnMut(usize, Height),
    ) {
        let nx = grid.nx();
        if nx == 0 || j1 < j0 {
            return;
        }
        let s = &self.samples;
        let mut best = vec![[NO_GUESS; 2]; (j1 - j0 + 1) * nx];
        let (lo, _) = query_rect(grid.x(0), grid.y(j0));
        let (_, hi) = query_rect(grid.x(nx - 1), grid.y(j1));
        s.index.for_each_in_rect(lo, hi, |t| {
            let p = s.corners(t);
            cover(grid, j0, j1, &p, |k, w| {
                keep_top_two(&mut best[k], s.guess(t, &p, w))
            });
        });
        for (k, pair) in best.iter().enumerate() {
            let (x, y) = (grid.x(k % nx), grid.y(j0 + k / nx));
            if let Some(h) = self.solve(x, y, pair) {
                put(k, h);
            }
        }
    }

    /// Whether `uv` is on face `patch` (inside its trimming loops, if any).
    fn inside(&self, patch: usize, uv: [f64; 2]) -> bool {
        self.trims[patch]
            .as_ref()
            .is_none_or(|t| t.contains(uv[0], uv[1]))
    }

    /// Newton from each start; the highest answer on a face.
    fn solve(&self, x: f64, y: f64, pair: &[Guess; 2]) -> Option<Height> {
        let mut top: Option<Height> = None;
        for g in pair.iter().filter(|g| g.patch != u32::MAX) {
            let patch = g.patch as usize;
            let h = match vertical_ray(&self.power[patch], x, y, g.uv) {
                Ray::Hit { uv, .. } if !self.inside(patch, uv) => continue,
                Ray::Hit { z, normal, uv } => Height {
                    z,
                    normal,
                    patch,
                    uv,
                    status: HeightStatus::Converged,
                },
                Ray::Off => continue,
                Ray::Singular if !self.inside(patch, g.uv) => continue,
                Ray::Singular => Height {
                    z: g.z,
                    normal: Vec3::z(),
                    patch,
                    uv: g.uv,
                    status: HeightStatus::Singular,
                },
            };
            if top.is_none_or(|t| h.z > t.z) {
                top = Some(h);
            }
        }
        top
    }
}
