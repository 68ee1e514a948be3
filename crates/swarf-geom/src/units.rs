//! Units at the input and output edge. swarf is in millimetres and radians inside;
//! part files, programs and reports in inches convert with these, once, where they
//! are read or written; angles given in degrees are turned into radians where they
//! are read ([`serde_degrees`]) and shown as given ([`degrees`]).

/// Millimetres per inch (exact, by the 1959 definition of the inch).
pub const MM_PER_INCH: f64 = 25.4;

use crate::domain::show;
use crate::math::display_degrees;

/// An angle in radians as the degrees a user gave ([`display_degrees`]: a plane at
/// 60 degrees reads 60 again in messages and files after the conversion to radians).
///
/// ```
/// use swarf_geom::units::degrees;
/// assert_eq!(degrees(60f64.to_radians()), 60.0);
/// ```
pub fn degrees(angle: f64) -> f64 {
    display_degrees(angle.to_degrees(), angle, f64::to_radians)
}

/// [`degrees`] for a message ([`show`]: no hundreds of digits for an absurd value).
pub fn shown_degrees(angle: f64) -> String {
    show(degrees(angle))
}

/// Serde for an angle held in radians and written in degrees (job files, reports):
/// `#[serde(with = "swarf_geom::units::serde_degrees")]`.
pub mod serde_degrees {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes radians `angle` as the degrees a user gave ([`super::degrees`]).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(angle: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(super::degrees(*angle))
    }

    /// Reads degrees as radians.
    ///
    /// # Errors
    /// A value that is not a number.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        f64::deserialize(d).map(f64::to_radians)
    }
}

/// [`serde_degrees`] for an optional angle.
pub mod serde_degrees_opt {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes radians `angle` as degrees, or nothing.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(angle: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        match angle {
            Some(a) => s.serialize_some(&super::degrees(*a)),
            None => s.serialize_none(),
        }
    }

    /// Reads optional degrees as radians.
    ///
    /// # Errors
    /// A value that is not a number.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Option::<f64>::deserialize(d).map(|a| a.map(f64::to_radians))
    }
}
