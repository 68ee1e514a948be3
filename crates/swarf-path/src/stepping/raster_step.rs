//! Raster stepover from a scallop height, and the scallop a stepover leaves.
//!
//! Raster passes are parallel vertical planes a fixed XY distance `s` apart; the
//! strategy knows nothing of the surface between them, so the stepover comes from a
//! flat-surface model.
//!
//! - **Ball** (radius `R`): on a horizontal plane two passes `s` apart leave the cusp
//!   where the two spheres meet, `h = R - sqrt(R^2 - s^2 / 4)`, i.e.
//!   `s = 2 sqrt(h (2R - h))`, exact.
//! - **Flat, bull, cone, taper ball, APT**: through an *effective radius* `r_e`, the
//!   radius of the ball that leaves the same scallop, with `s = 2 sqrt(h (2 r_e - h))`.
//!   On a horizontal plane a flat bottom leaves no scallop at all (`r_e` infinite), so
//!   the horizontal plane alone is a poor guide. `r_e` is taken as the smallest of
//!   [`crate::stepping::side_step::SideStep::effective_radius`] (the exact 2D scallop of two
//!   profile outlines on a plane tilted across the passes, see [`crate::stepping::side_step`])
//!   over the tilts `0..=`[`MAX_RASTER_TILT_DEG`] degrees: the stepover then keeps the
//!   scallop within `h` on every such plane, measured along the plane, and is smaller
//!   than the horizontal-plane stepover (conservative). A bull gets about its corner
//!   radius, a flat end or a cone the V of its rim or tip.
//!
//! The reported prediction ([`flat_scallop`]) is the exact scallop on a horizontal
//! plane for the stepover used: two copies of the lower envelope `h(rho)` `s` apart
//! meet at `s / 2`, so the cusp height is `h(s / 2)` (0 for a flat bottom wider than
//! the stepover). Steeper surfaces across the passes get larger scallops (a raster's
//! known weakness, thesis 002 §3.1.2); the iso-scallop strategy adapts to them.

use crate::error::PathError;
use crate::stepping::side_step::SideStep;
use swarf_tool::Cutter;
use swarf_tool::drop::Envelope;

/// Tilts up to this angle (degrees) are covered by the conservative effective radius.
pub const MAX_RASTER_TILT_DEG: u32 = 45;

/// The effective radius for scallop limit `h` (mm): the ball's radius, or the least
/// over tilts `0..=MAX_RASTER_TILT_DEG` degrees of the side-step model's.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `scallop` when `h` is not in
/// `(0, tool radius)`.
pub fn effective_radius(cutter: &Cutter, h: f64) -> Result<f64, PathError> {
    let model = SideStep::new(cutter, h)?;
    if let Cutter::Ball { radius, .. } = cutter {
        return Ok(*radius);
    }
    Ok((0..=MAX_RASTER_TILT_DEG)
        .map(|deg| model.effective_radius(f64::from(deg).to_radians()))
        .fold(f64::INFINITY, f64::min))
}

/// XY stepover (mm) for scallop limit `h` (module doc).
///
/// # Errors
/// As [`effective_radius`].
///
/// # Example
/// ```
/// let ball: swarf_tool::Cutter = "ball:d=8".parse().unwrap();
/// let s = swarf_path::stepping::raster_step::stepover_for_scallop(&ball, 0.15).unwrap();
/// assert!((s - 2.0 * (0.15f64 * (8.0 - 0.15)).sqrt()).abs() < 1e-12);
/// ```
pub fn stepover_for_scallop(cutter: &Cutter, h: f64) -> Result<f64, PathError> {
    let re = effective_radius(cutter, h)?;
    Ok(2.0 * (h * (2.0 * re - h)).max(0.0).sqrt())
}

/// Scallop (mm) left on a horizontal plane by passes `s` apart: `h(s / 2)` of the
/// cutter's lower envelope; `None` when `s / 2` is beyond the cutter's reach (the
/// passes leave strips uncut).
pub fn flat_scallop(cutter: &Cutter, s: f64) -> Option<f64> {
    let env = Envelope::new(&cutter.profile());
    let half = 0.5 * s;
    (half.is_finite() && half >= 0.0 && half <= env.radius()).then(|| env.height(half))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cutter(spec: &str) -> Cutter {
        spec.parse().unwrap()
    }

    #[test]
    fn ball_is_exact_and_round_trips() {
        let ball = cutter("ball:d=8");
        for h in [0.001, 0.15, 1.0, 3.9] {
            let s = stepover_for_scallop(&ball, h).unwrap();
            assert!((flat_scallop(&ball, s).unwrap() - h).abs() < 1e-12, "{h}");
        }
        assert_eq!(flat_scallop(&ball, 8.5), None);
    }

    #[test]
    fn other_shapes_step_less_than_on_a_horizontal_plane() {
        // The horizontal-plane stepover is 2 rho(h) (rho: the envelope's radius at
        // height h); the conservative stepover is never larger, and its horizontal
        // scallop never exceeds h.
        for spec in [
            "bull:d=10,r=2",
            "flat:d=6",
            "cone:d=10,angle=90",
            "taperball:d=6,angle=10,tip=1",
        ] {
            let c = cutter(spec);
            let h = 0.15;
            let s = stepover_for_scallop(&c, h).unwrap();
            let horizontal = 2.0 * c.profile().radius_at_height(h).unwrap();
            assert!(
                s > 0.0 && s <= horizontal + 1e-9,
                "{spec}: {s} vs {horizontal}"
            );
            assert!(flat_scallop(&c, s).unwrap() <= h + 1e-9, "{spec}");
        }
        // A bull steps about as its corner radius would (a ball of r = 2).
        let s = stepover_for_scallop(&cutter("bull:d=10,r=2"), 0.15).unwrap();
        let corner = 2.0 * (0.15f64 * (4.0 - 0.15)).sqrt();
        assert!((s - corner).abs() < 0.1 * corner, "{s} vs {corner}");
    }

    #[test]
    fn bad_scallops_are_errors() {
        let ball = cutter("ball:d=8");
        for h in [0.0, -1.0, 4.0, f64::NAN] {
            assert!(stepover_for_scallop(&ball, h).is_err(), "{h}");
        }
    }
}
