//! Rest detection from any of the three sources (thesis 002 ch. 4 and §5.1-5.3),
//! each ending in the same regions.
//!
//! - *contacts*: the double contacts recorded while the parent finishing path was
//!   planned (§5.1.1: no extra simulation). A parent whose passes run along a valley
//!   records none there.
//! - *reference tool*: contact-only crease scans of the part with the parent's tool
//!   ([`swarf_path::strategy::raster::crease_scan`]) along X and along Y every quarter tool
//!   radius, so that a valley in any direction is crossed by one family of lines.
//! - *stock*: the in-process model after the parent program(s) minus the design
//!   ([`crate::stock`]).
//!
//! Pairs become raw pieces through the spatial directory at pitch `R/2` (R the
//! reference tool's radius, §5.2.1) and the chain ordering; the boundary operations
//! of [`crate::region`] make the regions.

use crate::error::RestError;
use crate::pair::{DepthProbe, RestPair};
use crate::region::{RawPiece, RegionParams, RestRegion, pieces_from_pairs, regions};
use crate::stock::pieces_from_excess;
use rayon::prelude::*;
use swarf_geom::TriMesh;
use swarf_path::DoubleContact;
use swarf_path::strategy::raster::crease_scan;
use swarf_sim::Grid;
use swarf_tool::Cutter;
use swarf_tool::drop::MeshDropper;

/// The directory pitch in reference tool radii (thesis 002 §5.2.1).
pub const PITCH_RADII: f64 = 0.5;
/// Crease scan spacing in reference tool radii.
pub const SCAN_RADII: f64 = 0.25;
/// Most drops of the two crease scans of a part.
pub const MAX_SCAN_DROPS: f64 = 2e8;

/// Where the rest comes from.
#[derive(Debug, Clone, Copy)]
pub enum Source<'a> {
    /// Double contacts recorded while the parent path was planned.
    Contacts(&'a [DoubleContact]),
    /// Crease scans with the reference tool in two directions.
    Reference,
    /// The in-process stock: per-cell excess over the design (row-major over
    /// `grid`, NaN where not measured) and the design heights.
    Stock {
        /// The stock's grid.
        grid: &'a Grid,
        /// Stock minus design per cell, mm.
        excess: &'a [f64],
        /// Design height per cell, mm.
        design: &'a [f64],
    },
}

impl Source<'_> {
    /// The source's name in reports: `contacts`, `reference` or `stock`.
    pub fn name(&self) -> &'static str {
        match self {
            Source::Contacts(_) => "contacts",
            Source::Reference => "reference",
            Source::Stock { .. } => "stock",
        }
    }
}

/// What detection found.
#[derive(Debug, Clone, Default)]
pub struct Detection {
    /// The regions, after the boundary operations.
    pub regions: Vec<RestRegion>,
    /// Rest samples (pairs) found, before the depth threshold.
    pub samples: usize,
    /// Directory pitch used, mm.
    pub pitch: f64,
}

/// The rest on `mesh` that `reference` leaves, from `source` (module doc).
/// `tolerance` is the machining tolerance: contacts whose gap is below it are not a
/// valley.
///
/// # Errors
/// A region parameter out of its domain; an empty mesh (reference scans).
pub fn detect(
    mesh: &TriMesh,
    reference: &Cutter,
    source: Source<'_>,
    tolerance: f64,
    params: &RegionParams,
) -> Result<Detection, RestError> {
    params.validate()?;
    RestError::check("tolerance", tolerance, false)?;
    let radius = reference.radius();
    let pitch = PITCH_RADII * radius;
    let dropper = MeshDropper::new(mesh, reference);
    let (pieces, samples): (Vec<RawPiece>, usize) = match source {
        Source::Stock {
            grid,
            excess,
            design,
        } => {
            let p = pieces_from_excess(grid, excess, design, params.threshold);
            let n = p.len();
            (p, n)
        }
        Source::Contacts(dcs) => {
            let pairs = valley_pairs(&dropper, dcs);
            let n = pairs.len();
            (
                pieces_from_pairs(&dropper, &pairs, pitch, params.threshold),
                n,
            )
        }
        Source::Reference => {
            let pairs = reference_pairs(mesh, &dropper, tolerance)?;
            let n = pairs.len();
            (
                pieces_from_pairs(&dropper, &pairs, pitch, params.threshold),
                n,
            )
        }
    };
    Ok(Detection {
        regions: regions(pieces, params)?,
        samples,
        pitch,
    })
}

/// The valley pairs of recorded double contacts, with their depths (in parallel, in
/// input order). A double contact whose CL point is off the part (the tool hanging
/// over the part's edge, touching two of its boundary edges) is not a valley and is
/// left out.
pub fn valley_pairs(dropper: &MeshDropper, contacts: &[DoubleContact]) -> Vec<RestPair> {
    let probe = DepthProbe::new(dropper);
    contacts
        .par_iter()
        .filter(|d| dropper.surface_z(d.cl.x, d.cl.y).is_some())
        .filter_map(|d| probe.valley(d))
        .collect()
}

/// The valley pairs of crease scans along X and Y with `dropper`'s tool.
///
/// # Errors
/// An empty mesh; scans that would need more than [`MAX_SCAN_DROPS`] drops (a tool
/// tiny for the part).
pub fn reference_pairs(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    tolerance: f64,
) -> Result<Vec<RestPair>, RestError> {
    let spacing = SCAN_RADII * dropper.tool().radius();
    // The box of the usable triangles (corners within the coordinate domain).
    let b = mesh.aabb();
    let (lo, hi) = ([b.min.x, b.min.y], [b.max.x, b.max.y]);
    let reach = 2.0 * dropper.tool().radius();
    let drops =
        2.0 * ((hi[0] - lo[0] + reach) / spacing + 1.0) * ((hi[1] - lo[1] + reach) / spacing + 1.0);
    if drops > MAX_SCAN_DROPS {
        return Err(RestError::InvalidParameter {
            field: "reference tool".into(),
            value: dropper.tool().cutter().to_string(),
            expected: format!(
                "a tool large enough to scan a {:.1} x {:.1} mm part in at most {MAX_SCAN_DROPS:.0e} drops ({drops:.1e} needed)",
                hi[0] - lo[0],
                hi[1] - lo[1]
            ),
        });
    }
    let mut contacts = crease_scan(mesh, dropper, 0.0, spacing, tolerance)?;
    contacts.extend(crease_scan(
        mesh,
        dropper,
        std::f64::consts::FRAC_PI_2,
        spacing,
        tolerance,
    )?);
    Ok(valley_pairs(dropper, &contacts))
}
