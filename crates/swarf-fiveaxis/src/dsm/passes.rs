//! Passes along the common edge (module doc of [`crate::dsm`]): one pass per zone
//! fraction, a pose per station.
//!
//! A pass keeps its fraction `f` of each station's zone, `w = T1 + f (T2 - T1)`, so
//! it follows the zone's width along the edge instead of coming out ragged where the
//! zone narrows; `f = 1` is the snug pass (the insert's ball or the binding part
//! touching at the limit). Each pose is the drop at that footprint spun to the side
//! the pass asked for: *leading* where the second contact `Q` lies ahead of the tool
//! axis along the feed (the edge's tangent), *trailing* where it lies behind; the
//! side is chosen at every station, so the pass stays on one root branch. A station
//! that gives no pose (an empty zone, a drop off a face, no spin) is reported with
//! its reason and the pass is split there; consecutive poses whose axes turn more
//! than `max_turn` per mm of travel are reported too.
//!
//! Each band (the tool dropped on face 0 and spun onto face 1, or the reverse) has
//! its own zone on the other face's side of the edge, so both bands together cover
//! the valley. A pass the machine cannot reach (its rotary limits) is cut with the
//! other side where that one is reachable and not cut anyway: the spin sign the
//! machine allows.
//!
//! The stations' zones (most of the time) are found in parallel, each on its own,
//! so the result does not depend on the threads.

use super::{Dsm, Spin, SpinSide, Station, Zone};
use crate::error::FiveAxisError;
use rayon::prelude::*;
use serde::Serialize;
use swarf_tool::Pose;
use swarf_toolpath::{Contact, Pass, PathPoint};

/// Which side of the tool cuts the second face.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// `Q` ahead of the axis along the feed.
    Leading,
    /// `Q` behind the axis.
    Trailing,
}

impl Side {
    /// The other side.
    pub fn other(self) -> Side {
        match self {
            Side::Leading => Side::Trailing,
            Side::Trailing => Side::Leading,
        }
    }
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Side::Leading => "leading",
            Side::Trailing => "trailing",
        })
    }
}

/// Parameters of drop-and-spin passes.
#[derive(Debug, Clone, PartialEq)]
pub struct PassParams {
    /// Stations along the edge direction, mm, in cutting order.
    pub stations: Vec<f64>,
    /// Zone fractions of the passes, each in `[0, 1]`.
    pub fractions: Vec<f64>,
    /// The cutting sides: every fraction is cut with each, in this order.
    pub sides: Vec<Side>,
    /// The bands: the faces dropped on (each 0 or 1), in cutting order.
    pub bands: Vec<usize>,
    /// Largest axis turn per mm of travel before a pair of poses is reported,
    /// radians per mm.
    pub max_turn: f64,
}

/// One pose of a pass with its contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgePose {
    /// Station, mm.
    pub station: f64,
    /// Offset from the edge, mm.
    pub offset: f64,
    /// The band: the face dropped on (0 or 1).
    pub band: usize,
    /// The side cutting the other face.
    pub side: Side,
    /// The spun pose and its contacts.
    pub spin: Spin,
    /// First contact `P`.
    pub p: swarf_geom::Point3,
}

/// Something a pass could not do at a station.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StationIssue {
    /// Station, mm.
    pub station: f64,
    /// The band (the face dropped on).
    pub band: usize,
    /// Zone fraction of the pass.
    pub fraction: f64,
    /// Why.
    pub reason: String,
}

/// Drop-and-spin passes and what went wrong on the way.
#[derive(Debug, Clone, Default)]
pub struct EdgePasses {
    /// The passes as tool paths (split where a station gives no pose).
    pub passes: Vec<Pass>,
    /// Every pose with its contacts, pass by pass.
    pub poses: Vec<Vec<EdgePose>>,
    /// Stations without a pose, and axis turns above the limit.
    pub issues: Vec<StationIssue>,
    /// The zone at each station of each band.
    pub zones: Vec<StationZone>,
}

/// The zone of one band at one station.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StationZone {
    /// The band (the face dropped on).
    pub band: usize,
    /// Station, mm.
    #[serde(rename = "station_mm")]
    pub station: f64,
    /// The zone, `None` where it could not be found.
    pub zone: Option<Zone>,
}

/// What the machine says of a run of poses: `Err((index, reason))` for the first
/// pose it cannot reach.
pub type Reachable = Result<(), (usize, String)>;

