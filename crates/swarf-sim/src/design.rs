//! The design surface's height at every cell centre: the upper envelope of the part
//! seen along +z (`parts/README.md`), the reference the machined stock is measured
//! against.
//!
//! - **Mesh**: an exact vertical ray cast at each cell centre (plane of the triangle
//!   hit), the highest hit kept. Rows are taken in bands; the [`XyIndex`] gives the
//!   triangles meeting a band and [`crate::raster::cover`] the centres each holds.
//! - **Parametric part**: each patch is sampled on a uniform `(u, v)` grid (about one
//!   sample per [`SAMPLE_SPACING`] of control-net length, between [`MIN_SAMPLES`] and
//!   [`MAX_SAMPLES`] a direction) and the sample triangles are cast as above, carrying
//!   `(u, v)`; that gives, per cell, a starting point on the two highest patches there.
//!   Newton's method on `S_xy(u, v) = (x, y)` (`J = [S_u S_v]_xy`, the patch in power
//!   form, [`crate::power`]) then solves the
//!   vertical ray against each exactly, to [`NEWTON_XY`] in XY (so the height to that
//!   times the surface slope), and the higher is kept. Cells whose ray leaves a patch
//!   (Newton pushed against the domain boundary with a residual left) get no height
//!   from it; where the Jacobian is singular (a vertical tangent plane) the sampled
//!   height is kept and counted in [`DesignField::approximate`]. Cells outside every
//!   patch's projection are NaN: they are not measured.

use crate::error::SimError;
use crate::grid::Grid;
use crate::power::PowerPatch;
use crate::progress::Progress;
use crate::raster::cover;
use rayon::prelude::*;
use std::borrow::Cow;
use swarf_geom::{Aabb, Part, Patch, Point3, TriMesh, Vec3, XyIndex};

/// Target control-net length per sample of a patch, mm.
pub const SAMPLE_SPACING: f64 = 1.0;
/// Fewest samples per direction of a patch.
pub const MIN_SAMPLES: usize = 8;
/// Most samples per direction of a patch.
pub const MAX_SAMPLES: usize = 1024;
/// Newton stops when the ray's XY residual is below this, mm.
pub const NEWTON_XY: f64 = 1e-10;
/// A Newton step shorter than this fraction of the parameter range is the last one:
/// the next would change the point by about `|S''| step^2 / 2`, below 1e-10 mm for
/// second derivatives up to 1e4 mm per unit parameter squared.
pub const NEWTON_ACCEPT: f64 = 1e-7;
/// Most Newton steps per cell and patch.
const NEWTON_STEPS: usize = 16;
/// Rows per parallel band.
const BAND_ROWS: usize = 16;

/// The design: parametric patches or a triangle mesh.
#[derive(Debug, Clone, Copy)]
pub enum Design<'a> {
    /// Parametric patches.
    Part(&'a Part),
    /// A triangle mesh.
    Mesh(&'a TriMesh),
}

/// Design heights per cell.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignField {
    /// Height at each cell centre, row-major; NaN off the design.
    pub heights: Vec<f64>,
    /// Unit upward design normals per cell (when asked for); zero off the design.
    pub normals: Option<Vec<[f32; 3]>>,
    /// Cells whose height comes from the sampled patch, not from Newton.
    pub approximate: usize,
}

/// A design prepared for vertical ray casts.
#[derive(Debug, Clone)]
pub struct DesignSurface<'a> {
    design: Design<'a>,
    mesh: Cow<'a, TriMesh>,
    /// Per vertex `(u, v)` (parametric parts only).
    uv: Vec<[f64; 2]>,
    /// Per triangle, its patch (parametric parts only).
    patch_of: Vec<u32>,
    /// The patches in power form (parametric parts only).
    power: Vec<PowerPatch>,
    index: XyIndex,
}

/// A starting point on one patch.
#[derive(Debug, Clone, Copy)]
struct Guess {
    z: f64,
    uv: [f64; 2],
    patch: u32,
}

const NO_GUESS: Guess = Guess {
    z: f64::NEG_INFINITY,
    uv: [0.0; 2],
    patch: u32::MAX,
};

