//! The drop-and-spin method (paper 003): five-axis multipoint positioning of a
//! toroidal cutter in the valley where two faces S1 and S2 of a part meet.
//!
//! The paper is an abstract without equations; every step here is derived from the
//! geometry it describes.
//!
//! - **Edge** ([`edge`]). The part is the upper envelope of its faces, so where two
//!   faces cross the envelope has a V-shaped kink: the common edge, a valley. At a
//!   station (the vertical plane `p . d = s` across the edge, `d` the edge's overall
//!   direction in XY) both faces' heights along the plane's horizontal line are
//!   exact ([`swarf_geom::height`]); the edge point is the root of their difference.
//!   The reference line is that horizontal line; a footprint is its point at offset
//!   `w` from the edge, positive toward the face the tool spins onto.
//! - **Drop** ([`Dsm::drop_on`]). The tool, axis vertical at the footprint, is
//!   lowered onto S1 alone: the height where its clearance from S1 ([`clearance`],
//!   whole cutter) is 0. Above it the tool clears S1 everywhere (S1 is a height
//!   field), below it does not, so the root is the first contact, found by Illinois
//!   between the face's own height at the footprint (the tip on the face) and the top
//!   of its control box. `P` is where the clearance is attained, `n` S1's normal there.
//! - **Spin** ([`spin`]). The tool turns about the line through `P` along `n`: `P`
//!   and the tool's normal there are fixed, so it stays tangent to S1 at `P` (its
//!   axis sweeps a cone about `n`). The second contact is the least `|alpha|` either
//!   way at which the clearance from S2 returns to 0 (the dropped tool is in S2 inside
//!   the zone): scanned in [`SPIN_SCAN`] steps and refined by Illinois. The pose must
//!   still clear S1 everywhere ([`CONTACT_TOL`]).
//! - **Zone** ([`zone`]). `T1` is the offset where the dropped tool starts to touch S2
//!   (clearance 0 at `alpha = 0`). The insert's ball at `P` (centre `P + r n`, radius
//!   `r`) lies in the tool for every spin, so once it reaches S2 every spin gouges:
//!   the paper's limit `T2` is where that ball touches S2. A real cutter can bind
//!   earlier (its bottom, flute or the top of its flutes reaching S2 for every
//!   spin): the real limit is where the best spin's clearance, maximised over the
//!   full turn, drops to 0, and the tool part holding the deepest point there is
//!   named.
//! - **Parameters** ([`params`]): a drop-spin job's strategy table.
//! - **Passes** ([`passes`]). One pass per zone fraction along the edge, a pose per
//!   station, cutting with the leading or trailing side.
//!
//! Two planes meeting in a valley give closed forms (offsets `w` from the edge toward
//! S2, S1 falling at `b` toward it, S2 rising at `g`, insert-centre radius `R`, insert
//! radius `r`): with the insert centre `c = P + r n1` and `c . n = r` for both planes,
//! `T1 = [R (tan b - tan g) + r (sec b - sec g)] / (tan b + tan g)` and the ball limit
//! `T2 = R + r (cos g - cos b) / sin(b + g)`; in the symmetric case the insert circle
//! of a spun tool touches S2 where `2 sin b (1 - t) - sin b cos a + (1 - cos a) sin b
//! cos 2b - sqrt(1 - c²) = 0`, `c = cos b [cos a + (1 - cos a) cos 2b]`, `w = t R`
//! (the circle's lowest point over S2 is `R sqrt(1 - (axis . n2)²)` below its
//! centre). The tests hold the solver to them.

pub mod clearance;
pub mod edge;
pub mod fit;
pub mod params;
pub mod passes;
pub mod spin;
pub mod zone;

pub use clearance::{Clearance, Face};
pub use edge::Station;
pub use params::{BandChoice, DropSpinParams, MAX_DROP_SPIN_PASSES, SpinChoice, ZoneChoice};
pub use passes::{
    EdgePasses, EdgePose, PassParams, Reach, Reachable, Side, StationIssue, StationZone,
};
pub use spin::{Drop, Spin, SpinSide};
pub use zone::{Binding, Zone};

/// Spin angles are scanned in steps of this, radians (two degrees).
pub const SPIN_SCAN: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// Roots (heights, angles, offsets) are refined until their bracket is this narrow.
pub const ROOT_TOL: f64 = 1e-12;
/// A pose clears a face when its clearance is at least minus this, mm.
pub const CONTACT_TOL: f64 = 1e-6;
/// Most face samples one clearance query may measure (about twice what the shipped
/// edge job's bull d = 12, r = 2 measures): the work of a job grows with it,
/// so a corner too small for the faces is refused before any query.
pub const MAX_QUERY_SAMPLES: f64 = 6000.0;

use crate::error::FiveAxisError;
use swarf_geom::height::PartHeights;
use swarf_geom::{Part, Patch, Vec3};
use swarf_tool::{Cutter, Profile};

/// Two faces of a part and a cutter, ready for drop-and-spin queries.
#[derive(Debug, Clone)]
pub struct Dsm {
    faces: [Face; 2],
    ids: [usize; 2],
    heights: [PartHeights; 2],
    cutter: Cutter,
    profile: Profile,
    along: Vec3,
}

