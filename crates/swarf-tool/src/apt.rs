//! The APT general tool: `CUTTER/d, r, e, f, alpha, beta, h`.
//!
//! APT describes a milling cutter by seven numbers (thesis 000 §5.2, fig. 5.4: "two
//! cones and a torus"; the same parameters as HiAPI's APT tool page, which names e
//! "distance from corner centre to tool centreline" and f "distance from corner
//! centre to tool tip plane"). In the meridian half-plane (rho, z), tip at the origin:
//!
//! - the **bottom line** leaves the tip on the axis at `alpha` above the horizontal
//!   (`z = rho tan alpha`, a cone; `alpha = 0` is a flat bottom);
//! - the **side line** makes `beta` with the axis, positive widening upward;
//! - the **corner circle** of radius `r`, centre `(e, f)`, is tangent to both;
//! - `d` is the diameter at the theoretical sharp corner, where the bottom and side
//!   lines (extended) meet: `P = (d/2, d/2 tan alpha)`;
//! - `h` is the height of the cutting part (our flute length).
//!
//! Tangency to the bottom line (inward normal `(-sin alpha, cos alpha)`) gives
//! `f cos alpha - e sin alpha = r`; tangency to the side line through `P` (inward
//! normal `(-cos beta, sin beta)`) gives `(d/2 - e) cos beta + (f - P_z) sin beta = r`.
//! Eliminating `f`:
//!
//! ```text
//! e = d/2 - r (cos alpha - sin beta) / cos(alpha + beta)
//! f = (r + e sin alpha) / cos alpha
//! ```
//!
//! The profile is then: the bottom line from the tip to the tangent point
//! `T1 = (e + r sin alpha, f - r cos alpha)`, the arc from polar angle `alpha - pi/2`
//! to `-beta`, the side line from `T2 = (e + r cos beta, f - r sin beta)` up to height
//! `h`. A convex corner needs `alpha + beta < pi/2`; the corner circle must not cross
//! the axis: `e >= 0`.
//!
//! In thesis eq. 5.1's notation: torus radius `R = e`, insert radius `r = r`,
//! `theta_start = alpha`, `theta_end = pi/2 - beta` (theta measured from -z toward
//! +rho), the bottom cone ends at `(m, n) = T1`, the side cone rises by `b = h - T2_z`
//! while widening by `a = b tan beta`.

use crate::error::ToolError;
use crate::profile::Profile;
use crate::segment::{RhoZ, Segment};
use std::f64::consts::FRAC_PI_2;

/// A given `e` or `f` must agree with the one derived from `d, r, alpha, beta` to
/// within this (mm): the resolution of APT listings printed to four decimals.
pub const APT_PARAM_TOL: f64 = 1e-4;

/// A flute length short of the profile's need by at most this fraction (of
/// `max(1 mm, need)`) is rounding and is raised to the need.
pub const LENGTH_SNAP: f64 = 1e-9;

/// Corner centres this far (mm) past the axis are rounding and are put on it.
const AXIS_SNAP: f64 = 1e-9;

/// The seven APT parameters; build with [`Apt::new`], [`Apt::from_corner`] or
/// [`Apt::from_parts`], which validate. Lengths mm, angles radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Apt {
    /// Diameter at the theoretical sharp corner (bottom and side lines meet).
    pub d: f64,
    /// Corner radius.
    pub r: f64,
    /// Distance from the axis to the corner centre.
    pub e: f64,
    /// Height of the corner centre above the tip.
    pub f: f64,
    /// Angle of the bottom line above the horizontal, radians, in `[0, pi/2)`.
    pub alpha: f64,
    /// Angle of the side line from the axis, radians, in `(-pi/2, pi/2)`; positive
    /// widens upward.
    pub beta: f64,
    /// Height of the cutting part (flute length).
    pub h: f64,
}

impl Apt {
    /// The tool from all seven parameters; `e` and `f` are checked against the values
    /// derived from the others (to [`APT_PARAM_TOL`]) and replaced by them.
    ///
    /// # Units
    /// Lengths mm, angles radians.
    ///
    /// # Errors
    /// As [`Apt::from_parts`].
    pub fn new(
        d: f64,
        r: f64,
        e: f64,
        f: f64,
        alpha: f64,
        beta: f64,
        h: f64,
    ) -> Result<Apt, ToolError> {
        Apt::from_parts(d, r, Some(e), Some(f), alpha, beta, Some(h))
    }

