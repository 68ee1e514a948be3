//! Placeholder until the strategy lands (being written now).

use crate::error::PathError;
use crate::job::Job;
use crate::plan::Plan;

/// Plans the strategy.
///
/// # Errors
/// Always, for now.
pub fn plan(_part: &swarf_geom::Part, _job: &Job) -> Result<Plan, PathError> {
    Err(PathError::NoPath("iso_planar: not available yet".into()))
}
