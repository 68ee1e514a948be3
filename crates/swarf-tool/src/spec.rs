//! Tool spec strings: `shape:key=value,key=value`, parsed with `str::parse` and
//! written back canonically with `Display`.
//!
//! | shape | keys (lengths mm, angles degrees) |
//! |---|---|
//! | `flat` | `d` |
//! | `ball` | `d` |
//! | `bull` | `d`, `r` (corner radius) |
//! | `cone` | `d`, `angle` (included angle, in (0, 180)) |
//! | `taperball` | `d` (shank = largest cutting diameter), `angle` (taper half-angle per side, in [0, 90)), `tip` (ball tip **radius**) |
//! | `apt` | `d`, `r`, `e`, `f`, `alpha` (bottom, in [0, 90)), `beta` (side, in (-90, 90)), `h`; `e`, `f`, `h` optional |
//!
//! Every shape also takes `length` (flute length; for `apt` the same as `h`). Diameters
//! are from 0.01 to 1000 mm, a bull's corner radius 0 or at least 0.001 mm, and lengths up to 2000 mm
//! ([`swarf_geom::domain::TOOL_DIAMETER`], [`swarf_geom::domain::TOOL_LENGTH`]). Shapes
//! and keys are case-insensitive; spaces around items are ignored. Degrees live only
//! here, at the I/O edge; the kernel holds radians. `Display` writes `length` only when
//! it differs from the default, and angles rounded to 1e-9 degrees when that rounding
//! reads back to the same radians, so `s.parse::<Cutter>()?.to_string()` reads back to
//! the same cutter.

use crate::apt::Apt;
use crate::cutter::Cutter;
use crate::error::ToolError;
use std::fmt;
use std::str::FromStr;
use swarf_geom::domain::excerpt;
use swarf_geom::math::display_degrees;

/// A named shape of the spec.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shape {
    Flat,
    Ball,
    Bull,
    Cone,
    TaperBall,
    Apt,
}

impl Shape {
    pub(crate) fn parse(s: &str) -> Result<Shape, ToolError> {
        Ok(match s.trim().to_ascii_lowercase().as_str() {
            "flat" => Shape::Flat,
            "ball" => Shape::Ball,
            "bull" => Shape::Bull,
            "cone" => Shape::Cone,
            "taperball" => Shape::TaperBall,
            "apt" => Shape::Apt,
            _ => {
                return Err(ToolError::UnknownShape {
                    shape: excerpt(s.trim(), 40),
                });
            }
        })
    }

    fn name(self) -> &'static str {
        match self {
            Shape::Flat => "flat",
            Shape::Ball => "ball",
            Shape::Bull => "bull",
            Shape::Cone => "cone",
            Shape::TaperBall => "taperball",
            Shape::Apt => "apt",
        }
    }

    fn keys(self) -> (&'static [&'static str], &'static str) {
        match self {
            Shape::Flat | Shape::Ball => (&["d", "length"], "d, length"),
            Shape::Bull => (&["d", "r", "length"], "d, r, length"),
            Shape::Cone => (&["d", "angle", "length"], "d, angle, length"),
            Shape::TaperBall => (&["d", "angle", "tip", "length"], "d, angle, tip, length"),
            Shape::Apt => (
                &["d", "r", "e", "f", "alpha", "beta", "h", "length"],
                "d, r, e, f, alpha, beta, h, length",
            ),
        }
    }
}

/// The fields of one spec or table, before validation.
pub(crate) struct Fields {
    shape: Shape,
    values: [Option<f64>; 8],
}

impl Fields {
    pub(crate) fn new(shape: Shape) -> Fields {
        Fields {
            shape,
            values: [None; 8],
        }
    }

    fn slot(&self, key: &str) -> Result<(usize, &'static str), ToolError> {
        let key = key.trim().to_ascii_lowercase();
        let (keys, known) = self.shape.keys();
        let Some(i) = keys.iter().position(|k| *k == key) else {
            return Err(ToolError::UnknownKey {
                shape: self.shape.name(),
                key: excerpt(&key, 40),
                known,
            });
        };
        let taken = self.values.get(i).is_some_and(Option::is_some);
        let alias_taken = self.shape == Shape::Apt
            && match key.as_str() {
                "h" => self.get("length").is_some(),
                "length" => self.get("h").is_some(),
                _ => false,
            };
        if taken || alias_taken {
            return Err(ToolError::DuplicateKey { key });
        }
        Ok((i, keys[i]))
    }

    /// Sets `key` from its text (as written in a spec).
    pub(crate) fn set_text(&mut self, key: &str, text: &str) -> Result<(), ToolError> {
        let (i, field) = self.slot(key)?;
        let value = text
            .trim()
            .parse::<f64>()
            .map_err(|_| ToolError::NotANumber {
                field,
                value: excerpt(text.trim(), 40),
            })?;
        self.put(i, field, value)
    }

    /// Sets `key` to a number (from a table).
    pub(crate) fn set_number(&mut self, key: &str, value: f64) -> Result<(), ToolError> {
        let (i, field) = self.slot(key)?;
        self.put(i, field, value)
    }

    fn put(&mut self, i: usize, field: &'static str, value: f64) -> Result<(), ToolError> {
        if !value.is_finite() {
            return Err(ToolError::NotFinite { field, value });
        }
        if let Some(slot) = self.values.get_mut(i) {
            *slot = Some(value);
        }
        Ok(())
    }

