//! The closed cutter family and its named special cases of the APT tool.
//!
//! Each named shape is the APT tool ([`crate::apt`]) with some parameters fixed:
//!
//! | shape | d | r | e | f | alpha | beta |
//! |---|---|---|---|---|---|---|
//! | flat | 2R | 0 | R | 0 | 0 | 0 |
//! | ball | 2R | R | 0 | R | 0 | 0 |
//! | bull | 2R | c | R - c | c | 0 | 0 |
//! | cone | 2R | 0 | R | R / tan(half) | pi/2 - half | 0 |
//! | taperball | 2t (1 - sin b) / cos b | t | 0 | t | 0 | b |
//!
//! (R radius, c corner radius, half the cone's half-angle, t the taper ball's tip
//! radius, b its taper half-angle.) The named profiles below are written in closed form
//! independently of the APT construction; tests check that both agree.
//!
//! Flute length (APT `h`): when not given, `max(4 d, the height where the profile
//! reaches full radius)`. A taper ball is different: its `d` is the shank diameter,
//! the taper's upper bound. Its flutes end where the taper reaches `d/2` (height
//! `H = t (1 - sin b) + (d/2 - t cos b) / tan b`), so its length defaults to
//! `min(H, max(4 d, t (1 - sin b)))` and may not exceed `H` (the APT tool has no
//! cylinder above its side line).

use crate::apt::Apt;
use crate::error::ToolError;
use crate::profile::Profile;
use crate::segment::{RhoZ, Segment};
use std::f64::consts::FRAC_PI_2;

/// A milling cutter: one of the APT family. Lengths mm, angles radians. Build with the
/// validating constructors ([`Cutter::ball`] ...), by parsing a spec (`"bull:d=10,r=2"`
/// `.parse()`), or by deserialising; check hand-built values with
/// [`Cutter::validate`]. (De)serialises as its spec string ([`crate::spec`]); also
/// deserialises from a table `{ shape = "bull", d = 10, r = 2 }`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "crate::table::CutterRepr", into = "String")]
pub enum Cutter {
    /// Flat end mill.
    Flat {
        /// Radius (d/2).
        radius: f64,
        /// Flute length.
        length: f64,
    },
    /// Ball end mill.
    Ball {
        /// Radius of the ball and shank (d/2).
        radius: f64,
        /// Flute length.
        length: f64,
    },
    /// Bull-nose (toroidal) end mill.
    Bull {
        /// Radius (d/2).
        radius: f64,
        /// Corner radius r, `0 <= r <= radius`.
        corner: f64,
        /// Flute length.
        length: f64,
    },
    /// Conical (V, engraving, chamfer) cutter: a cone from a sharp tip up to `radius`,
    /// then cylindrical.
    Cone {
        /// Radius (d/2).
        radius: f64,
        /// Half of the included angle, from the axis, in `(0, pi/2)`.
        half_angle: f64,
        /// Flute length.
        length: f64,
    },
    /// Tapered ball end mill: a ball of `tip_radius`, then a side cone at
    /// `half_angle` from the axis, at most up to `radius` (d/2, the shank).
    TaperBall {
        /// Radius of the ball tip.
        tip_radius: f64,
        /// Taper half-angle per side, from the axis, in `[0, pi/2)`.
        half_angle: f64,
        /// Shank radius (d/2): the taper's upper bound.
        radius: f64,
        /// Flute length.
        length: f64,
    },
    /// The general APT tool.
    Apt(Apt),
}

impl Cutter {
    /// Flat end mill of diameter `d`.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// `d` not finite or not > 0; `length` not finite or <= 0.
    pub fn flat(d: f64, length: Option<f64>) -> Result<Cutter, ToolError> {
        Cutter::Flat {
            radius: 0.5 * d,
            length: f64::NAN,
        }
        .with_length(length)
    }

    /// Ball end mill of diameter `d`.
    ///
    /// # Errors
    /// As [`Cutter::flat`], and `length` below the ball's top.
    ///
    /// # Example
    /// ```
    /// let ball = swarf_tool::Cutter::ball(8.0, None).unwrap();
    /// assert_eq!((ball.radius(), ball.length()), (4.0, 32.0));
    /// ```
    pub fn ball(d: f64, length: Option<f64>) -> Result<Cutter, ToolError> {
        Cutter::Ball {
            radius: 0.5 * d,
            length: f64::NAN,
        }
        .with_length(length)
    }

