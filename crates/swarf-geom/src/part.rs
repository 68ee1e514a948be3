//! A part: a named set of patches.
//!
//! For 3-axis work the part's material is everything below the upper envelope of its
//! patches seen along +z (`../shared/parts/README.md`); for 5-axis work each patch is
//! a face of the part.

use crate::math::Aabb;
use crate::patch::Patch;
use serde::{Deserialize, Serialize};

/// A part made of parametric patches, in mm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Part {
    /// Free-text name from the part file.
    pub name: String,
    /// The faces, in file order (at least one).
    pub patches: Vec<Patch>,
}

impl Part {
    /// Box around all control points (holds the whole part).
    pub fn control_box(&self) -> Aabb {
        self.patches
            .iter()
            .fold(Aabb::empty(), |b, p| b.union(&p.control_box()))
    }
}