    fn get(&self, key: &str) -> Option<f64> {
        let (keys, _) = self.shape.keys();
        let i = keys.iter().position(|k| *k == key)?;
        self.values.get(i).copied().flatten()
    }

    fn req(&self, field: &'static str, what: &'static str) -> Result<f64, ToolError> {
        self.get(field).ok_or(ToolError::Missing {
            shape: self.shape.name(),
            field,
            what,
        })
    }

    /// Validates the fields into a cutter.
    pub(crate) fn build(&self) -> Result<Cutter, ToolError> {
        let d = self.req("d", "diameter, mm")?;
        let length = self.get("length");
        match self.shape {
            Shape::Flat => Cutter::flat(d, length),
            Shape::Ball => Cutter::ball(d, length),
            Shape::Bull => Cutter::bull(d, self.req("r", "corner radius, mm")?, length),
            Shape::Cone => {
                let angle = self.req("angle", "included angle, degrees")?;
                check_degrees("angle", angle, angle > 0.0 && angle < 180.0, "(0, 180)")?;
                Cutter::cone(d, (0.5 * angle).to_radians(), length)
            }
            Shape::TaperBall => {
                let angle = self.req("angle", "taper half-angle per side, degrees")?;
                check_degrees("angle", angle, (0.0..90.0).contains(&angle), "[0, 90)")?;
                let tip = self.req("tip", "ball tip radius, mm")?;
                Cutter::taper_ball(d, angle.to_radians(), tip, length)
            }
            Shape::Apt => self.build_apt(d, length),
        }
    }

    fn build_apt(&self, d: f64, length: Option<f64>) -> Result<Cutter, ToolError> {
        let r = self.req("r", "corner radius, mm")?;
        let alpha = self.req("alpha", "bottom angle from the horizontal, degrees")?;
        let beta = self.req("beta", "side angle from the axis, degrees")?;
        check_degrees("alpha", alpha, (0.0..90.0).contains(&alpha), "[0, 90)")?;
        check_degrees("beta", beta, beta > -90.0 && beta < 90.0, "(-90, 90)")?;
        let (e, f, h) = (self.get("e"), self.get("f"), self.get("h"));
        let mut apt = Apt::from_parts(d, r, e, f, alpha.to_radians(), beta.to_radians(), h)?;
        if let Some(l) = length {
            apt.h = apt.checked_height("length", l)?;
        }
        Ok(Cutter::Apt(apt))
    }
}

fn check_degrees(
    field: &'static str,
    degrees: f64,
    ok: bool,
    range: &'static str,
) -> Result<(), ToolError> {
    if ok {
        Ok(())
    } else {
        Err(ToolError::AngleOutOfRange {
            field,
            degrees,
            range,
        })
    }
}

impl FromStr for Cutter {
    type Err = ToolError;

    /// Parses `shape:key=value,...` (see the module doc).
    fn from_str(s: &str) -> Result<Cutter, ToolError> {
        let s = s.trim();
        if s.is_empty() {
            return Err(ToolError::Empty);
        }
        let (shape, rest) = s.split_once(':').unwrap_or((s, ""));
        let mut fields = Fields::new(Shape::parse(shape)?);
        if !rest.trim().is_empty() {
            for item in rest.split(',') {
                let (key, value) = item.split_once('=').ok_or_else(|| ToolError::Malformed {
                    item: excerpt(item.trim(), 40),
                })?;
                fields.set_text(key, value)?;
            }
        }
        fields.build()
    }
}

impl schemars::JsonSchema for Cutter {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Cutter".into()
    }

    /// A spec string (module doc) or a table of the same keys with `shape`.
    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "A cutter: a spec string `shape:key=value,...` (flat, ball, bull, cone, taperball, apt; lengths mm, angles degrees), or a table { shape = \"bull\", d = 10, r = 2 }",
            "type": ["string", "object"]
        })
    }
}

impl fmt::Display for Cutter {
    /// The canonical spec string.
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let deg = |rad: f64| display_degrees(rad.to_degrees(), rad, f64::to_radians);
        match *self {
            Cutter::Flat { radius, .. } => write!(out, "flat:d={}", 2.0 * radius)?,
            Cutter::Ball { radius, .. } => write!(out, "ball:d={}", 2.0 * radius)?,
            Cutter::Bull { radius, corner, .. } => {
                write!(out, "bull:d={},r={corner}", 2.0 * radius)?;
            }
            Cutter::Cone {
                radius, half_angle, ..
            } => {
                let angle = display_degrees(2.0 * half_angle.to_degrees(), half_angle, |x| {
                    (0.5 * x).to_radians()
                });
                write!(out, "cone:d={},angle={angle}", 2.0 * radius)?;
            }
            Cutter::TaperBall {
                tip_radius,
                half_angle,
                radius,
                ..
            } => write!(
                out,
                "taperball:d={},angle={},tip={tip_radius}",
                2.0 * radius,
                deg(half_angle)
            )?,
            Cutter::Apt(a) => {
                return write!(
                    out,
                    "apt:d={},r={},e={},f={},alpha={},beta={},h={}",
                    a.d,
                    a.r,
                    a.e,
                    a.f,
                    deg(a.alpha),
                    deg(a.beta),
                    a.h
                );
            }
        }
        let length = self.length();
        if length != self.default_length() {
            write!(out, ",length={length}")?;
        }
        Ok(())
    }
}

impl From<Cutter> for String {
    fn from(c: Cutter) -> String {
        c.to_string()
    }
}

#[cfg(test)]
mod tests;