impl<'a> DesignSurface<'a> {
    /// Prepares `design` (samples a part's patches, indexes the triangles).
    ///
    /// # Errors
    /// [`SimError::Empty`] for a part without patches or a mesh without triangles.
    pub fn new(design: Design<'a>) -> Result<DesignSurface<'a>, SimError> {
        let mut power = Vec::new();
        let (mesh, uv, patch_of) = match design {
            Design::Mesh(m) => {
                if m.is_empty() {
                    return Err(SimError::Empty("the design mesh has no triangle".into()));
                }
                (Cow::Borrowed(m), Vec::new(), Vec::new())
            }
            Design::Part(part) => {
                if part.patches.is_empty() {
                    return Err(SimError::Empty(format!("part {}: no patch", part.name)));
                }
                let (m, uv, patch_of) = sample_part(part);
                power = part
                    .patches
                    .iter()
                    .map(PowerPatch::new)
                    .collect::<Result<_, _>>()?;
                (Cow::Owned(m), uv, patch_of)
            }
        };
        let index = XyIndex::build(&mesh);
        Ok(DesignSurface {
            design,
            mesh,
            uv,
            patch_of,
            power,
            index,
        })
    }

    /// Box around the design (the sampled patches, or the mesh), mm.
    pub fn bounds(&self) -> Aabb {
        self.mesh.aabb()
    }

    /// Heights (and, when `normals`, unit upward normals) at every cell centre.
    pub fn heights(&self, grid: &Grid, normals: bool, progress: &dyn Progress) -> DesignField {
        let n = grid.len();
        let mut heights = vec![f64::NAN; n];
        let mut norms = normals.then(|| vec![[0.0f32; 3]; n]);
        let chunk = BAND_ROWS * grid.nx;
        progress.begin("design heights", grid.ny as u64);
        let approx: usize = match norms.as_mut() {
            Some(nv) => heights
                .par_chunks_mut(chunk)
                .zip(nv.par_chunks_mut(chunk))
                .enumerate()
                .map(|(b, (h, nb))| self.band(grid, b, h, Some(nb), progress))
                .sum(),
            None => heights
                .par_chunks_mut(chunk)
                .enumerate()
                .map(|(b, h)| self.band(grid, b, h, None, progress))
                .sum(),
        };
        progress.end();
        DesignField {
            heights,
            normals: norms,
            approximate: approx,
        }
    }

    /// Fills one band; returns the count of approximate cells.
    fn band(
        &self,
        grid: &Grid,
        b: usize,
        heights: &mut [f64],
        mut normals: Option<&mut [[f32; 3]]>,
        progress: &dyn Progress,
    ) -> usize {
        let j0 = b * BAND_ROWS;
        let j1 = j0 + heights.len() / grid.nx - 1;
        let half = 0.5 * grid.cell;
        let lo = [grid.origin[0], grid.y(j0) - half];
        let hi = [grid.max()[0], grid.y(j1) + half];
        let approx = match self.design {
            Design::Mesh(_) => {
                self.index.for_each_in_rect(lo, hi, |t| {
                    let tri = self.mesh.triangle(t as usize);
                    let p = tri.map(|q| [q.x, q.y, q.z]);
                    let up = upward(&tri);
                    cover(grid, j0, j1, &p, |k, w| {
                        let z = w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2];
                        if heights[k].is_nan() || z > heights[k] {
                            heights[k] = z;
                            if let Some(nb) = normals.as_deref_mut() {
                                nb[k] = up;
                            }
                        }
                    });
                });
                0
            }
            Design::Part(_) => self.part_band(grid, j0, j1, heights, normals),
        };
        progress.advance((j1 - j0 + 1) as u64);
        approx
    }

    /// Fills one band of a parametric part: sampled guesses, then Newton per cell.
    fn part_band(
        &self,
        grid: &Grid,
        j0: usize,
        j1: usize,
        heights: &mut [f64],
        mut normals: Option<&mut [[f32; 3]]>,
    ) -> usize {
        let mut best = vec![[NO_GUESS; 2]; heights.len()];
        let half = 0.5 * grid.cell;
        let lo = [grid.origin[0], grid.y(j0) - half];
        let hi = [grid.max()[0], grid.y(j1) + half];
        self.index.for_each_in_rect(lo, hi, |t| {
            let ids = self.mesh.triangles[t as usize];
            let p = ids.map(|v| {
                let q = self.mesh.vertices[v as usize];
                [q.x, q.y, q.z]
            });
            let uv = ids.map(|v| self.uv[v as usize]);
            let patch = self.patch_of[t as usize];
            cover(grid, j0, j1, &p, |k, w| {
                let g = Guess {
                    z: w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2],
                    uv: [0, 1].map(|d| w[0] * uv[0][d] + w[1] * uv[1][d] + w[2] * uv[2][d]),
                    patch,
                };
                keep_top_two(&mut best[k], g);
            });
        });
        let mut approx = 0;
        for (k, pair) in best.iter().enumerate() {
            let (i, j) = (k % grid.nx, j0 + k / grid.nx);
            let [x, y] = grid.centre(i, j);
            let mut top: Option<(f64, Vec3)> = None;
            for g in pair.iter().filter(|g| g.patch != u32::MAX) {
                let hit = match newton(&self.power[g.patch as usize], x, y, g.uv) {
                    Ray::Hit(z, n) => Some((z, n)),
                    Ray::Off => None,
                    Ray::Singular => {
                        approx += 1;
                        Some((g.z, Vec3::z()))
                    }
                };
                if let Some(h) = hit
                    && top.is_none_or(|t| h.0 > t.0)
                {
                    top = Some(h);
                }
            }
            if let Some((z, n)) = top {
                heights[k] = z;
                if let Some(nb) = normals.as_deref_mut() {
                    nb[k] = [n.x as f32, n.y as f32, n.z as f32];
                }
            }
        }
        approx
    }
}

