//! The cleanup tool path (thesis 002 §4.4 and §5.4): the regions' passes in an
//! order that keeps air time short, linked by skims.
//!
//! - **Patterns**: flow-cut ([`crate::pencil`]) or follow-pocket ([`crate::pocket`]),
//!   whose rings end with the cleanup tool's own pencil passes: rings shrinking in
//!   XY stop up to a step short of the valley's bottom, where the contact jumps from
//!   one side to the other, and the pencil pass is exactly there. The stepover
//!   follows from the scallop height as for the raster
//!   ([`swarf_path::stepping::raster_step::stepover_for_scallop`]).
//! - **Order**: regions greedily, each next the one whose first pass starts nearest
//!   (in XY) to where the previous ended, starting with the first region; inside a
//!   region the pattern's own order.
//! - **Links**: every pass after the first is entered by a skim at the highest drop
//!   height of the cleanup tool along the straight XY line from the previous pass's
//!   end to its start (sampled every quarter tool radius: a bump of the CL surface is
//!   at least as wide as the tool) plus [`SKIM_MARGIN`], never above the clearance
//!   plane.
//! - **Gouge**: every CL point is an exact drop of the cleanup tool onto the whole
//!   part, and moves between them are refined as the raster's are, to
//!   [`CHORD_FRACTION`] of the tolerance: the refinement tests the chord at its
//!   midpoint, and over a convex edge (the CL curve an arc meeting a line) the chord
//!   dips below the curve up to a quarter further elsewhere.
//!
//! An empty region set gives an empty tool path (no passes), not an error: the
//! caller says so and writes a program without moves.

use crate::detect::reference_pairs;
use crate::directory::group;
use crate::error::RestError;
use crate::order::{chains, open_path};
use crate::pair::{DepthProbe, RestPair};
use crate::params::CleanupParams;
use crate::pencil::Pencil;
use crate::pocket::follow_pocket;
use crate::region::{LINK_PITCHES, RestRegion};
use geo::{Contains, Point};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::TriMesh;
use swarf_path::Cutting;
use swarf_path::stepping::raster_step::stepover_for_scallop;
use swarf_tool::Cutter;
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::{Pass, Toolpath, top_z};

/// The chordal refinement of cleanup passes, as a fraction of the tolerance.
pub const CHORD_FRACTION: f64 = 0.5;
/// Locus points closer than this are one, mm.
pub const SAME_POINT: f64 = 1e-4;
/// Height of a skim link above the highest drop along it, mm.
pub const SKIM_MARGIN: f64 = 1.0;

/// The cleanup cut patterns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Pattern {
    /// Passes along the cleanup tool's bitangency curves.
    #[default]
    FlowCut,
    /// Rings from the region boundary inwards.
    FollowPocket,
}

/// Plans the cleanup of `regions` on `mesh`, left by `reference`, with `cutting`'s
/// tool (module doc).
///
/// # Errors
/// [`RestError::ToolNotSmaller`] for a cleanup tool wider than the reference tool;
/// [`RestError::InvalidParameter`] for a scallop the tool cannot leave or a region
/// needing too many rings.
pub fn plan_cleanup(
    mesh: &TriMesh,
    regions: &[RestRegion],
    reference: &Cutter,
    cutting: &Cutting,
    params: &CleanupParams,
) -> Result<Toolpath, RestError> {
    let tool = &cutting.tool;
    if tool.radius() > reference.radius() {
        return Err(RestError::ToolNotSmaller {
            cleanup: tool.to_string(),
            reference: reference.to_string(),
        });
    }
    let scallop = RestError::check("scallop", params.scallop_mm(), false)?;
    let stepover = stepover_for_scallop(tool, scallop)?;
    let tol = params.finish.tolerance;
    let chord = CHORD_FRACTION * tol;
    let dropper = MeshDropper::new(mesh, tool);
    let locus = if regions.is_empty() {
        Vec::new()
    } else {
        reference_pairs(mesh, &dropper, tol)?
    };
    let pencil = Pencil {
        mesh,
        dropper: &dropper,
        probe: DepthProbe::new(&dropper),
        tolerance: chord,
        passes: match params.pattern {
            Pattern::FlowCut => params.passes,
            Pattern::FollowPocket => 0,
        },
        stepover,
    };
    let mut per_region: Vec<Vec<Pass>> = Vec::with_capacity(regions.len());
    for r in regions {
        let mut passes = match params.pattern {
            Pattern::FollowPocket => follow_pocket(mesh, &dropper, r, stepover, chord)?,
            Pattern::FlowCut => Vec::new(),
        };
        let chains = locus_chains(&locus, r, 0.5 * tool.radius());
        passes.extend(pencil.passes(r, &chains));
        per_region.push(passes);
    }
    let mut passes = order_regions(per_region);
    let linking = cutting.linking_for(top_z(&passes));
    add_skims(&dropper, &mut passes, linking.clearance);
    Ok(Toolpath {
        passes,
        feeds: cutting.feeds,
        linking,
    })
}