/// Whether the machine reaches a run of poses.
pub type Reach<'a> = &'a dyn Fn(&[Pose]) -> Reachable;

/// A station's edge and zone for one band, or why there is none.
type Prepared = Result<(Station, Zone), String>;

/// The runs of one pass (split where a station gives no pose) and its issues.
type Runs = (Vec<Vec<EdgePose>>, Vec<StationIssue>);

impl Dsm {
    /// The pose of fraction `f` at `station` to `side`, dropped on face `k`, or the
    /// reason there is none.
    fn edge_pose(
        &self,
        (st, zone): &(Station, Zone),
        f: f64,
        (side, k): (Side, usize),
    ) -> Result<EdgePose, String> {
        let w = zone.t1 + f * (zone.t2 - zone.t1);
        let drop = self
            .drop_on(k, self.footprint(st, k, w))
            .map_err(|e| e.to_string())?;
        let ahead = |s: &Spin| (s.q - s.pose.cl).dot(&st.tangent);
        let spins: Vec<Spin> = [SpinSide::Plus, SpinSide::Minus]
            .into_iter()
            .filter_map(|side| self.spin(&drop, side))
            .collect();
        let chosen = spins
            .into_iter()
            .filter(|s| s.own_clearance >= -super::CONTACT_TOL)
            .max_by(|a, b| {
                let (x, y) = (ahead(a), ahead(b));
                match side {
                    Side::Leading => x.total_cmp(&y),
                    Side::Trailing => y.total_cmp(&x),
                }
            })
            .ok_or_else(|| format!("no spin at offset {w:.6} clears both faces"))?;
        Ok(EdgePose {
            station: st.s,
            offset: w,
            band: k,
            side,
            spin: chosen,
            p: drop.p,
        })
    }

    /// The runs of the pass at fraction `f` to `side` in `band`.
    fn runs(
        &self,
        params: &PassParams,
        prepared: &[Prepared],
        (band, side, f): (usize, Side, f64),
    ) -> Runs {
        let issue = |station: f64, reason: String| StationIssue {
            station,
            band,
            fraction: f,
            reason,
        };
        let (mut runs, mut issues) = (Vec::new(), Vec::new());
        let mut run: Vec<EdgePose> = Vec::new();
        for (&s, prep) in params.stations.iter().zip(prepared) {
            let pose = prep
                .as_ref()
                .map_err(Clone::clone)
                .and_then(|sz| self.edge_pose(sz, f, (side, band)));
            match pose {
                Ok(p) => {
                    if let Some(prev) = run.last() {
                        let travel = (p.spin.pose.cl - prev.spin.pose.cl).norm().max(1e-12);
                        let turn = prev.spin.pose.axis.angle(&p.spin.pose.axis);
                        if turn / travel > params.max_turn {
                            issues.push(issue(
                                s,
                                format!(
                                    "the axis turns {:.3} degrees over {travel:.4} mm, above the limit",
                                    turn.to_degrees()
                                ),
                            ));
                        }
                    }
                    run.push(p);
                }
                Err(reason) => {
                    issues.push(issue(s, reason));
                    if !run.is_empty() {
                        runs.push(std::mem::take(&mut run));
                    }
                }
            }
        }
        runs.push(run);
        runs.retain(|r| r.len() > 1);
        (runs, issues)
    }

    /// The runs of `runs` the machine cannot reach, with the station and reason.
    fn unreachable(runs: &[Vec<EdgePose>], reach: Reach<'_>) -> Vec<(usize, f64, String)> {
        runs.iter()
            .enumerate()
            .filter_map(|(k, run)| {
                let poses: Vec<Pose> = run.iter().map(|e| e.spin.pose).collect();
                reach(&poses)
                    .err()
                    .map(|(i, why)| (k, run[i.min(run.len() - 1)].station, why))
            })
            .collect()
    }