impl Dsm {
    /// The faces `faces` (patch indices) of `part` with `cutter`; stations are planes
    /// across `along` (the edge's overall direction in XY).
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] on `faces` for an index out of range or a
    /// face named twice, on `along` for a direction without an XY part, on `tool` for
    /// a cutter that is not a bull or a ball (no insert circle).
    pub fn new(
        part: &Part,
        faces: [usize; 2],
        cutter: &Cutter,
        along: Vec3,
    ) -> Result<Dsm, FiveAxisError> {
        let n = part.patches.len();
        if faces[0] == faces[1] || faces.iter().any(|&k| k >= n) {
            return Err(FiveAxisError::parameter(
                "faces",
                format!("{faces:?}: expected two different patch indices below {n}"),
            ));
        }
        let sampled = sampled_faces([&part.patches[faces[0]], &part.patches[faces[1]]], cutter)?;
        let xy = Vec3::new(along.x, along.y, 0.0);
        let Some(along) = xy
            .try_normalize(1e-12)
            .filter(|v| v.iter().all(|c| c.is_finite()))
        else {
            return Err(FiveAxisError::parameter(
                "along",
                "expected a direction with an XY part".to_string(),
            ));
        };
        let heights = |k: usize| {
            let one = Part::new(
                format!("{} face {}", part.name, faces[k]),
                vec![part.patches[faces[k]].clone()],
            );
            PartHeights::new(&one).map_err(|e| FiveAxisError::parameter("part", e.to_string()))
        };
        Ok(Dsm {
            faces: sampled,
            ids: faces,
            heights: [heights(0)?, heights(1)?],
            cutter: *cutter,
            profile: cutter.profile(),
            along,
        })
    }

    /// The cutter.
    pub fn cutter(&self) -> &Cutter {
        &self.cutter
    }

    /// The faces' patch indices in the part, in the order given.
    pub fn ids(&self) -> [usize; 2] {
        self.ids
    }

    /// The cutter's profile.
    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// Face `k` (0 or 1 in the order given).
    pub fn face(&self, k: usize) -> &Face {
        &self.faces[k.min(1)]
    }

    /// The insert radius `r` (a ball's radius) and the insert-centre radius `R`, mm.
    pub fn insert(&self) -> (f64, f64) {
        match self.cutter {
            Cutter::Bull { radius, corner, .. } => (corner, radius - corner),
            _ => (self.cutter.radius(), 0.0),
        }
    }
}

/// The two faces sampled for a corner radius `corner` (mm), and the most samples a
/// clearance query of radius `bound` (mm) measures on either.
fn faces_at(patches: [&Patch; 2], corner: f64, bound: f64) -> ([Face; 2], f64) {
    let faces = patches.map(|p| Face::new(p, clearance::SAMPLE_SPACING * corner));
    let per_query = faces[0]
        .samples_within(bound)
        .max(faces[1].samples_within(bound));
    (faces, per_query)
}

/// The two faces sampled for the clearance of `cutter`, at a spacing set by its
/// insert radius (a bull's corner, a ball's radius).
///
/// # Errors
/// [`FiveAxisError::InvalidParameter`] on `tool` for a cutter without an insert
/// circle to spin.
fn sampled_faces(patches: [&Patch; 2], cutter: &Cutter) -> Result<[Face; 2], FiveAxisError> {
    let corner = match *cutter {
        Cutter::Bull { corner, .. } if corner > 0.0 => corner,
        Cutter::Ball { radius, .. } => radius,
        _ => {
            return Err(FiveAxisError::parameter(
                "tool",
                format!("{cutter}: expected a bull or ball cutter (an insert circle to spin)"),
            ));
        }
    };
    let bound = clearance::query_radius(&cutter.profile(), cutter.radius());
    let (faces, per_query) = faces_at(patches, corner, bound);
    if per_query > MAX_QUERY_SAMPLES {
        // The least corner that fits, to the thousandth of a mm above: from the
        // sphere's section at the nominal spacing, then up by 1% until the faces'
        // own sampling fits (a few tries on this error path).
        let mut fits =
            bound / clearance::SAMPLE_SPACING * (std::f64::consts::PI / MAX_QUERY_SAMPLES).sqrt();
        for _ in 0..100 {
            if faces_at(patches, fits, bound).1 <= MAX_QUERY_SAMPLES {
                break;
            }
            fits *= 1.01;
        }
        return Err(FiveAxisError::parameter(
            "tool",
            format!(
                "{cutter}: a corner radius of {} mm samples the faces so finely that each \
                 clearance query would measure about {} points, more than the {} \
                 drop-and-spin takes: use a corner radius of at least {} mm with this \
                 cutter",
                swarf_geom::domain::show(corner),
                swarf_geom::domain::show(per_query.round()),
                swarf_geom::domain::show(MAX_QUERY_SAMPLES),
                swarf_geom::domain::show((fits * 1000.0).ceil() / 1000.0)
            ),
        ));
    }
    Ok(faces)
}
