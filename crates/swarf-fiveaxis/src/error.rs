//! The error type of swarf-fiveaxis.

use thiserror::Error;

/// What can go wrong in five-axis positioning, gouge correction, kinematics and
/// posting. Messages name the pass and point (0-based indices as stored in the tool
/// path), the axis or the field, so that a user can find the place.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FiveAxisError {
    /// A parameter is out of its valid range.
    #[error("{field}: {message}")]
    InvalidParameter {
        /// The parameter as the user knows it (e.g. `positioning.max_alpha`).
        field: String,
        /// What was expected.
        message: String,
    },
    /// The tool cannot be placed tangent to the surface at a contact point.
    #[error("pass {pass}, point {index}: {message}")]
    Positioning {
        /// Pass index.
        pass: usize,
        /// Point index in the pass.
        index: usize,
        /// Why.
        message: String,
    },
    /// No lead angle up to `max_alpha` is gouge-free at a contact point.
    #[error(
        "pass {pass}, point {index} (CC {cc:?}): no gouge-free lead angle up to max_alpha = \
         {max_alpha_deg} degrees; at max_alpha the tool is still {depth:.4} mm below the design \
         at {at:?} ({half} half)"
    )]
    NoGougeFreeTilt {
        /// Pass index.
        pass: usize,
        /// Point index in the pass.
        index: usize,
        /// The CC point, mm.
        cc: [f64; 3],
        /// The largest lead angle allowed, degrees.
        max_alpha_deg: f64,
        /// Gouge depth at `max_alpha`, mm.
        depth: f64,
        /// Where the deepest gouge is at `max_alpha`, mm.
        at: [f64; 3],
        /// Which half of the tool gouges (`front` or `back`).
        half: &'static str,
    },
    /// A machine file is malformed or describes an impossible machine.
    #[error("{file}: {message}")]
    Machine {
        /// The machine file.
        file: String,
        /// Line and field when known, and what was expected.
        message: String,
    },
    /// A pose the machine cannot reach (axis limits, or an orientation outside the
    /// reach of its rotary axes).
    #[error("pass {pass}, point {index}: axis {axis}: {message}")]
    Unreachable {
        /// Pass index (or motion index for program-level checks).
        pass: usize,
        /// Point index in the pass.
        index: usize,
        /// The axis at fault (`A`, `C`, `X`, ...; `orientation` when no rotary
        /// setting gives the tool axis).
        axis: String,
        /// Values and limits.
        message: String,
    },
    /// An NC writer refused the moves.
    #[error(transparent)]
    Nc(#[from] swarf_nc::NcError),
}

impl FiveAxisError {
    /// Shorthand for [`FiveAxisError::InvalidParameter`].
    pub fn parameter(field: impl Into<String>, message: impl Into<String>) -> Self {
        FiveAxisError::InvalidParameter {
            field: field.into(),
            message: message.into(),
        }
    }
}
