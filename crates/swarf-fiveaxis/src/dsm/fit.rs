//! The largest cutter that fits a valley where the given one does not (module doc of
//! [`crate::dsm`]): the same shape with every length scaled by `s`, the largest `s`
//! whose zone at the station is not empty, by halving down from 1 and then
//! bisection.
//!
//! A valley of two planes is the same at every scale, so a cutter fits it at every
//! size or at none; the size matters where the faces are finite or curved (a drop
//! falls off a face, the curvature closes the valley), which is where this answers.

use super::{Dsm, Station};
use crate::error::FiveAxisError;
use swarf_tool::Cutter;

/// Smallest scale tried, as a fraction of the cutter.
pub const MIN_SCALE: f64 = 1.0 / 64.0;
/// Bisection steps on the scale after the halving.
pub const FIT_STEPS: usize = 12;

/// `c` with every length scaled by `s` (bull and ball; any other cutter unchanged).
fn scaled(c: &Cutter, s: f64) -> Cutter {
    match *c {
        Cutter::Bull {
            radius,
            corner,
            length,
        } => Cutter::Bull {
            radius: radius * s,
            corner: corner * s,
            length: length * s,
        },
        Cutter::Ball { radius, length } => Cutter::Ball {
            radius: radius * s,
            length: length * s,
        },
        other => other,
    }
}

impl Dsm {
    /// The same faces with `cutter`.
    ///
    /// # Errors
    /// As [`Dsm::new`] on `tool`.
    pub fn with_cutter(&self, cutter: &Cutter) -> Result<Dsm, FiveAxisError> {
        let patches = [self.faces[0].patch(), self.faces[1].patch()];
        Ok(Dsm {
            faces: super::sampled_faces(patches, cutter)?,
            ids: self.ids,
            heights: self.heights.clone(),
            cutter: *cutter,
            profile: cutter.profile(),
            along: self.along,
        })
    }

    /// The largest cutter of this one's shape whose zone at `station` in band `k` is
    /// not empty (module doc), within `2^-FIT_STEPS` of its scale; `None` where this
    /// cutter fits, or where not even [`MIN_SCALE`] of it does.
    pub fn largest_fit(&self, station: &Station, k: usize) -> Option<Cutter> {
        let fits = |s: f64| {
            self.with_cutter(&scaled(&self.cutter, s))
                .is_ok_and(|d| d.zone(station, k).is_ok())
        };
        if fits(1.0) {
            return None;
        }
        let mut hi = 1.0;
        let mut lo = 0.5;
        while !fits(lo) {
            hi = lo;
            lo *= 0.5;
            if lo < MIN_SCALE {
                return None;
            }
        }
        for _ in 0..FIT_STEPS {
            let mid = 0.5 * (lo + hi);
            if fits(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(scaled(&self.cutter, lo))
    }
}
