//! Slope-aware spacing: raster and Z-level spacings that keep the scallop within `h`
//! on every slope of a range, and the scallop a spacing leaves on a slope.
//!
//! Thesis 002 §3.1.2: passes on the planes `y = y0 + d i` lie `d / cos(a)` apart along
//! a surface tilted by `a` across them; §6.2 derives the raster interval
//! `h / sin(b)` and §6.3 the Z-level interval `h / cos(b)` for a flat end at the
//! steepness threshold `b`, then claims a ball is safer. It is not: as `b -> 0` the
//! raster interval grows without bound while a ball's scallop on a level floor does
//! not vanish. The forms below hold per cutter shape.
//!
//! **Distance along the slope.** A vertical tool moved across a plane tilted by
//! `theta` (in the section normal to the feed) touches it at the same point of the
//! tool, so the contacts move by the tool's move projected on the plane: raster
//! passes `s` apart in XY are `w = s / cos(theta)` apart along the plane, Z-levels
//! `dz` apart are `w = dz / sin(theta)` apart.
//!
//! **Scallop between two contacts `w` apart on a plane.** Fed horizontally, a
//! vertical tool sweeps its meridian outline in that section
//! ([`crate::stepping::side_step`]); the scallop is that of two outlines touching the line `w`
//! apart, measured normal to it:
//! - **ball** (radius `R`): two circles, cusp midway, `h = R - sqrt(R^2 - w^2 / 4)`,
//!   so `w = 2 sqrt(2Rh - h^2)`, while the cusp stays on the ball: the contact is
//!   `theta` from its bottom, so the sphere reaches `90° - theta` uphill of it before
//!   the shank, `w / 2 <= R cos(theta)`. Beyond, on steep walls, the shank cuts the
//!   cusp lower (the tool contains the sphere: see the bull), so the form is then a
//!   bound;
//! - **bull** (corner radius `r`): the tool contains its corner disk, and on a plane
//!   the disk touches where the tool does (on the uphill corner, or anywhere on the
//!   floor at `theta = 0`); the tool's outline is never above the disk's, so the
//!   scallop is at most the ball's of radius `r`, `w >= 2 sqrt(2rh - h^2)`, with
//!   equality while both contacts and the cusp stay on the corner arcs (the cusp
//!   at `asin(w / 2r)` from the contact, within the downhill arc's `theta` and the
//!   uphill arc's `90° - theta`: `w / 2 <= r min(sin(theta), cos(theta))`). A level
//!   floor (`theta = 0`) is cut flat up to the floor width;
//! - **flat end** (radius `R`): the rim touches; the uncut region is the triangle
//!   between the plane, the first tool's side (at `90° - theta` to the plane) and
//!   the second tool's bottom (at `theta`), whose apex angle is `90°`: its height is
//!   `h = w sin(theta) cos(theta)`, while the bottom reaches (`w cos(theta) <= 2R`);
//! - **any other shape**: the exact 2D model of [`crate::stepping::side_step`] (its effective
//!   radius at that tilt, and [`side_step::plane_scallop`] for the forward figure).
//!
//! **Spacings.** The scallop holds on every slope of a range when the spacing is the
//! least over the range of `w(theta) cos(theta)` (raster, slopes `[0, theta_s]`) or
//! `w(theta) sin(theta)` (Z-level, slopes `[theta_s, 90°]`). For the ball's and the
//! bull's circle `w` is constant, so the least is at `theta_s`:
//! raster `2 cos(theta_s) sqrt(2Rh - h^2)`, Z-level `2 sin(theta_s) sqrt(2Rh - h^2)`
//! (`R` the corner radius for a bull): exact where the cusp stays on the ball or
//! the corner arcs at `theta_s`, a safe lower bound elsewhere. A bull takes the
//! larger of it and the side-step model's spacing below (the side-step model
//! treats a ball as its sphere, so a ball keeps the bound). For the flat end the raster spacing is
//! `h / sin(theta)` (least at `theta_s`, the thesis's form) but at most the diameter
//! `2R`, and the Z-level spacing `h / cos(theta)` (least at `theta_s`) but at most
//! `2R tan(theta_s)`, where the bottom still reaches. Other shapes take the least
//! over [`SLOPE_SAMPLES`] slopes of the side-step model (whose half-degree table
//! holds the scallop to about `1e-5 h` in the tests).