/// Keeps the highest guess of each of the two highest patches.
fn keep_top_two(pair: &mut [Guess; 2], g: Guess) {
    if g.patch == pair[0].patch {
        if g.z > pair[0].z {
            pair[0] = g;
        }
    } else if g.patch == pair[1].patch {
        if g.z > pair[1].z {
            pair[1] = g;
        }
        if pair[1].z > pair[0].z {
            pair.swap(0, 1);
        }
    } else if g.z > pair[0].z {
        pair[1] = pair[0];
        pair[0] = g;
    } else if g.z > pair[1].z {
        pair[1] = g;
    }
}

/// The outcome of a vertical ray against one patch.
enum Ray {
    /// Height and unit upward normal.
    Hit(f64, Vec3),
    /// The ray passes beside the patch.
    Off,
    /// Newton could not proceed (vertical tangent plane).
    Singular,
}

/// Solves `S_xy(u, v) = (x, y)` from `uv`.
fn newton(patch: &PowerPatch, x: f64, y: f64, uv: [f64; 2]) -> Ray {
    let [[u0, u1], [v0, v1]] = patch.domain();
    let (mut u, mut v) = (uv[0], uv[1]);
    let up = |du: Vec3, dv: Vec3| {
        let n = du.cross(&dv);
        let n = if n.z < 0.0 { -n } else { n };
        n.try_normalize(0.0).unwrap_or(Vec3::z())
    };
    let small = [NEWTON_ACCEPT * (u1 - u0), NEWTON_ACCEPT * (v1 - v0)];
    for _ in 0..NEWTON_STEPS {
        let (p, du, dv) = patch.eval1(u, v);
        let (rx, ry) = (x - p.x, y - p.y);
        if rx * rx + ry * ry <= NEWTON_XY * NEWTON_XY {
            return Ray::Hit(p.z, up(du, dv));
        }
        let det = du.x * dv.y - du.y * dv.x;
        if det.is_nan() || det.abs() <= 1e-300 {
            return Ray::Singular;
        }
        let su = (rx * dv.y - ry * dv.x) / det;
        let sv = (du.x * ry - du.y * rx) / det;
        let (cu, cv) = ((u + su).clamp(u0, u1), (v + sv).clamp(v0, v1));
        if cu == u && cv == v {
            return Ray::Off;
        }
        if cu == u + su && cv == v + sv && su.abs() <= small[0] && sv.abs() <= small[1] {
            // The last step is so short that the step after it would be below
            // rounding (quadratic convergence): take the tangent plane's height.
            return Ray::Hit(p.z + du.z * su + dv.z * sv, up(du, dv));
        }
        (u, v) = (cu, cv);
    }
    let (p, du, dv) = patch.eval1(u, v);
    if (x - p.x).hypot(y - p.y) <= 1e3 * NEWTON_XY {
        Ray::Hit(p.z, up(du, dv))
    } else {
        Ray::Off
    }
}

/// Unit normal of a triangle, turned upward, as `f32`.
fn upward(t: &[Point3; 3]) -> [f32; 3] {
    let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
    let n = if n.z < 0.0 { -n } else { n };
    let n = n.try_normalize(0.0).unwrap_or(Vec3::z());
    [n.x as f32, n.y as f32, n.z as f32]
}

/// Samples every patch of `part` on a uniform parameter grid: the triangle mesh, each
/// vertex's `(u, v)`, and each triangle's patch.
fn sample_part(part: &Part) -> (TriMesh, Vec<[f64; 2]>, Vec<u32>) {
    let mut vertices = Vec::new();
    let mut uv = Vec::new();
    let mut triangles = Vec::new();
    let mut patch_of = Vec::new();
    for (pi, patch) in part.patches.iter().enumerate() {
        let [nu, nv] = sample_counts(patch);
        let [[u0, u1], [v0, v1]] = patch.domain();
        let base = vertices.len() as u32;
        for a in 0..=nu {
            for b in 0..=nv {
                let u = u0 + (u1 - u0) * a as f64 / nu as f64;
                let v = v0 + (v1 - v0) * b as f64 / nv as f64;
                vertices.push(patch.eval(u, v));
                uv.push([u, v]);
            }
        }
        let id = |a: usize, b: usize| base + (a * (nv + 1) + b) as u32;
        for a in 0..nu {
            for b in 0..nv {
                triangles.push([id(a, b), id(a + 1, b), id(a + 1, b + 1)]);
                triangles.push([id(a, b), id(a + 1, b + 1), id(a, b + 1)]);
                patch_of.extend([pi as u32; 2]);
            }
        }
    }
    (
        TriMesh {
            vertices,
            triangles,
        },
        uv,
        patch_of,
    )
}

