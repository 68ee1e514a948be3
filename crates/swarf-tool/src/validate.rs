//! Validation of cutters and their flute lengths.
//!
//! Errors speak the spec's language ([`crate::spec`]): diameters, degrees, and the
//! spec's field names, whichever way the cutter was built. The flute length must reach
//! the top of the profile's curved part (`length_bounds().0`: the ball's equator, the
//! bull's corner top, the cone's full radius, the taper ball's ball-to-taper joint,
//! the APT side line's start) and may not pass `length_bounds().1` (where a taper ball's
//! taper reaches its shank diameter, where a narrowing APT side line reaches the axis).
//! A length short of the need by rounding ([`LENGTH_SNAP`]) is raised to it.

use crate::apt::{Apt, LENGTH_SNAP};
use crate::cutter::Cutter;
use crate::error::ToolError;
use std::f64::consts::FRAC_PI_2;
use swarf_geom::domain::{Domain, TOOL_DIAMETER, TOOL_LENGTH};

fn finite(field: &'static str, value: f64) -> Result<(), ToolError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ToolError::NotFinite { field, value })
    }
}

/// The least corner radius of a bull nose, mm (0 is a sharp corner): a thousandth of a
/// millimetre, below any ground insert, and where strategies that offset by the corner
/// would work at sub-micrometre steps.
pub const MIN_CORNER: f64 = 1e-3;

fn check_radius(radius: f64) -> Result<(), ToolError> {
    finite("d", 2.0 * radius)?;
    if radius <= 0.0 {
        return Err(ToolError::NotPositive {
            field: "d",
            value: 2.0 * radius,
        });
    }
    in_domain("d", 2.0 * radius, TOOL_DIAMETER)
}

/// `value` of `field` within `domain`.
pub(crate) fn in_domain(field: &'static str, value: f64, domain: Domain) -> Result<(), ToolError> {
    domain
        .check(value)
        .map(|_| ())
        .map_err(|message| ToolError::OutOfDomain { field, message })
}

fn check_at_most(field: &'static str, value: f64, limit: f64) -> Result<(), ToolError> {
    finite(field, value)?;
    if value > limit {
        return Err(ToolError::TooLarge {
            field,
            value,
            limit,
            why: "d/2",
        });
    }
    Ok(())
}

impl Cutter {
    /// The same shape with flute length `length` (checked), or the default length.
    ///
    /// # Errors
    /// The shape's own errors (see [`Cutter::validate`]); `length` not finite, <= 0,
    /// shorter than the profile needs or longer than it can reach.
    pub fn with_length(mut self, length: Option<f64>) -> Result<Cutter, ToolError> {
        if let Cutter::Apt(a) = self {
            let apt = Apt::from_parts(a.d, a.r, Some(a.e), Some(a.f), a.alpha, a.beta, length)?;
            return Ok(Cutter::Apt(apt));
        }
        self.check_shape()?;
        let l = match length {
            Some(l) => self.checked_length(l)?,
            None => self.default_length(),
        };
        match &mut self {
            Cutter::Flat { length, .. }
            | Cutter::Ball { length, .. }
            | Cutter::Bull { length, .. }
            | Cutter::Cone { length, .. }
            | Cutter::TaperBall { length, .. } => *length = l,
            Cutter::Apt(a) => a.h = l,
        }
        Ok(self)
    }

    /// Checks every parameter as the constructors do.
    ///
    /// # Errors
    /// The first problem found, named as in the spec (see [`ToolError`]).
    pub fn validate(&self) -> Result<(), ToolError> {
        if let Cutter::Apt(a) = self {
            return a.validate();
        }
        self.check_shape()?;
        self.checked_length(self.length()).map(|_| ())
    }

    fn check_shape(&self) -> Result<(), ToolError> {
        match *self {
            Cutter::Flat { radius, .. } | Cutter::Ball { radius, .. } => check_radius(radius),
            Cutter::Bull { radius, corner, .. } => {
                check_radius(radius)?;
                check_at_most("r", corner, radius)?;
                if corner < 0.0 {
                    return Err(ToolError::Negative {
                        field: "r",
                        value: corner,
                    });
                }
                if corner > 0.0 && corner < MIN_CORNER {
                    return Err(ToolError::OutOfDomain {
                        field: "r",
                        message: format!(
                            "expected 0 (a sharp corner) or a corner radius of at least \
                             {MIN_CORNER} mm, found {}",
                            swarf_geom::domain::show(corner)
                        ),
                    });
                }
                Ok(())
            }
            Cutter::Cone {
                radius, half_angle, ..
            } => {
                check_radius(radius)?;
                let degrees = 2.0 * half_angle.to_degrees();
                finite("angle", degrees)?;
                if half_angle > 0.0 && half_angle < FRAC_PI_2 {
                    Ok(())
                } else {
                    Err(ToolError::AngleOutOfRange {
                        field: "angle",
                        degrees,
                        range: "(0, 180) (included angle)",
                    })
                }
            }
            Cutter::TaperBall {
                tip_radius,
                half_angle,
                radius,
                ..
            } => {
                check_radius(radius)?;
                finite("angle", half_angle)?;
                if !(0.0..FRAC_PI_2).contains(&half_angle) {
                    return Err(ToolError::AngleOutOfRange {
                        field: "angle",
                        degrees: half_angle.to_degrees(),
                        range: "[0, 90) (taper half-angle per side)",
                    });
                }
                check_at_most("tip", tip_radius, radius)?;
                if tip_radius > 0.0 {
                    Ok(())
                } else {
                    Err(ToolError::NotPositive {
                        field: "tip",
                        value: tip_radius,
                    })
                }
            }
            Cutter::Apt(a) => a.validate(),
        }
    }