use crate::error::PathError;
use crate::stepping::side_step::{self, SideStep, ball_step, check_scallop};
use std::f64::consts::FRAC_PI_2;
use swarf_geom::units::shown_degrees;
use swarf_tool::Cutter;

/// Slopes sampled over a range by the general-cutter spacings and by
/// [`raster_max_scallop`] (at most one degree apart).
pub const SLOPE_SAMPLES: usize = 90;

/// Which closed form a cutter takes at a scallop height.
#[derive(Debug, Clone, Copy)]
enum Form {
    /// A ball of this radius.
    Circle(f64),
    /// A bull of this corner radius: the larger of the corner bound and the
    /// side-step model.
    Corner(f64),
    /// A flat end of this radius (the V of the rim).
    Rim(f64),
    /// The side-step model.
    General,
}

fn form(cutter: &Cutter, h: f64) -> Form {
    match *cutter {
        Cutter::Ball { radius, .. } => Form::Circle(radius),
        Cutter::Flat { radius, .. } => Form::Rim(radius),
        Cutter::Bull { radius, corner, .. } if corner <= 0.0 => Form::Rim(radius),
        Cutter::Bull { corner, .. } if h < corner => Form::Corner(corner),
        _ => Form::General,
    }
}

/// XY spacing (mm) of raster passes that leaves a scallop of at most `h` on every
/// plane sloping up to `max_slope` across the passes (module doc): a ball's
/// `2 cos(max_slope) sqrt(2Rh - h^2)`, a bull's at least that with its corner radius
/// (equal where the cusp stays on the corner arcs), a flat end's
/// `min(h / sin(max_slope), 2R)`.
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `scallop` when `h` is not in
/// `(0, tool radius)`, on `max_slope` when the slope is not in `(0, 90)`
/// degrees.
///
/// # Example
/// ```
/// let ball: swarf_tool::Cutter = "ball:d=10".parse().unwrap();
/// let s = swarf_path::stepping::slope_step::raster_spacing(&ball, 0.1, 60f64.to_radians()).unwrap();
/// assert!((s - 0.5 * 2.0 * (2.0 * 5.0 * 0.1 - 0.01f64).sqrt()).abs() < 1e-12);
/// ```
pub fn raster_spacing(cutter: &Cutter, h: f64, max_slope: f64) -> Result<f64, PathError> {
    check_scallop(cutter, h)?;
    check_slope("max_slope", max_slope)?;
    let (sin, cos) = max_slope.sin_cos();
    let general = || -> Result<f64, PathError> {
        let model = SideStep::new(cutter, h)?;
        let slopes = slope_fractions().map(|f| max_slope * f);
        Ok(least(slopes, |t| model.step(0.0, t) * t.cos()).min(2.0 * cutter.radius()))
    };
    Ok(match form(cutter, h) {
        Form::Circle(r) => circle_step(r, h) * cos,
        Form::Corner(r) => general()?.max(circle_step(r, h) * cos),
        Form::Rim(r) => (h / sin).min(2.0 * r),
        Form::General => general()?,
    })
}

