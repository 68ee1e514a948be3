//! Follow-pocket cleanup (thesis 002 §5.4): rings along the region's boundary,
//! working inwards at a constant stepover.
//!
//! The rings are the region's boundary offset inwards (geo's buffers) until nothing
//! is left, each next one at a constant stepover along the surface from the one
//! before ([`crate::stepping`]: the XY step shrinks on slopes and in concave bends
//! where a contact moves faster than the tool). Each ring (outer boundary and
//! holes) is a closed track dropped onto the part exactly
//! ([`swarf_path::track::drop_track`]: refined to the tolerance, split where the
//! tool leaves the part), cut outermost first.

use crate::error::RestError;
use crate::region::RestRegion;
use crate::stepping::step_out;
use geo::{BoundingRect, Buffer, LineString, MultiPolygon};
use swarf_geom::TriMesh;
use swarf_path::track::{Track, drop_track};
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::Pass;

/// The smallest XY step between rings, as a fraction of the stepover.
pub const MIN_STEP_FRACTION: f64 = 0.05;
/// Most rings in one region.
pub const MAX_RINGS: usize = 20_000;

/// The follow-pocket passes of `region`, `stepover` mm apart along the surface.
///
/// # Errors
/// [`RestError::InvalidParameter`] when the region could need more than
/// [`MAX_RINGS`] rings.
pub fn follow_pocket(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    region: &RestRegion,
    stepover: f64,
    tolerance: f64,
) -> Result<Vec<Pass>, RestError> {
    let Some(b) = region.boundary.bounding_rect() else {
        return Ok(Vec::new());
    };
    let min_step = MIN_STEP_FRACTION * stepover;
    let rings = (0.5 * b.width().min(b.height()) / min_step).ceil() + 2.0;
    if rings.is_nan() || rings > MAX_RINGS as f64 {
        return Err(RestError::InvalidParameter {
            field: "scallop".into(),
            value: format!("{stepover} mm stepover"),
            expected: format!(
                "a stepover giving at most {MAX_RINGS} rings across the region \
                 ({rings} could be needed)"
            ),
        });
    }
    let whole = MultiPolygon(vec![region.boundary.clone()]);
    let mut scratch = DropScratch::default();
    let level = |shape: &MultiPolygon<f64>, scratch: &mut DropScratch| -> Vec<Pass> {
        let mut out = Vec::new();
        for poly in &shape.0 {
            for ring in std::iter::once(poly.exterior()).chain(poly.interiors()) {
                out.extend(drop_ring(mesh, dropper, ring, tolerance, scratch));
            }
        }
        out
    };
    let first = level(&whole, &mut scratch);
    let inner = step_out(&first, stepover, min_step, rings as usize, |d| {
        let shape = whole.buffer(-d);
        (!shape.0.is_empty()).then(|| level(&shape, &mut scratch))
    });
    Ok(first
        .into_iter()
        .chain(inner.into_iter().flatten())
        .collect())
}

/// A closed ring dropped onto the part, as passes.
fn drop_ring(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    ring: &LineString<f64>,
    tolerance: f64,
    scratch: &mut DropScratch,
) -> Vec<Pass> {
    let pts: Vec<[f64; 2]> = ring.coords().map(|c| [c.x, c.y]).collect();
    let Some(track) = Track::new(&pts) else {
        return Vec::new();
    };
    drop_track(mesh, dropper, &track, tolerance, scratch)
        .pieces
        .into_iter()
        .map(|points| Pass {
            points,
            ..Pass::default()
        })
        .collect()
}
