//! The drop-height field on a square grid: the seed of every level's contour.
//!
//! Every node holds the drop height of the cutter there (`-inf` off the mesh). The
//! grid covers the mesh's XY box grown by the tool radius and two steps, so its
//! border nodes are off the mesh and every contour closes inside it. One field serves
//! every level: a level's contour is only the boundary of `{drop > z}`, and the nodes
//! tell on which side each is (module doc of [`super`]).

use crate::error::PathError;
use rayon::prelude::*;
use swarf_geom::TriMesh;
use swarf_tool::drop::{DropScratch, MeshDropper};

/// Most grid nodes one field may hold (16 bytes each).
pub const MAX_FIELD_NODES: usize = 50_000_000;

/// Drop heights on a grid of `nx` x `ny` nodes `step` apart from `origin`.
#[derive(Debug, Clone)]
pub(crate) struct DropField {
    pub origin: [f64; 2],
    pub step: f64,
    pub nx: usize,
    pub ny: usize,
    heights: Vec<f64>,
}

impl DropField {
    /// Drops the cutter at every node over `mesh` (rows in parallel, collected in
    /// order).
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] on `sampling` when the grid would hold
    /// more than [`MAX_FIELD_NODES`] nodes.
    pub fn sample(
        mesh: &TriMesh,
        dropper: &MeshDropper,
        radius: f64,
        step: f64,
    ) -> Result<DropField, PathError> {
        let b = mesh.aabb();
        let grow = radius + 2.0 * step;
        let origin = [b.min.x - grow, b.min.y - grow];
        let count = |lo: f64, hi: f64| ((hi - lo + 2.0 * grow) / step).ceil() + 1.0;
        let (fx, fy) = (count(b.min.x, b.max.x), count(b.min.y, b.max.y));
        let nodes = fx * fy;
        if nodes.is_nan() || nodes > MAX_FIELD_NODES as f64 {
            return Err(PathError::InvalidParameter {
                field: "sampling".into(),
                message: format!(
                    "{step} mm over a {:.1} x {:.1} mm part needs {fx:.0} x {fy:.0} drop \
                     points, more than the limit of {MAX_FIELD_NODES}: expected a coarser \
                     sampling",
                    b.max.x - b.min.x,
                    b.max.y - b.min.y
                ),
            });
        }
        let (nx, ny) = (fx as usize, fy as usize);
        let heights = (0..ny)
            .into_par_iter()
            .map_init(DropScratch::default, |scratch, j| {
                let y = origin[1] + step * j as f64;
                (0..nx)
                    .map(|i| {
                        let x = origin[0] + step * i as f64;
                        dropper
                            .drop(x, y, scratch)
                            .map_or(f64::NEG_INFINITY, |h| h.z)
                    })
                    .collect::<Vec<f64>>()
            })
            .flatten_iter()
            .collect();
        Ok(DropField {
            origin,
            step,
            nx,
            ny,
            heights,
        })
    }

    /// Drop height at node `(i, j)` (`-inf` off the mesh).
    pub fn height(&self, i: usize, j: usize) -> f64 {
        self.heights[j * self.nx + i]
    }

    /// XY of node `(i, j)`.
    pub fn xy(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.origin[0] + self.step * i as f64,
            self.origin[1] + self.step * j as f64,
        ]
    }

    /// The highest drop height (`-inf` when the cutter touches nothing).
    pub fn top(&self) -> f64 {
        self.heights
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }
}