/// Z-level spacing (mm) that leaves a scallop of at most `h` on every plane of slope
/// `min_slope` to 90 degrees (module doc): a ball's
/// `2 sin(min_slope) sqrt(2Rh - h^2)`, a bull's at least that with its corner radius
/// (equal where the cusp stays on the corner arcs), a flat end's
/// `min(h / cos(min_slope), 2R tan(min_slope))`.
///
/// # Units
/// mm, radians.
///
/// # Errors
/// As [`raster_spacing`], on `min_slope` for the slope.
///
/// # Example
/// ```
/// let flat: swarf_tool::Cutter = "flat:d=10".parse().unwrap();
/// let dz = swarf_path::stepping::slope_step::zlevel_spacing(&flat, 0.1, 60f64.to_radians()).unwrap();
/// assert!((dz - 0.2).abs() < 1e-12);
/// ```
pub fn zlevel_spacing(cutter: &Cutter, h: f64, min_slope: f64) -> Result<f64, PathError> {
    check_scallop(cutter, h)?;
    check_slope("min_slope", min_slope)?;
    let (sin, cos) = min_slope.sin_cos();
    let general = || -> Result<f64, PathError> {
        let model = SideStep::new(cutter, h)?;
        let span = FRAC_PI_2 - min_slope;
        let slopes = slope_fractions().map(|f| min_slope + span * f);
        Ok(least(slopes, |t| model.step(0.0, t) * t.sin()))
    };
    Ok(match form(cutter, h) {
        Form::Circle(r) => circle_step(r, h) * sin,
        Form::Corner(r) => general()?.max(circle_step(r, h) * sin),
        Form::Rim(r) => (h / cos).min(2.0 * r * sin / cos),
        Form::General => general()?,
    })
}

/// Scallop (mm, normal to the plane) between two passes whose contacts are `step`
/// apart along a plane of slope `slope` across them: the exact section of the
/// cutter's outline, shank included ([`side_step::plane_scallop`]; module doc).
/// `None` for a slope outside `[0, 90)` degrees, a negative or non-finite step, or
/// a step that leaves a strip uncut.
///
/// # Units
/// mm, radians.
pub fn surface_scallop(cutter: &Cutter, step: f64, slope: f64) -> Option<f64> {
    side_step::plane_scallop(&cutter.profile(), slope, step)
}

/// Scallop (mm, normal to the plane) left by raster passes `spacing` apart in XY on
/// a plane of slope `slope` across them: [`surface_scallop`] at
/// `spacing / cos(slope)`.
///
/// # Units
/// mm, radians.
///
/// # Example
/// ```
/// let flat: swarf_tool::Cutter = "flat:d=10".parse().unwrap();
/// let h = swarf_path::stepping::slope_step::raster_scallop(&flat, 1.0, 30f64.to_radians()).unwrap();
/// assert!((h - 0.5).abs() < 1e-9);
/// ```
pub fn raster_scallop(cutter: &Cutter, spacing: f64, slope: f64) -> Option<f64> {
    surface_scallop(cutter, spacing / slope.cos(), slope)
}

/// Scallop (mm, normal to the plane) left by Z-levels `dz` apart on a plane of slope
/// `slope`: [`surface_scallop`] at `dz / sin(slope)`; `None` also for a slope of 0.
///
/// # Units
/// mm, radians.
pub fn zlevel_scallop(cutter: &Cutter, dz: f64, slope: f64) -> Option<f64> {
    (slope > 0.0)
        .then(|| surface_scallop(cutter, dz / slope.sin(), slope))
        .flatten()
}

/// The largest [`raster_scallop`] (mm) over slopes `0..=max_slope` (radians),
/// sampled at [`SLOPE_SAMPLES`] intervals; `None` where the spacing leaves a strip
/// uncut on one of them or for a slope outside `[0, 90)` degrees.
pub fn raster_max_scallop(cutter: &Cutter, spacing: f64, max_slope: f64) -> Option<f64> {
    slope_fractions()
        .map(|f| raster_scallop(cutter, spacing, max_slope * f))
        .try_fold(0.0f64, |m, h| h.map(|h| m.max(h)))
}

/// Checks a slope limit: finite, in `(0, 90)` degrees.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `field` otherwise.
pub fn check_slope(field: &str, slope: f64) -> Result<(), PathError> {
    if slope > 0.0 && slope < FRAC_PI_2 {
        return Ok(());
    }
    Err(PathError::InvalidParameter {
        field: field.into(),
        message: format!(
            "{} degrees: expected a slope between 0 and 90 degrees",
            shown_degrees(slope)
        ),
    })
}