/// The cleanup tool's locus pairs inside `region`, grouped and ordered into chains.
fn locus_chains(locus: &[RestPair], region: &RestRegion, pitch: f64) -> Vec<Vec<RestPair>> {
    let inside: Vec<RestPair> = locus
        .iter()
        .filter(|p| region.boundary.contains(&Point::new(p.cl.x, p.cl.y)))
        .copied()
        .collect();
    let cls: Vec<[f64; 2]> = inside.iter().map(|p| [p.cl.x, p.cl.y]).collect();
    let mut out = Vec::new();
    for g in group(&cls, pitch, |_, _| true) {
        let pts: Vec<[f64; 2]> = g.iter().map(|&k| cls[k]).collect();
        for c in chains(&pts, &open_path(&pts), LINK_PITCHES * pitch) {
            let mut chain: Vec<RestPair> = Vec::with_capacity(c.len());
            for &i in &c {
                let p = inside[g[i]];
                // A crease met exactly by a sample is also found by the bisection
                // next to it: keep one of two points this close.
                if chain
                    .last()
                    .is_none_or(|q| (q.cl - p.cl).norm() > SAME_POINT)
                {
                    chain.push(p);
                }
            }
            out.push(chain);
        }
    }
    out
}

/// The regions' passes in greedy nearest-start order (module doc).
fn order_regions(mut per_region: Vec<Vec<Pass>>) -> Vec<Pass> {
    per_region.retain(|p| !p.is_empty());
    let mut out: Vec<Pass> = Vec::new();
    while !per_region.is_empty() {
        let here = out.last().and_then(|p| p.points.last()).map(|p| p.pose.cl);
        let next = match here {
            None => 0,
            Some(h) => {
                (0..per_region.len())
                    .map(|k| {
                        let s = per_region[k][0].points[0].pose.cl;
                        (k, (s.x - h.x).hypot(s.y - h.y))
                    })
                    .fold(
                        (0, f64::INFINITY),
                        |m, (k, d)| if d < m.1 { (k, d) } else { m },
                    )
                    .0
            }
        };
        out.extend(per_region.remove(next));
    }
    out.retain(|p| p.points.len() > 1);
    out
}

/// Sets every pass's skim height after the first (module doc).
fn add_skims(dropper: &MeshDropper, passes: &mut [Pass], clearance: f64) {
    let mut scratch = DropScratch::default();
    let step = 0.25 * dropper.tool().radius();
    for k in 1..passes.len() {
        let (Some(a), Some(b)) = (
            passes[k - 1].points.last().map(|p| p.pose.cl),
            passes[k].points.first().map(|p| p.pose.cl),
        ) else {
            continue;
        };
        let len = (b.x - a.x).hypot(b.y - a.y);
        let n = (len / step).ceil().max(1.0) as usize;
        let top = (0..=n)
            .filter_map(|i| {
                let t = i as f64 / n as f64;
                dropper
                    .drop(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), &mut scratch)
                    .map(|h| h.z)
            })
            .fold(a.z.max(b.z), f64::max);
        passes[k].skim = Some((top + SKIM_MARGIN).min(clearance));
    }
}
