//! Cleanup of the rest a parent job leaves (thesis 002): planned with its parent by
//! [`crate::cleanup`], in stages, not on the part alone.

use super::{FieldError, Kind};
use crate::plan::PlanInput;
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_rest::CleanupParams;
use swarf_tool::Cutter;

/// Rest-material cleanup ([`swarf_rest`]).
pub struct Cleanup;

impl Kind for Cleanup {
    type Params = CleanupParams;
    const KIND: &'static str = "cleanup";
    const LEADS: bool = false;

    fn finish(p: &CleanupParams) -> &Finish {
        &p.finish
    }

    fn scallop(p: &CleanupParams) -> Option<f64> {
        p.scallop
    }

    fn validate(p: &CleanupParams, tool: &Cutter) -> Result<(), FieldError> {
        Ok(p.validate(tool)?)
    }

    fn plan(_: &CleanupParams, _: &Cutting, _: PlanInput<'_>) -> Result<Plan, PathError> {
        Err(PathError::NoPath(
            "a cleanup job is planned with its parent (swarf plan, crate::cleanup)".into(),
        ))
    }
}
