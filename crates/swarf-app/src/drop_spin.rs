//! Drop-and-spin jobs (`kind = "drop-spin"`, paper 003): five-axis passes along the
//! common edge of two faces ([`swarf_fiveaxis::dsm`]).
//!
//! ```toml
//! [strategy]
//! kind = "drop-spin"
//! faces = [0, 1]       # dropped on the first, spun onto the second
//! angle = 0            # the edge's overall direction in XY, degrees
//! step = 2.5           # stations along the edge, mm (default: half the tool radius)
//! passes = 4           # passes across the spin zone, the last at its limit (or stepover)
//! spin = "leading"     # "trailing", "both"
//! zone = "full"        # "snug": the one pass at the zone's limit
//! bands = "both"       # "first", "second": the faces dropped on
//!
//! [output]
//! machine = "builtin:xyzac-trunnion"   # tilted poses need a machine for G-code
//! contacts = "edge-contacts.csv"       # P and Q per pose
//! ```
//!
//! Stations run along the faces' common extent in that direction, a tool radius in
//! from each end. Pass `j` of `n` keeps the zone fraction `j / n` at every station.
//! With a machine, a pass whose side the rotary limits do not reach is cut with the
//! other side (and the summary says so).

use crate::error::AppError;
use crate::error::{Result, bail};
use crate::five_axis::post_options;
use crate::job::Job;
use crate::strategy::Strategy;
use swarf_fiveaxis::FiveAxisError;
use swarf_fiveaxis::dsm::{DropSpinParams, MAX_DROP_SPIN_PASSES, SpinChoice, ZoneChoice};
use swarf_fiveaxis::dsm::{Dsm, EdgePasses, EdgePose, PassParams, Reachable, Side};
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::joints::solve_pass;
use swarf_geom::{Part, Vec3};
use swarf_path::{Plan, PlanReport};
use swarf_tool::Pose;

/// Most stations along an edge.
pub const MAX_STATIONS: usize = 100_000;
/// Largest axis turn per mm of travel before a pair of poses is reported, degrees.
pub const MAX_TURN_DEG: f64 = 10.0;

/// A planned drop-spin job: the tool path and the passes with their contacts.
#[derive(Debug, Clone)]
pub struct DropSpinPlan {
    /// The tool path.
    pub plan: Plan,
    /// The passes, their contacts, zones and station reports.
    pub passes: EdgePasses,
}

/// The stations of `dsm`'s faces along `along`, `step` apart, a tool radius in from
/// the ends of their common extent.
fn stations(job: &Job, s: &DropSpinParams, dsm: &Dsm, along: Vec3) -> Result<Vec<f64>> {
    let (a, b) = (dsm.span(0, along), dsm.span(1, along));
    let r = job.tool.radius();
    let (lo, hi) = (a[0].max(b[0]) + r, a[1].min(b[1]) - r);
    if hi <= lo {
        bail!(
            "strategy.faces: the faces' common extent along the edge ({:.3} mm) is not longer than the tool's diameter",
            hi - lo + 2.0 * r
        );
    }
    let step = s.step.unwrap_or(0.5 * r);
    let n = ((hi - lo) / step).ceil();
    if n > MAX_STATIONS as f64 {
        bail!(
            "strategy.step: {step} mm gives {n} stations over {:.3} mm; expected at most {MAX_STATIONS}",
            hi - lo
        );
    }
    let n = n.max(1.0) as usize;
    Ok((0..=n)
        .map(|i| lo + (hi - lo) * i as f64 / n as f64)
        .collect())
}

/// Whether `machine` reaches every pose of a run (no machine: any pose).
fn reach_on<'a>(
    job: &Job,
    machine: Option<&'a Machine>,
) -> Result<impl Fn(&[Pose]) -> Reachable + 'a> {
    let tool_length = match machine {
        Some(m) => post_options(job, m, Vec::new())?.tool_length,
        None => 0.0,
    };
    Ok(move |poses: &[Pose]| {
        let Some(m) = machine else { return Ok(()) };
        solve_pass(m, poses, None, tool_length, 0)
            .map(|_| ())
            .map_err(|e| match e {
                FiveAxisError::Unreachable {
                    index,
                    axis,
                    message,
                    ..
                } => (index, format!("{axis}: {message}")),
                e => (0, e.to_string()),
            })
    })
}