    /// The tool from `d, r, alpha, beta, h`, deriving `e` and `f`.
    ///
    /// # Errors
    /// As [`Apt::from_parts`].
    ///
    /// # Example
    /// ```
    /// let bull = swarf_tool::Apt::from_corner(10.0, 2.0, 0.0, 0.0, 30.0).unwrap();
    /// assert_eq!((bull.e, bull.f), (3.0, 2.0));
    /// ```
    pub fn from_corner(d: f64, r: f64, alpha: f64, beta: f64, h: f64) -> Result<Apt, ToolError> {
        Apt::from_parts(d, r, None, None, alpha, beta, Some(h))
    }

    /// The tool from its parameters where `e`, `f` and `h` may be omitted: `e` and `f`
    /// are derived (and checked when given), `h` defaults to
    /// [`Apt::default_height`].
    ///
    /// # Errors
    /// [`ToolError::NotFinite`], [`ToolError::NotPositive`] (d, h),
    /// [`ToolError::Negative`] (r), [`ToolError::AngleOutOfRange`] (alpha outside
    /// `[0, 90)`, beta outside `(-90, 90)` degrees), [`ToolError::AnglesTooSteep`],
    /// [`ToolError::CornerPastAxis`], [`ToolError::Inconsistent`] (e, f),
    /// [`ToolError::LengthTooShort`] / [`ToolError::LengthTooLong`] (h).
    pub fn from_parts(
        d: f64,
        r: f64,
        e: Option<f64>,
        f: Option<f64>,
        alpha: f64,
        beta: f64,
        h: Option<f64>,
    ) -> Result<Apt, ToolError> {
        let (e0, f0) = corner_centre(d, r, alpha, beta)?;
        crate::validate::in_domain("d", d, swarf_geom::domain::TOOL_DIAMETER)?;
        for (field, given, expected) in [("e", e, e0), ("f", f, f0)] {
            if let Some(given) = given {
                finite(field, given)?;
                if (given - expected).abs() > APT_PARAM_TOL {
                    return Err(ToolError::Inconsistent {
                        field,
                        given,
                        expected,
                    });
                }
            }
        }
        let mut apt = Apt {
            d,
            r,
            e: e0,
            f: f0,
            alpha,
            beta,
            h: 0.0,
        };
        apt.h = match h {
            Some(h) => apt.checked_height("h", h)?,
            None => apt.default_height(),
        };
        Ok(apt)
    }

    /// Checks the parameters as [`Apt::new`] does.
    ///
    /// # Errors
    /// As [`Apt::from_parts`].
    pub fn validate(&self) -> Result<(), ToolError> {
        Apt::new(
            self.d, self.r, self.e, self.f, self.alpha, self.beta, self.h,
        )
        .map(|_| ())
    }

    /// Lower end of the side line (`T2`): the corner circle's upper tangent point, or
    /// the sharp corner when `r = 0`.
    pub fn side_start(&self) -> RhoZ {
        let centre = RhoZ::new(self.e, self.f);
        if self.r > 0.0 {
            Segment::arc(centre, self.r, self.alpha - FRAC_PI_2, -self.beta).end()
        } else {
            centre
        }
    }

    /// The least `h` the profile needs: the height where the side line starts, mm.
    pub fn needed_height(&self) -> f64 {
        self.side_start().z
    }

    /// Height where a narrowing side line (`beta < 0`) reaches the axis; infinite
    /// otherwise, mm.
    pub fn axis_height(&self) -> f64 {
        if self.beta < 0.0 {
            let t2 = self.side_start();
            t2.z + t2.rho / (-self.beta).tan()
        } else {
            f64::INFINITY
        }
    }

    /// Default `h`: `max(min(4 d, 2000 mm), needed height)`, but no higher than a narrowing side
    /// line reaching the axis, mm.
    pub fn default_height(&self) -> f64 {
        (4.0 * self.d)
            .min(swarf_geom::domain::TOOL_LENGTH.max)
            .max(self.needed_height())
            .min(self.axis_height())
    }

