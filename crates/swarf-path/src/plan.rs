//! What a strategy gives: the tool path and the figures it reports beside it.

use crate::params::Cutting;
use crate::strategy::iso::pass_bound::PassBound;
use serde::{Deserialize, Serialize};
use swarf_geom::{Point3, Vec3};
use swarf_toolpath::{Pass, Toolpath, top_z};

/// A region a strategy could not cover, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Uncovered {
    /// Where: e.g. `patch 0, u in [0.2, 0.3], v in [0.9, 1.0]` or an XY box.
    pub region: String,
    /// Why it was left.
    pub reason: String,
}

/// A place where the cutter touches the part at two or more separated points at once
/// (a valley it cannot enter; thesis 002 §5.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoubleContact {
    /// The CL point (tool tip) of the pose.
    pub cl: Point3,
    /// The separated contact points.
    pub contacts: Vec<Point3>,
    /// The part's upward unit normal at each contact.
    pub normals: Vec<Vec3>,
    /// Index of the pass (raster row) it was found on.
    pub pass: usize,
    /// Largest gap between the cutter and the part at the XY midpoint of two of the
    /// contacts, mm (the valley's depth under the tool there); for ramp points, the
    /// largest lift of the tool between them.
    pub gap: f64,
    /// A pair of ramp points (where a ramp-limited pass leaves the part and where it
    /// touches again, [`crate::ramp`]) rather than a double contact.
    #[serde(default)]
    pub ramp: bool,
}

/// Figures a strategy reports beside its tool path.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct PlanReport {
    /// Largest scallop height the strategy predicts from its own geometry, mm.
    pub predicted_max_scallop: Option<f64>,
    /// Smallest and largest side step used, mm.
    pub side_step_range: Option<[f64; 2]>,
    /// Number of CL points the gouge check lifted, and the largest lift, mm.
    pub lifted_points: usize,
    /// Largest lift applied by the gouge check, mm.
    pub max_lift: f64,
    /// Regions left uncovered, with reasons.
    pub uncovered: Vec<Uncovered>,
    /// Iso strategies: per patch, the least number of full-length passes any pass
    /// family along the job's feed direction needs at its scallop height, and the
    /// column that needs them ([`crate::strategy::iso::pass_bound`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pass_bound: Vec<PassBound>,
    /// CL points cut from the passes below the floor or out of the tool's reach of
    /// the stock ([`swarf_toolpath::reach`]).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub clipped_points: usize,
    /// Passes split where they left that region and came back.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub split_passes: usize,
    /// Planning wall time, s (not part of deterministic outputs).
    #[serde(skip)]
    pub elapsed_s: f64,
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if takes a reference
fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl PlanReport {
    /// The smallest and largest of `steps` (mm) as a side step range; `None` for
    /// none.
    pub fn step_range(steps: &[f64]) -> Option<[f64; 2]> {
        (!steps.is_empty()).then(|| {
            [
                steps.iter().copied().fold(f64::INFINITY, f64::min),
                steps.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            ]
        })
    }
}

/// A planned job: the tool path and what the strategy reports about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The tool path.
    pub toolpath: Toolpath,
    /// The strategy's figures.
    pub report: PlanReport,
    /// Double contacts found while planning (raster strategy).
    pub double_contacts: Vec<DoubleContact>,
}

impl Plan {
    /// The plan of `passes` cut with `cutting`'s feeds, linked above their highest
    /// point by `cutting`'s linking rule.
    pub fn from_passes(
        passes: Vec<Pass>,
        cutting: &Cutting,
        report: PlanReport,
        double_contacts: Vec<DoubleContact>,
    ) -> Plan {
        let linking = cutting.linking_for(top_z(&passes));
        Plan {
            toolpath: Toolpath {
                passes,
                feeds: cutting.feeds,
                linking,
            },
            report,
            double_contacts,
        }
    }

    /// Double contacts as CSV (`x,y,z,cx,cy,cz` per contact point; the CL point
    /// repeated for each of its contacts), or `None` when the strategy records none.
    pub fn double_contacts_csv(&self) -> Option<String> {
        if self.double_contacts.is_empty() {
            return None;
        }
        let mut s = String::from("x,y,z,cx,cy,cz\n");
        for d in &self.double_contacts {
            for c in &d.contacts {
                s += &format!(
                    "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}\n",
                    d.cl.x, d.cl.y, d.cl.z, c.x, c.y, c.z
                );
            }
        }
        Some(s)
    }
}
