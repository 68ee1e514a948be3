//! The work a program asks of the simulator, bounded before any of it is done.
//!
//! Straight moves and arcs of a vertical tool are swept exactly or as a few chords;
//! tilted motions are sampled as tool instances ([`crate::sweep`]), `n` of them with
//! `n` proportional to the motion's travel over the sample tolerance (to its square
//! root where the second-order bound of [`crate::sweep_bound`] applies). Two budgets
//! keep that bounded: [`MAX_MOTION_SAMPLES`] per motion and [`MAX_TOTAL_SAMPLES`] per
//! verification, each refused with the sample tolerance that would fit.
//!
//! A tilted motion whose tip goes deeper than the tool's reach below the design's
//! lowest point (the floor, [`floor`]) is refused as well: no part of such a tool
//! position is within reach of the design, so the motion cuts through whatever holds
//! the part, and sampling it costs time in proportion to its depth for no
//! measurement (a `GOTO/..,-1000` in CL data took minutes before this check).

use crate::error::SimError;
use crate::sweep::{Sampling, SimTool, SweepPlan, sweep_plan};
use crate::sweep_bound::StockCeiling;
use swarf_toolpath::Motion;

/// Most samples one motion may be swept with.
pub const MAX_MOTION_SAMPLES: f64 = 2_000_000.0;
/// Most samples of all the motions of one verification.
pub const MAX_TOTAL_SAMPLES: f64 = 200_000_000.0;

/// The lowest height a tilted tool's tip may reach: the design's lowest point
/// `design_low` less the tool's reach from its tip, mm.
pub fn floor(tool: &SimTool, design_low: f64) -> f64 {
    design_low - tool.reach()
}

/// Refuses, before any sample is made, a program of `motions` (read from `file`)
/// whose sampling would take more than [`MAX_MOTION_SAMPLES`] for one motion or
/// [`MAX_TOTAL_SAMPLES`] in all, or whose tilted motions take the tip below
/// [`floor`] for a design whose lowest point is `design_low`. `stock_top` bounds the
/// stock's height (it decides which motions the second-order bound may sample).
///
/// # Units
/// mm.
///
/// # Errors
/// [`SimError::TooManySamples`] naming the file, the motion's line (or the program),
/// the samples wanted, the limit and a sample tolerance that fits;
/// [`SimError::BelowFloor`] naming the file, line, the tip's height and the floor.
pub fn check_sampling(
    tool: &SimTool,
    motions: &[Motion],
    sample_tol: f64,
    file: &str,
    design_low: f64,
    stock_top: f64,
) -> Result<(), SimError> {
    let floor = floor(tool, design_low);
    let ceiling = StockCeiling::Level(stock_top);
    let sampling = Sampling {
        tol: sample_tol,
        ceiling: &ceiling,
        first_order: false,
    };
    let mut total = 0.0;
    for m in motions {
        let (plan, wanted) = sweep_plan(tool, m, &sampling);
        if let SweepPlan::Instances { .. } = plan {
            let tip = m.start.cl.z.min(m.end.cl.z);
            if tip < floor {
                return Err(SimError::BelowFloor {
                    file: file.to_string(),
                    line: m.line,
                    tip,
                    floor,
                });
            }
        }
        if wanted > MAX_MOTION_SAMPLES {
            return Err(SimError::TooManySamples {
                file: file.to_string(),
                line: Some(m.line),
                samples: wanted,
                limit: MAX_MOTION_SAMPLES,
                suggested: sample_tol * wanted / MAX_MOTION_SAMPLES,
            });
        }
        total += wanted;
    }
    if total > MAX_TOTAL_SAMPLES {
        return Err(SimError::TooManySamples {
            file: file.to_string(),
            line: None,
            samples: total,
            limit: MAX_TOTAL_SAMPLES,
            suggested: sample_tol * total / MAX_TOTAL_SAMPLES,
        });
    }
    Ok(())
}