    /// `h` checked against the profile (raised to the need when short by rounding).
    pub(crate) fn checked_height(&self, field: &'static str, h: f64) -> Result<f64, ToolError> {
        finite(field, h)?;
        if h <= 0.0 {
            return Err(ToolError::NotPositive { field, value: h });
        }
        let needed = self.needed_height();
        if h < needed - LENGTH_SNAP * needed.max(1.0) {
            return Err(ToolError::LengthTooShort {
                field,
                value: h,
                needed,
            });
        }
        let limit = self.axis_height();
        if h > limit {
            return Err(ToolError::LengthTooLong {
                field,
                value: h,
                limit,
                why: "the narrowing side line reaches the axis there",
            });
        }
        let h = h.max(needed);
        crate::validate::in_domain(field, h, swarf_geom::domain::TOOL_LENGTH)?;
        Ok(h)
    }

    /// The profile: bottom line, corner arc, side line (empty pieces dropped).
    pub fn profile(&self) -> Profile {
        let centre = RhoZ::new(self.e, self.f);
        let mut b = Profile::builder();
        if self.r > 0.0 {
            b.arc(centre, self.r, self.alpha - FRAC_PI_2, -self.beta);
        } else {
            b.line_to(centre);
        }
        let t2 = b.at();
        let top_rho = (t2.rho + (self.h - t2.z) * self.beta.tan()).max(0.0);
        b.line_to(RhoZ::new(top_rho, self.h));
        b.finish()
    }
}

fn finite(field: &'static str, value: f64) -> Result<(), ToolError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ToolError::NotFinite { field, value })
    }
}

