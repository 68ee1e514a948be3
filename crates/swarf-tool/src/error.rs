//! The one error type of swarf-tool: what is wrong with a cutter description.
//!
//! Messages speak the language of the tool spec (`ball:d=8`, see [`crate::spec`]):
//! fields are named as in the spec, angles are in degrees and sizes are diameters
//! where the spec writes diameters, whichever way the cutter was built.

use thiserror::Error;

/// The shapes a spec may name, for error messages.
pub const KNOWN_SHAPES: &str = "flat, ball, bull, cone, taperball, apt";

/// Everything that can be wrong with a cutter description.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ToolError {
    /// The spec string is empty.
    #[error("empty tool spec: expected e.g. `ball:d=8` or `bull:d=10,r=2`")]
    Empty,
    /// The shape is not one of [`KNOWN_SHAPES`].
    #[error("unknown tool shape `{shape}`: expected one of {KNOWN_SHAPES}")]
    UnknownShape {
        /// The shape as written.
        shape: String,
    },
    /// A tool table has no `shape` entry, or it is not a string.
    #[error("tool table: expected `shape = \"...\"`, one of {KNOWN_SHAPES}")]
    MissingShape,
    /// A required field is absent.
    #[error("{shape} tool: missing `{field}` ({what})")]
    Missing {
        /// The shape.
        shape: &'static str,
        /// The missing field.
        field: &'static str,
        /// What the field means.
        what: &'static str,
    },
    /// A key that this shape does not take.
    #[error("{shape} tool: unknown key `{key}`, expected one of {known}")]
    UnknownKey {
        /// The shape.
        shape: &'static str,
        /// The key as written.
        key: String,
        /// The keys the shape takes.
        known: &'static str,
    },
    /// A key given twice.
    #[error("duplicate key `{key}`")]
    DuplicateKey {
        /// The key.
        key: String,
    },
    /// A spec item that is not `key=value`.
    #[error("expected `key=value`, got `{item}`")]
    Malformed {
        /// The item as written.
        item: String,
    },
    /// A value that does not parse as a number.
    #[error("`{field}`: expected a number, got `{value}`")]
    NotANumber {
        /// The field.
        field: &'static str,
        /// The value as written.
        value: String,
    },
    /// A NaN or infinite value.
    #[error("`{field}`: expected a finite number, got {value}")]
    NotFinite {
        /// The field.
        field: &'static str,
        /// The value.
        value: f64,
    },
    /// A size outside the stated domain of tools ([`swarf_geom::domain`]).
    #[error("`{field}`: {message}")]
    OutOfDomain {
        /// The field.
        field: &'static str,
        /// What was expected and found.
        message: String,
    },
    /// A value that must be positive.
    #[error("`{field}` must be > 0, got {value}")]
    NotPositive {
        /// The field.
        field: &'static str,
        /// The value.
        value: f64,
    },
    /// A value that must not be negative.
    #[error("`{field}` must be >= 0, got {value}")]
    Negative {
        /// The field.
        field: &'static str,
        /// The value.
        value: f64,
    },
    /// A value above its limit (`r > d/2`, `tip > d/2`).
    #[error("`{field}` must be <= {limit} ({why}), got {value}")]
    TooLarge {
        /// The field.
        field: &'static str,
        /// The value.
        value: f64,
        /// The largest allowed value.
        limit: f64,
        /// What the limit is.
        why: &'static str,
    },
    /// An angle outside its range.
    #[error("`{field}` must be in {range} degrees, got {degrees}")]
    AngleOutOfRange {
        /// The field.
        field: &'static str,
        /// The value, degrees.
        degrees: f64,
        /// The allowed range, e.g. `(0, 180)`.
        range: &'static str,
    },
    /// APT: the bottom and side lines do not make a convex corner.
    #[error(
        "`alpha` + `beta` must be < 90 degrees (the bottom and side lines must meet in a \
         corner), got {alpha} + {beta}"
    )]
    AnglesTooSteep {
        /// Bottom angle, degrees.
        alpha: f64,
        /// Side angle, degrees.
        beta: f64,
    },
    /// APT: the corner circle would reach past the axis.
    #[error(
        "`r` = {r} is too large for `d`, `alpha` and `beta`: the corner centre would lie at \
         e = {e} < 0, on the far side of the axis"
    )]
    CornerPastAxis {
        /// Corner radius.
        r: f64,
        /// The corner centre's distance from the axis it would get.
        e: f64,
    },
    /// APT: a given `e` or `f` disagrees with the one the other parameters imply.
    #[error(
        "`{field}` = {given} is inconsistent with `d`, `r`, `alpha`, `beta`: expected {expected}"
    )]
    Inconsistent {
        /// `e` or `f`.
        field: &'static str,
        /// The value given.
        given: f64,
        /// The value implied by the other parameters.
        expected: f64,
    },
    /// The flute length ends below where the profile needs it.
    #[error("`{field}` = {value} is shorter than the profile needs: expected >= {needed}")]
    LengthTooShort {
        /// `length` or `h`.
        field: &'static str,
        /// The value.
        value: f64,
        /// The least height the profile needs.
        needed: f64,
    },
    /// The flute length goes above where the profile can reach.
    #[error("`{field}` = {value} is too long ({why}): expected <= {limit}")]
    LengthTooLong {
        /// `length` or `h`.
        field: &'static str,
        /// The value.
        value: f64,
        /// The largest allowed value.
        limit: f64,
        /// Why.
        why: &'static str,
    },
    /// A tool library entry or file that is wrong ([`crate::library`]).
    #[error("{file}: {place}: {message}")]
    Library {
        /// The library file.
        file: String,
        /// Line, tool and field, e.g. `tool[2] \"ball6\": holder[1].d0`.
        place: String,
        /// What was expected and found.
        message: String,
    },
    /// A tool asked for by name or number that the library does not hold.
    #[error("{file}: no tool `{wanted}`: the library has {known}")]
    UnknownTool {
        /// The library file.
        file: String,
        /// The name or number asked for.
        wanted: String,
        /// The tools it has, `number name` each.
        known: String,
    },
    /// The shank or holder reaches into the part ([`crate::holder`]).
    #[error(
        "the holder collides at {collisions} of {poses} poses at stick-out {stick_out} mm \
         (first: pose {pose} at ({}, {}, {}), {piece} {depth:.3} mm into the part); {remedy}",
        at[0], at[1], at[2]
    )]
    HolderCollides {
        /// Poses that collide.
        collisions: usize,
        /// Poses checked.
        poses: usize,
        /// The stick-out checked, mm.
        stick_out: f64,
        /// The first pose that collides.
        pose: usize,
        /// Its tool tip, mm.
        at: [f64; 3],
        /// The piece that collides there (`holder[0]`, `shank[1]`).
        piece: String,
        /// How far into the part, mm.
        depth: f64,
        /// The stick-out that clears, or why none does.
        remedy: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_field_and_expectation() {
        let e = ToolError::TooLarge {
            field: "r",
            value: 6.0,
            limit: 5.0,
            why: "d/2",
        };
        assert_eq!(e.to_string(), "`r` must be <= 5 (d/2), got 6");
        let e = ToolError::UnknownShape {
            shape: "drill".into(),
        };
        assert!(
            e.to_string()
                .contains("flat, ball, bull, cone, taperball, apt")
        );
    }
}
