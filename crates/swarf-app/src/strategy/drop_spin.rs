//! Drop-and-spin passes along a common edge (paper 003): five-axis, planned by
//! [`crate::drop_spin`] with the job's machine, not on the part alone.

use super::{FieldError, Kind};
use crate::plan::PlanInput;
use swarf_fiveaxis::dsm::DropSpinParams;
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_tool::Cutter;

/// Drop-and-spin ([`swarf_fiveaxis::dsm`]).
pub struct DropSpin;

impl Kind for DropSpin {
    type Params = DropSpinParams;
    const KIND: &'static str = "drop-spin";
    const TILTED: bool = true;
    const LEADS: bool = false;

    fn finish(p: &DropSpinParams) -> &Finish {
        &p.finish
    }

    fn validate(p: &DropSpinParams, _: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate()?)
    }

    fn plan(_: &DropSpinParams, _: &Cutting, _: PlanInput<'_>) -> Result<Plan, PathError> {
        Err(PathError::NoPath(
            "a drop-spin job is planned by swarf-fiveaxis (swarf plan, crate::drop_spin)".into(),
        ))
    }
}