/// Plans the drop-spin job `job` on `part` (module doc), reachable on `machine`.
///
/// # Errors
/// Faces, tool or direction out of their domains; no edge or an empty zone at the
/// middle station (where the pass count is set from `stepover`); too many stations;
/// no pass at all (the first station report says why).
pub fn plan_drop_spin(job: &Job, part: &Part, machine: Option<&Machine>) -> Result<DropSpinPlan> {
    let start = std::time::Instant::now();
    let s = params_of(job)?;
    let a = s.angle;
    let along = Vec3::new(a.cos(), a.sin(), 0.0);
    let dsm = Dsm::new(part, s.faces, &job.tool, along)?;
    let stations = stations(job, s, &dsm, along)?;
    let fractions: Vec<f64> = match s.zone {
        ZoneChoice::Snug => vec![1.0],
        ZoneChoice::Full => {
            let n = match (s.passes, s.stepover) {
                (0, Some(step)) => {
                    let mid = dsm.station(stations[stations.len() / 2])?;
                    let z = dsm.zone(&mid, s.bands.faces()[0])?;
                    let n = ((z.t2 - z.t1) / step).ceil().max(1.0);
                    if n.is_nan() || n > MAX_DROP_SPIN_PASSES as f64 {
                        bail!(
                            "strategy.stepover: {step} mm across a zone of {:.3} mm gives {n} passes; expected at most {MAX_DROP_SPIN_PASSES} (a stepover of at least {:.6} mm)",
                            z.t2 - z.t1,
                            (z.t2 - z.t1) / MAX_DROP_SPIN_PASSES as f64
                        );
                    }
                    n as usize
                }
                (n, _) => n.max(1),
            };
            (1..=n).map(|j| j as f64 / n as f64).collect()
        }
    };
    let sides = match s.spin {
        SpinChoice::Leading => vec![Side::Leading],
        SpinChoice::Trailing => vec![Side::Trailing],
        SpinChoice::Both => vec![Side::Leading, Side::Trailing],
    };
    let params = PassParams {
        stations,
        fractions,
        sides,
        bands: s.bands.faces(),
        max_turn: MAX_TURN_DEG.to_radians(),
    };
    let reach = reach_on(job, machine)?;
    let all = dsm.passes(&params, &reach)?;
    if all.passes.is_empty() {
        bail!(
            "strategy: no drop-spin pass: {}",
            all.issues.first().map_or_else(
                || "no station gave a pose".to_string(),
                |i| format!(
                    "station {:.4}: {}{}",
                    i.station,
                    i.reason,
                    fit_note(&dsm, i.station, i.band)
                )
            )
        );
    }
    let report = PlanReport {
        elapsed_s: start.elapsed().as_secs_f64(),
        ..PlanReport::default()
    };
    let plan = Plan::from_passes(all.passes.clone(), &job.cutting(), report, Vec::new());
    Ok(DropSpinPlan { plan, passes: all })
}

/// The drop-spin parameters of `job`.
///
/// # Errors
/// A job whose strategy is not drop-spin.
pub fn params_of(job: &Job) -> Result<&DropSpinParams> {
    match &job.strategy {
        Strategy::DropSpin(s) => Ok(s),
        other => Err(AppError::Message(format!(
            "strategy.kind: {:?} is not drop-spin",
            other.kind()
        ))),
    }
}

/// Where the cutter has no zone at station `s` in `band`: the largest cutter of its
/// shape that has one, as a note to an error (empty otherwise).
pub fn fit_note(dsm: &Dsm, s: f64, band: usize) -> String {
    let Ok(st) = dsm.station(s) else {
        return String::new();
    };
    if dsm.zone(&st, band).is_ok() {
        return String::new();
    }
    dsm.largest_fit(&st, band).map_or_else(
        || " (no smaller cutter of this shape fits there either)".to_string(),
        |c| format!(" (the largest cutter of this shape that fits there: {c})"),
    )
}

/// The contact trajectories as CSV: per pose its pass, band (the face of `faces`
/// dropped on), side, station, offset, spin angle (degrees), `P` and `Q`.
pub fn contacts_csv(poses: &[Vec<EdgePose>], faces: [usize; 2]) -> String {
    let mut s = String::from("pass,dropped_on,side,station,offset,angle_deg,px,py,pz,qx,qy,qz\n");
    for (k, run) in poses.iter().enumerate() {
        for e in run {
            let (p, q) = (e.p, e.spin.q);
            s += &format!(
                "{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}\n",
                k + 1,
                faces[e.band],
                e.side,
                e.station,
                e.offset,
                e.spin.angle.to_degrees(),
                p.x,
                p.y,
                p.z,
                q.x,
                q.y,
                q.z
            );
        }
    }
    s
}

/// The zones and station reports as JSON.
pub fn drop_spin_json(p: &EdgePasses) -> serde_json::Value {
    let zones: Vec<serde_json::Value> = p
        .zones
        .iter()
        .map(|sz| match sz.zone {
            Some(z) => serde_json::json!({
                "band": sz.band, "station_mm": sz.station, "t1_mm": z.t1, "t2_mm": z.t2,
                "t2_ball_mm": z.t2_ball, "binding": z.binding,
            }),
            None => serde_json::json!({ "band": sz.band, "station_mm": sz.station, "zone": null }),
        })
        .collect();
    serde_json::json!({ "zones": zones, "issues": p.issues })
}