    /// Least and greatest flute length the shape allows, mm (shape assumed valid).
    pub fn length_bounds(&self) -> (f64, f64) {
        match *self {
            Cutter::Flat { .. } => (0.0, f64::INFINITY),
            Cutter::Ball { radius, .. } => (radius, f64::INFINITY),
            Cutter::Bull { corner, .. } => (corner, f64::INFINITY),
            Cutter::Cone {
                radius, half_angle, ..
            } => (radius / half_angle.tan(), f64::INFINITY),
            Cutter::TaperBall {
                tip_radius,
                half_angle,
                radius,
                ..
            } => {
                let (s, c) = half_angle.sin_cos();
                let needed = tip_radius * (1.0 - s);
                let full = if half_angle > 0.0 {
                    needed + (radius - tip_radius * c) / half_angle.tan()
                } else {
                    f64::INFINITY
                };
                (needed, full)
            }
            Cutter::Apt(a) => (a.needed_height(), a.axis_height()),
        }
    }

    /// The flute length used when none is given, mm (see the module doc).
    pub fn default_length(&self) -> f64 {
        match *self {
            Cutter::TaperBall { radius, .. } => {
                let (needed, full) = self.length_bounds();
                full.min((8.0 * radius).max(needed))
            }
            Cutter::Apt(a) => a.default_height(),
            _ => {
                let (needed, _) = self.length_bounds();
                (8.0 * self.radius()).min(TOOL_LENGTH.max).max(needed)
            }
        }
    }

    fn checked_length(&self, length: f64) -> Result<f64, ToolError> {
        if let Cutter::Apt(a) = self {
            return a.checked_height("length", length);
        }
        finite("length", length)?;
        if length <= 0.0 {
            return Err(ToolError::NotPositive {
                field: "length",
                value: length,
            });
        }
        let (needed, limit) = self.length_bounds();
        if length < needed - LENGTH_SNAP * needed.max(1.0) {
            return Err(ToolError::LengthTooShort {
                field: "length",
                value: length,
                needed,
            });
        }
        if length > limit {
            return Err(ToolError::LengthTooLong {
                field: "length",
                value: length,
                limit,
                why: "a taper ball's flutes end where the taper reaches d/2",
            });
        }
        let length = length.max(needed);
        in_domain("length", length, TOOL_LENGTH)?;
        Ok(length)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn length_bounds_per_shape() {
        let cone = Cutter::cone(10.0, 30f64.to_radians(), None).unwrap();
        let (needed, limit) = cone.length_bounds();
        assert!((needed - 5.0 * 3f64.sqrt()).abs() < 1e-12 && limit == f64::INFINITY);
        assert_eq!(cone.length(), 40.0);
        let taper = Cutter::taper_ball(6.0, 10f64.to_radians(), 1.0, Some(5.0)).unwrap();
        let (needed, limit) = taper.length_bounds();
        assert!((needed - (1.0 - 10f64.to_radians().sin())).abs() < 1e-15);
        let b = 10f64.to_radians();
        assert!((limit - (1.0 - b.sin() + (3.0 - b.cos()) / b.tan())).abs() < 1e-12);
        // Shorter flutes stop the taper below the shank diameter.
        assert!(taper.radius() < 3.0);
        let straight = Cutter::taper_ball(6.0, 0.0, 2.0, None).unwrap();
        assert_eq!((straight.length(), straight.radius()), (24.0, 2.0));
    }

    #[test]
    fn with_length_checks_and_snaps() {
        let ball = Cutter::ball(8.0, None).unwrap();
        assert_eq!(ball.with_length(Some(10.0)).unwrap().length(), 10.0);
        assert_eq!(ball.with_length(Some(4.0 - 1e-12)).unwrap().length(), 4.0);
        assert!(ball.with_length(Some(3.9)).is_err());
        assert!(ball.with_length(Some(f64::INFINITY)).is_err());
        let apt = Cutter::Apt(ball.to_apt());
        assert_eq!(apt.with_length(Some(12.0)).unwrap().length(), 12.0);
        assert!(matches!(
            apt.with_length(Some(3.0)),
            Err(ToolError::LengthTooShort { field: "h", .. })
        ));
    }
}
