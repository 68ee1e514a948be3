//! Z-level roughing of a single job: a box over the part's XY extent, its top the
//! job's stock's ([`crate::stock`]; for a caller without one, 1 mm above the part).
//! A sequence roughs its in-process stock instead ([`crate::sequence`]).

use super::meshes::mesh_of;
use super::{FieldError, Kind};
use crate::plan::PlanInput;
use swarf_path::strategy::roughing::{self, RoughingParams, RoughingStock};
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_tool::Cutter;

/// Z-level roughing ([`roughing`]).
pub struct Roughing;

impl Kind for Roughing {
    type Params = RoughingParams;
    const KIND: &'static str = "roughing";
    const LEADS: bool = false;

    fn finish(p: &RoughingParams) -> &Finish {
        &p.finish
    }

    fn validate(p: &RoughingParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(
        p: &RoughingParams,
        cutting: &Cutting,
        input: PlanInput<'_>,
    ) -> Result<Plan, PathError> {
        let mesh = mesh_of(input, p.finish.tolerance)?;
        let b = mesh.aabb();
        let top = cutting
            .material_top
            .unwrap_or(b.max.z + crate::stock::DEFAULT_BOX_ABOVE);
        let (min, max) = ([b.min.x, b.min.y], [b.max.x, b.max.y]);
        let material = move |x: f64, y: f64| {
            if x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1] {
                top
            } else {
                f64::NEG_INFINITY
            }
        };
        let stock = RoughingStock {
            min,
            max,
            top,
            material: &material,
        };
        Ok(roughing::plan(&mesh, &stock, cutting, p)?.0)
    }
}