    /// Bull-nose end mill of diameter `d` and corner radius `r`.
    ///
    /// # Errors
    /// As [`Cutter::ball`], and `r < 0`, `r > d/2`.
    pub fn bull(d: f64, r: f64, length: Option<f64>) -> Result<Cutter, ToolError> {
        Cutter::Bull {
            radius: 0.5 * d,
            corner: r,
            length: f64::NAN,
        }
        .with_length(length)
    }

    /// Conical cutter of diameter `d` and half-angle `half_angle` (radians, from the
    /// axis).
    ///
    /// # Errors
    /// As [`Cutter::ball`], and `half_angle` outside `(0, pi/2)`.
    pub fn cone(d: f64, half_angle: f64, length: Option<f64>) -> Result<Cutter, ToolError> {
        Cutter::Cone {
            radius: 0.5 * d,
            half_angle,
            length: f64::NAN,
        }
        .with_length(length)
    }

    /// Tapered ball end mill: shank diameter `d`, taper `half_angle` (radians, per
    /// side), ball tip radius `tip_radius`.
    ///
    /// # Errors
    /// As [`Cutter::ball`], `half_angle` outside `[0, pi/2)`, `tip_radius` not > 0
    /// or > d/2, `length` beyond where the taper reaches d/2.
    pub fn taper_ball(
        d: f64,
        half_angle: f64,
        tip_radius: f64,
        length: Option<f64>,
    ) -> Result<Cutter, ToolError> {
        Cutter::TaperBall {
            tip_radius,
            half_angle,
            radius: 0.5 * d,
            length: f64::NAN,
        }
        .with_length(length)
    }

    /// Flute length (APT `h`), mm.
    pub fn length(&self) -> f64 {
        match *self {
            Cutter::Flat { length, .. }
            | Cutter::Ball { length, .. }
            | Cutter::Bull { length, .. }
            | Cutter::Cone { length, .. }
            | Cutter::TaperBall { length, .. } => length,
            Cutter::Apt(a) => a.h,
        }
    }

    /// Largest cutting radius, mm.
    pub fn radius(&self) -> f64 {
        match *self {
            Cutter::Flat { radius, .. }
            | Cutter::Ball { radius, .. }
            | Cutter::Bull { radius, .. }
            | Cutter::Cone { radius, .. } => radius,
            Cutter::TaperBall { .. } | Cutter::Apt(_) => self.profile().radius(),
        }
    }

    /// Lowest height of the cutting surface at distance `rho` from the axis, above the
    /// tip; `None` for `rho > radius()` (a flat end gives 0 for every `rho <= R`).
    ///
    /// # Units
    /// mm. Hot loops should hoist [`Cutter::profile`] and call
    /// [`Profile::height_at_radius`].
    pub fn height_at_radius(&self, rho: f64) -> Option<f64> {
        self.profile().height_at_radius(rho)
    }

    /// Radius of the cutter at height `z` above the tip; `None` outside
    /// `[0, length]`.
    ///
    /// # Units
    /// mm.
    pub fn radius_at_height(&self, z: f64) -> Option<f64> {
        self.profile().radius_at_height(z)
    }

    /// The profile in the meridian half-plane, from the tip up (closed forms per
    /// shape).
    pub fn profile(&self) -> Profile {
        let mut b = Profile::builder();
        match *self {
            Cutter::Flat { radius, length } => {
                b.line_to(RhoZ::new(radius, 0.0))
                    .line_to(RhoZ::new(radius, length));
            }
            Cutter::Ball { radius, length } => {
                b.arc_segment(Segment::quarter_arc(RhoZ::new(0.0, radius), radius))
                    .line_to(RhoZ::new(radius, length));
            }
            Cutter::Bull {
                radius,
                corner,
                length,
            } => {
                let centre = RhoZ::new(radius - corner, corner);
                b.arc_segment(Segment::quarter_arc(centre, corner))
                    .line_to(RhoZ::new(radius, length));
            }
            Cutter::Cone {
                radius,
                half_angle,
                length,
            } => {
                b.line_to(RhoZ::new(radius, radius / half_angle.tan()))
                    .line_to(RhoZ::new(radius, length));
            }
            Cutter::TaperBall {
                tip_radius,
                half_angle,
                length,
                ..
            } => {
                let t = tip_radius;
                b.arc(RhoZ::new(0.0, t), t, -FRAC_PI_2, -half_angle);
                let t2 = b.at();
                b.line_to(RhoZ::new(
                    t2.rho + (length - t2.z) * half_angle.tan(),
                    length,
                ));
            }
            Cutter::Apt(a) => return a.profile(),
        }
        b.finish()
    }

