//! Level heights: evenly spaced from the scallop on the steepest-allowed wall, and
//! extra levels where the wall between two levels flattens.
//!
//! Levels `dz` apart meet a wall of slope `theta` (from horizontal) `dz / sin(theta)`
//! apart along it. The base spacing is [`crate::stepping::slope_step::zlevel_spacing`] for the
//! steep angle (a ball's `2 sin(steep_angle) sqrt(2Rh - h^2)`), so every wall at least
//! that steep keeps the scallop within `h`.
//!
//! Adaptive levels (as OpenCAMLib's AdaptiveWaterline refines where the contour
//! changes): for two consecutive levels the points of the lower contour are measured
//! to the upper contour in XY (`d`); the wall between them has slope
//! `atan(dz / d)` and the passes are `hypot(d, dz)` apart along it. Where that
//! predicts a scallop above `h` on a wall steeper than `flat_angle` (flatter areas
//! belong to a raster), the level halfway between is added and both halves are
//! checked again, down to the spacing that covers walls at `flat_angle`.

use super::contour::Loop;
use crate::error::PathError;
use crate::stepping::side_step::SideStep;

/// Most levels one waterline may cut.
pub const MAX_LEVELS: usize = 20_000;

/// Levels from `top` (excluded) down to `bottom` (included), evenly spaced at most
/// `dz` apart, descending.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `level_step` when that takes more than
/// [`MAX_LEVELS`] levels.
pub(crate) fn even_levels(top: f64, bottom: f64, dz: f64) -> Result<Vec<f64>, PathError> {
    if top <= bottom {
        return Ok(Vec::new());
    }
    let n = ((top - bottom) / dz).ceil();
    if n.is_nan() || n > MAX_LEVELS as f64 {
        return Err(too_many(top - bottom, dz));
    }
    let n = (n as usize).max(1);
    let step = (top - bottom) / n as f64;
    Ok((1..=n).map(|k| top - step * k as f64).collect())
}

pub(crate) fn too_many(height: f64, dz: f64) -> PathError {
    PathError::InvalidParameter {
        field: "level_step".into(),
        message: format!(
            "levels {dz:.6} mm apart over {height:.3} mm of height need more than \
             {MAX_LEVELS} levels: expected a larger level step or scallop"
        ),
    }
}

/// True when the passes of `upper` and `lower` (levels `dz` apart) leave a scallop
/// above the model's `h` somewhere on a wall steeper than `flat_angle`.
pub(crate) fn needs_split(
    upper: &[Loop],
    lower: &[Loop],
    dz: f64,
    model: &SideStep,
    flat_angle: f64,
) -> bool {
    let max_d = dz / flat_angle.tan().max(1e-12);
    let segments: Vec<[[f64; 2]; 2]> = upper
        .iter()
        .flat_map(|lp| (0..lp.len()).map(move |k| [lp[k].xy, lp[(k + 1) % lp.len()].xy]))
        .collect();
    if segments.is_empty() {
        return false;
    }
    let index = super::nearest::SegmentIndex::new(&segments, max_d);
    lower.iter().flatten().any(|p| {
        let Some(d) = index.distance_within(p.xy, max_d) else {
            return false;
        };
        let theta = dz.atan2(d);
        model
            .scallop(d.hypot(dz), 0.0, theta)
            .is_none_or(|s| s > model.h())
    })
}

/// `levels` (descending, with their loops) with levels added halfway wherever
/// [`needs_split`] holds, never closer than `min_dz`; `contour` makes a level's loops.
///
/// # Errors
/// As [`even_levels`] when the total exceeds [`MAX_LEVELS`].
pub(crate) fn refine(
    levels: Vec<(f64, Vec<Loop>)>,
    contour: impl Fn(f64) -> Vec<Loop>,
    model: &SideStep,
    flat_angle: f64,
    min_dz: f64,
) -> Result<Vec<(f64, Vec<Loop>)>, PathError> {
    let mut out: Vec<(f64, Vec<Loop>)> = Vec::with_capacity(levels.len());
    let height = levels.first().map_or(0.0, |l| l.0) - levels.last().map_or(0.0, |l| l.0);
    for level in levels {
        // Levels between the last one kept and this one, found depth first.
        let mut stack = vec![level];
        while let Some(lower) = stack.pop() {
            let split = out.last().is_some_and(|upper| {
                let dz = upper.0 - lower.0;
                0.5 * dz >= min_dz && needs_split(&upper.1, &lower.1, dz, model, flat_angle)
            });
            if !split {
                out.push(lower);
                if out.len() > MAX_LEVELS {
                    return Err(too_many(height, min_dz));
                }
                continue;
            }
            let mid = 0.5 * (out.last().map_or(lower.0, |u| u.0) + lower.0);
            stack.push(lower);
            stack.push((mid, contour(mid)));
        }
    }
    Ok(out)
}