/// Samples per direction: control-net length over [`SAMPLE_SPACING`], clamped.
fn sample_counts(patch: &Patch) -> [usize; 2] {
    let [cu, cv] = patch.count();
    let pt = |i: usize, j: usize| patch.point(i, j);
    let along_u = (0..cv)
        .map(|j| {
            (1..cu)
                .map(|i| (pt(i, j) - pt(i - 1, j)).norm())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let along_v = (0..cu)
        .map(|i| {
            (1..cv)
                .map(|j| (pt(i, j) - pt(i, j - 1)).norm())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    [along_u, along_v]
        .map(|l| ((l / SAMPLE_SPACING).ceil() as usize).clamp(MIN_SAMPLES, MAX_SAMPLES))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::Quiet;

    /// A bicubic Bezier patch over [0, 20] x [0, 10] with z = f(x, y) known in closed
    /// form: x = 20 u, y = 10 v (control points evenly spaced), z bilinear-cubic.
    fn graph_patch() -> (Patch, impl Fn(f64, f64) -> f64) {
        let zc = |i: usize, j: usize| [0.0, 3.0, -1.0, 2.0][i] + [0.0, 1.0, 2.0, 0.5][j];
        let mut pts = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                pts.push(Point3::new(
                    20.0 * i as f64 / 3.0,
                    10.0 * j as f64 / 3.0,
                    zc(i, j),
                ));
            }
        }
        let bern = |t: f64| {
            let s = 1.0 - t;
            [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t]
        };
        let f = move |x: f64, y: f64| {
            let (bu, bv) = (bern(x / 20.0), bern(y / 10.0));
            let mut z = 0.0;
            for (i, bi) in bu.iter().enumerate() {
                for (j, bj) in bv.iter().enumerate() {
                    z += bi * bj * zc(i, j);
                }
            }
            z
        };
        (Patch::bezier([3, 3], pts).unwrap(), f)
    }

    #[test]
    fn part_heights_are_exact_at_cell_centres() {
        let (patch, f) = graph_patch();
        let part = Part {
            name: "graph".into(),
            patches: vec![patch],
        };
        let surf = DesignSurface::new(Design::Part(&part)).unwrap();
        let b = surf.bounds();
        assert!((b.max.x - 20.0).abs() < 1e-12 && (b.max.y - 10.0).abs() < 1e-12);
        let grid = Grid::covering([-1.0, -1.0], [21.0, 11.0], 0.1, 1 << 30).unwrap();
        let field = surf.heights(&grid, true, &Quiet);
        assert_eq!(field.approximate, 0);
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let [x, y] = grid.centre(i, j);
                let z = field.heights[j * grid.nx + i];
                let inside = (0.0..=20.0).contains(&x) && (0.0..=10.0).contains(&y);
                assert_eq!(z.is_finite(), inside, "{x} {y}");
                if inside {
                    assert!((z - f(x, y)).abs() < 1e-9, "{x} {y}: {z} vs {}", f(x, y));
                }
            }
        }
        let n = field.normals.unwrap()[(grid.ny / 2) * grid.nx + grid.nx / 2];
        assert!(n[2] > 0.0 && ((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn mesh_heights_keep_the_upper_envelope() {
        let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let low = [p(0.0, 0.0, 0.0), p(4.0, 0.0, 0.0), p(0.0, 4.0, 0.0)];
        let high = [p(0.0, 0.0, 2.0), p(4.0, 0.0, 2.0), p(0.0, 4.0, 6.0)];
        let mesh = TriMesh::from_triangles(&[low, high]);
        let surf = DesignSurface::new(Design::Mesh(&mesh)).unwrap();
        let grid = Grid::covering([0.0, 0.0], [4.0, 4.0], 0.5, 1 << 20).unwrap();
        let field = surf.heights(&grid, false, &Quiet);
        let [x, y] = grid.centre(1, 2);
        assert!(
            (field.heights[2 * grid.nx + 1] - (2.0 + y)).abs() < 1e-12,
            "{x}"
        );
        assert!(field.heights[grid.len() - 1].is_nan());
        assert!(DesignSurface::new(Design::Mesh(&TriMesh::default())).is_err());
    }
}
