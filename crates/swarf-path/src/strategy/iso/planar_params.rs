//! The parameters of iso-planar finishing ([`super::planar`]): drive planes spaced
//! by a scallop limit or a fixed cross feed, and their feed direction.

use crate::error::PathError;
use crate::params::{
    Finish, StartSide, check_angle, check_scallop, check_stepover, require_spacing,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::domain::{SCALLOP, STEP};

/// Parameters of iso-planar finishing.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct IsoPlanarParams {
    /// Tolerance and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// Scallop height limit h, mm: the drive planes' spacing follows from it (or
    /// give `stepover`).
    #[schemars(extend("unit" = "mm", "domain" = format!("{SCALLOP}, below the tool radius")))]
    pub scallop: Option<f64>,
    /// Fixed distance between the drive planes, mm ("cross feed", thesis 000 ch. 8):
    /// then no boundary passes are added; instead of `scallop`.
    #[schemars(extend("unit" = "mm", "domain" = format!("{STEP}, below the tool diameter")))]
    pub stepover: Option<f64>,
    /// Feed direction in the XY plane, degrees from +X.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees"))]
    pub angle: f64,
    /// Side the first pass starts on.
    pub start: StartSide,
}

impl IsoPlanarParams {
    /// Drive planes spaced by the scallop limit `scallop` (mm), along +X.
    pub fn new(scallop: f64) -> IsoPlanarParams {
        IsoPlanarParams {
            scallop: Some(scallop),
            ..IsoPlanarParams::default()
        }
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming the field: a tolerance, scallop,
    /// stepover or angle out of range; neither or both of scallop and stepover; a
    /// stepover not below the tool's diameter.
    pub fn validate(&self, tool: &swarf_tool::Cutter) -> Result<(), PathError> {
        self.finish.validate()?;
        check_scallop(self.scallop, tool)?;
        check_stepover(self.stepover)?;
        require_spacing(self.scallop, self.stepover)?;
        check_angle(self.angle)?;
        match (self.scallop, self.stepover) {
            (Some(_), Some(_)) => Err(PathError::InvalidParameter {
                field: "stepover".into(),
                message: "give either `scallop` (plane spacing from a scallop limit) or `stepover` (a fixed cross feed), not both".into(),
            }),
            (None, Some(step)) if step >= 2.0 * tool.radius() => Err(PathError::InvalidParameter {
                field: "stepover".into(),
                message: format!(
                    "{step} mm is not smaller than the tool diameter {} mm",
                    2.0 * tool.radius()
                ),
            }),
            _ => Ok(()),
        }
    }
}
