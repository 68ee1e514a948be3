//! The strategies planned on a triangle mesh: a parametric part is tessellated
//! within a tenth of the tolerance first.

use super::{FieldError, Kind};
use crate::plan::PlanInput;
use std::borrow::Cow;
use swarf_geom::TriMesh;
use swarf_path::strategy::raster::{self, RasterParams};
use swarf_path::strategy::steep_shallow::{self, SteepShallowParams};
use swarf_path::strategy::waterline::{self, WaterlineParams};
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_tool::Cutter;

/// The fraction of the tolerance a parametric part is tessellated within for the
/// strategies that plan on meshes.
pub const TESSELLATION_FRACTION: f64 = 0.1;

/// `input` as a mesh: as it is, or its patches tessellated within
/// [`TESSELLATION_FRACTION`] of `tolerance`.
///
/// # Errors
/// A tessellation that fails.
pub fn mesh_of<'a>(input: PlanInput<'a>, tolerance: f64) -> Result<Cow<'a, TriMesh>, PathError> {
    Ok(match input {
        PlanInput::Mesh(mesh) => Cow::Borrowed(mesh),
        PlanInput::Part(part) => Cow::Owned(part.tessellate(tolerance * TESSELLATION_FRACTION)?),
    })
}

/// Drop-cutter raster finishing ([`raster`]).
pub struct Raster;

impl Kind for Raster {
    type Params = RasterParams;
    const KIND: &'static str = "raster";

    fn finish(p: &RasterParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &RasterParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &RasterParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(p: &RasterParams, cutting: &Cutting, input: PlanInput<'_>) -> Result<Plan, PathError> {
        raster::plan(&*mesh_of(input, p.finish.tolerance)?, cutting, p)
    }
}

/// Waterline finishing ([`waterline`]).
pub struct Waterline;

impl Kind for Waterline {
    type Params = WaterlineParams;
    const KIND: &'static str = "waterline";

    fn finish(p: &WaterlineParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &WaterlineParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &WaterlineParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(
        p: &WaterlineParams,
        cutting: &Cutting,
        input: PlanInput<'_>,
    ) -> Result<Plan, PathError> {
        waterline::plan(&*mesh_of(input, p.finish.tolerance)?, cutting, p)
    }
}

/// Steep-and-shallow finishing ([`steep_shallow`]).
pub struct SteepShallow;

impl Kind for SteepShallow {
    type Params = SteepShallowParams;
    const KIND: &'static str = "steep-shallow";

    fn finish(p: &SteepShallowParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &SteepShallowParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &SteepShallowParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(
        p: &SteepShallowParams,
        cutting: &Cutting,
        input: PlanInput<'_>,
    ) -> Result<Plan, PathError> {
        steep_shallow::plan(&*mesh_of(input, p.finish.tolerance)?, cutting, p)
    }
}
