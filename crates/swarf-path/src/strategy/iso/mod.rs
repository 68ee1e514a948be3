//! The iso strategies on parametric patches (paper 004): passes along
//! constant-parameter curves ([`parametric`]), sections by vertical drive planes
//! ([`planar`]), and passes placed so that the scallop between neighbours is the
//! limit ([`scallop`]); what they share (`setup`: parameters, side steps, gouge
//! check, ordering; boundary passes along the edges; clipping to trimmed faces), and
//! the least number of passes any family needs ([`pass_bound`]).

pub(crate) mod boundary;
pub(crate) mod boundary_edges;
pub mod parametric;
pub mod pass_bound;
pub mod planar;
mod planar_params;
pub mod scallop;
pub(crate) mod setup;
pub(crate) mod trim_clip;

use crate::error::PathError;
use crate::params::{Cutting, Finish, ParamDir, StartSide, check_scallop};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use setup::IsoJob;
use swarf_geom::domain::SCALLOP;

/// Parameters of iso-parametric and iso-scallop finishing.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct IsoParams {
    /// Tolerance and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// Scallop height limit h, mm: the side step follows from it (required).
    #[schemars(extend("unit" = "mm", "domain" = format!("{SCALLOP}, below the tool radius")))]
    pub scallop: Option<f64>,
    /// The parameter the passes run along (iso-parametric), or the boundary the
    /// first pass follows (iso-scallop).
    pub direction: ParamDir,
    /// Side the first pass starts on.
    pub start: StartSide,
}

impl IsoParams {
    /// Passes spaced by the scallop limit `scallop` (mm), along u from the low end.
    pub fn new(scallop: f64) -> IsoParams {
        IsoParams {
            scallop: Some(scallop),
            ..IsoParams::default()
        }
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming the field: a tolerance or scallop out
    /// of range, no scallop.
    pub fn validate(&self, tool: &swarf_tool::Cutter) -> Result<(), PathError> {
        self.finish.validate()?;
        crate::params::require_spacing(self.scallop, None)?;
        check_scallop(self.scallop, tool)
    }

    /// What the iso setup takes for the strategy `kind`.
    pub(crate) fn job<'a>(&self, cutting: &'a Cutting, kind: &'static str) -> IsoJob<'a> {
        IsoJob {
            cutting,
            finish: self.finish,
            scallop: self.scallop,
            stepover: None,
            direction: self.direction,
            start: self.start,
            kind,
        }
    }
}