    /// The pass at fraction `f` to `side` in `band`, cut with the other side where the
    /// machine reaches only that one (and it is not cut anyway).
    fn reachable_runs(
        &self,
        params: &PassParams,
        prepared: &[Prepared],
        (band, side, f): (usize, Side, f64),
        reach: Reach<'_>,
    ) -> Runs {
        let (mut runs, mut issues) = self.runs(params, prepared, (band, side, f));
        let bad = Self::unreachable(&runs, reach);
        if bad.is_empty() {
            return (runs, issues);
        }
        let other = side.other();
        let mut also = String::new();
        if !params.sides.contains(&other) {
            let (alt, alt_issues) = self.runs(params, prepared, (band, other, f));
            let alt_bad = Self::unreachable(&alt, reach);
            if let Some((_, _, why)) = alt_bad.first() {
                also = format!("; so is the {other} spin ({why})");
            }
            if !alt.is_empty() && alt_bad.is_empty() {
                let (_, s, why) = &bad[0];
                let mut issues = alt_issues;
                issues.push(StationIssue {
                    station: *s,
                    band,
                    fraction: f,
                    reason: format!(
                        "the {side} spin is out of the machine's reach ({why}): the pass cuts with the {other} side"
                    ),
                });
                return (alt, issues);
            }
        }
        for (k, s, why) in bad.iter().rev() {
            runs.remove(*k);
            issues.push(StationIssue {
                station: *s,
                band,
                fraction: f,
                reason: format!("the {side} spin is out of the machine's reach: {why}{also}"),
            });
        }
        (runs, issues)
    }

    /// Drop-and-spin passes (module doc): per band, side and fraction in that order;
    /// `reach` says which runs the machine can cut.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] on `stations` (fewer than two, not finite),
    /// `fractions` (none, or outside `[0, 1]`), `sides` (none), `bands` (none, or not
    /// 0 or 1) or `max_turn` (not above 0).
    pub fn passes(
        &self,
        params: &PassParams,
        reach: Reach<'_>,
    ) -> Result<EdgePasses, FiveAxisError> {
        validate(params)?;
        let mut out = EdgePasses::default();
        for &band in &params.bands {
            let prepared: Vec<Prepared> = params
                .stations
                .par_iter()
                .map(|&s| {
                    self.station(s)
                        .and_then(|st| self.zone(&st, band).map(|z| (st, z)))
                        .map_err(|e| e.to_string())
                })
                .collect();
            out.zones.extend(
                params
                    .stations
                    .iter()
                    .zip(&prepared)
                    .map(|(&s, p)| StationZone {
                        band,
                        station: s,
                        zone: p.as_ref().ok().map(|p| p.1),
                    }),
            );
            for &side in &params.sides {
                for &f in &params.fractions {
                    let (runs, issues) =
                        self.reachable_runs(params, &prepared, (band, side, f), reach);
                    out.issues.extend(issues);
                    for run in runs {
                        out.passes.push(self.pass_of(&run, band));
                        out.poses.push(run);
                    }
                }
            }
        }
        Ok(out)
    }

    /// The tool path pass of `run`, contacts on the second face.
    fn pass_of(&self, run: &[EdgePose], k: usize) -> Pass {
        let other = 1 - k;
        let points = run
            .iter()
            .map(|e| {
                let s = &e.spin;
                let normal = self
                    .face(other)
                    .patch()
                    .derivs(s.q_uv[0], s.q_uv[1])
                    .normal()
                    .map_or(swarf_geom::Vec3::z(), |n| if n.z < 0.0 { -n } else { n });
                PathPoint {
                    pose: s.pose,
                    contact: Some(Contact {
                        point: s.q,
                        normal,
                        face: self.ids[other],
                        uv: s.q_uv,
                    }),
                    lifted: 0.0,
                }
            })
            .collect();
        Pass {
            points,
            ..Pass::default()
        }
    }
}

fn validate(p: &PassParams) -> Result<(), FiveAxisError> {
    let bad = |field: &str, m: String| Err(FiveAxisError::parameter(field, m));
    if p.stations.len() < 2 || p.stations.iter().any(|s| !s.is_finite()) {
        return bad(
            "stations",
            format!(
                "{} stations: expected two or more finite positions",
                p.stations.len()
            ),
        );
    }
    if p.fractions.is_empty() || p.fractions.iter().any(|f| !(0.0..=1.0).contains(f)) {
        return bad(
            "fractions",
            format!(
                "{:?}: expected one or more zone fractions in [0, 1]",
                p.fractions
            ),
        );
    }
    if p.sides.is_empty() {
        return bad("sides", "expected one or more cutting sides".to_string());
    }
    if p.bands.is_empty() || p.bands.iter().any(|&b| b > 1) {
        return bad(
            "bands",
            format!(
                "{:?}: expected one or more faces dropped on, each 0 or 1",
                p.bands
            ),
        );
    }
    if p.max_turn.is_nan() || p.max_turn <= 0.0 {
        return bad(
            "max_turn",
            format!("{}: expected a turn rate above 0", p.max_turn),
        );
    }
    Ok(())
}
