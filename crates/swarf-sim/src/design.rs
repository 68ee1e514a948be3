//! The design surface's height at every cell centre: the upper envelope of the part
//! seen along +z (`parts/README.md`), the reference the machined stock is measured
//! against.
//!
//! This is a grid-filling adapter over the one height-field query of the geometry
//! kernel, [`swarf_geom::height`] (its module doc has the derivation): exact Newton on
//! the patches of a parametric part, seeded from their sample triangles, or vertical
//! ray casts on a mesh. Rows are taken in bands of `BAND_ROWS` (16), in parallel; each
//! band scan-converts the triangles the XY index gives for it. Cells where Newton met
//! a singular Jacobian (a vertical tangent plane) keep the sampled height and are
//! counted in [`DesignField::approximate`]. Cells outside every patch's projection are
//! NaN: they are not measured.

use crate::error::SimError;
use crate::grid::Grid;
use crate::progress::Progress;
use rayon::prelude::*;
use swarf_geom::height::{HeightStatus, Lattice, MeshHeights, PartHeights};
use swarf_geom::{Aabb, Part, TriMesh, Vec3};

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
pub enum DesignSurface<'a> {
    /// A parametric part.
    Part(PartHeights),
    /// A triangle mesh.
    Mesh(MeshHeights<'a>),
}

impl Lattice for Grid {
    fn nx(&self) -> usize {
        self.nx
    }
    fn x(&self, i: usize) -> f64 {
        Grid::x(self, i)
    }
    fn y(&self, j: usize) -> f64 {
        Grid::y(self, j)
    }
    fn columns(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
        Grid::columns(self, lo, hi)
    }
    fn rows(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
        Grid::rows(self, lo, hi)
    }
}

fn f32x3(n: Vec3) -> [f32; 3] {
    [n.x as f32, n.y as f32, n.z as f32]
}

impl<'a> DesignSurface<'a> {
    /// Prepares `design` (samples a part's patches, indexes the triangles).
    ///
    /// # Errors
    /// [`SimError::Empty`] for a part without patches or a mesh without triangles;
    /// [`SimError::Unsupported`] for a patch the kernel cannot put in power form.
    pub fn new(design: Design<'a>) -> Result<DesignSurface<'a>, SimError> {
        match design {
            Design::Mesh(m) => {
                if m.is_empty() {
                    return Err(SimError::Empty("the design mesh has no triangle".into()));
                }
                Ok(DesignSurface::Mesh(MeshHeights::new(m)))
            }
            Design::Part(part) => {
                if part.patches.is_empty() {
                    return Err(SimError::Empty(format!("part {}: no patch", part.name)));
                }
                let h = PartHeights::new(part)
                    .map_err(|e| SimError::Unsupported(format!("part {}: {e}", part.name)))?;
                Ok(DesignSurface::Part(h))
            }
        }
    }

    /// Box around the design (the sampled patches, or the mesh), mm.
    pub fn bounds(&self) -> Aabb {
        match self {
            DesignSurface::Part(p) => p.bounds(),
            DesignSurface::Mesh(m) => m.mesh().aabb(),
        }
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
        let mut approx = 0;
        match self {
            DesignSurface::Mesh(m) => m.fill_rows(grid, j0, j1, |k, z, n| {
                heights[k] = z;
                if let Some(nb) = normals.as_deref_mut() {
                    nb[k] = f32x3(n);
                }
            }),
            DesignSurface::Part(p) => p.fill_rows(grid, j0, j1, |k, h| {
                heights[k] = h.z;
                if let Some(nb) = normals.as_deref_mut() {
                    nb[k] = f32x3(h.normal);
                }
                approx += usize::from(h.status == HeightStatus::Singular);
            }),
        }
        progress.advance((j1 - j0 + 1) as u64);
        approx
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::Quiet;
    use swarf_geom::{Patch, Point3};

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
        let part = Part::new("graph", vec![patch]);
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
