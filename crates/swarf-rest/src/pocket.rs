//! Follow-pocket cleanup (thesis 002 §5.4): rings along the region's boundary,
//! working inwards at a constant stepover.
//!
//! The rings are the region's boundary offset inwards by `k s` (geo's buffers),
//! `k = 0, 1, ...` until nothing is left, plus one at `(k + 1/2) s` past the last
//! when that still has area, so that no point of the region is more than `s` from a
//! ring. Each ring (outer boundary and holes) is a closed track dropped onto the
//! part exactly ([`swarf_path::track::drop_track`]: refined to the tolerance, split
//! where the tool leaves the part), cut outermost first.
//!
//! **Stepover along the surface.** On a slope of angle `theta` two rings `s` apart
//! in XY are `s / cos theta` apart along the surface, so the XY step is the surface
//! step times `cos theta` at the steepest facet in the region (the facets whose
//! centroids lie inside its boundary), but not below [`MIN_COS`] times it: on the
//! near-vertical walls that bound a valley the rings crowd onto the wall in XY
//! anyway, and a finer step would only multiply passes.

use crate::error::RestError;
use crate::region::RestRegion;
use geo::{BoundingRect, Buffer, Contains, LineString, MultiPolygon, Point};
use swarf_geom::TriMesh;
use swarf_path::track::{Track, drop_track};
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::Pass;

/// The XY stepover is never below this fraction of the surface stepover.
pub const MIN_COS: f64 = 0.3;
/// Most rings in one region.
pub const MAX_RINGS: usize = 20_000;

/// The follow-pocket passes of `region`, `stepover` mm apart along the surface.
///
/// # Errors
/// [`RestError::InvalidParameter`] when the region would need more than
/// [`MAX_RINGS`] rings.
pub fn follow_pocket(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    region: &RestRegion,
    stepover: f64,
    tolerance: f64,
) -> Result<Vec<Pass>, RestError> {
    let step = stepover * steepest_cos(mesh, region).max(MIN_COS);
    let Some(b) = region.boundary.bounding_rect() else {
        return Ok(Vec::new());
    };
    let rings = (0.5 * b.width().min(b.height()) / step).ceil() + 2.0;
    if !(rings <= MAX_RINGS as f64) {
        return Err(RestError::InvalidParameter {
            field: "strategy.scallop".into(),
            value: format!("{stepover} mm stepover"),
            expected: format!(
                "a stepover giving at most {MAX_RINGS} rings across the region \
                 ({rings} needed)"
            ),
        });
    }
    let whole = MultiPolygon(vec![region.boundary.clone()]);
    let mut levels: Vec<MultiPolygon<f64>> = Vec::new();
    for k in 0..rings as usize {
        let inner = if k == 0 {
            whole.clone()
        } else {
            whole.buffer(-(k as f64) * step)
        };
        if inner.0.is_empty() {
            let half = whole.buffer(-((k as f64) - 0.5) * step);
            if !half.0.is_empty() {
                levels.push(half);
            }
            break;
        }
        levels.push(inner);
    }
    let mut scratch = DropScratch::default();
    let mut out = Vec::new();
    for level in &levels {
        for poly in &level.0 {
            for ring in std::iter::once(poly.exterior()).chain(poly.interiors()) {
                out.extend(drop_ring(mesh, dropper, ring, tolerance, &mut scratch));
            }
        }
    }
    Ok(out)
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
        .map(|points| Pass { points, skim: None })
        .collect()
}

/// The smallest upward normal component of the facets whose centroids lie in the
/// region (1 when none does).
fn steepest_cos(mesh: &TriMesh, region: &RestRegion) -> f64 {
    let Some(b) = region.boundary.bounding_rect() else {
        return 1.0;
    };
    (0..mesh.len())
        .filter_map(|k| {
            let t = mesh.triangles[k].map(|i| mesh.vertices[i as usize]);
            let (cx, cy) = (
                (t[0].x + t[1].x + t[2].x) / 3.0,
                (t[0].y + t[1].y + t[2].y) / 3.0,
            );
            let inside = cx >= b.min().x
                && cx <= b.max().x
                && cy >= b.min().y
                && cy <= b.max().y
                && region.boundary.contains(&Point::new(cx, cy));
            inside.then(|| mesh.normal(k)).flatten().map(|n| n.z.abs())
        })
        .fold(1.0, f64::min)
}