    /// The seven APT parameters of this cutter (see the module table).
    pub fn to_apt(&self) -> Apt {
        let apt = |d: f64, r: f64, e: f64, f: f64, alpha: f64, beta: f64, h: f64| Apt {
            d,
            r,
            e,
            f,
            alpha,
            beta,
            h,
        };
        match *self {
            Cutter::Flat { radius, length } => {
                apt(2.0 * radius, 0.0, radius, 0.0, 0.0, 0.0, length)
            }
            Cutter::Ball { radius, length } => {
                apt(2.0 * radius, radius, 0.0, radius, 0.0, 0.0, length)
            }
            Cutter::Bull {
                radius,
                corner,
                length,
            } => apt(
                2.0 * radius,
                corner,
                radius - corner,
                corner,
                0.0,
                0.0,
                length,
            ),
            Cutter::Cone {
                radius,
                half_angle,
                length,
            } => apt(
                2.0 * radius,
                0.0,
                radius,
                radius / half_angle.tan(),
                FRAC_PI_2 - half_angle,
                0.0,
                length,
            ),
            Cutter::TaperBall {
                tip_radius,
                half_angle,
                length,
                ..
            } => {
                let (s, c) = half_angle.sin_cos();
                let d = 2.0 * tip_radius * (1.0 - s) / c;
                apt(d, tip_radius, 0.0, tip_radius, 0.0, half_angle, length)
            }
            Cutter::Apt(a) => a,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apt_parameters_follow_the_table() {
        let apt = |c: Cutter| {
            let a = c.to_apt();
            [a.d, a.r, a.e, a.f, a.alpha, a.beta, a.h]
        };
        let flat = Cutter::flat(6.0, None).unwrap();
        assert_eq!(apt(flat), [6.0, 0.0, 3.0, 0.0, 0.0, 0.0, 24.0]);
        let ball = Cutter::ball(8.0, None).unwrap();
        assert_eq!(apt(ball), [8.0, 4.0, 0.0, 4.0, 0.0, 0.0, 32.0]);
        let bull = Cutter::bull(10.0, 2.0, Some(30.0)).unwrap();
        assert_eq!(apt(bull), [10.0, 2.0, 3.0, 2.0, 0.0, 0.0, 30.0]);
        let [d, r, e, f, alpha, beta, _] = apt(Cutter::cone(10.0, FRAC_PI_2 / 3.0, None).unwrap());
        assert_eq!([d, r, e, beta], [10.0, 0.0, 5.0, 0.0]);
        assert!(
            (f - 5.0 * 3f64.sqrt()).abs() < 1e-12 && (alpha - FRAC_PI_2 * 2.0 / 3.0).abs() < 1e-15
        );
        let b = 10f64.to_radians();
        let [d, r, e, f, _, beta, _] = apt(Cutter::taper_ball(6.0, b, 1.0, None).unwrap());
        assert!((d - 2.0 * (1.0 - b.sin()) / b.cos()).abs() < 1e-15);
        assert_eq!([r, e, f, beta], [1.0, 0.0, 1.0, b]);
        for c in [flat, ball, bull] {
            assert!(Cutter::Apt(c.to_apt()).validate().is_ok());
        }
    }

    #[test]
    fn radius_and_length_accessors() {
        let taper = Cutter::taper_ball(6.0, 10f64.to_radians(), 1.0, None).unwrap();
        assert!((taper.radius() - 3.0).abs() < 1e-12);
        assert_eq!(taper.radius_at_height(taper.length() + 1e-9), None);
        let general = Cutter::Apt(Apt::from_corner(10.0, 1.0, 0.0, 0.1, 20.0).unwrap());
        assert!((general.radius() - general.profile().top().rho).abs() < 1e-15);
        assert!(general.radius() > 5.0);
    }
}