/// Step along a plane (mm) between two circles of radius `r` that leaves scallop `h`:
/// `2 sqrt(2rh - h^2)`.
fn circle_step(r: f64, h: f64) -> f64 {
    ball_step(r, 0.0, h).unwrap_or(0.0)
}

/// `k / SLOPE_SAMPLES` for `k = 0..=SLOPE_SAMPLES`.
fn slope_fractions() -> impl Iterator<Item = f64> {
    (0..=SLOPE_SAMPLES).map(|k| k as f64 / SLOPE_SAMPLES as f64)
}

/// The least of `f` over `slopes`.
fn least(slopes: impl Iterator<Item = f64>, f: impl Fn(f64) -> f64) -> f64 {
    slopes.map(f).fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cutter(spec: &str) -> Cutter {
        spec.parse().unwrap()
    }

    fn close(a: f64, b: f64, eps: f64) -> bool {
        (a - b).abs() <= eps
    }

    const SLOPES_DEG: [f64; 5] = [5.0, 30.0, 45.0, 60.0, 85.0];

    #[test]
    fn ball_spacings_are_the_closed_forms() {
        let (ball, r) = (cutter("ball:d=10"), 5.0f64);
        for h in [0.01, 0.1, 1.0, 4.5] {
            // The two circles a chord c apart meet c / 2 from each contact.
            let chord = 2.0 * (r * r - (r - h) * (r - h)).sqrt();
            for t in SLOPES_DEG.map(f64::to_radians) {
                let s = raster_spacing(&ball, h, t).unwrap();
                let dz = zlevel_spacing(&ball, h, t).unwrap();
                assert!(close(s, chord * t.cos(), 1e-12), "{h} {t}: {s}");
                assert!(close(dz, chord * t.sin(), 1e-12), "{h} {t}: {dz}");
            }
        }
        // Cusps on the sphere (w / 2 <= R cos t).
        for (s, t) in [(1.0, 0.0f64), (1.0, 60.0), (0.03, 85.0)] {
            let t = t.to_radians();
            let half = 0.5 * s / t.cos();
            let want = r - (r * r - half * half).sqrt();
            assert!(close(raster_scallop(&ball, s, t).unwrap(), want, 1e-12));
            let dz = s * t.tan();
            if t > 0.0 {
                assert!(close(zlevel_scallop(&ball, dz, t).unwrap(), want, 1e-12));
            }
        }
        assert_eq!(raster_scallop(&ball, 10.5, 0.0), None);
        // Past the equator the shank cuts the cusp lower than the sphere would.
        let t = 85f64.to_radians();
        let sphere = r - (r * r - (0.15 / t.cos()).powi(2)).sqrt();
        let got = raster_scallop(&ball, 0.3, t).unwrap();
        assert!(got < 0.9 * sphere && got > 0.0, "{got} vs {sphere}");
    }

    #[test]
    fn flat_end_spacings_are_the_rim_v() {
        let (flat, r) = (cutter("flat:d=10"), 5.0f64);
        for t in SLOPES_DEG.map(f64::to_radians) {
            let h = 0.1;
            // The thesis's intervals, h / sin and h / cos, within the tool's reach.
            let s = raster_spacing(&flat, h, t).unwrap();
            assert!(close(s, (h / t.sin()).min(2.0 * r), 1e-12), "{t}: {s}");
            let dz = zlevel_spacing(&flat, h, t).unwrap();
            assert!(close(dz, (h / t.cos()).min(2.0 * r * t.tan()), 1e-12));
            // Forward: h = w sin cos, w the distance along the plane.
            let w = 1.5;
            let want = w * t.sin() * t.cos();
            let got = raster_scallop(&flat, w * t.cos(), t).unwrap();
            assert!(close(got, want, 1e-9), "{t}: {got} vs {want}");
            let got = zlevel_scallop(&flat, w * t.sin(), t).unwrap();
            assert!(close(got, want, 1e-9), "{t}: {got} vs {want}");
        }
        // The h / sin form has no bound on a level floor; the tool's width does.
        assert!(close(
            raster_spacing(&flat, 0.1, 0.001).unwrap(),
            10.0,
            1e-12
        ));
        assert!(close(raster_scallop(&flat, 9.0, 0.0).unwrap(), 0.0, 1e-9));
        assert_eq!(raster_scallop(&flat, 10.5, 0.0), None);
    }

    #[test]
    fn bull_spacings_use_the_corner_radius() {
        let bull = cutter("bull:d=10,r=2");
        let (r, a) = (2.0f64, 3.0f64);
        for h in [0.05, 0.1, 1.0] {
            let chord = 2.0 * (r * r - (r - h) * (r - h)).sqrt();
            for t in SLOPES_DEG.map(f64::to_radians) {
                let (s, dz) = (chord * t.cos(), chord * t.sin());
                let got = [raster_spacing(&bull, h, t), zlevel_spacing(&bull, h, t)];
                let got = got.map(Result::unwrap);
                // The cusp, chord / 2 from each contact, on both corner arcs: exact
                // (within the side-step table); elsewhere the corner form is a bound.
                let on_arcs = 0.5 * chord <= r * t.sin().min(t.cos());
                if on_arcs {
                    assert!(close(got[0], s, 1e-4 * s), "{h} {t}: {got:?}");
                    assert!(close(got[1], dz, 1e-4 * dz), "{h} {t}: {got:?}");
                }
                assert!(got[0] >= s - 1e-12 && got[1] >= dz - 1e-12, "{h} {t}");
            }
        }
        // Both contacts and the cusp on the corner arcs at 45 degrees: the corner's
        // circle; 1 mm from each contact is within r sin 45 of both.
        let t = 45f64.to_radians();
        let want = r - (r * r - 1.0f64).sqrt();
        let got = raster_scallop(&bull, 2.0 * t.cos(), t).unwrap();
        assert!(close(got, want, 1e-9), "{got} vs {want}");
        // A level floor: flat up to the floor width 2a, then the corner arcs.
        assert!(close(raster_scallop(&bull, 5.9, 0.0).unwrap(), 0.0, 1e-9));
        let got = raster_scallop(&bull, 2.0 * a + 2.0, 0.0).unwrap();
        assert!(close(got, want, 1e-9), "{got} vs {want}");
    }

    #[test]
    fn bad_inputs_name_the_field_in_degrees() {
        let ball = cutter("ball:d=10");
        for h in [0.0, -1.0, 5.0, f64::NAN, f64::INFINITY] {
            let e = raster_spacing(&ball, h, 0.5).unwrap_err().to_string();
            assert!(e.starts_with("scallop"), "{e}");
            assert!(zlevel_spacing(&ball, h, 0.5).is_err());
        }
        for t in [0.0, -0.1, 90f64.to_radians(), f64::NAN, f64::INFINITY] {
            let e = raster_spacing(&ball, 0.1, t).unwrap_err().to_string();
            assert!(e.starts_with("max_slope"), "{e}");
            let e = zlevel_spacing(&ball, 0.1, t).unwrap_err().to_string();
            assert!(e.starts_with("min_slope"), "{e}");
        }
        let e = check_slope("f", 90f64.to_radians())
            .unwrap_err()
            .to_string();
        assert!(e.contains("f: 90 degrees"), "{e}");
        for c in [ball, cutter("bull:d=10,r=2")] {
            assert_eq!(raster_scallop(&c, 1.0, 90f64.to_radians()), None);
            assert_eq!(raster_scallop(&c, f64::NAN, 0.3), None);
            assert_eq!(raster_scallop(&c, -1.0, 0.3), None);
            assert_eq!(zlevel_scallop(&c, 1.0, 0.0), None);
            assert_eq!(raster_max_scallop(&c, 1.0, f64::NAN), None);
        }
    }
}
