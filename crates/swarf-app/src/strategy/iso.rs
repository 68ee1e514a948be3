//! The iso strategies (paper 004): planned on the part's patches, never on a mesh.

use super::{FieldError, Kind};
use crate::plan::PlanInput;
use swarf_geom::Part;
use swarf_path::strategy::iso::planar::IsoPlanarParams;
use swarf_path::strategy::iso::{IsoParams, parametric, planar, scallop};
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_tool::Cutter;

/// `input`'s patches, or the error of an iso strategy `kind` given a mesh.
fn patches<'a>(input: PlanInput<'a>, kind: &str) -> Result<&'a Part, PathError> {
    match input {
        PlanInput::Part(part) => Ok(part),
        PlanInput::Mesh(_) => Err(PathError::NoPath(format!(
            "strategy {kind:?} plans on parametric patches; a mesh part needs strategy \"raster\", \"waterline\" or \"steep-shallow\""
        ))),
    }
}

/// Iso-parametric finishing ([`parametric`]).
pub struct IsoParametric;

impl Kind for IsoParametric {
    type Params = IsoParams;
    const KIND: &'static str = "iso-parametric";

    fn finish(p: &IsoParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &IsoParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &IsoParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(p: &IsoParams, cutting: &Cutting, input: PlanInput<'_>) -> Result<Plan, PathError> {
        parametric::plan(patches(input, Self::KIND)?, cutting, p)
    }
}

/// Iso-planar finishing ([`planar`]).
pub struct IsoPlanar;

impl Kind for IsoPlanar {
    type Params = IsoPlanarParams;
    const KIND: &'static str = "iso-planar";

    fn finish(p: &IsoPlanarParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &IsoPlanarParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &IsoPlanarParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(
        p: &IsoPlanarParams,
        cutting: &Cutting,
        input: PlanInput<'_>,
    ) -> Result<Plan, PathError> {
        planar::plan(patches(input, Self::KIND)?, cutting, p)
    }
}

/// Iso-scallop finishing ([`scallop`]).
pub struct IsoScallop;

impl Kind for IsoScallop {
    type Params = IsoParams;
    const KIND: &'static str = "iso-scallop";

    fn finish(p: &IsoParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &IsoParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &IsoParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(p: &IsoParams, cutting: &Cutting, input: PlanInput<'_>) -> Result<Plan, PathError> {
        scallop::plan(patches(input, Self::KIND)?, cutting, p)
    }
}