/// Validates `d, r, alpha, beta` and returns the corner centre `(e, f)`.
fn corner_centre(d: f64, r: f64, alpha: f64, beta: f64) -> Result<(f64, f64), ToolError> {
    for (field, v) in [("d", d), ("r", r), ("alpha", alpha), ("beta", beta)] {
        finite(field, v)?;
    }
    if d <= 0.0 {
        return Err(ToolError::NotPositive {
            field: "d",
            value: d,
        });
    }
    if r < 0.0 {
        return Err(ToolError::Negative {
            field: "r",
            value: r,
        });
    }
    if !(0.0..FRAC_PI_2).contains(&alpha) {
        return Err(ToolError::AngleOutOfRange {
            field: "alpha",
            degrees: alpha.to_degrees(),
            range: "[0, 90)",
        });
    }
    if !(beta > -FRAC_PI_2 && beta < FRAC_PI_2) {
        return Err(ToolError::AngleOutOfRange {
            field: "beta",
            degrees: beta.to_degrees(),
            range: "(-90, 90)",
        });
    }
    if alpha + beta >= FRAC_PI_2 {
        return Err(ToolError::AnglesTooSteep {
            alpha: alpha.to_degrees(),
            beta: beta.to_degrees(),
        });
    }
    let e = 0.5 * d - r * (alpha.cos() - beta.sin()) / (alpha + beta).cos();
    if e < -AXIS_SNAP {
        return Err(ToolError::CornerPastAxis { r, e });
    }
    let e = e.max(0.0);
    Ok((e, (r + e * alpha.sin()) / alpha.cos()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deg(x: f64) -> f64 {
        x.to_radians()
    }

    /// Distance from `c` to the line through `p` with direction `u` (unit).
    fn line_distance(c: RhoZ, p: RhoZ, u: (f64, f64)) -> f64 {
        ((c.rho - p.rho) * u.1 - (c.z - p.z) * u.0).abs()
    }

    #[test]
    fn corner_circle_is_tangent_to_both_lines_through_the_sharp_corner() {
        for &(d, r, a, b, h) in &[
            (10.0, 2.0, 0.0, 0.0, 50.0),
            (10.0, 1.5, 10.0, 5.0, 50.0),
            (12.0, 3.0, 30.0, -20.0, 15.0),
            (8.0, 0.5, 45.0, 30.0, 50.0),
            (6.0, 1.0, 0.0, 10.0, 50.0),
        ] {
            let apt = Apt::from_corner(d, r, deg(a), deg(b), h).unwrap();
            let c = RhoZ::new(apt.e, apt.f);
            let (sa, ca) = deg(a).sin_cos();
            let (sb, cb) = deg(b).sin_cos();
            let corner = RhoZ::new(d / 2.0, d / 2.0 * deg(a).tan());
            assert!((line_distance(c, RhoZ::new(0.0, 0.0), (ca, sa)) - r).abs() < 1e-12);
            assert!((line_distance(c, corner, (sb, cb)) - r).abs() < 1e-12);
            // The circle lies on the material side of both lines.
            assert!(c.z * ca - c.rho * sa > 0.0);
            assert!((corner.rho - c.rho) * cb + (c.z - corner.z) * sb > 0.0);
        }
    }

    #[test]
    fn special_cases_get_their_textbook_centres() {
        let ball = Apt::from_corner(8.0, 4.0, 0.0, 0.0, 32.0).unwrap();
        assert_eq!((ball.e, ball.f), (0.0, 4.0));
        let flat = Apt::from_corner(6.0, 0.0, 0.0, 0.0, 24.0).unwrap();
        assert_eq!((flat.e, flat.f), (3.0, 0.0));
        let cone = Apt::from_corner(10.0, 0.0, deg(45.0), 0.0, 40.0).unwrap();
        assert!((cone.e - 5.0).abs() < 1e-15 && (cone.f - 5.0).abs() < 1e-14);
    }

    #[test]
    fn given_e_and_f_are_checked() {
        assert!(Apt::new(10.0, 2.0, 3.0, 2.0, 0.0, 0.0, 30.0).is_ok());
        assert!(Apt::new(10.0, 2.0, 3.00005, 2.0, 0.0, 0.0, 30.0).is_ok());
        let err = Apt::new(10.0, 2.0, 3.5, 2.0, 0.0, 0.0, 30.0).unwrap_err();
        assert_eq!(
            err,
            ToolError::Inconsistent {
                field: "e",
                given: 3.5,
                expected: 3.0
            }
        );
        assert!(err.to_string().contains("expected 3"));
        let err = Apt::new(10.0, 2.0, 3.0, 1.0, 0.0, 0.0, 30.0).unwrap_err();
        assert!(matches!(err, ToolError::Inconsistent { field: "f", .. }));
    }

    #[test]
    fn invalid_parameters_are_named() {
        let e = |r: Result<Apt, ToolError>| r.unwrap_err();
        assert!(matches!(
            e(Apt::from_corner(0.0, 0.0, 0.0, 0.0, 1.0)),
            ToolError::NotPositive { field: "d", .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(f64::NAN, 0.0, 0.0, 0.0, 1.0)),
            ToolError::NotFinite { field: "d", .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, -1.0, 0.0, 0.0, 1.0)),
            ToolError::Negative { field: "r", .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, 6.0, 0.0, 0.0, 40.0)),
            ToolError::CornerPastAxis { .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, 1.0, deg(90.0), 0.0, 40.0)),
            ToolError::AngleOutOfRange { field: "alpha", .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, 1.0, 0.0, deg(-90.0), 40.0)),
            ToolError::AngleOutOfRange { field: "beta", .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, 1.0, deg(50.0), deg(40.0), 40.0)),
            ToolError::AnglesTooSteep { .. }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, 2.0, 0.0, 0.0, 1.0)),
            ToolError::LengthTooShort {
                field: "h",
                needed: 2.0,
                ..
            }
        ));
        assert!(matches!(
            e(Apt::from_corner(10.0, 1.0, 0.0, deg(-45.0), 40.0)),
            ToolError::LengthTooLong { field: "h", .. }
        ));
    }

    #[test]
    fn heights_and_profile_of_a_general_tool() {
        let apt = Apt::from_parts(10.0, 1.5, None, None, deg(10.0), deg(5.0), None).unwrap();
        assert_eq!(apt.h, 40.0);
        let p = apt.profile();
        assert_eq!(p.segments().len(), 3);
        let t2 = apt.side_start();
        assert!((t2.z - apt.needed_height()).abs() < 1e-15);
        let top = p.top();
        assert!((top.z - 40.0).abs() < 1e-12);
        assert!((top.rho - (t2.rho + (40.0 - t2.z) * deg(5.0).tan())).abs() < 1e-12);
        // Bottom line at alpha: height at radius 1 is tan(alpha).
        assert!((p.height_at_radius(1.0).unwrap() - deg(10.0).tan()).abs() < 1e-14);
        let narrowing = Apt::from_parts(10.0, 1.0, None, None, 0.0, deg(-10.0), None).unwrap();
        assert!(narrowing.h < 40.0 && narrowing.h == narrowing.axis_height());
        assert!(narrowing.profile().top().rho < 1e-9);
        assert!(narrowing.validate().is_ok());
    }
}
