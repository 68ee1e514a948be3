//! Steep rest: the walls a raster leaves too much on, and their cleanup with Z-level
//! passes (thesis 002 §3.1.2 and §6.2.2).
//!
//! **Where.** Raster passes `d` apart in XY, fed along `phi`, lie `d / cos(s)` apart
//! along a facet whose slope across them is `s` (`sin s = |n . c|` with `c` the XY
//! unit vector across the passes, [`swarf_path::classify`]); the scallop they leave
//! there is [`raster_scallop`], which grows with `s` (the step along the facet grows)
//! until the passes leave a strip uncut. The steep rest is every facet whose slope
//! across the passes exceeds `s*`, the least slope at which that scallop exceeds
//! the threshold, found by bisection to [`ANGLE_TOL`]. For a ball of radius `R` and
//! a threshold `t` on the ball it is `cos s* = d / (2 sqrt(2Rt - t²))`.
//!
//! **Cleanup.** The facets are classified on the Go board with `s*` as the steep
//! angle and the parent's feed angle; the cleanup tool's waterline levels, spaced
//! for every slope from `s*` up ([`swarf_path::stepping::slope_step::zlevel_spacing`]), are
//! kept where their contacts lie in the steep cells grown by the overlap
//! ([`steep_levels`]). A facet's steepest slope is at least its slope across the
//! passes, so the levels keep the scallop within the cleanup's on all of it.
//!
//! A parent whose scallop stays within the threshold on every facet (its slopes
//! across the passes all below `s*`) leaves no steep rest: no passes, not an error.

use crate::error::RestError;
use swarf_geom::TriMesh;
use swarf_path::Cutting;
use swarf_path::classify::{ClassRegion, ClassifyParams, classify};
use swarf_path::stepping::slope_step::raster_scallop;
use swarf_path::strategy::steep_shallow::steep_levels;
use swarf_path::strategy::waterline::WaterlineParams;
use swarf_tool::Cutter;
use swarf_toolpath::Pass;

/// The bisection for the steep rest angle stops when its bracket is this narrow,
/// radians.
pub const ANGLE_TOL: f64 = 1e-9;

/// The raster that finished before the cleanup.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RasterParent {
    /// Its tool.
    pub tool: Cutter,
    /// The XY spacing of its passes, mm.
    pub spacing: f64,
    /// Its feed direction in the XY plane from +X, radians.
    pub feed_angle: f64,
}

/// Parameters of a steep cleanup.
#[derive(Debug, Clone, PartialEq)]
pub struct SteepParams {
    /// The cleanup levels: scallop, milling direction, sampling (the Go-board cell
    /// too). Their steep and flat angles are set from the steep rest angle.
    pub waterline: WaterlineParams,
    /// Scallop the parent may leave, mm: thicker is steep rest.
    pub threshold: f64,
    /// The levels reach this far past the steep rest, mm.
    pub overlap: f64,
}

/// The steep rest of a raster, as its cleanup found it.
#[derive(Debug, Clone, PartialEq)]
pub struct SteepRest {
    /// Slope across the parent's passes above which it leaves rest, radians.
    pub angle: f64,
    /// The steep rest: the facets sloping more than `angle` across the passes.
    pub region: ClassRegion,
    /// Range of the Z steps between the cleanup levels, mm (`None` without passes).
    pub level_step: Option<[f64; 2]>,
}

/// The least slope across `parent`'s passes (radians) at which its scallop exceeds
/// `threshold` (module doc).
///
/// # Errors
/// [`RestError::InvalidParameter`] on `threshold` when it is not a
/// finite length above 0 or when the parent already leaves more than it on a
/// level floor; on `parent.spacing` for a spacing that is not above 0.
pub fn steep_rest_angle(parent: &RasterParent, threshold: f64) -> Result<f64, RestError> {
    RestError::check("threshold", threshold, false)?;
    RestError::check("parent.spacing", parent.spacing, false)?;
    let leaves =
        |s: f64| raster_scallop(&parent.tool, parent.spacing, s).is_none_or(|h| h > threshold);
    if leaves(0.0) {
        return Err(RestError::InvalidParameter {
            field: "threshold".into(),
            value: threshold.to_string(),
            expected: format!(
                "a scallop above the {} mm the parent's passes {} mm apart leave on a level floor \
                 (steep rest cannot tell walls from floors there)",
                raster_scallop(&parent.tool, parent.spacing, 0.0)
                    .map_or_else(|| "strip".to_string(), |h| format!("{h:.6}")),
                parent.spacing
            ),
        });
    }
    let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
    while hi - lo > ANGLE_TOL {
        let mid = 0.5 * (lo + hi);
        if leaves(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

/// The steep rest `parent` leaves on `mesh` and the Z-level passes of `cutting`'s
/// tool that clean it up, top level first (module doc; none where there is no steep
/// rest).
///
/// # Errors
/// As [`steep_rest_angle`]; [`RestError::InvalidParameter`] on `overlap`
/// when it is negative; the classification's and the waterline's errors.
pub fn plan_steep(
    mesh: &TriMesh,
    parent: &RasterParent,
    cutting: &Cutting,
    params: &SteepParams,
) -> Result<(SteepRest, Vec<Pass>), RestError> {
    RestError::check("overlap", params.overlap, true)?;
    let angle = steep_rest_angle(parent, params.threshold)?;
    let wl = &params.waterline;
    let cell = wl.sampling.unwrap_or(0.25 * cutting.tool.radius());
    let classes = classify(
        mesh,
        &ClassifyParams {
            steep_angle: angle,
            flat_angle: 0.5 * angle,
            cell,
            feed_angle: Some(parent.feed_angle),
        },
    )?;
    let (passes, level_step) = if classes.steep.cells > 0 {
        let levels = WaterlineParams {
            steep_angle: angle,
            flat_angle: 0.5 * angle,
            adaptive: false,
            sampling: Some(cell),
            ..*wl
        };
        steep_levels(mesh, &classes.grid, cutting, &levels, params.overlap)?
    } else {
        (Vec::new(), None)
    };
    let rest = SteepRest {
        angle,
        region: classes.steep,
        level_step: level_step.filter(|_| !passes.is_empty()),
    };
    Ok((rest, passes))
}
